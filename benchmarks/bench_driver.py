"""The trajectory driver against the loops it replaces.

Side by side in one run (best of ``REPEAT`` rounds, taking turns, of the thread's CPU time:
the kernels run on one thread, and other work on a shared machine takes the core away from
either at random), on the example group's pendulum (l = 2.0800838231 m, alpha = 4 pi/5):

- :func:`pendulab.engine.kernels.drive` (every step; one in 1000 kept; the explorer's CSV blocks
  from a carried state) against separate loops compiled here as they would be written
  without it: a plain loop, a thinning loop, the web's ``advance`` with its ``i % stride``
  per step. These loops step through :func:`pendulab.engine.kernels.step`, as the driver does.

Every pair is checked to give the same bits before it is timed. Ratios are ours/baseline
times: below 1 is faster. Run: ``.venv/bin/python benchmarks/bench_driver.py [--quick]``.
"""
from __future__ import annotations

import math
import os
import sys
import time

import numpy as np
from _peers import side_by_side
from numba import njit

from pendulab.engine.kernels import RK4, TAYLOR2, VERLET, drive, step

G = 9.80665
ALPHA, C = 4 * math.pi / 5, -G / 2.0800838231
REPEAT = 3 if "--quick" in sys.argv else 15


# ------------------------------------------------------------------ the loops the driver replaces
@njit(cache=True, nogil=True)
def plain_loop(method, order, alpha, c, h, z1, z2):
    a, b = alpha, 0.0
    for i in range(len(z1)):
        a, b = step(method, order, a, b, h, c)
        z1[i] = a
        z2[i] = b


@njit(cache=True, nogil=True)
def thinning_loop(method, order, alpha, c, h, n, stride, z1, z2):
    a, b = alpha, 0.0
    k = 0
    keep = stride
    for i in range(1, n + 1):
        a, b = step(method, order, a, b, h, c)
        if i == keep or i == n:  # noqa: SIM109
            z1[k] = a
            z2[k] = b
            k += 1
            keep += stride


@njit(cache=True, nogil=True)
def modulo_loop(method, order, z1, z2, c, h, i0, i1, stride, n, out1, out2, out_i):
    k = 0
    for i in range(i0 + 1, i1 + 1):
        z1, z2 = step(method, order, z1, z2, h, c)
        if i % stride == 0 or i == n:
            out1[k] = z1
            out2[k] = z2
            out_i[k] = i
            k += 1
    return z1, z2, k


def _drive_all(code, order, h, z1, z2):
    n = len(z1)
    return drive(code, order, ALPHA, 0.0, C, h, 0, n, 1, n, z1, z2)


def every_step_row(code: int, order: int, name: str, h: float, n: int) -> dict:
    z1, z2, r1, r2 = (np.empty(n) for _ in range(4))
    _drive_all(code, order, h, z1, z2)
    plain_loop(code, order, ALPHA, C, h, r1, r2)
    assert np.array_equal(z1, r1) and np.array_equal(z2, r2)
    t = side_by_side({"driver": lambda: _drive_all(code, order, h, z1, z2),
                      "loop": lambda: plain_loop(code, order, ALPHA, C, h, r1, r2)}, REPEAT, time.thread_time)
    return {"what": f"drive, {name}, every step, h = {h:g} (s per 10^6 steps)", "ours": t["driver"] * 1e6 / n,
            "peer_name": "plain loop, four branches", "peer": t["loop"] * 1e6 / n, "target": "<= 1.0x"}


def rows() -> list[dict]:
    n, stride = 1_000_000, 1000
    out = [every_step_row(TAYLOR2, 2, "taylor2", 1e-3, n), every_step_row(RK4, 4, "rk4", 1e-3, n // 2),
           every_step_row(VERLET, 2, "verlet", 1e-3, n)]
    h = 1e-3
    size = n // stride + (n % stride != 0)  # the kept steps: stride, 2 stride, ..., n
    z1, z2, r1, r2 = (np.empty(size) for _ in range(4))
    drive(TAYLOR2, 2, ALPHA, 0.0, C, h, 0, n, stride, n, z1, z2)
    thinning_loop(TAYLOR2, 2, ALPHA, C, h, n, stride, r1, r2)
    assert np.array_equal(z1, r1) and np.array_equal(z2, r2)
    t = side_by_side({"driver": lambda: drive(TAYLOR2, 2, ALPHA, 0.0, C, h, 0, n, stride, n, z1, z2),
                      "loop": lambda: thinning_loop(TAYLOR2, 2, ALPHA, C, h, n, stride, r1, r2)}, REPEAT, time.thread_time)
    out.append({"what": f"drive, taylor2, 1 in {stride} kept, h = {h:g} (s per 10^6 steps)", "ours": t["driver"],
                "peer_name": "the thinning loop", "peer": t["loop"], "target": "<= 1.0x"})
    # The explorer's CSV: blocks of 65536 steps from a carried state, 1 in 7 kept.
    block, stride = 65536, 7
    size = block // stride + 2
    o1, o2, q1, q2 = (np.empty(size) for _ in range(4))
    oi = np.empty(size, dtype=np.int64)

    def by_driver():
        a, b, kept = ALPHA, 0.0, []
        for i0 in range(0, n, block):
            a, b, k = drive(TAYLOR2, 2, a, b, C, h, i0, min(n, i0 + block), stride, n, o1, o2)
            kept.append(o1[k - 1])
        return a, b, kept

    def by_modulo():
        a, b, kept = ALPHA, 0.0, []
        for i0 in range(0, n, block):
            a, b, k = modulo_loop(TAYLOR2, 2, a, b, C, h, i0, min(n, i0 + block), stride, n, q1, q2, oi)
            kept.append(q1[k - 1])
        return a, b, kept

    assert by_driver() == by_modulo()
    t = side_by_side({"driver": by_driver, "loop": by_modulo}, REPEAT, time.thread_time)
    out.append({"what": f"CSV blocks from a carried state, 1 in {stride} kept (s per 10^6 steps)",
                "ours": t["driver"], "peer_name": "advance (i % stride)", "peer": t["loop"], "target": "<= 1.0x"})
    return out


if __name__ == "__main__":
    from _peers import print_table

    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} CPUs; ratio = ours / peer (times)")
    print_table(rows())
    print(f"load average now {os.getloadavg()[0]:.2f}")
