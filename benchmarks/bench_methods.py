"""Steps and time each method needs for the period to 1e-10 s, against scipy's DOP853.

Pendulum: the example group's l = 2.0800838231 m, alpha = 4 pi/5 (problem 3(b)). For each
integrator, the largest step h on a grid h = 0.2 * 2^(-k/2) whose estimate
(crossing.estimate_period: the inverse cubic of 3(d), or with --dense the zero of theta'
on the flow's Taylor series, PeriodEstimate.dense) is within TARGET of the exact period,
also at the next two smaller steps; then the time of one estimate at that h (best of
REPEAT). The peer: scipy.integrate.solve_ivp(DOP853) with an event on theta' = 0 (from +
to -), at the largest rtol = atol = 10^-k (or 3 10^-k) that meets the same target.
The exact period: mpmath's AGM at 30 digits from the same doubles.

Run: .venv/bin/python benchmarks/bench_methods.py [--target 1e-13] [--dense]
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

from pendulab.numerics.crossing import estimate_period

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from reference import reference_period

LENGTH, ALPHA, G = 2.0800838231, 4 * math.pi / 5, 9.80665
EXACT = float(reference_period(LENGTH, ALPHA, G, dps=30))  # mpmath, the doubles taken exactly
TARGET = 1e-10
ESTIMATE = "cubic"
REPEAT = 3
METHODS = ["taylor2", "verlet", "rk4", "taylor:4", "taylor:8", "taylor:12"]
GRID = [0.2 * 2 ** (-k / 2) for k in range(0, 48)]


def best_time(f) -> float:
    f()
    times = []
    for _ in range(REPEAT):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def method_row(method: str):
    errs = {}
    for i, h in enumerate(GRID):
        try:
            e = estimate_period(LENGTH, ALPHA, h, method=method)
            errs[i] = (abs(getattr(e, ESTIMATE) - EXACT), e.j + 2)
        except ValueError:
            errs[i] = (math.inf, 0)
        ok = [errs.get(k, (math.inf,))[0] <= TARGET for k in (i - 2, i - 1, i)]
        if all(ok):
            k = i - 2
            h = GRID[k]
            secs = best_time(lambda h=h: estimate_period(LENGTH, ALPHA, h, method=method))
            return h, errs[k][1], errs[k][0], secs
    return None


def dop853_row():
    from scipy.integrate import solve_ivp

    exact = EXACT
    c = -G / LENGTH

    def rhs(t, y):
        return [y[1], c * math.sin(y[0])]

    def top(t, y):  # theta' = 0 going from + to -
        return y[1]

    # The start (theta' = 0, then < 0) counts as the first such event: stop at the second.
    top.terminal, top.direction = 2, -1
    for tol in [m * 10.0**-k for k in range(3, 15) for m in (3, 1)]:

        def run(tol=tol):
            return solve_ivp(rhs, (0, 1.5 * exact), [ALPHA, 0.0], method="DOP853", rtol=tol, atol=tol, events=top)

        sol = run()
        err = abs(sol.t_events[0][-1] - exact)
        if err <= TARGET:
            return tol, sol.nfev, err, best_time(run)
    return None


def main() -> None:
    global TARGET, ESTIMATE
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target", type=float, default=TARGET, help="period error to reach, s")
    parser.add_argument("--dense", action="store_true", help="the dense-output estimate instead of the cubic")
    args = parser.parse_args()
    TARGET, ESTIMATE = args.target, ("dense" if args.dense else "cubic")
    print(f"period of l = {LENGTH}, alpha = 4pi/5 to {TARGET:g} s by the {ESTIMATE} estimate (exact {EXACT!r})")
    print(f"{'method':>10} {'h or tol':>10} {'steps/nfev':>11} {'|error| s':>10} {'time s':>9} {'vs DOP853':>9}")
    ref = dop853_row()
    if ref is None:
        print(f"DOP853 did not reach {TARGET:g} at any tolerance down to 1e-14")
        return
    rows = [(m, method_row(m)) for m in METHODS]
    for m, r in rows:
        if r is None:
            print(f"{m:>10}  did not reach the target on the grid")
            continue
        h, steps, err, secs = r
        print(f"{m:>10} {h:>10.3g} {steps:>11d} {err:>10.2e} {secs:>9.2e} {secs / ref[3]:>9.2f}")
    tol, nfev, err, secs = ref
    print(f"{'DOP853':>10} {tol:>10.0e} {nfev:>11d} {err:>10.2e} {secs:>9.2e} {1.0:>9.2f}")


if __name__ == "__main__":
    main()
