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

import numpy as np
import pytest
from playwright.sync_api import TimeoutError as PlaywrightTimeoutError
from playwright.sync_api import sync_playwright

from _browser import find_chromium
from conftest import ellipk_period
from pendulab import taylor
from pendulab.web.child import serve_in_child

CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
]


@pytest.fixture(scope="module")
def server():
    """The real command, ``pendulab serve --port N``, until the module's tests are done."""
    with serve_in_child() as base:
        yield base


@pytest.fixture(scope="module")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=find_chromium(p), args=CHROMIUM_ARGS)
        yield b
        b.close()


@pytest.fixture
def page(browser, server):
    """A page that may reach nothing but the pendulab server: anything else is recorded and aborted."""
    context = browser.new_context(viewport={"width": 1400, "height": 1100}, accept_downloads=True)
    yield guarded_page(context, server)
    context.close()


def guarded_page(context, server):
    """A new page of ``context`` that records (and aborts) requests leaving the server, and console errors."""
    pg = context.new_page()
    pg.outside, pg.errors = [], []

    def route(r):
        if r.request.url.startswith(server + "/"):
            r.continue_()
        else:
            pg.outside.append(r.request.url)
            r.abort()

    pg.route("**/*", route)
    pg.on("pageerror", lambda e: pg.errors.append(str(e)))
    pg.on("console", lambda m: pg.errors.append(m.text) if m.type == "error" else None)
    return pg


def shown_period(pg) -> float:
    return float(pg.locator("#period-exact").text_content())


def wait_for_period(pg, expected: float, timeout: float = 20.0) -> float:
    """Poll the period on the page until it shows ``expected`` (12 significant digits)."""
    deadline = time.monotonic() + timeout
    while True:
        text = pg.locator("#period-exact").text_content()
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
    assert shot.stat().st_size > 50_000  # a drawn page, not a blank one
    assert page.outside == [] and page.errors == []


def test_the_url_reproduces_the_view(page, server):
    url = server + "/?length=2.0800838231&amplitude=4pi%2F5&unit=rad&g=9.80665&method=taylor2&step=0.01&t_max=12&speed=2"
    page.goto(url)
    wait_for_period(page, ellipk_period(2.0800838231, 0.8 * math.pi))
    assert page.input_value("#length") == "2.0800838231"
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
    assert offered == list(taylor.METHODS) + [f"taylor:{p}" for p in range(1, 31)]
    assert "Euler" in page.locator("#method option[value='taylor:1']").text_content()
    assert page.eval_on_selector_all("#method2 option", "os => os.map(o => o.value)") == [""] + offered


def test_csv_download_is_the_trajectory(page, server, tmp_path):
    page.goto(server + "/?length=1&amplitude=pi%2F4&unit=rad&step=0.1&t_max=2.1")
    wait_for_period(page, ellipk_period(1, math.pi / 4))
    with page.expect_download() as info:
        page.click("#csv")
    path = tmp_path / "trajectory.csv"
    info.value.save_as(path)
    lines = path.read_text().splitlines()
    assert lines[0] == "t_s,theta_rad,omega_rad_per_s" and len(lines) == 1 + 22
    # Figure 3 of the coursework, t = 2.1: z1 = 0.796774928412, z2 = -0.297068336875 (as the coursework prints them).
    t, z1, z2 = map(float, lines[-1].split(","))
    assert t == pytest.approx(2.1) and z1 == pytest.approx(0.796774928412, rel=1e-11)
    assert z2 == pytest.approx(-0.297068336875, rel=1e-11)


def test_bad_input_is_named_on_the_page(page, server):
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    wait_for_period(page, ellipk_period(3.5, 0.8 * math.pi))
    page.fill("#step", "0")
    page.wait_for_selector("#error:not([hidden])")
    assert page.locator("#error").text_content().startswith("step = 0 is not allowed")
    assert "invalid" in page.get_attribute("#step", "class")
    page.fill("#amplitude", "200")
    page.fill("#step", "1e-3")
    page.wait_for_function("document.querySelector('#error').textContent.startsWith('amplitude')")
    assert "invalid" in page.get_attribute("#amplitude", "class")
    # The value is echoed as typed (with the unit sent apart), not as "200deg".
    assert page.locator("#error").text_content().startswith("amplitude = 200 is not allowed")
    page.fill("#amplitude", "30")
    wait_for_period(page, ellipk_period(3.5, math.pi / 6))
    assert page.locator("#error").is_hidden()


def test_play_pause(page, server):
    page.goto(server + "/?length=1&amplitude=30&unit=deg&step=1e-3&t_max=10")
    wait_for_period(page, ellipk_period(1, math.pi / 6))

    def clock() -> float:
        return float(page.locator("#clock").text_content().split()[2])

    a = clock()
    page.wait_for_timeout(400)
    assert clock() != a  # it swings
    page.click("#play")
    assert page.locator("#play").text_content() == "Play"
    a = clock()
    page.wait_for_timeout(400)
    assert clock() == a  # paused


# ---------------------------------------------------------------- every screen, every state

LONG_RUN = "/?length=1&amplitude=30&unit=deg&g=9.80665&method=taylor2&step=1e-3&t_max=2000"
VIEWPORTS = [(390, 844), (1024, 768), (1400, 900)]


