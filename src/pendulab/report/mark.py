"""A marked class (:mod:`pendulab.jobs.mark`) as a sheet: CSV for a spreadsheet in either
locale, JSON, plain text or a PDF with the class summary and a histogram of marks.

Every word is the catalogues' (``mark.*``); the numbers are the results' own: a key prints
in the report's form for its quantity (:func:`pendulab.jobs.mark.key_text`, the digit
policy of :mod:`pendulab.core.digits`) in every format, so the CSV, the JSON's ``key_text``,
the text and the PDF show the report's digits.
"""
from __future__ import annotations

import csv
import io
import json
import os
import tempfile
from pathlib import Path
from typing import Any, Literal

from ..core.atomic import check_writable, write_bytes
from ..core.errors import InputError
from ..jobs.mark import ClassMarks, Verdict
from .key import plain_cell, repeated_words
from .typeset import needs_system_fonts, typeset
from .words import sentence

#: ``excel``: ``,`` between cells and a decimal point; ``excel-pt``: ``;`` and a decimal
#: comma, as a spreadsheet in a Portuguese locale reads them, and a UTF-8 byte order mark
#: so that it reads the names' accents.
Dialect = Literal["excel", "excel-pt"]
DIALECTS = ("excel", "excel-pt")
FORMATS = ("csv", "json", "txt", "pdf")

#: The marked sheet's columns, one row per group and question.
SHEET_COLUMNS = ("line", "students", "names", "flags", "part", "question", "answer", "key", "verdict", "why",
                 "points", "max_points")


def number(x: Any, dialect: Dialect = "excel") -> str:
    """A cell's number: floats by their shortest round-trip repr (integral points as integers)."""
    if x is None:
        return ""
    if isinstance(x, bool):
        return str(x)
    if isinstance(x, float):
        s = repr(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)
        return s.replace(".", ",") if dialect == "excel-pt" else s
    return str(x)


def _key_cell(v: Verdict, dialect: Dialect = "excel") -> str:
    """The key as the report prints it (its digit policy), a decimal comma for ``excel-pt``."""
    text = v.key_text or number(v.key)
    return text.replace(".", ",") if dialect == "excel-pt" and isinstance(v.key, float) else text


def why(v: Verdict, lang: str = "en") -> str:
    """Why an answer is right or wrong, in words."""
    method = "" if v.method is None else sentence(f"mark.method.{v.method}", lang, detail=v.detail)
    freedom = sentence(f"mark.freedom.{v.freedom}", lang)
    if v.code == "outside" and v.method is None:
        words = sentence("mark.code.outside_text", lang)
    else:
        words = sentence(f"mark.code.{v.code}", lang, method=method, freedom=freedom, digits=v.digits,
                         low="" if v.low is None else f"{v.low:.6g}", high="" if v.high is None else f"{v.high:.6g}")
    # a key the engine does not trust says so, right or wrong (3(b)'s untrusted return)
    return f"{words}; {sentence(f'mark.status.{v.status}', lang)}" if v.status else words


def flags(g: dict[str, Any], lang: str = "en") -> str:
    """A group's flags: listed before, repeated students, no row of answers."""
    out = []
    if g["duplicate_of"] is not None:
        out.append(sentence("key.listed_again.group", lang, students=" ".join(map(str, g["students"])),
                            lines=f"{g['duplicate_of']}, {g['line']}"))
    out += [w for r in g["repeated"] for w in repeated_words(r, lang)]
    if not g["answered"]:
        out.append(sentence("mark.unanswered", lang))
    return "; ".join(out)


def sheet(marks: ClassMarks, lang: str = "en", dialect: Dialect = "excel") -> list[list[str]]:
    """The marked sheet: the header row, then one row per group and question."""
    rows = [list(SHEET_COLUMNS)]
    for gm in marks.groups:
        g = gm.to_dict()
        head = [str(gm.line), " ".join(map(str, gm.students)), "; ".join(gm.names or ()), flags(g, lang)]
        for v in gm.verdicts:
            rows.append(head + [v.part, v.column, v.answer, _key_cell(v, dialect),
                                sentence("mark.right" if v.right else "mark.wrong", lang), why(v, lang),
                                number(v.points, dialect), number(v.max_points, dialect)])
    return rows


def _safe(cell: str) -> str:
    """A cell a spreadsheet never runs as a formula (:func:`pendulab.report.key.plain_cell`);
    a number with a decimal comma (``-0,5``) is a number too."""
    return cell if plain_cell(cell.replace(",", ".")) == cell.replace(",", ".") else plain_cell(cell)


def _csv(marks: ClassMarks, lang: str, dialect: Dialect) -> bytes:
    buf = io.StringIO()
    w = csv.writer(buf, delimiter=";" if dialect == "excel-pt" else ",", lineterminator="\r\n")
    w.writerows([[_safe(c) for c in row] for row in sheet(marks, lang, dialect)])
    return (("\ufeff" if dialect == "excel-pt" else "") + buf.getvalue()).encode("utf-8")


