"""The answer key (:mod:`pendulab.jobs.key`) as CSV, JSON or a PDF table, written atomically.

The CSV is one header row and one row per group; the answers common to the class and the
class questions keyed go to a second CSV beside it (:func:`pendulab.jobs.key.class_path`).
"""
from __future__ import annotations

import csv
import io
import json
import os
import re
from pathlib import Path
from typing import Any

from ..core.atomic import check_writable, temp_folder, write_bytes, write_together
from ..core.errors import InputError
from ..jobs.key import FORMATS, AnswerKey, class_path, output_format
from .markup import fixed, num, sci
from .typeset import breakable, needs_system_fonts, typeset
from .words import sentence


def document(key: AnswerKey, lang: str = "en") -> dict[str, Any]:
    """The key's JSON document: :meth:`AnswerKey.to_dict` and every question with what a
    correct method may give (:func:`questions`)."""
    d = key.to_dict()
    d["questions"] = questions(key)
    return d


def questions(key: AnswerKey) -> dict[str, Any]:
    """Every question as ``pendulab mark`` reads it (:mod:`pendulab.jobs.mark`): its column,
    the printed programs' answer (``key``, and ``key_text`` in the report's digits) and what
    each freedom of the coursework gives (``alternatives``, ``low``, ``high``)."""
    from ..jobs.mark import class_questions, group_questions

    return {"class": [q.to_dict() for q in class_questions()],
            "groups": [{"line": g["line"], "questions": [q.to_dict() for q in group_questions(g["students"])]}
                       for g in key.groups]}


def _group_key(g: dict[str, Any], column: str) -> str:
    """A group's key for the answers file's ``column``, in the report's digits ("" where the
    group has no such answer: no bracket when the h = 0.2 simulation does not return)."""
    from ..jobs.mark import group_questions, key_text

    return next((key_text(q) for q in group_questions(g["students"]) if q.column == column), "")


def repeated_words(r: dict[str, Any], lang: str = "en") -> list[str]:
    """The flags of one repeated student (:meth:`pendulab.jobs.key.Repeated.to_dict`) in words."""
    out = []
    if r["within"] > 1:
        out.append(sentence("key.repeated.within", lang, student=r["student"], times=r["within"], line=r["line"]))
    if r["other_lines"]:
        out.append(sentence("key.repeated.across", lang, student=r["student"], line=r["line"],
                            lines=", ".join(map(str, r["other_lines"]))))
    return out


def repeated_warning(repeated: list, lang: str = "en") -> str | None:
    """One line for every repeated student of a class (:func:`pendulab.jobs.key.repeated_students`),
    or None when there is none."""
    words = [w for r in repeated for w in repeated_words(r.to_dict(), lang)]
    if not words:
        return None
    return sentence("key.repeated.summary", lang, count=len({r.student for r in repeated}), flags="; ".join(words))


def repeated_cell(g: dict[str, Any], lang: str = "en") -> str | None:
    """A group's repeated students as one cell (``None``: none)."""
    words = [w for r in g.get("repeated", []) for w in repeated_words(r, lang)]
    return "; ".join(words) or None


def _cell(x: Any) -> Any:
    """A CSV cell: floats by their shortest round-trip repr, booleans as yes/no, None empty,
    a text a spreadsheet would run as a formula made plain (:func:`plain_cell`)."""
    if x is None:
        return ""
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, float):
        return repr(x)
    if isinstance(x, str):
        return plain_cell(x)
    return x


#: The first characters that make a spreadsheet read a cell as a formula (OWASP, CSV Injection).
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def plain_cell(text: str) -> str:
    """``text`` as a spreadsheet shows it and never runs it: a text that begins with ``=``,
    ``+``, ``-``, ``@``, a tab or a carriage return gets a leading ``'`` (OWASP's advice for
    CSV injection); a number (``-0.5``) is left as it is."""
    if text.startswith(FORMULA_STARTS) and not _NUMBER.fullmatch(text):
        return "'" + text
    return text


def _tag(h: float) -> str:
    return f"h{h:g}"