def open_page(browser, server, url: str, width: int = 1400, height: int = 1100):
    context = browser.new_context(viewport={"width": width, "height": height})
    pg = guarded_page(context, server)
    pg.goto(server + url)
    pg.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 6", timeout=60_000)
    pg.wait_for_function("document.querySelector('#status').textContent.includes('steps of')", timeout=60_000)
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
                                 "p.title[2] <= p.bar[0] || p.title[1] >= p.bar[3])", timeout=10_000)
        plots = pg.evaluate(TITLE_AND_MODE_BAR)
        assert len(plots) == 6 and all(p["title"] for p in plots)
        assert any(p["bar"] for p in plots) == (width >= 700)
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
        full = taylor.simulate(1, alpha, 1e-3, 2000.0)
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
        assert title == f"Phase portrait: {phase['orbits']} periods sampled, 0 to {phase['t_last']:.12g} s"
        assert phase["t_last"] > 0.9 * 2000
        assert pg.errors == []
    finally:
        context.close()


def clock(pg) -> tuple[float, float]:
    parts = pg.locator("#clock").text_content().split()
    return float(parts[2]), float(parts[6].rstrip("°"))


def test_the_animation_shows_the_true_state_at_its_time(browser, server):
    # Before: -15.6 deg shown at t = 1 s where the simulated pendulum is at -29.9 deg.
    context, pg = open_page(browser, server, LONG_RUN + "&paused=1&t=1")
    try:
        t, shown = clock(pg)
        assert t == 1.0 and pg.locator("#play").text_content() == "Play"
        full = taylor.simulate(1, math.radians(30), 1e-3, 2.0)
        assert shown == pytest.approx(math.degrees(full.theta[1000]), abs=0.01)
        # The time cursor: the same time on theta(t), the error and energy plots, the same state on the phase portrait.
        for plot in ("plot-theta", "plot-error", "plot-energy"):
            assert pg.evaluate(f"document.getElementById('{plot}').layout.shapes[0].x0") == 1.0
        dot = pg.evaluate("(() => { const gd = document.getElementById('plot-phase'); return gd.data[gd.data.length - 1].x[0]; })()")
        assert math.degrees(dot) == pytest.approx(math.degrees(full.theta[1000]), abs=0.01)
        # Moving the cursor moves all of them and goes into the URL.
        pg.evaluate("(() => { const c = document.getElementById('cursor'); c.value = '1.5'; c.dispatchEvent(new Event('input')); })()")
        t, shown = clock(pg)
        assert t == 1.5 and shown == pytest.approx(math.degrees(full.theta[1500]), abs=0.01)
        assert pg.evaluate("document.getElementById('plot-theta').layout.shapes[0].x0") == 1.5
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
    page.goto(server + "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20")
    wait_for_period(page, ellipk_period(3.5, 0.8 * math.pi))
    assert page.evaluate("getComputedStyle(document.getElementById('results')).opacity") == "1"
    page.fill("#length", "abc")
    page.wait_for_selector("#error:not([hidden])")
    page.wait_for_function("getComputedStyle(document.getElementById('results')).opacity < 0.5")
    assert "length" in page.locator("#error").text_content()
    page.fill("#length", "2")
    wait_for_period(page, ellipk_period(2, 0.8 * math.pi))
    page.wait_for_function("getComputedStyle(document.getElementById('results')).opacity == 1")


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
    page.wait_for_selector(".swagger-ui .opblock", timeout=30_000)
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
        pg.wait_for_function("document.querySelectorAll('.js-plotly-plot').length == 6 && "
                             "document.querySelector('#plot-convergence .xtick')", timeout=60_000)
        plots = pg.evaluate(PLOT_PARTS)
        assert len(plots) == 6
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


@pytest.mark.parametrize("width, height", VIEWPORTS)
def test_the_controls_come_first(browser, server, width, height):
    # At 1024 px the controls were a narrow sticky column beside the results: scrolled, it sat
    # beside the Period card halfway down, an empty column above and below it.
    context, pg = open_page(browser, server, "/", width, height)
    try:
        pg.evaluate("window.scrollTo(0, document.body.scrollHeight)")
        pg.wait_for_timeout(200)
        pg.evaluate("window.scrollTo(0, 0)")
        box = pg.evaluate("""() => Object.fromEntries(['inputs', 'animation', 'periods', 'results'].map(id => {
            const r = document.getElementById(id).getBoundingClientRect();
            return [id, [r.left, r.top + scrollY, r.right, r.bottom + scrollY]]; }))""")
        form, results = box["inputs"], box["results"]
        if width > 1100:  # a sidebar: to the left of the results, from their top
            assert form[2] <= results[0] and form[1] <= results[1] + 1
        else:  # above the results, the width of the page, and all of it shown (nothing to scroll inside)
            assert form[3] <= results[1] and form[3] <= box["animation"][1]
            assert form[2] - form[0] >= results[2] - results[0] - 1
            assert pg.evaluate("(() => { const f = document.getElementById('inputs'); return f.scrollHeight <= f.clientHeight + 1; })()")
        # The swing comes before the period, which comes before the plots.
        assert box["animation"][1] <= box["periods"][1]
        assert pg.errors == []
    finally:
        context.close()
