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
import re
import threading
from collections.abc import Mapping
from typing import Any

import numpy as np

from .. import _validate as v
from ..cases import G_TEXT, PROBLEM5, G
from ..errors import InputError, PendulabError
from ..exact import parse_angle, parse_number

#: A request that would run more steps than this is refused, so one request cannot hold the
#: server's cores for long.
MAX_STEPS = 10_000_000
#: A request that would return more points than this is refused, so one answer stays a few MB.
MAX_POINTS = 1_000_000
#: Points returned for plotting when the request does not say (thinned evenly).
DEFAULT_PLOT_POINTS = 2_000
#: At most this many steps in one convergence sweep.
MAX_SWEEP = 40
#: Longest accepted parameter text: numbers and angles are short.
_MAX_TEXT = 64
# An exponent of 4+ digits would make the exact parser build a huge integer (1e99999999).
_BIG_EXPONENT = re.compile(r"[eE][+-]?0*\d{4,}")

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

#: Heavy simulations hold up to 24 bytes a step; let two run at a time, not two hundred.
_SIMULATIONS = threading.BoundedSemaphore(2)

_ALLOWED = {
    "length": "a finite number > 0 (m), such as 3.5",
    "amplitude": "an angle in [0, pi) rad, such as 0.785, pi/4, 4pi/5 or 45deg",
    "step": "a finite number > 0 (s), such as 1e-3",
    "t_max": "a finite number > 0 (s), such as 20",
    "g": f"a finite number > 0 (m/s^2), such as {G_TEXT}",
}


def _text(params: Mapping[str, str], name: str, default: str | None = None) -> str:
    """The raw text of ``name``; missing (or empty) without a default is an error."""
    raw = params.get(name)
    if raw is None or not str(raw).strip():
        if default is not None:
            return default
        raise InputError(name, "(missing)", _ALLOWED.get(name, "a value"))
    s = str(raw).strip()
    if len(s) > _MAX_TEXT or _BIG_EXPONENT.search(s):
        shown = s if len(s) <= 20 else s[:17] + "..."
        raise InputError(name, repr(shown), _ALLOWED.get(name, "a value") + f" (at most {_MAX_TEXT} characters, exponent < 1000)")
    return s


def _positive(params: Mapping[str, str], name: str, default: str | None = None) -> float:
    s = _text(params, name, default)
    try:
        x = float(parse_number(name, s))
    except (InputError, OverflowError):
        raise InputError(name, repr(s), _ALLOWED[name]) from None
    try:
        return v.positive(name, x)
    except InputError:
        raise InputError(name, s, _ALLOWED[name]) from None


def _amplitude(params: Mapping[str, str]) -> float:
    """``alpha`` in radians from ``0.785``, ``4pi/5`` or ``144deg`` (the CLI's forms)."""
    s = _text(params, "amplitude")
    try:
        angle = parse_angle("amplitude", s)
        x = float(angle)
    except (InputError, OverflowError):
        raise InputError("amplitude", repr(s), _ALLOWED["amplitude"]) from None
    # pi itself (or more) written exactly rounds to the double below pi: refuse it as written.
    if not (math.isfinite(x) and 0 <= x < math.pi) or (angle.pi_power == 1 and angle.coef >= 1):
        raise InputError("amplitude", s, "an angle in [0, pi) rad, that is 0 to 179.99... deg")
    return x


def _method(params: Mapping[str, str]) -> str:
    from ..taylor import method_code

    name = _text(params, "method", "taylor2")
    method_code(name)  # the registry as it is now: methods added later appear by themselves
    return name


def _points(params: Mapping[str, str], default: int) -> int:
    s = _text(params, "points", str(default))
    allowed = f"an integer in [2, {MAX_POINTS}]"
    try:
        x = int(s)
    except ValueError:
        raise InputError("points", repr(s), allowed) from None
    if not 2 <= x <= MAX_POINTS:
        raise InputError("points", s, allowed)
    return x


def _steps_needed(name: str, value: float, span: float, step: float, n: float | None = None) -> None:
    """Refuse a run of more than :data:`MAX_STEPS` steps (``n``, default ``span/step``)."""
    n = span / step if n is None else n
    if n > MAX_STEPS:
        raise InputError(
            name, f"{value:g}",
            f"such that at most {MAX_STEPS:.0e} steps are run: here {span:.4g} s / {step:g} s = {n:.3g} steps; "
            f"use step >= {span / MAX_STEPS:.3g} s",
        )


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
    p["method"] = _method(params)
    _, p["t_max"], p["step"] = v.time_span(0.0, p["t_max"], p["step"])
    _steps_needed("step", p["step"], p["t_max"], p["step"], step_count(0.0, p["t_max"], p["step"]))
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
    _steps_needed("step", step, span, step)
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


