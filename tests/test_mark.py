"""``pendulab mark``: a class of 30 marked, every correct variant accepted, every wrong answer refused.

The answers are built here from the printed programs (``pendulab/programs/*.py``, loaded as
the report loads them), run with the freedoms the coursework leaves: Newton from a random
start in the convergence interval and stopped a step earlier; every valid 4-point table of
3(d) and every fifth node beside it; each estimator of the period in 3(c); another ``t_max``
in 3(b) and the original's ``Y_0 .. Y_600`` in 4; fewer digits; then one wrong answer per
question, spread over the groups. Nothing here comes from :mod:`pendulab.jobs.mark`'s
alternatives: only the column names are shared.
"""
from __future__ import annotations

import csv
import io
import json
import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.cli import main
from pendulab.core.errors import InputError
from pendulab.jobs import mark
from pendulab.jobs.coursework import load
from pendulab.jobs.key import Entry, parse_entries

P = load()
P2, P3, P4, P5 = (P[f"problem{k}.py"] for k in (2, 3, 4, 5))
TAYLOR, AGM, LENGTH = P["taylor.py"].taylor, P["agm.py"].t_hat, P["length.py"].group_length


def class_answers(rng: random.Random, variant: int) -> dict[str, str]:
    """Problems 1, 2, 3(a), 4, 5 as one student group would answer them: the printed
    programs with the ``variant``'s freedoms."""
    out: dict[str, str] = {}
    r1 = P["problem1.py"].solve()
    out["1b_g"] = r1["g_text"] if variant % 2 else repr(r1["g"])  # the guaranteed digits, or all of them
    out["1b_digits"] = str(r1["digits"])
    a, b, _, _ = P2.interval()
    start = a + (b - a) * rng.random() if variant % 3 else (a if variant % 2 else b)
    xs, delta = P2.newton(start)
    q, _rho, k = P2.quotients(xs, delta)
    c = abs(P2.d2f(xs[-1]) / (2 * P2.df(xs[-1])))
    out["2_x0_deg"] = f"{math.degrees(start):.6f}"
    out["2_alpha_deg"] = repr(math.degrees(xs[-2] if variant % 4 == 1 else xs[-1]))  # a step earlier
    out["2_q0"], out["2_q1"] = f"{q[0]:.6f}", f"{q[1]:.6f}"
    out["2_k_max"], out["2_constant"] = str(k), f"{c:.10f}"
    out["2_error_estimate"] = f"{(c * (xs[-1] - xs[-2]) ** 2 + delta if variant % 2 else abs(xs[-1] - xs[-2])):.2e}"
    t, z1, z2 = TAYLOR(1.0, math.pi / 4, 0.1, 2.1)
    for j in (1, 2, 3, 18, 19, 20, 21):  # Figure 3 prints 12 digits
        out[f"3a_z1_{j}"], out[f"3a_z2_{j}"] = (f"{z1[j]:.12g}", f"{z2[j]:.12g}") if variant % 2 else (
            repr(z1[j]), repr(z2[j]))
    t_max = math.ceil(AGM(P4.L, P4.ALPHA)) if variant % 5 else 6  # 6: the original's Y_0 .. Y_600
    t, z1, _ = TAYLOR(P4.L, P4.ALPHA, P4.H, t_max)
    out["4a_t_max"] = str(t_max)
    for i in range(1, 11):
        out[f"4a_z1_{i}"] = repr(z1[len(t) - 11 + i])
    am, r, _, coef, res = P4.fit(t, z1)
    for i in range(7):
        out[f"4c_A{i + 1}{i + 1}"], out[f"4c_r{i + 1}"] = f"{am[i, i]:.6f}", f"{r[i]:.6f}"
    for name, x in zip(P4.NAMES, coef):
        out[f"4d_{name}"] = f"{x:.10g}"
    out["4d_ssd"] = f"{math.fsum(res ** 2):.6e}"
    out["4d_max_deviation"] = f"{max(abs(res)):.4e}"
    out["4d_below"] = "sim" if max(abs(res)) < P4.TOL else "não"
    rows = P5.table(AGM(P5.L, P5.ALPHA))
    out["5b_single"], out["5c_S10"] = repr(rows[0][1]), repr(rows[1][1])
    for n, s, e, _ in rows[1:]:
        out[f"5d_S_{n}"], out[f"5d_error_{n}"] = repr(s), f"{e:.3e}"
    return out


