"""The foundation's kernels against their peers, side by side in one run, as ratios.

1. Taylor steps (3) per second, problem 3's pendulum, h = 1e-6: the trajectory driver and
   the streamed first-return search, each against the same loop in C (``cc -O2``,
   compiled now) and the trajectory also against a plain Python loop. The trajectory is
   checked bit for bit against C over 5 000 000 steps, the search to the same return step,
   and both are timed over short runs (500 000 and 1 000 000 steps), by the thread's CPU
   time (all run on this thread; other work on a shared machine takes the core away from
   either at random).
2. Exact periods of 10^6 random amplitudes in [0, pi) on one thread: ``agm_period``
   (correctly rounded) against ``scipy.special.ellipk(sin^2(alpha/2))`` scaled to a period,
   with the largest relative error of each against mpmath on 200 amplitudes (half within
   1e-3 of pi). ``agm_period``'s kernel is serial; numpy and scipy run on one thread.

Run: ``.venv/bin/python benchmarks/bench_core.py`` (about 30 s). ``benchmarks/run.py``
prints these rows in its table.
"""
from __future__ import annotations

import math
import sys
import time

import mpmath
import numpy as np
from _peers import build_c, ptr, side_by_side

from pendulab.engine.kernels import TAYLOR2, drive, first_return
from pendulab.numerics.period import agm_period

G = 9.80665


def python_loop(alpha, c, h, n):
    z1, z2 = [alpha], [0.0]
    for i in range(n):
        s = math.sin(z1[i])
        z1.append(z1[i] + h * z2[i] + 0.5 * h * h * c * s)
        z2.append(z2[i] + h * c * s + 0.5 * h * h * c * z2[i] * math.cos(z1[i]))
    return z1, z2


def taylor_rows(dll, repeat: int = 5) -> list[dict]:
    alpha, c, h = 4 * math.pi / 5, -G / 2.0800838231, 1e-6
    n = 5_000_000
    z1, z2, c1, c2 = (np.empty(n + 1) for _ in range(4))
    code = TAYLOR2
    z1[0], z2[0] = alpha, 0.0
    drive(code, 2, alpha, 0.0, c, h, 0, n, 1, n, z1[1:], z2[1:])
    dll.taylor2(alpha, c, h, n, ptr(c1), ptr(c2))
    assert np.array_equal(z1, c1) and np.array_equal(z2, c2), "C and numba disagree"
    # Timed on short runs (500 000 steps), best of 8 x repeat rounds, both writing the same two
    # arrays: the loops are within a few percent of each other, and a 5 000 000-step run (80 MB)
    # meets more of this machine's disturbances, while other arrays alone can shift a loop by
    # a few percent (their addresses).
    n_short = 500_000
    s1, s2 = z1[:n_short + 1], z2[:n_short + 1]
    t = side_by_side({
        "numba": lambda: drive(code, 2, alpha, 0.0, c, h, 0, n_short, 1, n_short, s1[1:], s2[1:]),
        "C": lambda: dll.taylor2(alpha, c, h, n_short, ptr(z1), ptr(z2)),
    }, 8 * repeat, time.thread_time)
    t = {k: v * n / n_short for k, v in t.items()}
    n_py = 200_000
    t_py = side_by_side({"py": lambda: python_loop(alpha, c, h, n_py)}, 1, time.thread_time)["py"] * n / n_py
    m = 10_000_000
    steps = first_return(code, 2, alpha, c, h, m)[1]
    assert dll.taylor2_return(alpha, c, h, m) == steps
    # Timed as the trajectory: short runs (10^6 steps, before the return), best of 8 x repeat.
    m_short = 1_000_000
    r = side_by_side({
        "numba": lambda: first_return(code, 2, alpha, c, h, m_short),
        "C": lambda: dll.taylor2_return(alpha, c, h, m_short),
    }, 8 * repeat, time.thread_time)
    r = {k: v * steps / m_short for k, v in r.items()}
    return [
        {"what": "Taylor (3) trajectory, h = 1e-6 (M steps/s)", "ours": n / t["numba"] / 1e6,
         "peer_name": "C loop (cc -O2)", "peer": n / t["C"] / 1e6, "target": ">= 1.0"},
        {"what": "  same, plain Python loop against C (M steps/s)", "ours": n / t_py / 1e6,
         "peer_name": "C loop (cc -O2)", "peer": n / t["C"] / 1e6, "target": ""},
        {"what": "period search streamed, h = 1e-6 (M steps/s)", "ours": steps / r["numba"] / 1e6,
         "peer_name": "C loop (cc -O2)", "peer": steps / r["C"] / 1e6, "target": ">= 1.0"},
    ]


def period_rows(repeat: int = 5) -> list[dict]:
    from scipy.special import ellipk

    alpha = np.random.default_rng(0).uniform(0, math.pi, 1_000_000)
    t0 = 2 * math.pi * math.sqrt(1 / G)
    t = side_by_side({
        "agm": lambda: agm_period(1.0, alpha),
        "ellipk": lambda: 2 / math.pi * t0 * ellipk(np.sin(alpha / 2) ** 2),
    }, repeat)
    sample = np.concatenate([alpha[:100], math.pi - np.logspace(-3, -12, 100)])
    with mpmath.workdps(60):
        ref = np.array([float(4 * mpmath.sqrt(1 / mpmath.mpf(G)) * mpmath.ellipk(mpmath.sin(mpmath.mpf(a) / 2) ** 2))
                        for a in sample])
    with np.errstate(all="ignore"):
        err_agm = np.max(np.abs(agm_period(1.0, sample) / ref - 1))
        err_k = np.max(np.abs(2 / math.pi * t0 * ellipk(np.sin(sample / 2) ** 2) / ref - 1))
    return [{"what": "exact periods, 10^6 amplitudes, 1 thread (M/s)", "ours": 1 / t["agm"],
             "peer_name": "scipy ellipk(sin^2(a/2))", "peer": 1 / t["ellipk"], "target": ">= 1.0",
             "note": f"max rel. error {err_agm:.1e} (ellipk: {err_k:.1e})"}]


def main() -> None:
    from _peers import print_table

    print_table(taylor_rows(build_c()) + period_rows())


if __name__ == "__main__":
    sys.exit(main())
