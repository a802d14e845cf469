"""Where more panels stop paying: the composite 3-point Gauss rule's relative error against
mpmath (``4 sqrt(l/g) K(sin^2(alpha/2))`` at 40 digits) and its time, n = 10^0 .. 10^KMAX,
for problem 5's pendulum (4pi/5) and near pi, plain and substituted. The measurement behind
``pendulab.numerics.quadrature.MAX_N``.

Run: ``.venv/bin/python benchmarks/quadrature_cap.py [KMAX]`` (KMAX = 7: about a minute).
"""
from __future__ import annotations

import math
import sys
import time

import mpmath

from pendulab.numerics.quadrature import quadrature_period

L, G = 3.5, 9.80665
CASES = [("4pi/5 plain", 4 * math.pi / 5, False), ("4pi/5 subst", 4 * math.pi / 5, True),
         ("pi-1e-3 subst", math.pi - 1e-3, True), ("pi-1e-6 subst", math.pi - 1e-6, True),
         ("pi-1e-6 plain", math.pi - 1e-6, False)]


def reference(alpha: float) -> mpmath.mpf:
    with mpmath.workdps(40):
        return 4 * mpmath.sqrt(mpmath.mpf(L) / G) * mpmath.ellipk(mpmath.sin(mpmath.mpf(alpha) / 2) ** 2)


def main(kmax: int) -> None:
    for label, alpha, sub in CASES:
        exact = reference(alpha)
        for k in range(kmax + 1):
            start = time.perf_counter()
            p = quadrature_period(L, alpha, 10**k, G, substitution=sub)
            seconds = time.perf_counter() - start
            err = float(abs(mpmath.mpf(p) - exact) / exact)
            print(f"{label:15} n=1e{k}  rel.err={err:.3e}  {seconds:.2f}s", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
