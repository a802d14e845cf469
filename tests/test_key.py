"""``pendulab key``: every group's problem 3 answers, checked against plain Python.

The reference is :mod:`plain_pendulum`, written in this folder from the coursework's
formulas (group length, AGM (8), Taylor (3), sign change, inverse interpolation by
divided differences), not the library's code.
"""
from __future__ import annotations

import csv
import io
import json
import math
from decimal import Decimal

import pypdf
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plain_pendulum as plain
from pendulab.cli import main
from pendulab.core.errors import InputError
from pendulab.jobs.key import answer_key, parse_entries, parse_groups, repeated_students
from reference import EXAMPLE_LENGTH, EXAMPLE_LENGTH_TEXT, KEY_AGREEMENT, G

GROUPS = [(262, 407, 634), (99999, 1), (81234, 90876), (11111,), (98765, 43210, 55555)]


@pytest.fixture(scope="module")
def key():
    return answer_key(GROUPS)


@pytest.mark.parametrize("i", range(len(GROUPS)))
def test_group_answers_match_plain_python(key, i):
    g = key.groups[i]
    students = GROUPS[i]
    assert g["students"] == list(students)
    assert g["length_text"] == plain.length_text(students)
    length = float(g["length_text"])
    t_hat = plain.t_hat(length)
    assert g["t_hat"] == pytest.approx(t_hat, rel=KEY_AGREEMENT["3(b) T^ (8), 7 iterations"])
    digits = str(sum(students)).replace("0", "")
    assert g["sum"] == sum(students) and g["digits"] == digits
    # 3(b): what the h = 0.2 simulation does first, searched over four t_hat periods.
    event = plain.first_event(length, 0.2, 4 * t_hat)
    assert g["plot"]["outcome"] == event[0]
    if event[0] == "returns":
        j = event[1]
        assert g["plot"]["j"] == j
        assert g["plot"]["bracket"] == [float(Decimal(j) * Decimal("0.2")), float(Decimal(j + 1) * Decimal("0.2"))]
        assert g["plot"]["t_hat_inside"] == (j * 0.2 <= t_hat <= (j + 1) * 0.2)
        assert g["plot"]["left_at"] is None
    else:
        assert g["plot"]["left_at"] == pytest.approx(event[1], abs=1e-12)
        assert g["plot"]["bracket"] is None and g["plot"]["t_hat_inside"] is None
    # 3(c)-(d): each step's bracket and estimates.
    assert [e["step"] for e in g["estimates"]] == [1e-2, 1e-3, 1e-4]
    # The plain program agrees with the key within KEY_AGREEMENT.
    t_abs = KEY_AGREEMENT["3(c) T linear, T = p(0) and their errors"]
    errors = []
    for e in g["estimates"]:
        ref = plain.estimate(length, e["step"])
        assert e["j"] == ref["j"]
        assert e["bracket"] == [float(Decimal(ref["j"] + k) * Decimal(repr(e["step"]))) for k in (0, 1)]
        assert e["bracket"] == pytest.approx(list(ref["bracket"]), abs=1e-12)
        assert e["linear"] == pytest.approx(ref["linear"], abs=t_abs)
        assert e["cubic"] == pytest.approx(ref["cubic"], abs=t_abs)
        assert e["linear_t_hat_error"] == pytest.approx(abs(ref["linear"] - t_hat), abs=t_abs)
        assert e["cubic_t_hat_error"] == pytest.approx(abs(ref["cubic"] - t_hat), abs=t_abs)
        assert e["cubic_error_estimate"] == pytest.approx(ref["error_estimate"],
                                                          abs=KEY_AGREEMENT["3(d) error estimate"])
        errors.append((e["step"], abs(ref["linear"] - t_hat), abs(ref["cubic"] - t_hat)))
    for (h0, l0, c0), (h1, l1, c1), e in zip(errors, errors[1:], g["estimates"][1:]):
        order = KEY_AGREEMENT["3(c) observed orders"]
        assert e["linear_order"] == pytest.approx(math.log(l0 / l1) / math.log(h0 / h1), abs=order)
        assert e["cubic_order"] == pytest.approx(math.log(c0 / c1) / math.log(h0 / h1), abs=order)
    assert g["estimates"][0]["linear_order"] is None
    ip = g["interpolation"]
    ref = plain.estimate(length, 1e-3)
    assert [row["node"] for row in ip["table"]] == [ref["j"] - 1 + k for k in range(4)]
    assert [row["t"] for row in ip["table"]] == list(ref["times"])  # the nodes (3)'s program used, bit for bit
    assert [row["z2"] for row in ip["table"]] == pytest.approx(ref["nodes"], rel=KEY_AGREEMENT["3(d) nodes x_k = z_(2,j-1+k)"])
    assert [row["coefficient"] for row in ip["table"]] == pytest.approx(ref["coefficients"],
                                                                        rel=KEY_AGREEMENT["3(d) Newton coefficients"])


