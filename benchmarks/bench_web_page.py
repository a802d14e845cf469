"""Benchmark of the explorer page in a browser: weight on the wire, first plot, recompute, frames.

``pendulab serve`` in a child process, the page in headless Chromium (the one the browser
tests drive), on loopback. Side by side in one run, as ratios:

1. weight   bytes on the wire of a cold load (empty cache), gzip accepted (as every browser
            does) and with ``Accept-Encoding: identity`` (what compression saves)
2. first    time from navigation to the period on the page and to the first plot drawn,
            median of ``COLD`` cold loads (a new browser context each)
3. update   a new amplitude typed while the animation plays: the time from the keystroke
            (the ``input`` event, debounce of 200 ms included) to the new period on the page
            and to the angle plot redrawn, median of ``TYPED`` amplitudes
4. frames   animation frames a second while playing, and the script time of one frame
            (the swing, the lab's photogates, stopwatch and energies, the energy bars, the
            four plot cursors)

The aims: at most 1.5 MB on the wire, the first plot within 1.5 s, a new period
within 700 ms of typing, 60 frames a second. Run: ``.venv/bin/python benchmarks/bench_web_page.py``
(about a minute); ``--write`` puts its table into ``docs/performance.md`` between
``<!-- page -->`` and ``<!-- /page -->``.
"""
from __future__ import annotations

import os
import statistics
import subprocess
import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from _peers import write_between  # beside this file

from _browser import find_chromium
from served import serve_in_child

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "performance.md"
BEGIN, END = "<!-- page -->", "<!-- /page -->"

URL = "/?length=3.5&amplitude=144&unit=deg&step=1e-3&t_max=20"
COLD = 5
TYPED = 10
#: The aims: bytes on the wire, ms to the first plot, ms from a keystroke to the new period, frames a second.
AIMS = {"wire": 1.5e6, "plot": 1500.0, "period": 700.0, "fps": 60.0}
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]

#: Records, in page time (ms from navigation), when the period first shows and the first plot is drawn.
WATCH = """
window.__marks = {};
new MutationObserver(() => {
  const m = window.__marks;
  const p = document.getElementById('period-agm');
  if (!m.period && p && p.textContent !== '–') m.period = performance.now();
  if (!m.plot && document.querySelector('.js-plotly-plot .main-svg')) m.plot = performance.now();
}).observe(document, {subtree: true, childList: true, characterData: true});
"""


def cold_load(browser, base: str, identity: bool) -> tuple[int, float, float]:
    """(bytes on the wire, ms to the period, ms to the first plot) of one load with an empty cache."""
    context = browser.new_context(viewport={"width": 1400, "height": 900},
                                  extra_http_headers={"Accept-Encoding": "identity"} if identity else {})
    page = context.new_page()
    page.add_init_script(WATCH)
    cdp = context.new_cdp_session(page)
    cdp.send("Network.enable")
    cdp.send("Network.setCacheDisabled", {"cacheDisabled": True})
    wire: list[int] = []
    cdp.on("Network.loadingFinished", lambda e: wire.append(int(e["encodedDataLength"])))
    page.goto(base + URL)
    page.wait_for_function("window.__marks.plot && window.__marks.period", timeout=60_000)
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=60_000)
    page.wait_for_timeout(300)  # the convergence and ratio requests that follow the first plot
    marks = page.evaluate("window.__marks")
    context.close()
    return sum(wire), marks["period"], marks["plot"]


