"""The trajectory driver against the loops it replaces, and the certified fast step against the literal one.

Side by side in one run (best of ``REPEAT`` rounds, taking turns), on the example group's
pendulum (l = 2.0800838231 m, alpha = 4 pi/5) with the coursework's algorithm (3):

- ``fill_trajectory`` and ``fill_thinned`` (both now :func:`pendulab._kernels.drive`) and the
  explorer's CSV blocks (``drive`` from a carried state) against the separate loops they
  replace, compiled here as they were written: a plain loop, a thinning loop, and the web's
  ``advance`` with its ``i % stride`` per step;
- the literal step (the C library's sin and cos) against the table step with its rounding
  certificate (``taylor2_fast_step``), at h = 1e-6 (the fine steps where the certificate
  passes) and h = 1e-3.

Every pair is checked to give the same bits before it is timed. Ratios are ours/baseline
times: below 1 is faster. Run: ``.venv/bin/python benchmarks/bench_driver.py [--quick]``.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
from _peers import side_by_side
from numba import njit

from pendulab._kernels import TAYLOR2, drive, fill_thinned, fill_trajectory, step, taylor2_fast_step

G = 9.80665
ALPHA, C = 4 * math.pi / 5, -G / 2.0800838231
REPEAT = 3 if "--quick" in sys.argv else 15


# ------------------------------------------------------------------ the loops the driver replaces
@njit(cache=True, nogil=True)
def plain_loop(method, order, alpha, c, h, z1, z2):
    a, b = alpha, 0.0
    z1[0] = a
    z2[0] = b
    for i in range(1, len(z1)):
        a, b = step(method, order, a, b, h, c)
        z1[i] = a
        z2[i] = b


@njit(cache=True, nogil=True)
def thinning_loop(method, order, alpha, c, h, n, stride, z1, z2):
    a, b = alpha, 0.0
    z1[0] = a
    z2[0] = b
    k = 1
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


@njit(cache=True, nogil=True)
def fast_loop(alpha, c, h, z1, z2):
    a, b = alpha, 0.0
    z1[0] = a
    z2[0] = b
    for i in range(1, len(z1)):
        a, b = taylor2_fast_step(a, b, h, c)
        z1[i] = a
        z2[i] = b


def every_step_rows(n: int, h: float) -> list[dict]:
    z1, z2, r1, r2 = (np.empty(n + 1) for _ in range(4))
    fill_trajectory(TAYLOR2, 2, ALPHA, C, h, z1, z2)
    plain_loop(TAYLOR2, 2, ALPHA, C, h, r1, r2)
    assert np.array_equal(z1, r1) and np.array_equal(z2, r2)
    t = side_by_side({"driver": lambda: fill_trajectory(TAYLOR2, 2, ALPHA, C, h, z1, z2),
                      "loop": lambda: plain_loop(TAYLOR2, 2, ALPHA, C, h, r1, r2)}, REPEAT)
    out = [{"what": f"trajectory, every step, h = {h:g} (s per 10^6 steps)", "ours": t["driver"],
            "peer_name": "the plain loop", "peer": t["loop"], "target": "<= 1.0x"}]
    fast_loop(ALPHA, C, h, r1, r2)
    assert np.array_equal(z1, r1) and np.array_equal(z2, r2)
    t = side_by_side({"literal": lambda: fill_trajectory(TAYLOR2, 2, ALPHA, C, h, z1, z2),
                      "fast": lambda: fast_loop(ALPHA, C, h, r1, r2)}, REPEAT)
    out.append({"what": f"trajectory, literal step, h = {h:g} (s per 10^6 steps)", "ours": t["literal"],
                "peer_name": "certified table step", "peer": t["fast"], "target": "decision"})
    return out


def rows() -> list[dict]:
    n, stride = 1_000_000, 1000
    out = every_step_rows(n, 1e-3) + every_step_rows(n, 1e-6)
    h = 1e-3
    size = n // stride + 2
    z1, z2, r1, r2 = (np.empty(size) for _ in range(4))
    fill_thinned(TAYLOR2, 2, ALPHA, C, h, n, stride, z1, z2)
    thinning_loop(TAYLOR2, 2, ALPHA, C, h, n, stride, r1, r2)
    kept = n // stride + 1
    assert np.array_equal(z1[:kept], r1[:kept]) and np.array_equal(z2[:kept], r2[:kept])
    t = side_by_side({"driver": lambda: fill_thinned(TAYLOR2, 2, ALPHA, C, h, n, stride, z1, z2),
                      "loop": lambda: thinning_loop(TAYLOR2, 2, ALPHA, C, h, n, stride, r1, r2)}, REPEAT)
    out.append({"what": f"trajectory, 1 in {stride} kept, h = {h:g} (s per 10^6 steps)", "ours": t["driver"],
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
    t = side_by_side({"driver": by_driver, "loop": by_modulo}, REPEAT)
    out.append({"what": f"CSV blocks from a carried state, 1 in {stride} kept (s per 10^6 steps)",
                "ours": t["driver"], "peer_name": "advance (i % stride)", "peer": t["loop"], "target": "<= 1.0x"})
    return out


if __name__ == "__main__":
    from _peers import print_table

    print(f"load average {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} CPUs; ratio = ours / peer (times)")
    print_table(rows())
    print(f"load average now {os.getloadavg()[0]:.2f}")
