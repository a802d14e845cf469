"""How far the double-precision AGM period is from the correctly rounded period, in ulps.

2000 random pendulums (l in [0.1, 10] m, alpha in [0, pi)); reference: mpmath's AGM at
40 digits from the same doubles, rounded once to a double.
Run: ``.venv/bin/python benchmarks/agm_ulps.py``.
"""
import math

import mpmath
import numpy as np

from pendulab.period import agm_period

rng = np.random.default_rng(1)
alphas, lengths = rng.uniform(0, math.pi, 2000), rng.uniform(0.1, 10, 2000)
ulps = []
with mpmath.workdps(40):
    for a, l in zip(alphas, lengths):
        ref = float(2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(l) / mpmath.mpf(9.80665)) / mpmath.agm(1, mpmath.cos(mpmath.mpf(a) / 2)))
        ulps.append(abs(agm_period(l, a) - ref) / math.ulp(ref))
counts = np.bincount(np.round(ulps).astype(int))
print(f"{len(ulps)} pendulums; distance to the correctly rounded period, in ulps:")
for k, c in enumerate(counts):
    print(f"  {k} ulp: {c}")
