"""The explorer's query parameters: text in, checked values out.

Each value is read by the CLI's own parsers (:mod:`pendulab.core.inputs`), so a value is
judged the same way in the page and in a terminal; a bad one raises
:class:`pendulab.core.errors.InputError` naming the field, the value as typed and the allowed
range. The work a request may cause is bounded by :mod:`pendulab.web.limits`.
"""
from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from ..core import inputs
from ..core import validate as v
from ..core.cases import G_TEXT, G
from ..core.errors import InputError, shown_value
from ..core.methods import Method
from . import limits, words

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

ALLOWED = {
    "length": "a finite number > 0 (m), such as 3.5 or 75cm",
    "amplitude": "an angle in [0, pi) rad, such as 0.785, pi/4, 4pi/5 or 45deg",
    "step": "a finite number > 0 (s), such as 1e-3 or 1ms",
    "t_max": "a finite number > 0 (s), such as 20 or 20s",
    "g": f"a finite number > 0 (m/s^2), such as {G_TEXT}",
    "unit": "rad or deg: the unit of a plain-number amplitude",
    "omega0": "a finite number (rad/s), such as 2 or -1.5: the angular velocity at t = 0",
    "columns": "state (t, theta, omega) or all (also the exact motion, the global error and the energy error)",
    "damping": "a finite number >= 0 (1/s), such as 0.1: gamma of the damping term gamma theta'",
    "drag": "a finite number >= 0 (1/rad), such as 0.5: beta of the drag term beta theta'|theta'|",
    "mass": "a finite number > 0 (kg), such as 0.2: the bob's mass (the energies in J; not the period)",
}

#: 10^-1 .. 10^-4, four per decade: the range of problem 3(c) and a decade above.
DEFAULT_STEPS = tuple(float(10 ** (-k / 4)) for k in range(4, 17))


def text(params: Mapping[str, str], name: str, default: str | None = None) -> str:
    """The raw text of ``name``; missing (or empty) without a default is an error. In a
    Portuguese query (``lang=pt``) a decimal comma is a point (``3,5`` is 3.5), as the
    messages write the examples; a list (``steps``, :func:`step_list`) keeps its commas."""
    raw = params.get(name)
    if raw is None or not str(raw).strip():
        if default is not None:
            return default
        raise InputError(name, "(missing)", ALLOWED.get(name, "a value"))
    if words.safe_language(params) == "pt":
        return _DECIMAL_COMMA.sub(".", str(raw))
    return str(raw)


#: A comma between two digits: the decimal comma of Portuguese.
_DECIMAL_COMMA = re.compile(r"(?<=\d),(?=\d)")


def as_typed(exc: InputError, params: Mapping[str, str]) -> InputError:
    """``exc`` with its value as the query typed it (``0,5``) where :func:`text` read a
    Portuguese decimal comma as a point and the error shows the value read (``0.5``)."""
    raw = params.get(exc.name)
    if raw is None or words.safe_language(params) != "pt":
        return exc
    raw = str(raw).strip()
    if _DECIMAL_COMMA.sub(".", raw) == raw or shown_value(exc.value) != inputs.shown(_DECIMAL_COMMA.sub(".", raw)):
        return exc
    return InputError(exc.name, inputs.shown(raw), exc.allowed, mentions=exc.mentions, alternative=exc.alternative,
                      index=exc.index)


def positive(params: Mapping[str, str], name: str, default: str | None = None) -> float:
    """A number > 0 by :func:`pendulab.core.inputs.positive`, the CLI's parser; a length or a
    time may carry its unit as on the command line (``75cm``, ``10ms``), in m or s."""
    unit = _WITH_UNIT.get(name)
    if unit is not None:
        return float(unit(name, text(params, name, default)))
    return float(inputs.positive(name, text(params, name, default), ALLOWED[name]))


#: The fields that take a unit, and their parsers (the CLI's ``-l``, ``--step``, ``--t-max``).
_WITH_UNIT = {"length": inputs.length, "step": inputs.duration, "t_max": inputs.duration}


