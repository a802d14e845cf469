"""Every value a person types, parsed in one place.

The CLI's parameter types (:mod:`pendulab.cli._common`) and the web API's query
parameters (:mod:`pendulab.web.parameters`) both call these functions, so a value is judged the
same way wherever it is typed. Each function takes the argument's ``name`` and the text,
and returns the value or raises :class:`~pendulab.core.errors.InputError` naming the argument,
the text (shortened if long, quoted if unprintable) and what is allowed.

The grammar
-----------
number
    ``3.5``, ``-2``, ``.5``, ``2e-3``, ``1/3``: ASCII digits only (``１`` or ``²`` are
    refused everywhere), kept exactly (:class:`~pendulab.core.exact.Exact`). At most
    :data:`MAX_TEXT` characters and a decimal exponent of at most :data:`MAX_EXPONENT`:
    the exact value is then built in microseconds (``1e-99999999`` would never finish).
    A number whose double overflows, or is subnormal where a positive number is asked
    for, is refused: the library would compute with infinity or with lost digits.
angle
    ``0.785``, ``0.785rad``, ``pi/4``, ``4pi/5``, ``4*pi/5``, ``π/4``, ``45deg``,
    ``45 degrees``, ``45°``; radians unless a unit says otherwise.
quantity
    a number with an optional unit suffix: ``115.2cm``, ``1.152 m``, ``2ms``.
list
    items separated by commas, spaces, or both (``1e-2,1e-3``, ``1e-2 1e-3``,
    ``1e-2, 1e-3``); an empty item (``1e-2,,1e-3``, a trailing comma) is refused.
student numbers
    a list (as above) of positive integers of 1 to 18 ASCII digits.
method
    a name of :mod:`pendulab.core.methods` (``taylor2``, ``rk4``, ``verlet``, ``taylor:P``).
output path
    a file name with one of the allowed extensions, in an existing writable folder:
    checked before any work is done.
"""
from __future__ import annotations

import math
import os
import re
from collections.abc import Callable, Iterable
from fractions import Fraction
from pathlib import Path
from typing import TypeVar, cast

from .cases import EXAMPLE_GROUP
from .errors import InputError, shown
from .exact import Exact, below_pi

T = TypeVar("T")

#: The longest single value accepted, characters (a double needs at most 25).
MAX_TEXT = 64
#: The longest list accepted, characters.
MAX_LIST_TEXT = 4096
#: The largest decimal exponent accepted (``1e400`` is already far beyond the doubles).
MAX_EXPONENT = 400
#: The most items in one list.
MAX_ITEMS = 1000
#: Digits of one student number.
MAX_STUDENT_DIGITS = 18
#: The smallest positive normal double and the largest double.
TINY = 2.2250738585072014e-308
HUGE = 1.7976931348623157e308

_NUM = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_FLAGS = re.ASCII | re.IGNORECASE
_EXPONENT = re.compile(r"[eE]([+-]?[0-9]+)$", re.ASCII)
_RATIO = re.compile(rf"(?P<num>{_NUM})(?:\s*/\s*(?P<den>{_NUM}))?", _FLAGS)
_PI_FORM = re.compile(
    rf"(?P<num>{_NUM}|[+-])?\s*\*?\s*(?:pi|π)\s*(?:\*\s*(?P<mul>{_NUM}))?\s*(?:/\s*(?P<den>{_NUM}))?", _FLAGS
)
_DEG_FORM = re.compile(rf"(?P<num>{_NUM}(?:\s*/\s*{_NUM})?)\s*(?:deg|degrees?|°)", _FLAGS)
_RAD_FORM = re.compile(rf"(?P<num>{_NUM}(?:\s*/\s*{_NUM})?)\s*(?:rad|radians?)", _FLAGS)
_QUANTITY = re.compile(rf"(?P<num>{_NUM})\s*(?P<unit>[a-z]*)", _FLAGS)
#: What separates the items of a list: commas, spaces, or both.
SEPARATOR = re.compile(r"\s*,\s*|\s+")
_ANY_EXPONENT = re.compile(r"(?<=[0-9.])[eE]([+-]?[0-9]+)", re.ASCII)

