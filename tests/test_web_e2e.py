"""End to end: ``pendulab serve`` in a subprocess, the page in headless Chromium.

A Chromium driven by Playwright: the one ``_browser.find_chromium`` finds (``make test``
installs Debian's ``chromium`` when there is none).
Reference periods: mpmath's complete elliptic integral at 30 digits,
``T = 4 sqrt(l/g) K(sin^2(alpha/2))``, independent of the library's AGM loop.
"""
from __future__ import annotations

import contextlib
import math
import os
import time
from pathlib import Path
from urllib.parse import parse_qs, urlparse

import mpmath
import numpy as np
import pytest
from PIL import Image
from playwright.sync_api import TimeoutError as PlaywrightTimeoutError

from _browser import VIEWPORTS, record_errors
from pendulab.core import methods
from pendulab.core.inputs import parse_angle
from pendulab.numerics import simulation
from reference import EXAMPLE_LENGTH, EXAMPLE_LENGTH_TEXT, ellipk_period


@pytest.fixture
def page(browser, server):
    """A page that may reach nothing but the pendulab server: anything else is recorded and aborted."""
    context = browser.new_context(viewport={"width": 1400, "height": 1100}, accept_downloads=True)
    yield guarded_page(context, server)
    context.close()


def guarded_page(context, server):
    """A new page of ``context`` that records (and aborts) requests leaving the server, and console errors."""
    pg = record_errors(context.new_page())
    pg.outside = []

    def route(r):
        if r.request.url.startswith(server + "/"):
            r.continue_()
        else:
            pg.outside.append(r.request.url)
            r.abort()

    pg.route("**/*", route)
    return pg


def shown_period(pg) -> float:
    return float(pg.locator("#period-agm").text_content())


def wait_for_period(pg, expected: float, timeout: float = 90.0) -> float:
    """Poll the period on the page until it shows ``expected`` (12 significant digits;
    ``timeout``: a hang guard for a slow, loaded machine)."""
    deadline = time.monotonic() + timeout
    while True:
        text = pg.locator("#period-agm").text_content()
        try:
            if math.isclose(float(text), expected, rel_tol=1e-11):
                return float(text)
        except ValueError:
            pass
        if time.monotonic() > deadline:
            raise AssertionError(f"page shows period {text!r}, expected {expected!r}")
        time.sleep(0.1)


def test_page_shows_the_librarys_period_and_follows_the_amplitude(page, server, tmp_path):
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    wait_for_period(page, ellipk_period(3.5, 0.8 * math.pi))  # problem 5's pendulum
    # All four plots drawn by plotly, which came from the pendulab server.
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 4")
    assert page.evaluate("typeof window.Plotly") == "object"
    # Estimates shown with their errors.
    cubic_err = float(page.locator("#err-cubic").text_content())
    assert 1e-8 < cubic_err < 1e-5

    # Change the amplitude: the period shown follows, and so does the URL.
    page.fill("#amplitude", "60")
    wait_for_period(page, ellipk_period(3.5, math.pi / 3))
    query = parse_qs(urlparse(page.url).query)
    assert query["amplitude"] == ["60"] and query["unit"] == ["deg"] and query["length"] == ["3.5"]

    # Radians, in the coursework's notation.
    page.select_option("#unit", "rad")
    page.fill("#amplitude", "pi/4")
    wait_for_period(page, ellipk_period(3.5, math.pi / 4))

    # Moon gravity from its preset.
    page.get_by_role("button", name="Moon").click()
    assert page.input_value("#g") == "1.62"
    wait_for_period(page, ellipk_period(3.5, math.pi / 4, 1.62))

    shot = tmp_path / "explorer.png"
    page.screenshot(path=str(shot), full_page=True)
    if os.environ.get("PENDULAB_SCREENSHOT"):  # to look at the page by eye
        page.screenshot(path=os.environ["PENDULAB_SCREENSHOT"], full_page=True)
    # The angle plot shows its curve: pixels of the first simulation's colour (app.js
    # COLORS.a, #2f6fdb) along a line, not a blank or a half-drawn plot.
    plot = tmp_path / "theta.png"
    page.locator("#plot-theta").screenshot(path=str(plot))
    pixels = np.asarray(Image.open(plot).convert("RGB"), dtype=int)
    curve = np.all(np.abs(pixels - (0x2F, 0x6F, 0xDB)) <= 40, axis=-1)
    assert curve.sum() >= 300, curve.sum()
    # across the plot's width (the dashed exact motion is drawn over it: not every column)
    assert np.count_nonzero(curve.any(axis=0)) >= pixels.shape[1] // 3
    assert page.outside == [] and page.errors == []


def test_the_url_reproduces_the_view(page, server):
    url = server + f"/?length={EXAMPLE_LENGTH_TEXT}&amplitude=4pi%2F5&unit=rad&g=9.80665&method=taylor2&step=0.01&t_max=12&speed=2"
    page.goto(url)
    wait_for_period(page, ellipk_period(EXAMPLE_LENGTH, 0.8 * math.pi))
    assert page.input_value("#length") == EXAMPLE_LENGTH_TEXT
    assert page.input_value("#amplitude") == "4pi/5"
    assert page.input_value("#unit") == "rad"
    assert page.input_value("#step") == "0.01"
    assert page.input_value("#speed") == "2"
    # The page writes back the same state: copying its URL gives the same view.
    assert parse_qs(urlparse(page.url).query) == parse_qs(urlparse(url).query)
    assert page.outside == []


def test_every_method_is_offered(page, server):
    page.goto(server + "/")
    page.wait_for_function("document.querySelectorAll('#method option').length > 0")
    offered = page.eval_on_selector_all("#method option", "os => os.map(o => o.value)")
    # The registry: its named methods, then taylor:P for every order, Euler's method (taylor:1) first.
    assert offered == [m.name for m in methods.menu()] + [f"taylor:{p}" for p in range(1, 31)]
    assert "Euler" in page.locator("#method option[value='taylor:1']").text_content()
    assert page.eval_on_selector_all("#method2 option", "os => os.map(o => o.value)") == [""] + offered


