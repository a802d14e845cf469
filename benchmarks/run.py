"""All of pendulab's performance benchmarks in one table: each row measured side by side
with its peer in the same run, as a ratio.

Rows: the Taylor kernels against a C loop (``cc -O2``, compiled now), the sweep against the
same C loop on one core, exact periods against ``scipy.special.ellipk`` on one thread, the
AGM in double precision against the coursework program, numpy and ``scipy.special.ellipkm1``,
``pendulab period`` against ``import numpy``, cold starts against warm ones, the warm
``pendulab report`` against the import floor (``import numpy, matplotlib.pyplot, typst``),
the explorer page in headless Chromium (its bytes against the same page uncompressed, its
times and frame rate against the aims; left out, with a line that says why, where no
Chromium or Playwright is found), and whether ``agm_period`` is correctly rounded (10^5
pendulums against mpmath). The machine's load (``os.getloadavg``) is printed before and
after: ratios are only meaningful when it is low.

Run: ``make bench`` or ``.venv/bin/python benchmarks/run.py [--quick] [--write]`` (about 4
minutes; ``--quick``: 10^4 pendulums for the rounding check, 3 repeats instead of 5, 2 of
the report and its floor, 2 cold page loads and 3 typed amplitudes). ``--write`` puts the
table into ``docs/performance.md`` between ``<!-- kernels -->`` and ``<!-- /kernels -->``.
"""
from __future__ import annotations

import contextlib
import io
import os
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 3 if quick else 5
    from _peers import build_c, print_table
    from agm_ulps import ulps_rows
    from bench_agm import agm_rows
    from bench_core import period_rows, taylor_rows
    from bench_start import start_rows
    from bench_sweep import sweep_rows

    load = os.getloadavg()[0]
    print(f"pendulab benchmarks: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load average {load:.2f} (1 min)")
    t = time.perf_counter()
    dll = build_c()
    rows = taylor_rows(dll, repeat) + sweep_rows(dll, repeat=repeat) + period_rows(repeat) + agm_rows(5 * repeat)
    rows += start_rows()
    left_out: list[str] = []
    rows += report(2 if quick else repeat, left_out) + page((2, 3) if quick else (5, 10), left_out)
    rows += ulps_rows(10_000 if quick else 100_000)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        print_table(rows)
        for line in left_out:
            print(line)
        print(f"\nOne run of `benchmarks/run.py{' --quick' if quick else ''}`: {os.cpu_count()} CPUs, "
              f"{time.perf_counter() - t:.0f} s, load average {load:.1f} at the start, "
              f"{os.getloadavg()[0]:.1f} at the end. The ratio is pendulab's value over the peer's "
              "(rates: higher is better; times: lower is better).")
    print()
    print(out.getvalue(), end="")
    if "--write" in sys.argv:
        from _peers import write_between

        write_between(Path(__file__).resolve().parent.parent / "docs" / "performance.md",
                      "<!-- kernels -->", "<!-- /kernels -->", out.getvalue().rstrip())


def report(repeat: int, left_out: list[str]) -> list[dict]:
    """The warm report's rows, where its extra (typst, matplotlib) is installed."""
    import importlib.util

    missing = [m for m in ("typst", "matplotlib") if importlib.util.find_spec(m) is None]
    if missing:
        left_out.append(f"left out: the warm report ({', '.join(missing)} not installed: pip install '.[report]')")
        return []
    from bench_report import report_rows

    return report_rows(repeat)


def page(rounds: tuple[int, int], left_out: list[str]) -> list[dict]:
    """The explorer page's rows (``rounds``: cold loads, typed amplitudes), where Playwright
    and a Chromium are found."""
    try:
        from bench_web_page import page_rows
    except ImportError as exc:
        left_out.append(f"left out: the explorer page ({exc.name or exc} not installed: pip install '.[test]')")
        return []
    try:
        return page_rows(*rounds)
    except LookupError as exc:  # no Chromium: the line says how to get one
        left_out.append(f"left out: the explorer page ({exc})")
        return []


if __name__ == "__main__":
    main()
