"""The teacher's answer key: every group's answers to problem 3, and the common answers once.

Each group's pendulum length comes from its student numbers (problem 3(b)), so problem 3
differs between groups; problems 1, 2, 4 and 5 do not. :func:`answer_key` computes both
from :mod:`pendulab.jobs.problems` as plain data; :func:`pendulab.report.key.write_key` writes it
as CSV, JSON or a PDF table.
"""
from __future__ import annotations

import math
import os
import re
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path
from typing import Any

from ..core import inputs
from ..core.errors import InputError

#: Output formats by file extension.
FORMATS = ("csv", "json", "pdf")
#: The largest groups file read (a class of thousands of groups is a few hundred kB):
#: a file that is not a regular file (a pipe, a device) is read up to this many bytes too.
MAX_FILE_BYTES = 10**7
#: The most groups in one key (a class is tens of groups): a few seconds of work at most
#: (a group's cost: ``benchmarks/key_cost.py``).
MAX_GROUPS = 1000
#: Seconds a pipe or device may stay silent while its groups are read (a named pipe that
#: no program writes to is empty at once; a terminal, or a writer that never writes, waits).
READ_TIMEOUT = 10.0


#: A line's names follow its numbers after this separator: ``262, 407, 634 | Ana; João; Maria``.
NAMES_SEPARATOR = "|"


@dataclass(frozen=True)
class Entry:
    """One group of the class: its student numbers, their names (optional) and its line."""

    students: tuple[int, ...]
    names: tuple[str, ...] | None = None
    line: int | None = None


def _has_letters(text: str) -> bool:
    return any(ch.isalpha() for ch in text)


def _cells(line: str) -> list[str]:
    """The cells of a spreadsheet row: split at ``;`` when the line has one (a Portuguese
    locale's list separator), else at ``,``; quotes as the csv module reads them."""
    import csv

    delimiter = ";" if ";" in re.sub(r'"[^"]*"', "", line) else ","  # outside quoted cells
    row = next(csv.reader([line], delimiter=delimiter, skipinitialspace=True), [])
    return [c.strip() for c in row]


_NUMERIC_CELL = re.compile(r"[0-9][0-9\s,;]*")


def _parse_line(line: str) -> tuple[tuple[int, ...], tuple[str, ...] | None]:
    """One group's numbers and names (see :func:`parse_entries`); InputError if the line is bad."""
    numbers, sep, names_text = line.partition(NAMES_SEPARATOR)
    if sep or not _has_letters(line):
        # a spreadsheet's row ends in empty cells: "262;407;634;;"
        students = inputs.students("groups", numbers.strip().rstrip(",; \t").replace(";", ","))
        names = inputs.names("groups", names_text, len(students)) if sep else None
        return students, names
    cells = [c for c in _cells(line) if c]  # a spreadsheet pads its rows with empty cells
    k = 0
    while k < len(cells) and _NUMERIC_CELL.fullmatch(cells[k]):
        k += 1
    if k == 0:
        raise InputError("groups", inputs.shown(line), "student numbers first, then the names")
    students = inputs.students("groups", " ".join(c.replace(";", " ") for c in cells[:k]))
    rest = cells[k:]
    if len(rest) == 1 and ";" in rest[0]:  # one quoted cell "Ana Sá; João Simões"
        rest = rest[0].split(";")
    return students, inputs.names("groups", ";".join(rest), len(students))


def parse_entries(text: str, source: str = "groups") -> list[Entry]:
    """One group per line, as people and spreadsheets write it.

    A line holds the group's student numbers separated by commas, semicolons or spaces,
    then optionally its students' names, one per number and in their order: after ``|``
    and separated by ``;`` (``262, 407, 634 | Ana Sá; João Simões``), or as further
    cells of a spreadsheet row, separated by ``;`` or ``,`` (``262;407;634;Ana Sá;João
    Simões;Maria Luís``, ``"262 407 634","Ana Sá; João Simões; Maria Luís"``). The first
    line with words and no digit is a header row (``students;names``) and is skipped.

    Blank lines, empty cells and ``#`` comments (whole lines or line ends) are skipped. A
    bad line raises :class:`~pendulab.core.errors.InputError` naming ``source`` and its
    line number; a file with no group at all is refused too. Repeated students are kept
    as written (:func:`repeated_students` finds them).
    """
    from ..numerics.group import group_length

    entries: list[Entry] = []
    header_seen = False
    text = text.removeprefix("\ufeff")  # the byte order mark that Notepad and Excel write
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line or not line.strip(",; \t"):
            continue
        if (not entries and not header_seen and NAMES_SEPARATOR not in line and _has_letters(line)
                and not any(ch.isdigit() for ch in line)):
            header_seen = True  # a header row: "students", "números;nomes"
            continue
        if len(entries) == MAX_GROUPS:
            raise InputError("groups", source, f"a file of at most {MAX_GROUPS} groups (line {number} "
                                               f"starts group {MAX_GROUPS + 1}); split the class into several keys")
        try:
            students, names = _parse_line(line)
            group_length(students)
        except InputError as exc:
            raise InputError("groups", f"{source} line {number}: {inputs.shown(raw.strip())}", exc.allowed) from None
        entries.append(Entry(students, names, number))
    if not entries:
        raise InputError("groups", source, "a file with at least one group (one line of student numbers)")
    return entries


