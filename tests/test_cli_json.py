"""Every ``--json`` of the command line is the ``to_dict()`` of a library result, computed
here by calling the library, plus only the words the catalogues give for the result's
decisions and, where the command writes files, the record of what it wrote: no field of a
result is projected, renamed or added by the command line itself."""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

from pendulab.core.inputs import angle_range
from pendulab.jobs import problems
from pendulab.jobs.key import answer_key, read_entries
from pendulab.numerics.approximations import approximation_table
from pendulab.numerics.crossing import estimate_periods
from pendulab.numerics.group import group_length
from pendulab.numerics.period import FIXED_ITERATIONS_ULPS, periods
from pendulab.numerics.simulation import simulate
from pendulab.report.key import document
from pendulab.report.words import sentence


def plain(x):
    """``x`` as JSON gives it back: arrays and tuples as lists, non-finite floats as null."""
    if isinstance(x, dict):
        return {str(k): plain(v) for k, v in x.items()}
    if isinstance(x, np.ndarray):
        return plain(x.tolist())
    if isinstance(x, (list, tuple)):
        return [plain(v) for v in x]
    if isinstance(x, np.generic):
        return plain(x.item())
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def words_and_rest(out: str, words: set[str]) -> tuple[dict, dict]:
    """The JSON printed, split into the word keys and the rest."""
    doc = json.loads(out)
    assert words <= set(doc), (words - set(doc))
    return {k: doc.pop(k) for k in words}, doc


def test_period(cli):
    res = cli("period", "-l", "3.5", "-a", "4pi/5", "--iterations", "7", "--digits", "30", "--json")
    words, rest = words_and_rest(res.out, set())
    assert rest == plain(periods("3.5", "4pi/5", iterations=7, digits=30).to_dict())
    # Below pi as written, pi as a double: (8) on doubles has no value, and a note says why.
    near = "0.9999999999999999999999999pi"
    res = cli("period", "-l", "1", "-a", near, "--json")
    r = periods("1", near)
    assert not r.amplitude_double_below_pi and r.period is None
    words, rest = words_and_rest(res.out, {"period_note"})
    assert rest == plain(r.to_dict())
    assert words == {"period_note": sentence("period.note", amplitude=near)}
    assert "period_note" not in json.loads(cli("period", "--json").out)


def test_simulate(cli):
    res = cli("simulate", "-l", "1", "-a", "pi/4", "--step", "0.1", "--t-max", "2.1", "--method", "rk4", "--json")
    assert json.loads(res.out) == plain(simulate(1.0, math.pi / 4, 0.1, 2.1, method="rk4").to_dict())


def test_estimate(cli):
    res = cli("estimate", "-l", "1", "-a", "2", "--step", "1e-2,1e-3", "--dense", "--json")
    expected = estimate_periods(1.0, 2.0, [1e-2, 1e-3]).to_dict()
    assert json.loads(res.out) == plain(expected)
    assert expected["rows"][0]["cubic_order"] is None and expected["rows"][1]["cubic_order"] > 1


def test_length(cli):
    assert json.loads(cli("length", "262", "407", "634", "--json").out) == plain(group_length([262, 407, 634]).to_dict())


def test_gravity(cli):
    words, rest = words_and_rest(cli("gravity", "--json").out, {"rule", "abs_error_formula", "rel_error_formula"})
    r = problems.problem1()
    assert rest == plain(r.to_dict()) and rest["g_text"] == r.g_text
    assert words == {k: sentence(f"p1.{k}") for k in words}


@pytest.mark.parametrize("x0", [None, "50deg"])
def test_newton(cli, x0):
    res = cli("newton", "--json", *(["--x0", x0] if x0 else []))
    words, rest = words_and_rest(res.out, {"x0_rule", "justification"})
    r = problems.problem2(x0=None if x0 is None else math.radians(50))
    details = [c.pop("detail") for c in rest["interval_conditions"]]
    assert rest == plain(r.to_dict())
    assert words["x0_rule"] == sentence("p2.x0_rule" if x0 is None else "p2.x0_given")
    assert words["justification"] == sentence("p2.justification." + ("positive" if r.curvature_positive else "negative"))
    # Each condition's detail: its sentence with the relation that holds (or fails) and its numbers.
    relation = {"sign_change": ("<", ">="), "step_from_a": ("<=", ">"), "step_from_b": ("<=", ">")}
    assert details == [sentence(f"p2.condition.{c.name}", relation=relation.get(c.name, ("", ""))[not c.holds],
                                **c.values) for c in r.interval.conditions]


