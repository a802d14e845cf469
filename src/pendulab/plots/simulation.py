"""Figures 1 and 2 of the coursework: a simulation's time series and phase portrait."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..numerics.simulation import kept_steps, stride_for
from ._axes import axes, expect

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..numerics.simulation import Trajectory


def time_series(trajectory: Trajectory, ax: Axes | None = None, title: bool = True,
                labels: dict[str, str] | None = None, **style: Any) -> Axes:
    """Figure 1: the points ``(t_j, z1_j)`` of a simulation. Returns the axes drawn on.

    ``labels`` replaces the axis labels (keys ``x``, ``y``)."""
    expect(trajectory, "Trajectory", "time_series", "pendulab.simulate(...)")
    ax = axes(ax)
    words = {"x": "t (s)", "y": r"$z_{1,j} \approx \theta(t_j)$ (rad)"} | (labels or {})
    kw: dict[str, Any] = {"marker": "o", "markersize": 3, "linestyle": "none", "color": "C0"} | style
    ax.plot(trajectory.t, trajectory.theta, **kw)
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.set_xlabel(words["x"])
    ax.set_ylabel(words["y"])
    if title:
        ax.set_title(
            rf"$l = {trajectory.length:.10g}$, $\alpha = {trajectory.amplitude:.6g}$, $h = {trajectory.step:g}$",
            fontsize="medium",
        )
    return ax


def phase_portrait(trajectory: Trajectory, ax: Axes | None = None, max_arrows: int = 400,
                   arrow_width: float = 0.006, labels: dict[str, str] | None = None) -> Axes:
    """Figure 2: phase points ``Z_j = (z1_j, z2_j)`` joined by arrows, ``P = (alpha, 0)`` circled.

    Long trajectories are thinned to at most ``max_arrows`` arrows, the first and last point kept. ``arrow_width`` is the
    shaft's width as a fraction of the axes' width; the heads scale with it, so a figure
    printed a few centimetres wide keeps visible heads. ``labels`` replaces the axis
    labels and the legend's (keys ``x``, ``y``, ``P``). Returns the axes drawn on.
    """
    expect(trajectory, "Trajectory", "phase_portrait", "pendulab.simulate(...)")
    ax = axes(ax)
    words = {"x": r"$z_1 \approx \theta$ (rad)", "y": r"$z_2 \approx \theta'$ (rad/s)",
             "P": r"$P = (\alpha, 0)$"} | (labels or {})
    z1, z2 = trajectory.theta, trajectory.omega
    n = len(z1) - 1
    keep = kept_steps(n, stride_for(n, max_arrows + 1))
    x, y = z1[keep], z2[keep]
    ax.quiver(
        x[:-1], y[:-1], np.diff(x), np.diff(y),
        angles="xy", scale_units="xy", scale=1, width=arrow_width, headwidth=3.5, headlength=4.5,
        headaxislength=4, color="C0",
    )
    ax.plot(x, y, "o", markersize=2, color="C0")
    ax.plot([trajectory.amplitude], [0.0], "o", markersize=12, markerfacecolor="none",
            markeredgecolor="C3", markeredgewidth=1.3, label=words["P"])
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.axvline(0, color="0.7", linewidth=0.6)
    ax.set_xlabel(words["x"])
    ax.set_ylabel(words["y"])
    ax.legend(loc="upper left", fontsize="small")
    return ax