def test_bad_input_is_named_on_the_page(page, server):
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    wait_for_period(page, ellipk_period(3.5, 0.8 * math.pi))
    page.fill("#step", "0")
    page.wait_for_selector("#step-error:not([hidden])")
    assert page.locator("#step-error").text_content().startswith("step = 0 is not allowed")
    assert page.get_attribute("#step", "aria-invalid") == "true"
    assert "step-error" in page.get_attribute("#step", "aria-describedby").split()
    page.fill("#amplitude", "200")
    page.fill("#step", "1e-3")
    page.wait_for_function("document.querySelector('#amplitude-error').textContent.startsWith('amplitude')")
    assert page.get_attribute("#amplitude", "aria-invalid") == "true"
    assert page.get_attribute("#step", "aria-invalid") is None and page.locator("#step-error").is_hidden()
    # The value is echoed as typed (with the unit sent apart), not as "200deg"; the hint stays described.
    assert page.locator("#amplitude-error").text_content().startswith("amplitude = 200 is not allowed")
    assert page.get_attribute("#amplitude", "aria-describedby").split() == ["amplitude-error", "amplitude-hint"]
    page.fill("#amplitude", "30")
    wait_for_period(page, ellipk_period(3.5, math.pi / 6))
    assert page.locator("#amplitude-error").is_hidden() and page.get_attribute("#amplitude", "aria-invalid") is None
    # A decimal comma gets a hint; an empty g says which g is used.
    page.fill("#length", "1,5")
    page.wait_for_selector("#length-error:not([hidden])")
    assert "write a decimal point: 1.5" in page.locator("#length-error").text_content()
    page.fill("#length", "1.5")
    page.fill("#g", "")
    wait_for_period(page, ellipk_period(1.5, math.pi / 6))
    assert page.locator("#g-hint").is_visible() and "9.80665" in page.locator("#g-hint").text_content()


def test_play_pause(page, server):
    page.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=10")
    wait_for_period(page, ellipk_period(1, math.pi / 6))

    def clock() -> float:
        return float(page.locator("#clock").text_content().split()[2])

    # It swings: the clock moves on (a condition, not a 400 ms wait: on a loaded machine the
    # first frames come after the plots are drawn; 90 s is a hang guard).
    page.wait_for_function("(a) => document.getElementById('clock').textContent !== a",
                           arg=page.locator("#clock").text_content(), timeout=90_000)
    page.click("#play")
    assert page.locator("#play").text_content() == "Play"
    a = clock()
    page.wait_for_timeout(400)
    assert clock() == a  # paused


# ---------------------------------------------------------------- every screen, every state

LONG_RUN = "/?length=1&amplitude=30&unit=deg&g=9.80665&method=taylor2&step=1e-3&t_max=2000"


def open_page(browser, server, url: str, width: int = 1400, height: int = 1100):
    context = browser.new_context(viewport={"width": width, "height": height})
    pg = guarded_page(context, server)
    pg.goto(server + url)
    pg.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=90_000)
    pg.wait_for_function("document.querySelector('#status').textContent.includes('steps of')", timeout=90_000)
    return context, pg


@pytest.mark.parametrize("width, height", VIEWPORTS)
@pytest.mark.parametrize("url", ["/", LONG_RUN + "&method2=verlet",
                                 "/?length=1e-5&amplitude=30&unit=deg&step=1e-3&t_max=20&scale=1"])
def test_no_sideways_overflow_and_no_console_errors(browser, server, width, height, url):
    context, pg = open_page(browser, server, url, width, height)
    try:
        pg.wait_for_timeout(500)  # a few animation frames, the cursor moving over the plots
        assert pg.evaluate("document.documentElement.scrollWidth") <= width
        # Nothing inside is cut off either: every control lies within the viewport's width.
        right = pg.evaluate("Math.max(...[...document.querySelectorAll('input, select, button, .card')]"
                            ".map(e => e.getBoundingClientRect().right))")
        assert right <= width
        assert pg.errors == [] and pg.outside == []
        if os.environ.get("PENDULAB_SCREENSHOT_DIR"):  # to look at the page by eye
            name = f"{width}x{height}_{abs(hash(url)) % 1000}.png"
            pg.screenshot(path=str(Path(os.environ["PENDULAB_SCREENSHOT_DIR"]) / name), full_page=True)
    finally:
        context.close()


#: Each plot's title and mode bar as boxes (left, top, right, bottom), the bar's shown on hover.
TITLE_AND_MODE_BAR = """() => [...document.querySelectorAll('.js-plotly-plot')].map(gd => {
  const box = (e) => { if (!e) return null; const r = e.getBoundingClientRect();
                       return r.width ? [r.left, r.top, r.right, r.bottom] : null; };
  return {id: gd.id, text: gd.querySelector('.gtitle')?.textContent,
          title: box(gd.querySelector('.gtitle')), bar: box(gd.querySelector('.modebar'))};
})"""


def overlap(a, b) -> bool:
    return a is not None and b is not None and a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


@pytest.mark.parametrize("width, height", VIEWPORTS)
@pytest.mark.parametrize("url", ["/", LONG_RUN])
def test_no_title_runs_under_its_mode_bar(browser, server, width, height, url):
    # At 1400 px the phase portrait's long title ("... of the run") ran under the mode bar;
    # at 1024 px, where a plot is about 310 px wide, nearly every title did.
    context, pg = open_page(browser, server, url, width, height)
    try:
        for plot_id in ("plot-theta", "plot-phase", "plot-estimates", "plot-convergence"):
            pg.hover(f"#{plot_id}")  # the bar shows on hover (none on a phone)
        with contextlib.suppress(PlaywrightTimeoutError):  # the assertion below says which plot
            pg.wait_for_function(f"({TITLE_AND_MODE_BAR})().every(p => !p.bar || !p.title || "
                                 "p.title[2] <= p.bar[0] || p.title[1] >= p.bar[3])", timeout=90_000)
        plots = pg.evaluate(TITLE_AND_MODE_BAR)
        assert len(plots) == 7 and all(p["title"] for p in plots)
        assert any(p["bar"] for p in plots)
        for p in plots:
            assert not overlap(p["title"], p["bar"]), p
            # The title stays inside its plot's box, above the plot area.
            assert p["title"][2] <= pg.evaluate(f"document.getElementById('{p['id']}').getBoundingClientRect().right")
        if os.environ.get("PENDULAB_SCREENSHOT_DIR"):  # to look at the page by eye
            pg.screenshot(path=str(Path(os.environ["PENDULAB_SCREENSHOT_DIR"]) / f"titles_{width}_{len(url)}.png"),
                          full_page=True)
        assert pg.errors == []
    finally:
        context.close()


