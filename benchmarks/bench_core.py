"""Benchmark of the foundation's kernels against their peers, side by side, as ratios.

1. Taylor steps (3) per second: the numba kernel against the same recurrence as a plain
   Python loop and as a plain C loop compiled now with the system's ``cc -O2`` (the
   practical limit: each step costs one sin and one cos).
2. Exact periods per second on 10^6 amplitudes: the vectorised AGM (7)-(8) against
   ``scipy.special.ellipk``, with the accuracy of both against mpmath.

Run: ``.venv/bin/python benchmarks/bench_core.py`` (about 30 s).
"""
from __future__ import annotations

import ctypes
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import mpmath
import numpy as np

from pendulab._kernels import TAYLOR2, fill_trajectory, first_return
from pendulab.period import agm_period

C_SOURCE = r"""
#include <math.h>
/* Equations (3), storing every point, as pendulab._kernels.trajectory does. */
void taylor2(double alpha, double c, double h, long n, double *z1, double *z2) {
    z1[0] = alpha; z2[0] = 0.0;
    for (long i = 0; i < n; i++) {
        double s = sin(z1[i]);
        z1[i + 1] = z1[i] + h * z2[i] + 0.5 * h * h * c * s;
        z2[i + 1] = z2[i] + h * c * s + 0.5 * h * h * c * z2[i] * cos(z1[i]);
    }
}
/* Equations (3) streamed to the first sign change of z2 from + to - (as first_return). */
long taylor2_return(double alpha, double c, double h, long n) {
    double z1 = alpha, z2 = 0.0;
    for (long i = 0; i < n; i++) {
        double s = sin(z1);
        double z1n = z1 + h * z2 + 0.5 * h * h * c * s;
        double z2n = z2 + h * c * s + 0.5 * h * h * c * z2 * cos(z1);
        if (!(fabs(z1n) < M_PI)) return -i;
        if (z2 > 0.0 && z2n <= 0.0 && z1n > 0.0) return i;
        z1 = z1n; z2 = z2n;
    }
    return n;
}
"""


def build_c() -> ctypes.CDLL:
    folder = Path(tempfile.mkdtemp(prefix="pendulab-bench-"))
    src, lib = folder / "taylor2.c", folder / "taylor2.so"
    src.write_text(C_SOURCE)
    subprocess.run(["cc", "-O2", "-shared", "-fPIC", str(src), "-o", str(lib), "-lm"], check=True)
    dll = ctypes.CDLL(str(lib))
    dbl, p = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
    dll.taylor2.argtypes = [dbl, dbl, dbl, ctypes.c_long, p, p]
    dll.taylor2_return.argtypes = [dbl, dbl, dbl, ctypes.c_long]
    dll.taylor2_return.restype = ctypes.c_long
    return dll


def python_loop(alpha, c, h, n):
    z1, z2 = [alpha], [0.0]
    for i in range(n):
        s = math.sin(z1[i])
        z1.append(z1[i] + h * z2[i] + 0.5 * h * h * c * s)
        z2.append(z2[i] + h * c * s + 0.5 * h * h * c * z2[i] * math.cos(z1[i]))
    return z1, z2


def best(fn, repeat=5):
    """Best wall time of ``repeat`` runs (the least disturbed by the other core's load)."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def bench_taylor(dll) -> list[tuple[str, float]]:
    alpha, c, h = 4 * math.pi / 5, -9.80665 / 2.0800838231, 1e-6
    n = 5_000_000
    # Both loops fill the same preallocated arrays: the loop is measured, not malloc.
    z1, z2 = np.empty(n + 1), np.empty(n + 1)
    c1, c2 = np.empty(n + 1), np.empty(n + 1)
    fill_trajectory(TAYLOR2, 2, alpha, c, h, z1[:10], z2[:10])  # compile (or load from the cache)
    first_return(TAYLOR2, 2, alpha, c, h, 10)
    pz = ctypes.POINTER(ctypes.c_double)
    t_numba = best(lambda: fill_trajectory(TAYLOR2, 2, alpha, c, h, z1, z2))
    t_c = best(lambda: dll.taylor2(alpha, c, h, n, c1.ctypes.data_as(pz), c2.ctypes.data_as(pz)))
    assert np.allclose(z1, c1, atol=1e-9), "C and numba disagree"
    n_py = 200_000
    t_py = best(lambda: python_loop(alpha, c, h, n_py), repeat=2) * n / n_py
    # Streaming search: h = 1e-6 on problem 3's pendulum takes 4.79e6 steps.
    m = 10_000_000
    steps = first_return(TAYLOR2, 2, alpha, c, h, m)[1]
    assert dll.taylor2_return(alpha, c, h, m) == steps
    t_nr = best(lambda: first_return(TAYLOR2, 2, alpha, c, h, m))
    t_cr = best(lambda: dll.taylor2_return(alpha, c, h, m))
    rows = [
        ("trajectory: numba kernel", n / t_numba),
        ("trajectory: plain C loop (cc -O2)", n / t_c),
        ("trajectory: plain Python loop", n / t_py),
        ("first return (streamed): numba kernel", steps / t_nr),
        ("first return (streamed): plain C loop", steps / t_cr),
    ]
    return rows


def bench_periods() -> list[tuple[str, float, float]]:
    from scipy.special import ellipk

    rng = np.random.default_rng(0)
    alpha = rng.uniform(0, math.pi, 1_000_000)
    agm_period(1.0, alpha[:10])  # compile (or load from the cache)
    t_agm = best(lambda: agm_period(1.0, alpha))
    t0 = 2 * math.pi * math.sqrt(1 / 9.80665)
    t_k = best(lambda: 2 / math.pi * t0 * ellipk(np.sin(alpha / 2) ** 2))
    # Accuracy on 200 amplitudes, half of them within 1e-3 of pi, against mpmath.
    sample = np.concatenate([alpha[:100], math.pi - np.logspace(-3, -12, 100)])
    with mpmath.workdps(40):
        ref = np.array([float(4 * mpmath.sqrt(1 / mpmath.mpf(9.80665)) * mpmath.ellipk(mpmath.sin(mpmath.mpf(a) / 2) ** 2))
                        for a in sample])
    err_agm = np.max(np.abs(agm_period(1.0, sample) / ref - 1))
    err_k = np.max(np.abs(2 / math.pi * t0 * ellipk(np.sin(sample / 2) ** 2) / ref - 1))
    return [("AGM (7)-(8), pendulab.agm_period", 1e6 / t_agm, err_agm),
            ("scipy.special.ellipk(sin^2(alpha/2))", 1e6 / t_k, err_k)]


def main() -> None:
    dll = build_c()
    rows = bench_taylor(dll)
    c_rate = rows[1][1]
    print("Taylor steps (3) per second (best of 5; h = 1e-6, problem 3's pendulum)")
    for name, rate in rows:
        ref = c_rate if name.startswith("trajectory") else rows[4][1]
        print(f"  {name:42s} {rate / 1e6:8.2f} M steps/s   {rate / ref:6.3f} x C")
    prows = bench_periods()
    print("Exact periods of 10^6 random amplitudes in [0, pi) (best of 5)")
    for name, rate, err in prows:
        print(f"  {name:42s} {rate / 1e6:8.2f} M periods/s {rate / prows[1][1]:6.3f} x ellipk   "
              f"max rel. error {err:.1e}")


if __name__ == "__main__":
    sys.exit(main())