def typing(browser, base: str, typed: int = TYPED) -> tuple[list[float], list[float], list[float], float]:
    """Recompute times (ms) to the period and to the redrawn angle plot; frame rate and script ms per frame."""
    context = browser.new_context(viewport={"width": 1400, "height": 900})
    page = context.new_page()
    page.goto(base + URL)
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=60_000)
    page.wait_for_timeout(500)
    to_period, to_plot = [], []
    for k in range(typed):
        amplitude = 100 + 5 * k
        ms = page.evaluate("""(a) => new Promise((done) => {
            const gd = document.getElementById('plot-theta'), period = document.getElementById('period-agm');
            const before = period.textContent, t0 = performance.now(); let tp = null;
            const obs = new MutationObserver(() => { if (tp === null && period.textContent !== before) tp = performance.now(); });
            obs.observe(period, {childList: true, characterData: true, subtree: true});
            const plotted = () => { if (tp === null) return; gd.removeListener('plotly_afterplot', plotted); obs.disconnect();
                                    done([tp - t0, performance.now() - t0]); };
            gd.on('plotly_afterplot', plotted);
            const input = document.getElementById('amplitude'); input.value = String(a);
            input.dispatchEvent(new Event('input'));
        })""", amplitude)
        to_period.append(ms[0])
        to_plot.append(ms[1])
        page.wait_for_timeout(300)
    frames = page.evaluate("""() => new Promise((done) => {
        const inner = window.tick; const spent = [];
        window.tick = function () { const t = performance.now(); inner(); spent.push(performance.now() - t); };
        let n = 0; const t0 = performance.now();
        const count = () => { n++; if (performance.now() - t0 < 2000) requestAnimationFrame(count);
                              else { window.tick = inner; done([n / ((performance.now() - t0) / 1000), spent]); } };
        requestAnimationFrame(count);
    })""")
    context.close()
    return to_period, to_plot, frames[1], frames[0]


def measure(cold: int = COLD, typed: int = TYPED) -> dict:
    """Every measurement of the page, one server and one browser: ``gz`` and ``plain`` (the
    cold loads, gzip and identity), ``to_period``, ``to_plot``, ``spent`` (ms) and ``fps``.

    Raises :class:`LookupError` where no Chromium is found (the line says how to get one).
    """
    with serve_in_child() as base, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=find_chromium(p), args=ARGS)
        cold_load(browser, base, False)  # warm the server (numba's cache, the first AGM)
        gz = [cold_load(browser, base, False) for _ in range(cold)]
        plain = [cold_load(browser, base, True) for _ in range(cold)]
        to_period, to_plot, spent, fps = typing(browser, base, typed)
        version = browser.version
        browser.close()
    return {"gz": gz, "plain": plain, "to_period": to_period, "to_plot": to_plot, "spent": spent, "fps": fps,
            "browser": version}


def page_rows(cold: int = COLD, typed: int = TYPED) -> list[dict]:
    """The page's rows of the one table (``benchmarks/run.py``): the bytes a browser fetches
    against the same page uncompressed (a peer measured in the same run), and the times and
    frame rate against the aims (no peer program draws this page)."""
    m = measure(cold, typed)
    med = statistics.median
    aim = "aim"
    return [
        {"what": f"explorer page, cold load, gzip (kB on the wire, median of {cold})", "ours": med(r[0] for r in m["gz"]) / 1e3,
         "peer_name": "the same, no compression", "peer": med(r[0] for r in m["plain"]) / 1e3, "target": "", "lower": True},
        {"what": "  same, against the aim (kB)", "ours": med(r[0] for r in m["gz"]) / 1e3, "peer_name": aim,
         "peer": AIMS["wire"] / 1e3, "target": "<= 1.0", "lower": True},
        {"what": f"  first plot drawn (ms from navigation, median of {cold})", "ours": med(r[2] for r in m["gz"]),
         "peer_name": aim, "peer": AIMS["plot"], "target": "<= 1.0", "lower": True},
        {"what": f"explorer page, keystroke to new period (ms, median of {typed})",
         "ours": med(m["to_period"]), "peer_name": aim, "peer": AIMS["period"], "target": "<= 1.0", "lower": True},
        {"what": "explorer page, animation (frames a second)", "ours": m["fps"], "peer_name": aim, "peer": AIMS["fps"],
         "target": ">= 0.92"},
    ]


def _shown(x: float) -> str:
    """A measurement as the table shows it: whole from 100 up (1042 ms, not 1.04e+03), else 3 digits."""
    return f"{x:.0f}" if abs(x) >= 100 else f"{x:.3g}"