def group_answers(students, variant: int) -> tuple[dict[str, str], set[str]]:
    """Problem 3(b)-(d) for a group, and the answers of 3(d)'s other tables and fifth nodes
    that no correct method gives (to choose a wrong yes/no)."""
    out: dict[str, str] = {}
    total, digits, l_text = LENGTH(list(students))
    length = float(l_text)
    exact = AGM(length, P3.ALPHA)
    out["3b_sum"], out["3b_length"], out["3b_t_hat"] = str(total), l_text, repr(exact)
    out["3b_digits"] = "".join(map(str, digits))
    t_max, j, over, t = P3.plot_t_max(length, exact)
    out["3b_outcome"] = "returns" if j is not None else "leaves" if over is not None else "none"
    # another favourable t_max: two periods
    out["3b_t_max"] = f"{t_max:.6g}" if variant % 2 else f"{0.2 * math.ceil(2 * exact / 0.2):.6g}"
    if j is not None:
        out["3b_bracket_lo"], out["3b_bracket_hi"] = f"{t[j]:.6g}", f"{t[j + 1]:.6g}"
    negligible = set()
    for h, tag in ((1e-2, "h1e-2"), (1e-3, "h1e-3"), (1e-4, "h1e-4")):
        r = P3.period(length, h, exact)
        est = [r["linear"], r["p0"], r["bracket"][0], r["bracket"][1]][variant % 4]
        out[f"3c_j_{tag}"], out[f"3c_T_{tag}"] = str(r["j"]), f"{est:.10g}"
        out[f"3c_error_{tag}"] = f"{abs(est - exact):.3e}"
    tt, z1, z2 = TAYLOR(length, P3.ALPHA, 1e-3, 1.5 * exact + 8e-3)
    jj = P3.sign_change(z1, z2)[0]
    for s in (-2, -1, 0):
        for fifth in (jj + s - 1, jj + s + 4):
            nodes = [jj + s + k for k in range(4)] + [fifth]
            r = P3.inverse_cubic([z2[k] for k in nodes], [tt[k] for k in nodes])
            small = max(abs(r["e0"]), r["rounding"]) < P3.NEGLIGIBLE * abs(r["p0"] - exact)
            negligible.add("yes" if small else "no")
            if (s, fifth - jj) == ((-1, -2), (-2, 2), (0, 4), (-1, 3), (0, -1), (-2, -3))[variant % 6]:
                for k in range(4):  # the table (z2_j, t_j) and p's Newton coefficients
                    out[f"3d_t{k}"], out[f"3d_z2_{k}"] = f"{tt[jj + s + k]:.3f}", repr(z2[jj + s + k])
                    out[f"3d_c{k}"] = f"{r['coef'][k]:.8e}"
                out["3d_p0"], out["3d_fifth_t"] = repr(r["p0"]), f"{tt[fifth]:.3f}"
                out["3d_divided_difference"], out["3d_error_estimate"] = f"{r['dd4']:.4e}", f"{r['e0']:.3e}"
                out["3d_rounding_level"], out["3d_negligible"] = f"{r['rounding']:.1e}", "yes" if small else "no"
    return out, negligible


def wrong(column: str, text: str, negligible: set[str]) -> str:
    """A wrong answer to ``column``, given the right one."""
    if column in ("3b_outcome",):
        return "none" if text == "returns" else "returns"
    if column == "3d_negligible":
        return "maybe" if negligible == {"yes", "no"} else ("no" if "yes" in negligible else "yes")
    if column in ("4d_below",):
        return "sim"
    if column in ("3b_bracket_lo", "3b_bracket_hi") and not text:
        return "1.5"
    near = {"2_alpha_deg": 1e-9, "3b_t_hat": 1e-12, "3d_p0": 1e-9, "4d_gamma": 1e-6, "5d_S_100000": 1e-11,
            "3a_z1_21": 1e-9, "4c_A22": 2e-8}  # near misses: above rounding, below what a reader sees
    x = float(text.replace(",", "."))
    if column in near:
        return repr(x * (1 + near[column]))
    if column.startswith(("1b_digits", "2_k_max", "3b_sum", "3c_j", "4a_t_max")):
        return str(int(x) + 1)
    if column == "3b_t_max":
        return "0.2"
    return repr(1.5 * x + 1)