NUMBER_WORDS = "a number such as 3.5, 2e-3 or 1/3"
#: The ranges of the number parsers, with their bounds: a finite real, a positive number
#: (its double normal, so it keeps all 53 bits), and a non-negative one.
REAL_RANGE = f"0 or of magnitude between 1e-{MAX_EXPONENT} and {HUGE:.4g}"
POSITIVE_RANGE = f"between {TINY:.4g} and {HUGE:.4g}"
NON_NEGATIVE_RANGE = f"0 or between {TINY:.4g} and {HUGE:.4g}"
ANGLE_WORDS = "an angle such as 0.785, pi/4, 4pi/5, 45deg or 45°"


# --------------------------------------------------------------------------- text
def clean(name: str, text: object, allowed: str, max_len: int = MAX_TEXT) -> str:
    """The stripped text, or an error: missing, empty, too long, or with non-ASCII digits."""
    if text is None:
        raise InputError(name, "(missing)", allowed)
    s = str(text).strip()
    if not s:
        raise InputError(name, "(empty)", allowed)
    if len(s) > max_len:
        raise InputError(name, shown(s), f"{allowed} (at most {max_len} characters)")
    if any(c.isnumeric() and not c.isascii() for c in s):
        raise InputError(name, shown(s), f"{allowed}, written with the digits 0-9")
    return s


def _decimal(literal: str) -> Fraction:
    """The exact value of one decimal literal; ``ValueError`` past the exponent cap."""
    m = _EXPONENT.search(literal)
    if m and abs(int(m.group(1))) > MAX_EXPONENT:
        raise ValueError(literal)
    return Fraction(literal)


def _beyond_cap(text: str) -> bool:
    """Whether ``text`` writes a decimal exponent beyond :data:`MAX_EXPONENT` (``1e-99999999``)."""
    return any(abs(int(e)) > MAX_EXPONENT for e in _ANY_EXPONENT.findall(text))


def _ratio(text: str) -> Fraction | None:
    """``a`` or ``a/b`` exactly; None when ``text`` is not of that form (or ``b = 0``)."""
    m = _RATIO.fullmatch(text)
    if not m:
        return None
    try:
        value = _decimal(m["num"])
        if m["den"] is not None:
            den = _decimal(m["den"])
            if den == 0:
                return None
            value /= den
    except ValueError:
        return None
    return value


def is_number(text: object) -> bool:
    """Whether ``text`` is a plain number or ratio (``144``, ``1/3``), no unit, no pi."""
    return _ratio(str(text).strip()) is not None


# --------------------------------------------------------------------------- numbers
def real(name: str, text: object, allowed: str = NUMBER_WORDS, bounds: str = REAL_RANGE) -> Exact:
    """A finite real number (``3.5``, ``-2e-3``, ``1/3``), kept exactly.

    A number beyond the exponent cap or whose double overflows is refused with
    ``bounds``, the caller's range in words.
    """
    s = clean(name, text, allowed)
    value = _ratio(s)
    if value is None:
        raise InputError(name, shown(s), f"{allowed}, {bounds}" if _beyond_cap(s) else allowed)
    x = Exact(value, 0, s)
    if not math.isfinite(float(x)):
        raise InputError(name, shown(s), f"{allowed}, {bounds}")
    return x


def positive(name: str, text: object, allowed: str = "a finite number > 0") -> Exact:
    """A number > 0 whose double is normal: between 2.2e-308 and 1.8e308."""
    x = real(name, text, allowed, POSITIVE_RANGE)
    if x.coef <= 0:
        raise InputError(name, shown(x.text), allowed)
    if not TINY <= float(x) <= HUGE:
        raise InputError(name, shown(x.text), f"{allowed}, {POSITIVE_RANGE}")
    return x


def non_negative(name: str, text: object, allowed: str = "a finite number >= 0") -> Exact:
    """A number >= 0: 0, or a number between 2.2e-308 and 1.8e308."""
    x = real(name, text, allowed, NON_NEGATIVE_RANGE)
    if x.coef < 0:
        raise InputError(name, shown(x.text), allowed)
    if x.coef != 0 and not TINY <= float(x) <= HUGE:
        raise InputError(name, shown(x.text), f"{allowed}, {NON_NEGATIVE_RANGE}")
    return x


