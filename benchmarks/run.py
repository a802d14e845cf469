"""All of pendulab's performance benchmarks in one table: each row measured side by side
with its peer in the same run, as a ratio.

Rows: the Taylor kernels against a C loop (``cc -O2``, compiled now), the sweep against the
same C loop on one core, exact periods against ``scipy.special.ellipk`` on one thread,
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


def ratio(row: dict) -> float | None:
    """pendulab's value over the peer's: a rate (higher is better) or a time (lower is better)."""
    if row.get("peer") in (None, 0):
        return None
    return row["ours"] / row["peer"]


def print_table(rows: list[dict]) -> None:
    """One line per row: what, ours, peer, ratio (higher is better for pendulab), target."""
    print(f"| {'what':66} | {'pendulab':>9} | {'peer':26} | {'peer value':>10} | {'ratio':>6} | {'target':11} |")
    print(f"|{'-' * 68}|{'-' * 11}|{'-' * 28}|{'-' * 12}|{'-' * 8}|{'-' * 13}|")
    for r in rows:
        rt = ratio(r)
        peer = "" if r.get("peer") is None else f"{r['peer']:.3g}"
        print(f"| {r['what']:66} | {r['ours']:>9.3g} | {r['peer_name']:26} | {peer:>10} | "
              f"{'' if rt is None else f'{rt:.2f}x':>6} | {r['target']:11} |")
        if r.get("note"):
            print(f"|   {r['note']} | | | | | |")


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 3 if quick else 5
    from _peers import build_c
    from agm_ulps import ulps_rows
    from bench_core import period_rows, taylor_rows
    from bench_start import start_rows
    from bench_sweep import sweep_rows

    print(f"pendulab benchmarks: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.2f} (1 min)")
    t = time.perf_counter()
    dll = build_c()
    rows = taylor_rows(dll, repeat) + sweep_rows(dll, repeat=repeat) + period_rows(repeat)
    rows += start_rows() + ulps_rows(10_000 if quick else 100_000)
    print()
    print_table(rows)
    print(f"\nratio: pendulab's value over the peer's (rates: higher is better; times: lower is better); "
          f"{time.perf_counter() - t:.0f} s; load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
