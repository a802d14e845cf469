"""The explorer's answers: checked parameters in, JSON-ready dicts (or CSV text) out.

A presenter, like the CLI: it reads the query with :mod:`pendulab.web.parameters`, calls
:func:`pendulab.numerics.crossing.search_period`, :func:`pendulab.numerics.period.periods` and the
streamed pass of :mod:`pendulab.web.sampling`, and renders their results; the shape of
each answer is :mod:`pendulab.web.models`. Every bad input raises
:class:`pendulab.core.errors.InputError` (the route turns it into status 422 naming the field
and the allowed range). Nothing here touches HTTP, so the tests call these functions
directly as well as through the app.
"""
from __future__ import annotations

import functools
import math
import sys
from collections.abc import Iterator, Mapping
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from pydantic import BaseModel

from ..core import inputs
from ..core import validate as v
from ..core.cases import PROBLEM5, G
from ..core.digits import distance_of, estimate_of, with_error
from ..core.errors import InputError
from ..core.methods import Status, resolve
from . import limits, models, parameters, sampling, words
from .sampling import finite_list

if TYPE_CHECKING:
    from ..numerics.crossing import PeriodSearch
    from ..numerics.period import Periods

__all__ = ["config_view", "convergence_view", "motion_view", "period_curve_view", "period_endpoint",
           "simulate_view", "trajectory_csv", "warm"]

#: Rows computed per block of the streamed CSV.
CSV_BLOCK = 8192
#: Points of the exact orbit drawn in the phase portrait (one period).
ORBIT_POINTS = 257
#: The CSV's header for each choice of ``columns``: the state, or also what the page plots
#: (the exact motion, the global error theta - theta_exact, the energy error (E - E0)/(m g l)).
CSV_COLUMNS = {
    "state": "t,theta,omega",
    "all": "t,theta,omega,theta_exact,omega_exact,theta_error,energy_error",
}


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _count(period: float, spacing: float) -> float:
    """Samples a period, ``period / spacing``; a count beyond the doubles (a period of 1e107 s
    sampled every 1e-215 s) as the largest double: JSON has no infinity, and the page reads
    it as plenty. Divided as Python floats: their overflow is inf, with no numpy warning."""
    return min(float(period) / float(spacing), sys.float_info.max) if spacing > 0 else sys.float_info.max


def period_view(length: float, amplitude: float, g: float, per: Periods | None = None) -> dict[str, Any]:
    """The periods of :func:`pendulab.numerics.period.periods` that :class:`models.PeriodAnswer` lists
    (the AGM period (7)-(8) and the small-angle one), and the amplitude in degrees; ``per``
    where the caller has them already."""
    from ..numerics.period import periods

    per = periods(length, amplitude, g) if per is None else per
    return _answer(models.PeriodAnswer, per.to_dict()) | {"amplitude_deg": math.degrees(amplitude)}