def simulate_arrays(p: Mapping[str, Any], points: int) -> dict[str, Any]:
    """Run :func:`pendulab.taylor.simulate` and keep at most ``points`` evenly spaced points."""
    from ..taylor import simulate, step_count

    idx = thin(step_count(0.0, p["t_max"], p["step"]) + 1, points)
    stride = int(idx[1] - idx[0]) if len(idx) > 1 else 1
    with _SIMULATIONS:  # the kernel stores only the kept points
        tr = simulate(p["length"], p["amplitude"], p["step"], p["t_max"], g=p["g"], method=p["method"], stride=stride)
    return {"n_steps": tr.n_steps, "stride": stride, "t": tr.t, "theta": tr.theta, "omega": tr.omega}


def simulate_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/simulate``: trajectory (thinned to ``points``), exact period, estimates."""
    p = parse_simulation(params)
    points = _points(params, DEFAULT_PLOT_POINTS)
    est = estimate_view(p["length"], p["amplitude"], p["step"], p["g"], p["method"])
    sim = simulate_arrays(p, points)
    return {
        "input": {k: p[k] for k in ("length", "amplitude", "step", "t_max", "g", "method")}
        | {"amplitude_deg": math.degrees(p["amplitude"])},
        "units": {"t": "s", "theta": "rad", "omega": "rad/s", "period": "s"},
        "n_steps": sim["n_steps"],
        "stride": sim["stride"],
        "points": len(sim["t"]),
        "t": _finite_list(sim["t"]),
        "theta": _finite_list(sim["theta"]),
        "omega": _finite_list(sim["omega"]),
        "period": period_view(p["length"], p["amplitude"], p["g"]) | est,
    }


def trajectory_csv(params: Mapping[str, str]) -> tuple[str, str]:
    """``GET /api/trajectory.csv``: the trajectory at full precision (thinned only past ``points``).

    Returns the CSV text and a file name.
    """
    p = parse_simulation(params)
    points = _points(params, MAX_POINTS)
    sim = simulate_arrays(p, points)
    rows = np.column_stack([sim["t"], sim["theta"], sim["omega"]])
    lines = ["t_s,theta_rad,omega_rad_per_s"]
    lines += [f"{a!r},{b!r},{c!r}" for a, b, c in rows.tolist()]
    name = f"pendulab_l{p['length']:g}_a{math.degrees(p['amplitude']):.6g}deg_h{p['step']:g}_{p['method']}.csv"
    return "\n".join(lines) + "\n", name


def _step_list(params: Mapping[str, str]) -> list[float]:
    s = params.get("steps")
    if s is None or not str(s).strip():
        # 10^-1 .. 10^-4, four per decade: the range of problem 3(c) and a decade above.
        return [float(10 ** (-k / 4)) for k in range(4, 17)]
    items = [x.strip() for x in str(s).split(",") if x.strip()]
    allowed = f"a comma-separated list of 1 to {MAX_SWEEP} steps > 0 (s)"
    if not 1 <= len(items) <= MAX_SWEEP:
        raise InputError("steps", f"{len(items)} values", allowed)
    out = []
    for item in items:
        try:
            out.append(_positive({"step": item}, "step"))
        except InputError:
            raise InputError("steps", repr(item[:20]), allowed) from None
    return out


def convergence_view(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/convergence``: the period estimates and their errors for a list of steps."""
    from ..crossing import default_t_max
    from ..taylor import METHODS

    p = parse_pendulum(params)
    method = _method(params)
    steps = sorted(set(_step_list(params)), reverse=True)
    exact = period_view(p["length"], p["amplitude"], p["g"])
    total = sum(default_t_max(exact["exact"], h, 0.0) / h for h in steps)
    if total > MAX_STEPS:
        raise InputError(
            "steps", f"{min(steps):g} (smallest)",
            f"such that at most {MAX_STEPS:.0e} steps are run in all: these need {total:.3g}",
        )
    rows = []
    for h in steps:
        est = estimate_view(p["length"], p["amplitude"], h, p["g"], method)
        rows.append({"step": h} | est)
    return {"method": method, "order": METHODS[method][1], "period": exact, "rows": rows}


def config_view() -> dict[str, Any]:
    """``GET /api/config``: the methods the library has now, g presets, limits, defaults."""
    from ..taylor import METHODS

    return {
        "methods": [{"name": name, "order": order} for name, (_, order) in METHODS.items()],
        "g_presets": G_PRESETS,
        "limits": {"max_steps": MAX_STEPS, "max_points": MAX_POINTS, "plot_points": DEFAULT_PLOT_POINTS},
        "defaults": DEFAULTS,
        "problem5": {"length": PROBLEM5.l, "amplitude": PROBLEM5.alpha},
    }


def period_endpoint(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/period``: the exact period of a pendulum."""
    p = parse_pendulum(params)
    return period_view(p["length"], p["amplitude"], p["g"])
