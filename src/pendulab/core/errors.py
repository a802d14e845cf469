"""Exceptions of pendulab.

Every bad input raises :class:`InputError` (a ``ValueError``) whose message names the
argument, the value received and the allowed range; every numerical failure raises a
:class:`NumericalError` subclass with a message that says what to change. The CLI turns
both into one line on stderr and exit status 2; the web API turns an ``InputError`` into
status 422 naming its field.

``NumericalError`` is deliberately not a ``ValueError``: code that catches ``ValueError``
for bad input must not swallow a failed computation, and code that expects a numerical
failure (no return to ``P``) must not hide a bug that raised ``ValueError``.
"""
from __future__ import annotations


class PendulabError(Exception):
    """Base class of the project's errors."""


class InputError(PendulabError, ValueError):
    """A value outside its allowed range.

    Parameters
    ----------
    name : str
        The argument's name as the library spells it (``t_max``); the CLI shows it as
        its option (``--t-max``), the web API as its query field.
    value : object
        The value received (shown as written; a long or unprintable text is shortened).
    allowed : str
        The allowed range, in words (``"a finite number > 0"``).
    mentions : tuple of str
        Other arguments that ``allowed`` names (every occurrence of the word) by the library's spelling (``"t_max"`` in
        ``">= t_max/1e5"``): the CLI writes them as its options (``--t-max``).
    alternative : InputError, optional
        The same limit stated for another argument (a step count too large blames
        ``step``; its alternative blames ``t_max``): the CLI blames that one instead when
        the person typed it and left this one at its default.
    index : tuple of int, optional
        Where ``value`` lies in an array argument: the first bad element
        (``amplitude[3] = 4 is not allowed``).
    """

    def __init__(self, name: str, value: object, allowed: str, *, mentions: tuple[str, ...] = (),
                 alternative: InputError | None = None, index: tuple[int, ...] | None = None):
        self.name = name
        self.value = value
        self.allowed = allowed
        self.mentions = mentions
        self.alternative = alternative
        self.index = index
        where = name if index is None else f"{name}[{', '.join(map(str, index))}]"
        super().__init__(f"{where} = {shown_value(value)} is not allowed: must be {allowed}")


def shown_value(value: object) -> str:
    """A value as a message shows it: a float as its shortest repr without a trailing ``.0``
    (``1`` typed shows as ``1``), anything else as ``str``."""
    if isinstance(value, float):  # numpy's float64 too, whose repr names its type
        text = repr(float(value))
        return text[:-2] if text.endswith(".0") else text
    return str(value)


def shown(text: object) -> str:
    """``text`` as an error message shows it: as typed when short and printable, else quoted
    (no terminal escapes echoed)."""
    s = str(text)
    if not s:
        return "(empty)"
    if len(s) > 40:
        return repr(s[:37] + "...")
    return s if s and s.isprintable() and s == s.strip() else repr(s)


def printable(text: object) -> str:
    """``text`` whole, each control character (a terminal escape in a path) written as its
    escape (``\\x1b``): what a line on a terminal may print of a name."""
    return "".join(c if c.isprintable() or c == " " else c.encode("unicode_escape").decode("ascii")
                   for c in str(text))


class NumericalError(PendulabError):
    """A computation that cannot give the asked-for result (no sign change, no convergence)."""


class NoReturnError(NumericalError):
    """The simulated pendulum does not come back to P = (alpha, 0) within t_max.

    ``t_max``: the end of the simulated interval (None where no interval helps, as for an
    amplitude whose motion underflows); ``suggested_t_max``: one that holds the return.
    """

    def __init__(self, message: str, *, t_max: float | None = None, suggested_t_max: float | None = None):
        super().__init__(message)
        self.t_max = t_max
        self.suggested_t_max = suggested_t_max


class LeftOscillationError(NumericalError):
    """The discrete pendulum went over the top (``|theta| >= pi``): no period to find.

    ``t``: the time of the first point over the top (``t0 + j h``), so a caller needs no
    second simulation to find it.
    """

    def __init__(self, message: str, *, t: float | None = None):
        super().__init__(message)
        self.t = t


class UntrustedError(NumericalError):
    """The simulation returns to P, but its numbers cannot be trusted near the separatrix.

    ``max_energy_drift``: its energy error at the return; ``separatrix_distance``: the energy
    that takes the pendulum over the top (both per unit ``m l^2``, 1/s^2).
    """

    def __init__(self, message: str, *, max_energy_drift: float, separatrix_distance: float):
        super().__init__(message)
        self.max_energy_drift = max_energy_drift
        self.separatrix_distance = separatrix_distance


class MissingExtraError(ImportError):
    """An optional dependency that a command or function needs is not installed.

    The message is one line naming the package and the extra that installs it, e.g.
    ``drawing plots needs matplotlib, which is not installed: pip install 'pendulab[report]'``.
    """

