"""Classical closed-form approximations of the pendulum's period, against the AGM period.

Each formula gives the ratio ``T/T0`` to the small-angle period ``T0 = 2 pi sqrt(l/g)``
as a function of the amplitude ``alpha`` alone, so its relative error
``T_approx/T - 1 = (T_approx/T0) M(1, cos(alpha/2)) - 1`` (the true ``T/T0`` is
``1/M(1, cos(alpha/2))``, equations (7)-(8)) does not depend on ``l`` or ``g``.

References
----------
.. [9]  The coursework's approximation (9): ``T~ = T0 (1 + k^2/4)``, ``k = sin(alpha/2)``,
   the first two terms of ``T/T0 = sum ((2n)!/(2^(2n) (n!)^2))^2 k^(2n)`` (DLMF 19.5.1).
.. [KF] R. B. Kidd, S. L. Fogg, "A simple formula for the large-angle pendulum period",
   Phys. Teach. 40, 81-83 (2002): ``T0 / sqrt(cos(alpha/2))``.
.. [LA] F. M. S. Lima, P. Arun, "An accurate formula for the period of a simple
   pendulum oscillating beyond the small angle regime", Am. J. Phys. 74, 892-895 (2006):
   ``-T0 ln(cos(alpha/2)) / (1 - cos(alpha/2))``.
.. [G]  W. P. Ganley, "Simple pendulum approximation", Am. J. Phys. 53, 73-76 (1985):
   ``T0 sqrt(F alpha / sin(F alpha))`` with ``F`` "approximately ``sqrt(3)/2``"; this
   module takes ``F = sqrt(3)/2`` exactly, the value that reproduces the ``alpha^2/16``
   term of the series (R. R. Parwani, arXiv:physics/0303036). With it the error
   stays within 1e-3 up to 94 degrees (Ganley's abstract: 100 degrees with his fitted F).
.. [CS] C. G. Carvalhaes, P. Suppes, "Approximations for the period of the simple
   pendulum based on the arithmetic-geometric mean", Am. J. Phys. 76, 1150-1154 (2008):
   ``T0 / v_n``, ``v_n = (a_n + b_n)/2`` after ``n`` iterations of (7).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import validate as v
from ..core.cases import G
from ..core.errors import InputError
from .arrays import elementwise
from .period import agm_mean
from .results import Result

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

_GANLEY_F = math.sqrt(3) / 2


def _small_angle(alpha: np.ndarray) -> np.ndarray:
    return np.ones_like(alpha)


def _coursework9(alpha: np.ndarray) -> np.ndarray:
    k = np.sin(alpha / 2)
    return 1 + k * k / 4


def _kidd_fogg(alpha: np.ndarray) -> np.ndarray:
    return 1 / np.sqrt(np.cos(alpha / 2))


def _lima_arun(alpha: np.ndarray) -> np.ndarray:
    # 1 - cos(a/2) = 2 sin^2(a/4) without cancellation; the limit at a = 0 is 1.
    # ln(cos(a/2)) = log1p(-(1 - cos(a/2))): log(c) would lose digits where c -> 1.
    one_minus_c = 2 * np.sin(alpha / 4) ** 2
    with np.errstate(invalid="ignore", divide="ignore"):
        r = -np.log1p(-one_minus_c) / one_minus_c
    return np.where(alpha == 0, 1.0, r)


def _ganley(alpha: np.ndarray) -> np.ndarray:
    x = _GANLEY_F * alpha
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.sqrt(x / np.sin(x))
    return np.where(alpha == 0, 1.0, r)


def _agm(n: int) -> Callable[[np.ndarray], np.ndarray]:
    return lambda alpha: 1 / agm_mean(np.cos(alpha / 2), n)


@dataclass(frozen=True)
class Formula:
    """One approximation: its name, the ratio ``T/T0`` as a function of ``alpha``, its source."""

    name: str
    label: str
    ratio: Callable[[np.ndarray], np.ndarray]
    source: str


#: The AGM truncated after these iteration counts is compared by default.
AGM_ITERATIONS = (1, 2, 3)

FORMULAS: dict[str, Formula] = {
    f.name: f
    for f in [
        Formula("small-angle", "T0", _small_angle, "small-angle limit, problem 1"),
        Formula("coursework-9", "T0 (1 + k^2/4)", _coursework9, "coursework equation (9)"),
        Formula("kidd-fogg", "T0 / sqrt(cos(a/2))", _kidd_fogg, "Kidd, Fogg, Phys. Teach. 40, 81 (2002)"),
        Formula(
            "lima-arun",
            "-T0 ln(cos(a/2)) / (1 - cos(a/2))",
            _lima_arun,
            "Lima, Arun, Am. J. Phys. 74, 892 (2006)",
        ),
        Formula("ganley", "T0 sqrt(Fa / sin(Fa)), F = sqrt(3)/2", _ganley, "Ganley, Am. J. Phys. 53, 73 (1985)"),
    ]
    + [
        Formula(f"agm{n}", f"T0 / v_{n}, {n} AGM iteration{'s' * (n > 1)}", _agm(n),
                "Carvalhaes, Suppes, Am. J. Phys. 76, 1150 (2008); (7)-(8)")
        for n in AGM_ITERATIONS
    ]
}


def approximate_period(name: str, length: Any, amplitude: Any, g: Any = G) -> Any:
    """The period by the formula ``name`` (a key of :data:`FORMULAS` or ``agmN``)."""
    formula = _formula(name)
    t0 = 2 * math.pi * math.sqrt(v.positive("length", length) / v.positive("g", g))
    alpha = np.asarray(v.amplitudes("amplitude", amplitude), dtype=float)
    r = t0 * formula.ratio(alpha)
    return float(r) if np.ndim(r) == 0 else r


def _formula(name: str) -> Formula:
    if name in FORMULAS:
        return FORMULAS[name]
    if isinstance(name, str) and name.startswith("agm") and name[3:].isascii() and name[3:].isdigit():
        n = v.integer("name", int(name[3:]), 0, 64)
        return Formula(name, f"T0 / v_{n}", _agm(n), "Carvalhaes, Suppes (2008); (7)-(8)")
    raise InputError("formula", repr(name), "one of " + ", ".join(FORMULAS) + ", agmN (N an integer)")


@dataclass(frozen=True, eq=False)
class ApproximationErrors(Result):
    """Relative errors ``T_approx/T - 1`` of each formula at each amplitude.

    Attributes
    ----------
    amplitudes : ndarray, shape (n,)
        ``alpha`` (rad).
    period_ratio : ndarray, shape (n,)
        ``T/T0 = 1/M(1, cos(alpha/2))`` (AGM to convergence).
    formulas : tuple of Formula
    errors : dict name -> ndarray, shape (n,)
        Signed relative errors. Values near 1e-16 are rounding, not the formula.
    """

    amplitudes: np.ndarray
    period_ratio: np.ndarray
    formulas: tuple[Formula, ...]
    errors: dict[str, np.ndarray]

    def _columns(self) -> dict[str, np.ndarray]:
        return {"amplitude": self.amplitudes, "period_ratio": self.period_ratio, **self.errors}

    def max_amplitude_within(self, name: str, tol: float) -> float:
        """The largest tabulated amplitude up to which ``|error| <= tol`` holds throughout."""
        bad = np.abs(self.errors[name]) > tol
        if not bad.any():
            return float(self.amplitudes[-1])
        first = int(np.argmax(bad))
        return float(self.amplitudes[first - 1]) if first > 0 else math.nan


@elementwise(amplitudes=0.0)
def approximation_errors(amplitudes: ArrayLike | None = None,
                         names: Sequence[str] | None = None) -> ApproximationErrors:
    """Relative error of each approximation against the AGM period over ``[0, pi)``.

    Parameters
    ----------
    amplitudes : array_like, optional
        Amplitudes in ``[0, pi)`` (rad), increasing. Default: 1000 points from 0.1 to
        179.9 degrees.
    names : sequence of str, optional
        Formulas (keys of :data:`FORMULAS`, or ``agmN``); default all of them.
    """
    if amplitudes is None:
        amplitudes = np.radians(np.linspace(0.1, 179.9, 1000))
    alpha = np.atleast_1d(np.asarray(v.amplitudes("amplitudes", amplitudes), dtype=float))
    formulas = tuple(_formula(n) for n in (names if names is not None else FORMULAS))
    m = agm_mean(np.cos(alpha / 2))
    errors = {f.name: f.ratio(alpha) * m - 1 for f in formulas}
    return ApproximationErrors(alpha, 1 / m, formulas, errors)


#: Ulps of ``|T_approx/T|`` within which ``T_approx/T - 1``, computed in doubles, lies of its
#: value (the cos, sqrt, log1p and AGM steps of each formula): the measured worst over
#: [0.1, 179.9] deg is 3.2 ulps (Ganley: 4.3) but near 180 deg, where Lima-Arun's
#: log(cos(alpha/2)) loses up to 210, and there its error is far above 4 significant digits'
#: reach. tests/test_approximations.py searches for the worst case of the table's digits.
ROUNDING_ULPS = 16


def rounding_error(relative_error: float) -> float:
    """A bound on the rounding of a computed ``T_approx/T - 1`` where it is small: what
    ``pendulab approximations`` prints it to (at most 4 significant digits)."""
    return ROUNDING_ULPS * 2.0**-53 * abs(1 + relative_error)


#: The amplitudes (degrees) of the table of ``pendulab approximations``.
TABLE_DEGREES = (1, 10, 30, 60, 90, 120, 150, 170, 179, 179.9)
#: The error levels whose reach (the largest amplitude within them) the table gives.
REACH_TOLERANCES = (1e-2, 1e-4, 1e-6)


@dataclass(frozen=True, eq=False)
class FormulaErrors(Result):
    """One formula's row of :class:`ApproximationTable`.

    Attributes
    ----------
    name, formula, source : str
        The formula's name, its expression (``T0 / sqrt(cos(a/2))``) and its reference.
    relative_errors : ndarray
        ``T_approx/T - 1`` at the table's amplitudes.
    max_amplitude_deg_within : dict
        For each error level (``"0.01"``, ...), the largest amplitude (degrees) up to which
        ``|error|`` stays within it, on a grid of 1000 amplitudes from 0.1 to 179.9 degrees
        (:meth:`ApproximationErrors.max_amplitude_within`).
    """

    name: str
    formula: str
    source: str
    relative_errors: np.ndarray
    max_amplitude_deg_within: dict[str, float]


@dataclass(frozen=True, eq=False)
class ApproximationTable(Result):
    """The relative errors of every formula at a few amplitudes, and how far each stays
    within 1e-2, 1e-4, 1e-6 (``pendulab approximations``)."""

    amplitudes_deg: tuple[float, ...]
    formulas: tuple[FormulaErrors, ...]


def approximation_table(fine: ApproximationErrors | None = None,
                        degrees: tuple[float, ...] = TABLE_DEGREES,
                        tolerances: tuple[float, ...] = REACH_TOLERANCES) -> ApproximationTable:
    """The errors at ``degrees`` and the reach of each formula within ``tolerances``, measured
    on ``fine`` (default: :func:`approximation_errors` over its 1000 amplitudes)."""
    fine = approximation_errors() if fine is None else fine
    table = approximation_errors(np.radians(degrees))
    return ApproximationTable(tuple(degrees), tuple(
        FormulaErrors(f.name, f.label, f.source, table.errors[f.name],
                      {f"{t:g}": math.degrees(fine.max_amplitude_within(f.name, t)) for t in tolerances})
        for f in table.formulas))
