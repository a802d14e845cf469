"""Is ``agm_period`` correctly rounded? 10^5 random pendulums and the hard cases, against mpmath.

Pendulums: l uniform in [0.1, 10] m, alpha uniform in [0, pi - 1e-12], plus alpha = pi - 10^-k
(k = 1..15 in steps of 1/4) and the 8 doubles just below pi. Reference: mpmath's elliptic K
at 60 digits (``T = 4 sqrt(l/g) K(sin^2(alpha/2))``, independent of the AGM) from the same
doubles, rounded once to the nearest double. Printed: how many periods differ from it
(0 means correctly rounded), the largest relative error of the kernel's unrounded
double-double against the bound the rounding test assumes, how many elements took the
mpmath path, and for contrast the plain double-precision AGM loop's distance in ulps.

Run: ``.venv/bin/python benchmarks/agm_ulps.py [N]`` (N = 100000: about a minute).
"""
from __future__ import annotations

import math
import sys

import mpmath
import numpy as np

from pendulab.engine.agm import ERROR_BOUND, agm_periods_dd
from pendulab.numerics.period import agm_mean, agm_period, small_angle_period

G = 9.80665


def reference(length: float, alpha: float) -> mpmath.mpf:
    m = mpmath.sin(mpmath.mpf(alpha) / 2) ** 2
    return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(G)) * mpmath.ellipk(m)


def ulps_rows(n: int = 100_000) -> list[dict]:
    rng = np.random.default_rng(1)
    below_pi = [math.pi]
    for _ in range(8):
        below_pi.append(math.nextafter(below_pi[-1], 0))
    hard = np.concatenate([math.pi - 10.0 ** -np.arange(1, 15.01, 0.25), below_pi[1:]])
    alpha = np.concatenate([rng.uniform(0, math.pi - 1e-12, n), hard])
    length = np.concatenate([rng.uniform(0.1, 10, n), np.full(len(hard), 1.0)])
    got = agm_period(length, alpha)
    hi, lo, hard = np.empty(alpha.size), np.empty(alpha.size), np.empty(alpha.size, np.int64)
    recomputed = agm_periods_dd(alpha, length, G, hi, lo, hard)[0]
    wrong = worst = 0
    plain = np.zeros(8, dtype=int)
    with mpmath.workdps(60):  # 1 - m is 1e-32 at the double below pi: 60 digits keep 28 of it
        for a, l_, t, h, e in zip(alpha, length, got, hi, lo):
            ref = reference(l_, a)
            nearest = mpmath.libmp.to_float(ref._mpf_, rnd="n")
            wrong += t != nearest
            worst = max(worst, float(abs((mpmath.mpf(h) + mpmath.mpf(e)) / ref - 1)))
            d = abs(small_angle_period(l_) / agm_mean(math.cos(a / 2)) - nearest) / math.ulp(nearest)
            plain[min(int(round(d)), 7)] += 1
    total = alpha.size
    return [{"what": f"agm_period on {total} pendulums: not correctly rounded", "ours": wrong,
             "peer_name": "", "peer": None, "target": "0",
             "note": (f"double-double error <= 2^{math.log2(worst):.1f} (rounding test assumes "
                      f"2^{math.log2(ERROR_BOUND):.0f}); {recomputed} recomputed in mpmath; plain "
                      f"double AGM: " + ", ".join(f"{c} at {k} ulp" for k, c in enumerate(plain) if c))}]


def main() -> None:
    from _peers import print_table

    print_table(ulps_rows(int(sys.argv[1]) if len(sys.argv) > 1 else 100_000))


if __name__ == "__main__":
    main()
