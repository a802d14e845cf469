"""The AGM (7)-(8) in double precision against its peers, side by side in one run, as ratios.

1. The coursework's ``T^`` (7 iterations) of one pendulum: ``agm_period(..., iterations=7)``
   against the coursework program ``agm.py``'s ``t_hat`` (the plain loop, no checks).
2. ``T^`` of 10^5 amplitudes in [0, pi): ``agm_period(1, alphas, iterations=7)`` against the
   program's loop run on numpy arrays.
3. The mean to convergence of 10^5 values ``cos(alpha/2)``: ``agm_mean`` against
   ``scipy.special.ellipkm1`` (``K = pi / (2 M)``, DLMF 19.8.5), the library a user would take.
4. ``approximation_errors()`` (1000 amplitudes, every formula), against numpy's ``cos`` of
   the same amplitudes (a floor: what any formula costs).

``--against SRC``: also load the pendulab package found in the folder ``SRC`` (another
checkout's ``src``) under another name and time the same calls with it, each beside
ours in the same rounds: the ratio is this tree's time over that one's.

Run: ``.venv/bin/python benchmarks/bench_agm.py [--against SRC]``; on a machine with
other work, ``NUMBA_NUM_THREADS=1`` keeps the compiled rows from measuring the wait for a
core. ``benchmarks/run.py`` prints the first four rows in its table.
"""
from __future__ import annotations

import math
import sys
from types import ModuleType

import numpy as np
from _peers import load_against, side_by_side

import pendulab
from pendulab.jobs import coursework
from pendulab.numerics import approximations, period

G = 9.80665


def calls(pkg: ModuleType, period_mod: ModuleType, approx_mod: ModuleType) -> dict:
    rng = np.random.default_rng(0)
    alphas = rng.uniform(0, math.pi, 100_000)
    b0 = np.cos(alphas / 2)
    alpha = 4 * math.pi / 5
    return {
        "scalar": lambda: period_mod.agm_period(2.08, alpha, iterations=7),
        "scalar_mean": lambda: period_mod.agm_mean(math.cos(alpha / 2)),
        "array": lambda: period_mod.agm_period(1.0, alphas, iterations=7),
        "array_mean": lambda: period_mod.agm_mean(b0),
        "approx": lambda: approx_mod.approximation_errors(),
    }


def repeated(f, n: int):
    def run():
        for _ in range(n):
            f()
    return run


def timed(fns: dict, repeat: int, inner: dict) -> dict[str, float]:
    """Best time of each call (s), ``inner[k]`` calls per timing."""
    loops = {k: repeated(f, inner.get(k, 1)) for k, f in fns.items()}
    return {k: v / inner.get(k, 1) for k, v in side_by_side(loops, repeat).items()}


INNER = {"scalar": 2000, "scalar_mean": 2000, "t_hat": 2000}


def agm_rows(repeat: int = 25, against: str | None = None) -> list[dict]:
    from scipy.special import ellipkm1

    t_hat = coursework.load()["agm.py"].t_hat
    ours = calls(pendulab, period, approximations)
    rng = np.random.default_rng(0)
    alphas = rng.uniform(0, math.pi, 100_000)
    b0 = np.cos(alphas / 2)

    def numpy_loop():
        a, b = np.ones_like(alphas), np.cos(alphas / 2)
        for _ in range(7):
            a, b = (a + b) / 2, np.sqrt(a * b)
        return 2 * math.pi * math.sqrt(1 / G) / ((a + b) / 2)

    fns = {**ours, "t_hat": lambda: t_hat(2.08, 4 * math.pi / 5),
           "numpy": numpy_loop, "ellipkm1": lambda: math.pi / (2 * ellipkm1(b0 * b0)),
           "cos": lambda: np.cos(np.radians(np.linspace(0.1, 179.9, 1000)) / 2)}
    if against:
        other = load_against(against)
        from importlib import import_module

        theirs = calls(other, import_module("pendulab_against.numerics.period"), import_module("pendulab_against.numerics.approximations"))
        fns.update({f"old_{k}": f for k, f in theirs.items()})
        INNER.update({f"old_{k}": INNER[k] for k in ("scalar", "scalar_mean")})
    t = timed(fns, repeat, INNER)
    rows = [
        {"what": "T^ (7 iterations), one pendulum (us)", "ours": 1e6 * t["scalar"],
         "peer_name": "agm.py t_hat (plain loop)", "peer": 1e6 * t["t_hat"], "target": "", "lower": True},
        {"what": "T^ (7 iterations), 10^5 amplitudes (ms)", "ours": 1e3 * t["array"],
         "peer_name": "the same loop in numpy", "peer": 1e3 * t["numpy"], "target": "<= 1", "lower": True},
        {"what": "AGM to convergence, 10^5 values (ms)", "ours": 1e3 * t["array_mean"],
         "peer_name": "scipy ellipkm1", "peer": 1e3 * t["ellipkm1"], "target": "<= 1", "lower": True},
        {"what": "approximation_errors(), 1000 amplitudes (ms)", "ours": 1e3 * t["approx"],
         "peer_name": "numpy cos of 1000", "peer": 1e3 * t["cos"], "target": "", "lower": True},
    ]
    if against:
        what = {"scalar": "T^, one pendulum (us)", "scalar_mean": "AGM to convergence, one value (us)",
                "array": "T^, 10^5 amplitudes (ms)", "array_mean": "AGM to convergence, 10^5 values (ms)",
                "approx": "approximation_errors(), 1000 amplitudes (ms)"}
        for k, text in what.items():
            scale = 1e6 if "(us)" in text else 1e3
            rows.append({"what": f"{text}, this tree", "ours": scale * t[k], "peer_name": "--against tree",
                         "peer": scale * t[f"old_{k}"], "target": "<= 1", "lower": True})
    return rows


def main() -> None:
    import os

    from _peers import print_table

    against = sys.argv[sys.argv.index("--against") + 1] if "--against" in sys.argv else None
    print(f"load average {os.getloadavg()[0]:.2f} (1 min)")
    print_table(agm_rows(against=against))
    print(f"load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
