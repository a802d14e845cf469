"""The cost of one step of each integrator, relative to the coursework's algorithm (3).

What the limits weigh: :func:`pendulab.core.methods.cost_per_step` (used by the CLI's
``estimate --step`` list, the sweep's cap and the web's) holds the ratios this script
measures. Each method runs the period search's kernel (``kernels.first_return``, the
loop ``estimate`` and ``sweep`` run) for ``STEPS`` steps of a pendulum that does not
return within them (``c = -1e-6``, period about 6300 s, ``h = 1e-3``); best of
``REPEAT`` rounds of CPU time, all methods in each round, side by side. The taylor:P row is fitted by
least squares as ``a + b P + c P^2`` (the recurrences of ``taylor_step`` cost ``O(P^2)``),
and the fit's largest relative residual is printed.

Run: ``.venv/bin/python benchmarks/method_cost.py [--steps 2000000]``
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from pendulab.core import methods
from pendulab.engine.kernels import first_return

ALPHA, C, H = 0.5, -1e-6, 1e-3
REPEAT = 7


def ns_per_step(names: list[str], steps: int) -> dict[str, float]:
    """CPU time per step of each method (``time.process_time``: this process's time only, so
    other programs on a busy machine count less), best of REPEAT rounds; each round runs
    every method once, in turn, so that a disturbance meets all of them alike."""
    runs = {}
    for name in names:
        m = methods.resolve(name)
        code, order = int(m.code), m.order
        n = max(int(steps / max(1.0, m.order / 4) ** 2), 20_000) if m.code == methods.Kernel.TAYLOR else steps
        first_return(code, order, ALPHA, C, H, 1000)  # compiled (or loaded) before timing
        runs[name] = (code, order, n)
    best = dict.fromkeys(names, float("inf"))
    for _ in range(REPEAT):
        for name, (code, order, n) in runs.items():
            t = time.process_time()
            status = first_return(code, order, ALPHA, C, H, n)[0]
            best[name] = min(best[name], (time.process_time() - t) / n * 1e9)
            assert status == methods.Status.NO_RETURN  # all the steps ran
    return best


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=2_000_000)
    args = ap.parse_args()
    named = ["taylor2", "rk4", "verlet"]
    orders = [1, 2, 3, 4, 6, 8, 12, 16, 20, 25, 30]
    # The Taylor method of any order runs fewer steps at high orders (its steps cost more).
    ns_all = ns_per_step(named + [f"taylor:{p}" for p in orders], args.steps)
    ns = {m: ns_all[m] for m in named}
    ns_p = {p: ns_all[f"taylor:{p}"] for p in orders}
    base = ns["taylor2"]
    print(f"CPU ns per step (best of {REPEAT} rounds), and relative to taylor2; the registry's model beside it")
    print(f"{'method':10} {'ns/step':>9} {'measured':>9} {'model':>9}")
    for m in named:
        print(f"{m:10} {ns[m]:9.2f} {ns[m] / base:9.2f} {methods.cost_per_step(m):9.2f}")
    for p in orders:
        print(f"{'taylor:' + str(p):10} {ns_p[p]:9.2f} {ns_p[p] / base:9.2f} {methods.cost_per_step(f'taylor:{p}'):9.2f}")
    ps = np.array(orders, dtype=float)
    rel = np.array([ns_p[p] / base for p in orders])
    coef = np.linalg.lstsq(np.vstack([np.ones_like(ps), ps, ps * ps]).T, rel, rcond=None)[0]
    fit = coef[0] + coef[1] * ps + coef[2] * ps * ps
    print(f"fit taylor:P relative cost = {coef[0]:.3g} + {coef[1]:.3g} P + {coef[2]:.3g} P^2 "
          f"(largest relative residual {np.max(np.abs(fit / rel - 1)):.2f})")


if __name__ == "__main__":
    main()