def table(m: dict, load: tuple[float, float]) -> str:
    """The measurements as a Markdown table, medians and maxima against the aims (the shape
    ``--write`` puts into docs/performance.md), and a line saying where they were taken."""
    med = statistics.median
    gz = [r[0] / 1e3 for r in m["gz"]]
    rows = [
        ("cold page on the wire, gzip (kB)", gz, AIMS["wire"] / 1e3),
        ("the same without compression (kB)", [r[0] / 1e3 for r in m["plain"]], None),
        ("navigation to the period shown (ms)", [r[1] for r in m["gz"]], None),
        ("navigation to the first plot (ms)", [r[2] for r in m["gz"]], AIMS["plot"]),
        ("a new amplitude typed to its period shown, 200 ms debounce included (ms)", m["to_period"], AIMS["period"]),
        ("the same to the angle plot redrawn (ms)", m["to_plot"], None),
        ("script per animation frame (ms)", m["spent"], None),
    ]
    lines = ["| measure | median | max | aim | median / aim |", "|---|---:|---:|---:|---:|"]
    for name, values, aim in rows:
        mid = med(values)
        lines.append(f"| {name} | {_shown(mid)} | {_shown(max(values))} | {'' if aim is None else f'{aim:.4g}'} | "
                     f"{'' if aim is None else f'{mid / aim:.2f}'} |")
    lines.append(f"| animation frames a second | {m['fps']:.3g} | | {AIMS['fps']:.3g} | {m['fps'] / AIMS['fps']:.2f} |")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    lines.append("")
    lines.append(f"One run of `benchmarks/bench_web_page.py` at {commit or 'this tree'}: headless Chromium "
                 f"{m['browser']}, {os.cpu_count()} CPUs, load average {load[0]:.1f} at the start, {load[1]:.1f} at the end; "
                 f"medians of {len(m['gz'])} cold loads and {len(m['to_period'])} typed amplitudes.")
    return "\n".join(lines)


def main() -> None:
    start_load = os.getloadavg()[0]
    m = measure()
    gz, plain, to_period, to_plot, spent, fps = (m[k] for k in ("gz", "plain", "to_period", "to_plot", "spent", "fps"))
    med = statistics.median
    print(f"load average {os.getloadavg()[0]:.2f} (1 min) after the run, {os.cpu_count()} CPUs: "
          "times are only comparable between runs at a similar load")
    gz_bytes, plain_bytes = med(r[0] for r in gz), med(r[0] for r in plain)
    print(f"cold page load, problem 5's pendulum, 1400x900, median of {COLD} loads")
    print(f"{'':34} {'wire kB':>9} {'period ms':>10} {'1st plot ms':>12} {'bytes ratio':>12}")
    for name, rows, size in (("gzip (what a browser asks for)", gz, gz_bytes),
                             ("identity (no compression)", plain, plain_bytes)):
        print(f"{name:34} {size / 1e3:9.0f} {med(r[1] for r in rows):10.0f} {med(r[2] for r in rows):12.0f} "
              f"{size / gz_bytes:12.2f}")
    print(f"\nnew amplitude typed while the animation plays (200 ms debounce included), {TYPED} values")
    print(f"  to the new period:      median {med(to_period):6.0f} ms, max {max(to_period):6.0f} ms")
    print(f"  to the angle plot:      median {med(to_plot):6.0f} ms, max {max(to_plot):6.0f} ms")
    print(f"animation: {fps:.1f} frames a second; script per frame median {med(spent):.2f} ms, "
          f"max {max(spent):.2f} ms ({len(spent)} frames)")
    checks = [("wire <= 1.5 MB", gz_bytes <= AIMS["wire"]), ("first plot <= 1.5 s", med(r[2] for r in gz) <= AIMS["plot"]),
              ("period <= 700 ms after typing", med(to_period) <= AIMS["period"]),
              ("about 60 frames a second", fps >= 0.92 * AIMS["fps"])]
    print("aims: " + "; ".join(f"{name}: {'met' if ok else 'NOT met'}" for name, ok in checks))
    if "--write" in sys.argv:
        write_between(DOC, BEGIN, END, table(m, (start_load, os.getloadavg()[0])))
        print(f"written to {DOC}")


if __name__ == "__main__":
    main()
