"""The axes a plot function draws on."""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def axes(ax: Axes | None = None) -> Axes:
    """``ax``, or pyplot's current axes (as matplotlib's own functions draw without one)."""
    if ax is not None:
        return ax
    from ..core.extras import require

    return require("matplotlib.pyplot", "pendulab.plots").gca()


def expect(result: object, kind: str, function: str, how: str) -> None:
    """Refuse, with a TypeError naming what ``function`` draws, a result of another kind
    (a period estimate given to ``time_series``), before matplotlib is touched."""
    if type(result).__name__ != kind:
        raise TypeError(f"{function}() draws a {kind} ({how}), not {type(result).__name__}")
