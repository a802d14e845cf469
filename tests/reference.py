"""The reference values the tests share, each with its source.

Literals come from the specification (the coursework); computed references come from
mpmath at high precision or from the coursework programs (``pendulab/programs``), never
from the code under test.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np

#: Standard gravity, m/s^2: the spec, "The physics" (its double; ``G_TEXT`` as written).
G = 9.80665
G_TEXT = "9.80665"

#: Figure 3 of the coursework (the spec's table): l = 1, alpha = pi/4, h = 0.1, t in [0, 2.1].
FIGURE3_INPUTS = {"length": 1.0, "amplitude": math.pi / 4, "step": 0.1, "t_max": 2.1}
#: Its rows ``j: (t_j, z1_j, z2_j)``, 12 significant digits as the coursework prints them.
FIGURE3 = {
    0: (0.0, 0.785398163397, 0.0),
    1: (0.1, 0.750726419819, -0.693434871572),
    2: (0.2, 0.647933915928, -1.33755362818),
    3: (0.3, 0.484585008774, -1.87713178299),
    18: (1.8, 0.569659507564, 1.6947608797),
    19: (1.9, 0.712689739829, 1.09586683808),
    20: (2.0, 0.790214993286, 0.413982837259),
    21: (2.1, 0.796774928412, -0.297068336875),
}

#: Problem 3(b), footnote 4 of the coursework: the example group and its pendulum's length.
EXAMPLE_GROUP = (262, 407, 634)
EXAMPLE_LENGTH_TEXT = "2.0800838231"
EXAMPLE_LENGTH = float(EXAMPLE_LENGTH_TEXT)


def reference_period(length, alpha, g=G, dps=50):
    """``T = 4 sqrt(l/g) K(m)``, ``m = sin^2(alpha/2)`` (DLMF 19.2.8, 22.19), in mpmath at ``dps`` digits.

    Each argument is taken exactly: a float as its binary value, a string as the decimal it
    writes, an ``mpf`` as it is (compute it at ``dps`` digits). Independent of the
    library's AGM loop: the reference of the period tests.
    """
    with mpmath.workdps(dps):
        m = mpmath.sin(mpmath.mpf(alpha) / 2) ** 2
        return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(g)) * mpmath.ellipk(m)


def reference_period_kp(length, kp, g=G):
    """``4 sqrt(l/g) K(m)`` from ``k' = cos(alpha/2)``, ``m = 1 - k'^2``, at the caller's mpmath
    precision: for amplitudes near pi, where the caller computes ``k'`` without cancellation
    (``sin((1 - c) pi/2)`` for ``alpha = c pi``)."""
    return 4 * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(g)) * mpmath.ellipk(1 - kp * kp)


def period_mp(length, amplitude, g=G_TEXT, dps=50):
    """``T = 2 pi sqrt(l/g) / M(1, cos(alpha/2))`` (8) by ``mpmath.agm`` at ``dps`` digits, from
    the inputs taken exactly: a string as written (``"4pi/5"``, with the true pi, parsed by
    :func:`pendulab.core.inputs.parse_angle`), a float as its binary value. Independent of the
    library's double loop and of Arb: the cross-check of ``period_digits``."""
    from pendulab.core.exact import Exact
    from pendulab.core.inputs import parse_angle, parse_number

    def exact(x, parser, name):
        return parser(name, x) if isinstance(x, str) else Exact.of(float(x))

    l_, a_, g_ = exact(length, parse_number, "length"), exact(amplitude, parse_angle, "amplitude"), exact(g, parse_number, "g")
    with mpmath.workdps(dps):
        if a_.pi_power == 1:
            c = 1 - a_.coef
            b0 = mpmath.sinpi(mpmath.mpf(c.numerator) / (2 * c.denominator))  # cos(c pi/2), 1 - c exact
        else:
            b0 = mpmath.cos(a_.mpf(dps) / 2)
        t0 = 2 * mpmath.pi * mpmath.sqrt(l_.mpf(dps) / g_.mpf(dps))
        return t0 / mpmath.agm(1, b0)


def ellipk_period(length: float, alpha: float, g: float = G) -> float:
    """:func:`reference_period` at 30 digits, rounded to a double."""
    return float(reference_period(length, alpha, g, dps=30))


def taylor2_plain(alpha: float, c: float, h: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` steps of (3) from ``(alpha, 0)`` with ``c = -g/l``, by the coursework program
    ``taylor.py`` (plain Python, ``math.sin`` and ``math.cos``): the kernels' reference bit
    for bit. ``l = 1, g = -c`` gives the program's ``c = -g/l`` exactly."""
    from plain_pendulum import taylor

    _, z1, z2 = taylor.taylor(1.0, alpha, h, n * h, g=-c)
    assert len(z1) == n + 1
    return np.array(z1), np.array(z2)

#: How close the key's answers come to the tests' independent computations (relative, or
#: absolute in the answer's unit, as each test says): a few roundings of a correct program.
KEY_AGREEMENT = {
    "1(b) g": 1e-14,
    "1(b) |e_g|, |e_g|/|g| and the corner extremes": 1e-12,
    "2 alpha": 1e-15,
    "2 q_k for k <= k_max": 1e-2,
    "3(b) T^ (8), 7 iterations": 1e-15,
    "3(c) T linear, T = p(0) and their errors": 1e-11,
    "3(c) observed orders": 0.01,
    "3(d) nodes x_k = z_(2,j-1+k)": 1e-11,
    "3(d) Newton coefficients": 1e-9,
    "3(d) error estimate": 1e-13,
    "4 coefficients": 1e-10,
    "4 SSD E(c)": 1e-8,
    "4 max deviation": 1e-10,
    "5 S_n for every n": 1e-12,
    "5 errors and rates": 1e-6,
}
