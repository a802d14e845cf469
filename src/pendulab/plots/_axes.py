"""The axes a plot function draws on."""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def axes(ax: Axes | None = None) -> Axes:
    """``ax``, or pyplot's current axes (as matplotlib's own functions draw without one)."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.gca()