def drawn(pg, plot_id: str, trace: int = 0) -> dict:
    """A trace as plotly drew it: data, and each axis as (range, length in pixels)."""
    return pg.evaluate(
        """([id, i]) => { const gd = document.getElementById(id); const L = gd._fullLayout;
        return {x: gd.data[i].x, y: gd.data[i].y, xr: L.xaxis.range, xl: L.xaxis._length, yr: L.yaxis.range, yl: L.yaxis._length}; }""",
        [plot_id, trace])


def test_long_run_plots_keep_their_shape(browser, server):
    # l = 1, 30 deg, h = 1e-3, t_max = 2000 s: 980 periods on one plot.
    context, pg = open_page(browser, server, LONG_RUN)
    try:
        alpha = math.radians(30)
        full = simulation.simulate(1, alpha, 1e-3, 2000.0)
        # theta(t): in every pixel column holding a turn, the drawn curve reaches the turn's
        # value (+-alpha within 0.1 % for taylor2 at this step) within 1 %.
        d = drawn(pg, "plot-theta")
        t = np.array(d["x"], dtype=float)
        y = np.array(d["y"], dtype=float)
        px = np.floor((t - d["xr"][0]) / (d["xr"][1] - d["xr"][0]) * d["xl"]).astype(int)
        turns = np.flatnonzero((full.omega[:-1] > 0) != (full.omega[1:] > 0)) + 1
        assert len(turns) > 1900
        checked = 0
        for i in turns:
            c = int(np.floor((full.t[i] - d["xr"][0]) / (d["xr"][1] - d["xr"][0]) * d["xl"]))
            col = y[px == c]
            value = full.theta[i]
            assert abs(value) == pytest.approx(alpha, rel=1e-3)
            reached = col.max() if value > 0 else -col.min()
            assert reached >= 0.99 * abs(value), (full.t[i], reached, value)
            checked += 1
        assert checked == len(turns)
        # Phase portrait: no drawn segment longer than 5 % of the orbit's width (in pixels).
        d = drawn(pg, "plot-phase")
        x = np.array([np.nan if v is None else v for v in d["x"]], dtype=float)
        v = np.array([np.nan if w is None else w for w in d["y"]], dtype=float)
        sx = d["xl"] / (d["xr"][1] - d["xr"][0])
        sy = d["yl"] / (d["yr"][1] - d["yr"][0])
        width_px = (np.nanmax(x) - np.nanmin(x)) * sx
        seg = np.hypot(np.diff(x) * sx, np.diff(v) * sy)
        assert np.nanmax(seg) <= 0.05 * width_px
        assert np.sum(np.isnan(seg)) >= 2  # several orbits, apart
        # With one method there is no legend: the title names the orbits and their time span.
        answer = pg.evaluate("fetch('/api/simulate' + location.search + '&points=3000').then(r => r.json())")
        title = pg.evaluate("document.getElementById('plot-phase').layout.title.text")
        phase = answer["phase"]
        assert phase["orbits"] == np.sum(np.isnan(x)) + 1 > 2
        assert title == f"Phase portrait: {phase['orbits']} periods, 0 to {phase['t_last']:.12g} s"
        assert phase["t_last"] > 0.9 * 2000
        assert pg.errors == []
    finally:
        context.close()


def clock(pg) -> tuple[float, float]:
    parts = pg.locator("#clock").text_content().split()
    return float(parts[2]), float(parts[6].rstrip("°"))


def cursor_time(pg, plot_id: str) -> tuple[float, float]:
    """The time under a plot's cursor line (its left edge on screen, read back through the x
    axis) and the time one pixel spans there."""
    return tuple(pg.evaluate("""id => { const gd = document.getElementById(id), xa = gd._fullLayout.xaxis;
        const el = gd.parentElement.querySelector('.cursor-line');
        return [xa.p2l(el.getBoundingClientRect().left - gd.getBoundingClientRect().left - xa._offset),
                xa.p2l(1) - xa.p2l(0)]; }""", plot_id))


def cursor_state(pg) -> tuple[float, float, float, float]:
    """(theta, theta') under the phase portrait's cursor dot (its centre, through both axes), and a pixel of each."""
    return tuple(pg.evaluate("""() => { const gd = document.getElementById('plot-phase'), L = gd._fullLayout;
        const r = gd.parentElement.querySelector('.cursor-dot').getBoundingClientRect(), g = gd.getBoundingClientRect();
        return [L.xaxis.p2l(r.left + r.width / 2 - g.left - L.xaxis._offset),
                L.yaxis.p2l(r.top + r.height / 2 - g.top - L.yaxis._offset),
                L.xaxis.p2l(1) - L.xaxis.p2l(0), L.yaxis.p2l(0) - L.yaxis.p2l(1)]; }"""))


def test_the_animation_shows_the_true_state_at_its_time(browser, server):
    # Before: -15.6 deg shown at t = 1 s where the simulated pendulum is at -29.9 deg.
    context, pg = open_page(browser, server, LONG_RUN + "&paused=1&t=1")
    try:
        t, shown = clock(pg)
        assert t == 1.0 and pg.locator("#play").text_content() == "Play"
        full = simulation.simulate(1, math.radians(30), 1e-3, 2.0)
        assert shown == pytest.approx(math.degrees(full.theta[1000]), abs=0.01)
        # The time cursor: the same time on theta(t), the error and energy plots, the same state on the phase portrait.
        for plot in ("plot-theta", "plot-error", "plot-energy"):
            at, pixel = cursor_time(pg, plot)
            assert abs(at - 1.0) <= pixel  # within a pixel (of a 2000 s axis)
        theta, omega, px_theta, px_omega = cursor_state(pg)
        assert abs(theta - full.theta[1000]) <= px_theta and abs(omega - full.omega[1000]) <= px_omega
        # Moving the cursor moves all of them and goes into the URL.
        pg.evaluate("(() => { const c = document.getElementById('cursor'); c.value = '1.5'; c.dispatchEvent(new Event('input')); })()")
        t, shown = clock(pg)
        assert t == 1.5 and shown == pytest.approx(math.degrees(full.theta[1500]), abs=0.01)
        at, pixel = cursor_time(pg, "plot-theta")
        assert abs(at - 1.5) <= pixel
        assert parse_qs(urlparse(pg.url).query)["t"] == ["1.5"]
    finally:
        context.close()


def test_period_marks_are_capped(browser, server):
    # Before: 4898 dashed lines for t_max = 10000 s (15 s to draw).
    context, pg = open_page(browser, server, "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=10000")
    try:
        shapes = pg.evaluate("document.getElementById('plot-theta').layout.shapes.length")
        assert shapes <= 13
        assert "periods of T" in pg.evaluate("document.getElementById('plot-theta').layout.title.text")
    finally:
        context.close()


