"""The teacher's answer key: every group's answers to problem 3, and the common answers once.

Each group's pendulum length comes from its student numbers (problem 3(b)), so problem 3
differs between groups; problems 1, 2, 4 and 5 do not. :func:`answer_key` computes both
from :mod:`pendulab.problems` as plain data; :func:`pendulab.report.key.write_key` writes it
as CSV, JSON or a PDF table.
"""
from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import inputs
from .errors import InputError

#: Output formats by file extension.
FORMATS = ("csv", "json", "pdf")
#: The largest groups file read (a class of thousands of groups is a few hundred kB).
MAX_FILE_BYTES = 10**7


def parse_groups(text: str, source: str = "groups") -> list[tuple[int, ...]]:
    """One group per line: student numbers separated by commas or spaces.

    Blank lines and ``#`` comments (whole lines or line ends) are skipped. A bad line
    raises :class:`~pendulab.errors.InputError` naming ``source`` and its line number;
    a file with no group at all is refused too.
    """
    from .group import group_length

    groups = []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        try:
            students = inputs.students("groups", line)  # the CLI's grammar of student numbers
            group_length(students)
        except InputError as exc:
            raise InputError("groups", f"{source} line {number}: {inputs.shown(raw.strip())}", exc.allowed) from None
        groups.append(students)
    if not groups:
        raise InputError("groups", source, "a file with at least one group (one line of student numbers)")
    return groups


def read_groups(path: str | os.PathLike) -> list[tuple[int, ...]]:
    """The groups of the file ``path`` (see :func:`parse_groups`)."""
    p = Path(path)
    try:
        if p.is_file() and p.stat().st_size > MAX_FILE_BYTES:  # by its size, before reading it
            raise InputError("groups", inputs.shown(str(path)), f"a file of at most {MAX_FILE_BYTES:.0e} bytes")
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else type(exc).__name__
        raise InputError("groups", inputs.shown(str(path)), f"a readable UTF-8 text file ({reason})") from None
    return parse_groups(text, str(path))


def output_format(path: str | os.PathLike) -> str:
    """``csv``, ``json`` or ``pdf`` from the extension of ``path``."""
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in FORMATS:
        raise InputError("output", inputs.shown(str(path)), "a file name ending in .csv, .json or .pdf")
    return ext


@dataclass(frozen=True, eq=False)
class AnswerKey:
    """The answers of every group (problem 3) and the common ones (problems 1, 2, 4, 5)."""

    common: dict[str, Any]
    groups: list[dict[str, Any]]

    def to_dict(self) -> dict[str, Any]:
        return {"common": self.common, "groups": self.groups}


def _f(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def group_answers(students: Sequence[int]) -> dict[str, Any]:
    """One group's answers to problem 3 as plain data (JSON-ready)."""
    from . import problems

    r = problems.problem3(students)
    est = r.plot_estimate
    plot = {
        "step": r.plot.step,
        "outcome": r.plot_outcome,
        "bracket": None if est is None else list(est.bracket),
        "j": None if est is None else est.j,
        "left_at": r.plot_left_at,
        "t_max": r.plot_t_max,
    }
    estimates = [{
        "step": e.step, "j": e.j, "bracket": list(e.bracket),
        "linear": e.linear, "linear_error": abs(e.linear - r.t_hat),
        "cubic": e.cubic, "cubic_error": abs(e.cubic - r.t_hat),
        "cubic_error_estimate": e.cubic_error_estimate,
    } for e in r.estimates]
    ip = r.cubic.interpolation
    interpolation = {
        "step": r.cubic.step, "j": r.cubic.j,
        "table": [{"node": r.cubic.j - 1 + k, "z2": float(ip.z2[k]), "t": float(ip.t[k]),
                   "coefficient": float(ip.coefficients[k])} for k in range(4)],
        "value": ip.value, "error_estimate": ip.error_estimate,
        "taylor_error": r.taylor_error, "ratio": _f(r.interpolation_ratio),
        "negligible": r.interpolation_negligible,
    }
    return {
        "students": list(r.group.numbers), "sum": r.group.total, "digits": r.group.digits,
        "length": r.group.length, "length_text": r.group.text, "t_hat": r.t_hat,
        "plot": plot, "estimates": estimates, "interpolation": interpolation,
    }


def common_answers() -> dict[str, Any]:
    """Problems 1, 2, 4 and 5, which are the same for every group."""
    from . import problems

    p1, p2, p4, p5 = problems.problem1(), problems.problem2(), problems.problem4(), problems.problem5()
    return {
        "problem1": {"g": p1.g, "abs_error": p1.abs_error, "rel_error": p1.rel_error,
                     "significant_digits": p1.significant_digits, "g_text": p1.g_text},
        "problem2": {"interval_degrees": list(p2.interval_degrees), "x0": p2.x0, "alpha": p2.alpha,
                     "alpha_degrees": p2.alpha_degrees, "iterates": list(p2.run.iterates),
                     "k_max": p2.run.k_max, "asymptotic_constant": p2.run.asymptotic_constant,
                     "error_estimate": p2.run.error_estimate},
        "problem4": {"t_max": p4.t_max, "points": p4.points, "names": list(p4.fit.names),
                     "coefficients": [float(c) for c in p4.fit.coefficients], "ssd": p4.fit.ssd,
                     "max_deviation": p4.fit.max_deviation, "below_tolerance": p4.below_tolerance},
        "problem5": {"t_hat": p5.t_hat, "single": p5.single, "composite10": p5.composite10,
                     "rows": [{"n": row.n, "estimate": row.estimate, "error": row.error, "rate": row.rate}
                              for row in p5.rows]},
    }


def answer_key(groups: Sequence[Sequence[int]]) -> AnswerKey:
    """The answer key of ``groups`` (each a sequence of student numbers)."""
    return AnswerKey(common_answers(), [group_answers(g) for g in groups])
