"""End to end: ``pendulab serve`` in a subprocess, the page in headless Chromium.

A Chromium driven by Playwright: the one ``_browser.find_chromium`` finds (``make test``
installs Debian's ``chromium`` when there is none).
Reference periods: mpmath's complete elliptic integral at 30 digits,
``T = 4 sqrt(l/g) K(sin^2(alpha/2))``, independent of the library's AGM loop.
"""
from __future__ import annotations

import math
import os
import time
from urllib.parse import parse_qs, urlparse

import pytest
from playwright.sync_api import sync_playwright

from pendulab import taylor
from pendulab.web.child import serve_in_child
from _browser import find_chromium
from conftest import ellipk_period

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
    pg = context.new_page()
    pg.outside = []
    pg.errors = []

    def route(r):
        if r.request.url.startswith(server + "/"):
            r.continue_()
        else:
            pg.outside.append(r.request.url)
            r.abort()

    pg.route("**/*", route)
    pg.on("pageerror", lambda e: pg.errors.append(str(e)))
    pg.on("console", lambda m: pg.errors.append(m.text) if m.type == "error" else None)
    yield pg
    context.close()


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
    assert offered == list(taylor.METHODS)


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
