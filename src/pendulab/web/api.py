"""The web explorer's API as plain functions: query strings in, JSON-ready dicts out.

A presenter, like the CLI: it parses the query with the library's own parsers and
validators, calls :func:`pendulab.taylor.simulate`, :func:`pendulab.crossing.estimate_period`
and :func:`pendulab.period.agm_period`, and renders their results. Every bad input
raises :class:`pendulab.errors.InputError` (the route turns it into status 422 naming
the field and the allowed range). Nothing here touches HTTP, so the tests call these
functions directly as well as through the app.
"""
from __future__ import annotations

import math
import os
import threading
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from .. import inputs
from ..cases import G_TEXT, PROBLEM5, G
from ..errors import InputError, PendulabError
from ..methods import Method

#: A request that would run more steps than this is refused, so one request cannot hold the
#: server's cores for long.
MAX_STEPS = 10_000_000
#: A request that would return more points than this is refused, so one answer stays a few MB.
MAX_POINTS = 1_000_000
#: Points returned for plotting when the request does not say (thinned evenly).
DEFAULT_PLOT_POINTS = 2_000
#: At most this many steps in one convergence sweep.
MAX_SWEEP = 40
#: Gravity presets, m/s^2. Earth: standard gravity (the coursework's g); Moon and
#: Jupiter: NASA Planetary Fact Sheets (surface gravity, equatorial for Jupiter).
G_PRESETS = {"earth": G, "moon": 1.62, "jupiter": 24.79}

#: The default view: problem 5's pendulum (l = 3.5 m, alpha = 4 pi/5 = 144 deg).
DEFAULTS = {
    "length": "3.5",
    "amplitude": "144",
    "unit": "deg",
    "step": "1e-3",
    "t_max": "20",
    "g": G_TEXT,
    "method": "taylor2",
}

#: Phase-portrait points per exact period, and at most this many in all.
PHASE_PER_PERIOD, PHASE_POINTS = 256, 4000
#: Animation samples: at most this many (16 per period where they fit).
FRAME_POINTS = 8000
#: Global-error samples (the exact motion is evaluated there): 64 per period, at most this many.
ERROR_POINTS = 20000
#: An energy drift above this fraction of the swing's energy is flagged.
ENERGY_WARN = 0.01

#: Simulations run at once: one per core (the kernels release the GIL), at least two.
#: The app's routes wait for a slot without holding a thread (``app.py``); this
#: semaphore bounds direct callers of these functions too.
SIMULATION_SLOTS = max(2, os.cpu_count() or 2)
_SIMULATIONS = threading.BoundedSemaphore(SIMULATION_SLOTS)

_ALLOWED = {
    "length": "a finite number > 0 (m), such as 3.5",
    "amplitude": "an angle in [0, pi) rad, such as 0.785, pi/4, 4pi/5 or 45deg",
    "step": "a finite number > 0 (s), such as 1e-3",
    "t_max": "a finite number > 0 (s), such as 20",
    "g": f"a finite number > 0 (m/s^2), such as {G_TEXT}",
    "unit": "rad or deg: the unit of a plain-number amplitude",
}
#: An ordinary view (the defaults): which of step and t_max is unusual is judged against them.
_TYPICAL = {"step": 1e-3, "t_max": 20.0}


def _text(params: Mapping[str, str], name: str, default: str | None = None) -> str:
    """The raw text of ``name``; missing (or empty) without a default is an error."""
    raw = params.get(name)
    if raw is None or not str(raw).strip():
        if default is not None:
            return default
        raise InputError(name, "(missing)", _ALLOWED.get(name, "a value"))
    return str(raw)


def _positive(params: Mapping[str, str], name: str, default: str | None = None) -> float:
    """A number > 0 by :func:`pendulab.inputs.positive`, the CLI's parser."""
    return float(inputs.positive(name, _text(params, name, default), _ALLOWED[name]))


def _amplitude(params: Mapping[str, str]) -> float:
    """``alpha`` in radians from ``0.785``, ``4pi/5`` or ``144deg`` (the CLI's forms).

    ``unit=deg`` reads a plain number as degrees (``144``); an error then shows the
    amplitude as typed, without the unit appended.
    """
    unit = str(params.get("unit") or "rad").strip().lower()
    if unit not in ("rad", "deg"):
        raise InputError("unit", inputs.shown(unit), _ALLOWED["unit"])
    s = _text(params, "amplitude")
    text = s.strip() + "deg" if unit == "deg" and inputs.is_number(s) else s
    try:
        return float(inputs.angle("amplitude", text))
    except InputError as exc:
        raise InputError("amplitude", inputs.shown(s.strip()) if s.strip() else exc.value, exc.allowed) from None