def estimate_view(length: float, amplitude: float, step: float, g: float, method: str,
                  period: float | None = None, lang: str = "en") -> dict[str, Any]:
    """The period estimated from a streamed simulation, or why there is none.

    Returns ``{"estimate": {...}, "status": "found", "reason": None}`` with the bracket
    ``[t_j, t_{j+1}]``, its midpoint, the linear and inverse-cubic (problem 3(d)) estimates
    and their absolute errors against the AGM period; else ``estimate`` None, the search's
    status (:class:`pendulab.numerics.crossing.PeriodSearch`; ``not_run`` where the search does not
    run) and a line saying why. ``period``: the AGM period where the caller has it.
    """
    from ..numerics.crossing import default_t_max, search_period
    from ..numerics.period import agm_period

    period = float(agm_period(length, amplitude, g)) if period is None else period
    span = default_t_max(period, step)
    if reason := limits.search_too_long(span, step, period, resolve(method), lang):
        return {"estimate": None, "status": NOT_RUN, "reason": reason}  # the period is too long for this step: say so, keep the rest
    if amplitude == 0:
        return {"estimate": None, "status": NOT_RUN, "reason": words.say("reason.at-rest", lang)}
    s = search_period(length, amplitude, step, g=g, method=method, period=period)
    if not s.found or s.estimate is None:
        return {"estimate": None, "status": s.status.name.lower(), "reason": search_reason(s, lang)}
    e = s.estimate.to_dict()
    mid = 0.5 * (e["bracket"][0] + e["bracket"][1])
    errors = {"bracket_mid": abs(mid - e["period"]), "linear": _num(e["linear_error"]), "cubic": _num(e["cubic_error"])}
    shown: dict[str, str | None] = {}
    for k in ("linear", "cubic"):
        x, t = e[k], e["period"]
        ok = x is not None and math.isfinite(x)
        shown[k] = estimate_of(x, t) if ok else None
        # the error and the relative error to 3 digits at most, and those T's half ulp leaves
        shown[f"{k}_error"] = distance_of(x, t, 3) if ok else None
        shown[f"{k}_relative"] = (with_error(abs(x - t) / t, (math.ulp(t) / 2 + math.ulp(abs(x - t))) / t
                                             + math.ulp(abs(x - t) / t), 3) if ok else None)
    return {"estimate": _answer(models.Estimate, e) | {"bracket_mid": mid, "errors": errors, "shown": shown},
            "status": "found", "reason": None}


def _answer(model: type[BaseModel], result: Mapping[str, Any]) -> dict[str, Any]:
    """The entries of a result's ``to_dict()`` that the response ``model`` lists (the same
    names), a float that is not finite as None; the model's other entries the caller adds."""
    return {k: _num(v) if isinstance(v, float) else v for k, v in result.items() if k in model.model_fields}


#: The status of an estimate whose search does not run (too long, at rest, launched).
NOT_RUN = "not_run"


def search_reason(s: PeriodSearch, lang: str = "en") -> str:
    """Why a period search (:func:`pendulab.numerics.crossing.search_period`) found no period, from its
    status and data, in the page's words (``web.reason.*``; the search's ``t_max`` is the page's,
    not the reader's)."""
    num = functools.partial(words.number, lang=lang)
    if s.underflow:
        k = s.g / s.length
        return words.say("reason.underflow", lang, amplitude=num(s.amplitude, ".3g"), change=num(k * s.step, ".3g"),
                         moving=num(cast(float, s.moving_amplitude), ".3g"))  # set where underflow is
    if s.status == Status.UNTRUSTED and s.estimate is not None and s.max_energy_drift is not None:
        why = (words.say("reason.untrusted-energy", lang, drift=num(s.max_energy_drift, ".2g"),
                         distance=num(s.separatrix_distance or 0.0, ".2g"))
               if s.max_energy_drift > (s.separatrix_distance or 0.0) else
               words.say("reason.untrusted-off", lang, percent=num(100 * abs(s.estimate.cubic - s.period) / s.period, ".0f")))
        return words.say("reason.untrusted", lang, cubic=num(s.estimate.cubic, ".6g"), period=num(s.period, ".6g"), why=why)
    if s.status == Status.NODES_COINCIDE:
        return words.say("reason.nodes-coincide", lang, amplitude=num(s.amplitude, ".3g"))
    if s.status == Status.LEFT_OSCILLATION:
        return words.say("reason.left-oscillation", lang, t=num(cast(float, s.t_left), ".6g"), h=num(s.step, "g"),
                         amplitude=num(s.amplitude, ".6g"), method=s.method)
    if s.status == Status.NO_RETURN:
        return words.say("reason.no-return", lang, t_max=num(s.t_max, ".4g"), period=num(s.period, ".6g"))
    return words.say("reason.too-early", lang, j=s.j, h=num(s.step, "g"))


