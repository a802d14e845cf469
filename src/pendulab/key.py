"""The teacher's answer key: every group's answers to problem 3, and the common answers once.

Each group's pendulum length comes from its student numbers (problem 3(b)), so problem 3
differs between groups; problems 1, 2, 4 and 5 do not. :func:`answer_key` computes both
from :mod:`pendulab.problems`; :func:`write_key` writes CSV, JSON or a PDF table.
"""
from __future__ import annotations

import csv
import io
import json
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


# --------------------------------------------------------------------------- output
def _csv(key: AnswerKey) -> str:
    buf = io.StringIO()
    for name, answers in key.common.items():  # the common answers once, as comment lines
        buf.write(f"# {name}: {json.dumps(answers, allow_nan=False)}\n")
    steps = [e["step"] for e in key.groups[0]["estimates"]] if key.groups else []
    head = ["students", "length", "t_hat", "plot_outcome", "plot_bracket_lo", "plot_bracket_hi", "plot_left_at"]
    for h in steps:
        head += [f"{p}_h{h:g}" for p in ("bracket_lo", "bracket_hi", "linear", "linear_error", "cubic",
                                         "cubic_error", "cubic_error_estimate")]
    head += ["interpolation_value", "interpolation_error_estimate", "interpolation_negligible"]
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(head)
    for g in key.groups:
        b = g["plot"]["bracket"] or [None, None]
        row = [" ".join(map(str, g["students"])), g["length_text"], repr(g["t_hat"]), g["plot"]["outcome"],
               b[0], b[1], g["plot"]["left_at"]]
        for e in g["estimates"]:
            row += [e["bracket"][0], e["bracket"][1], e["linear"], e["linear_error"], e["cubic"],
                    e["cubic_error"], e["cubic_error_estimate"]]
        ip = g["interpolation"]
        row += [ip["value"], ip["error_estimate"], ip["negligible"]]
        w.writerow(["" if x is None else repr(x) if isinstance(x, float) else x for x in row])
    return buf.getvalue()


_NAMES = {"gamma": "gamma", "a0": "a_0", "b0": "b_0", "a1": "a_1", "b1": "b_1", "a2": "a_2", "b2": "b_2"}


def _pdf(key: AnswerKey) -> bytes:
    import tempfile

    from .report.markup import fixed, num, sci
    from .report.typeset import typeset

    rows = []
    for g in key.groups:
        p = g["plot"]
        shown = (f"[{num(p['bracket'][0], 4)}, {num(p['bracket'][1], 4)}]" if p["outcome"] == "returns"
                 else f"leaves at $t = {num(p['left_at'], 4)}$" if p["outcome"] == "leaves" else "no return")
        cells = [", ".join(map(str, g["students"])), g["length_text"], num(g["t_hat"], 12), shown]
        for e in g["estimates"]:
            cells += [num(e["cubic"], 10), sci(e["cubic_error"], 2)]
        ip = g["interpolation"]
        cells += [sci(ip["error_estimate"], 2)]
        rows.append(cells)
    c = key.common
    common = [
        ["1(b)", f"$g = {num(c['problem1']['g'], 10)}$, $|e_g| <= {num(c['problem1']['abs_error'], 4)}$: "
                 f"{c['problem1']['significant_digits']} significant digits, $g approx {c['problem1']['g_text']}$"],
        ["2", f"$alpha = {num(c['problem2']['alpha'], 15)}$ rad $= {num(c['problem2']['alpha_degrees'], 13)} degree$, "
              f"$K_infinity = {num(c['problem2']['asymptotic_constant'], 10)}$"],
        ["4", f"{c['problem4']['points']} points, $E = {sci(c['problem4']['ssd'], 6)}$, "
              f"$max_j |z_(1,j) - tilde(phi)(t_j)| = {sci(c['problem4']['max_deviation'], 4)}$; "
              + ", ".join(f"${_NAMES.get(n, n)} = {num(x, 10)}$"
                          for n, x in zip(c['problem4']['names'], c['problem4']['coefficients']))],
        ["5", f"$hat(T) = {num(c['problem5']['t_hat'], 15)}$; one application of (11): "
              f"${num(c['problem5']['single'], 12)}$; $S_10$: ${num(c['problem5']['composite10'], 12)}$; "
              f"rate at $n = {c['problem5']['rows'][-1]['n']}$: {fixed(c['problem5']['rows'][-1]['rate'], 4)}"],
    ]
    steps = [sci(e["step"], 1) for e in key.groups[0]["estimates"]]
    data = {"rows": rows, "common": common, "steps": steps, "count": len(rows)}
    with tempfile.TemporaryDirectory(prefix="pendulab-key-") as tmp:
        return typeset(Path(tmp), "key.typ", data)


def render(key: AnswerKey, fmt: str) -> bytes:
    """The key as ``csv``, ``json`` or ``pdf`` bytes."""
    if fmt == "json":
        return (json.dumps(key.to_dict(), indent=1, allow_nan=False) + "\n").encode()
    if fmt == "csv":
        return _csv(key).encode()
    if fmt == "pdf":
        return _pdf(key)
    raise InputError("format", fmt, "one of " + ", ".join(FORMATS))


def write_key(key: AnswerKey, output: str | os.PathLike) -> Path:
    """Write ``key`` atomically to ``output`` (format from its extension)."""
    from ._atomic import check_writable, write_bytes

    fmt = output_format(output)
    out = check_writable("output", output)
    write_bytes(out, render(key, fmt))
    return out
