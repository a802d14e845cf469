"""The canonical inputs of the coursework, defined once.

Shared by the tests, the CLI defaults and the report. Each value is the one the
coursework's problem statement gives (cited beside it); ``Exact`` keeps the numbers as
the statement writes them, so ``--digits`` computes from the true decimal values.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from .exact import Exact

#: Standard gravity used throughout the coursework (Introduction), m/s^2.
G_TEXT = "9.80665"
G = 9.80665
G_EXACT = Exact(Fraction(G_TEXT), 0, G_TEXT)


@dataclass(frozen=True)
class Pendulum:
    """A pendulum released at rest: length ``l`` (m) and amplitude ``alpha`` (rad)."""

    length: Exact
    amplitude: Exact

    @property
    def l(self) -> float:  # noqa: E743 - the coursework's name
        return float(self.length)

    @property
    def alpha(self) -> float:
        return float(self.amplitude)


def _p(length: str, coef: Fraction, text: str) -> Pendulum:
    return Pendulum(Exact(Fraction(length), 0, length), Exact(coef, 1, text))


#: Figures 1-3: l = 1, alpha = pi/4, h = 0.1, t in [0, 2.1].
FIGURE3 = _p("1", Fraction(1, 4), "pi/4")
FIGURE3_STEP = 0.1
FIGURE3_T_MAX = 2.1

#: Problem 1(b): l = 115.2 cm, T = 2.1536 s, errors 0.3 cm and 2e-4 s.
GRAVITY_LENGTH = 1.152
GRAVITY_LENGTH_ERROR = 0.003
GRAVITY_PERIOD = 2.1536
GRAVITY_PERIOD_ERROR = 2e-4

#: Problem 2: l = 0.5, target period of approximation (9) 1.5 s.
NEWTON_LENGTH = 0.5
NEWTON_TARGET = 1.5

#: Problem 3(b): the example group of the footnote 4 and its amplitude 4 pi/5, h = 0.2.
EXAMPLE_GROUP = (262, 407, 634)
PROBLEM3_AMPLITUDE = Exact(Fraction(4, 5), 1, "4pi/5")
PROBLEM3_PLOT_STEP = 0.2
#: Problem 3(c): h = 10^-j, j = 2, 3, 4; 3(d): h = 1e-3.
PROBLEM3_STEPS = (1e-2, 1e-3, 1e-4)
PROBLEM3_CUBIC_STEP = 1e-3

#: Problem 4: l = 3.5, alpha = pi/4, h = 0.01, t_max = ceil(T); entries rounded to 6 decimals.
PROBLEM4 = _p("3.5", Fraction(1, 4), "pi/4")
PROBLEM4_STEP = 0.01
PROBLEM4_ROUND = 6
#: The coursework's names Y_0 .. Y_600 fit t_max = 6 (601 points), not t_max = ceil(T);
#: the report and the key give that fit beside.
PROBLEM4_ALT_T_MAX = 6.0

#: Problem 5: l = 3.5, alpha = 4 pi/5; n = 10^k, k = 1..5.
PROBLEM5 = _p("3.5", Fraction(4, 5), "4pi/5")
PROBLEM5_N = (10, 100, 1000, 10000, 100000)