def build_class(size: int, seed: int = 29):
    rng = random.Random(seed)
    students = [tuple(rng.randrange(10000, 100000) for _ in range(rng.randint(1, 4))) for _ in range(size)]
    students[0] = (262, 407, 634)
    if size > 3:
        students[1] = (11111,)  # l = 1: the h = 0.2 simulation goes over the top, no bracket
    entries = [Entry(s, None, i + 1) for i, s in enumerate(students)]
    cols = mark.columns()
    rows, wrong_cells = [], set()
    for i, s in enumerate(students):
        answers = class_answers(rng, i)
        group, negligible = group_answers(s, i)
        answers |= group
        for k, c in enumerate(cols):
            if k % size == i:  # one wrong answer per question
                answers[c] = wrong(c, answers.get(c, ""), negligible)
                wrong_cells.add((i, c))
        rows.append(answers)
    return entries, cols, rows, wrong_cells


def answers_csv(entries, cols, rows, delimiter=",", decimal="."):
    buf = io.StringIO()
    w = csv.writer(buf, delimiter=delimiter)
    w.writerow(["line", "students", "names"] + cols)
    for e, a in zip(entries, rows):
        cells = [a.get(c, "") for c in cols]
        if decimal != ".":
            cells = [x.replace(".", decimal) if x[:1].isdigit() or x[:1] == "-" else x for x in cells]
        w.writerow([e.line, " ".join(map(str, e.students)), ""] + cells)
    return buf.getvalue()


def check(marks, wrong_cells, cols):
    for i, g in enumerate(marks.groups):
        for v in g.verdicts:
            expected = (i, v.column) not in wrong_cells
            assert v.right == expected, (i, g.students, v.to_dict())
    assert {c for _, c in wrong_cells} == set(cols)


@pytest.mark.slow
def test_a_class_of_30_every_correct_variant_accepted_every_wrong_refused(tmp_path):
    entries, cols, rows, wrong_cells = build_class(30)
    marks = mark.mark_class(entries, mark.parse_answers(answers_csv(entries, cols, rows)))
    check(marks, wrong_cells, cols)
    # The command line: the marked sheet opens in pandas, one row per group and question.
    import pandas as pd

    groups = tmp_path / "groups.txt"
    groups.write_text("students\n" + "\n".join(" ".join(map(str, e.students)) for e in entries) + "\n")
    answers = tmp_path / "answers.csv"
    answers.write_text(answers_csv([Entry(e.students, None, e.line + 1) for e in entries], cols, rows,
                                   ";", ","), encoding="utf-8")
    out = tmp_path / "marked.csv"
    assert main(["mark", "--groups", str(groups), "--answers", str(answers), "-o", str(out),
                 "--csv-dialect", "excel-pt"]) == 0
    df = pd.read_csv(out, sep=";", decimal=",", encoding="utf-8-sig", dtype={"answer": str})
    assert len(df) == 30 * len(cols) and list(df.columns) == ["line", "students", "names", "flags", "part",
                                                              "question", "answer", "key", "verdict", "why",
                                                              "points", "max_points"]
    assert (df["verdict"] == "wrong").sum() == len(wrong_cells)
    assert df.groupby("line")["points"].sum().tolist() == [
        len(cols) - sum(1 for i2, _ in wrong_cells if i2 == i) for i in range(30)]
    text = out.read_text(encoding="utf-8-sig")
    assert text.splitlines()[0].startswith("line;students;names;flags")


@pytest.fixture(scope="module")
def small_class():
    return build_class(3, seed=7)


def test_three_groups_marked(small_class):
    entries, cols, rows, wrong_cells = small_class
    marks = mark.mark_class(entries, mark.parse_answers(answers_csv(entries, cols, rows)))
    check_some = [(i, v.column, v.right) for i, g in enumerate(marks.groups) for v in g.verdicts
                  if v.right == ((i, v.column) in wrong_cells)]
    assert check_some == []
    s = marks.summary()
    assert s["groups"] == 3 and sum(s["histogram"]) == 3 and s["max_points"] == len(cols)