def parse_groups(text: str, source: str = "groups") -> list[tuple[int, ...]]:
    """The student numbers of each group of ``text`` (see :func:`parse_entries`)."""
    return [e.students for e in parse_entries(text, source)]


def read_entries(path: str | os.PathLike) -> list[Entry]:
    """The groups of the file ``path`` (see :func:`parse_entries`); ``-`` is standard input.

    Whatever ``path`` is, at most :data:`MAX_FILE_BYTES` bytes are read: a regular file
    is refused by its size, a pipe or a device (``/dev/zero``) once it gives more; a named
    pipe is opened without waiting for a writer, and one that stays silent for
    :data:`READ_TIMEOUT` seconds is refused. A UTF-8 byte order mark is skipped.
    """
    shown = inputs.shown(str(path))
    try:
        data = _read_capped(str(path))
        text = data.decode("utf-8")
    except TimeoutError:  # an OSError: told first
        raise InputError("groups", shown, f"a file that can be read (nothing came in {READ_TIMEOUT:g} s)") from None
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else type(exc).__name__
        raise InputError("groups", shown, f"a readable UTF-8 text file ({reason})") from None
    except _TooBig:
        raise InputError("groups", shown, f"a file of at most {MAX_FILE_BYTES:.0e} bytes") from None
    return parse_entries(text, str(path))


class _TooBig(Exception):
    """More than :data:`MAX_FILE_BYTES` bytes."""


def _read_capped(path: str) -> bytes:
    """At most :data:`MAX_FILE_BYTES` bytes of ``path`` (``-``: standard input), see :func:`read_groups`."""
    import select
    import stat

    if path == "-":
        try:
            fd = sys.stdin.buffer.fileno()
        except (AttributeError, OSError, ValueError):  # no descriptor (a test's stream; closed at start)
            data = sys.stdin.buffer.read(MAX_FILE_BYTES + 1)
            if len(data) > MAX_FILE_BYTES:
                raise _TooBig from None
            return data
        return _read_fd(fd)
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # a named pipe: no wait for a writer
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(21, "a folder, not a file")
        if stat.S_ISREG(st.st_mode):
            if st.st_size > MAX_FILE_BYTES:  # by its size, before reading it
                raise _TooBig
            os.set_blocking(fd, True)
        chunks: list[bytes] = []
        size = 0
        while size <= MAX_FILE_BYTES:
            try:
                chunk = os.read(fd, min(1 << 20, MAX_FILE_BYTES + 1 - size))
            except BlockingIOError:  # a pipe or device with nothing to read yet
                if not select.select([fd], [], [], READ_TIMEOUT)[0]:
                    raise TimeoutError from None
                continue
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)
            size += len(chunk)
        raise _TooBig
    finally:
        os.close(fd)


def _read_fd(fd: int) -> bytes:
    """At most :data:`MAX_FILE_BYTES` bytes of standard input, waiting at most
    :data:`READ_TIMEOUT` s for each block (``sleep 40 | pendulab key --groups -`` ends, as
    ``/dev/stdin`` does); the descriptor stays blocking (its file is the shell's too)."""
    import select

    chunks: list[bytes] = []
    size = 0
    while size <= MAX_FILE_BYTES:
        if not select.select([fd], [], [], READ_TIMEOUT)[0]:
            raise TimeoutError
        chunk = os.read(fd, min(1 << 20, MAX_FILE_BYTES + 1 - size))
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        size += len(chunk)
    raise _TooBig


def read_groups(path: str | os.PathLike) -> list[tuple[int, ...]]:
    """The student numbers of each group of the file ``path``."""
    return [e.students for e in read_entries(path)]


def duplicates(entries: Sequence[Entry]) -> dict[int, int]:
    """``{line: line of its first listing}`` for every group listed again (the same student
    numbers, in any order)."""
    first: dict[tuple[int, ...], int] = {}
    out = {}
    for i, e in enumerate(entries, start=1):
        line = e.line if e.line is not None else i
        key = tuple(sorted(e.students))
        if key in first:
            out[line] = first[key]
        else:
            first[key] = line
    return out


