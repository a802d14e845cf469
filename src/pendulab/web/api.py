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
import threading
from collections.abc import Mapping
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

#: Heavy simulations hold up to 24 bytes a step; let two run at a time, not two hundred.
_SIMULATIONS = threading.BoundedSemaphore(2)

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
    from ..methods import menu

    return {
        "methods": [{"name": m.name, "order": m.order, "description": m.description} for m in menu()],
        "g_presets": G_PRESETS,
        "limits": {"max_steps": MAX_STEPS, "max_points": MAX_POINTS, "plot_points": DEFAULT_PLOT_POINTS},
        "defaults": DEFAULTS,
        "problem5": {"length": PROBLEM5.l, "amplitude": PROBLEM5.alpha},
    }


def period_endpoint(params: Mapping[str, str]) -> dict[str, Any]:
    """``GET /api/period``: the exact period of a pendulum."""
    p = parse_pendulum(params)
    return period_view(p["length"], p["amplitude"], p["g"])
