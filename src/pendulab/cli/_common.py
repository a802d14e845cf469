"""Shared pieces of the CLI: parameter types, common options, JSON output."""
from __future__ import annotations

import json
import math
import re
import sys
from collections.abc import Callable
from typing import Any

import click

from ..core import inputs
from ..core.cases import G_TEXT
from ..core.errors import InputError
from ..core.exact import Exact

#: Key of ``click.Context.meta``: parameter name -> (its text, whether the person typed it),
#: for the messages of library errors (:func:`pendulab.cli.in_cli_words`).
TYPED = "pendulab.typed"


class Parsed(click.ParamType):
    """A parameter type whose parser is one of :mod:`pendulab.core.inputs`' functions.

    ``parse(text)`` returns the value or raises :class:`InputError`; the message then
    names the option as the command spells it (``--t-max``), the text and the range.
    """

    def __init__(self, parse: Callable[[str], Any], name: str):
        self.parse = parse
        self.name = name

    def convert(self, value, param, ctx):
        if not isinstance(value, str):  # a default that is already a value
            return value
        if ctx is not None and param is not None and param.name:
            source = ctx.get_parameter_source(param.name)
            typed = source not in (None, click.core.ParameterSource.DEFAULT, click.core.ParameterSource.DEFAULT_MAP)
            ctx.meta.setdefault(TYPED, {})[param.name] = (value, typed)
        try:
            return self.parse(value)
        except InputError as exc:
            self.fail(one_line(str(exc).replace(exc.name, option_name(param), 1)), param, ctx)


def one_line(text: str) -> str:
    """``text`` on one line: each run of white space that holds a line break (or a tab) becomes
    one space. Other runs are kept: a value echoed as typed keeps its spaces (``1  2``)."""
    return _BREAKS.sub(" ", text).strip()


_BREAKS = re.compile(r"\s*[^\S ]\s*")


def option_name(param: click.Parameter | None) -> str:
    """``--t-max`` for an option, ``NUMBERS`` for an argument."""
    if param is None:
        return "value"
    if isinstance(param, click.Option) and param.opts:
        return max(param.opts, key=len)
    return (param.name or "value").upper()


def integer(low: int, high: int) -> Parsed:
    """An integer in ``[low, high]`` (ASCII digits; ``1e3`` is 1000)."""
    return Parsed(lambda s: inputs.integer("value", s, low, high), f"{low}..{high}")


def choice(*values: str) -> Parsed:
    """One of ``values``, exactly as written."""
    def parse(text: str) -> str:
        if text not in values:
            raise InputError("value", inputs.shown(text) if text.strip() else "(empty)", "one of " + ", ".join(values))
        return text

    return Parsed(parse, "|".join(values))


def output(*extensions: str) -> Parsed:
    """A file to write, with one of ``extensions``, in a writable folder: checked before any work."""
    return Parsed(lambda s: str(inputs.output_path("value", s, extensions)), "|".join(e.lstrip(".") for e in extensions))


ANGLE = Parsed(lambda s: inputs.angle("amplitude", s), "angle")
#: An amplitude taken exactly: ``0 <= alpha < pi`` on the exact value (its double may be pi).
EXACT_ANGLE = Parsed(lambda s: inputs.exact_angle("amplitude", s), "angle")
POSITIVE = Parsed(lambda s: inputs.positive("value", s), "number")
FLOAT = Parsed(lambda s: float(inputs.real("value", s)), "number")
POSITIVE_LIST = Parsed(lambda s: inputs.positive_list("value", s), "list")
METHOD = Parsed(lambda s: inputs.method("method", s).name, "method")
FIGURE = output(".png", ".svg", ".pdf")
#: A length > 0 with an optional unit (``75cm``), in metres, kept exactly.
LENGTH = Parsed(lambda s: inputs.length("length", s), "length")
#: A time > 0 (a step, a period) with an optional unit (``10ms``), in seconds.
DURATION = Parsed(lambda s: float(inputs.duration("value", s)), "time")
#: A start or end time, any sign, with an optional unit (``2s``), in seconds.
INSTANT = Parsed(lambda s: float(inputs.instant("value", s)), "time")
#: Times > 0 separated by commas or spaces: ``1e-2,1e-3`` or ``10ms 1ms``.
DURATION_LIST = Parsed(
    lambda s: [float(x) for x in inputs.parse_list("value", s, inputs.duration,
                                                   "a list of numbers > 0 such as 1e-2,1e-3 or 10ms,1ms")],
    "list")


def json_option(f: Callable) -> Callable:
    return click.option("--json", "as_json", is_flag=True, help="Print one JSON document on stdout.")(f)


def g_option(f: Callable) -> Callable:
    return click.option(
        "-g", "--g", "g", type=POSITIVE, default=G_TEXT, show_default=True, help="Gravitational acceleration, m/s^2."
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
    from ..core.atomic import check_writable
    from ..core.extras import require

    check_writable(name, path)
    require("matplotlib", f"--{name}")


def save_plot(draw: Callable, path, size: tuple[float, float] = (6.4, 4.2)) -> None:
    """Call ``draw(ax)`` on a fresh figure and save it atomically (format from the extension).

    A ``Figure`` made without pyplot: no backend switch, no figure left in pyplot's list.
    """
    from ..core.atomic import save_figure
    from ..core.extras import require

    figure = require("matplotlib.figure", "drawing plots")
    fig = figure.Figure(figsize=size, layout="constrained")
    draw(fig.subplots())
    save_figure(fig, path, dpi=150)