def listed_again(entries: Sequence[Entry]) -> list[tuple[tuple[int, ...], list[int]]]:
    """Each group listed more than once: its student numbers and every line that lists it
    (the first listing's first), in the order of the first listings. Empty when none is."""
    lines: dict[int, list[int]] = {}
    for line, first in duplicates(entries).items():
        lines.setdefault(first, [first]).append(line)
    by_line = {(e.line if e.line is not None else i): e for i, e in enumerate(entries, start=1)}
    return [(by_line[first].students, ls) for first, ls in lines.items()]


@dataclass(frozen=True)
class Repeated:
    """A student number found more than once: twice or more in the group of ``line``
    (``within``), and in the groups of ``other_lines`` (groups with other numbers: a group
    listed again whole is :func:`duplicates`' case)."""

    student: int
    line: int
    within: int
    other_lines: tuple[int, ...]

    def to_dict(self) -> dict[str, Any]:
        return {"student": self.student, "line": self.line, "within": self.within,
                "other_lines": list(self.other_lines)}


def repeated_students(entries: Sequence[Entry]) -> list[Repeated]:
    """Every student number listed twice in one group (``12121, 21212, 12121``) or in two
    groups of different numbers, once per (student, line), in the order of the file."""
    from collections import Counter

    lines = [e.line if e.line is not None else i for i, e in enumerate(entries, start=1)]
    dup = duplicates(entries)
    where: dict[int, list[int]] = {}
    for e, line in zip(entries, lines):
        if line in dup:  # the same group again: flagged as listed again
            continue
        for n in dict.fromkeys(e.students):
            where.setdefault(n, []).append(line)
    out = []
    for e, line in zip(entries, lines):
        counts = Counter(e.students)
        first = dup.get(line, line)
        for n in dict.fromkeys(e.students):
            others = tuple(x for x in where.get(n, ()) if x != first)
            if counts[n] > 1 or others:
                out.append(Repeated(n, line, counts[n], others))
    return out


def output_format(path: str | os.PathLike) -> str:
    """``csv``, ``json`` or ``pdf`` from the extension of ``path``."""
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in FORMATS:
        raise InputError("output", inputs.shown(str(path)), "a file name ending in .csv, .json or .pdf")
    return ext


def class_path(output: str | os.PathLike) -> Path:
    """Where the class-wide CSV goes beside the per-group ``output``: ``key.csv`` -> ``key-class.csv``."""
    p = Path(output)
    return p.with_name(f"{p.stem}-class{p.suffix}")


@dataclass(frozen=True, eq=False)
class AnswerKey:
    """The answers of every group (problem 3) and the common ones (problems 1, 2, 4, 5)."""

    common: dict[str, Any]
    groups: list[dict[str, Any]]

    def to_dict(self) -> dict[str, Any]:
        """The key as plain data: the answers (what a correct method may give for each is
        :mod:`pendulab.jobs.mark`'s, :func:`pendulab.report.key.document`)."""
        return {"common": self.common, "groups": self.groups}


