"""The report's figure style and reproducible SVG output; the drawing is :mod:`pendulab.plots`'s.

Every figure is a :class:`matplotlib.figure.Figure` made and saved inside
``matplotlib.rc_context(STYLE)``: the report never touches the global matplotlib state
(backend, ``rcParams``) of the program that builds it.
"""
from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

#: One column of the report (cm -> inch): two figures sit side by side.
WIDTH = 8.4 / 2.54
HEIGHT = 5.6 / 2.54

STYLE: Any = {
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


def draw(paint: Callable, path: Path, width: float = WIDTH, height: float = HEIGHT) -> str:
    """Call ``paint(ax)`` on a new Figure in the report's style, write it as SVG; the file name."""
    import matplotlib
    from matplotlib.figure import Figure

    with matplotlib.rc_context(STYLE):
        fig = Figure(figsize=(width, height), layout="constrained")
        paint(fig.add_subplot())
        fig.savefig(path, format="svg", metadata={"Date": None, "Creator": None})
    return path.name