def exact_state(p: Mapping[str, Any], t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(theta, theta')`` of the exact motion at ``t``: from rest (:func:`pendulab.numerics.motion.exact_motion`)
    or launched with ``omega0`` (:func:`pendulab.numerics.launched.launched_motion`)."""
    if p.get("omega0", 0.0):
        from ..numerics.launched import launched_motion

        return launched_motion(p["length"], p["amplitude"], p["omega0"], t, p["g"])
    from ..numerics.motion import exact_motion

    m = exact_motion(p["length"], p["amplitude"], t, p["g"])
    return m.theta, m.omega


def _energy0(p: Mapping[str, Any]) -> float:
    """The release's energy above the bottom, ``E0/(m g l)`` (:func:`pendulab.numerics.motion.energy_drift`
    of the release from rest at the bottom)."""
    from ..numerics.motion import energy_drift

    return float(energy_drift(p["amplitude"], p.get("omega0", 0.0), 0.0, 0.0, p["length"], p["g"]))


def _flags(p: Mapping[str, Any], sim: Mapping[str, Any], err_t: np.ndarray | None = None,
           err: np.ndarray | None = None, lang: str = "en") -> dict[str, Any]:
    """The diagnosis of the run (:func:`pendulab.numerics.diagnosis.diagnose`), each finding in words.

    ``notes``: every finding as ``{"kind", "severity", "text"}``; severity ``"wrong"`` (not
    the pendulum's motion), ``"warn"`` (out of step with the exact motion) or ``"note"`` (a
    small bounded energy error). ``warnings``: the texts of the first two kinds.
    """
    from ..numerics.diagnosis import PHASE_WARN, diagnose

    h = p["step"]
    goes_round = bool(p.get("omega0", 0.0)) and sim.get("circulates", False)
    left = sim["left"] * h if sim["left"] >= 0 and not goes_round else None  # over the top, as the exact motion does
    bad = sim["bad"] * h if sim["bad"] >= 0 else None
    # At the inputs' extremes (omega0 = 1e300, g/l = 1e600) E0 overflows to inf or nan, which the
    # diagnosis reads as it reads a blown-up run: no warning for the log.
    with np.errstate(over="ignore", invalid="ignore"):
        d = diagnose(_energy0(p), h * np.asarray(sim["energy_idx"], dtype=float), sim["energy"], sim["period"],
                     sim["n"] * h, left, bad, err_t, err, damped=damped(p))
    num = functools.partial(words.number, lang=lang)
    notes = []
    for f in d.notes:
        key = f.kind + ((".launched" if p.get("omega0", 0.0) else ".rest") if f.kind == "over-the-top" else "")
        key = "lab.flag-damped" if f.kind == "damped" else f"flag.{key}"
        text = words.say(key, lang, t=num(f.t, ".6g") if f.t is not None else "", h=num(h, "g"),
                         percent=num(100 * f.value, ".3g") if f.value is not None else "",
                         rad=num(f.value, ".3g") if f.value is not None else "",
                         deg=num(math.degrees(f.value), ".3g") if f.value is not None else "",
                         limit=num(PHASE_WARN, "g"))
        notes.append({"kind": f.kind, "severity": f.severity, "text": text})
    out = d.to_dict()
    warnings = [n["text"] for n in notes if n["severity"] != "note"]
    return {
        "left_oscillation_t": left, "nonfinite_t": bad,
        "max_energy_drift": out["max_energy_drift"], "energy_drift_relative": out["energy_drift_relative"],
        "energy_drift_kind": out["energy_drift_kind"], "max_theta_error": out["max_theta_error"],
        "trustworthy": out["trustworthy"], "warnings": warnings, "notes": notes,
    }


def damped(p: Mapping[str, Any]) -> bool:
    """Whether the run is damped (``damping`` or ``drag`` not 0)."""
    return bool(p.get("damping", 0.0) or p.get("drag", 0.0))


def simulate_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/simulate``: what the page draws, the exact motion, the period, estimates, flags.

    ``t, theta``: the min and max of ``theta`` in each of ``points // 2`` columns of steps, in
    time order (every step when they fit), so a plot of them reaches every extreme of the
    trajectory. ``phase``: the state about 256 times per period, whole orbits (``null``
    between them). ``frames``: the state 16 times per period (at most 8000) for the
    animation, ``exact_frames`` the exact state at the same times, ``exact_phase`` one
    period of the exact orbit. ``exact``: the exact motion with the same column rule; ``error``:
    ``theta_sim - theta_exact`` 64 times per period (at most 20 000; min/max per column); ``energy``: the
    drift ``(E - E0)/(m g l)`` at every step, min/max per column.
    """
    from ..numerics.period import periods

    p = parameters.simulation(params)
    lang = words.language(params)
    points = parameters.points(params, limits.DEFAULT_PLOT_POINTS, limits.MAX_POINTS)
    launched = _launch_view(p, params)
    per = periods(p["length"], p["amplitude"], p["g"])  # the one AGM period of the request, passed down
    if damped(p):  # the coursework's estimates time the undamped pendulum against its AGM period
        est = {"estimate": None, "status": NOT_RUN, "reason": words.say("lab.reason-damped", lang)}
    elif launched is None:
        est = estimate_view(p["length"], p["amplitude"], p["step"], p["g"], p["method"], per.period, lang)
    else:  # the coursework's estimate times a release at rest; a launch has its period from pendulab.numerics.launched
        est = {"estimate": None, "status": NOT_RUN, "reason": words.say(
            "reason.launched-turn" if launched["circulates"] else "reason.launched", lang, omega0=words.number(p["omega0"], "g", lang))}
    sim = sampling.simulate_arrays(p, points, None if launched else per.period)
    sim["circulates"] = bool(launched and launched["circulates"])
    h, n, nb = p["step"], sim["n"], sim["columns"]
    f_idx, e_idx = sim["frame_idx"], sim["error_idx"]
    f_t, e_t = h * f_idx, h * e_idx
    # A blown-up simulation (inf - inf), or a phase sqrt(g/l) t beyond the doubles: NaN, shown as null.
    with np.errstate(invalid="ignore", over="ignore"):
        ex_e = exact_state(p, e_t)[0]
        err = sim["error_theta"] - ex_e
    keep = sampling.minmax((e_idx * nb) // (n + 1), err, nb)
    if launched is None:
        ex_t, ex_th = sampling.exact_overlay(p["length"], p["amplitude"], p["g"], sim["period"], n * h, nb)
    else:  # a launch: the exact motion at the error's samples, 64 a period, min/max per column
        ex_keep = sampling.minmax((e_idx * nb) // (n + 1), ex_e, nb)
        ex_t, ex_th = e_t[ex_keep], ex_e[ex_keep]
    ph_t = h * sim["phase_idx"]
    with np.errstate(invalid="ignore", over="ignore"):  # sqrt(g/l) t beyond the doubles: null, as above
        ex_frames = exact_state(p, f_t)
        # One period of the exact orbit, a closed curve in the phase plane (a turn, for a launch that goes round).
        orbit = exact_state(p, np.linspace(0.0, sim["period"], ORBIT_POINTS))
    return {
        "input": {k: p[k] for k in ("length", "amplitude", "step", "t_max", "g", "method", "damping", "drag", "mass")}
        | {"amplitude_deg": math.degrees(p["amplitude"])},
        "units": {"t": "s", "theta": "rad", "omega": "rad/s", "period": "s", "energy": "m g l"},
        "n_steps": n,
        "columns": nb,
        "thinning": "none" if len(sim["idx"]) == n + 1 else "min/max per column",
        "points": len(sim["idx"]),
        "t": finite_list(h * sim["idx"]),
        "theta": finite_list(sim["theta"]),
        "omega": finite_list(sim["omega"]),
        "exact": {"t": ex_t.tolist(), "theta": finite_list(ex_th)},
        "error": {"t": e_t[keep].tolist(), "theta": finite_list(err[keep]), "samples": len(e_idx),
                  "per_period": _count(sim["period"], h * (e_idx[1] - e_idx[0])) if len(e_idx) > 1 else None},
        "energy": {"t": finite_list(h * sim["energy_idx"]), "drift": finite_list(sim["energy"])},
        "phase": {
            "theta": sampling.gapped(sim["phase_theta"], sim["phase_idx"], sim["phase_stride"]),
            "omega": sampling.gapped(sim["phase_omega"], sim["phase_idx"], sim["phase_stride"]),
            "t_first": float(ph_t[0]), "t_last": float(ph_t[-1]),
            "stride": sim["phase_stride"], "orbits": sim["phase_windows"],
        },
        "frames": {
            "t": f_t.tolist(), "theta": finite_list(sim["frame_theta"]), "omega": finite_list(sim["frame_omega"]),
            "per_period": _count(sim["period"], h * (f_idx[1] - f_idx[0])) if len(f_idx) > 1 else None,
        },
        "exact_frames": {"theta": finite_list(ex_frames[0]), "omega": finite_list(ex_frames[1])},
        "exact_phase": {"theta": finite_list(orbit[0]), "omega": finite_list(orbit[1])},
        "launch": launched,
        "flags": _flags(p, sim, e_t, err, lang),
        "period": period_view(p["length"], p["amplitude"], p["g"], per) | est
        | ({"period": launched["period"]} if launched else {}),
    }


def _launch_view(p: Mapping[str, Any], params: Mapping[str, str]) -> dict[str, Any] | None:
    """None for a release at rest; else the launch: ``omega0``, ``k``, whether it goes round,
    its period (a turn's time when it does) and turning angle (:mod:`pendulab.numerics.launched`)."""
    if not p["omega0"]:
        return None
    from ..numerics.launched import launch

    info = launch(p["length"], p["amplitude"], p["omega0"], p["g"])
    if not math.isfinite(info.period):
        raise InputError("omega0", inputs.shown(parameters.text(params, "omega0")),
                         "not exactly the speed that reaches the top (the separatrix, which takes forever)")
    turning = info.turning_angle
    return _answer(models.Launch, info.to_dict()) | {
        "omega0": p["omega0"], "turning_angle_deg": math.degrees(turning) if turning is not None else None}


def trajectory_csv(params: Mapping[str, str]) -> tuple[Iterator[str], str]:
    """``GET /api/trajectory.csv``: the trajectory at full precision (thinned only past ``points``).

    Parses at once (a bad input raises here); returns the file name and a generator of
    text blocks, each computed when asked for, so the server holds one block at a time.
    """
    p = parameters.simulation(params)
    words.language(params)  # judged, as every route judges it
    points = parameters.points(params, limits.MAX_CSV_ROWS, limits.MAX_CSV_ROWS)
    columns = parameters.text(params, "columns", "state").strip().lower()
    if columns not in CSV_COLUMNS:
        raise InputError("columns", inputs.shown(columns), parameters.ALLOWED["columns"])
    p = dict(p) | {"columns": columns}
    name = f"pendulab_l{p['length']:g}_a{math.degrees(p['amplitude']):.6g}deg_h{p['step']:g}_{p['method']}.csv"
    return csv_blocks(p, points), name


def csv_blocks(p: Mapping[str, Any], points: int) -> Iterator[str]:
    """The CSV text in blocks of :data:`CSV_BLOCK` rows: header first, then the kept steps."""
    from ..numerics.simulation import method_code, step_count, stride_for

    method, order = method_code(p["method"])
    n = step_count(0.0, p["t_max"], p["step"])
    stride = stride_for(n, points)  # at most ``points`` rows, step 0's included
    h, c = p["step"], -p["g"] / p["length"]
    damping = (p.get("damping", 0.0), p.get("drag", 0.0))
    full = p if p.get("columns", "state") == "all" else None
    w0 = float(p.get("omega0", 0.0))
    first = _csv_rows(p, np.zeros(1), np.array([p["amplitude"]]), np.array([w0])) if full else f"{0.0!r},{p['amplitude']!r},{w0!r}\n"
    yield CSV_COLUMNS["all" if full else "state"] + "\n" + first
    state = (p["amplitude"], w0)
    i = 0
    while i < n:
        i1 = min(n, i + stride * CSV_BLOCK)
        state, block = _csv_block(method, order, state, c, h, i, i1, stride, n, full, damping)
        i = i1
        yield block


def _csv_rows(p: Mapping[str, Any], t: np.ndarray, theta: np.ndarray, omega: np.ndarray) -> str:
    """Rows with the exact motion, the global error and the energy error beside the state
    (:func:`pendulab.numerics.motion.energy_drift`, in ``m g l``)."""
    from ..numerics.motion import energy_drift

    with np.errstate(invalid="ignore", over="ignore"):
        ex_theta, ex_omega = exact_state(p, t)
        drift = energy_drift(theta, omega, p["amplitude"], p.get("omega0", 0.0), p["length"], p["g"])
        err = theta - ex_theta
    cols = [a.tolist() for a in (t, theta, omega, ex_theta, ex_omega, err, drift)]
    return "".join(",".join(repr(x) for x in row) + "\n" for row in zip(*cols))


def _csv_block(code: int, order: int, state: tuple[float, float], c: float, h: float,
               i0: int, i1: int, stride: int, n: int,
               full: Mapping[str, Any] | None = None,
               damping: tuple[float, float] = (0.0, 0.0)) -> tuple[tuple[float, float], str]:
    from ..engine.kernels import drive
    from ..numerics.simulation import kept_steps

    size = (i1 - i0) // stride + 2
    z1, z2 = np.empty(size), np.empty(size)
    a, b, k = drive(code, order, state[0], state[1], c, h, i0, i1, stride, n, z1, z2, float(damping[0]), float(damping[1]))
    ii = kept_steps(n, stride, i0 + 1, i1)  # the steps drive kept
    if full is not None:
        return (a, b), _csv_rows(full, h * ii[:k], z1[:k], z2[:k])
    t = (h * ii[:k]).tolist()
    rows = "".join(f"{x!r},{y!r},{z!r}\n" for x, y, z in zip(t, z1[:k].tolist(), z2[:k].tolist()))
    return (a, b), rows


def convergence_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/convergence``: the period estimates and their errors for a list of steps."""
    from ..numerics.crossing import default_t_max

    p = parameters.pendulum(params)
    lang = words.language(params)
    method = parameters.method(params)
    steps = sorted(set(parameters.step_list(params)), reverse=True)
    periods = period_view(p["length"], p["amplitude"], p["g"])
    largest = parameters.DEFAULT_STEPS[0]
    need = default_t_max(periods["period"], largest, 0.0) / largest
    if need > limits.max_steps(method):
        # Even the default list's largest step cannot reach the first return: the period is too long.
        name = parameters.unusual(p["length"], p["g"])
        raise v.too_much_work(
            name, inputs.shown(parameters.text(params, name, parameters.DEFAULTS["g"])),
            f"such that the period search (1.5 T + 4h, T = {periods['period']:.3g} s) fits",
            limits.max_steps(method), need, f"steps of {method.name} of h = {largest:g} s",
        )
    limits.check_sweep([default_t_max(periods["period"], h, 0.0) for h in steps], steps, method)
    rows = []
    for h in steps:
        est = estimate_view(p["length"], p["amplitude"], h, p["g"], method.name, periods["period"], lang)
        rows.append({"step": h} | est)
    return {"method": method.name, "order": method.order, "period": periods, "rows": rows}


def motion_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/motion``: the exact motion alone (no simulation), for the page's second pendulum.

    The period view of the pendulum and ``frames``: ``theta`` and ``theta'`` of
    :func:`pendulab.numerics.motion.exact_motion` at evenly spaced times from 0 to ``t_max``, 16 a
    period where at most :data:`pendulab.web.sampling.FRAME_POINTS` fit (the page
    interpolates between them).
    """
    from ..numerics.motion import exact_motion

    p = parameters.pendulum(params)
    words.language(params)  # the page sends its language with every request: judged here too
    t_max = parameters.positive(params, "t_max", parameters.DEFAULTS["t_max"])
    view = period_view(p["length"], p["amplitude"], p["g"])
    frames = 16 * t_max / view["period"]
    if not math.isfinite(frames):  # 16 frames a period: a count beyond the doubles
        raise InputError("t_max", inputs.shown(params.get("t_max", t_max)), f"at most {1e300 * view['period']:.3g} s "
                         f"(10^300 periods of {view['period']:.6g} s)")
    count = int(min(sampling.FRAME_POINTS, max(2.0, math.ceil(frames) + 1)))
    t = np.linspace(0.0, t_max, count)
    with np.errstate(invalid="ignore", over="ignore"):  # sqrt(g/l) t beyond the doubles: null
        m = exact_motion(p["length"], p["amplitude"], t, p["g"])
    return view | {"frames": {"t": t.tolist(), "theta": finite_list(m.theta), "omega": finite_list(m.omega),
                              "per_period": _count(view["period"], t[1] - t[0])}}


#: The approximations the T(alpha)/T0 curve draws (keys of :data:`pendulab.numerics.approximations.FORMULAS`).
CURVE_FORMULAS = ("small-angle", "coursework-9", "kidd-fogg", "lima-arun", "ganley")


@functools.cache
def period_curve_view() -> dict[str, Any]:
    """``GET /api/period_curve``: ``T(alpha)/T0`` from 0 to 179 deg, by the AGM and approximated.

    ``period_ratio``: the AGM period (7)-(8) over the small-angle one; each approximation's
    ratio is its formula's (:mod:`pendulab.numerics.approximations`, with its source).
    """
    from ..numerics.approximations import FORMULAS
    from ..numerics.period import agm_period, small_angle_period

    deg = np.arange(0.0, 180.0)
    alpha = np.radians(deg)
    t0 = float(small_angle_period(1.0, G))
    period_ratio = [float(agm_period(1.0, float(a), G)) / t0 for a in alpha]
    approx = []
    for name in CURVE_FORMULAS:
        f = FORMULAS[name]
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.broadcast_to(f.ratio(alpha), alpha.shape)
        approx.append({"name": name, "label": f.label + (" (eq. 9)" if name == "coursework-9" else ""),
                       "source": f.source, "ratio": finite_list(np.asarray(ratio, dtype=float))})
    return {"amplitude_deg": deg.tolist(), "period_ratio": period_ratio, "approximations": approx}


def config_view(params: Mapping[str, str] | None = None) -> dict[str, Any]:
    """``GET /api/config``: the methods of the library, g presets, limits, defaults, and the
    page's words in the language ``lang`` asks for (:func:`pendulab.web.words.catalogue`)."""
    from ..core.methods import MAX_TAYLOR_ORDER, menu

    lang = words.language(params or {})
    said = words.catalogue(lang)  # a method's description in the language (the registry's own where it has none)
    return {
        "methods": [{"name": m.name, "order": m.order, "description": said.get(f"method.{m.name}", m.description)}
                    for m in menu()],
        # The family taylor:P of the registry, every order (taylor:1 is Euler's method).
        "family": [{"name": m.name, "order": m.order,
                    "description": words.say("method.euler", lang) if m.order == 1 else words.say("method.taylor", lang, order=m.order)}
                   for m in (resolve(f"taylor:{p}") for p in range(1, MAX_TAYLOR_ORDER + 1))],
        "g_presets": parameters.G_PRESETS,
        "limits": {"max_steps": limits.MAX_WORK, "max_points": limits.MAX_POINTS, "plot_points": limits.DEFAULT_PLOT_POINTS},
        "defaults": parameters.DEFAULTS,
        "problem5": {"length": PROBLEM5.l, "amplitude": PROBLEM5.alpha},
        "lang": lang,
        "words": words.catalogue(lang),
    }


def period_endpoint(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/period``: the AGM and small-angle periods of a pendulum (:func:`period_view`)."""
    p = parameters.pendulum(params)
    words.language(params)
    return period_view(p["length"], p["amplitude"], p["g"])


def warm() -> None:
    """Run every kernel once on a tiny case: compiled (or loaded from numba's cache) before a visitor waits."""
    q = {"length": "1", "amplitude": "30deg", "step": "0.05", "t_max": "2", "method": "taylor2"}
    simulate_view(q)
    for _ in csv_blocks(parameters.simulation(q), 10):
        pass
