"""Figures beyond the coursework: approximation errors and sweep errors."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._axes import axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..jobs.sweep import SweepResult
    from ..numerics.approximations import ApproximationErrors

# Below this a relative error is rounding of double precision, not the formula: drawn at the floor.
_FLOOR = 1e-17


def approximation_errors(table: ApproximationErrors, ax: Axes | None = None) -> Axes:
    """``|relative error|`` of each period formula against the amplitude (degrees), log scale.

    ``table`` is a :class:`pendulab.numerics.approximations.ApproximationErrors`. Returns ``ax``.
    """
    ax = axes(ax)
    deg = np.degrees(table.amplitudes)
    lines = []
    rounding = 4 * np.finfo(float).eps  # below: rounding of the comparison itself, not drawn
    for f in table.formulas:
        err = np.abs(table.errors[f.name])
        err = np.where(err < rounding, np.nan, err)
        (line,) = ax.semilogy(deg, err, label=f"{f.name}: {f.label}")
        lines.append(line)
    ax.axhline(rounding, color="0.6", linestyle=":", linewidth=0.8)
    ax.set_xlim(0, 180)
    ax.set_ylim(1e-16, 10)
    ax.set_xlabel(r"amplitude $\alpha$ (degrees)")
    ax.set_ylabel(r"$|T_{\rm approx}/T - 1|$")
    ax.grid(True, which="major", linewidth=0.3)
    ax.legend(fontsize="x-small", loc="lower right")
    return ax


def sweep_errors(result: SweepResult, ax: Axes | None = None) -> Axes:
    """``|cubic period error|`` against the amplitude, one line per (method, step).

    ``result`` is a :class:`pendulab.jobs.sweep.SweepResult`. Pendulums whose simulation did
    not return (status other than ``found``) are left out. Returns ``ax``.
    """
    ax = axes(ax)
    lines = []
    for row in result.summary():
        r = result.select(row["method"], row["step"])
        ok = r["status"] == "found"
        err = np.maximum(np.abs(r["cubic_signed_error"][ok]), _FLOOR)
        (line,) = ax.semilogy(np.degrees(r["amplitude"][ok]), err, label=f"{row['method']}, h = {row['step']:g}")
        lines.append(line)
    ax.set_xlabel(r"amplitude $\alpha$ (degrees)")
    ax.set_ylabel(r"$|T_{\rm cubic} - T|$ (s)")
    ax.grid(True, which="major", linewidth=0.3)
    ax.legend(fontsize="x-small")
    return ax
