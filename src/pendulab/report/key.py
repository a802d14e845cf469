"""The answer key (:mod:`pendulab.key`) as CSV, JSON or a PDF table, written atomically."""
from __future__ import annotations

import csv
import io
import json
import os
import tempfile
from pathlib import Path

from .._atomic import check_writable, write_bytes
from ..errors import InputError
from ..key import FORMATS, AnswerKey, output_format
from .markup import fixed, num, sci
from .typeset import typeset


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
    fmt = output_format(output)
    out = check_writable("output", output)
    write_bytes(out, render(key, fmt))
    return out
