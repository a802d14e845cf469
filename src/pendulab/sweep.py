"""Many pendulums at once: the period error of each method over a range of amplitudes.

Every pendulum of the sweep runs the same streamed period search as
:func:`pendulab.crossing.estimate_period` (:func:`pendulab._kernels.first_return`: the
first sign change of ``theta'`` from + to - near ``P = (alpha, 0)``), here for arrays
of amplitudes and lengths in one parallel numba kernel. The window of five points
around the sign change gives the linear and the inverse cubic estimates of problem 3(d),
vectorised over the pendulums (same formulas as :mod:`pendulab.interpolation`).

A sweep can also run on a Dask cluster (``scheduler="tcp://host:8786"``): the pendulums
are cut into chunks, each chunk runs the serial kernel on a worker, and the result is the
same, bit for bit, as on one machine.
"""
from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numba import get_num_threads, njit

from . import _validate as v
from ._atomic import atomic_path, check_writable
from ._kernels import first_return
from .cases import G
from .errors import InputError
from .methods import Status, resolve
from .period import _check_amplitudes, agm_period

#: Status of each pendulum, as :func:`pendulab._kernels.first_return` reports it.
STATUS = tuple(s.name.lower() for s in Status)
#: Pendulums per chunk (one progress tick, one Dask task): large enough to keep
#: both cores busy, small enough for a smooth progress bar.
CHUNK = 2048
#: Seconds to wait for a Dask scheduler before giving up with one clear error.
CONNECT_TIMEOUT = 10



@njit(cache=True, nogil=True)
def first_returns_serial(method, order, alphas, cs, h, n_steps):
    """``first_return`` for each pendulum ``(alphas[i], cs[i])`` with ``n_steps[i]`` steps, in turn.

    Releases the GIL: :func:`first_returns` runs it on several threads at once, and a
    Dask worker runs it for one chunk.
    """
    m = len(alphas)
    status = np.empty(m, np.int64)
    j = np.empty(m, np.int64)
    z1w = np.empty((m, 5))
    z2w = np.empty((m, 5))
    for i in range(m):
        s, ji, w1, w2 = first_return(method, order, alphas[i], cs[i], h, n_steps[i])
        status[i] = s
        j[i] = ji
        z1w[i, :] = w1
        z2w[i, :] = w2
    return status, j, z1w, z2w


#: Pendulums per task of :func:`first_returns`: small enough that the threads finish
#: together (the periods differ by 5x between 1 and 179 degrees), large enough that a task
#: outlasts its scheduling.
BLOCK = 16
_POOL: list[ThreadPoolExecutor] = []


def first_returns(method, order, alphas, cs, h, n_steps, threads: int | None = None):
    """:func:`first_returns_serial` on ``threads`` threads (default: numba's thread count).

    Blocks of :data:`BLOCK` pendulums go to the threads as they become free. The serial
    kernel releases the GIL, so the threads run on separate cores; each pendulum gives
    the same result, bit for bit, as on one thread. (A ``parallel=True`` build of the
    same loop ran each thread about 1.5x slower than the serial kernel.)
    """
    threads = get_num_threads() if threads is None else threads
    m = len(alphas)
    if threads <= 1 or m <= BLOCK:
        return first_returns_serial(method, order, alphas, cs, h, n_steps)
    if not _POOL or _POOL[0]._max_workers != threads:
        _POOL[:] = [ThreadPoolExecutor(threads, thread_name_prefix="pendulab-sweep")]
    starts = range(0, m, BLOCK)
    parts = list(_POOL[0].map(
        lambda lo: first_returns_serial(method, order, alphas[lo:lo + BLOCK], cs[lo:lo + BLOCK], h,
                                        n_steps[lo:lo + BLOCK]), starts))
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(4))


def inverse_cubic_rows(z2: np.ndarray, t: np.ndarray, fifth_z2: np.ndarray, fifth_t: np.ndarray):
    """:func:`pendulab.interpolation.inverse_cubic`'s ``p(0)`` and error estimate, row by row.

    ``z2, t`` have shape ``(m, 4)``. Newton's divided differences (Burden-Faires,
    Algorithm 3.2) computed by the same in-place table, vectorised over the rows.
    """
    x5 = np.concatenate([z2, fifth_z2[:, None]], axis=1)
    # Scaled by a power of two per row, as inverse_cubic does: the same results bit for
    # bit, but no overflow of t[z2_0..z2_4] ~ h/z2^4 at tiny amplitudes.
    x5 = np.ldexp(x5, -np.frexp(np.max(np.abs(x5), axis=1))[1][:, None])
    z2 = x5[:, :4]
    coef = np.concatenate([t, fifth_t[:, None]], axis=1).astype(float)
    for k in range(1, 5):
        coef[:, k:] = (coef[:, k:] - coef[:, k - 1 : -1]) / (x5[:, k:] - x5[:, : 5 - k])
    # The first four coefficients are those of the cubic on the first four nodes.
    p = coef[:, 3].copy()
    for k in (2, 1, 0):
        p = p * (0.0 - z2[:, k]) + coef[:, k]
    error = coef[:, 4] * np.prod(0.0 - z2, axis=1)
    return p, error


