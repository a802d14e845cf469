"""The report's figure style and reproducible SVG output; the drawing is ``programs/plots.py``'s.

Every figure is a :class:`matplotlib.figure.Figure` made and saved inside
``matplotlib.rc_context(STYLE)``: the report never touches the global matplotlib state
(backend, ``rcParams``) of the program that builds it.

Drawn for speed as well as looks (``benchmarks/bench_report.py``): tick labels are plain
text, powers of ten written with Unicode superscripts (matplotlib's mathtext parses each
label with pyparsing, most of a figure's time), and the axes sit in fixed margins instead
of a layout engine (which draws the figure once more to measure it).
"""
from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

#: One column of the report (cm -> inch): two figures sit side by side.
WIDTH = 8.4 / 2.54
HEIGHT = 5.6 / 2.54
#: The margins around the axes (cm): room for the tick labels and the axis labels.
MARGINS = {"left": 1.5, "right": 0.25, "bottom": 1.05, "top": 0.25}

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
    "axes.formatter.use_mathtext": False,
    "axes.unicode_minus": True,
}

#: The figures' formulas as plain Unicode text, the same in every language, under the
#: names of ``programs/plots.py``'s ``WORDS``: a label in mathtext would load and run its
#: parser (a fifth of the figures' time). The words of each language come from the catalogue.
LABELS = {
    "t": "t (s)", "z1j": "z₁,ⱼ ≈ θ(tⱼ) (rad)", "z1": "z₁ ≈ θ (rad)", "z2": "z₂ ≈ θ′ (rad/s)",
    "P": "P = (α, 0)", "fit": "φ̃", "fit_y": "z₁,ⱼ, φ̃(t) (rad)", "dev": "z₁,ⱼ − φ̃(tⱼ) (rad)",
    "n": "n", "guide": "∝ 1/√n",
}


def words(catalogue: dict[str, Any]) -> dict[str, str]:
    """The figures' labels in the catalogue's language: :data:`LABELS` and its words."""
    return LABELS | {"data": catalogue["p4.fig.data"], "rule": catalogue["p5.fig.plain"],
                     "error": catalogue["p5.fig.error"]}


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def power_of_ten(x: float, pos: Any = None) -> str:
    """A log or symlog axis's tick label: ``10⁻⁵`` (``−10⁻⁵``) at a power of ten, ``0`` at
    zero, nothing between them: the labels of matplotlib's own formatter, as plain text."""
    import math

    if x == 0:
        return "0"
    if not math.isfinite(x):
        return ""
    e = math.log10(abs(x))
    if abs(e - round(e)) >= 1e-9:
        return ""
    return ("−" if x < 0 else "") + "10" + str(round(e)).translate(_SUPERSCRIPT)


def draw(paint: Callable, path: Path, width: float = WIDTH, height: float = HEIGHT) -> str:
    """Call ``paint(ax)`` on a new Figure in the report's style, write it as SVG; the file name."""
    import matplotlib
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter

    inch = 2.54
    with matplotlib.rc_context(STYLE):
        fig = Figure(figsize=(width, height))
        fig.subplots_adjust(left=MARGINS["left"] / inch / width, right=1 - MARGINS["right"] / inch / width,
                            bottom=MARGINS["bottom"] / inch / height, top=1 - MARGINS["top"] / inch / height)
        ax = fig.add_subplot()
        paint(ax)
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() in ("log", "symlog"):
                axis.set_major_formatter(FuncFormatter(power_of_ten))
        fig.savefig(path, format="svg", metadata={"Date": None, "Creator": None})
    return path.name
