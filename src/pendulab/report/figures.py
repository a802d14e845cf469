"""The report's figures: matplotlib drawings of results already computed.

Each function takes an ``ax`` and the result objects, draws, and returns the artists;
:func:`save_svg` writes a figure reproducibly (no date, fixed element ids), so the same
inputs give the same PDF byte for byte.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

#: One column of the report (cm -> inch): two figures sit side by side.
WIDTH = 8.4 / 2.54
HEIGHT = 5.6 / 2.54


def new_figure(width: float = WIDTH, height: float = HEIGHT):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(
        {
            "font.size": 8,
            "axes.titlesize": 8,
            "axes.labelsize": 8,
            "legend.fontsize": 7,
            "xtick.labelsize": 7,
            "ytick.labelsize": 7,
            "svg.hashsalt": "pendulab",  # reproducible ids in the SVG
            "svg.fonttype": "path",
            "lines.linewidth": 1.0,
            "font.family": "serif",
            "font.serif": ["DejaVu Serif"],
            "mathtext.fontset": "cm",
            "axes.formatter.use_mathtext": True,
        }
    )
    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    return fig, ax


def save_svg(fig, path: Path) -> str:
    """Write ``fig`` as SVG without a date, close it, return the file name."""
    import matplotlib.pyplot as plt

    fig.savefig(path, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    return path.name


def fit_plot(ax, t, y, t_fine, phi, labels):
    """Problem 4(d)(i): the data ``Y_j`` and the least-squares function ``phi~``."""
    data = ax.plot(t[::5], y[::5], "o", ms=1.6, color="C0", label=labels[2])
    curve = ax.plot(t_fine, phi, "-", color="C3", lw=0.8, label=labels[3])
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.legend(loc="best", frameon=False)
    ax.grid(alpha=0.3, lw=0.4)
    return data, curve


def residual_plot(ax, t, residual, labels):
    """Problem 4(d)(ii): the deviation ``phi~(t_j) - z1_j`` at the data points."""
    line = ax.plot(t, residual, "-", color="C2", lw=0.8)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 3))
    ax.grid(alpha=0.3, lw=0.4)
    return line


def convergence(ax, series, labels):
    """Log-log error against ``n`` (or ``h``) for each ``(x, error, label, marker)``."""
    lines = []
    for x, err, label, marker in series:
        x = np.asarray(x, dtype=float)
        err = np.asarray(err, dtype=float)
        ok = err > 0
        lines += ax.loglog(x[ok], err[ok], marker + "-", ms=3, label=label)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.grid(alpha=0.3, lw=0.4, which="both")
    ax.legend(loc="best", frameon=False)
    return lines
