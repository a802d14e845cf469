"""Figures of problems 2, 4 and 5, drawn from the results of :mod:`pendulab.jobs.problems`.

The labels default to English; the report passes its catalogue's words.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._axes import axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..jobs.problems import Problem2, Problem4, Problem5

#: 5(d): the n^(-1/2) guide is drawn this factor above the first error, beside the data
#: (which follow it exactly) rather than on top of them.
GUIDE_OFFSET = 4.0


def fit(result: Problem4, ax: Axes | None = None, show_exact: bool = False, title: bool = True,
        labels: dict[str, str] | None = None) -> Axes:
    """4(d)(i): every data point ``(t_j, z1_j)`` and the least-squares ``phi~`` on one plot.

    ``result`` is a :class:`pendulab.jobs.problems.Problem4`. ``labels`` replaces the legend's
    and the axes' words (keys ``data``, ``fit``, ``exact``, ``x``, ``y``). Returns ``ax``.
    """
    ax = axes(ax)
    t, y = result.data.t, result.data.theta
    words = {"data": f"data $(t_j, z_{{1,j}})$, {len(t)} points",
             "fit": r"least squares $\tilde\phi(t)$, basis (10)", "exact": r"exact $\theta(t)$",
             "x": "t (s)", "y": r"$z_{1,j}$, $\tilde\phi(t)$ (rad)"} | (labels or {})
    # The curve wide and light underneath, every point small and dark over it: the fit
    # passes through the data, and both stay visible.
    ax.plot(result.curve_t, result.curve_phi, "-", color="C3", alpha=0.45, linewidth=2.4, zorder=2,
            solid_capstyle="butt", label=words["fit"])
    ax.plot(t, y, "o", markersize=1.1, color="C0", markeredgewidth=0, zorder=3, label=words["data"])
    if show_exact:
        ax.plot(result.curve_t, result.curve_exact, ":", color="0.3", linewidth=1, label=words["exact"])
    ax.set_xlabel(words["x"])
    ax.set_ylabel(words["y"])
    if title:
        ax.set_title(
            rf"$l = {result.length:g}$, $\alpha = {result.amplitude:.6g}$, $h = {result.step:g}$; "
            rf"SSD = {result.fit.ssd:.3e}, max dev. = {result.fit.max_deviation:.2e}",
            fontsize="medium",
        )
    ax.legend(loc="best", frameon=False, fontsize="small", markerscale=3)
    ax.grid(alpha=0.3, linewidth=0.4)
    return ax


def fit_residuals(result: Problem4, ax: Axes | None = None, labels: dict[str, str] | None = None) -> Axes:
    """The deviations ``z1_j - phi~(t_j)`` of problem 4 and the band ``+-tolerance`` of 4(d)(ii).

    The y axis is linear inside the band and logarithmic beyond (``symlog``): deviations
    hundreds of times the tolerance and the band itself show on one plot. ``labels``
    replaces the axis labels (keys ``x``, ``y``). Returns the axes drawn on.
    """
    ax = axes(ax)
    words = {"x": "t (s)", "y": r"$z_{1,j} - \tilde\phi(t_j)$ (rad)"} | (labels or {})
    tol = result.tolerance
    ax.axhspan(-tol, tol, color="C3", alpha=0.18, linewidth=0, zorder=1)
    for s in (1, -1):
        ax.axhline(s * tol, color="C3", linestyle="--", linewidth=0.6, zorder=2)
    ax.axhline(0, color="0.6", linewidth=0.5, zorder=2)
    ax.plot(result.data.t, result.fit.residuals, "-", color="C2", linewidth=0.8, zorder=3)
    ax.set_yscale("symlog", linthresh=tol, linscale=1.0)
    ax.set_xlabel(words["x"])
    ax.set_ylabel(words["y"])
    ax.grid(alpha=0.3, linewidth=0.4)
    return ax


def quadrature_convergence(result: Problem5, ax: Axes | None = None, labels: dict[str, str] | None = None) -> Axes:
    """5(d): ``|S_n - T^|`` against ``n`` on log-log axes, with an ``n^(-1/2)`` guide.

    The guide is drawn ``GUIDE_OFFSET`` times above the data, which follow it exactly.
    ``result`` is a :class:`pendulab.jobs.problems.Problem5`. Returns ``ax``.
    """
    ax = axes(ax)
    words = {"plain": "rule (11), integral (1)", "guide": r"$\propto n^{-1/2}$",
             "sub": r"after $\sin(\theta/2) = \sin(\alpha/2)\sin\varphi$",
             "x": "n (subintervals)", "y": r"$|T_{S_n} - \hat T|$ (s)"} | (labels or {})
    rows = result.rows
    n = np.array([r.n for r in rows], dtype=float)
    err = np.array([r.error for r in rows])
    ax.loglog(n, err, "o-", color="C0", markersize=3, label=words["plain"])
    ax.loglog(n, GUIDE_OFFSET * err[0] * (n / n[0]) ** -0.5, ":", color="0.4", label=words["guide"])
    sub = [(r.n, r.substitution_error) for r in rows if r.substitution_error is not None]
    if sub:
        floor = np.finfo(float).eps * result.t_hat
        ns, es = zip(*sub)
        shown = np.maximum(np.array(es), floor)  # an error of exactly 0 sits on the rounding floor
        ax.loglog(ns, shown, "s-", color="C2", markersize=3, label=words["sub"])
    ax.set_xlabel(words["x"])
    ax.set_ylabel(words["y"])
    ax.grid(True, which="both", alpha=0.3, linewidth=0.4)
    ax.legend(loc="best", frameon=False, fontsize="small")
    return ax


def newton_corrections(result: Problem2, ax: Axes | None = None) -> Axes:
    """2(b): ``|x[k+1] - x[k]|`` against ``k`` (semilog): the exponent doubles each step.

    ``result`` is a :class:`pendulab.jobs.problems.Problem2`. Returns ``ax``.
    """
    ax = axes(ax)
    d = np.abs(np.array(result.run.corrections))
    k = np.arange(len(d))
    keep = d > 0
    ax.semilogy(k[keep], d[keep], "o-", color="C0")
    ax.axhline(result.run.rounding_level, color="C3", linestyle="--", linewidth=0.8, label="rounding level")
    ax.set_xlabel("k")
    ax.set_ylabel(r"$|x_{k+1} - x_k|$ (rad)")
    ax.legend(fontsize="small")
    return ax