def integer(name: str, text: object, low: int, high: int) -> int:
    """An integer in ``[low, high]``; ``1e5`` is the integer 100000, ``2.5`` is refused."""
    allowed = f"an integer in [{low}, {high}]"
    s = clean(name, text, allowed)
    value = _ratio(s)
    if value is None or value.denominator != 1 or not low <= value <= high:
        raise InputError(name, shown(s), allowed)
    return int(value)


def quantity(name: str, text: object, units: dict[str, Fraction], default_unit: str, strict: bool) -> Exact:
    """A number with an optional unit suffix, in the first unit of ``units`` (SI).

    ``quantity("length", "115.2cm", {"m": 1, "cm": 1/100}, "m", True)`` is 1.152 m exactly.
    ``strict``: ``> 0``; else ``>= 0``.
    """
    allowed = (f"a finite number {'> 0' if strict else '>= 0'}, "
               f"in {' or '.join(units)} (default {default_unit})")
    si = next(iter(units))
    # The range rules of positive(), on the value in SI units.
    bounds = f"{'' if strict else '0 or '}between {TINY:.4g} {si} and {HUGE:.4g} {si}"
    s = clean(name, text, allowed)
    m = _QUANTITY.fullmatch(s)
    unit = (m["unit"] or default_unit) if m else None
    if not m or unit not in units:
        raise InputError(name, shown(s), allowed)
    try:
        value = _decimal(m["num"]) * units[unit]
    except ValueError:  # beyond the exponent cap
        raise InputError(name, shown(s), f"{allowed}, {bounds}") from None
    x = Exact(value, 0, s)
    if value < 0 or (strict and value == 0):
        raise InputError(name, shown(s), allowed)
    if value != 0 and not TINY <= float(x) <= HUGE:
        raise InputError(name, shown(s), f"{allowed}, {bounds}")
    return x


# --------------------------------------------------------------------------- lengths and times
#: Units a typed length or time may carry, as exact factors to metres and seconds.
LENGTH_UNITS = {"m": Fraction(1), "cm": Fraction(1, 100), "mm": Fraction(1, 1000)}
TIME_UNITS = {"s": Fraction(1), "ms": Fraction(1, 1000)}
_UNIT_FORM = re.compile(rf"(?P<num>{_NUM}(?:\s*/\s*{_NUM})?)\s*(?P<unit>[a-z]+)", _FLAGS)


def length(name: str, text: object) -> Exact:
    """A length > 0 in metres, kept exactly: ``2.08``, ``1/3``, ``75cm``, ``0.75m``, ``750mm``."""
    return _in_units(name, text, LENGTH_UNITS, positive, "a finite number > 0", _POSITIVE_BOUNDS)


def duration(name: str, text: object) -> Exact:
    """A time > 0 in seconds (a step, a period), kept exactly: ``0.01``, ``10ms``, ``2s``."""
    return _in_units(name, text, TIME_UNITS, positive, "a finite number > 0", _POSITIVE_BOUNDS)


def instant(name: str, text: object) -> Exact:
    """A time in seconds, of any sign (a start or an end time): ``2.1``, ``2s``, ``-500ms``."""
    return _in_units(name, text, TIME_UNITS, real, NUMBER_WORDS, _REAL_BOUNDS)


_POSITIVE_BOUNDS = f"between {TINY:.4g} {{u}} and {HUGE:.4g} {{u}}"
_REAL_BOUNDS = f"0 or of magnitude between 1e-{MAX_EXPONENT} {{u}} and {HUGE:.4g} {{u}}"


def _in_units(name: str, text: object, units: dict[str, Fraction],
              parse: Callable[[str, object, str], Exact], words: str, bounds: str) -> Exact:
    """``parse`` of a number that may carry one of ``units``: the value in the first unit.

    The number is checked by ``parse`` as typed; with a unit, its value in the first unit
    is checked again against the doubles' range. The messages show the text with its unit.
    """
    si = next(iter(units))
    allowed = f"{words}, optionally with a unit: {', '.join(units)} (default {si})"
    ranged = f"{allowed}, {bounds.format(u=si)}"
    s = clean(name, text, allowed)
    m = _UNIT_FORM.fullmatch(s)
    number_text, factor = (s, Fraction(1)) if m is None else (m["num"], units.get(m["unit"]))
    if factor is None:
        raise InputError(name, shown(s), allowed)
    try:
        number = parse(name, number_text, allowed)
    except InputError as exc:  # out of range, or not a number of the kind asked for
        raise InputError(name, shown(s), allowed if exc.allowed == allowed else ranged) from None
    if m is None:
        return number
    x = Exact(number.coef * factor, 0, s)
    if x.coef != 0 and not TINY <= abs(float(x)) <= HUGE:
        raise InputError(name, shown(s), ranged)
    return x


