"""Figures beyond the coursework: approximation errors, sweep errors, global error of a simulation."""
from __future__ import annotations

import numpy as np

# Below this a relative error is rounding of double precision, not the formula: drawn at the floor.
_FLOOR = 1e-17


def approximation_errors(ax, table):
    """``|relative error|`` of each period formula against the amplitude (degrees), log scale.

    ``table`` is a :class:`pendulab.approximations.ApproximationErrors`. Returns the lines.
    """
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
    return lines


def sweep_errors(ax, result):
    """``|cubic period error|`` against the amplitude, one line per (method, step).

    ``result`` is a :class:`pendulab.sweep.SweepResult`. Pendulums whose simulation did
    not return (status other than ``found``) are left out. Returns the lines.
    """
    lines = []
    for row in result.summary():
        r = result.select(row["method"], row["step"])
        ok = r["status"] == "found"
        err = np.maximum(np.abs(r["cubic_error"][ok]), _FLOOR)
        (line,) = ax.semilogy(np.degrees(r["amplitude"][ok]), err, label=f"{row['method']}, h = {row['step']:g}")
        lines.append(line)
    ax.set_xlabel(r"amplitude $\alpha$ (degrees)")
    ax.set_ylabel(r"$|T_{\rm cubic} - T|$ (s)")
    ax.grid(True, which="major", linewidth=0.3)
    ax.legend(fontsize="x-small")
    return lines


def global_error(ax, errors):
    """``|theta error|`` and ``|energy drift|`` of simulations against time, one pair per entry.

    ``errors`` is a sequence of :class:`pendulab.motion.GlobalError`. Returns the lines.
    """
    lines = []
    for i, e in enumerate(errors):
        (a,) = ax.semilogy(e.t, np.maximum(np.abs(e.theta_error), _FLOOR), color=f"C{i}",
                           label=rf"{e.method}, $h = {e.step:g}$: $|z_1 - \theta|$")
        (b,) = ax.semilogy(e.t, np.maximum(np.abs(e.energy_drift), _FLOOR), color=f"C{i}", linestyle="--",
                           label=rf"{e.method}: $|E - E_0|$")
        lines += [a, b]
    ax.set_xlabel("t (s)")
    ax.set_ylabel("error")
    ax.grid(True, which="major", linewidth=0.3)
    ax.legend(fontsize="x-small")
    return lines
