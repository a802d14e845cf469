"""Each problem of the coursework as a function returning a result object.

The CLI, the report and the web explorer render these results; nothing here prints.
Defaults are the canonical inputs of :mod:`pendulab.core.cases`.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from ..core import cases
from ..core.errors import NumericalError
from ..core.methods import Status
from ..numerics.crossing import PeriodEstimate, estimate_period, observed_orders, search_error, search_period
from ..numerics.group import GroupLength, group_length
from ..numerics.period import FIXED_ITERATIONS_ULPS, agm_period
from ..numerics.results import Result
from ..numerics.simulation import Trajectory, simulate

if TYPE_CHECKING:  # names for annotations; the modules load when a problem runs
    import numpy as np

    from ..numerics.lsq import LeastSquaresFit
    from ..numerics.newton import IntervalCheck, NewtonResult, PeriodEquation
    from ..numerics.quadrature import Rule
    from ..numerics.uncertainty import GravityEstimate


# --------------------------------------------------------------------------- problem 3
#: 3(d): the interpolation error counts as negligible when it is below this fraction of
#: the Taylor method's own error in the period.
NEGLIGIBLE_RATIO = 1e-3
#: 3(b): how far (in periods T^) the h = 0.2 simulation is searched for its first
#: return to P or its passage over the top.
PLOT_SEARCH_PERIODS = 4.0
#: 3(b): ``t_max`` spans this many periods ``T^`` of (8), the coursework's hint.
PLOT_PERIODS = 2.0

#: 3(b): what the h = 0.2 simulation does first (``Problem3.plot_outcome``): it returns to
#: P, it leaves the oscillation, or neither within the search (not ``Status.NO_RETURN``,
#: the period search's status).
RETURNS, LEAVES, NEITHER = "returns", "leaves", "none"


@dataclass(frozen=True, eq=False)
class Problem3(Result):
    """Problem 3: the Taylor simulation and the period recovered from it.

    Attributes
    ----------
    figure3 : Trajectory
        3(a): ``l = 1``, ``alpha = pi/4``, ``h = 0.1`` on ``[0, 2.1]`` (Figure 3).
    group : GroupLength
        3(b): the group's length ``l``.
    amplitude : float
        ``4 pi/5``.
    t_hat : float
        ``T^`` of (8) (7 iterations, as the coursework prescribes) for the group's pendulum;
        the reference of problems 3 to 5, as the coursework prescribes.
    plot : Trajectory
        3(b): ``h = 0.2`` on ``[0, plot_t_max]`` (see :func:`plot_t_max`).
    plot_t_max : float
    plot_outcome : str
        What the ``h = 0.2`` simulation does first: ``"returns"`` to ``P`` (bracket in
        ``plot_estimate``), ``"leaves"`` the oscillation (goes over the top, ``|z1| > pi``,
        at ``plot_left_at``: the step is too large for this pendulum), or ``"none"``
        (neither within ``PLOT_SEARCH_PERIODS`` periods ``T^``).
    plot_left_at : float or None
        The first ``t_j`` with ``|z1_j| > pi`` when ``plot_outcome == "leaves"``.
    plot_estimate : PeriodEstimate or None
        The bracket of the ``h = 0.2`` simulation when it returns.
    estimates : list of PeriodEstimate
        3(c): one per step ``h = 10^-j``, ``j = 2, 3, 4``.
    linear_orders, cubic_orders : list of float or None
        Observed orders of the period error between consecutive steps.
    cubic : PeriodEstimate
        3(d): the estimate with ``h = 1e-3`` (its ``interpolation`` holds the table).
    interpolation_resolved : bool
        3(d): the error estimate stands above the rounding level of the times ``t_k``
        (``cubic.interpolation.rounding_level``); else it is rounding noise, and the
        interpolation error is bounded by that level instead.
    interpolation_bound : float
        ``max(|error estimate|, rounding level)``: how large the interpolation error can be.
    interpolation_ratio : float
        3(d): ``interpolation_bound`` over the Taylor method's error in the period.
    interpolation_negligible : bool
        3(d)'s answer: ``interpolation_ratio < NEGLIGIBLE_RATIO``.
    plot_status : str
        The ``h = 0.2`` search's status (``PeriodSearch.status``, lower case): ``"untrusted"``
        where it returns but near the separatrix cannot be trusted (a sum of 1115:
        ``l = 1.4953487812``, the return 27 % of ``T`` off); ``"found"`` for a trusted return.
    """

    figure3: Trajectory
    group: GroupLength
    amplitude: float
    t_hat: float
    plot: Trajectory
    plot_t_max: float
    plot_outcome: str
    plot_left_at: float | None
    plot_estimate: PeriodEstimate | None
    estimates: list[PeriodEstimate]
    linear_orders: list[float | None]
    cubic_orders: list[float | None]
    cubic: PeriodEstimate
    interpolation_resolved: bool
    interpolation_bound: float
    interpolation_ratio: float
    interpolation_negligible: bool
    plot_status: str = "found"

    @property
    def taylor_error(self) -> float:
        """3(d): the error of the Taylor method in the period, ``|p(0) - T^|`` at ``h = 1e-3``."""
        return abs(self.cubic.cubic - self.t_hat)


def plot_t_max(t_hat: float, step: float) -> float:
    """``t_max`` for 3(b) from (8) alone, as the coursework suggests: the first multiple of
    ``h`` at or beyond ``PLOT_PERIODS`` periods ``T^``. (The quotient is rounded to 9
    decimals first, so that a product that lands a rounding error above an integer, such
    as ``24 * 0.2 / 0.2``, gives that integer.)
    """
    return step * math.ceil(round(PLOT_PERIODS * t_hat / step, 9))


def plot_outcome(length: float, amplitude: float, step: float, t_hat: float):
    """3(b): ``(outcome, left_at, estimate, t_max, status)`` of the simulation with step ``step``
    (``status``: the search's, lower case; ``"untrusted"`` for a return near the separatrix).

    The simulation is searched over ``PLOT_SEARCH_PERIODS`` periods ``t_hat``: it returns to
    ``P`` (sign change of ``z2`` with ``z1 > 0``), or its discrete energy grows until it
    goes over the top (``|z1| > pi``), which the pendulum's exact motion, released below the top
    at rest, never does.
    """
    search = PLOT_SEARCH_PERIODS * t_hat
    found = search_period(length, amplitude, step, search)
    if found.status == Status.LEFT_OSCILLATION:  # the search carries the time it went over the top
        assert found.t_left is not None
        return LEAVES, found.t_left, None, plot_t_max(t_hat, step), found.status.name.lower()
    if found.estimate is None:
        if found.status != Status.NO_RETURN:
            raise search_error(found)
        return NEITHER, None, None, plot_t_max(t_hat, step), found.status.name.lower()
    return RETURNS, None, found.estimate, plot_t_max(t_hat, step), found.status.name.lower()


def problem3(
    students: Sequence[int] = cases.EXAMPLE_GROUP,
    steps: Sequence[float] = cases.PROBLEM3_STEPS,
    cubic_step: float = cases.PROBLEM3_CUBIC_STEP,
) -> Problem3:
    """Solve problem 3 for a group of students (default: the coursework's example group, ``cases.EXAMPLE_GROUP``)."""
    fig = cases.FIGURE3
    figure3 = simulate(fig.l, fig.alpha, cases.FIGURE3_STEP, cases.FIGURE3_T_MAX)
    group = group_length(students)
    length = group.length
    alpha = float(cases.PROBLEM3_AMPLITUDE)
    t_hat = agm_period(length, alpha, iterations=7)
    h = cases.PROBLEM3_PLOT_STEP
    outcome, left_at, plot_estimate, t_max, plot_status = plot_outcome(length, alpha, h, t_hat)
    plot = simulate(length, alpha, h, t_max)
    steps = list(steps)
    if cubic_step not in steps:
        steps.append(cubic_step)
    estimates = [estimate_period(length, alpha, s) for s in steps]
    cubic = estimates[steps.index(cubic_step)]
    taylor_err = abs(cubic.cubic - t_hat)
    ip = cubic.interpolation
    bound = max(abs(ip.error_estimate), ip.rounding_level)
    ratio = bound / taylor_err if taylor_err > 0 else math.inf
    return Problem3(
        figure3=figure3,
        group=group,
        amplitude=alpha,
        t_hat=t_hat,
        plot=plot,
        plot_t_max=t_max,
        plot_outcome=outcome,
        plot_left_at=left_at,
        plot_estimate=plot_estimate,
        estimates=estimates,
        linear_orders=observed_orders(steps, [abs(e.linear - t_hat) for e in estimates]),
        cubic_orders=observed_orders(steps, [abs(e.cubic - t_hat) for e in estimates]),
        cubic=cubic,
        interpolation_resolved=ip.error_estimate_resolved,
        interpolation_bound=bound,
        interpolation_ratio=ratio,
        interpolation_negligible=ratio < NEGLIGIBLE_RATIO,
        plot_status=plot_status,
    )


# --------------------------------------------------------------------------- problem 1
def problem1(
    length: float = cases.GRAVITY_LENGTH,
    length_error: float = cases.GRAVITY_LENGTH_ERROR,
    period: float = cases.GRAVITY_PERIOD,
    period_error: float = cases.GRAVITY_PERIOD_ERROR,
) -> GravityEstimate:
    """Problem 1: ``g = 4 pi^2 l/T^2`` from ``l = 115.2 cm``, ``T = 2.1536 s`` and its error.

    Returns the :class:`pendulab.numerics.uncertainty.GravityEstimate` (formulas of 1(a), bounds,
    guaranteed significant digits of 1(b) and the rule used).
    """
    from ..numerics.uncertainty import gravity_estimate

    return gravity_estimate(length, length_error, period, period_error)


def digit_thresholds(value: float, digits: int) -> tuple[int, float, float]:
    """1(b): ``k = floor(log10|value|)`` and the bounds ``0.5 10^(k-n+1)`` for ``n`` and ``n+1`` digits.

    An approximation has ``n`` significant digits when its error is at most the first
    bound; the second is the bound for one digit more.
    """
    from ..numerics.uncertainty import leading_exponent

    k = leading_exponent(value)  # exact: log10 rounds up just below a power of ten
    return k, 0.5 * 10.0 ** (k - digits + 1), 0.5 * 10.0 ** (k - digits)


# --------------------------------------------------------------------------- problem 2
#: The conditions of :func:`pendulab.numerics.newton.check_interval`, in its order.
CONDITION_KEYS = ("sign", "df", "d2f", "step_a", "step_b")


@dataclass(frozen=True, eq=False)
class Problem2(Result):
    """Problem 2: the amplitude with ``T~ = target`` by Newton's method on (9).

    Attributes
    ----------
    equation : PeriodEquation
        ``f(alpha) = (2 pi/p)(1 + sin^2(alpha/2)/4) - target``, with ``p``, ``f``, ``f'``, ``f''``.
    interval : IntervalCheck
        2(a): ``[a, b]`` and the five sufficient conditions, each with its numbers.
    interval_deg : (float, float)
        ``[a, b]`` in degrees.
    x0 : float
        The starting value (rad).
    x0_from_fourier : bool
        ``x0`` was chosen by Fourier's condition (not given by the caller).
    x0_in_interval : bool
    run : NewtonResult
        Iterates, corrections, ``q_k``, ``k_max``, asymptotic constant, error estimate.
    alpha, alpha_deg : float
        The last iterate, rad and degrees.
    closed_form : float
        ``2 arcsin(2 sqrt(target p/(2 pi) - 1))``: (9) solved by hand, as a check.
    condition_values : dict
        The numbers of each condition of 2(a) under a short key: ``sign`` (``f_a``, ``f_b``),
        ``df`` and ``d2f`` (``min``, ``max`` on the grid), ``step_a`` and ``step_b``
        (``step``, ``width``).
    ratios : tuple of float
        ``|x[k+2]-x[k+1]| / |x[k+1]-x[k]|`` -> 0: convergence is superlinear (2(b)).
    curvature_positive : bool
        ``f'' >= 0`` on ``[a, b]`` (the interval lies below ``pi/2``; else above it, as the
        conditions of 2(a) require a constant sign): the decision behind the words
        (``p2.justification.*`` of the catalogues) on why the grid check is a proof for this ``f``.
    """

    equation: PeriodEquation
    interval: IntervalCheck
    interval_deg: tuple[float, float]
    x0: float
    x0_from_fourier: bool
    x0_in_interval: bool
    run: NewtonResult
    alpha: float
    alpha_deg: float
    closed_form: float
    condition_values: dict[str, dict[str, float]]
    ratios: tuple[float | None, ...]
    curvature_positive: bool

    @property
    def asymptotic_constant(self) -> float | None:
        return self.run.asymptotic_constant

    @property
    def error_estimate(self) -> float:
        return self.run.error_estimate

    def to_dict(self) -> dict[str, Any]:
        """Flat (``pendulab newton --json``): the equation's numbers, the run's (iterates,
        ``q_k``, the stop), ``[a, b]`` and each condition of 2(a) with its numbers."""
        e, chk = self.equation, self.interval
        return {
            "length": e.length, "target": e.target, "g": e.g, "p": e.p,
            "alpha": self.alpha, "alpha_deg": self.alpha_deg, "closed_form": self.closed_form,
            "x0": self.x0, "x0_from_fourier": self.x0_from_fourier, "x0_in_interval": self.x0_in_interval,
            **self.run.to_dict(),
            "ratios": list(self.ratios),
            "interval": [chk.a, chk.b], "interval_deg": list(self.interval_deg),
            "interval_conditions": [{"name": c.name, "holds": c.holds, **c.values} for c in chk.conditions],
            "curvature_positive": self.curvature_positive,
        }


def problem2(
    length: float = cases.NEWTON_LENGTH,
    target: float = cases.NEWTON_TARGET,
    x0: float | None = None,
    g: float = cases.G,
) -> Problem2:
    """Problem 2: solve ``T~(alpha) = target`` (9) by Newton's method, ``l = 0.5``, target 1.5 s.

    ``x0=None`` starts from the end of the convergence interval where ``f f'' > 0``
    (Fourier's condition: the iterates then approach the root monotonically).
    """
    from ..core import validate as v
    from ..core.errors import InputError, NumericalError
    from ..numerics.newton import PeriodEquation

    eq = PeriodEquation(length, target, g)
    if x0 is not None and not 0 < v.finite("x0", x0) < math.pi:
        raise InputError("x0", x0, "an angle in (0, pi) rad, i.e. 0 < x0 < 180deg")
    chk = eq.interval()
    start = eq.fourier_start(chk) if x0 is None else float(x0)
    try:
        run = eq.newton(start)
    except NumericalError as exc:
        lo, hi = (round(math.degrees(t), 9) for t in (chk.a, chk.b))
        raise NumericalError(f"{exc}, e.g. [{lo:g}, {hi:g}] deg") from None
    d = [abs(b - a) for a, b in zip(run.iterates, run.iterates[1:])]
    ratios = tuple(d[k + 1] / d[k] if d[k] > 0 else None for k in range(len(d) - 1))
    a_deg = round(math.degrees(chk.a), 9)
    b_deg = round(math.degrees(chk.b), 9)
    return Problem2(
        equation=eq,
        interval=chk,
        interval_deg=(a_deg, b_deg),
        x0=start,
        x0_from_fourier=x0 is None,
        x0_in_interval=chk.a <= start <= chk.b,
        run=run,
        alpha=run.root,
        alpha_deg=math.degrees(run.root),
        closed_form=eq.closed_form(),
        condition_values={key: dict(c.values) for key, c in zip(CONDITION_KEYS, chk.conditions)},
        ratios=ratios,
        curvature_positive=chk.conditions[2].values["min"] >= 0,  # f'' = (2 pi/p) cos(alpha)/8 on the grid
    )


# --------------------------------------------------------------------------- problem 4
#: 4(d)(ii)'s threshold.
PROBLEM4_TOLERANCE = 1e-5
#: Points per data step for the deviation from the exact motion between data points.
PROBLEM4_FINE = 20
#: The most data steps of problem 4 (2e6 points of exact motion, about 100 MB of work arrays).
PROBLEM4_MAX_STEPS = 100_000


#: Where problem 4's ``t_max`` came from: ``ceil(T^)`` (the default) or the caller.
TMaxRule = Literal["ceil_t_hat", "given"]


@dataclass(frozen=True, eq=False)
class Problem4(Result):
    """Problem 4: least-squares fit of the Taylor data by (10).

    Attributes
    ----------
    length, amplitude, step : float
        ``l = 3.5``, ``alpha = pi/4``, ``h = 0.01``.
    t_hat : float
        ``T^`` of (8), 7 iterations.
    t_max : float
        ``ceil(T^)`` (4 for ``l = 3.5``: 401 points, not the original's ``Y_0 .. Y_600``)
        unless given.
    t_max_rule : {"ceil_t_hat", "given"}
        Where ``t_max`` came from.
    data : Trajectory
        4(a): the points ``Y_j = (t_j, z1_j)``.
    last_points : ndarray, shape (10, 2)
        4(a): the last 10 data points.
    fit : LeastSquaresFit
        4(c)-(d): normal equations (rounded), the SPD proof, coefficients, deviations.
    tolerance : float
        ``1e-5``.
    below_tolerance : bool
        4(d)(ii), answered at the data points: ``max_j |z1_j - phi~(t_j)| < 1e-5``.
    exact_deviation, exact_deviation_at : float
        ``max |theta(t) - phi~(t)|`` over ``[t0, t_max]`` sampled 20 times per step, against
        the exact motion ``theta(t)`` (Jacobi functions): the deviation between data points.
    taylor_error : float
        ``max_j |z1_j - theta(t_j)|``: the data's own error (Taylor method).
    curve_t, curve_phi, curve_exact : ndarray
        ``phi~`` and the exact ``theta`` on the fine grid (20 points per step), for plots.
    """

    length: float
    amplitude: float
    step: float
    t_hat: float
    t_max: float
    t_max_rule: TMaxRule
    data: Trajectory
    last_points: np.ndarray
    fit: LeastSquaresFit
    tolerance: float
    below_tolerance: bool
    exact_deviation: float
    exact_deviation_at: float
    taylor_error: float
    curve_t: np.ndarray
    curve_phi: np.ndarray
    curve_exact: np.ndarray

    @property
    def points(self) -> int:
        return len(self.data.t)

    def to_dict(self) -> dict[str, Any]:
        """Flat (``pendulab fit --json``): the inputs, the last points, the normal equations
        and their proof of definiteness, the coefficients by name, the deviations; without
        the data and the fine curves (``data``, ``curve_*``: arrays for plots)."""
        f = self.fit
        return {
            "length": self.length, "amplitude": self.amplitude, "step": self.step, "t_hat": self.t_hat,
            "t_max": self.t_max, "t_max_rule": self.t_max_rule, "points": self.points,
            "last_points": self.last_points, "decimals": f.decimals,
            "normal_matrix": f.normal_matrix, "normal_rhs": f.normal_rhs,
            **f.definiteness.to_dict(),
            "coefficients": f.coefficient_dict(),
            "reference_coefficients": dict(zip(f.names, f.reference_coefficients.tolist())),
            "coefficient_shift": f.coefficient_shift,
            "ssd": f.ssd, "max_deviation": f.max_deviation, "argmax_deviation": f.argmax_deviation,
            "tolerance": self.tolerance, "below_tolerance": self.below_tolerance,
            "exact_deviation": self.exact_deviation, "exact_deviation_at": self.exact_deviation_at,
            "taylor_error": self.taylor_error,
        }


def problem4(
    length: float = cases.PROBLEM4.l,
    amplitude: float = cases.PROBLEM4.alpha,
    step: float = cases.PROBLEM4_STEP,
    t_max: float | None = None,
    decimals: int | None = cases.PROBLEM4_ROUND,
    g: float = cases.G,
    taylor_data: tuple | None = None,
) -> Problem4:
    """Problem 4: data by the Taylor algorithm, fit by (10) through rounded normal equations.

    ``taylor_data``: the lists ``(t, z1, z2)`` of (3) for these inputs when already computed
    (the report passes the coursework program's, the same doubles, so it needs no compiled
    kernel); the simulation is then not run again.
    """
    import numpy as np

    from ..numerics.lsq import TRIG_BASIS, evaluate, least_squares
    from ..numerics.motion import exact_motion

    t_hat = agm_period(length, amplitude, g, iterations=7)
    rule: TMaxRule = "ceil_t_hat" if t_max is None else "given"
    if t_max is None:
        t_max = float(math.ceil(t_hat))
    from ..core import validate as v
    from ..core.errors import InputError

    # Work by arithmetic first: at most PROBLEM4_MAX_STEPS data steps (the exact motion is
    # then evaluated on 20 times as many points), and at least one point per term of (10).
    _, t_end, h = v.time_span(0.0, t_max, v.positive("step", step))
    n = v.steps_within("step", 0.0, t_end, h, PROBLEM4_MAX_STEPS)
    if n + 1 < len(TRIG_BASIS):
        gaps = len(TRIG_BASIS) - 1
        why = f"so that the data has at least {len(TRIG_BASIS)} points, one per coefficient of (10)"
        raise InputError("step", step, f"<= t_max/{gaps} = {t_end / gaps:.6g} s {why}", mentions=("t_max",),
                         alternative=InputError("t_max", t_max, f">= {gaps} x step = {gaps * h:.6g} s {why}",
                                                mentions=("step",)))
    if taylor_data is None:
        data = simulate(length, amplitude, step, t_max, 0.0, g)
    else:
        t, z1, z2 = (np.asarray(a, dtype=float) for a in taylor_data)
        if not len(t) == len(z1) == len(z2) == n + 1:
            raise InputError("taylor_data", f"{len(t)} points", f"the {n + 1} points t_0, ..., t_N of (6)")
        data = Trajectory(t, z1, z2, float(length), float(amplitude), float(g), float(h), 0.0)
    if not np.all(np.isfinite(data.theta)):
        raise NumericalError(
            f"the Taylor data overflowed (theta is not finite): step h = {data.step:g} s is too large for "
            f"g/l = {data.g / data.length:.3g} 1/s^2; use h well below sqrt(l/g) = {(data.length / data.g) ** 0.5:.3g} s"
        )
    fit = least_squares(data.t, data.theta, decimals=decimals)
    fine = np.linspace(data.t[0], data.t[-1], PROBLEM4_FINE * (len(data.t) - 1) + 1)
    curve_phi = evaluate(fit.coefficients, TRIG_BASIS, fine)
    curve_exact = exact_motion(length, amplitude, fine, g).theta
    dev = np.abs(curve_exact - curve_phi)
    j = int(np.argmax(dev))
    taylor_err = float(np.max(np.abs(exact_motion(length, amplitude, data.t, g).theta - data.theta)))
    below = fit.max_deviation < PROBLEM4_TOLERANCE
    return Problem4(
        length=float(length),
        amplitude=float(amplitude),
        step=float(step),
        t_hat=t_hat,
        t_max=float(t_max),
        t_max_rule=rule,
        data=data,
        last_points=data.time_series()[-10:],
        fit=fit,
        tolerance=PROBLEM4_TOLERANCE,
        below_tolerance=below,
        exact_deviation=float(dev[j]),
        exact_deviation_at=float(fine[j]),
        taylor_error=taylor_err,
        curve_t=fine,
        curve_phi=curve_phi,
        curve_exact=curve_exact,
    )


# --------------------------------------------------------------------------- problem 5
#: 5(d): an error below this many units of roundoff of ``T^`` is rounding, not truncation
#: (the floor of the observed rates in :func:`pendulab.numerics.quadrature.convergence_table`).
ROUNDING_FLOOR = 64 * 2.0**-52


@dataclass(frozen=True, eq=False)
class Problem5(Result):
    """Problem 5: the period integral (1) by rule (11), simple and composite.

    Attributes
    ----------
    length, amplitude, g : float
        ``l = 3.5``, ``alpha = 4 pi/5``.
    t_hat : float
        ``T^`` of (8), 7 iterations: the reference of the plain errors,
        and of the substituted ones while it is within rounding of :attr:`period`.
    period : float
        The period to convergence, correctly rounded (:func:`~pendulab.numerics.period.agm_period`):
        the substituted errors' reference where ``T^`` is more than
        ``FIXED_ITERATIONS_ULPS`` from it, more than the loop's rounding can account for
        (within about 3e-14 of pi, where 7 iterations have not converged: 46 ulp off at
        the last double below pi, ``benchmarks/adversarial.py``).
    rule : Rule
        Rule (11) (3-point Gauss-Legendre, checked: weights sum 2, degree 5).
    single : float
        5(b): one application of (11) on ``[0, alpha]``.
    composite10 : float
        5(c): ``S_10``.
    rows : tuple of QuadratureRow
        5(d): ``n``, period, error, observed rate; with the substitution's columns.
    rounding_floor : float
        ``64 u T^``: an error below it is rounding, not truncation.
    substitution_converged_n : int or None
        The first ``n`` whose substituted error is at the rounding floor.
    graded : bool
        The substituted columns use panels graded towards the peak near pi.
    """

    length: float
    amplitude: float
    g: float
    t_hat: float
    period: float
    rule: Rule
    single: float
    composite10: float
    rows: tuple
    rounding_floor: float
    substitution_converged_n: int | None
    graded: bool = False

    @property
    def t_hat_ulps(self) -> int:
        """``T^ - T`` in ulps of the correctly rounded ``T``."""
        return _ulps_from(self.t_hat, self.period)

    @property
    def t_hat_converged(self) -> bool:
        """``T^`` is within the rounding of the double loop (``FIXED_ITERATIONS_ULPS``) of ``T``."""
        return _converged(self.t_hat, self.period)

    @property
    def substitution_reference(self) -> float:
        """The substituted errors' reference: ``T^`` (8) where it has converged, else ``T``."""
        return _substitution_reference(self.t_hat, self.period)

    def to_dict(self) -> dict[str, Any]:
        """The numbers (``pendulab quadrature --json``): the fields but the rule, ``t_hat_ulps``,
        ``t_hat_converged``, and with the substitution its reference by name (``"t_hat"`` or ``"period"``)."""
        d = super().to_dict()
        del d["rule"], d["substitution_reference"]  # the rule is a constant, GAUSS3
        if any(row.substitution_estimate is not None for row in self.rows):
            d["substitution_reference"] = "t_hat" if self.t_hat_converged else "period"
        return d


def _ulps_from(t_hat: float, rounded: float) -> int:
    """``t_hat - rounded`` in ulps of ``rounded``: one rule for problem 5's note and its table."""
    return round((t_hat - rounded) / math.ulp(rounded))


def _converged(t_hat: float, rounded: float) -> bool:
    """``t_hat`` is within the rounding of the double loop (``FIXED_ITERATIONS_ULPS``) of ``rounded``."""
    return abs(_ulps_from(t_hat, rounded)) <= FIXED_ITERATIONS_ULPS


def _substitution_reference(t_hat: float, rounded: float) -> float:
    """``t_hat`` where it has converged (:func:`_converged`), else ``rounded``.

    The substituted rule reaches the rounding level: against a ``T^`` that has not converged
    (near pi) its error would be ``T^``'s, so it is measured against the true period there.
    """
    return t_hat if _converged(t_hat, rounded) else rounded


def problem5(
    length: float = cases.PROBLEM5.l,
    amplitude: float = cases.PROBLEM5.alpha,
    ns: Sequence[int] = (1,) + tuple(cases.PROBLEM5_N),
    substitution: bool = True,
    g: float = cases.G,
    graded: bool = False,
) -> Problem5:
    """Problem 5: ``T`` from (1) by rule (11) on 1, 10, ..., 10^5 subintervals, errors against (8).

    ``graded`` (with ``substitution``): the substituted integral on panels graded towards
    its peak, which equal panels cannot resolve near pi (:func:`~pendulab.numerics.quadrature.quadrature_period`).
    """
    from ..numerics.quadrature import GAUSS3, convergence_table, quadrature_period

    t_hat = agm_period(length, amplitude, g, iterations=7)
    rounded = agm_period(length, amplitude, g)
    rows = convergence_table(length, amplitude, ns, t_hat, g, substitution=substitution, graded=graded,
                             substitution_reference=_substitution_reference(t_hat, rounded))
    floor = ROUNDING_FLOOR * abs(t_hat)
    converged = next((row.n for row in rows if row.substitution_error is not None
                      and row.substitution_error <= floor), None)
    return Problem5(
        length=float(length),
        amplitude=float(amplitude),
        g=float(g),
        t_hat=t_hat,
        period=rounded,
        rule=GAUSS3,
        single=quadrature_period(length, amplitude, 1, g),
        composite10=quadrature_period(length, amplitude, 10, g),
        rows=tuple(rows),
        rounding_floor=floor,
        substitution_converged_n=converged,
        graded=graded,
    )
