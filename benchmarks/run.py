"""All of pendulab's performance benchmarks in one table: each row measured side by side
with its peer in the same run, as a ratio.

Rows: the Taylor kernels against a C loop (``cc -O2``, compiled now), the sweep against the
same C loop on one core, exact periods against ``scipy.special.ellipk`` on one thread, the
AGM in double precision against the coursework program, numpy and ``scipy.special.ellipkm1``,
``pendulab period`` against ``import numpy``, cold starts against warm ones, and whether
``agm_period`` is correctly rounded (10^5 pendulums against mpmath). The machine's load
(``os.getloadavg``) is printed before and after: ratios are only meaningful when it is low.

Run: ``make bench`` or ``.venv/bin/python benchmarks/run.py [--quick]`` (about 2 minutes;
``--quick``: 10^4 pendulums for the rounding check, 3 repeats instead of 5).
"""
from __future__ import annotations

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

    print(f"pendulab benchmarks: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.2f} (1 min)")
    t = time.perf_counter()
    dll = build_c()
    rows = taylor_rows(dll, repeat) + sweep_rows(dll, repeat=repeat) + period_rows(repeat) + agm_rows(5 * repeat)
    rows += start_rows() + ulps_rows(10_000 if quick else 100_000)
    print()
    print_table(rows)
    print(f"\nratio: pendulab's value over the peer's (rates: higher is better; times: lower is better); "
          f"{time.perf_counter() - t:.0f} s; load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