def _method(params: Mapping[str, str]) -> Method:
    """The integrator by :func:`pendulab.methods.resolve`: the registry as it is now."""
    return inputs.method("method", _text(params, "method", "taylor2"))


def _points(params: Mapping[str, str], default: int) -> int:
    return inputs.integer("points", _text(params, "points", str(default)), 2, MAX_POINTS)


def _unusual(length: float, g: float) -> str:
    """``"length"`` or ``"g"``: the one further, in decades, from an ordinary pendulum (1 m, 9.81 m/s^2)."""
    return "length" if abs(math.log10(length)) >= abs(math.log10(g / G)) else "g"


def _too_many_steps(span: float, step: float, params: Mapping[str, str] | None = None) -> InputError | None:
    """The error for a run of more than :data:`MAX_STEPS` steps of ``step`` over ``span`` s, or None.

    Blames the one of ``step`` and ``t_max`` further (in decades) from an ordinary view.
    """
    n = span / step
    if n <= MAX_STEPS:
        return None
    if params is not None and abs(math.log10(span / _TYPICAL["t_max"])) > abs(math.log10(_TYPICAL["step"] / step)):
        return InputError("t_max", inputs.shown(_text(params, "t_max")),
                          f"<= {MAX_STEPS:.0e} steps of h = {step:g} s, i.e. t_max <= {MAX_STEPS * step:.4g} s "
                          "(or a larger step)")
    shown = inputs.shown(_text(params, "step")) if params is not None else f"{step:g}"
    return InputError("step", shown,
                      f"such that at most {MAX_STEPS:.0e} steps are run: here {span:.4g} s / {step:g} s = {n:.3g} "
                      f"steps; use step >= {span / MAX_STEPS:.3g} s")


def _finite_list(a: np.ndarray) -> list:
    """A JSON list; a non-finite value (a blown-up simulation) becomes ``null``."""
    out = a.tolist()
    if not np.all(np.isfinite(a)):
        out = [x if math.isfinite(x) else None for x in out]
    return out


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def parse_pendulum(params: Mapping[str, str]) -> dict[str, Any]:
    """``length``, ``amplitude`` (rad) and ``g`` from a query; raises InputError."""
    return {
        "length": _positive(params, "length"),
        "amplitude": _amplitude(params),
        "g": _positive(params, "g", DEFAULTS["g"]),
    }


def parse_simulation(params: Mapping[str, str]) -> dict[str, Any]:
    """All inputs of a simulation: pendulum, ``step``, ``t_max``, ``method``."""
    from ..taylor import step_count

    p = parse_pendulum(params)
    p["step"] = _positive(params, "step")
    p["t_max"] = _positive(params, "t_max")
    p["method"] = _method(params).name
    if not p["step"] < p["t_max"]:
        raise InputError("step", inputs.shown(_text(params, "step")), f"< t_max = {p['t_max']:g} s")
    if err := _too_many_steps(p["t_max"], p["step"], params):
        raise err
    step_count(0.0, p["t_max"], p["step"])  # finite: at most MAX_STEPS
    return p


def period_view(length: float, amplitude: float, g: float) -> dict[str, Any]:
    """The exact (AGM, equations (7)-(8)) and small-angle periods."""
    from ..period import agm_period, small_angle_period

    return {
        "length": length,
        "amplitude": amplitude,
        "amplitude_deg": math.degrees(amplitude),
        "g": g,
        "exact": float(agm_period(length, amplitude, g)),
        "small_angle": float(small_angle_period(length, g)),
    }