# --------------------------------------------------------------------------- angles
def angle_value(name: str, text: object) -> Exact:
    """Any angle, exactly, in radians: ``0.785``, ``pi/4``, ``4pi/5``, ``45deg``, ``45°``."""
    s = clean(name, text, ANGLE_WORDS)
    try:
        if m := _PI_FORM.fullmatch(s):
            coef = Fraction(1)
            if m["num"] in ("+", "-"):
                coef = Fraction(-1 if m["num"] == "-" else 1)
            elif m["num"] is not None:
                coef *= _decimal(m["num"])
            if m["mul"] is not None:
                coef *= _decimal(m["mul"])
            if m["den"] is not None:
                coef /= _decimal(m["den"])
            return Exact(coef, 1, s)
        if m := _DEG_FORM.fullmatch(s):
            value = _ratio(m["num"])
            if value is not None:
                return Exact(value / 180, 1, s)
        elif m := _RAD_FORM.fullmatch(s):
            value = _ratio(m["num"])
            if value is not None:
                return Exact(value, 0, s)
        elif (value := _ratio(s)) is not None:
            return Exact(value, 0, s)
    except (ValueError, ZeroDivisionError):
        pass
    cap = f", with decimal exponents in [-{MAX_EXPONENT}, {MAX_EXPONENT}]" if _beyond_cap(s) else ""
    raise InputError(name, shown(s), ANGLE_WORDS + cap)


def angle(name: str, text: object, open_low: bool = False) -> Exact:
    """An angle in ``[0, pi)`` (``open_low``: in ``(0, pi)``), checked on the exact value.

    ``pi`` itself written exactly (``pi``, ``180deg``) rounds to the double below pi; it
    is refused as written, and so is any value whose double is not below ``math.pi``.
    """
    lo = "(0" if open_low else "[0"
    allowed = f"an angle in {lo}, pi) rad such as 0.785, pi/4, 4pi/5, 45deg or 45°"
    try:
        x = angle_value(name, text)
    except InputError as exc:
        raise InputError(name, exc.value, allowed + exc.allowed[len(ANGLE_WORDS):]) from None
    if x.coef < 0 or (open_low and x.coef == 0) or (x.pi_power == 1 and x.coef >= 1):
        raise InputError(name, shown(x.text), allowed)
    value = float(x)
    if not (0 <= value < math.pi) or (open_low and value == 0):
        raise InputError(name, shown(x.text), allowed)
    return x


def exact_angle(name: str, text: object) -> Exact:
    """An angle in ``[0, pi)`` decided on the exact value alone, never on its double.

    ``0.9999999999999999999999999pi`` is accepted although its double rounds to pi:
    for the commands that compute with the exact input (certified digits). A multiple of
    pi is judged by its rational coefficient, radians by a certified comparison with pi
    (Arb balls).
    """
    allowed = "an angle in [0, pi) rad such as 0.785, pi/4, 4pi/5, 45deg or 45°"
    try:
        x = angle_value(name, text)
    except InputError as exc:
        raise InputError(name, exc.value, allowed + exc.allowed[len(ANGLE_WORDS):]) from None
    if x.coef < 0 or not below_pi(x):
        raise InputError(name, shown(x.text), allowed)
    return x


def parse_number(name: str, text: str) -> Exact:
    """A plain real number or ratio, ``2.0800838231`` or ``1/3``, exactly (:func:`real`)."""
    return real(name, text)


