"""Pendulum-steps per second of the sweep kernel against a plain C loop, side by side.

1000 pendulums, amplitudes 1..179 degrees, l = 1, h = 1e-4 (default), taylor2, each run to
its first return. Peer: the same search in C (``cc -O2``, compiled now) running the
pendulums one after the other on one core. Ours: ``pendulab.jobs.sweep.first_returns`` (the
lock-step kernel, 16 pendulums at a time in vector instructions, on numba's threads over
blocks of pendulums), the same on one thread, and the scalar kernel (the one
``estimate_period`` runs) on one thread. Steps counted are those the scalar kernel took
(``j + 2`` per pendulum); C and the scalar kernel find the same ``j`` for every pendulum.

``--against SRC``: also time the lock-step and the scalar kernels of the pendulab package
in the folder ``SRC`` (another checkout's ``src``), taking turns, by the CPU time of this
thread: the ratio is this tree's rate over that one's (both checked to find the same returns).

Run: ``.venv/bin/python benchmarks/bench_sweep.py [h] [--against SRC]``. ``benchmarks/run.py``
prints these rows in its table.
"""
from __future__ import annotations

import ctypes
import sys
import time

import numpy as np
from _peers import build_c, load_against, ptr, side_by_side
from numba import get_num_threads

from pendulab.jobs.sweep import first_returns, first_returns_serial
from pendulab.numerics.crossing import default_t_max
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import step_count

G = 9.80665


def sweep_rows(dll, h: float = 1e-4, repeat: int = 3, against: str | None = None) -> list[dict]:
    alphas = np.radians(np.linspace(1, 179, 1000))
    cs = np.full_like(alphas, -G)
    n = np.array([step_count(0.0, default_t_max(T, h), h) for T in agm_period(1.0, alphas)], dtype=np.int64)
    j_c = np.empty(len(alphas), dtype=np.int64)
    status, j, _, _ = first_returns_serial(0, 2, alphas, cs, h, n)
    dll.sweep(ptr(alphas), ptr(cs), h, ptr(n, ctypes.c_long), len(alphas), ptr(j_c, ctypes.c_long))
    assert np.all(status == 0) and np.array_equal(j, j_c), "C and numba disagree"
    steps = int(np.sum(j + 2))
    fns = {
        "threads": lambda: first_returns(0, 2, alphas, cs, h, n),
        "lanes": lambda: first_returns(0, 2, alphas, cs, h, n, threads=1),
        "serial": lambda: first_returns_serial(0, 2, alphas, cs, h, n),
        "C": lambda: dll.sweep(ptr(alphas), ptr(cs), h, ptr(n, ctypes.c_long), len(alphas), ptr(j_c, ctypes.c_long)),
    }
    if against:
        from importlib import import_module

        load_against(against)
        other = import_module("pendulab_against.jobs.sweep")
        for theirs, mine in zip(other.first_returns(0, 2, alphas, cs, h, n, threads=1),
                                first_returns(0, 2, alphas, cs, h, n, threads=1), strict=True):
            assert np.array_equal(mine, theirs), "the two trees' lanes disagree"
    t = side_by_side(fns, repeat)
    if against:  # each kernel in this thread: its CPU time, less disturbed by other work
        cpu = side_by_side({
            "lanes": fns["lanes"], "old_lanes": lambda: other.first_returns(0, 2, alphas, cs, h, n, threads=1),
            "serial": fns["serial"], "old_serial": lambda: other.first_returns_serial(0, 2, alphas, cs, h, n),
        }, 3 * repeat, clock=time.thread_time)
    c_rate = steps / t["C"] / 1e6
    return [
        {"what": f"sweep, 1000 pendulums, h = {h:g}, {get_num_threads()} threads (M pendulum-steps/s)",
         "ours": steps / t["threads"] / 1e6, "peer_name": "C loop, one core", "peer": c_rate, "target": ">= 2.0"},
        {"what": "  same, one thread", "ours": steps / t["lanes"] / 1e6,
         "peer_name": "C loop, one core", "peer": c_rate, "target": ""},
        {"what": "  scalar kernel (estimate_period's), one thread", "ours": steps / t["serial"] / 1e6,
         "peer_name": "C loop, one core", "peer": c_rate, "target": ""},
    ] + ([
        {"what": "  lanes, one thread, this tree (CPU time)", "ours": steps / cpu["lanes"] / 1e6,
         "peer_name": "--against tree", "peer": steps / cpu["old_lanes"] / 1e6, "target": ">= 1"},
        {"what": "  scalar kernel, one thread, this tree (CPU time)", "ours": steps / cpu["serial"] / 1e6,
         "peer_name": "--against tree", "peer": steps / cpu["old_serial"] / 1e6, "target": ">= 1"},
    ] if against else [])


def main() -> None:
    from _peers import print_table

    args = sys.argv[1:]
    against = None
    if "--against" in args:
        at = args.index("--against")
        against = args[at + 1]
        del args[at:at + 2]
    h = float(args[0]) if args else 1e-4
    print_table(sweep_rows(build_c(), h, against=against))


if __name__ == "__main__":
    main()
