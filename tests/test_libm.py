"""The kernels' sin and cos (numba's math.sin and math.cos, which LLVM may merge into one
sincos) return Python's math.sin and math.cos bit for bit: the coursework's numbers depend
on their being the same functions.
"""
import math

import numpy as np
from numba import njit

from pendulab.engine.kernels import FOUND, TAYLOR2, cos, drive, first_return, sin
from reference import EXAMPLE_LENGTH, G, taylor2_plain


@njit
def _both(x, s, c):
    for i in range(x.size):
        s[i] = sin(x[i])
        c[i] = cos(x[i])


@njit
def _of_int(k):
    return sin(k), cos(k)


def _arguments() -> np.ndarray:
    rng = np.random.default_rng(20261127)
    parts = [
        rng.uniform(-math.pi, math.pi, 100_000),  # the pendulum's range
        rng.uniform(-1e3, 1e3, 20_000),
        np.copysign(10.0 ** rng.uniform(-320, 308, 20_000), rng.uniform(-1, 1, 20_000)),  # subnormal to huge
        np.nextafter(np.pi / 4 * np.arange(-64, 65), np.inf),  # near the argument reduction's boundaries
        [0.0, -0.0, 5e-324, math.pi, -math.pi, 1e22, 2.0**1000, math.inf, -math.inf, math.nan],
    ]
    return np.concatenate([np.asarray(p, dtype=float) for p in parts])


def test_sin_cos_are_maths_bit_for_bit():
    x = _arguments()
    s, c = np.empty_like(x), np.empty_like(x)
    with np.errstate(invalid="ignore"):
        _both(x, s, c)
    ref_s = np.array([math.sin(v) if math.isfinite(v) else math.nan for v in x])
    ref_c = np.array([math.cos(v) if math.isfinite(v) else math.nan for v in x])
    # Bit patterns: -0.0 and 0.0 differ, NaN equals NaN only where both are NaN.
    finite = np.isfinite(x)
    assert np.array_equal(s[finite].view(np.int64), ref_s[finite].view(np.int64))
    assert np.array_equal(c[finite].view(np.int64), ref_c[finite].view(np.int64))
    assert np.isnan(s[~finite]).all() and np.isnan(c[~finite]).all()
    assert _of_int(3) == (math.sin(3), math.cos(3))


def test_taylor2_kernels_equal_the_python_loop_bit_for_bit():
    code = TAYLOR2
    c = -G / EXAMPLE_LENGTH
    for alpha, h, n in ((4 * math.pi / 5, 1e-3, 6000), (math.pi / 4, 0.1, 6000), (3.1, 0.01, 6000),
                        (4 * math.pi / 5, 1e-5, 500_000)):
        ref1, ref2 = taylor2_plain(alpha, c, h, n)  # the coursework program taylor.py
        z1, z2 = np.empty(n), np.empty(n)
        drive(code, 2, alpha, 0.0, c, h, 0, n, 1, n, z1, z2)
        assert np.array_equal(z1, ref1[1:]) and np.array_equal(z2, ref2[1:])
        status, j, z1w, z2w = first_return(code, 2, alpha, c, h, n)
        assert status == FOUND
        assert np.array_equal(z1w, ref1[j - 2:j + 3]) and np.array_equal(z2w, ref2[j - 2:j + 3])