def parse_angle(name: str, text: str | float) -> Exact:
    """An angle: ``0.785``, ``pi/4``, ``4pi/5``, ``4*pi/5``, ``45deg``, ``45°``; a float is
    taken exactly (its binary value).

    Returns the exact angle in radians; the range is not checked here (:func:`angle`
    checks it).
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return Exact.of(text)
    return angle_value(name, text)


# --------------------------------------------------------------------------- lists
def items(name: str, text: object, allowed: str, max_items: int = MAX_ITEMS) -> list[str]:
    """The items of a list separated by commas, spaces or both; no empty item."""
    s = clean(name, text, allowed, MAX_LIST_TEXT)
    parts = SEPARATOR.split(s)
    if any(not p for p in parts):
        raise InputError(name, shown(s), f"{allowed}, with no empty item (doubled or trailing comma)")
    if len(parts) > max_items:
        raise InputError(name, f"{len(parts)} items", f"{allowed}, at most {max_items} items")
    return parts


def parse_list(name: str, text: object, parse: Callable[[str, str], T], allowed: str,
               max_items: int = MAX_ITEMS) -> list[T]:
    """``[parse(name, item) for item in items(...)]``; an item's error names the item, in the list's words."""
    out = []
    for part in items(name, text, allowed, max_items):
        try:
            out.append(parse(name, part))
        except InputError as exc:
            why = allowed if exc.allowed in allowed else f"{allowed}; this item is not ({exc.allowed})"
            raise InputError(name, exc.value, why) from None
    return out


def positive_list(name: str, text: object, max_items: int = MAX_ITEMS) -> list[float]:
    """Numbers > 0 separated by commas or spaces: ``1e-2,1e-3,1e-4``."""
    return [float(x) for x in parse_list(name, text, positive, "a list of numbers > 0 such as 1e-2,1e-3",
                                         max_items)]


def integer_list(name: str, text: object, low: int, high: int, max_items: int = MAX_ITEMS) -> list[int]:
    """Integers in ``[low, high]`` separated by commas or spaces: ``1,10,1e3``."""
    return parse_list(name, text, lambda n, s: integer(n, s, low, high),
                      f"a list of integers in [{low}, {high:.0e}]", max_items)


def students(name: str, texts: object) -> tuple[int, ...]:
    """Student numbers: ``262,407,634``, ``262 407 634``, or several texts of either form.

    Each is a positive integer of 1 to :data:`MAX_STUDENT_DIGITS` ASCII digits.
    """
    allowed = (f"student numbers: positive integers of 1 to {MAX_STUDENT_DIGITS} digits 0-9, "
               f"separated by commas or spaces, such as {','.join(map(str, EXAMPLE_GROUP))}")
    if isinstance(texts, (list, tuple)):
        texts = " ".join(str(t).strip() for t in texts)
    parts = items(name, texts, allowed, 100)
    for p in parts:
        if not (p.isascii() and p.isdigit() and len(p) <= MAX_STUDENT_DIGITS and int(p) > 0):
            raise InputError(name, shown(p), allowed)
    return tuple(int(p) for p in parts)


#: The longest student name (characters) on a report's cover or in a key's groups file.
MAX_NAME = 80


def names(name: str, text: object, count: int) -> tuple[str, ...]:
    """Student names separated by ``;``, one per student number (``count`` of them), in the
    order of the numbers: ``"Ana Sá; João Simões; 李明"``. Any printable Unicode, and the
    zero-width joiner and non-joiner that Persian and Indic names need; each name is
    stripped and has 1 to :data:`MAX_NAME` characters, with at most :data:`MAX_MARKS`
    combining marks on one letter (a stack taller than a line would cross the page's lines).
    """
    allowed = (f"{count} name{'s' if count != 1 else ''} separated by ';', one per student number, "
               f"each of 1 to {MAX_NAME} printable characters, at most {MAX_MARKS} accents on a letter")
    if text is None:
        raise InputError(name, "(missing)", allowed)
    s = str(text)
    if len(s) > (MAX_NAME + 2) * max(count, 1):
        raise InputError(name, shown(s), allowed)
    parts = tuple(" ".join(p.split()) for p in s.split(";"))
    if len(parts) != count:
        raise InputError(name, shown(s.strip()), f"{allowed} ({len(parts)} given)")
    for p in parts:
        if not p or len(p) > MAX_NAME or not _name_text(p):
            raise InputError(name, shown(p), allowed)
    return parts


#: The most combining marks on one letter of a name (Vietnamese stacks two, some Indic scripts three or four).
MAX_MARKS = 4
#: Zero-width joiner and non-joiner: not "printable" to Python, a letter's shape in Persian, Arabic, Indic names.
_JOINERS = frozenset("\u200c\u200d")


def _name_text(text: str) -> bool:
    """Printable characters and joiners, no letter with more than :data:`MAX_MARKS` combining marks."""
    import unicodedata

    run = 0
    for c in text:
        if not (c.isprintable() or c in _JOINERS):
            return False
        run = run + 1 if unicodedata.combining(c) else 0
        if run > MAX_MARKS:
            return False
    return True


# --------------------------------------------------------------------------- names, paths
def method(name: str, text: object):
    """An integrator of :mod:`pendulab.core.methods`: ``taylor2``, ``rk4``, ``verlet``, ``taylor:P``."""
    from . import methods

    s = clean(name, text, methods.allowed())
    return methods.resolve(s, name)


def angle_range(name: str, text: object, max_count: int) -> list[float]:
    """``START:STOP:COUNT`` (COUNT evenly spaced angles, ends included) or one angle; in (0, pi)."""
    allowed = (f"START:STOP:COUNT with 0 < START < STOP < pi and COUNT an integer in [2, {max_count}], "
               "or one angle in (0, pi), such as 1deg:179deg:1000")
    s = clean(name, text, allowed)
    parts = s.split(":")
    try:
        if len(parts) == 1:
            return [float(angle(name, s, open_low=True))]
        if len(parts) == 3:
            start = float(angle(name, parts[0], open_low=True))
            stop = float(angle(name, parts[1], open_low=True))
            count = integer(name, parts[2], 2, max_count)
            if not start < stop:
                raise InputError(name, shown(s), allowed + " (the range is empty or reversed)")
            step = (stop - start) / (count - 1)  # numpy.linspace's arithmetic, bit for bit
            return [start + i * step for i in range(count - 1)] + [stop]
    except InputError as exc:
        if "reversed" in exc.allowed:
            raise
    raise InputError(name, shown(s), allowed)


def path_text(name: str, text: object, allowed: str = "a file path") -> str:
    """A file path as typed: not empty, no NUL character, at most 4096 characters."""
    s = "" if text is None else os.fspath(cast("str | os.PathLike[str]", text))  # TypeError for others, as before
    if not s.strip():
        raise InputError(name, "(empty)", allowed)
    if len(s) > 4096 or "\0" in s:
        raise InputError(name, shown(s), allowed)
    return s


def output_path(name: str, text: object, extensions: Iterable[str]) -> Path:
    """A file to write: one of ``extensions`` (``".png"``), in an existing writable folder.

    Checked before any work, so a run never computes for minutes and then fails to save.
    """
    from .atomic import check_writable

    exts = tuple(e.lower() for e in extensions)
    allowed = f"a file name ending in {', '.join(exts[:-1]) + ' or ' if len(exts) > 1 else ''}{exts[-1]}"
    s = path_text(name, text, allowed)
    try:
        p = check_writable(name, s)
    except OSError as exc:  # a name too long for the file system, and the like
        raise InputError(name, shown(s), f"{allowed}, a path this system accepts ({exc.strerror})") from None
    if p.suffix.lower() not in exts:
        raise InputError(name, shown(s), allowed)
    return p


#: The latest ``SOURCE_DATE_EPOCH`` accepted: 9999-12-31 23:59:59 UTC, the last second
#: Python's ``datetime`` (which matplotlib uses for a figure's date) can hold.
MAX_EPOCH = 253402300799


def source_date_epoch(text: str | None) -> int | None:
    """The ``SOURCE_DATE_EPOCH`` environment variable (reproducible-builds.org): seconds since
    1970-01-01 UTC as ASCII digits, in ``[0, MAX_EPOCH]``; None where unset or empty (as
    matplotlib reads it). Anything else is refused here, before matplotlib or Typst sees it."""
    if text is None or text == "":
        return None
    s = text.strip()
    if not (s.isascii() and s.isdigit() and len(s) <= 12 and int(s) <= MAX_EPOCH):
        raise InputError("SOURCE_DATE_EPOCH", shown(text),
                         f"an integer number of seconds since 1970-01-01 UTC, 0 to {MAX_EPOCH} (or unset)")
    return int(s)