def _f(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def _time(j: int, h: float) -> float:
    """``t_j = j h`` as the double nearest to the product of ``j`` and ``h`` as written
    (``48 * 0.2`` is the double 9.600000000000001; the time is 9.6)."""
    return float(Decimal(j) * Decimal(repr(h)))


def group_answers(students: Sequence[int]) -> dict[str, Any]:
    """One group's answers to problem 3 as plain data (JSON-ready).

    Times ``t_j`` are given as :func:`_time` (the double nearest to ``j h``).
    """
    from . import problems

    r = problems.problem3(students)
    est = r.plot_estimate
    h = r.plot.step
    bracket = None if est is None else [_time(est.j, h), _time(est.j + 1, h)]
    plot = {
        "step": h,
        "outcome": r.plot_outcome,
        "status": r.plot_status,
        "j": None if est is None else est.j,
        "bracket": bracket,
        "t_hat_inside": None if bracket is None else bracket[0] <= r.t_hat <= bracket[1],
        "left_at": None if r.plot_left_at is None else _time(round(r.plot_left_at / h), h),
        "t_max": r.plot_t_max,
    }
    estimates = [{
        "step": e.step, "j": e.j, "bracket": [_time(e.j, e.step), _time(e.j + 1, e.step)],
        "linear": e.linear, "linear_t_hat_error": abs(e.linear - r.t_hat), "linear_order": _f(lo_),
        "cubic": e.cubic, "cubic_t_hat_error": abs(e.cubic - r.t_hat), "cubic_order": _f(co),
        "cubic_error_estimate": e.cubic_error_estimate,
    } for e, lo_, co in zip(r.estimates, r.linear_orders, r.cubic_orders)]
    ip = r.cubic.interpolation
    c = r.cubic
    interpolation = {
        "step": c.step, "j": c.j,
        # the nodes' t_k as the interpolation used them, fl(k h) as (3)'s program has them (not j h as written)
        "table": [{"node": c.j - 1 + k, "z2": float(ip.z2[k]), "t": float(ip.t[k]),
                   "coefficient": float(ip.coefficients[k])} for k in range(4)],
        "value": ip.value, "error_estimate": ip.error_estimate, "rounding_level": ip.rounding_level,
        "taylor_error": r.taylor_error, "ratio": _f(r.interpolation_ratio),
        "negligible": r.interpolation_negligible,
    }
    return {
        "students": list(r.group.numbers), "sum": r.group.sum, "digits": r.group.digits,
        "length": r.group.length, "length_text": r.group.length_text, "t_hat": r.t_hat,
        "plot": plot, "estimates": estimates, "interpolation": interpolation,
    }


def _floats(a) -> list:
    return [[float(x) for x in row] for row in a] if getattr(a, "ndim", 1) == 2 else [float(x) for x in a]


def _problem4(p4) -> dict[str, Any]:
    f = p4.fit
    return {"t_max": p4.t_max, "points": p4.points, "names": list(f.names), "decimals": f.decimals,
            "normal_matrix": _floats(f.normal_matrix), "normal_rhs": _floats(f.normal_rhs),
            "coefficients": _floats(f.coefficients), "ssd": f.ssd, "max_deviation": f.max_deviation,
            "argmax_deviation": f.argmax_deviation, "below_tolerance": p4.below_tolerance,
            "tolerance": p4.tolerance}


def common_answers() -> dict[str, Any]:
    """Problems 1, 2, 4 (the coursework's 401 points, and the 601 of ``Y_0 .. Y_600``) and 5,
    which are the same for every group."""
    from ..core.cases import PROBLEM4_ALT_T_MAX
    from . import problems

    p1, p2, p4, p5 = problems.problem1(), problems.problem2(), problems.problem4(), problems.problem5()
    p4_alt = problems.problem4(t_max=PROBLEM4_ALT_T_MAX)
    from .coursework import load

    programs = load()
    program5 = programs["problem5.py"].table(programs["agm.py"].t_hat(p5.length, p5.amplitude))
    assert [r[0] for r in program5] == [row.n for row in p5.rows]
    run = p2.run
    return {
        "problem1": {"g": p1.g, "dg_dl": p1.dg_dl, "dg_dT": p1.dg_dT, "abs_error": p1.abs_error,
                     "rel_error": p1.rel_error, "g_min": p1.g_min, "g_max": p1.g_max,
                     "worst_error": p1.worst_error, "significant_digits": p1.significant_digits,
                     "g_text": p1.g_text},
        "problem2": {"interval_deg": list(p2.interval_deg), "x0": p2.x0, "alpha": p2.alpha,
                     "alpha_deg": p2.alpha_deg, "iterates": list(run.iterates),
                     "q": [_f(q) for q in run.q], "q_rounding": list(run.q_rounding),
                     "k_max": run.k_max, "asymptotic_constant": run.asymptotic_constant,
                     "error_estimate": run.error_estimate},
        "problem4": _problem4(p4),
        "problem4_601": _problem4(p4_alt),
        # S_n, its error and rate as problem5.py prints them (the report's digits); the
        # substitution's columns, beyond the coursework, from the engine
        "problem5": {"t_hat": p5.t_hat, "single": program5[0][1], "composite10": program5[1][1],
                     "rows": [{"n": row.n, "estimate": printed[1], "error": printed[2], "rate": printed[3],
                               "substitution_estimate": row.substitution_estimate,
                               "substitution_error": row.substitution_error}
                              for row, printed in zip(p5.rows, program5)]},
    }


def answer_key(groups: Sequence[Sequence[int] | Entry]) -> AnswerKey:
    """The answer key of ``groups`` (each an :class:`Entry` or a sequence of student numbers).

    Each group's answers carry its ``line`` (in the groups file, else its place in
    ``groups``), its ``names`` and ``duplicate_of``: the line of its first listing when the
    same student numbers were listed before (its answers are computed once), and
    ``repeated``: its students listed twice in it or also in other groups
    (:func:`repeated_students`).
    """
    entries = [g if isinstance(g, Entry) else Entry(tuple(g)) for g in groups]
    entries = [e if e.line is not None else Entry(e.students, e.names, i) for i, e in enumerate(entries, start=1)]
    dup = duplicates(entries)
    repeated: dict[int, list[dict[str, Any]]] = {}
    for r in repeated_students(entries):
        repeated.setdefault(r.line, []).append(r.to_dict())
    done: dict[tuple[int, ...], dict[str, Any]] = {}
    out = []
    for e in entries:
        if e.students not in done:
            done[e.students] = group_answers(e.students)
        line = e.line or 0  # every entry has its line by now
        out.append({"line": e.line, "names": None if e.names is None else list(e.names),
                    "duplicate_of": dup.get(line), "repeated": repeated.get(line, [])} | done[e.students])
    return AnswerKey(common_answers(), out)