def csv_columns(key: AnswerKey) -> list[tuple[str, Any]]:
    """The per-group table: (header, function of a group's answers) for each column."""
    cols: list[tuple[str, Any]] = [
        ("line", lambda g: g["line"]),
        ("students", lambda g: " ".join(map(str, g["students"]))),
        ("names", lambda g: "; ".join(g["names"]) if g["names"] else None),
        ("duplicate_of_line", lambda g: g["duplicate_of"]),
        ("repeated_students", repeated_cell),
        ("sum", lambda g: g["sum"]),
        ("nonzero_digits", lambda g: g["digits"]),
        ("length", lambda g: g["length_text"]),
        ("t_hat", lambda g: g["t_hat"]),
        ("h0.2_outcome", lambda g: g["plot"]["outcome"]),
        ("h0.2_j", lambda g: g["plot"]["j"]),
        ("h0.2_bracket_lo", lambda g: (g["plot"]["bracket"] or [None])[0]),
        ("h0.2_bracket_hi", lambda g: (g["plot"]["bracket"] or [None, None])[1]),
        ("h0.2_t_hat_inside", lambda g: g["plot"]["t_hat_inside"]),
        ("h0.2_left_at", lambda g: g["plot"]["left_at"]),
    ]
    steps = [e["step"] for e in key.groups[0]["estimates"]] if key.groups else []
    for i, h in enumerate(steps):
        for name in ("j", "bracket_lo", "bracket_hi", "linear", "linear_t_hat_error", "linear_order", "cubic",
                     "cubic_t_hat_error", "cubic_order", "cubic_error_estimate"):
            if name == "bracket_lo":
                get: Any = lambda g, i=i: g["estimates"][i]["bracket"][0]  # noqa: E731
            elif name == "bracket_hi":
                get = lambda g, i=i: g["estimates"][i]["bracket"][1]  # noqa: E731
            else:
                get = lambda g, i=i, name=name: g["estimates"][i][name]  # noqa: E731
            cols.append((f"{_tag(h)}_{name}", get))
    cols.append(("3d_j", lambda g: g["interpolation"]["j"]))
    for k in range(4):
        for name in ("node", "z2", "t", "coefficient"):
            cols.append((f"3d_{name}{k}", lambda g, k=k, name=name: g["interpolation"]["table"][k][name]))
    for name in ("value", "error_estimate", "taylor_error", "negligible"):
        cols.append((f"3d_{name}", lambda g, name=name: g["interpolation"][name]))
    from ..jobs.mark import group_questions

    # every question of 3(b)-(d) under the answers file's name, as printed (pendulab mark)
    for q in group_questions((262, 407, 634)):
        cols.append((f"key_{q.column}", lambda g, c=q.column: _group_key(g, c)))
    return cols


def _csv(key: AnswerKey) -> str:
    """One header row, then one row per group: nothing else (a spreadsheet opens it as is)."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    cols = csv_columns(key)
    w.writerow([h for h, _ in cols])
    for g in key.groups:
        w.writerow([_cell(get(g)) for _, get in cols])
    return buf.getvalue()


def class_rows(key: AnswerKey) -> list[tuple[str, str, Any]]:
    """The answers common to every group as (problem, answer, value) rows."""
    c = key.common
    rows: list[tuple[str, str, Any]] = []
    for name, value in c["problem1"].items():
        rows.append(("1", name, value))
    p2 = c["problem2"]
    rows += [("2", "interval_deg_a", p2["interval_deg"][0]), ("2", "interval_deg_b", p2["interval_deg"][1]),
             ("2", "x0", p2["x0"]), ("2", "alpha", p2["alpha"]), ("2", "alpha_deg", p2["alpha_deg"])]
    rows += [("2", f"x_{k}", x) for k, x in enumerate(p2["iterates"])]
    rows += [("2", f"q_{k}", q) for k, q in enumerate(p2["q"])]
    rows += [("2", f"q_{k}_rounding", q) for k, q in enumerate(p2["q_rounding"])]
    rows += [("2", "k_max", p2["k_max"]), ("2", "asymptotic_constant", p2["asymptotic_constant"]),
             ("2", "error_estimate", p2["error_estimate"])]
    for part in ("problem4", "problem4_601"):
        p4 = c[part]
        label = f"4 ({p4['points']} points)"
        rows += [(label, "t_max", p4["t_max"]), (label, "points", p4["points"])]
        for i, row in enumerate(p4["normal_matrix"]):
            rows += [(label, f"A_{i + 1}{k + 1}", x) for k, x in enumerate(row)]
        rows += [(label, f"r_{i + 1}", x) for i, x in enumerate(p4["normal_rhs"])]
        rows += [(label, n, x) for n, x in zip(p4["names"], p4["coefficients"])]
        rows += [(label, n, p4[n]) for n in ("ssd", "max_deviation", "argmax_deviation", "below_tolerance")]
    p5 = c["problem5"]
    rows += [("5", "t_hat", p5["t_hat"]), ("5", "single", p5["single"]), ("5", "composite10", p5["composite10"])]
    for row in p5["rows"]:
        rows += [("5", f"{name}_n{row['n']}", row[name]) for name in
                 ("estimate", "error", "rate", "substitution_estimate", "substitution_error")]
    return rows


def _class_csv(key: AnswerKey) -> str:
    """The class-wide answers, one per row, and every class question as ``pendulab mark`` reads it."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["problem", "answer", "value"])
    for problem, answer, value in class_rows(key):
        w.writerow([problem, answer, _cell(value)])
    from ..jobs.mark import class_questions, key_text

    for q in class_questions():  # every question as the answers file names it, as printed
        w.writerow([f"question {q.part}", q.column, key_text(q)])
    return buf.getvalue()