def test_a_start_at_55_degrees_is_right():
    """The issue's case: Newton from 55 deg gives q_0 = 0.3348, 9.6 % from the program's 0.3055."""
    a, _, _, _ = P2.interval()
    assert math.degrees(a) == pytest.approx(55)
    xs, delta = P2.newton(a)
    q = P2.quotients(xs, delta)[0]
    qs = {x.column: x for x in mark.class_questions()}
    assert mark.judge(qs["2_q0"], f"{q[0]:.4f}")[0]
    assert abs(q[0] - qs["2_q0"].key) / qs["2_q0"].key > 0.09
    assert not mark.judge(qs["2_q0"], "0.36")[0]
    assert mark.judge(qs["2_alpha_deg"], repr(math.degrees(xs[-2])))[1] == "matches"  # a step earlier


def test_answers_in_a_portuguese_spreadsheet(small_class):
    entries, cols, rows, _ = small_class
    text = "\ufeff" + answers_csv(entries, cols, rows, ";", ",")
    a = mark.parse_answers(text)
    b = mark.parse_answers(answers_csv(entries, cols, rows))
    assert [r.students for r in a] == [e.students for e in entries]
    for ra, rb in zip(a, b):
        for c in cols:
            na, nb = mark.read_number(ra.answers[c]), mark.read_number(rb.answers[c])
            assert (na is None and nb is None) or (na is not None and nb is not None and na.value == nb.value)


@pytest.mark.parametrize("text, allowed", [
    ("line,x\n1,2\n", "students"), ("students,bogus\n1,2\n", "columns"),
    ("students,1b_g\n1 2,9.8\n2 1,9.8\n", "one row per group"), ("students,1b_g\n1 x,9.8\n", "student numbers"),
])
def test_bad_answers_are_named(text, allowed):
    with pytest.raises(InputError) as exc:
        mark.parse_answers(text, "a.csv")
    assert exc.value.name == "answers" and allowed in str(exc.value)


def test_an_answer_of_no_group_is_refused():
    with pytest.raises(InputError) as exc:
        mark.mark_class(parse_entries("262 407 634\n"), mark.parse_answers("students\n1 2\n"), source="a.csv")
    assert "a.csv row 2" in str(exc.value)


@pytest.mark.parametrize("scheme, ok", [
    ('{"points": {"2_q0": 3}}', True), ('{"points": {"nope": 1}}', False), ('{"points": {"2_q0": -1}}', False),
    ('{"min_digits": {"2_q0": 40}}', False), ("[1]", False), ("{", False), ('{"min_digits": {"2_q0": 2}}', True),
])
def test_scheme(scheme, ok):
    if ok:
        s = mark.parse_scheme(scheme)
        assert s.points["1b_g"] == 1 and (s.points["2_q0"] == 3 or s.min_digits["2_q0"] == 2)
    else:
        with pytest.raises(InputError):
            mark.parse_scheme(scheme)


def test_default_scheme_round_trip():
    s = mark.default_scheme()
    assert mark.parse_scheme(json.dumps(s.to_dict())) == s
    assert set(s.points) == set(mark.columns())


_DECIMAL = st.decimals(allow_nan=False, allow_infinity=False, places=None).filter(lambda d: abs(d) < 10**300)


@settings(max_examples=200, deadline=None)
@given(_DECIMAL, st.booleans())
def test_read_number_point_or_comma(d, comma):
    text = str(d)
    written = text.replace(".", ",") if comma else text
    n = mark.read_number(written)
    assert n is not None and n.value == float(text)
    digits = d.as_tuple().digits
    assert n.digits == max(1, len("".join(map(str, digits)).lstrip("0")))


@settings(max_examples=100, deadline=None)
@given(st.text(alphabet="0123456789,.;e-+ x\"\n", max_size=60))
def test_answers_parser_accepts_or_names(text):
    try:
        rows = mark.parse_answers("students;1b_g\n" + text, "f")
    except InputError as exc:
        assert exc.name == "answers"
    else:
        assert all(r.students and all(n > 0 for n in r.students) for r in rows)