@dataclass(frozen=True)
class SweepResult:
    """One row per (method, step, pendulum): the simulated period and its errors.

    Columns (all arrays of the same length): ``method`` (str), ``order``, ``step``,
    ``length``, ``amplitude`` (rad), ``exact`` (AGM period (8)), ``status`` (one of
    :data:`STATUS`), ``steps`` (steps taken), ``linear``, ``cubic`` (period estimates; NaN
    unless ``status == "found"``), ``linear_error``, ``cubic_error`` (``estimate - exact``),
    ``cubic_error_estimate`` (the interpolation error estimate of problem 3(d)).
    """

    columns: dict[str, np.ndarray]

    def __len__(self) -> int:
        return len(self.columns["amplitude"])

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def select(self, method: str, step: float) -> dict[str, np.ndarray]:
        """The rows of one (method, step) pair."""
        rows = (self.columns["method"] == method) & (self.columns["step"] == step)
        return {k: c[rows] for k, c in self.columns.items()}

    def summary(self) -> list[dict[str, Any]]:
        """Per (method, step): pendulums found, largest ``|cubic error|`` and relative error."""
        out = []
        keys = dict.fromkeys(zip(self.columns["method"].tolist(), self.columns["step"].tolist()))
        for method, step in keys:
            r = self.select(method, step)
            ok = r["status"] == "found"
            rel = np.abs(r["cubic_error"][ok] / r["exact"][ok])
            out.append(
                {
                    "method": method,
                    "order": int(r["order"][0]),
                    "step": step,
                    "pendulums": int(len(ok)),
                    "found": int(ok.sum()),
                    "max_abs_cubic_error": float(np.max(np.abs(r["cubic_error"][ok]))) if ok.any() else math.nan,
                    "max_rel_cubic_error": float(rel.max()) if ok.any() else math.nan,
                    "pendulum_steps": int(r["steps"].sum()),
                }
            )
        return out

    def write(self, path: str | os.PathLike) -> Path:
        """Write the table atomically as CSV (``.csv``) or Parquet (``.parquet``)."""
        import pyarrow as pa

        p = check_writable("output", path)
        suffix = p.suffix.lower()
        if suffix not in (".csv", ".parquet"):
            raise InputError("output", str(path), "a file name ending in .csv or .parquet")
        table = pa.table(dict(self.columns.items()))
        with atomic_path(p) as tmp:
            if suffix == ".csv":
                import pyarrow.csv as pacsv

                pacsv.write_csv(table, tmp)
            else:
                import pyarrow.parquet as pq

                pq.write_table(table, tmp)
        return p


def _run_chunk(code: int, order: int, alphas: np.ndarray, lengths: np.ndarray, g: float, h: float,
               parallel: bool = True) -> dict[str, np.ndarray]:
    """The period search for one chunk of pendulums with one method and step (pure)."""
    from .crossing import default_t_max
    from .taylor import step_count

    exact = np.asarray(agm_period(lengths, alphas, g), dtype=float)
    n_steps = np.array([step_count(0.0, default_t_max(float(T), h), h) for T in exact], dtype=np.int64)
    cs = -g / lengths
    if parallel:
        status, j, _z1w, z2w = first_returns(code, order, alphas, cs, h, n_steps)
    else:
        status, j, _z1w, z2w = first_returns_serial(code, order, alphas, cs, h, n_steps)
    # As estimate_period: where theta' changes by less than the smallest normal double per
    # step, its sign change is lost to underflow; no return is found.
    underflow = alphas * (g / lengths) * h < np.finfo(float).tiny
    status = np.where(underflow, int(Status.NO_RETURN), status)
    found = status == Status.FOUND
    t = (j[:, None] - 2 + np.arange(5)) * h  # t_k = k h (6): nodes j-2 .. j+2
    with np.errstate(invalid="ignore", divide="ignore"):
        linear = t[:, 2] + h * z2w[:, 2] / (z2w[:, 2] - z2w[:, 3])
        cubic, err_est = inverse_cubic_rows(z2w[:, 1:5], t[:, 1:5], z2w[:, 0], t[:, 0])
    nan = np.full(len(alphas), np.nan)
    linear = np.where(found, linear, nan)
    cubic = np.where(found, cubic, nan)
    err_est = np.where(found, err_est, nan)
    # Steps taken: j + 2 when found (one past the sign change), else the index reported.
    steps = np.where(found, j + 2, np.where(status == Status.LEFT_OSCILLATION, j + 1, j))
    return {
        "exact": exact,
        "status": status,
        "steps": steps,
        "linear": linear,
        "cubic": cubic,
        "cubic_error_estimate": err_est,
    }


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


#: The most steps of all pendulums together (minutes of work on a few cores).
MAX_TOTAL_STEPS = 10**11
#: The most rows (pendulum, step, method) of one sweep: about 400 MB of results.
MAX_ROWS = 10**6