_NAMES = {"gamma": "gamma", "a0": "a_0", "b0": "b_0", "a1": "a_1", "b1": "b_1", "a2": "a_2", "b2": "b_2"}


def _block(title: str, heads: list[str], rows: list[list[str]], note: str = "", plain: bool = False) -> dict[str, Any]:
    """One table of the class-wide pages: markup heads and cells (``plain``: cells printed as is)."""
    return {"title": title, "heads": heads, "rows": rows, "note": note, "plain": plain}


def class_blocks(key: AnswerKey) -> list[dict[str, Any]]:
    """The class-wide pages of the PDF key: problems 1, 2, 4, 5 and every question keyed."""
    c = key.common
    p1, p2, p5 = c["problem1"], c["problem2"], c["problem5"]
    blocks = [_block("Problem 1(b)", ["quantity", "value"], [
        ["$tilde(g) = 4 pi^2 tilde(l) \\/ tilde(T)^2$", num(p1["g"], 12)],
        ["$partial G \\/ partial l$, $partial G \\/ partial T$", f"{num(p1['dg_dl'], 10)}, {num(p1['dg_dT'], 10)}"],
        ["$|e_g| lt.tilde$ (first order)", num(p1["abs_error"], 10)],
        ["$|e_g| \\/ |g| lt.tilde$", num(p1["rel_error"], 10)],
        ["corners: $g in [g_min, g_max]$", f"[{num(p1['g_min'], 10)}, {num(p1['g_max'], 10)}]"],
        ["largest error at the corners", num(p1["worst_error"], 10)],
        ["significant digits", f"{p1['significant_digits']}: $g approx {p1['g_text']}$"],
    ])]
    rows = []
    for k, x in enumerate(p2["iterates"]):
        q = p2["q"][k] if k < len(p2["q"]) else None
        rho = p2["q_rounding"][k] if k < len(p2["q_rounding"]) else None
        rows.append([str(k), num(x, 17), "—" if q is None else num(q, 10), "—" if rho is None else sci(rho, 2)])
    blocks.append(_block(
        "Problem 2", ["$k$", "$x_k$ (rad)", "$q_k$", "rounding of $q_k$"], rows,
        f"$[a, b] = [{num(p2['interval_deg'][0], 8)}°, {num(p2['interval_deg'][1], 8)}°]$, "
        f"$x_0 = {num(p2['x0'], 17)}$; $alpha = {num(p2['alpha'], 17)}$ rad $= {num(p2['alpha_deg'], 15)}°$; "
        f"$k_max = {p2['k_max']}$ (rounding of $q_k$ at most 1%), "
        f"$K_infinity = |f''(z) \\/ (2 f'(z))| = {num(p2['asymptotic_constant'], 10)}$; "
        f"error estimate of the last iterate {sci(p2['error_estimate'], 2)} rad."))
    for part in ("problem4", "problem4_601"):
        p4 = c[part]
        dec = p4["decimals"] if p4["decimals"] is not None else 15
        names = ", ".join(f"${_NAMES.get(n, n)}$" for n in p4["names"])
        rows = [[fixed(x, dec) for x in row] + [fixed(r, dec)] for row, r in zip(p4["normal_matrix"], p4["normal_rhs"])]
        blocks.append(_block(
            f"Problem 4, {p4['points']} points ($t_max = {num(p4['t_max'], 6)}$): normal equations $[A | r]$",
            [f"$A_(i {k + 1})$" for k in range(len(rows))] + ["$r_i$"], rows,
            f"Unknowns in the order {names}. Coefficients: "
            + ", ".join(f"${_NAMES.get(n, n)} = {num(x, 12)}$" for n, x in zip(p4["names"], p4["coefficients"]))
            + f"; $E = {sci(p4['ssd'], 8)}$; $max_j |tilde(phi)(t_j) - z_(1,j)| = {sci(p4['max_deviation'], 6)}$ "
            f"at $t = {num(p4['argmax_deviation'], 6)}$: (ii) {'yes' if p4['below_tolerance'] else 'no'} "
            f"(tolerance {sci(p4['tolerance'], 1)})."))
    rows = [[str(r["n"]), num(r["estimate"], 16), sci(r["error"], 4), "—" if r["rate"] is None else fixed(r["rate"], 4),
             num(r["substitution_estimate"], 16), sci(r["substitution_error"], 3)] for r in p5["rows"]]
    blocks.append(_block(
        "Problem 5", ["$n$", "$S_n$ on (1)", "error", "rate", "substituted", "error"], rows,
        f"$hat(T) = {num(p5['t_hat'], 16)}$ s; one application of (11): {num(p5['single'], 15)}; "
        f"$S_10$: {num(p5['composite10'], 15)}."))
    from ..jobs.mark import class_questions, group_questions, key_text

    by_problem: dict[str, list[list[str]]] = {}
    for q in class_questions():  # one block per problem: a block is never split across pages
        by_problem.setdefault(q.part[0], []).append([q.column, q.part, key_text(q),
                                                     sentence(f"mark.freedom.{q.freedom}")])
    for problem, rows in by_problem.items():
        blocks.append(_block(f"Problem {problem}: every question common to the class, as `pendulab mark` reads it",
                             ["question", "part", "key", "accepted"], rows, plain=True))
    picked = ("3b_t_max", "3d_fifth_t", "3d_divided_difference", "3d_error_estimate", "3d_rounding_level")
    rows = []
    for g in key.groups:
        by = {q.column: key_text(q) for q in group_questions(g["students"])}
        rows.append([str(g["line"]), " ".join(map(str, g["students"]))] + [by.get(c, "") for c in picked])
    blocks.append(_block("Problem 3(b), 3(d) for each group, as `pendulab mark` reads them",
                         ["line", "students", *picked], rows, plain=True))
    return blocks