def test_blown_up_simulation_is_flagged_on_the_page(browser, server):
    context, pg = open_page(browser, server, "/?length=1e-5&amplitude=30&unit=deg&step=1e-3&t_max=20")
    try:
        assert pg.locator("#flags").is_visible()
        assert "over the top" in pg.locator("#flags").text_content()
        assert pg.locator(".estimates.untrusted").count() == 1
    finally:
        context.close()


def test_stale_results_are_dimmed_after_an_error(page, server):
    """The graphics of stale results fade and their cards are dashed; their text keeps its
    contrast (no opacity on it: axe's colour contrast holds in the error state too)."""
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    wait_for_period(page, ellipk_period(3.5, 0.8 * math.pi))
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot').length >= 4")
    faded = ("[...document.querySelectorAll('#canvas, .js-plotly-plot')].every((e) => getComputedStyle(e).opacity < 0.5)"
             " && getComputedStyle(document.getElementById('periods')).borderTopStyle === 'dashed'")
    assert page.evaluate("getComputedStyle(document.getElementById('canvas')).opacity") == "1"
    page.fill("#length", "abc")
    page.wait_for_selector("#length-error:not([hidden])")
    page.wait_for_function(faded)
    text = "[...document.querySelectorAll('#periods, #animation, #plots')].map((e) => getComputedStyle(e).opacity)"
    assert page.evaluate(text) == ["1", "1", "1"]
    assert "length" in page.locator("#length-error").text_content()
    page.fill("#length", "2")
    wait_for_period(page, ellipk_period(2, 0.8 * math.pi))
    page.wait_for_function("getComputedStyle(document.getElementById('canvas')).opacity == 1")


def test_every_new_control_is_in_the_url(page, server):
    url = (server + "/?length=1&amplitude=pi%2F4&unit=rad&g=1.62&method=rk4&step=0.01&t_max=12"
           "&method2=verlet&step2=0.02&speed=0.5&exact=0&scale=1&paused=1&t=2.5")
    page.goto(url)
    wait_for_period(page, ellipk_period(1, math.pi / 4, 1.62))
    assert page.input_value("#method2") == "verlet" and page.input_value("#step2") == "0.02"
    assert not page.is_checked("#exact") and page.is_checked("#scale")
    assert page.locator("#play").text_content() == "Play" and clock(page)[0] == 2.5
    assert parse_qs(urlparse(page.url).query) == parse_qs(urlparse(url).query)
    # Two methods side by side: two tables, two curves.
    assert page.locator("#est2-cubic").count() == 1
    assert page.evaluate("document.getElementById('plot-theta').data.length") == 2  # no exact overlay: exact=0
    # A method the menu may not list stays as the URL has it.
    page.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=5&method=taylor:4")
    wait_for_period(page, ellipk_period(1, math.pi / 6))
    assert page.input_value("#method") == "taylor:4"
    assert parse_qs(urlparse(page.url).query)["method"] == ["taylor:4"]


def test_sliders_and_dragging_the_bob_set_the_inputs(page, server):
    page.goto(server + "/?length=3.5&amplitude=30&unit=deg&step=1e-3&t_max=20&paused=1&t=0")
    wait_for_period(page, ellipk_period(3.5, math.pi / 6))
    # The length slider moves log10(l): 0 is 1 m.
    page.evaluate("(() => { const s = document.getElementById('length-slider'); s.value = '0'; s.dispatchEvent(new Event('input')); })()")
    assert page.input_value("#length") == "1"
    wait_for_period(page, ellipk_period(1, math.pi / 6))
    # So does g's (log10 too), and a preset button moves the slider.
    page.evaluate("(() => { const s = document.getElementById('g-slider'); s.value = '1'; s.dispatchEvent(new Event('input')); })()")
    assert page.input_value("#g") == "10"
    wait_for_period(page, ellipk_period(1, math.pi / 6, 10))
    page.get_by_role("button", name="Moon").click()
    assert page.evaluate("Number(document.getElementById('g-slider').value)") == pytest.approx(math.log10(1.62), abs=0.01)
    wait_for_period(page, ellipk_period(1, math.pi / 6, 1.62))
    # Drag the bob (at 30 deg at t = 0) to 60 deg: the amplitude follows.
    box = page.locator("#canvas").bounding_box()
    w, h = box["width"], box["width"] * 340 / 420
    px, py, r = box["x"] + w / 2, box["y"] + h / 2, h / 2 - 26
    a0, a1 = math.radians(30), math.radians(60)
    page.mouse.move(px + r * math.sin(a0), py + r * math.cos(a0))
    page.mouse.down()
    page.mouse.move(px + r * math.sin(a1), py + r * math.cos(a1), steps=5)
    page.mouse.up()
    page.wait_for_function("Math.abs(Number(document.getElementById('amplitude').value) - 60) < 1")
    shown = float(page.input_value("#amplitude"))
    wait_for_period(page, ellipk_period(1, math.radians(shown), 1.62))
    assert parse_qs(urlparse(page.url).query)["amplitude"] == [page.input_value("#amplitude")]


def test_api_docs_work_offline(page, server):
    page.goto(server + "/api/docs")
    page.wait_for_selector(".swagger-ui .opblock", timeout=90_000)
    assert page.locator(".opblock-summary-path", has_text="/api/simulate").count() == 1
    assert page.outside == [] and page.errors == []


#: Each plot's box, its legend's box and the boxes of its axes' tick labels (left, top, right, bottom).
PLOT_PARTS = """() => [...document.querySelectorAll('.js-plotly-plot')].map(gd => {
  const box = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
  const ticks = (cls) => [...gd.querySelectorAll(`.${cls} text`)]
    .filter(t => t.textContent && t.getBoundingClientRect().width).map(t => [t.textContent, box(t)]);
  const legend = gd.querySelector('.legend');
  return {id: gd.id, box: box(gd), legend: legend && legend.getBoundingClientRect().width ? box(legend) : null,
          xticks: ticks('xtick'), yticks: ticks('ytick')};
})"""


