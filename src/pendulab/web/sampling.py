"""What the explorer draws of a simulation: which steps are kept, in O(points) memory.

``theta(t)`` and the energy drift keep each column's smallest and largest value (the
min/max reduction of Jugel et al., "M4: A Visualization-Oriented Time Series Data
Aggregation", PVLDB 7(10), 2014); the phase portrait keeps whole orbits; the animation and
the global error keep evenly spaced steps. :func:`simulate_arrays` runs the one streamed
pass (:func:`pendulab.engine.kernels.folded`: the library's trajectory driver, folded as it goes) in
pieces, as the library's drivers run theirs, so a request whose client has gone stops between
two pieces.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..core.interrupt import CHUNK_COST
from ..core.methods import cost_per_step
from ..numerics.simulation import kept_steps, stride_for

#: Phase-portrait points per period, and at most this many in all.
PHASE_PER_PERIOD, PHASE_POINTS = 256, 4000
#: Animation samples: at most this many (16 per period where they fit).
FRAME_POINTS = 8000
#: Global-error samples (the exact motion is evaluated there): 64 per period, at most this many.
ERROR_POINTS = 20000
def finite_list(a: np.ndarray) -> list:
    """A JSON list; a non-finite value (a blown-up simulation) becomes ``null``."""
    out = a.tolist()
    if not np.all(np.isfinite(a)):
        out = [x if math.isfinite(x) else None for x in out]
    return out


def phase_samples(n: int, steps_per_period: float) -> tuple[np.ndarray, int, int]:
    """Steps drawn in the phase portrait: a curve, never chords across the orbit.

    About :data:`PHASE_PER_PERIOD` points per period (stride ``k``). When the whole
    run at that stride exceeds :data:`PHASE_POINTS`, whole orbits (1.05 periods each) are
    taken at evenly spread times, first and last included, so that a drift of the orbit
    still shows. Returns ``(steps, stride, windows)``.
    """
    # A run shorter than a period (T = 1e150 s) has its points spread over the run instead.
    k = max(1, int(min(steps_per_period, 2.0 * n) // PHASE_PER_PERIOD))
    if n // k + 1 <= PHASE_POINTS:
        return kept_steps(n, k), k, 1
    span = min(n, int(math.ceil(1.05 * steps_per_period)))
    per = span // k + 1
    windows = max(2, PHASE_POINTS // per)
    starts = np.round(np.linspace(0, n - span, windows)).astype(np.int64)
    idx = (starts[:, None] + k * np.arange(per, dtype=np.int64)[None, :]).ravel()
    return idx, k, windows


def frame_samples(n: int, steps_per_period: float, per_period: int = 16, most: int | None = None) -> np.ndarray:
    """Evenly spaced steps, ``per_period`` a period where at most ``most`` (:data:`FRAME_POINTS`) fit.

    The animation interpolates between them; the global error is evaluated at 64 a period.
    """
    most = FRAME_POINTS if most is None else most
    return kept_steps(n, max(int(min(steps_per_period, 2.0 * n) // per_period), stride_for(n, most)))


def minmax(bins: np.ndarray, values: np.ndarray, nb: int) -> np.ndarray:
    """Positions of the smallest and largest finite value of each bin, in order (M4's min/max)."""
    ok = np.flatnonzero(np.isfinite(values))
    if len(ok) <= 2 * nb:
        return ok
    order = ok[np.lexsort((values[ok], bins[ok]))]
    b = bins[order]
    first = np.flatnonzero(np.r_[True, b[1:] != b[:-1]])
    last = np.r_[first[1:] - 1, len(order) - 1]
    return np.unique(np.r_[order[first], order[last]])


def columns(i_lo: np.ndarray, v_lo: np.ndarray, i_hi: np.ndarray, v_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every column's kept steps and values, in time order (a column of NaN keeps none)."""
    idx = np.r_[i_lo, i_hi]
    val = np.r_[v_lo, v_hi]
    ok = idx >= 0
    idx, val = idx[ok], val[ok]
    idx, first = np.unique(idx, return_index=True)
    return idx, val[first]


def exact_overlay(length: float, alpha: float, g: float, period: float, t_end: float, nb: int) -> tuple[np.ndarray, np.ndarray]:
    """The exact motion (:func:`pendulab.numerics.motion.exact_motion`) drawn with the same min/max rule.

    Between two turning points ``theta`` is monotone, so in each of ``nb`` time columns its
    extremes are at the column's ends or at a turn ``t = k T/2`` (``theta = (-1)^k alpha``):
    the columns' ends plus the first two turns of each column give its exact extent.
    """
    from ..numerics.motion import exact_motion

    edges = np.linspace(0.0, t_end, nb + 1)
    with np.errstate(invalid="ignore", over="ignore"):  # a phase sqrt(g/l) t beyond the doubles: NaN, drawn as a gap
        theta_edges = exact_motion(length, alpha, edges, g).theta
    half = 0.5 * period
    k0 = np.ceil(edges[:-1] / half)
    k0 = np.where(k0 < 1, 1, k0)
    ts, ths = [edges], [theta_edges]
    if alpha > 0:
        for k in (k0, k0 + 1):
            t = k * half
            inside = t < edges[1:]
            ts.append(t[inside])
            ths.append(np.where(np.mod(k[inside], 2) == 0, alpha, -alpha))
    t = np.concatenate(ts)
    th = np.concatenate(ths)
    order = np.argsort(t, kind="stable")
    return t[order], th[order]


def gapped(values: np.ndarray, idx: np.ndarray, stride: int) -> list:
    """A JSON list with ``null`` between samples that are not consecutive (plotly breaks the line)."""
    out = finite_list(values)
    if len(idx) < 2:
        return out
    breaks = np.flatnonzero(np.diff(idx) > stride) + 1  # the last step may follow closer
    for b in breaks[::-1].tolist():
        out.insert(b, None)
    return out


def simulate_arrays(p: Mapping[str, Any], points: int, period: float | None = None) -> dict[str, Any]:
    """One streamed pass over the simulation: what the page draws, in O(points) memory.

    ``theta(t)``: the min and max of ``theta`` in each of ``points // 2`` columns of steps
    (every step when ``n + 1 <= points``); the energy drift likewise; the phase portrait
    and animation samples; the first step that left the oscillation or went non-finite.
    The steps run in pieces (:func:`pendulab.core.interrupt.run_pieces`): inside
    :func:`pendulab.core.interrupt.stop_when`, a set event stops the pass between two pieces.
    ``period``: the AGM period of a release at rest where the caller has it.
    """
    from ..engine import fold, kernels
    from ..numerics.period import agm_period
    from ..numerics.simulation import method_code, step_count

    code, order = method_code(p["method"])
    n = step_count(0.0, p["t_max"], p["step"])
    c = -p["g"] / p["length"]
    h = p["step"]
    omega0 = p.get("omega0", 0.0)
    if omega0:  # a launch: its own period (a turn, when it goes round), pendulab.numerics.launched
        from ..numerics.launched import launch

        period = launch(p["length"], p["amplitude"], omega0, p["g"]).period
        period = period if math.isfinite(period) else p["t_max"]
    elif period is None:
        period = float(agm_period(p["length"], p["amplitude"], p["g"]))
    per = period / h
    nb = max(1, min(points // 2, n + 1))
    phase_idx, phase_stride, windows = phase_samples(n, per)
    frame_idx = frame_samples(n, per)
    error_idx = frame_samples(n, per, 64, ERROR_POINTS)
    samples = np.union1d(np.union1d(phase_idx, frame_idx), error_idx)
    rec = kernels.folded(code, order, p["amplitude"], omega0, c, h, n, nb, samples,
                         max(1, int(CHUNK_COST / cost_per_step(p["method"]))), p.get("damping", 0.0), p.get("drag", 0.0))
    left, bad = int(rec.where[fold.LEFT]), int(rec.where[fold.BAD])
    val, at = rec.value, rec.step
    idx, theta = columns(at[fold.I_LO], val[fold.TH_LO], at[fold.I_HI], val[fold.TH_HI])
    _, omega = columns(at[fold.I_LO], val[fold.OM_LO], at[fold.I_HI], val[fold.OM_HI])
    e_idx, drift = columns(at[fold.E_I_LO], val[fold.E_LO], at[fold.E_I_HI], val[fold.E_HI])
    s_th, s_om = rec.s_theta, rec.s_omega
    pos = np.searchsorted(samples, phase_idx)
    fpos = np.searchsorted(samples, frame_idx)
    epos = np.searchsorted(samples, error_idx)
    return {
        "n": n, "columns": nb, "period": period,
        "idx": idx, "theta": theta, "omega": omega,
        "energy_idx": e_idx, "energy": drift,
        "energy_max": float(np.max(np.abs(drift))) if len(drift) else math.nan,
        "phase_idx": phase_idx, "phase_stride": phase_stride, "phase_windows": windows,
        "phase_theta": s_th[pos], "phase_omega": s_om[pos],
        "frame_idx": frame_idx, "frame_theta": s_th[fpos], "frame_omega": s_om[fpos],
        "error_idx": error_idx, "error_theta": s_th[epos],
        "left": left, "bad": bad,
    }