def _pdf(key: AnswerKey) -> bytes:
    rows, names = [], []
    for g in key.groups:
        p = g["plot"]
        shown = (f"[{num(p['bracket'][0], 6)}, {num(p['bracket'][1], 6)}]" if p["outcome"] == "returns"
                 else f"leaves at $t = {num(p['left_at'], 6)}$" if p["outcome"] == "leaves" else "no return")
        if p["status"] == "untrusted":  # near the separatrix (the report's 3(b) says why)
            shown += " untrusted"
        inside = "—" if p["t_hat_inside"] is None else "yes" if p["t_hat_inside"] else "no"
        cells = [str(g["line"]), ", ".join(map(str, g["students"])), str(g["sum"]), g["length_text"],
                 num(g["t_hat"], 16), shown, inside]
        for e in g["estimates"]:
            cells.append(f"{num(e['cubic'], 12)} \\ #text(size: 7pt)[{sci(e['cubic_t_hat_error'], 2)}]")
        ip = g["interpolation"]
        cells += [sci(ip["error_estimate"], 2), "yes" if ip["negligible"] else "no",
                  "" if g["duplicate_of"] is None else f"*line {g['duplicate_of']}*"]
        rows.append(cells)
        names.append(breakable("; ".join(g["names"])) if g["names"] else "")  # plain text, never markup
    steps = [sci(e["step"], 1) for e in key.groups[0]["estimates"]]
    data = {"rows": rows, "names": names, "steps": steps, "count": len(rows), "blocks": class_blocks(key),
            "duplicates": sum(g["duplicate_of"] is not None for g in key.groups)}
    with temp_folder("pendulab-key-") as tmp:
        return typeset(Path(tmp), "key.typ", data, system_fonts=needs_system_fonts(names))


def render(key: AnswerKey, fmt: str) -> bytes:
    """The key as ``csv`` (one row per group), ``json`` or ``pdf`` bytes."""
    if fmt == "json":
        return (json.dumps(document(key), indent=1, allow_nan=False) + "\n").encode()
    if fmt == "csv":
        return _csv(key).encode()
    if fmt == "pdf":
        return _pdf(key)
    raise InputError("format", fmt, "one of " + ", ".join(FORMATS))


def write_key(key: AnswerKey, output: str | os.PathLike) -> list[Path]:
    """Write ``key`` atomically to ``output`` (format from its extension); a ``.csv`` also
    gets the class-wide answers and tolerances beside it (:func:`class_path`), the two
    written as one (:func:`pendulab.core.atomic.write_together`): never a new key beside an
    old class file.

    Returns the files written.
    """
    fmt = output_format(output)
    out = check_writable("output", output)
    if fmt == "csv":
        side = class_path(out)
        write_together([(out, render(key, fmt)), (side, _class_csv(key).encode())])
        return [out, side]
    write_bytes(out, render(key, fmt))
    return [out]
