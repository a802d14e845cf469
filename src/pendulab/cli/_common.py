"""Shared pieces of the CLI: parameter types, common options, JSON output."""
from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from typing import Any

import click

from ..cases import G_TEXT
from ..errors import InputError
from ..exact import Exact, parse_angle, parse_number


class _Type(click.ParamType):
    """A parameter type whose check is one of the library's validators."""

    def _fail(self, exc: InputError, param: click.Parameter | None, ctx) -> None:
        opt = param.opts[-1] if param is not None and param.opts else (param.name if param else "value")
        self.fail(f"{opt} = {exc.value!s} is not allowed: must be {exc.allowed}", param, ctx)

    def convert(self, value, param, ctx):
        if not isinstance(value, str):
            return value
        try:
            return self.parse(value)
        except InputError as exc:
            self._fail(exc, param, ctx)

    def parse(self, text: str) -> Any:
        raise NotImplementedError


class AngleType(_Type):
    """An amplitude: ``0.785``, ``pi/4``, ``4pi/5``, ``4*pi/5``, ``45deg``, ``45°``; in [0, pi)."""

    name = "angle"

    def parse(self, text: str) -> Exact:
        angle = parse_angle("amplitude", text)
        x = float(angle)
        if not (0 <= x < math.pi) or (angle.pi_power == 1 and angle.coef >= 1):
            raise InputError("amplitude", text, "an angle in [0, pi) rad, e.g. 0 to 179.99deg")
        return angle


class PositiveType(_Type):
    """A finite number > 0, kept exactly as written (``Exact``)."""

    name = "number"

    def parse(self, text: str) -> Exact:
        x = parse_number("value", text)
        if not (math.isfinite(float(x)) and float(x) > 0):
            raise InputError("value", text, "a finite number > 0")
        return x


class FloatType(_Type):
    """A finite real number."""

    name = "number"

    def parse(self, text: str) -> float:
        return float(parse_number("value", text))


class PositiveListType(_Type):
    """A comma-separated list of numbers > 0: ``1e-2,1e-3,1e-4``."""

    name = "list"

    def parse(self, text: str) -> list[float]:
        items = [s for s in text.split(",") if s.strip()]
        if not items:
            raise InputError("value", repr(text), "a comma-separated list of numbers > 0")
        out = []
        for s in items:
            try:
                x = float(parse_number("value", s))
            except InputError:
                raise InputError("value", repr(s), "a comma-separated list of numbers > 0") from None
            if not (math.isfinite(x) and x > 0):
                raise InputError("value", s, "a comma-separated list of numbers > 0")
            out.append(x)
        return out


ANGLE = AngleType()
POSITIVE = PositiveType()
FLOAT = FloatType()
POSITIVE_LIST = PositiveListType()


def json_option(f: Callable) -> Callable:
    return click.option("--json", "as_json", is_flag=True, help="Print one JSON document on stdout.")(f)


def g_option(f: Callable) -> Callable:
    return click.option(
        "--g", "g", type=POSITIVE, default=G_TEXT, show_default=True, help="Gravitational acceleration, m/s^2."
    )(f)


def jsonable(x: Any) -> Any:
    """Convert numpy values, tuples and non-finite floats for ``json.dumps``."""
    if isinstance(x, dict):
        return {str(k): jsonable(val) for k, val in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(val) for val in x]
    if hasattr(x, "tolist"):  # numpy arrays and scalars
        return jsonable(x.tolist())
    if isinstance(x, Exact):
        return float(x)
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def emit_json(data: dict) -> None:
    """Write ``data`` as one JSON document on stdout."""
    sys.stdout.write(json.dumps(jsonable(data), indent=2) + "\n")


def fmt(x: float, digits: int = 15) -> str:
    """A float with ``digits`` significant digits, the way tables print it."""
    return f"{x:.{digits}g}"


def check_plot_path(name: str, path: str) -> None:
    """Before the work: ``path`` can be written and matplotlib (``pendulab[report]``) is there."""
    from .._atomic import check_writable
    from .._extras import require

    check_writable(name, path)
    require("matplotlib", f"--{name}")


def save_plot(draw: Callable, path, size: tuple[float, float] = (6.4, 4.2)) -> None:
    """Call ``draw(ax)`` on a fresh figure and save it atomically (format from the extension).

    A ``Figure`` made without pyplot: no backend switch, no figure left in pyplot's list.
    """
    from .._atomic import save_figure
    from .._extras import require

    figure = require("matplotlib.figure", "drawing plots")
    fig = figure.Figure(figsize=size, layout="constrained")
    draw(fig.subplots())
    save_figure(fig, path, dpi=150)