@pytest.mark.parametrize("width, height", VIEWPORTS)
@pytest.mark.parametrize("url", ["/", LONG_RUN + "&method2=verlet"])
def test_legends_and_tick_labels_stay_readable(browser, server, width, height, url):
    # At 390 and 1024 px the phase portrait's legend ("... (13 stretches of one period, 0 to
    # 1999.998 s)") ran past the plot's right edge, cut off; at 1024 px the convergence plot's
    # log axes labelled 2 and 5 between the decades, "10^-4" and "2" reading as "10^-42".
    context, pg = open_page(browser, server, url, width, height)
    try:
        pg.wait_for_function("document.querySelectorAll('.js-plotly-plot').length == 7 && "
                             "document.querySelector('#plot-convergence .xtick')", timeout=90_000)
        plots = pg.evaluate(PLOT_PARTS)
        assert len(plots) == 7
        legends = 0
        for p in plots:
            if p["legend"]:
                legends += 1
                left, top, right, bottom = p["box"]
                lg = p["legend"]
                assert left <= lg[0] and lg[2] <= right and top <= lg[1] and lg[3] <= bottom, p
            for axis, gap in (("xticks", 4), ("yticks", 1)):
                labels = p[axis]
                for i, (text_a, a) in enumerate(labels):
                    for text_b, b in labels[i + 1:]:
                        # Apart by `gap` pixels: labels closer than that read as one.
                        near = [a[0] - gap, a[1] - gap, a[2] + gap, a[3] + gap]
                        assert not overlap(near, b), (p["id"], axis, text_a, text_b, a, b)
        assert legends >= (2 if "method2" in url else 1)
        assert pg.errors == []
    finally:
        context.close()


# ---------------------------------------------------------------- a classroom on every screen

FLAGGED = "/?length=1e-5&amplitude=30&unit=deg&step=1e-3&t_max=20"


@pytest.mark.parametrize("width, height", VIEWPORTS)
def test_first_screen_has_the_pendulum_and_the_flags(browser, server, width, height):
    # A phone showed the pendulum at y = 1160, the "over the top" banner below the whole form;
    # at 1400x900 the controls scrolled inside themselves, "rods to scale" cut off.
    context, pg = open_page(browser, server, FLAGGED, width, height)
    try:
        pg.evaluate("window.scrollTo(0, 0)")
        box = pg.evaluate("""() => Object.fromEntries(['canvas', 'flags', 'inputs', 'play', 'csv', 'copy-link'].map(id => {
            const r = document.getElementById(id).getBoundingClientRect(); return [id, [r.left, r.top, r.right, r.bottom]]; }))""")
        for name in ("canvas", "play", "csv", "copy-link"):  # the swing and its buttons, whole, on the first screen
            left, top, right, bottom = box[name]
            assert top >= 0 and bottom <= height and left >= 0 and right <= width, (name, box[name])
        assert box["flags"][1] < box["canvas"][1] and box["flags"][3] <= height  # the flags above it
        assert "over the top" in pg.locator("#flags").text_content()
        # The controls never scroll inside themselves: nothing hidden in an inner scroll area.
        form = pg.evaluate("""(() => { const f = document.getElementById('inputs'), cs = getComputedStyle(f);
            return [f.scrollHeight, f.clientHeight, cs.overflowY, cs.maxHeight]; })()""")
        assert form[0] <= form[1] + 1 and form[2] == "visible" and form[3] == "none", form
        if width >= 1400:  # a wide screen: every control on the first screen, "rods to scale" included
            assert pg.evaluate("document.getElementById('scale').getBoundingClientRect().bottom") <= height
            assert box["inputs"][3] <= height
        assert pg.errors == [] and pg.outside == []
    finally:
        context.close()


@pytest.mark.parametrize("width, height", VIEWPORTS)
def test_each_message_is_beside_its_field(browser, server, width, height):
    context, pg = open_page(browser, server, "/", width, height)
    try:
        for field, bad in (("t_max", "-1"), ("length", "0")):
            pg.fill(f"#{field}", bad)
            pg.wait_for_selector(f"#{field}-error:not([hidden])")
            pg.evaluate(f"document.getElementById('{field}').scrollIntoView({{block: 'center'}})")
            f = pg.locator(f"#{field}").bounding_box()
            e = pg.locator(f"#{field}-error").bounding_box()
            # Right under the field, in the same column, and on screen with it.
            assert 0 <= e["y"] - (f["y"] + f["height"]) <= 8, (field, f, e)
            assert e["x"] <= f["x"] + 1 and e["y"] + e["height"] <= height
            assert pg.get_attribute(f"#{field}", "aria-invalid") == "true"
            assert pg.locator(f"#{field}-error").text_content().startswith(f"{field} = {bad}")
            pg.fill(f"#{field}", "20" if field == "t_max" else "3.5")
            pg.wait_for_selector(f"#{field}-error", state="hidden")
    finally:
        context.close()


def swipe_up(cdp, x: float, y: float, distance: float, steps: int = 15) -> None:
    """A finger's swipe upwards from (x, y), as the touch screen sends it (Chromium's DevTools protocol)."""
    cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
    for k in range(1, steps + 1):
        cdp.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": x, "y": y - distance * k / steps}]})
        time.sleep(0.016)
    cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})


def test_a_swipe_over_a_plot_scrolls_the_page_on_a_phone(browser, server):
    context = browser.new_context(viewport={"width": 390, "height": 844}, has_touch=True, is_mobile=True,
                                  device_scale_factor=2)
    pg = guarded_page(context, server)
    try:
        pg.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=20")
        pg.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=90_000)
        pg.evaluate("document.getElementById('plot-error').scrollIntoView({block: 'center'})")
        pg.wait_for_timeout(300)
        before = pg.evaluate("[scrollY, [...document.getElementById('plot-error')._fullLayout.xaxis.range]]")
        box = pg.locator("#plot-error").bounding_box()
        swipe_up(context.new_cdp_session(pg), box["x"] + box["width"] / 2, box["y"] + box["height"] / 2 + 100, 300)
        pg.wait_for_timeout(300)
        after = pg.evaluate("[scrollY, [...document.getElementById('plot-error')._fullLayout.xaxis.range]]")
        assert after[0] > before[0] + 150, (before, after)  # the page scrolled
        assert after[1] == before[1]  # the plot did not zoom or pan
        # Zoom stays there, behind an explicit button of the always-shown mode bar.
        assert pg.locator("#plot-error .modebar-btn[data-attr='dragmode'][data-val='zoom']").count() == 1
        assert pg.evaluate("document.getElementById('plot-error')._fullLayout.dragmode") is False
        assert pg.errors == [] and pg.outside == []
    finally:
        context.close()