def estimate_view(length: float, amplitude: float, step: float, g: float, method: str) -> dict[str, Any]:
    """The period estimated from a streamed simulation, or why there is none.

    Returns ``{"estimate": {...}}`` with the bracket ``[t_j, t_{j+1}]``, its midpoint, the
    linear and inverse-cubic (problem 3(d)) estimates and their absolute errors against
    the AGM period, or ``{"estimate": None, "reason": "..."}``.
    """
    from ..crossing import default_t_max, estimate_period
    from ..period import agm_period

    exact = float(agm_period(length, amplitude, g))
    span = default_t_max(exact, step)
    if span / step > MAX_STEPS:  # the period is too long for this step: say so, keep the rest
        hint = f"; use step >= {span / MAX_STEPS:.3g} s" if span / MAX_STEPS < exact / 20 else ""
        return {"estimate": None, "reason": (
            f"the period search would run {span / step:.3g} steps of h = {step:g} s to reach 1.5 T + 4h = {span:.4g} s, "
            f"more than the {MAX_STEPS:.0e} allowed{hint}")}
    try:
        e = estimate_period(length, amplitude, step, g=g, method=method)
    except PendulabError as exc:  # no return, went over the top, amplitude 0: a result, not a bad request
        return {"estimate": None, "reason": " ".join(str(exc).split())}
    mid = 0.5 * (e.bracket[0] + e.bracket[1])
    return {
        "estimate": {
            "step": e.step,
            "method": e.method,
            "j": e.j,
            "bracket": [e.bracket[0], e.bracket[1]],
            "bracket_mid": mid,
            "linear": _num(e.linear),
            "cubic": _num(e.cubic),
            "cubic_error_estimate": _num(e.cubic_error_estimate),
            "errors": {
                "bracket_mid": abs(mid - e.exact),
                "linear": _num(e.linear_error),
                "cubic": _num(e.cubic_error),
            },
            "exact": e.exact,
        },
        "reason": None,
    }


def thin(n_points: int, points: int) -> np.ndarray:
    """Indices ``0, k, 2k, ...`` plus the last one: at most ``points`` of ``n_points``, evenly spaced."""
    if n_points <= points:
        return np.arange(n_points)
    stride = math.ceil((n_points - 1) / (points - 1))
    idx = np.arange(0, n_points, stride)
    if idx[-1] != n_points - 1:
        idx = np.append(idx, n_points - 1)
    return idx


def _uniform(n: int, stride: int) -> np.ndarray:
    idx = np.arange(0, n + 1, stride, dtype=np.int64)
    return idx if idx[-1] == n else np.append(idx, n)


