"""Figures 1 and 2 of the coursework, and the period error against the step."""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np


def time_series(ax, trajectory, **style):
    """Figure 1: the points ``(t_j, z1_j)`` of a simulation. Returns the line drawn."""
    kw = {"marker": "o", "markersize": 3, "linestyle": "none", "color": "C0"} | style
    (line,) = ax.plot(trajectory.t, trajectory.theta, **kw)
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(r"$z_{1,j} \approx \theta(t_j)$ (rad)")
    ax.set_title(
        rf"$l = {trajectory.length:.10g}$, $\alpha = {trajectory.amplitude:.6g}$, $h = {trajectory.step:g}$",
        fontsize="medium",
    )
    return line


def phase_portrait(ax, trajectory, max_arrows: int = 400):
    """Figure 2: phase points ``Z_j = (z1_j, z2_j)`` joined by arrows, ``P = (alpha, 0)`` circled.

    Long trajectories are thinned to about ``max_arrows`` arrows. Returns the quiver.
    """
    z1, z2 = trajectory.theta, trajectory.omega
    stride = max(1, len(z1) // max_arrows)
    x, y = z1[::stride], z2[::stride]
    q = ax.quiver(
        x[:-1], y[:-1], np.diff(x), np.diff(y),
        angles="xy", scale_units="xy", scale=1, width=0.003, color="C0",
    )
    ax.plot(x, y, "o", markersize=2.5, color="C0")
    ax.plot([trajectory.amplitude], [0.0], "o", markersize=14, markerfacecolor="none",
            markeredgecolor="C3", markeredgewidth=1.5, label=r"$P = (\alpha, 0)$")
    ax.axhline(0, color="0.7", linewidth=0.6)
    ax.axvline(0, color="0.7", linewidth=0.6)
    ax.set_xlabel(r"$z_1 \approx \theta$ (rad)")
    ax.set_ylabel(r"$z_2 \approx \theta'$ (rad/s)")
    ax.legend(loc="upper left", fontsize="small")
    return q


def period_error(ax, steps: Sequence[float], errors: dict[str, Sequence[float]]):
    """Period error against the step on log-log axes, one line per estimator."""
    lines = []
    for label, err in errors.items():
        (line,) = ax.loglog(steps, err, "o-", label=label)
        lines.append(line)
    ax.set_xlabel("step h (s)")
    ax.set_ylabel("|estimate - T| (s)")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize="small")
    return lines
