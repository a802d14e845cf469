"""Pendulum-steps per second of the sweep kernel: all cores, one core, and a plain Python loop.

1000 pendulums, amplitudes 1..179 degrees, l = 1, one step h, each run to its first return
(pendulab.sweep.first_returns). Steps counted are those the kernel actually took.
Target (issue 6): 5e7 pendulum-steps/s on 2 cores with taylor2.

Run: .venv/bin/python benchmarks/bench_sweep.py [h]     (default h = 1e-4)
"""
from __future__ import annotations

import math
import os
import sys
import time

import numba
import numpy as np

from pendulab.crossing import default_t_max
from pendulab.period import agm_period
from pendulab.sweep import first_returns, first_returns_serial
from pendulab.taylor import method_code, step_count

G = 9.80665


def python_loop(alpha: float, c: float, h: float, n: int) -> int:
    """The same first-return search as the kernel, in plain Python (the coursework's (3))."""
    z1, z2 = alpha, 0.0
    for i in range(n):
        s = math.sin(z1)
        z1n = z1 + h * z2 + 0.5 * h * h * c * s
        z2n = z2 + h * c * s + 0.5 * h * h * c * z2 * math.cos(z1)
        if z2 > 0.0 and z2n <= 0.0 and z1n > 0.0:
            return i + 2
        z1, z2 = z1n, z2n
    return n


def rate(kernel, code, order, alphas, cs, h, n) -> tuple[float, int]:
    kernel(code, order, alphas[:2], cs[:2], h, n[:2])  # compile / load the cache
    best = math.inf
    for _ in range(3):
        t = time.perf_counter()
        status, j, _, _ = kernel(code, order, alphas, cs, h, n)
        best = min(best, time.perf_counter() - t)
    steps = int(np.sum(j + 2))
    return steps / best, steps


def main() -> None:
    h = float(sys.argv[1]) if len(sys.argv) > 1 else 1e-4
    alphas = np.radians(np.linspace(1, 179, 1000))
    cs = np.full_like(alphas, -G)
    exact = agm_period(1.0, alphas)
    n = np.array([step_count(0.0, default_t_max(T, h), h) for T in exact], dtype=np.int64)
    print(f"1000 pendulums, 1..179 deg, h = {h:g}, {os.cpu_count()} CPUs; million pendulum-steps/s")
    # "parallel, 1 thread": the same parallel kernel with numba.set_num_threads(1), so the
    # ratio to it is the threads' speed-up; "serial kernel" is the one Dask workers run.
    print(f"{'method':>10} {'all cores':>10} {'parallel, 1 thread':>19} {'speed-up':>9} {'serial kernel':>14}")
    for method in ("taylor2", "verlet", "rk4", "taylor:4"):
        code, order = method_code(method)
        par, steps = rate(first_returns, code, order, alphas, cs, h, n)
        numba.set_num_threads(1)
        one, _ = rate(first_returns, code, order, alphas, cs, h, n)
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        ser, _ = rate(first_returns_serial, code, order, alphas, cs, h, n)
        print(f"{method:>10} {par / 1e6:>10.1f} {one / 1e6:>19.1f} {par / one:>9.2f} {ser / 1e6:>14.1f}")
    # Plain Python on 10 pendulums (the peer a user would write first).
    sub = slice(0, 1000, 100)
    t = time.perf_counter()
    steps = sum(python_loop(a, -G, h, int(k)) for a, k in zip(alphas[sub], n[sub]))
    py = steps / (time.perf_counter() - t)
    code, order = method_code("taylor2")
    par, _ = rate(first_returns, code, order, alphas, cs, h, n)
    print(f"plain Python loop, taylor2: {py / 1e6:.2f} million steps/s; numba all cores / Python = {par / py:.0f}")


if __name__ == "__main__":
    main()
