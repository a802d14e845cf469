"""matplotlib renderings of computed results: ``f(result, ax=None) -> Axes``.

Each function draws a result already computed by the library on ``ax`` and returns it;
without ``ax`` it draws on pyplot's current axes (a new figure in a notebook cell), as
matplotlib's own functions do. Nothing here computes a number or changes matplotlib's
settings (no backend switch, no ``rcParams`` edits: a caller who wants a style wraps the
call in ``matplotlib.rc_context``). The CLI and the report pass the axes of a
:class:`matplotlib.figure.Figure` of their own, so they never touch pyplot.

The functions are importable from here: ``from pendulab.plots import time_series``.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from ..core.extras import lazy

if TYPE_CHECKING:
    from .beyond import approximation_errors, sweep_errors
    from .problems import fit, fit_residuals, newton_corrections, quadrature_convergence
    from .simulation import phase_portrait, time_series

__all__ = [
    "approximation_errors",
    "fit",
    "fit_residuals",
    "newton_corrections",
    "phase_portrait",
    "quadrature_convergence",
    "sweep_errors",
    "time_series",
]

# name -> submodule: loaded on first use, so ``import pendulab.plots`` imports nothing heavy.
_WHERE = {
    "approximation_errors": "beyond",
    "sweep_errors": "beyond",
    "fit": "problems",
    "fit_residuals": "problems",
    "newton_corrections": "problems",
    "quadrature_convergence": "problems",
    "phase_portrait": "simulation",
    "time_series": "simulation",
}

__getattr__, __dir__ = lazy(__name__, _WHERE, __all__)