def amplitude(params: Mapping[str, str]) -> float:
    """``alpha`` in radians from ``0.785``, ``4pi/5`` or ``144deg`` (the CLI's forms).

    ``unit=deg`` reads a plain number as degrees (``144``); an error then shows the
    amplitude as typed, without the unit appended.
    """
    unit = str(params.get("unit") or "rad").strip().lower()
    if unit not in ("rad", "deg"):
        raise InputError("unit", inputs.shown(unit), ALLOWED["unit"])
    s = text(params, "amplitude")
    typed = s.strip() + "deg" if unit == "deg" and inputs.is_number(s) else s
    try:
        return float(inputs.angle("amplitude", typed))
    except InputError as exc:
        raise InputError("amplitude", inputs.shown(s.strip()) if s.strip() else exc.value, exc.allowed) from None


def method(params: Mapping[str, str]) -> Method:
    """The integrator by :func:`pendulab.core.methods.resolve`: the registry as it is now."""
    return inputs.method("method", text(params, "method", "taylor2"))


def points(params: Mapping[str, str], default: int, most: int) -> int:
    """``points`` in ``[2, most]``."""
    return inputs.integer("points", text(params, "points", str(default)), 2, most)


def pendulum(params: Mapping[str, str]) -> dict[str, Any]:
    """``length``, ``amplitude`` (rad) and ``g`` from a query; raises InputError."""
    return {
        "length": positive(params, "length"),
        "amplitude": amplitude(params),
        "g": positive(params, "g", DEFAULTS["g"]),
    }


def omega0(params: Mapping[str, str]) -> float:
    """The initial angular velocity theta'(0), rad/s (0 when not given)."""
    return float(inputs.real("omega0", text(params, "omega0", "0"), ALLOWED["omega0"]))


def non_negative(params: Mapping[str, str], name: str) -> float:
    """A number >= 0 by :func:`pendulab.core.inputs.non_negative` (0 when not given)."""
    return float(inputs.non_negative(name, text(params, name, "0"), ALLOWED[name]))


def mass(params: Mapping[str, str]) -> float:
    """The bob's mass, kg (1 when not given): it scales the energies in J, never the motion."""
    return float(inputs.positive("mass", text(params, "mass", "1"), ALLOWED["mass"]))


def simulation(params: Mapping[str, str]) -> dict[str, Any]:
    """All inputs of a simulation: pendulum, ``step``, ``t_max``, ``method``, ``damping``, ``drag``
    and ``mass``; its work within the limits."""
    from ..numerics.simulation import step_count

    p = pendulum(params)
    p["step"] = positive(params, "step")
    p["t_max"] = positive(params, "t_max")
    m = method(params)
    p["method"] = m.name
    p["omega0"] = omega0(params)
    p["damping"] = non_negative(params, "damping")
    p["drag"] = non_negative(params, "drag")
    p["mass"] = mass(params)
    if not p["step"] < p["t_max"]:
        raise InputError("step", inputs.shown(text(params, "step")), f"< t_max = {p['t_max']:g} s")
    limits.check_run(p["t_max"], p["step"], m, text(params, "step"), text(params, "t_max"))
    step_count(0.0, p["t_max"], p["step"])  # finite: within the limits
    return p


def step_list(params: Mapping[str, str]) -> list[float]:
    """``steps``: 1 to :data:`pendulab.web.limits.MAX_SWEEP` steps > 0, comma-separated; the default list when absent."""
    s = params.get("steps")
    if s is None or not str(s).strip():
        return list(DEFAULT_STEPS)
    allowed = f"a comma-separated list of 1 to {limits.MAX_SWEEP} steps > 0 (s)"
    parts = inputs.items("steps", s, allowed, max_items=10**6)
    if len(parts) > limits.MAX_SWEEP:
        raise InputError("steps", f"{len(parts)} values", allowed)
    return [float(x) for x in inputs.parse_list("steps", s, inputs.duration, allowed, limits.MAX_SWEEP)]


def unusual(length: float, g: float) -> str:
    """``"length"`` or ``"g"``: the one further, in decades, from an ordinary pendulum (1 m, 9.81 m/s^2)."""
    return v.furthest(("length", length, 1.0), ("g", g, G))