def test_the_interpolation_table_lists_the_nodes_used():
    """Issue 32: at l of the group 11112, t_3558 = fl(3558 x 0.001) = 3.5580000000000003, one ulp
    above 3.558: the key's 3(d) table holds the node the interpolation and the program used."""
    from pendulab.jobs.key import group_answers

    table = group_answers((11112,))["interpolation"]["table"]
    ref = plain.estimate(float(plain.length_text((11112,))), 1e-3)
    assert [row["t"] for row in table] == list(ref["times"]) == [(ref["j"] - 1 + k) * 1e-3 for k in range(4)]
    assert any(row["t"] != float(Decimal(row["node"]) / 1000) for row in table)  # the check can fail


def test_short_pendulums_leave_the_oscillation(key):
    # l = 1 (all digits 1): the h = 0.2 simulation goes over the top; l = 2.08 returns.
    by = {tuple(g["students"]): g for g in key.groups}
    assert by[(99999, 1)]["plot"]["outcome"] == "leaves"
    assert by[(11111,)]["plot"]["outcome"] == "leaves"
    assert by[(262, 407, 634)]["plot"]["outcome"] == "returns"


def test_common_answers_once(key):
    d = key.to_dict()
    assert set(d["common"]) == {"problem1", "problem2", "problem4", "problem4_601", "problem5"}
    assert all("problem1" not in g for g in d["groups"])
    # Independent: g = 4 pi^2 l / T^2 of 1(b), and (9) solved in closed form for 2.
    import math

    assert d["common"]["problem1"]["g"] == pytest.approx(4 * math.pi**2 * 1.152 / 2.1536**2,
                                                         rel=KEY_AGREEMENT["1(b) g"])
    p = math.sqrt(G / 0.5)
    assert d["common"]["problem2"]["alpha"] == pytest.approx(2 * math.asin(2 * math.sqrt(1.5 * p / (2 * math.pi) - 1)),
                                                             abs=KEY_AGREEMENT["2 alpha"])
    assert d["common"]["problem4"]["points"] == 401 and d["common"]["problem4_601"]["points"] == 601
    assert [r["n"] for r in d["common"]["problem5"]["rows"]] == [1, 10, 100, 1000, 10000, 100000]
    q = d["common"]["problem2"]["q"]
    x = d["common"]["problem2"]["iterates"]
    assert q == [abs(x[k + 2] - x[k + 1]) / abs(x[k + 1] - x[k]) ** 2 for k in range(len(x) - 2)]
    assert "tolerances" not in d  # what a correct method may give is each question's range (questions)


def test_parse_groups_commas_spaces_comments():
    text = "# the class\n262, 407, 634\n\n99999 1   # two students\n1,2 3\n"
    assert parse_groups(text) == [(262, 407, 634), (99999, 1), (1, 2, 3)]


def test_parse_groups_with_names():
    text = "262, 407, 634 | Ana Sá; João Simões; Ζωή\n1 2\n3 4 |  Ольга ;李明 \n"
    entries = parse_entries(text)
    assert [(e.students, e.names, e.line) for e in entries] == [
        ((262, 407, 634), ("Ana Sá", "João Simões", "Ζωή"), 1), ((1, 2), None, 2), ((3, 4), ("Ольга", "李明"), 3)]