def test_fit(cli):
    words, rest = words_and_rest(cli("fit", "--t-max", "2", "--json").out, {"answer"})
    r = problems.problem4(t_max=2.0)
    assert rest == plain(r.to_dict())
    assert words["answer"].startswith("Yes" if r.below_tolerance else "No")


@pytest.mark.parametrize("args, substitution", [(["--n", "1,10,100"], False), (["--n", "10,100", "--substitution"], True),
                                               (["-a", "3.14159265358979", "--n", "10,100", "--graded"], True)])
def test_quadrature(cli, args, substitution):
    words, rest = words_and_rest(cli("quadrature", *args, "--json").out, {"t_hat_note", "answer_5a", "rate_explanation"})
    alpha = float(args[1]) if args[0] == "-a" else problems.cases.PROBLEM5.alpha
    ns = [int(n) for n in args[args.index("--n") + 1].split(",")]
    r = problems.problem5(amplitude=alpha, ns=ns, substitution=substitution, graded="--graded" in args)
    assert rest == plain(r.to_dict())
    assert ("substitution_reference" in rest) == substitution
    assert words["answer_5a"] == sentence("p5.answer_5a")
    if r.t_hat_converged:
        assert words["t_hat_note"] is None
    else:
        assert f"{r.t_hat_ulps:+d} ulp" in words["t_hat_note"] and f"{FIXED_ITERATIONS_ULPS} ulp" in words["t_hat_note"]


def test_approximations(cli):
    assert json.loads(cli("approximations", "--json").out) == plain(approximation_table().to_dict())


def test_key(cli, tmp_path):
    groups = tmp_path / "groups.txt"
    groups.write_text("262 407 634\n99999 1\n")
    doc = json.loads(cli("key", "--groups", groups, "--json").out)
    assert doc == plain(document(answer_key(read_entries(groups))))


@pytest.mark.parametrize("files", [False, True])
def test_sweep(cli, tmp_path, files):
    """The sweep's JSON is the result's ``to_dict()`` (``g`` and the summary per method and
    step) and the files the command wrote (``output``, ``plot``: null where none)."""
    from pendulab.jobs.sweep import sweep

    written = {"output": str(tmp_path / "rows.csv"), "plot": str(tmp_path / "errors.png")} if files else {}
    args = [a for k, path in written.items() for a in (f"--{k}", path)]
    doc = json.loads(cli("sweep", "--amplitude", "10deg:170deg:5", "--step", "1e-2", "--method", "taylor2,rk4",
                         "-l", "2", "--g", "9.8", *args, "--json").out)
    amplitudes = angle_range("amplitude", "10deg:170deg:5", 5)  # the parser's doubles, as the command's
    result = sweep(amplitudes, [1e-2], ["taylor2", "rk4"], lengths=2.0, g=9.8)
    assert {k: doc.pop(k) for k in ("output", "plot")} == {"output": written.get("output"), "plot": written.get("plot")}
    assert doc == plain(result.to_dict())
    assert doc["g"] == 9.8 and [(s["method"], s["pendulums"]) for s in doc["summary"]] == [("taylor2", 5), ("rk4", 5)]
    if files:  # the paths named are the files written: the rows, and a PNG
        with open(written["output"], newline="") as f:
            rows = list(csv.DictReader(f))
        assert np.array_equal([float(r["cubic"]) for r in rows], result["cubic"], equal_nan=True)
        with open(written["plot"], "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_report(cli, tmp_path, monkeypatch):
    """What ``report`` wrote (the file, its size, its language) and the answers it states: the
    key's document for the group, names and all. The PDF itself is test_report.py's: here the
    builder writes a stand-in, so the test reads the record the command prints about it."""
    import pendulab.report
    from pendulab.jobs.key import Entry

    def build(numbers, lang, output, progress, names):
        Path(output).write_bytes(b"%PDF-1.7 stand-in")
        return Path(output)

    monkeypatch.setattr(pendulab.report, "build_report", build)
    out = tmp_path / "r.pdf"
    doc = json.loads(cli("report", "--students", "99999,1", "--names", "Ana; Rui", "--lang", "pt", "-o", out,
                         "--json").out)
    assert doc == {"output": str(out), "bytes": 17, "lang": "pt",
                   "answers": plain(document(answer_key([Entry((99999, 1), ("Ana", "Rui"))])))}
    group = doc["answers"]["groups"][0]
    assert (group["students"], group["names"]) == ([99999, 1], ["Ana", "Rui"])  # the cover's names too
