"""Many pendulums at once: the period error of each method over a range of amplitudes.

Every pendulum of the sweep runs the same streamed period search as
:func:`pendulab.numerics.crossing.estimate_period` (:func:`pendulab.engine.kernels.first_return`: the
first sign change of ``theta'`` from + to - near ``P = (alpha, 0)``), here for arrays
of amplitudes and lengths on all cores (:mod:`.kernel`; for (3) a lock-step kernel whose
estimates differ from estimate_period's in the last bits, see there); the window of five points around
the sign change gives the linear and inverse cubic estimates of problem 3(d)
(:mod:`.chunk`); the rows form a :class:`SweepResult` (:mod:`.result`), written to CSV or
Parquet.

A sweep can also run on a Dask cluster (``scheduler="tcp://host:8786"``, :mod:`.cluster`):
the pendulums are cut into chunks, each chunk runs the kernel on one thread of a worker, and the
result is the same, bit for bit, as on one machine.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ...core import validate as v
from ...core.cases import G
from ...core.errors import InputError
from ...core.methods import resolve
from ...engine.lanes import BLOCK, LANES, first_returns, first_returns_lanes, first_returns_serial
from ...numerics.period import agm_period
from .chunk import run_chunk
from .result import STATUS, SweepResult

__all__ = ["BLOCK", "CHUNK", "LANES", "STATUS", "SweepResult", "first_returns", "first_returns_lanes",
           "first_returns_serial", "sweep"]

#: Pendulums per chunk (one progress tick, one Dask task): large enough to keep
#: both cores busy, small enough for a smooth progress bar.
CHUNK = 2048


def _check_methods(methods: Any) -> list[tuple[str, int, int]]:
    if isinstance(methods, str):
        methods = [methods]
    out = [(m.name, int(m.code), m.order) for m in map(resolve, methods)]
    if not out:
        raise InputError("method", "[]", "at least one method")
    return out


def _check_steps(steps: Any) -> list[float]:
    steps = [steps] if np.ndim(steps) == 0 else list(np.asarray(steps, dtype=float).ravel())
    if not steps:
        raise InputError("step", "[]", "at least one step > 0")
    return [v.positive("step", h) for h in steps]


#: The most steps of (3) of all pendulums together (minutes of work on a few cores); other
#: methods' steps count by their cost (:func:`pendulab.core.methods.cost_per_step`).
MAX_TOTAL_STEPS = 10**11
#: The most rows (pendulum, step, method) of one sweep: about 400 MB of results.
MAX_ROWS = 10**6


def _check_work(alpha: np.ndarray, length: np.ndarray, g: float, steps: list[float], names: list[str]) -> None:
    """Refuse by arithmetic, before any allocation, a step no pendulum search can take or a sweep too long.

    Each pendulum runs to ``1.5 T + 4h`` (:func:`pendulab.numerics.crossing.default_t_max`): at most
    :data:`pendulab.numerics.simulation.MAX_STEPS` steps of (3) each, :data:`MAX_TOTAL_STEPS` in all, a
    method's steps weighed by its cost (:func:`pendulab.core.methods.cost_per_step`).
    """
    from ...core.methods import cost_per_step
    from ...numerics.crossing import default_t_max
    from ...numerics.simulation import MAX_STEPS

    methods = len(names)
    cost = sum(cost_per_step(m) for m in names)  # of one step of every method
    worst = max(names, key=cost_per_step)
    most = v.steps_for(worst, MAX_STEPS)
    rows = len(alpha) * len(steps) * methods
    if rows > MAX_ROWS:  # each row holds about 400 bytes of result columns
        raise InputError("amplitude", f"{len(alpha)} amplitudes",
                         f"at most {MAX_ROWS // (len(steps) * methods)} amplitudes with {len(steps)} step(s) and "
                         f"{methods} method(s): at most {MAX_ROWS:.0e} pendulums in one sweep")
    periods = np.asarray(agm_period(length, alpha, g), dtype=float)
    longest, total_time = float(periods.max()), float(periods.sum())
    total = 0.0
    for h in steps:
        n = default_t_max(longest, h) / h
        if not n <= most:
            raise v.too_much_work("step", h, f">= {v.bound_text(default_t_max(longest, h) / most, True)} s", most, n,
                                  v.steps_of(worst), hint=f"the longest period ({longest:.4g} s) needs 1.5 T / h steps")
        total += cost * (1.5 * total_time + 4 * h * len(periods)) / h
    if not total <= MAX_TOTAL_STEPS:
        raise v.too_much_work("step", min(steps), "larger", MAX_TOTAL_STEPS, total, "steps of taylor2", in_all=True,
                              hint="other methods' steps weighed by their cost; or fewer amplitudes or methods")


def sweep(
    amplitudes: Any,
    steps: Any,
    methods: Any = ("taylor2",),
    lengths: Any = 1.0,
    g: Any = G,
    progress: Callable[[int], None] | None = None,
    scheduler: Any = None,
    chunk: int = CHUNK,
) -> SweepResult:
    """The period of many pendulums from simulation, for each method and step.

    Parameters
    ----------
    amplitudes : array_like
        ``alpha`` in ``(0, pi)`` (rad), one per pendulum.
    steps : float or sequence of float
        Steps ``h`` > 0.
    methods : str or sequence of str
        Integrators (see :func:`pendulab.core.methods.resolve`).
    lengths : float or array_like
        ``l`` > 0 (m), broadcast against ``amplitudes``.
    g : float
        m/s^2.
    progress : callable, optional
        Called with the number of pendulums just finished (for a progress bar).
    scheduler : str or dask.distributed.Client, optional
        Run the chunks on this Dask cluster (address like ``"tcp://10.0.0.1:8786"``).
    chunk : int
        Pendulums per chunk (per task).

    Returns
    -------
    SweepResult
        ``len(methods) * len(steps) * n`` rows, grouped by method then step.

    Notes
    -----
    Each pendulum is simulated to ``t_max = 1.5 T + 4h``
    (:func:`pendulab.numerics.crossing.default_t_max`); a pendulum that leaves the oscillation or
    does not return gets a status other than ``"found"`` and NaN estimates.
    """
    alpha = np.atleast_1d(np.asarray(v.amplitudes("amplitude", amplitudes), dtype=float)).ravel()
    if len(alpha) == 0:
        raise InputError("amplitude", "[]", "at least one amplitude in (0, pi)")
    if np.any(alpha == 0):
        raise InputError("amplitude", 0, "> 0 for a period from a simulation (at rest nothing moves)")
    length = np.asarray(lengths, dtype=float)
    bad = ~(np.isfinite(length) & (length > 0))
    if bad.any():
        v.positive("length", length[bad].flat[0])
    try:
        # Copies: a broadcast view handed to the kernels makes numpy warn (its writeable flag).
        alpha, length = (np.array(a, dtype=float) for a in np.broadcast_arrays(alpha, length))
    except ValueError:
        raise InputError("lengths", f"shape {length.shape}", f"a number or an array of shape {alpha.shape}") from None
    g = v.positive("g", g)
    hs = _check_steps(steps)
    ms = _check_methods(methods)
    chunk = v.integer("chunk", chunk, 1)
    _check_work(alpha, length, g, hs, [name for name, _, _ in ms])
    bounds = [(i, min(i + chunk, len(alpha))) for i in range(0, len(alpha), chunk)]
    jobs = [(name, code, order, h, lo, hi) for name, code, order in ms for h in hs for lo, hi in bounds]

    if scheduler is None:
        parts = []
        for _, code, order, h, lo, hi in jobs:
            parts.append(run_chunk(code, order, alpha[lo:hi], length[lo:hi], g, h))
            if progress is not None:
                progress(hi - lo)
    else:
        from .cluster import run_on_cluster

        parts = run_on_cluster(scheduler, jobs, alpha, length, g, progress)

    cols: dict[str, list] = {k: [] for k in ("method", "order", "step", "length", "amplitude")}
    for (name, _, order, h, lo, hi) in jobs:
        cols["method"].append(np.full(hi - lo, name, dtype=object))
        cols["order"].append(np.full(hi - lo, order, dtype=np.int64))
        cols["step"].append(np.full(hi - lo, h))
        cols["length"].append(length[lo:hi])
        cols["amplitude"].append(alpha[lo:hi])
    columns = {k: np.concatenate(c) for k, c in cols.items()}
    columns["method"] = columns["method"].astype(str)
    for key in ("period", "status", "steps", "linear", "cubic", "cubic_error_estimate"):
        columns[key] = np.concatenate([p[key] for p in parts])
    columns["status"] = np.asarray(STATUS)[columns["status"]]
    columns["linear_signed_error"] = columns["linear"] - columns["period"]
    columns["cubic_signed_error"] = columns["cubic"] - columns["period"]
    return SweepResult(columns, g)
