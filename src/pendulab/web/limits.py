"""What one request of the explorer may cost: work weighted by the method, points, bytes.

Work is counted in steps of the coursework's method (3) (``taylor2``): a step of another
method counts as :func:`pendulab.core.methods.cost_per_step` of them (measured), so
``taylor:30``, about forty times dearer a step, gets about a fortieth of the steps. The
trajectory and the period search of one request are each within :data:`MAX_WORK`. Every check runs before any work starts and
raises :class:`pendulab.core.errors.InputError` naming the field to change.
"""
from __future__ import annotations

import os

from ..core import inputs
from ..core import validate as v
from ..core.methods import Method

#: The work one request may run, in steps of (3) (about 1 s of one core for taylor2).
MAX_WORK = 10_000_000
#: At most this many points in an ``/api/simulate`` answer (its size: :data:`MAX_ANSWER_BYTES`).
MAX_POINTS = 20_000
#: An ``/api/simulate`` answer is at most this many bytes: about 10 numbers per point (theta,
#: omega, t, the energy, the exact curve's column ends and turns, the error) plus the phase
#: portrait's and animation's fixed counts, each number at most 24 characters and a comma.
MAX_ANSWER_BYTES = 7_000_000
#: At most this many rows in a CSV (streamed block by block: the server holds one block).
MAX_CSV_ROWS = 1_000_000
#: Points returned for plotting when the request does not say.
DEFAULT_PLOT_POINTS = 2_000
#: At most this many steps in one convergence sweep.
MAX_SWEEP = 40
#: Simulations run at once: one per core (the kernels release the GIL), at least two.
SIMULATION_SLOTS = max(2, os.cpu_count() or 2)

#: An ordinary view (the defaults): which of step and t_max is unusual is judged against them.
_TYPICAL = {"step": 1e-3, "t_max": 20.0}

def max_steps(method: Method) -> int:
    """The most steps of ``method`` one request may run."""
    return v.steps_for(method, MAX_WORK)


def check_run(span: float, step: float, method: Method, step_text: str | None = None,
              t_max_text: str | None = None) -> None:
    """Refuse a run of ``span / step`` steps of ``method`` beyond :func:`max_steps`.

    Blames the one of ``step`` and ``t_max`` further (in decades) from an ordinary view;
    the values are shown as typed when given.
    """
    most = max_steps(method)
    n = span / step
    if n <= most + 0.5:  # N = Round(t_max / h), (6)
        return
    what = f"steps of {method.name}"
    if t_max_text is not None and v.furthest(("step", step, _TYPICAL["step"]), ("t_max", span, _TYPICAL["t_max"])) == "t_max":
        raise v.too_much_work("t_max", inputs.shown(t_max_text), f"<= {v.bound_text(most * step, False, 4)} s with h = {step:g} s",
                              most, n, what, hint="or a larger step")
    shown = inputs.shown(step_text) if step_text is not None else f"{step:g}"
    raise v.too_much_work("step", shown, f">= {v.bound_text(span / most, True)} s for {span:.4g} s", most, n, what,
                          hint="or a shorter t_max")


def search_too_long(span: float, step: float, period: float, method: Method, lang: str = "en") -> str | None:
    """Why the period search over ``span`` s (``1.5 T + 4h``) is not run, or None when it fits
    (``web.reason.too-long``, in ``lang``)."""
    from .words import number, say

    most = max_steps(method)
    if span / step <= most:
        return None
    hint = say("reason.use-step", lang, step=number(span / most, ".3g", lang)) if span / most < period / 20 else ""
    return say("reason.too-long", lang, steps=number(span / step, ".3g", lang), h=number(step, "g", lang),
               span=number(span, ".4g", lang), most=number(most, ".3g", lang), method=method.name, hint=hint)


def check_sweep(spans: list[float], steps: list[float], method: Method) -> None:
    """Refuse a convergence sweep whose period searches run more than :data:`MAX_WORK` in all."""
    total = sum(s / h for s, h in zip(spans, steps))
    most = max_steps(method)
    if total > most:
        raise v.too_much_work("steps", f"{min(steps):g} (smallest)", "larger steps", most, total,
                              f"steps of {method.name}", in_all=True)