def test_no_cloud_buttons_and_readable_plot_text(page, server):
    page.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=20&method2=verlet")
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=90_000)
    for plot_id in ("plot-theta", "plot-phase"):
        page.hover(f"#{plot_id}")
    titles = page.eval_on_selector_all(".modebar-btn", "bs => bs.map(b => b.getAttribute('data-title') || '')")
    assert titles and not [t for t in titles if "cloud" in t.lower() or "studio" in t.lower() or "plotly" in t.lower()]
    assert page.locator(".modebar-btn--logo").count() == 0
    assert page.eval_on_selector_all("a[href]", "as => as.map(a => a.href)") and not [
        h for h in page.eval_on_selector_all("a[href]", "as => as.map(a => a.href)") if not h.startswith(server)]
    # Text in the plots at least 12 px (titles 15, ticks 13): readable from the back of a room.
    sizes = page.eval_on_selector_all(".js-plotly-plot .main-svg text",
                                      "ts => ts.filter(t => t.textContent.trim()).map(t => parseFloat(getComputedStyle(t).fontSize))")
    assert sizes and min(sizes) >= 12


def test_reduced_motion_does_not_autoplay(browser, server):
    context = browser.new_context(viewport={"width": 1400, "height": 900}, reduced_motion="reduce")
    pg = guarded_page(context, server)
    try:
        pg.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=10")
        wait_for_period(pg, ellipk_period(1, math.pi / 6))
        a = clock(pg)
        pg.wait_for_timeout(400)
        assert clock(pg) == a and pg.locator("#play").text_content() == "Play"
        pg.click("#play")
        # Play still plays: the clock's time moves on (90 s: a hang guard on a loaded machine)
        pg.wait_for_function("(a) => parseFloat(document.getElementById('clock').textContent.split(/\\s+/)[2]"
                             ".replace(',', '.')) > a", arg=a[0], timeout=90_000)
        assert clock(pg)[0] > a[0]
    finally:
        context.close()


def test_flags_say_what_is_wrong_and_spare_a_bounded_oscillation(browser, server):
    # Verlet at h = 0.2: a bounded 2 % energy oscillation, the swing a pendulum's.
    context, pg = open_page(browser, server, "/?length=3.5&amplitude=144&unit=deg&step=0.2&t_max=20&method=verlet")
    try:
        flags = pg.locator("#flags")
        assert flags.is_visible() and "Bounded energy error" in flags.text_content()
        assert "Not the pendulum" not in flags.text_content() and pg.locator(".estimates.untrusted").count() == 0
        # taylor2 at h = 0.01 over 2000 s: 4.7 rad out of phase with the exact motion, said so.
        pg.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-2&t_max=2000")
        pg.wait_for_function("document.querySelector('#flags p[data-kind=phase]')", timeout=90_000)
        assert "out of step with the exact motion" in pg.locator("#flags").text_content()
    finally:
        context.close()


@pytest.mark.slow
def test_rk4_at_half_a_second_is_flagged_as_damping_at_every_size(browser, server):
    # RK4 at l = 1 m, 30 deg, h = 0.5 s loses its energy to a standstill: named numerical damping, never "bounded".
    for width, height in VIEWPORTS:
        context, pg = open_page(browser, server, "/?length=1&amplitude=30&unit=deg&step=0.5&t_max=20&method=rk4",
                                width, height)
        try:
            pg.wait_for_function("document.querySelector('#flags p[data-kind=energy-decay]')", timeout=90_000)
            text = pg.locator("#flags").text_content()
            assert "numerical damping" in text and "bounded" not in text.lower()
            assert pg.locator(".estimates.untrusted").count() == 1
        finally:
            context.close()


def test_second_method_in_every_plot_and_a_log_error(browser, server):
    context, pg = open_page(browser, server, "/?length=1&amplitude=30&unit=deg&step=1e-2&t_max=20&method2=verlet&errlog=1")
    try:
        pg.wait_for_function("(document.getElementById('plot-convergence').data || []).some(t => t.name.includes('verlet'))",
                             timeout=90_000)
        names = {pid: pg.evaluate(f"document.getElementById('{pid}').data.map(t => t.name || '')")
                 for pid in ("plot-theta", "plot-phase", "plot-error", "plot-energy", "plot-estimates", "plot-convergence")}
        for pid, ns in names.items():
            assert any("verlet" in n for n in ns) and any("taylor2" in n for n in ns), (pid, ns)
        assert pg.evaluate("document.getElementById('plot-error')._fullLayout.yaxis.type") == "log"
        y = pg.evaluate("document.getElementById('plot-error').data[0].y")
        assert all(v is None or v > 0 for v in y)
    finally:
        context.close()


def bob_at(pg, x: float, y: float) -> list[int]:
    """The canvas's colour (RGBA) at (x, y) CSS pixels from its top left."""
    return pg.evaluate("""([x, y]) => { const c = document.getElementById('canvas'), k = c.width / c.clientWidth;
        return [...c.getContext('2d').getImageData(Math.round(x * k), Math.round(y * k), 1, 1).data]; }""", [x, y])


BLUE, PURPLE = [0x2F, 0x6F, 0xDB], [0x7A, 0x5C, 0xC9]


def near(rgba, rgb, tol=12) -> bool:
    return all(abs(a - b) <= tol for a, b in zip(rgba, rgb))


def test_dragging_left_releases_on_the_left(page, server):
    page.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=20&paused=1&t=0")
    wait_for_period(page, ellipk_period(1, math.pi / 6))
    box = page.locator("#canvas").bounding_box()
    w, h = box["width"], box["width"] * 340 / 420
    px, py, r = w / 2, h / 2, h / 2 - 26
    a0, a1 = math.radians(30), math.radians(-50)
    page.mouse.move(box["x"] + px + r * math.sin(a0), box["y"] + py + r * math.cos(a0))
    page.mouse.down()
    page.mouse.move(box["x"] + px + r * math.sin(a1), box["y"] + py + r * math.cos(a1), steps=6)
    page.mouse.up()
    page.wait_for_function("Math.abs(Number(document.getElementById('amplitude').value) - 50) < 1")
    wait_for_period(page, ellipk_period(1, math.radians(float(page.input_value("#amplitude")))))
    assert parse_qs(urlparse(page.url).query)["side"] == ["left"]
    page.evaluate("(() => { const c = document.getElementById('cursor'); c.value = '0'; c.dispatchEvent(new Event('input')); })()")
    a = math.radians(float(page.input_value("#amplitude")))
    assert near(bob_at(page, px - r * math.sin(a), py + r * math.cos(a)), BLUE)  # drawn on the left
    assert not near(bob_at(page, px + r * math.sin(a), py + r * math.cos(a)), BLUE)


