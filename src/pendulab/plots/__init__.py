"""matplotlib renderings of computed results.

Each function takes an ``ax`` (``None``: a new :class:`matplotlib.figure.Figure` of its
own), draws results already computed by the library, and returns the ``ax``. Nothing
here computes a number or changes matplotlib's global state (no backend switch, no
``rcParams`` edits: a caller who wants a style wraps the call in ``matplotlib.rc_context``).
"""
from __future__ import annotations


def axes(ax=None):
    """``ax``, or the axes of a new Figure (not registered with pyplot: no global state)."""
    if ax is not None:
        return ax
    from matplotlib.figure import Figure

    return Figure(layout="constrained").add_subplot()