def summary_text(marks: ClassMarks, lang: str = "en") -> str:
    s = marks.summary()
    shown = {k: "—" if s[k] is None else f"{s[k]:.4g}" for k in ("mean", "median", "lowest", "highest")}
    return sentence("mark.summary", lang, groups=s["groups"], max_points=f"{s['max_points']:g}", **shown)


def histogram_lines(marks: ClassMarks) -> list[str]:
    """The histogram as text: one line per tenth of the maximum."""
    counts = marks.summary()["histogram"]
    n = len(counts)
    return [f"{100 * i // n:3d}-{100 * (i + 1) // n:3d} % {'#' * c} {c}" for i, c in enumerate(counts)]


def text(marks: ClassMarks, lang: str = "en") -> str:
    """Plain text for a terminal: each group's points and its wrong answers, then the summary."""
    out = []
    for gm in marks.groups:
        g = gm.to_dict()
        out.append(f"line {gm.line}: {' '.join(map(str, gm.students))}"
                   + (f" ({'; '.join(gm.names)})" if gm.names else "")
                   + f"  {gm.points:g}/{gm.max_points:g}")
        if flags(g, lang):
            out.append(f"  ! {flags(g, lang)}")
        for v in gm.verdicts:
            if not v.right or v.status:  # a right answer to an untrusted key is shown too
                out.append(f"  {v.column:<22} {v.answer or '-':<22} key {_key_cell(v):<18} {why(v, lang)}")
    out.append(summary_text(marks, lang))
    out += histogram_lines(marks)
    return "\n".join(out) + "\n"


def document(marks: ClassMarks, lang: str = "en") -> dict[str, Any]:
    """The JSON document: :meth:`ClassMarks.to_dict`, each verdict with its words beside its codes."""
    d = marks.to_dict()
    for g, gm in zip(d["groups"], marks.groups):
        g["flags"] = flags(g, lang)
        for vd, v in zip(g["verdicts"], gm.verdicts):
            vd["why"] = why(v, lang)
    return d


def _pdf(marks: ClassMarks, lang: str) -> bytes:
    s = marks.summary()
    groups = []
    for gm in marks.groups:
        g = gm.to_dict()
        groups.append({
            "title": f"line {gm.line}: {', '.join(map(str, gm.students))}", "names": "; ".join(gm.names or ()),
            "points": f"{gm.points:g} / {gm.max_points:g}", "flags": flags(g, lang),
            "rows": [[v.part, v.column, v.answer, _key_cell(v), sentence("mark.right" if v.right else "mark.wrong",
                                                                          lang), why(v, lang), f"{v.points:g}"]
                     for v in gm.verdicts],
        })
    counts = s["histogram"]
    n = len(counts)
    data = {"summary": summary_text(marks, lang), "histogram": counts,
            "bins": [f"{100 * i // n}–{100 * (i + 1) // n} %" for i in range(n)], "groups": groups,
            "right": [[c, str(k)] for c, k in s["right_per_question"].items()], "count": len(groups),
            "heads": ["part", "question", "answer", "key", "verdict", "why", "points"]}
    texts = [g["names"] for g in groups]
    with tempfile.TemporaryDirectory(prefix="pendulab-mark-") as tmp:
        return typeset(Path(tmp), "mark.typ", data, system_fonts=needs_system_fonts(texts))


def output_format(path: str | os.PathLike) -> str:
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in FORMATS:
        raise InputError("output", str(path), "a file name ending in .csv, .json, .txt or .pdf")
    return ext


def render(marks: ClassMarks, fmt: str, lang: str = "en", dialect: Dialect = "excel") -> bytes:
    if fmt == "csv":
        return _csv(marks, lang, dialect)
    if fmt == "json":
        return (json.dumps(document(marks, lang), indent=1, allow_nan=False) + "\n").encode()
    if fmt == "txt":
        return text(marks, lang).encode()
    if fmt == "pdf":
        return _pdf(marks, lang)
    raise InputError("format", fmt, "one of " + ", ".join(FORMATS))


def write_marks(marks: ClassMarks, output: str | os.PathLike, lang: str = "en", dialect: Dialect = "excel") -> Path:
    """Write the marked sheet atomically to ``output`` (format from its extension)."""
    out = check_writable("output", output)
    write_bytes(out, render(marks, output_format(output), lang, dialect))
    return out


def template_csv(rows: list[list[str]], dialect: Dialect = "excel") -> bytes:
    """``pendulab key --template``: the answers file to fill in, in the dialect's separator."""
    buf = io.StringIO()
    csv.writer(buf, delimiter=";" if dialect == "excel-pt" else ",", lineterminator="\r\n").writerows(
        [[_safe(c) for c in row] for row in rows])
    return (("\ufeff" if dialect == "excel-pt" else "") + buf.getvalue()).encode("utf-8")


def scheme_json(scheme: Any) -> bytes:
    """The marking scheme as an editable JSON file."""
    return (json.dumps(scheme.to_dict(), indent=1) + "\n").encode()