def test_second_pendulum_swings_beside_with_its_exact_period_to_scale(page, server):
    page.goto(server + "/?length=3.5&amplitude=10&unit=deg&step=1e-3&t_max=20&paused=1&t=0"
              "&second=1&length2=20&amplitude2=120&g2=9.80665&scale=1")
    wait_for_period(page, ellipk_period(3.5, math.radians(10)))
    page.wait_for_selector("#period2-line:not([hidden])")
    assert float(page.locator("#period2-agm").text_content()) == pytest.approx(
        ellipk_period(20, math.radians(120)), rel=1e-11)
    # Both rods at one scale: the ruler (a fixed length, the full radius) is 20 m here.
    w = page.locator("#canvas").bounding_box()["width"]
    h = w * 340 / 420
    rmax = min(h / 2 - 22, w * 0.23 - 14)
    a1, a2 = math.radians(10), math.radians(120)
    r1, r2 = rmax * 3.5 / 20, rmax
    assert near(bob_at(page, 0.27 * w + r1 * math.sin(a1), h / 2 + r1 * math.cos(a1)), BLUE)
    assert near(bob_at(page, 0.73 * w + r2 * math.sin(a2), h / 2 + r2 * math.cos(a2)), PURPLE)
    # Without "to scale" each fills its circle.
    page.click("#scale")
    assert near(bob_at(page, 0.27 * w + rmax * math.sin(a1), h / 2 + rmax * math.cos(a1)), BLUE)
    # On the T(alpha)/T0 curve, both marked at their amplitudes.
    marks = page.evaluate("document.getElementById('plot-ratio').data.filter(t => t.mode === 'markers').map(t => [t.x[0], t.y[0]])")
    assert [m[0] for m in marks] == pytest.approx([10, 120])
    assert marks[1][1] == pytest.approx(ellipk_period(20, a2) / (2 * math.pi * math.sqrt(20 / 9.80665)), rel=1e-11)


def test_period_ratio_curve_and_its_approximations(page, server):
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    page.wait_for_function("document.getElementById('plot-ratio').data && document.getElementById('plot-ratio').data.length >= 7",
                           timeout=90_000)
    data = page.evaluate("document.getElementById('plot-ratio').data.map(t => ({name: t.name, x: t.x, y: t.y}))")
    exact = data[0]
    assert exact["x"][0] == 0 and exact["x"][-1] == 179 and len(exact["x"]) == 180
    for deg in (0, 30, 90, 144, 179):  # 2 K(sin^2(alpha/2)) / pi, mpmath at 30 digits
        with mpmath.workdps(30):
            ref = 2 * mpmath.ellipk(mpmath.sin(mpmath.radians(deg) / 2) ** 2) / mpmath.pi
        assert exact["y"][deg] == pytest.approx(float(ref), rel=1e-13)
    names = [d["name"] for d in data]
    assert "T0 (1 + k^2/4) (eq. 9)" in names and any("sqrt(cos" in n for n in names)
    eq9 = data[names.index("T0 (1 + k^2/4) (eq. 9)")]
    assert eq9["y"][90] == pytest.approx(1 + math.sin(math.pi / 4) ** 2 / 4, rel=1e-15)
    mark = data[names.index("this pendulum")]
    assert mark["x"] == [pytest.approx(144)] and mark["y"][0] == pytest.approx(exact["y"][144], rel=1e-12)


def test_photogate_times_the_swing(browser, server):
    context, pg = open_page(browser, server, "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=60&speed=4")
    try:
        pg.wait_for_function("document.getElementById('gate').dataset.period", timeout=90_000)
        measured = float(pg.get_attribute("#gate", "data-period"))
        assert measured == pytest.approx(ellipk_period(1, math.pi / 6), rel=2e-3)
        assert "AGM" in pg.locator("#gate").text_content()
        # Over the top (theta'(0) = 7 rad/s): every pass is one more turn, the same way.
        pg.goto(server + "/?length=1&amplitude=17&unit=deg&step=1e-3&t_max=60&omega0=7")
        pg.wait_for_function("document.getElementById('gate').dataset.period", timeout=90_000)
        turn = float(pg.locator("#period-agm").text_content())
        assert float(pg.get_attribute("#gate", "data-period")) == pytest.approx(turn, rel=2e-3)
    finally:
        context.close()


def test_energy_bars_follow_the_state(page, server):
    page.goto(server + "/?length=2&amplitude=144&unit=deg&step=1e-3&t_max=20&paused=1&t=0")
    wait_for_period(page, ellipk_period(2, 0.8 * math.pi))
    page.wait_for_function("document.getElementById('val-exact-U').textContent !== '–'")

    def bars() -> dict[str, float]:  # "Ke": kinetic, exact; "Us": potential, simulated; ...
        return {f"{k}{who[0]}": float(page.locator(f"#val-{who}-{k}").text_content())
                for who in ("exact", "sim") for k in "KUE"}

    e0 = 1 - math.cos(0.8 * math.pi)  # in m g l, at rest at the amplitude
    b = bars()
    assert b["Ke"] == 0 and b["Ue"] == pytest.approx(e0, abs=1e-3) and b["Ee"] == pytest.approx(e0, abs=1e-3)
    # A quarter period later the bob is at the bottom: all kinetic.
    quarter = ellipk_period(2, 0.8 * math.pi) / 4
    page.evaluate(f"(() => {{ const c = document.getElementById('cursor'); c.value = '{quarter}'; c.dispatchEvent(new Event('input')); }})()")
    b = bars()
    assert b["Ue"] == pytest.approx(0, abs=2e-3) and b["Ke"] == pytest.approx(e0, abs=2e-3)
    assert b["Ks"] == pytest.approx(e0, abs=5e-3) and b["Us"] == pytest.approx(0, abs=5e-3)


def test_exact_orbit_under_the_simulated_one(page, server):
    page.goto(server + "/?length=1&amplitude=144&unit=deg&step=0.05&t_max=20&method=taylor2")
    page.wait_for_function("document.getElementById('plot-phase').data && "
                           "document.getElementById('plot-phase').data.some(t => t.name === 'exact orbit')", timeout=90_000)
    orbit = page.evaluate("document.getElementById('plot-phase').data.find(t => t.name === 'exact orbit')")
    theta, omega = np.array(orbit["x"]), np.array(orbit["y"])
    # On the exact orbit the energy is that of the release: theta'^2 l/(2g) - cos(theta) = -cos(alpha).
    e = omega**2 / (2 * 9.80665) - np.cos(theta)
    assert np.max(np.abs(e + math.cos(0.8 * math.pi))) < 1e-12
    assert theta.max() == pytest.approx(0.8 * math.pi, rel=1e-12) and len(theta) > 200