@pytest.mark.parametrize("text", [
    "students;names\n262;407;634;Ana Sá;João Simões;Maria Luís\n",
    "números,nomes\n262,407,634,Ana Sá,João Simões,Maria Luís\n",
    '"262 407 634","Ana Sá; João Simões; Maria Luís"\n',
    "262 407 634;Ana Sá;João Simões;Maria Luís;;;\n",
    "\ufeffstudents\n262 407 634 | Ana Sá; João Simões; Maria Luís\n",
])
def test_groups_as_spreadsheets_write_them(text):
    [e] = parse_entries(text)
    assert e.students == (262, 407, 634) and e.names == ("Ana Sá", "João Simões", "Maria Luís")


def test_groups_semicolons_and_padding():
    text = "alunos\n262;407;634\n99999;1;;\n;;;\n"
    assert parse_groups(text) == [(262, 407, 634), (99999, 1)]


def test_header_only_first():
    with pytest.raises(InputError) as exc:
        parse_groups("262 407\nstudents\n", "g.txt")
    assert "g.txt line 2:" in str(exc.value.value)


def test_repeated_students_within_and_across():
    entries = parse_entries("12121, 21212, 12121\n262 407 634\n407 5\n634 407 262\n")
    got = {(r.student, r.line): (r.within, r.other_lines) for r in repeated_students(entries)}
    assert got == {(12121, 1): (2, ()), (407, 2): (1, (3,)), (407, 3): (1, (2,)), (407, 4): (1, (3,))}
    k = answer_key(entries[:1])
    assert k.groups[0]["repeated"] == [{"student": 12121, "line": 1, "within": 2, "other_lines": []}]


_NAME = st.text(alphabet="abcçãéíóú ÁBZ", min_size=1, max_size=8).map(lambda s: " ".join(s.split())).filter(bool)


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.lists(st.integers(1, 10**7), min_size=1, max_size=4), st.booleans()), min_size=1, max_size=5),
       st.sampled_from([";", ",", "|"]), st.booleans(), st.data())
def test_groups_with_names_round_trip(rows, delimiter, header, data):
    lines = ["students" + (f"{delimiter}names" if delimiter != "|" else "")] if header else []
    want = []
    for numbers, named in rows:
        names = [data.draw(_NAME) for _ in numbers] if named else None
        if delimiter == "|":
            line = ", ".join(map(str, numbers)) + (" | " + "; ".join(names) if names else "")
        else:
            line = delimiter.join(map(str, numbers + (names or [])))
        lines.append(line)
        want.append((tuple(numbers), None if names is None else tuple(names)))
    got = [(e.students, e.names) for e in parse_entries("\n".join(lines))]
    assert got == want


@pytest.mark.parametrize("text, line", [
    ("262,407\n12a, 5\n", 2), ("1\n\n-3 4\n", 3), ("0\n", 1), ("5\n7 8\nx\n", 3), ("1.5 2\n", 1),
    ("5,,6\n", 1), ("7 8\n262 ² 634\n", 2), ("１２\n", 1),
    ("1 2 | Ana\n", 1), ("1\n2 | A; B\n", 2), ("1 | \n", 1), ("| Ana\n", 1),
])
def test_bad_line_is_named(text, line):
    with pytest.raises(InputError) as exc:
        parse_groups(text, "g.txt")
    assert f"g.txt line {line}:" in str(exc.value.value)


def test_empty_file_is_refused():
    with pytest.raises(InputError):
        parse_groups("# nothing\n\n")


@settings(max_examples=60, deadline=None)
@given(st.lists(st.lists(st.integers(1, 10**7), min_size=1, max_size=5), min_size=1, max_size=6),
       st.sampled_from([", ", " ", ",", " , "]))
def test_parse_groups_round_trip(groups, sep):
    text = "\n".join(sep.join(map(str, g)) for g in groups)
    assert parse_groups(text) == [tuple(g) for g in groups]


@settings(max_examples=60, deadline=None)
@given(st.text(alphabet="0123456789 ,#-.ax\n", max_size=40))
def test_parse_groups_accepts_or_names_a_line(text):
    try:
        groups = parse_groups(text, "f")
    except InputError as exc:
        assert exc.name == "groups"
    else:
        assert groups and all(g and all(n >= 0 for n in g) for g in groups)