def phase_samples(n: int, steps_per_period: float) -> tuple[np.ndarray, int, int]:
    """Steps drawn in the phase portrait: a curve, never chords across the orbit.

    About :data:`PHASE_PER_PERIOD` points per exact period (stride ``k``). When the whole
    run at that stride exceeds :data:`PHASE_POINTS`, whole orbits (1.05 periods each) are
    taken at evenly spread times, first and last included, so that a drift of the orbit
    still shows. Returns ``(steps, stride, windows)``.
    """
    # A run shorter than a period (T = 1e150 s) has its points spread over the run instead.
    k = max(1, int(min(steps_per_period, 2.0 * n) // PHASE_PER_PERIOD))
    if n // k + 1 <= PHASE_POINTS:
        return _uniform(n, k), k, 1
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
    k = max(1, int(min(steps_per_period, 2.0 * n) // per_period), math.ceil(n / (most - 1)))
    return _uniform(n, min(k, n))


def _minmax(bins: np.ndarray, values: np.ndarray, nb: int) -> np.ndarray:
    """Positions of the smallest and largest finite value of each bin, in order (M4's min/max)."""
    ok = np.flatnonzero(np.isfinite(values))
    if len(ok) <= 2 * nb:
        return ok
    order = ok[np.lexsort((values[ok], bins[ok]))]
    b = bins[order]
    first = np.flatnonzero(np.r_[True, b[1:] != b[:-1]])
    last = np.r_[first[1:] - 1, len(order) - 1]
    return np.unique(np.r_[order[first], order[last]])


def _columns(i_lo: np.ndarray, v_lo: np.ndarray, i_hi: np.ndarray, v_hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every column's kept steps and values, in time order (a column of NaN keeps none)."""
    idx = np.r_[i_lo, i_hi]
    val = np.r_[v_lo, v_hi]
    ok = idx >= 0
    idx, val = idx[ok], val[ok]
    idx, first = np.unique(idx, return_index=True)
    return idx, val[first]


def exact_overlay(length: float, alpha: float, g: float, period: float, t_end: float, nb: int) -> tuple[np.ndarray, np.ndarray]:
    """The exact motion (:func:`pendulab.motion.exact_motion`) drawn with the same min/max rule.

    Between two turning points ``theta`` is monotone, so in each of ``nb`` time columns its
    extremes are at the column's ends or at a turn ``t = k T/2`` (``theta = (-1)^k alpha``):
    the columns' ends plus the first two turns of each column give its exact extent.
    """
    from ..motion import exact_motion

    edges = np.linspace(0.0, t_end, nb + 1)
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


def _gapped(values: np.ndarray, idx: np.ndarray, stride: int) -> list:
    """A JSON list with ``null`` between samples that are not consecutive (plotly breaks the line)."""
    out = _finite_list(values)
    if len(idx) < 2:
        return out
    breaks = np.flatnonzero(np.diff(idx) > stride) + 1  # the last step may follow closer
    for b in breaks[::-1].tolist():
        out.insert(b, None)
    return out


def simulate_arrays(p: Mapping[str, Any], points: int) -> dict[str, Any]:
    """One streamed pass over the simulation: what the page draws, in O(points) memory.

    ``theta(t)``: the min and max of ``theta`` in each of ``points // 2`` columns of steps
    (every step when ``n + 1 <= points``); the energy drift likewise; the phase portrait
    and animation samples; the first step that left the oscillation or went non-finite.
    """
    from ..period import agm_period
    from ..taylor import method_code, step_count
    from ._view import scan

    code, order = method_code(p["method"])
    n = step_count(0.0, p["t_max"], p["step"])
    c = -p["g"] / p["length"]
    h = p["step"]
    period = float(agm_period(p["length"], p["amplitude"], p["g"]))
    per = period / h
    nb = max(1, min(points // 2, n + 1))
    phase_idx, phase_stride, windows = phase_samples(n, per)
    frame_idx = frame_samples(n, per)
    error_idx = frame_samples(n, per, 64, ERROR_POINTS)
    samples = np.union1d(np.union1d(phase_idx, frame_idx), error_idx)
    s_th, s_om = np.empty(len(samples)), np.empty(len(samples))
    i_lo, i_hi, e_i_lo, e_i_hi = (np.empty(nb, dtype=np.int64) for _ in range(4))
    th_lo, th_hi, om_lo, om_hi, e_lo, e_hi = (np.empty(nb) for _ in range(6))
    with _SIMULATIONS:
        left, bad = scan(code, order, p["amplitude"], c, h, n, samples, s_th, s_om,
                         i_lo, i_hi, th_lo, th_hi, om_lo, om_hi, e_i_lo, e_i_hi, e_lo, e_hi)
    idx, theta = _columns(i_lo, th_lo, i_hi, th_hi)
    _, omega = _columns(i_lo, om_lo, i_hi, om_hi)
    e_idx, drift = _columns(e_i_lo, e_lo, e_i_hi, e_hi)
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
        "left": int(left), "bad": int(bad),
    }


def _flags(p: Mapping[str, Any], sim: Mapping[str, Any]) -> dict[str, Any]:
    """What makes a simulation untrustworthy, as facts with their times, and one line each."""
    h, alpha = p["step"], p["amplitude"]
    swing = 1.0 - math.cos(alpha)  # the oscillation's energy, E(alpha) - E(0), in m g l
    left = sim["left"] * h if sim["left"] >= 0 else None
    bad = sim["bad"] * h if sim["bad"] >= 0 else None
    drift = sim["energy_max"]
    rel = drift / swing if swing > 0 and math.isfinite(drift) else None
    warnings = []
    if bad is not None:
        warnings.append(f"the simulation blew up: theta or theta' is no longer a finite number from t = {bad:.6g} s")
    if left is not None:
        warnings.append(
            f"the simulated pendulum went over the top (|theta| >= 180 deg) at t = {left:.6g} s, which the real one "
            f"released at rest below 180 deg never does: step h = {h:g} s is too large for this method"
        )
    if rel is not None and rel > ENERGY_WARN and bad is None:
        warnings.append(
            f"the energy drifted by up to {100 * rel:.3g} % of the swing's energy m g l (1 - cos alpha): "
            "the simulated motion is not the pendulum's; use a smaller step or another method"
        )
    return {
        "left_oscillation_t": left, "nonfinite_t": bad,
        "energy_drift_max": _num(drift) if drift == drift else None,
        "energy_drift_relative": _num(rel) if rel is not None else None,
        "trustworthy": not warnings, "warnings": warnings,
    }


def simulate_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/simulate``: what the page draws, the exact motion and period, estimates, flags.

    ``t, theta``: the min and max of ``theta`` in each of ``points // 2`` columns of steps, in
    time order (every step when they fit), so a plot of them reaches every extreme of the
    trajectory. ``phase``: the state about 256 times per period, whole orbits (``null``
    between them). ``frames``: the state 16 times per period (at most 8000) for the
    animation. ``exact``: the exact motion with the same column rule; ``error``:
    ``theta_sim - theta_exact`` 64 times per period (at most 20 000; min/max per column); ``energy``: the
    drift ``(E - E0)/(m g l)`` at every step, min/max per column.
    """
    from ..motion import exact_motion

    p = parse_simulation(params)
    points = _points(params, DEFAULT_PLOT_POINTS)
    est = estimate_view(p["length"], p["amplitude"], p["step"], p["g"], p["method"])
    sim = simulate_arrays(p, points)
    h, n, nb = p["step"], sim["n"], sim["columns"]
    f_idx, e_idx = sim["frame_idx"], sim["error_idx"]
    f_t, e_t = h * f_idx, h * e_idx
    err = sim["error_theta"] - exact_motion(p["length"], p["amplitude"], e_t, p["g"]).theta
    keep = _minmax((e_idx * nb) // (n + 1), err, nb)
    ex_t, ex_th = exact_overlay(p["length"], p["amplitude"], p["g"], sim["period"], n * h, nb)
    ph_t = h * sim["phase_idx"]
    return {
        "input": {k: p[k] for k in ("length", "amplitude", "step", "t_max", "g", "method")}
        | {"amplitude_deg": math.degrees(p["amplitude"])},
        "units": {"t": "s", "theta": "rad", "omega": "rad/s", "period": "s", "energy": "m g l"},
        "n_steps": n,
        "columns": nb,
        "thinning": "none" if len(sim["idx"]) == n + 1 else "min/max per column",
        "points": len(sim["idx"]),
        "t": _finite_list(h * sim["idx"]),
        "theta": _finite_list(sim["theta"]),
        "omega": _finite_list(sim["omega"]),
        "exact": {"t": ex_t.tolist(), "theta": _finite_list(ex_th)},
        "error": {"t": e_t[keep].tolist(), "theta": _finite_list(err[keep]), "samples": len(e_idx),
                  "per_period": sim["period"] / (h * (e_idx[1] - e_idx[0])) if len(e_idx) > 1 else None},
        "energy": {"t": _finite_list(h * sim["energy_idx"]), "drift": _finite_list(sim["energy"])},
        "phase": {
            "theta": _gapped(sim["phase_theta"], sim["phase_idx"], sim["phase_stride"]),
            "omega": _gapped(sim["phase_omega"], sim["phase_idx"], sim["phase_stride"]),
            "t_first": float(ph_t[0]), "t_last": float(ph_t[-1]),
            "stride": sim["phase_stride"], "orbits": sim["phase_windows"],
        },
        "frames": {
            "t": f_t.tolist(), "theta": _finite_list(sim["frame_theta"]), "omega": _finite_list(sim["frame_omega"]),
            "per_period": sim["period"] / (h * (f_idx[1] - f_idx[0])) if len(f_idx) > 1 else None,
        },
        "flags": _flags(p, sim),
        "period": period_view(p["length"], p["amplitude"], p["g"]) | est,
    }


#: Rows computed per block of the streamed CSV.
CSV_BLOCK = 8192


def trajectory_csv(params: Mapping[str, str]) -> tuple[Iterator[str], str]:
    """``GET /api/trajectory.csv``: the trajectory at full precision (thinned only past ``points``).

    Parses at once (a bad input raises here); returns the file name and a generator of
    text blocks, each computed when asked for, so the server holds one block at a time.
    """
    p = parse_simulation(params)
    points = _points(params, MAX_POINTS)
    name = f"pendulab_l{p['length']:g}_a{math.degrees(p['amplitude']):.6g}deg_h{p['step']:g}_{p['method']}.csv"
    return csv_blocks(p, points), name


def csv_blocks(p: Mapping[str, Any], points: int) -> Iterator[str]:
    """The CSV text in blocks of :data:`CSV_BLOCK` rows: header first, then the kept steps."""
    from ..taylor import method_code, step_count

    code, order = method_code(p["method"])
    n = step_count(0.0, p["t_max"], p["step"])
    idx = thin(n + 1, points)
    stride = int(idx[1] - idx[0]) if len(idx) > 1 else 1
    h, c = p["step"], -p["g"] / p["length"]
    yield "t_s,theta_rad,omega_rad_per_s\n" + f"{0.0!r},{p['amplitude']!r},{0.0!r}\n"
    state = (p["amplitude"], 0.0)
    i = 0
    while i < n:
        i1 = min(n, i + stride * CSV_BLOCK)
        state, text = _csv_block(code, order, state, c, h, i, i1, stride, n)
        i = i1
        yield text


def _csv_block(code: int, order: int, state: tuple[float, float], c: float, h: float,
               i0: int, i1: int, stride: int, n: int) -> tuple[tuple[float, float], str]:
    from ._view import advance

    size = (i1 - i0) // stride + 2
    z1, z2, ii = np.empty(size), np.empty(size), np.empty(size, dtype=np.int64)
    with _SIMULATIONS:
        a, b, k = advance(code, order, state[0], state[1], c, h, i0, i1, stride, n, z1, z2, ii)
    t = (h * ii[:k]).tolist()
    rows = "".join(f"{x!r},{y!r},{z!r}\n" for x, y, z in zip(t, z1[:k].tolist(), z2[:k].tolist()))
    return (a, b), rows


#: 10^-1 .. 10^-4, four per decade: the range of problem 3(c) and a decade above.
_DEFAULT_STEPS = tuple(float(10 ** (-k / 4)) for k in range(4, 17))


def _step_list(params: Mapping[str, str]) -> list[float]:
    s = params.get("steps")
    if s is None or not str(s).strip():
        return list(_DEFAULT_STEPS)
    allowed = f"a comma-separated list of 1 to {MAX_SWEEP} steps > 0 (s)"
    parts = inputs.items("steps", s, allowed, max_items=10**6)
    if len(parts) > MAX_SWEEP:
        raise InputError("steps", f"{len(parts)} values", allowed)
    return [float(x) for x in inputs.parse_list("steps", s, inputs.positive, allowed, MAX_SWEEP)]


def convergence_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/convergence``: the period estimates and their errors for a list of steps."""
    from ..crossing import default_t_max

    p = parse_pendulum(params)
    method = _method(params)
    steps = sorted(set(_step_list(params)), reverse=True)
    exact = period_view(p["length"], p["amplitude"], p["g"])
    total = sum(default_t_max(exact["exact"], h, 0.0) / h for h in steps)
    if default_t_max(exact["exact"], _DEFAULT_STEPS[0], 0.0) / _DEFAULT_STEPS[0] > MAX_STEPS:
        # Even the default list's largest step cannot reach the first return: the period is too long.
        name = _unusual(p["length"], p["g"])
        raise InputError(
            name, inputs.shown(_text(params, name, DEFAULTS["g"])),
            f"such that the period search (1.5 T + 4h, T = {exact['exact']:.3g} s) fits in {MAX_STEPS:.0e} "
            f"steps of h = {_DEFAULT_STEPS[0]:g} s",
        )
    if total > MAX_STEPS:
        raise InputError(
            "steps", f"{min(steps):g} (smallest)",
            f"such that at most {MAX_STEPS:.0e} steps are run in all: these need {total:.3g}",
        )
    rows = []
    for h in steps:
        est = estimate_view(p["length"], p["amplitude"], h, p["g"], method.name)
        rows.append({"step": h} | est)
    return {"method": method.name, "order": method.order, "period": exact, "rows": rows}


def config_view() -> dict[str, Any]:
    """``GET /api/config``: the methods the library has now, g presets, limits, defaults."""
    from ..methods import MAX_TAYLOR_ORDER, menu, resolve

    return {
        "methods": [{"name": m.name, "order": m.order, "description": m.description} for m in menu()],
        # The family taylor:P of the registry, every order (taylor:1 is Euler's method).
        "family": [{"name": m.name, "order": m.order, "description": m.description + (" (Euler's method)" if m.order == 1 else "")}
                   for m in (resolve(f"taylor:{p}") for p in range(1, MAX_TAYLOR_ORDER + 1))],
        "g_presets": G_PRESETS,
        "limits": {"max_steps": MAX_STEPS, "max_points": MAX_POINTS, "plot_points": DEFAULT_PLOT_POINTS},
        "defaults": DEFAULTS,
        "problem5": {"length": PROBLEM5.l, "amplitude": PROBLEM5.alpha},
    }


def period_endpoint(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/period``: the exact period of a pendulum."""
    p = parse_pendulum(params)
    return period_view(p["length"], p["amplitude"], p["g"])


def warm() -> None:
    """Run every kernel once on a tiny case: compiled (or loaded from numba's cache) before a visitor waits."""
    q = {"length": "1", "amplitude": "30deg", "step": "0.05", "t_max": "2", "method": "taylor2"}
    simulate_view(q)
    p = parse_simulation(q)
    for _ in csv_blocks(p, 10):
        pass