def _check_work(alpha: np.ndarray, length: np.ndarray, g: float, steps: list[float], methods: int) -> None:
    """Refuse by arithmetic, before any allocation, a step no pendulum search can take or a sweep too long.

    Each pendulum runs to ``1.5 T + 4h`` (:func:`pendulab.crossing.default_t_max`): at most
    :data:`pendulab.taylor.MAX_STEPS` steps each, :data:`MAX_TOTAL_STEPS` in all.
    """
    from .crossing import default_t_max
    from .taylor import MAX_STEPS

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
        if not n <= MAX_STEPS:
            raise InputError("step", h, f">= {default_t_max(longest, h) / MAX_STEPS:.3g} s: the longest period "
                             f"({longest:.4g} s) needs 1.5 T / h steps, at most {MAX_STEPS:.0e}")
        total += methods * (1.5 * total_time + 4 * h * len(periods)) / h
    if not total <= MAX_TOTAL_STEPS:
        raise InputError("step", min(steps), f"such that the sweep runs at most {MAX_TOTAL_STEPS:.0e} steps in all "
                         f"(these need {total:.3g}); use larger steps, or fewer amplitudes or methods")


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
        Integrators (see :func:`pendulab.methods.resolve`).
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
    (:func:`pendulab.crossing.default_t_max`); a pendulum that leaves the oscillation or
    does not return gets a status other than ``"found"`` and NaN estimates.
    """
    alpha = np.atleast_1d(np.asarray(_check_amplitudes(amplitudes), dtype=float)).ravel()
    if len(alpha) == 0:
        raise InputError("amplitude", "[]", "at least one amplitude in (0, pi)")
    if np.any(alpha == 0):
        raise InputError("amplitude", 0, "> 0 for a period from a simulation (at rest nothing moves)")
    length = np.asarray(lengths, dtype=float)
    bad = ~(np.isfinite(length) & (length > 0))
    if bad.any():
        v.positive("length", length[bad].flat[0])
    try:
        alpha, length = (np.ascontiguousarray(a, dtype=float) for a in np.broadcast_arrays(alpha, length))
    except ValueError:
        raise InputError("lengths", f"shape {length.shape}", f"a number or an array of shape {alpha.shape}") from None
    g = v.positive("g", g)
    hs = _check_steps(steps)
    ms = _check_methods(methods)
    chunk = v.integer("chunk", chunk, 1)
    _check_work(alpha, length, g, hs, len(ms))
    bounds = [(i, min(i + chunk, len(alpha))) for i in range(0, len(alpha), chunk)]
    jobs = [(name, code, order, h, lo, hi) for name, code, order in ms for h in hs for lo, hi in bounds]

    if scheduler is None:
        parts = []
        for _name, code, order, h, lo, hi in jobs:
            parts.append(_run_chunk(code, order, alpha[lo:hi], length[lo:hi], g, h))
            if progress is not None:
                progress(hi - lo)
    else:
        parts = _run_dask(scheduler, jobs, alpha, length, g, progress)

    cols: dict[str, list] = {k: [] for k in ("method", "order", "step", "length", "amplitude")}
    for (name, _code, order, h, lo, hi) in jobs:
        cols["method"].append(np.full(hi - lo, name, dtype=object))
        cols["order"].append(np.full(hi - lo, order, dtype=np.int64))
        cols["step"].append(np.full(hi - lo, h))
        cols["length"].append(length[lo:hi])
        cols["amplitude"].append(alpha[lo:hi])
    columns = {k: np.concatenate(c) for k, c in cols.items()}
    columns["method"] = columns["method"].astype(str)
    for key in ("exact", "status", "steps", "linear", "cubic", "cubic_error_estimate"):
        columns[key] = np.concatenate([p[key] for p in parts])
    columns["status"] = np.asarray(STATUS)[columns["status"]]
    columns["linear_error"] = columns["linear"] - columns["exact"]
    columns["cubic_error"] = columns["cubic"] - columns["exact"]
    return SweepResult(columns)


def _run_dask(scheduler: Any, jobs: Sequence, alpha: np.ndarray, length: np.ndarray, g: float,
              progress: Callable[[int], None] | None) -> list[dict[str, np.ndarray]]:
    """Submit one task per chunk to a Dask cluster; results come back in job order."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError:  # pragma: no cover - the dask extra is part of the test extra
        raise InputError("scheduler", scheduler, "usable only with dask.distributed installed "
                         "(pip install 'pendulab[dask]')") from None
    own = not hasattr(scheduler, "submit")
    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT) if own else scheduler
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError("scheduler", scheduler, f"the address of a reachable Dask scheduler ({exc})") from None
    try:
        futures = [
            client.submit(_run_chunk, code, order, alpha[lo:hi], length[lo:hi], g, h, False, pure=True)
            for _, code, order, h, lo, hi in jobs
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        parts: list = [None] * len(futures)
        for fut in as_completed(futures):
            i = index[fut.key]
            parts[i] = fut.result()
            if progress is not None:
                _, _, _, _, lo, hi = jobs[i]
                progress(hi - lo)
        return parts
    finally:
        if own:
            client.close()