@pytest.fixture
def groups_file(tmp_path):
    p = tmp_path / "groups.txt"
    p.write_text("# two groups\n262, 407, 634\n99999 1\n", encoding="utf-8")
    return p


def test_cli_json(groups_file, capsys):
    assert main(["key", "--groups", str(groups_file), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert [g["students"] for g in d["groups"]] == [[262, 407, 634], [99999, 1]]
    for g in d["groups"]:
        assert {"students", "length", "t_hat", "estimates", "names", "line", "duplicate_of"} <= set(g)
        assert "exact" not in g
        for e in g["estimates"]:
            assert {"step", "bracket", "linear", "cubic", "cubic_error_estimate", "linear_order"} <= set(e)


@pytest.fixture
def class_file(tmp_path):
    """A class with names, a group listed twice (numbers in another order) and an l = 1 group."""
    p = tmp_path / "class.txt"
    p.write_text("# class\n262, 407, 634 | Ana Sá; João \"Jó\" Simões, Jr.; 李明\n45678 53221\n99999 1\n"
                 "634 262 407\n", encoding="utf-8")
    return p


@pytest.mark.slow
def test_cli_csv_is_a_plain_table(class_file, tmp_path, capsys):
    import pandas as pd

    out = tmp_path / "key.csv"
    assert main(["key", "--groups", str(class_file), "--output", str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    warnings = [line for line in err if "warning" in line]
    assert warnings == ["pendulab: warning: 1 group listed more than once: 262 407 634 (lines 2, 5)"]
    text = out.read_text(encoding="utf-8")
    rows = list(csv.reader(io.StringIO(text)))
    assert len(rows) == 1 + 4 and len({len(r) for r in rows}) == 1  # one header, one row per group
    assert not any(line.startswith("#") for line in text.splitlines())
    df = pd.read_csv(out)  # as a spreadsheet reads it: no options
    assert list(df["line"]) == [2, 3, 4, 5] and df.shape == (4, len(rows[0]))
    assert list(df["duplicate_of_line"].isna()) == [True, True, True, False] and df["duplicate_of_line"][3] == 2
    assert df["names"][0] == 'Ana Sá; João "Jó" Simões, Jr.; 李明' and df["names"].isna()[1]
    assert list(df["sum"]) == [1303, 98899, 100000, 1303] and str(df["nonzero_digits"][2]) == "1"
    assert list(df["h0.2_t_hat_inside"].fillna("")) == ["no", "yes", "", "no"]
    assert df["h0.2_bracket_lo"][1] == 9.6 and df["h0.2_left_at"][2] == 4.0  # t_j = j h, no float noise
    for h in ("0.01", "0.001", "0.0001"):
        for col in ("j", "bracket_lo", "bracket_hi", "linear", "linear_t_hat_error", "linear_order", "cubic",
                    "cubic_t_hat_error", "cubic_order", "cubic_error_estimate"):
            assert f"h{h}_{col}" in df
    for k in range(4):
        assert {f"3d_node{k}", f"3d_z2{k}", f"3d_t{k}", f"3d_coefficient{k}"} <= set(df)
    assert df["t_hat"][0] == pytest.approx(plain.t_hat(EXAMPLE_LENGTH), rel=1e-15)
    # Every float cell is the shortest text that reads back as its double; the key_ columns
    # are the questions of pendulab mark in the report's printed digits.
    header = rows[0]
    for row in rows[1:]:
        for name, cell in zip(header, row):
            if not name.startswith("key_") and "." in cell and "_" in name and cell.replace(".", "").replace("-", "").replace("e", "").isdigit():
                assert repr(float(cell)) == cell, (name, cell)
    # The class-wide answers beside it, a plain table too.
    side = pd.read_csv(tmp_path / "key-class.csv")
    assert list(side.columns) == ["problem", "answer", "value"]
    answers = dict(zip(side["answer"], side["value"]))
    assert {"q_0", "q_1", "q_2", "k_max", "A_11", "r_7", "estimate_n100000", "ssd"} <= set(answers)
    # Each class question with what a correct method may give; no fixed tolerance beside them.
    assert "4 (601 points)" in set(side["problem"]) and "tolerance" not in set(side["problem"])
    assert {"question 2(c)", "question 5(d)"} <= set(side["problem"])


@pytest.mark.slow
def test_cli_pdf_has_the_class_page_and_names(class_file, tmp_path, capsys):
    pdf = tmp_path / "key.pdf"
    assert main(["key", "--groups", str(class_file), "--output", str(pdf)]) == 0
    reader = pypdf.PdfReader(str(pdf))
    content = "\n".join(p.extract_text() for p in reader.pages)
    assert EXAMPLE_LENGTH_TEXT in content and "99999, 1" in content and "leaves at" in content
    assert "Ana Sá" in content and "line 2" in content
    words = " ".join(content.split())
    for phrase in ("Answers common to every group", "Problem 2", "401 points", "601 points", "Problem 5"):
        assert phrase in words, phrase
    assert "Marking tolerances" not in words
    for n in ("10000", "100000"):
        assert f"\n{n} " in content


@pytest.mark.parametrize("content, args, words", [
    ("1,2\nabc\n", [], "line 2"),
    ("1,2\n", ["--output", "key.txt"], "--output"),
    ("1,2\n", ["--output", "/nonexistent-folder/key.csv"], "--output"),
])
def test_cli_bad_input_one_line_before_the_work(tmp_path, capsys, monkeypatch, content, args, words):
    from pendulab.jobs import key as key_module

    def no_work(*a, **k):
        raise AssertionError("the work started")

    monkeypatch.setattr(key_module, "answer_key", no_work)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "g.txt").write_text(content)
    assert main(["key", "--groups", "g.txt", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["g.txt"]


def test_missing_groups_file(tmp_path, capsys):
    assert main(["key", "--groups", str(tmp_path / "none.txt")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--groups" in err


def test_failed_run_keeps_the_older_file(groups_file, tmp_path, monkeypatch):
    from pendulab.report import key as key_module

    out = tmp_path / "key.json"
    out.write_text("older")

    def broken(*a, **k):
        raise RuntimeError("rendering failed")

    monkeypatch.setattr(key_module, "render", broken)
    with pytest.raises(RuntimeError):
        main(["key", "--groups", str(groups_file), "--output", str(out)])
    assert out.read_text() == "older"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["groups.txt", "key.json"]


def test_the_coursework_programs_reach_the_class_wide_tolerances(key):
    """The key's answers within KEY_AGREEMENT: the plain coursework programs (numpy/scipy, written
    from the formulas, independent of the engine) agree with the key's answers to them."""
    import numpy as np

    from pendulab.jobs.coursework import load

    p = load()
    c = key.to_dict()["common"]
    one = p["problem1.py"].solve()
    rel = KEY_AGREEMENT["1(b) |e_g|, |e_g|/|g| and the corner extremes"]
    assert c["problem1"]["g"] == pytest.approx(one["g"], rel=KEY_AGREEMENT["1(b) g"])
    for mine, theirs in (("abs_error", "abs_error"), ("rel_error", "rel_error"), ("g_min", "g_min"),
                         ("g_max", "g_max"), ("worst_error", "worst")):
        assert c["problem1"][mine] == pytest.approx(one[theirs], rel=rel)
    assert c["problem1"]["significant_digits"] == one["digits"] and c["problem1"]["g_text"] == one["g_text"]
    p2 = p["problem2.py"]
    _a, b, _, _ = p2.interval()
    xs, delta = p2.newton(b)
    q, _, k_max = p2.quotients(xs, delta)
    assert math.radians(c["problem2"]["interval_deg"][0]) <= xs[-1] <= math.radians(c["problem2"]["interval_deg"][1])
    assert c["problem2"]["alpha"] == pytest.approx(xs[-1], abs=KEY_AGREEMENT["2 alpha"])
    assert c["problem2"]["k_max"] == k_max
    assert c["problem2"]["q"][:k_max + 1] == pytest.approx(q[:k_max + 1], rel=KEY_AGREEMENT["2 q_k for k <= k_max"])
    p4, taylor, agm = p["problem4.py"], p["taylor.py"], p["agm.py"]
    for part in ("problem4", "problem4_601"):
        t, z1, _ = taylor.taylor(p4.L, p4.ALPHA, p4.H, c[part]["t_max"])
        A, r, _, coef, res = p4.fit(t, z1)
        assert np.array_equal(A, c[part]["normal_matrix"]) and np.array_equal(r, c[part]["normal_rhs"])
        assert c[part]["coefficients"] == pytest.approx(list(coef), abs=KEY_AGREEMENT["4 coefficients"])
        assert c[part]["ssd"] == pytest.approx(math.fsum(res**2), rel=KEY_AGREEMENT["4 SSD E(c)"])
        assert c[part]["max_deviation"] == pytest.approx(np.max(np.abs(res)), abs=KEY_AGREEMENT["4 max deviation"])
    p5 = p["problem5.py"]
    rows = p5.table(agm.t_hat(p5.L, p5.ALPHA))
    assert [r["n"] for r in c["problem5"]["rows"]] == [n for n, *_ in rows]
    for mine, (n, s_n, err, rate) in zip(c["problem5"]["rows"], rows):
        assert mine["estimate"] == pytest.approx(s_n, rel=KEY_AGREEMENT["5 S_n for every n"]), n
        assert mine["error"] == pytest.approx(err, rel=KEY_AGREEMENT["5 errors and rates"]), n
        assert mine["rate"] == (None if rate is None else pytest.approx(rate, rel=KEY_AGREEMENT["5 errors and rates"]))


@pytest.mark.parametrize("old_class", [True, False])
def test_a_failure_between_the_two_renames_leaves_the_old_pair(key, tmp_path, monkeypatch, old_class):
    """key.csv and key-class.csv are written as one: a rename that fails after the first
    one puts the old key back (or removes the new one where there was none) and leaves no
    temporary file."""
    import os

    from pendulab.core import atomic
    from pendulab.report.key import write_key

    out, side = tmp_path / "key.csv", tmp_path / "key-class.csv"
    out.write_text("old key\n")
    if old_class:
        side.write_text("old class\n")
    calls = []
    real = os.replace

    def replace(src, dst):
        if str(dst).endswith(".journal"):  # the commit's journal put in place: not one of the pair
            return real(src, dst)
        calls.append(dst)
        if len(calls) == 2:  # the first file is in place, the second not
            assert out.read_text().startswith("line,students")
            raise OSError(28, "No space left on device")
        real(src, dst)

    monkeypatch.setattr(atomic.os, "replace", replace)
    with pytest.raises(OSError):
        write_key(key, out)
    assert calls[:2] == [out, side]
    assert out.read_text() == "old key\n"
    assert side.read_text() == "old class\n" if old_class else not side.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["key.csv"] + ["key-class.csv"] * old_class)
    out.unlink()  # no old key at all: the new one is removed again, no stale partner
    calls.clear()
    with pytest.raises(OSError):
        write_key(key, out)
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["key-class.csv"] * old_class
    monkeypatch.setattr(atomic.os, "replace", real)
    assert write_key(key, out) == [out, side]  # and a write that succeeds writes both
    assert out.read_text().startswith("line,students") and side.read_text().startswith("problem,answer,value")


def test_groups_listed_again_are_data_and_the_warning_names_each(tmp_path, capsys):
    from pendulab.jobs.key import listed_again

    text = "1 2\n3 4\n2 1\n5\n4 3\n1 2\n"
    assert listed_again(parse_entries(text)) == [((1, 2), [1, 3, 6]), ((3, 4), [2, 5])]
    assert listed_again(parse_entries("1 2\n3 4\n")) == []
    groups = tmp_path / "g.txt"
    groups.write_text(text)
    assert main(["key", "--groups", str(groups), "--json"]) == 0
    warnings = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert warnings == ["pendulab: warning: 2 groups listed more than once: 1 2 (lines 1, 3, 6); 3 4 (lines 2, 5)"]
