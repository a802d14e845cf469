"""``pendulab key``: every group's problem 3 answers, checked against plain Python.

The reference is :mod:`plain_pendulum`, written in this folder from the coursework's
formulas (group length, AGM (8), Taylor (3), sign change, inverse interpolation by
divided differences), not the library's code.
"""
from __future__ import annotations

import csv
import io
import json

import pypdf
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import plain_pendulum as plain
from pendulab.cli import main
from pendulab.errors import InputError
from pendulab.key import answer_key, parse_groups

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
    exact = plain.agm7_period(length)
    assert g["t_hat"] == pytest.approx(exact, rel=1e-15)
    # 3(b): what the h = 0.2 simulation does first, searched over four exact periods.
    event = plain.first_event(length, 0.2, 4 * exact)
    assert g["plot"]["outcome"] == event[0]
    if event[0] == "returns":
        assert g["plot"]["j"] == event[1]
        assert g["plot"]["bracket"] == pytest.approx([event[1] * 0.2, (event[1] + 1) * 0.2], abs=1e-12)
        assert g["plot"]["left_at"] is None
    else:
        assert g["plot"]["left_at"] == pytest.approx(event[1], abs=1e-12)
        assert g["plot"]["bracket"] is None
    # 3(c)-(d): each step's bracket and estimates.
    assert [e["step"] for e in g["estimates"]] == [1e-2, 1e-3, 1e-4]
    for e in g["estimates"]:
        ref = plain.estimate(length, e["step"])
        assert e["j"] == ref["j"]
        assert e["bracket"] == pytest.approx(list(ref["bracket"]), abs=1e-12)
        assert e["linear"] == pytest.approx(ref["linear"], rel=1e-12)
        assert e["cubic"] == pytest.approx(ref["cubic"], rel=1e-12)
        assert e["cubic_error"] == pytest.approx(abs(ref["cubic"] - exact), rel=1e-6, abs=1e-15)
        # The estimate is a difference of nearly equal numbers: compare at its own scale.
        assert e["cubic_error_estimate"] == pytest.approx(ref["error_estimate"], rel=1e-6, abs=1e-13)
    ip = g["interpolation"]
    ref = plain.estimate(length, 1e-3)
    assert [row["node"] for row in ip["table"]] == [ref["j"] - 1 + k for k in range(4)]
    assert [row["z2"] for row in ip["table"]] == pytest.approx(ref["nodes"], rel=1e-12)
    assert [row["coefficient"] for row in ip["table"]] == pytest.approx(ref["coefficients"], rel=1e-9)


def test_short_pendulums_leave_the_oscillation(key):
    # l = 1 (all digits 1): the h = 0.2 simulation goes over the top; l = 2.08 returns.
    by = {tuple(g["students"]): g for g in key.groups}
    assert by[(99999, 1)]["plot"]["outcome"] == "leaves"
    assert by[(11111,)]["plot"]["outcome"] == "leaves"
    assert by[(262, 407, 634)]["plot"]["outcome"] == "returns"


def test_common_answers_once(key):
    d = key.to_dict()
    assert set(d["common"]) == {"problem1", "problem2", "problem4", "problem5"}
    assert all("problem1" not in g for g in d["groups"])
    # Independent: g = 4 pi^2 l / T^2 of 1(b), and (9) solved in closed form for 2.
    import math

    assert d["common"]["problem1"]["g"] == pytest.approx(4 * math.pi**2 * 1.152 / 2.1536**2, rel=1e-15)
    p = math.sqrt(9.80665 / 0.5)
    assert d["common"]["problem2"]["alpha"] == pytest.approx(2 * math.asin(2 * math.sqrt(1.5 * p / (2 * math.pi) - 1)),
                                                             rel=1e-14)


def test_parse_groups_commas_spaces_comments():
    text = "# the class\n262, 407, 634\n\n99999 1   # two students\n1,2 3\n"
    assert parse_groups(text) == [(262, 407, 634), (99999, 1), (1, 2, 3)]


@pytest.mark.parametrize("text, line", [
    ("262,407\n12a, 5\n", 2), ("1\n\n-3 4\n", 3), ("0\n", 1), ("5\n7 8\nx\n", 3), ("1.5 2\n", 1),
    ("5,,6\n", 1), ("7 8\n262 ² 634\n", 2), ("１２\n", 1),
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
        assert {"students", "length", "t_hat", "estimates"} <= set(g)
        for e in g["estimates"]:
            assert {"step", "bracket", "linear", "cubic", "cubic_error_estimate"} <= set(e)


def test_cli_csv_and_pdf(groups_file, tmp_path, capsys):
    out = tmp_path / "key.csv"
    assert main(["key", "--groups", str(groups_file), "--output", str(out)]) == 0
    text = out.read_text()
    rows = list(csv.DictReader(io.StringIO("\n".join(line for line in text.splitlines() if not line.startswith("#")))))
    assert [r["students"] for r in rows] == ["262 407 634", "99999 1"]
    assert rows[1]["plot_outcome"] == "leaves" and float(rows[1]["plot_left_at"]) == pytest.approx(4.0)
    assert float(rows[0]["t_hat"]) == pytest.approx(plain.agm7_period(2.0800838231), rel=1e-15)
    assert sum(line.startswith("# problem") for line in text.splitlines()) == 4
    pdf = tmp_path / "key.pdf"
    assert main(["key", "--groups", str(groups_file), "--output", str(pdf)]) == 0
    reader = pypdf.PdfReader(str(pdf))
    content = "\n".join(p.extract_text() for p in reader.pages)
    assert "2.0800838231" in content and "99999, 1" in content and "leaves at" in content


@pytest.mark.parametrize("content, args, words", [
    ("1,2\nabc\n", [], "line 2"),
    ("1,2\n", ["--output", "key.txt"], "--output"),
    ("1,2\n", ["--output", "/nonexistent-folder/key.csv"], "--output"),
])
def test_cli_bad_input_one_line_before_the_work(tmp_path, capsys, monkeypatch, content, args, words):
    from pendulab import key as key_module

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
