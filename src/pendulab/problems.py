"""Each problem of the coursework as a function returning a result object.

The CLI, the report and the web explorer render these results; nothing here prints.
Defaults are the canonical inputs of :mod:`pendulab.cases`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

from . import cases
from .crossing import PeriodEstimate, estimate_period, observed_orders
from .group import GroupLength, group_length
from .period import agm_period
from .taylor import Trajectory, simulate


# --------------------------------------------------------------------------- problem 3
@dataclass(frozen=True)
class Problem3:
    """Problem 3: the Taylor simulation and the period recovered from it.

    Attributes
    ----------
    figure3 : Trajectory
        3(a): ``l = 1``, ``alpha = pi/4``, ``h = 0.1`` on ``[0, 2.1]`` (Figure 3).
    group : GroupLength
        3(b): the group's length ``l``.
    amplitude : float
        ``4 pi/5``.
    exact : float
        ``T^`` of (8) (7 iterations, as the coursework prescribes) for the group's pendulum.
    plot : Trajectory
        3(b): ``h = 0.2`` on ``[0, plot_t_max]``, ``plot_t_max`` the first multiple of ``h``
        beyond ``1.25 T^`` so the first return to ``P`` is in view.
    plot_estimate : PeriodEstimate or None
        The bracket of the ``h = 0.2`` simulation (None if it never returns).
    estimates : list of PeriodEstimate
        3(c): one per step ``h = 10^-j``, ``j = 2, 3, 4``.
    linear_orders, cubic_orders : list of float or None
        Observed orders of the period error between consecutive steps.
    cubic : PeriodEstimate
        3(d): the estimate with ``h = 1e-3`` (its ``interpolation`` holds the table).
    """

    figure3: Trajectory
    group: GroupLength
    amplitude: float
    exact: float
    plot: Trajectory
    plot_t_max: float
    plot_estimate: PeriodEstimate | None
    estimates: list[PeriodEstimate]
    linear_orders: list[float | None]
    cubic_orders: list[float | None]
    cubic: PeriodEstimate

    @property
    def taylor_error(self) -> float:
        """3(d): the error of the Taylor method in the period, ``|p(0) - T^|`` at ``h = 1e-3``."""
        return abs(self.cubic.cubic - self.exact)


def plot_t_max(exact: float, step: float) -> float:
    """``t_max`` for 3(b): the first multiple of ``h`` beyond ``1.25 T^`` (based on (8))."""
    return step * math.ceil(1.25 * exact / step)


def problem3(
    students: Sequence[int] = cases.EXAMPLE_GROUP,
    steps: Sequence[float] = cases.PROBLEM3_STEPS,
    cubic_step: float = cases.PROBLEM3_CUBIC_STEP,
) -> Problem3:
    """Solve problem 3 for a group of students (default: the spec's 262, 407, 634)."""
    fig = cases.FIGURE3
    figure3 = simulate(fig.l, fig.alpha, cases.FIGURE3_STEP, cases.FIGURE3_T_MAX)
    group = group_length(students)
    length = group.length
    alpha = float(cases.PROBLEM3_AMPLITUDE)
    exact = agm_period(length, alpha, iterations=7)
    h = cases.PROBLEM3_PLOT_STEP
    t_max = plot_t_max(exact, h)
    plot = simulate(length, alpha, h, t_max)
    try:
        plot_estimate = estimate_period(length, alpha, h, t_max)
    except ValueError:
        plot_estimate = None
    steps = list(steps)
    if cubic_step not in steps:
        steps.append(cubic_step)
    estimates = [estimate_period(length, alpha, s) for s in steps]
    cubic = estimates[steps.index(cubic_step)]
    return Problem3(
        figure3=figure3,
        group=group,
        amplitude=alpha,
        exact=exact,
        plot=plot,
        plot_t_max=t_max,
        plot_estimate=plot_estimate,
        estimates=estimates,
        linear_orders=observed_orders(steps, [abs(e.linear - exact) for e in estimates]),
        cubic_orders=observed_orders(steps, [abs(e.cubic - exact) for e in estimates]),
        cubic=cubic,
    )