def test_csv_has_every_shown_column_for_both_methods(page, server, tmp_path):
    from scipy.integrate import solve_ivp

    page.goto(server + "/?length=1&amplitude=pi%2F4&unit=rad&step=0.1&t_max=2.1&method2=rk4&step2=0.05")
    wait_for_period(page, ellipk_period(1, math.pi / 4))
    page.wait_for_selector("#csv2:not([hidden])")
    tables = []
    for link in ("#csv", "#csv2"):
        with page.expect_download() as info:
            page.click(link)
        path = tmp_path / f"{link[1:]}.csv"
        info.value.save_as(path)
        tables.append(path.read_text().splitlines())
    head = "t,theta,omega,theta_exact,omega_exact,theta_error,energy_error"
    assert tables[0][0] == head and tables[1][0] == head
    assert len(tables[0]) == 1 + 22 and len(tables[1]) == 1 + 43
    # The exact columns against scipy's DOP853 at rtol 1e-12; the error and energy columns from the row itself.
    sol = solve_ivp(lambda t, z: [z[1], -9.80665 * math.sin(z[0])], (0, 2.1), [math.pi / 4, 0.0], method="DOP853",
                    rtol=1e-12, atol=1e-14, dense_output=True)
    for rows in tables:
        for line in rows[1:]:
            t, th, om, th_ex, om_ex, err, de = map(float, line.split(","))
            ref = sol.sol(t)
            assert th_ex == pytest.approx(ref[0], abs=1e-10) and om_ex == pytest.approx(ref[1], abs=1e-9)
            assert err == th - th_ex
            assert de == pytest.approx(om**2 / (2 * 9.80665) - math.cos(th) + math.cos(math.pi / 4), abs=1e-15)
    # Figure 3 of the coursework, t = 2.1: z1 = 0.796774928412 (taylor2, h = 0.1).
    assert float(tables[0][-1].split(",")[1]) == pytest.approx(0.796774928412, rel=1e-11)


def test_a_launch_goes_over_the_top_and_the_exact_motion_follows(page, server):
    # l = 1 m, 17 deg, theta'(0) = 7 rad/s: k = 1.147 > 1, the pendulum goes round.
    page.goto(server + "/?length=1&amplitude=17&unit=deg&step=1e-3&t_max=20&omega0=7&paused=1&t=0")
    page.wait_for_selector("#period-label:has-text('one turn')")
    w = math.sqrt(9.80665)
    k = math.hypot(math.sin(math.radians(17) / 2), 7 / (2 * w))
    m = 1 / k**2
    with mpmath.workdps(30):  # a turn takes 2 K(1/k^2)/(k w) (DLMF 22.19), mpmath's K
        turn = float(2 * mpmath.ellipk(m) / (k * w))
    assert float(page.locator("#period-agm").text_content()) == pytest.approx(turn, rel=1e-11)
    assert not page.locator("#flags").text_content()  # going over the top is right here
    # The exact curve on theta(t) grows by 2 pi a turn, with the simulation on it (scipy DOP853 as reference).
    from scipy.integrate import solve_ivp

    page.wait_for_function("document.getElementById('plot-theta').data && document.getElementById('plot-theta').data.length >= 2")
    ex = page.evaluate("document.getElementById('plot-theta').data[1]")
    t, th = np.array(ex["x"]), np.array(ex["y"])
    sol = solve_ivp(lambda _, z: [z[1], -9.80665 * math.sin(z[0])], (0, 20), [math.radians(17), 7.0],
                    method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t)
    assert np.max(np.abs(th - sol.y[0])) < 1e-7 and th[-1] > 2 * math.pi * 15
    assert parse_qs(urlparse(page.url).query)["omega0"] == ["7"]
    release = page.evaluate("document.getElementById('plot-phase').data.find(t => t.name.startsWith('P ='))")
    assert release["x"] == [pytest.approx(math.radians(17))] and release["y"] == [7]  # released at (alpha, omega0)
    # Less of it: it swings, to its turning angle 2 asin(k), and sits there on the T(alpha)/T0 curve.
    page.fill("#omega0", "2")
    page.wait_for_selector("#period-label:has-text('turning angle')")
    k = math.hypot(math.sin(math.radians(17) / 2), 2 / (2 * w))
    assert float(page.locator("#period-agm").text_content()) == pytest.approx(ellipk_period(1, 2 * math.asin(k)), rel=1e-11)
    page.wait_for_function("document.getElementById('plot-ratio').data.some(t => t.name === 'this pendulum' && "
                           f"Math.abs(t.x[0] - {math.degrees(2 * math.asin(k))}) < 1e-9)")
    # A bad value is named under its field.
    page.fill("#omega0", "fast")
    page.wait_for_selector("#omega0-error:not([hidden])")
    assert page.locator("#omega0-error").text_content().startswith("omega0 = fast")


def test_zoom_fetches_finer_data(browser, server):
    # 2000 s in 1500 columns: a window of 20 s holds 15 of them; zoomed, it gets about 1500.
    context, pg = open_page(browser, server, LONG_RUN)
    try:
        in_window = "document.getElementById('plot-theta').data[0].x.filter(t => t <= 20).length"
        before = pg.evaluate(in_window)
        pg.evaluate("Plotly.relayout('plot-theta', {'xaxis.range': [0, 20]})")
        pg.wait_for_function(f"{in_window} > 1000", timeout=90_000)
        assert before < 100
        d = drawn(pg, "plot-theta")
        t, theta = np.array(d["x"], dtype=float), np.array(d["y"], dtype=float)
        # The page's 30 deg is the double nearest pi/6 (math.radians(30) is one ulp below it).
        full = simulation.simulate(1, float(parse_angle("amplitude", "30deg")), 1e-3, 20.0)
        steps = np.rint(t / 1e-3).astype(int)
        assert np.array_equal(theta, full.theta[steps])  # the simulation's values at those steps, bit for bit
        assert d["xr"] == pytest.approx([0, 20])  # the view stays where it was zoomed
        assert "Zoomed" in pg.locator("#status").text_content()
    finally:
        context.close()
