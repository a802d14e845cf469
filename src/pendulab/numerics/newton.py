"""Problem 2: Newton's method, its convergence quotients and a guaranteed interval.

:func:`newton` runs ``x[k+1] = x[k] - f(x[k]) / f'(x[k])`` and records every iterate;
:func:`quotients` gives ``q_k = |x[k+2] - x[k+1]| / |x[k+1] - x[k]|^2`` and chooses
``k_max``; :func:`check_interval` verifies the classical sufficient conditions for
convergence from every starting value of ``[a, b]``. The equation of problem 2,
``f(alpha) = T~(alpha) - target`` with the approximation (9), is :class:`PeriodEquation`.

References
----------
.. [1] K. E. Atkinson, *An Introduction to Numerical Analysis*, 2nd ed., Wiley, 1989,
   section 2.2 (Newton's method: quadratic convergence, ``(z - x[k+1]) / (z - x[k])^2 ->
   -f''(z) / (2 f'(z))``).
.. [2] H. Pina, *Métodos Numéricos*, McGraw-Hill, 1995, chapter 2: the sufficient
   conditions on ``[a, b]`` (``f(a) f(b) < 0``; ``f'`` without zeros; ``f''`` of constant
   sign; ``|f(a)/f'(a)| <= b - a`` and ``|f(b)/f'(b)| <= b - a``) under which Newton's
   method converges to the only zero in ``[a, b]`` from every ``x0`` in ``[a, b]``.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from ..core import validate as v
from ..core.cases import G
from ..core.errors import InputError, NumericalError
from .results import Result

#: Unit roundoff of IEEE double precision.
U = 2.0**-53
#: q_k is kept while its relative rounding error bound is at most this.
Q_RTOL = 0.01

Fn = Callable[[float], float]
#: How a run stops (:attr:`NewtonResult.criterion`): at a given tolerance on the correction,
#: or at the rounding level of ``x`` (``4 delta``, see :func:`rounding_level`).
Criterion = Literal["tolerance", "rounding_level"]
#: What stopped it (:attr:`NewtonResult.stop_reason`): ``f(x_k) = 0`` exactly, or a
#: correction at or below the criterion's limit.
StopReason = Literal["zero_value", "small_correction"]
#: The sufficient conditions of :func:`check_interval`, in order (:attr:`Condition.name`).
ConditionName = Literal["sign_change", "derivative_nonzero", "curvature_constant", "step_from_a", "step_from_b"]


# --------------------------------------------------------------------------- iteration
@dataclass(frozen=True, eq=False)
class NewtonResult(Result):
    """Every iterate of a Newton run and what it says about convergence.

    Attributes
    ----------
    iterates : tuple of float
        ``x_0 .. x_N``; ``root`` is ``x_N``.
    values, derivatives : tuple of float
        ``f(x_k)`` and ``f'(x_k)`` for ``k = 0 .. N``.
    corrections : tuple of float
        ``x[k+1] - x[k]``, ``k = 0 .. N-1``.
    criterion : {"tolerance", "rounding_level"}
        The stopping rule: ``|x[k+1] - x[k]| <= tol`` (``tol`` given) or ``<= 4 delta_k``, the
        rounding level of ``x`` (:func:`rounding_level`), beyond which another step cannot
        reduce the error.
    tol : float or None
        The tolerance given (``criterion == "tolerance"``).
    stop_reason : {"zero_value", "small_correction"}
        What stopped the run: ``f(x_N) = 0`` exactly, or ``|x_N - x_(N-1)| <= stop_limit``.
    stop_correction, stop_limit : float or None
        ``|x_N - x_(N-1)|`` and the limit it met (``stop_reason == "small_correction"``).
    rounding_level : float
        ``delta``: the rounding error of one iterate near the root,
        ``u (|x| + S / |f'(x)|)`` with ``S`` the size of the terms that make ``f``.
    q : tuple of float or None
        ``q_k = |x[k+2]-x[k+1]| / |x[k+1]-x[k]|^2``, ``k = 0 .. N-2`` (None where the
        denominator is 0).
    q_rounding : tuple of float
        First-order bound of the relative rounding error of each ``q_k``:
        ``delta/|x[k+2]-x[k+1]| + 2 delta/|x[k+1]-x[k]|``.
    k_max : int or None
        The last ``k`` whose ``q_k`` has ``q_rounding <= 1%`` (None if no quotient does):
        beyond it the numerator is rounding noise, not the error.
    asymptotic_constant : float or None
        ``|f''(z) / (2 f'(z))|`` at ``z = x_N`` (needs ``f''``), the limit of ``q_k``.
    error_estimate : float
        ``|z - x_N| ~ C |x_N - x_{N-1}|^2 + delta`` (superlinear convergence: the last
        correction bounds the previous error, and the next error is ``C`` times its square).
    """

    iterates: tuple[float, ...]
    values: tuple[float, ...]
    derivatives: tuple[float, ...]
    corrections: tuple[float, ...]
    criterion: Criterion
    tol: float | None
    stop_reason: StopReason
    stop_correction: float | None
    stop_limit: float | None
    rounding_level: float
    q: tuple[float | None, ...]
    q_rounding: tuple[float, ...]
    k_max: int | None
    asymptotic_constant: float | None
    error_estimate: float

    @property
    def root(self) -> float:
        return self.iterates[-1]

    @property
    def iterations(self) -> int:
        return len(self.iterates) - 1

    @property
    def q_kmax(self) -> float | None:
        return None if self.k_max is None else self.q[self.k_max]


def rounding_level(x: float, dfx: float, f_scale: float) -> float:
    """``u (|x| + S/|f'(x)|)``: one iterate's rounding error near a simple root.

    ``f`` is computed with an absolute error of about ``u S`` (``S`` the size of the terms
    summed in ``f``); a Newton step turns it into ``u S / |f'|`` in ``x``, and storing ``x``
    adds ``u |x|``.
    """
    return U * (abs(x) + (abs(f_scale) / abs(dfx) if dfx else math.inf))


def quotients(iterates, delta: float) -> tuple[list[float | None], list[float], int | None]:
    """``q_k``, the rounding bound of each, and ``k_max`` (see :class:`NewtonResult`)."""
    x = [float(t) for t in iterates]
    d = [abs(b - a) for a, b in zip(x, x[1:])]
    q: list[float | None] = []
    rho: list[float] = []
    for k in range(len(d) - 1):
        q.append(d[k + 1] / d[k] ** 2 if d[k] > 0 else None)
        num = delta / d[k + 1] if d[k + 1] > 0 else math.inf
        rho.append(num + (2 * delta / d[k] if d[k] > 0 else math.inf))
    k_max = None
    for k, r in enumerate(rho):
        if r <= Q_RTOL and q[k] is not None:
            k_max = k
        else:
            break
    return q, rho, k_max


def newton(
    f: Fn,
    df: Fn,
    x0: float,
    *,
    d2f: Fn | None = None,
    f_scale: float | None = None,
    tol: float | None = None,
    max_iter: int = 100,
    domain: tuple[float, float] | None = None,
) -> NewtonResult:
    """Newton's method ``x[k+1] = x[k] - f(x[k]) / f'(x[k])`` from ``x0``, every iterate kept.

    Parameters
    ----------
    f, df : callable
        ``f`` and ``f'`` on floats.
    x0 : float
        Starting value.
    d2f : callable, optional
        ``f''``, for the asymptotic constant ``|f''(z) / (2 f'(z))|``.
    f_scale : float, optional
        Size of the terms summed to compute ``f`` (its rounding error is about
        ``u f_scale``). Default: ``max |f(x_k)|`` over the iterates, a rough stand-in.
    tol : float, optional
        Stop when ``|x[k+1] - x[k]| <= tol``. Default ``4 delta`` (see
        :func:`rounding_level`): the correction is at the rounding level of ``x``, so a
        further step can no longer reduce the error.
    max_iter : int
        At most this many steps; not converged by then raises :class:`NumericalError`.
    domain : (lo, hi), optional
        Open interval the iterates must stay in (else :class:`NumericalError`).

    Returns
    -------
    NewtonResult
    """
    x = v.finite("x0", x0)
    max_iter = v.integer("max_iter", max_iter, 1, 10000)
    if tol is not None:
        tol = v.non_negative("tol", tol)

    def inside(t: float) -> bool:
        return domain is None or domain[0] < t < domain[1]

    if domain is not None and not inside(x):
        raise InputError("x0", x0, f"in the domain ({domain[0]:g}, {domain[1]:g})")
    xs, fs, dfs = [x], [f(x)], [df(x)]
    scale = f_scale
    reason: StopReason | None = None
    stop: tuple[float, float] | None = None
    for _ in range(max_iter):
        fx, dfx = fs[-1], dfs[-1]
        if fx == 0:
            reason = "zero_value"
            break
        if dfx == 0 or not math.isfinite(dfx):
            raise NumericalError(f"Newton's method: f'(x) = {dfx} at x = {x!r}; start closer to the root")
        x_new = x - fx / dfx
        if not math.isfinite(x_new) or not inside(x_new):
            where = "" if domain is None else f" left the domain ({domain[0]:g}, {domain[1]:g})"
            raise NumericalError(
                f"Newton's method: iterate x_{len(xs)} = {x_new!r}{where}; start inside a convergence interval"
            )
        xs.append(x_new)
        fs.append(f(x_new))
        dfs.append(df(x_new))
        s = scale if scale is not None else max(abs(t) for t in fs)
        limit = tol if tol is not None else 4 * rounding_level(x_new, dfx, s)
        step = abs(x_new - x)
        x = x_new
        if step <= limit:
            reason, stop = "small_correction", (step, limit)
            break
    else:
        raise NumericalError(f"Newton's method did not converge in {max_iter} steps from x0 = {x0!r}")
    s = scale if scale is not None else max(abs(t) for t in fs)
    delta = rounding_level(xs[-1], dfs[-1], s)
    q, rho, k_max = quotients(xs, delta)
    const = abs(d2f(xs[-1]) / (2 * dfs[-1])) if d2f is not None else None
    q_max = q[k_max] if k_max is not None else None
    c_est = const if const is not None else (q_max if q_max is not None else 0.0)
    last = abs(xs[-1] - xs[-2]) if len(xs) > 1 else 0.0
    assert reason is not None  # the loop ends by break or raises
    return NewtonResult(
        iterates=tuple(xs),
        values=tuple(fs),
        derivatives=tuple(dfs),
        corrections=tuple(b - a for a, b in zip(xs, xs[1:])),
        criterion="tolerance" if tol is not None else "rounding_level",
        tol=tol,
        stop_reason=reason,
        stop_correction=None if stop is None else stop[0],
        stop_limit=None if stop is None else stop[1],
        rounding_level=delta,
        q=tuple(q),
        q_rounding=tuple(rho),
        k_max=k_max,
        asymptotic_constant=const,
        error_estimate=c_est * last**2 + delta,
    )


# --------------------------------------------------------------------------- interval
@dataclass(frozen=True, eq=False)
class Condition(Result):
    """One sufficient condition, whether it holds, and the numbers that show it.

    ``name`` says which (:data:`ConditionName`); ``values`` holds its numbers: ``f_a``,
    ``f_b`` (sign change); ``min``, ``max`` of ``f'`` or ``f''`` on the grid; ``step``
    (``|f(a)/f'(a)|`` or ``|f(b)/f'(b)|``) and ``width`` (``b - a``).
    """

    name: ConditionName
    holds: bool
    values: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False)
class IntervalCheck(Result):
    """The classical sufficient conditions for Newton's method on ``[a, b]`` (reference [2] of the module).

    When all hold, ``f`` has exactly one zero ``z`` in ``[a, b]`` and Newton's method
    converges to it from every ``x0`` in ``[a, b]``.

    Attributes
    ----------
    a, b : float
        The interval.
    conditions : tuple of Condition
        Sign change; ``f'`` without zeros; ``f''`` of constant sign; the Newton steps from
        ``a`` and from ``b`` stay in ``[a, b]``.
    samples : int
        Points of the grid on which ``f'`` and ``f''`` were evaluated.
    """

    a: float
    b: float
    conditions: tuple[Condition, ...]
    samples: int

    @property
    def holds(self) -> bool:
        return all(c.holds for c in self.conditions)


def check_interval(f: Fn, df: Fn, d2f: Fn, a: float, b: float, samples: int = 2001) -> IntervalCheck:
    """Check the sufficient conditions for global convergence of Newton's method on ``[a, b]``.

    ``f'`` and ``f''`` are evaluated on ``samples`` equally spaced points (endpoints
    included): a numerical check. Where ``f'`` and ``f''`` are monotone on ``[a, b]`` (as
    for :class:`PeriodEquation`) the endpoints decide and the check is a proof.
    """
    a, b = v.finite("a", a), v.finite("b", b)
    if not a < b:
        raise InputError("b", b, f"> a = {a!r}")
    grid = np.linspace(a, b, v.integer("samples", samples, 2))
    fa, fb = f(a), f(b)
    d1 = np.array([df(t) for t in grid])
    d2 = np.array([d2f(t) for t in grid])
    dfa, dfb = df(a), df(b)
    step_a = abs(fa / dfa) if dfa else math.inf
    step_b = abs(fb / dfb) if dfb else math.inf
    width = b - a
    conds = (
        Condition("sign_change", fa * fb < 0, {"f_a": fa, "f_b": fb}),
        Condition("derivative_nonzero", bool(np.all(d1 > 0) or np.all(d1 < 0)),
                  {"min": float(d1.min()), "max": float(d1.max())}),
        Condition("curvature_constant", bool(np.all(d2 >= 0) or np.all(d2 <= 0)),
                  {"min": float(d2.min()), "max": float(d2.max())}),
        Condition("step_from_a", step_a <= width, {"step": step_a, "width": width}),
        Condition("step_from_b", step_b <= width, {"step": step_b, "width": width}),
    )
    return IntervalCheck(a, b, conds, len(grid))


# --------------------------------------------------------------------------- problem 2's equation
@dataclass(frozen=True)
class PeriodEquation:
    """``f(alpha) = (2 pi/p)(1 + sin^2(alpha/2)/4) - target``, ``p = sqrt(g/l)`` (problem 2, (9)).

    ``f'(alpha) = (2 pi/p) sin(alpha)/8`` and ``f''(alpha) = (2 pi/p) cos(alpha)/8``: on
    ``(0, pi)`` ``f'`` > 0 and ``f''`` has the sign of ``cos``, positive on ``(0, pi/2)``,
    negative on ``(pi/2, pi)``. ``T~`` runs from ``2 pi/p`` (alpha = 0) to ``1.25 (2 pi/p)``
    (alpha -> pi), so a target strictly between has exactly one root in ``(0, pi)``.
    """

    length: float
    target: float
    g: float = G

    def __post_init__(self):
        object.__setattr__(self, "length", v.positive("length", self.length))
        object.__setattr__(self, "g", v.positive("g", self.g))
        target = v.positive("target", self.target)
        lo, hi = self.small_angle_period, 1.25 * self.small_angle_period
        if not lo < target < hi:
            raise InputError(
                "target", self.target,
                f"in ({lo:.6g}, {hi:.6g}) s, the range of (9) for 0 < alpha < pi with l = {self.length:g}",
            )
        object.__setattr__(self, "target", target)

    @property
    def p(self) -> float:
        return math.sqrt(self.g / self.length)

    @property
    def small_angle_period(self) -> float:
        """``2 pi / p``."""
        return 2 * math.pi / self.p

    def f(self, alpha: float) -> float:
        k = math.sin(0.5 * alpha)
        return self.small_angle_period * (1 + 0.25 * k * k) - self.target

    def df(self, alpha: float) -> float:
        return self.small_angle_period * math.sin(alpha) / 8

    def d2f(self, alpha: float) -> float:
        return self.small_angle_period * math.cos(alpha) / 8

    @property
    def f_scale(self) -> float:
        """Size of the terms of ``f`` (for its rounding error): ``1.25 (2 pi/p) + target``."""
        return 1.25 * self.small_angle_period + self.target

    def closed_form(self) -> float:
        """The root in closed form: ``alpha = 2 arcsin(2 sqrt(target p/(2 pi) - 1))``."""
        return 2 * math.asin(2 * math.sqrt(self.target / self.small_angle_period - 1))

    def newton(self, x0: float, **kwargs) -> NewtonResult:
        """Newton's method on ``f`` from ``x0`` in ``(0, pi)``, iterates kept in ``(0, pi)``."""
        x0 = v.finite("x0", x0)
        if not 0 < x0 < math.pi:
            raise InputError("x0", x0, "an angle in (0, pi) rad, i.e. 0 < x0 < 180deg")
        return newton(self.f, self.df, x0, d2f=self.d2f, f_scale=self.f_scale, domain=(0.0, math.pi), **kwargs)

    def check(self, a: float, b: float) -> IntervalCheck:
        return check_interval(self.f, self.df, self.d2f, a, b)

    def interval(self, grid_degrees: tuple[float, ...] = (5.0, 1.0, 0.1, 0.01)) -> IntervalCheck:
        """The narrowest interval with ends on a degree grid where all conditions hold.

        Tries ends at multiples of 5 degrees first (then 1, 0.1, 0.01), narrowest first,
        inside ``(0, 90]`` or ``[90, 180)`` where ``f''`` keeps its sign.
        """
        for spacing in grid_degrees:
            n = round(180 / spacing)
            ends = [i * spacing for i in range(1, n)]  # (0, 180) exclusive
            fs = [self.f(math.radians(d)) for d in ends]
            cell = next((i for i in range(len(ends) - 1) if fs[i] * fs[i + 1] <= 0), None)
            if cell is None:
                continue
            for width in range(1, 8):
                for left in range(cell - width + 1, cell + 1):
                    right = left + width
                    if left < 0 or right >= len(ends):
                        continue
                    a, b = ends[left], ends[right]
                    if a < 90 < b:
                        continue
                    chk = self.check(math.radians(a), math.radians(b))
                    if chk.holds:
                        return chk
        raise NumericalError("no convergence interval found for Newton's method; give x0 instead")

    def fourier_start(self, chk: IntervalCheck) -> float:
        """The end of ``[a, b]`` where ``f f'' > 0`` (Fourier): from it the iterates are monotone."""
        return chk.a if self.f(chk.a) * self.d2f(chk.a) > 0 else chk.b