def test_template_and_cli_text(tmp_path, capsys):
    groups = tmp_path / "g.txt"
    groups.write_text("números;nomes\n262;407;634;Ana Sá;João Simões;Maria Luís\n", encoding="utf-8")
    tpl = tmp_path / "answers.csv"
    assert main(["key", "--groups", str(groups), "--template", "-o", str(tpl)]) == 0
    head = next(csv.reader(io.StringIO(tpl.read_text(encoding="utf-8"))))
    assert head[:3] == ["line", "students", "names"] and head[3:] == mark.columns()
    assert main(["mark", "--groups", str(groups), "--answers", str(tpl)]) == 0
    out = capsys.readouterr().out
    assert "line 2: 262 407 634 (Ana Sá; João Simões; Maria Luís)  0/" in out and "no answer" in out
    assert main(["mark", "--groups", str(groups), "--answers", str(tpl), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    g = d["groups"][0]
    assert g["points"] == 0 and g["max_points"] == len(mark.columns())
    assert {v["code"] for v in g["verdicts"]} == {"missing"}
    assert main(["key", "--groups", str(groups), "--template", "scheme"]) == 0
    assert mark.parse_scheme(capsys.readouterr().out).points["1b_g"] == 1


def test_bad_option_is_one_line(tmp_path, capsys):
    groups = tmp_path / "g.txt"
    groups.write_text("262 407 634\n")
    assert main(["mark", "--groups", str(groups), "--answers", str(tmp_path / "none.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "answers" in err[0]


@pytest.mark.parametrize("students", [(262, 407, 634), (11111,), (98765, 43210)])
def test_engine_lists_are_the_programs(students):
    """mark takes problem 3's Taylor lists from the engine: the program's doubles, bit for bit."""
    from pendulab.numerics.simulation import simulate

    length = float(LENGTH(list(students))[2])
    exact = AGM(length, P3.ALPHA)
    for h in (1e-2, 1e-3, 1e-4):
        t, z1, z2 = TAYLOR(length, P3.ALPHA, h, 1.5 * exact + 8 * h)
        run = simulate(length, P3.ALPHA, h, 1.5 * exact + 8 * h)
        assert run.t.tolist() == t and run.theta.tolist() == z1 and run.omega.tolist() == z2


def test_the_same_digits_in_key_and_marked_sheet(tmp_path):
    """A question's key prints the same in key.csv, key-class.csv, key --json and the marked
    sheet: the report's digit policy (pendulab.core.digits)."""
    from pendulab.core import digits
    from pendulab.jobs.key import answer_key
    from pendulab.report import key as key_out
    from pendulab.report import mark as sheet

    entries = parse_entries("262 407 634\n11111\n")
    k = answer_key(entries)
    d = key_out.document(k)
    rows = list(csv.DictReader(io.StringIO(key_out.render(k, "csv").decode())))
    marks = mark.mark_class(entries, [])
    marked = sheet.sheet(marks)
    printed = {(r[0], r[5]): r[7] for r in marked[1:]}
    for g, row, qd in zip(k.groups, rows, d["questions"]["groups"]):
        for q in qd["questions"]:
            assert row[f"key_{q['column']}"] == q["key_text"] == printed[(str(g["line"]), q["column"])]
    # 3(d)'s p(0) in the digits the report's policy gives an estimate of its rounding
    q = next(x for x in mark.group_questions((262, 407, 634)) if x.column == "3d_p0")
    assert mark.key_text(q) == digits.shown("estimate", q.key, q.slack)
    # problem 5 of the key is the printed program's
    rows5 = P5.table(AGM(P5.L, P5.ALPHA))
    assert [r["estimate"] for r in d["common"]["problem5"]["rows"]] == [r[1] for r in rows5]
    side = key_out._class_csv(k)
    for q in mark.class_questions():
        assert f"question {q.part},{q.column},{mark.key_text(q)}" in side


@pytest.mark.slow
def test_marked_sheet_pdf_and_text(tmp_path):
    import pypdf

    groups = tmp_path / "g.txt"
    groups.write_text("262 407 634 | Ana Sá; João Simões; Maria Luís\n12121, 21212, 12121\n", encoding="utf-8")
    tpl = tmp_path / "answers.csv"
    assert main(["key", "--groups", str(groups), "--template", "-o", str(tpl)]) == 0
    for out in (tmp_path / "m.pdf", tmp_path / "m.txt"):
        assert main(["mark", "--groups", str(groups), "--answers", str(tpl), "-o", str(out), "--lang", "pt"]) == 0
    text = " ".join(p.extract_text() for p in pypdf.PdfReader(tmp_path / "m.pdf").pages)
    assert "Grupos: 2" in text and "262, 407, 634" in text and "sem resposta" in text
    assert "o aluno 12121 aparece 2 vezes" in text.replace("\n", " ")
    plain = (tmp_path / "m.txt").read_text(encoding="utf-8")
    assert plain.startswith("line 1: 262 407 634 (Ana Sá; João Simões; Maria Luís)  0/")
    assert "90-100 %" in plain


def test_a_formula_in_an_answer_is_never_run():
    """An answer typed as =1+1 (or a name starting with @) reaches the sheet as text."""
    from pendulab.report import mark as sheet

    entries = parse_entries("262 407 634 | @Ana; Rui; Eva\n")
    rows = mark.parse_answers("students,1b_g,2_q0\n262 407 634,=HYPERLINK(1),-0.3\n")
    text = sheet.render(mark.mark_class(entries, rows), "csv").decode()
    cells = list(csv.reader(io.StringIO(text)))
    assert "'=HYPERLINK(1)" in [c for r in cells for c in r] and "'@Ana; Rui; Eva" in cells[1]
    assert "-0.3" in [c for r in cells for c in r]
    pt = sheet.render(mark.mark_class(entries, rows), "csv", dialect="excel-pt").decode("utf-8-sig")
    pt_cells = [c for r in csv.reader(io.StringIO(pt), delimiter=";") for c in r]
    assert "-0.3" in pt_cells and "'=HYPERLINK(1)" in pt_cells  # an answer as typed, never run


@pytest.mark.slow
@pytest.mark.parametrize(("redirect", "reason"), [(">&-", "Bad file descriptor"), ("> /dev/full", "No space left")])
def test_template_on_a_bad_stdout_is_one_line(tmp_path, redirect, reason):
    """The answers template written to standard output goes through the checked writer."""
    import subprocess
    import sys

    groups = tmp_path / "g.txt"
    groups.write_text("262 407 634\n")
    res = subprocess.run(f"{sys.executable} -m pendulab key --groups {groups} --template answers {redirect}",
                         shell=True, capture_output=True, text=True, timeout=300)
    assert res.returncode == 1
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pendulab key: error: cannot write to standard output: " + reason)


def test_an_untrusted_3b_return_is_marked_and_said_untrusted(tmp_path, capsys):
    """A sum of 1115 (l = 1.4953487812): problem3.py's h = 0.2 simulation returns, at a bracket
    27 % of T off, which the engine calls untrusted (the report's and key's 3(b)). A student
    who answers as the program does is right, and the mark says "untrusted" beside 3(b)'s
    outcome and bracket, in the text (right answers are otherwise not listed), --json and pt."""
    from pendulab.report.mark import why

    _total, _digits, l_text = LENGTH([1115])
    _t_max, j, _over, t = P3.plot_t_max(float(l_text), AGM(float(l_text), P3.ALPHA))
    assert j is not None  # the program finds a return
    answers = {"3b_outcome": "returns", "3b_bracket_lo": repr(t[j]), "3b_bracket_hi": repr(t[j + 1])}
    cols = ("3b_outcome", "3b_bracket_lo", "3b_bracket_hi")
    gm = mark.mark_group(Entry((1115,), None, 1), mark.AnswerRow((1115,), 2, answers), mark.default_scheme())
    v = {x.column: x for x in gm.verdicts}
    assert all(v[c].right and v[c].status == "untrusted" for c in cols), [(v[c].right, v[c].status) for c in cols]
    assert "untrusted" in why(v["3b_outcome"]) and "não fiável" in why(v["3b_bracket_lo"], "pt")
    assert not any(x.status for c, x in v.items() if c not in cols)  # only 3(b)'s return
    trusted = {q.column: q for q in mark.group_questions((262, 407, 634))}
    assert trusted["3b_outcome"].status == trusted["3b_bracket_lo"].status == ""
    # the command's text and --json
    groups = tmp_path / "g.txt"
    groups.write_text("1115\n", encoding="utf-8")
    sheet = tmp_path / "answers.csv"
    sheet.write_text(answers_csv([Entry((1115,), None, 1)], mark.columns(), [answers]), encoding="utf-8")
    assert main(["mark", "--groups", str(groups), "--answers", str(sheet)]) == 0
    lines = [line for line in capsys.readouterr().out.splitlines() if line.split()[:1] == ["3b_outcome"]]
    assert len(lines) == 1 and "returns" in lines[0] and "untrusted" in lines[0]
    assert main(["mark", "--groups", str(groups), "--answers", str(sheet), "--json"]) == 0
    d = {x["column"]: x for x in json.loads(capsys.readouterr().out)["groups"][0]["verdicts"]}
    assert d["3b_outcome"]["right"] and d["3b_outcome"]["status"] == "untrusted" and "untrusted" in d["3b_outcome"]["why"]
