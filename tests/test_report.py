"""The PDF report: it builds in both languages, fits 15 pages, and says what the library computed.

Reference values: the spec (Figure 3's table, the example group's l = 2.0800838231) or
an independent computation in the test (mpmath's AGM, the closed form of problem 2,
g = 4 pi^2 l / T^2); the rest are the library's own results, which the report must print.
"""
from __future__ import annotations

import functools
import gc
import math
import re

import mpmath
import numpy as np
import pypdf
import pytest

from pendulab.cli import main
from pendulab.jobs import problems
from pendulab.report import build_report, load_catalogue
from reference import EXAMPLE_LENGTH, EXAMPLE_LENGTH_TEXT, G_TEXT, G

EXAMPLE = (262, 407, 634)
OTHER = (81234, 90876)  # sum 172110 -> digits 1,7,2,1,1
SHORT = (99999, 1)  # sum 100000 -> l = 1: the h = 0.2 simulation goes over the top


@functools.cache
def pdf_text(path) -> str:
    """The PDF's text (extracted once per file: pypdf takes seconds on the appendix's code)."""
    reader = pypdf.PdfReader(str(path))
    text = "\n".join(page.extract_text() for page in reader.pages)
    return text.replace("\u2212", "-")  # the typeset minus sign


def words(path) -> str:
    """The text with math italics as plain letters and single spaces (for phrases with math)."""
    import unicodedata

    return " ".join(unicodedata.normalize("NFKC", pdf_text(path)).split())


def pages(path) -> int:
    return len(pypdf.PdfReader(str(path)).pages)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The report for the example group in English and Portuguese, the l = 1 group, and another in Portuguese."""
    d = tmp_path_factory.mktemp("report")
    out = {}
    for key, students, lang in (("en", EXAMPLE, "en"), ("pt", EXAMPLE, "pt"), ("short", SHORT, "en"),
                                ("other", OTHER, "pt")):
        path = d / f"{key}.pdf"
        build_report(students, lang=lang, output=path)
        out[key] = path
    return out


def test_catalogues_have_the_same_entries():
    en, pt = load_catalogue("en"), load_catalogue("pt")
    assert en.keys() == pt.keys()
    assert en["p1.title"] != pt["p1.title"]


@pytest.mark.parametrize("key", ["en", "pt", "short", "other"])
def test_builds_within_15_pages_and_every_placeholder_filled(built, key):
    n = pages(built[key])
    assert 8 <= n <= 15
    text = pdf_text(built[key])
    assert "MISSING" not in text
    # Every question has its heading.
    for part in ("1(a)", "1(b)", "2(a)", "2(b)", "2(c)", "3(a)", "3(b)", "3(c)", "3(d)",
                 "4(a)", "4(b)", "4(c)", "4(d)", "5(a)", "5(b)", "5(c)", "5(d)"):
        assert part in text, part


def test_languages_differ(built):
    en, pt = pdf_text(built["en"]), pdf_text(built["pt"])
    assert "Problem 4: trigonometric least squares" in en
    assert "Problema 4: mínimos quadrados trigonométricos" in pt
    body = pt.split("Apêndice: os programas")[0]  # the appendix prints the programs' English docstrings
    assert "algarismos significativos" in body and "significant digits" not in body


def test_problem1_numbers(built):
    text = pdf_text(built["en"])
    g = 4 * math.pi**2 * 1.152 / 2.1536**2  # independent: the formula itself
    assert f"{g:.10g}" in text
    r = problems.problem1()
    assert f"{r.significant_digits} significant digits" in text
    assert r.significant_digits == 2  # error bound 0.027 <= 0.05 but > 0.005 (spec data)


def test_problem2_numbers(built):
    text = pdf_text(built["en"])
    # Independent: (9) solved in closed form, alpha = 2 asin(2 sqrt(1.5 p / (2 pi) - 1)).
    p = math.sqrt(G / 0.5)
    alpha = 2 * math.asin(2 * math.sqrt(1.5 * p / (2 * math.pi) - 1))
    assert f"{alpha:.12f}" in text
    assert f"{math.degrees(alpha):.9f}" in text
    r = problems.problem2()
    assert f"{r.run.asymptotic_constant:.10g}" in text


def test_problem3_numbers(built):
    text = pdf_text(built["en"])
    # The spec's Figure 3 table (12 significant digits).
    for value in ("0.750726419819", "-0.693434871572", "0.647933915928", "-1.33755362818",
                  "0.796774928412", "-0.297068336875"):
        assert value in text, value
    assert EXAMPLE_LENGTH_TEXT in text  # the spec's footnote 4
    # T^ of the group's pendulum, independently by mpmath's AGM.
    t_hat = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(EXAMPLE_LENGTH_TEXT) / mpmath.mpf(G_TEXT)) / mpmath.agm(
        1, mpmath.cos(2 * mpmath.pi / 5))
    assert mpmath.nstr(t_hat, 12) in text
    r = problems.problem3(EXAMPLE)
    assert f"{r.cubic.cubic:.12g}" in text  # p(0) of 3(d), 12 digits as every estimate
    for e in r.estimates:
        assert f"{e.linear:.12g}" in text


def test_problem4_numbers(built):
    text = pdf_text(built["en"])
    r = problems.problem4()
    assert r.points == 401  # t_max = ceil(T) = 4 for l = 3.5 (not the original's Y_600)
    assert "calls them" in text and "600" in text and "use the 401 points" in text  # the note on Y_600
    for row in r.fit.normal_matrix:
        for x in row:
            assert f"{x:.6f}".replace("-", "-") in text
    for c in r.fit.coefficients:
        assert f"{c:.10g}" in text
    assert "(ii) No." in text  # max deviation ~2e-3, above 1e-5


def test_problem5_numbers(built):
    text = pdf_text(built["en"])
    from pendulab.jobs.coursework import load

    p5 = load()["problem5.py"]
    table = p5.table(load()["agm.py"].t_hat(3.5, 4 * math.pi / 5))
    r = problems.problem5()
    right = load()["digits.py"].right
    assert right(table[0][1], p5.rounding_error(1)) in text and table[0][1] == pytest.approx(r.single, rel=1e-12)
    assert right(table[1][1], p5.rounding_error(10)) in text
    assert table[1][1] == pytest.approx(r.composite10, rel=1e-12)
    for (n, period, _, _), row in zip(table[1:], r.rows[1:]):
        # Table 10: the program's S_n with the digits its rounding error leaves right, as
        # the program prints it; the engine's agrees to rounding.
        assert right(period, p5.rounding_error(n)) in text and period == pytest.approx(row.estimate, rel=1e-11), n
        assert f"{row.substitution_estimate:.15g}" in text


def test_agm_section(built):
    from decimal import ROUND_FLOOR, Decimal

    from pendulab.numerics.period import fixed_iterations_limit

    # The limit to 15 digits, rounded down: every amplitude the text allows is within it.
    shown = Decimal(fixed_iterations_limit()).quantize(Decimal("1e-14"), rounding=ROUND_FLOOR)
    assert str(shown) in pdf_text(built["en"]) and float(shown) <= fixed_iterations_limit()


@pytest.mark.parametrize("key", ["en", "pt", "short", "other"])
def test_appendix_prints_every_program_whole_unwrapped(built, key):
    """Every line of every program, each on one line of the PDF, in the report's language,
    after its header (the file and how to run it); the code at 8 pt."""
    from pendulab.jobs import coursework

    lang = "pt" if key in ("pt", "other") else "en"
    text = pdf_text(built[key])
    lines = {" ".join(line.split()) for line in text.splitlines()}
    for name in coursework.PROGRAMS:
        assert f"{name} {coursework.usage(name, lang)}" in lines, name
        for line in coursework.source(name, lang).splitlines():
            if line.strip():
                assert " ".join(line.split()) in lines, (name, line)
    sizes = set()

    def visit(text, cm, tm, font, size):
        if text.strip() and font and "Mono" in font.get("/BaseFont", "") and size:
            sizes.add(round(size * tm[0] * cm[0], 2))

    reader = pypdf.PdfReader(str(built[key]))
    reader.pages[-1].extract_text(visitor_text=visit)
    assert sizes and min(sizes) >= 8


def test_report_numbers_come_from_the_programs(tmp_path):
    """The sections call the coursework programs, and print what they return: a program
    made to answer differently changes the report."""
    from pendulab.jobs.coursework import load
    from pendulab.report.markup import err, num, sci

    p = load()
    calls = []

    def spy(module, name):
        real = getattr(p[module], name)

        def wrapper(*args, **kwargs):
            calls.append(f"{module}:{name}")
            return real(*args, **kwargs)

        return (p[module], name, wrapper)

    spies = [spy("length.py", "group_length"), spy("agm.py", "t_hat"), spy("taylor.py", "taylor"),
             spy("problem1.py", "solve"), spy("problem2.py", "newton"), spy("problem2.py", "interval"),
             spy("problem3.py", "period"), spy("problem3.py", "plot_t_max"), spy("problem4.py", "fit"),
             spy("problem5.py", "table")]
    doc = _forced(tmp_path, EXAMPLE, None, spies, "en")
    assert {s[0].__name__ + ".py:" + s[1] for s in spies} == set(calls)
    # The printed numbers are the programs' own.
    r3 = p["problem3.py"].period(EXAMPLE_LENGTH, 1e-2, p["agm.py"].t_hat(EXAMPLE_LENGTH, 4 * math.pi / 5))
    assert doc.tables["p3c"][0][1] == str(r3["j"]) and doc.tables["p3c"][0][3] == num(r3["linear"], 12)
    t5 = p["problem5.py"].table(p["agm.py"].t_hat(3.5, 4 * math.pi / 5))
    assert [row[1] for row in doc.tables["p5d"]] == [err(period, p["problem5.py"].rounding_error(n))
                                                     for n, period, _, _ in t5[1:]]
    assert doc.values["p1.g"] == num(p["problem1.py"].solve()["g"], 10)
    # A program that answers differently: the report follows it.
    changed = _forced(tmp_path, EXAMPLE, ["problem 5"],
                      [(p["problem5.py"], "table", lambda exact: [(n, 1.25, 0.5, 0.25) for n in (1, 10, 100)])], "en")
    shown = [err(1.25, p["problem5.py"].rounding_error(n)) for n in (1, 10, 100)]
    assert changed.values["p5.q1"] == shown[0] and changed.values["p5.e10"] == sci(0.5, 3)
    assert [row[1] for row in changed.tables["p5d"]] == shown[1:] and shown[0].startswith("1.2500")


def _plotted(ax) -> list:
    """Every array an axes shows: its lines' points, its collections' offsets and a
    quiver's arrows, in drawing order."""
    out = [line.get_xydata() for line in ax.lines]
    for c in ax.collections:
        out.append(c.get_offsets())
        if hasattr(c, "U"):
            out += [c.U, c.V]
    return [a for a in map(np.asarray, out) if a.size]


@pytest.mark.parametrize("students", [EXAMPLE, SHORT])
def test_report_figures_are_the_programs_figures(students, tmp_path, monkeypatch):
    """Figures R1-R5 of the report are the ones ``plots.py`` draws when run for the group:
    the same functions of the program, on the same data arrays, bit for bit; a program
    made to draw otherwise changes the report's figure."""
    from matplotlib.figure import Figure

    from pendulab.jobs.coursework import load
    from pendulab.report import figures
    from pendulab.report.builder import section_data

    drawn = {}
    real = figures.draw

    def draw(paint, path, **size):
        def keep(ax):
            paint(ax)
            drawn[path.stem] = ax

        return real(keep, path, **size)

    monkeypatch.setattr(figures, "draw", draw)
    plots = load()["plots.py"]
    called = []
    for name in ("figure1", "figure2", "figure3", "figure4", "figure5"):
        function = getattr(plots, name)
        monkeypatch.setattr(plots, name, lambda *a, _f=function, _n=name, **k: (called.append(_n), _f(*a, **k)))
    section_data(students, "en", tmp_path)
    assert sorted(called) == ["figure1", "figure2", "figure3", "figure4", "figure5"]
    report = {"R1": "p3b_time", "R2": "p3b_phase", "R3": "p4d_fit", "R4": "p4d_residual", "R5": "p5d_conv"}
    programs = plots.figures(list(students))
    assert set(programs) == set(report)
    for name, (function, data) in programs.items():
        ax = Figure().add_subplot()
        function(ax, *data)
        theirs, ours = _plotted(ax), _plotted(drawn[report[name]])
        assert len(theirs) == len(ours) >= 1, name
        assert all(np.array_equal(a, b) for a, b in zip(theirs, ours)), name
        assert ax.get_xscale() == drawn[report[name]].get_xscale(), name
        assert ax.get_yscale() == drawn[report[name]].get_yscale(), name
    # A program that draws other data: the report's figure follows it.
    monkeypatch.setattr(plots, "figure1", lambda ax, t, z1, words=None: ax.plot(t, [0.5] * len(t)))
    section_data(students, "en", tmp_path, only=["problem 3"])
    assert np.all(_plotted(drawn["p3b_time"])[0][:, 1] == 0.5)


def test_short_pendulum_says_the_simulation_leaves_the_oscillation(built):
    text = words(built["short"]).split("Appendix: the programs")[0]  # the programs cite the example group
    assert "1.0000000000" in text and EXAMPLE_LENGTH_TEXT not in text
    assert "The step is too large for this pendulum" in text
    assert "it leaves the oscillation at t = 4 s" in text
    assert "then in view" not in text and "does not return to P within" not in text


def test_same_inputs_same_bytes(built, tmp_path):
    again = tmp_path / "again.pdf"
    build_report(EXAMPLE, lang="en", output=again)
    assert again.read_bytes() == built["en"].read_bytes()


def test_cli_writes_the_report(tmp_path, capsys):
    out = tmp_path / "r.pdf"
    assert main(["report", "--students", "99999,1", "--lang", "pt", "--output", str(out)]) == 0
    assert pages(out) <= 15
    text = words(out)
    assert "O passo é demasiado grande para este pêndulo" in text and "sai da oscilação em t = 4 s" in text
    err = capsys.readouterr().err
    assert "\x1b[" not in err  # no progress display when stderr is not a terminal
    assert gc.isenabled()  # the cycle collector, paused for the report, is back
    assert gc.get_freeze_count() == 0  # and the report's objects are its to free, none kept frozen


def test_cli_pauses_the_cycle_collector_only_while_building(monkeypatch, tmp_path):
    import pendulab.report

    seen = []

    def fake(*args, **kwargs):
        seen.append(gc.isenabled())
        raise RuntimeError("stop")

    monkeypatch.setattr(pendulab.report, "build_report", fake)
    with pytest.raises(RuntimeError):
        main(["report", "--output", str(tmp_path / "r.pdf")])
    assert seen == [False] and gc.isenabled()


@pytest.mark.parametrize(
    "args, words",
    [
        (["--students", "262,abc"], "--students"),
        (["--students", "0,5"], "--students"),
        (["--students", "-3"], "--students"),
        (["--students", "1,,2"], "--students"),
        (["--lang", "fr"], "--lang"),
        (["--output", "/nonexistent-folder/r.pdf"], "--output"),
    ],
)
def test_bad_input_one_line_exit_2(args, words, capsys, tmp_path):
    if args[0] != "--output":
        args = args + ["--output", str(tmp_path / "r.pdf")]
    assert main(["report", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err
    assert not (tmp_path / "r.pdf").exists()


def test_output_that_is_a_folder_fails_before_the_work(tmp_path, capsys):
    assert main(["report", "--output", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--output" in err and "folder" in err


def test_failed_run_keeps_the_older_file(tmp_path, monkeypatch):
    from pendulab.report import builder

    out = tmp_path / "report.pdf"
    out.write_bytes(b"older report")

    def broken(*args, **kwargs):
        raise RuntimeError("typesetting failed")

    monkeypatch.setattr(builder, "compile_pdf", broken)
    with pytest.raises(RuntimeError):
        build_report(EXAMPLE, output=out)
    assert out.read_bytes() == b"older report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.pdf"]  # no temporary left


# ----------------------------------------------------------------------------- Section 0
def _nome_error(alpha, n=7):
    """v_n/M - 1 = theta_3(q^(2^(n+1)))^2 - 1 (a_n = M theta_3(q^(2^n))^2): the truncation
    error of n iterations of (7), by the theta series, not by the AGM."""
    with mpmath.workdps(60):
        q = mpmath.qfrom(m=mpmath.sin(alpha / 2) ** 2)
        big_q = q ** (2 ** (n + 1))
        # theta_3(Q)^2 - 1 = 4Q + 4Q^2 + ... (series kept to where it matters)
        series = 2 * sum(big_q ** (k * k) for k in range(1, 4))
        return 2 * series + series**2


def test_section0_takes_the_inputs_exactly(tmp_path):
    from pendulab.report.builder import section_data

    doc = section_data(EXAMPLE, "en", tmp_path, only=["AGM period"])
    # `pendulab period -l 2.0800838231 -a 4pi/5 --digits 20`, and mpmath here from the exact inputs.
    with mpmath.workdps(60):
        t = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(EXAMPLE_LENGTH_TEXT) / mpmath.mpf(G_TEXT)) / mpmath.agm(
            1, mpmath.cos(2 * mpmath.pi / 5))
    assert mpmath.nstr(t, 20) == "4.7894242309743877759"
    assert "$T = 4.7894242309743877759$ s" in doc.entry("agm.text")


# ----------------------------------------------------------------------------- every group
def _choice_parents() -> set[str]:
    """The keys the template shows that the catalogue only has as alternatives ``key.option``."""
    from importlib import resources

    template = resources.files("pendulab.report").joinpath("report.typ").read_text()
    catalogue = load_catalogue("en")
    return {k for k in re.findall(r'T\("([^"]+)"\)', template) if k not in catalogue}


def _alternatives(parents) -> set[str]:
    catalogue = load_catalogue("en")
    return {k for k in catalogue if k.rsplit(".", 1)[0] in parents}


def _random_groups(n=32, seed=11):
    import random

    rng = random.Random(seed)
    return [tuple(rng.randint(1, 99999) for _ in range(rng.randint(1, 4))) for _ in range(n)]


#: Groups whose length is 1 m: every digit of the sum is 1 (or 0).
SHORT_GROUPS = [(99999, 1), (1,), (100, 11), (55555, 55556)]


@pytest.fixture(scope="module")
def group_docs(tmp_path_factory):
    """Sections 0 and 3 for 32 random groups and the l = 1 groups, en and pt alternately (no PDF)."""
    from pendulab.report import document
    from pendulab.report.builder import section_data

    d = tmp_path_factory.mktemp("groups")
    out = []
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(document.Doc, "figure", lambda self, name, paint, **size: self.figures.update({name: name}))
        for i, students in enumerate(_random_groups() + SHORT_GROUPS):
            lang = ("en", "pt")[i % 2]
            out.append((students, lang, section_data(students, lang, d, only=["problem 3"])))
    return out


def test_every_group_problem3_matches_plain_python(group_docs):
    import plain_pendulum as plain
    from pendulab.report.markup import num

    assert len(group_docs) >= 36
    outcomes = set()
    for students, _lang, doc in group_docs:
        text = plain.length_text(students)
        assert doc.values["p3b.l"] == text
        digits = str(sum(students)).replace("0", "")
        assert doc.choices["p3b.len"] == ("p3b.len.one" if len(digits) == 1 else "p3b.len.many")
        length = float(text)
        t_hat = plain.t_hat(length)
        event = plain.first_event(length, 0.2, 4 * t_hat)
        outcomes.add(event[0])
        assert doc.choices["p3b.tmax"] == f"p3b.tmax.{event[0]}"
        sentence = doc.entry("p3b.bracket")
        if event[0] == "returns":
            j = event[1]
            # Where T^ lies against [t_j, t_(j+1)], by the plain program's own numbers.
            side = "below" if t_hat < j * 0.2 else "above" if t_hat > (j + 1) * 0.2 else "inside"
            assert doc.choices["p3b.bracket"] == f"p3b.bracket.{side}"
            assert f"t_{j} = {num(j * 0.2, 6)}" in sentence and f"t_{j + 1} = {num((j + 1) * 0.2, 6)}" in sentence
            seen = (j + 1) * 0.2
        else:
            assert doc.choices["p3b.bracket"] == f"p3b.bracket.{event[0]}"
            assert f"t = {num(event[1], 6)}" in sentence
            seen = event[1]
        # t_max from (8) alone: the least multiple of h = 0.2 at or beyond 2 T^; the text
        # says whether the event is in view on [0, t_max].
        t_max = float(doc.values["p3b.tmax"])
        assert t_max >= 2 * t_hat - 1e-9 and t_max - 0.2 < 2 * t_hat
        assert doc.values["p3b.tmax"] in doc.entry("p3b.tmax")
        view = "in" if seen <= t_max + 1e-9 else "out"
        assert doc.choices["p3b.view"] == f"p3b.view.{event[0]}_{view}"
        assert doc.entry("p3b.view") in doc.entry("p3b.tmax")
        ref = plain.estimate(length, 1e-3)
        assert f"j = {ref['j']}" in doc.entry("p3d")
        resolved = abs(ref["error_estimate"]) > ref["rounding_level"]
        assert doc.choices["p3d.est"] == ("p3d.est.resolved" if resolved else "p3d.est.rounding")
        bound = max(abs(ref["error_estimate"]), ref["rounding_level"])
        assert float(doc.values["p3d.bound"].replace(" × 10#super[−", "e-").rstrip("]")) == pytest.approx(bound, rel=0.01)
        ratio = bound / abs(ref["cubic"] - t_hat)
        assert doc.choices["p3d.verdict"] == ("p3d.verdict.negligible" if ratio < 1e-3 else "p3d.verdict.not_negligible")
    assert outcomes == {"returns", "leaves"}


def _forced(tmp_path, students, only, patches, lang):
    from pendulab.report import document
    from pendulab.report.builder import section_data

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(document.Doc, "figure", lambda self, name, paint, **size: self.figures.update({name: name}))
        for target, name, value in patches:
            mp.setattr(target, name, value)
        return section_data(students, lang, tmp_path, only=only)


def _with_t_hat(t_hat):
    """``agm.t_hat`` answering ``t_hat`` whatever the pendulum: T^ moved, the simulation kept."""
    return lambda *args, **kwargs: t_hat


def _forced_docs(tmp_path, lang):
    """The branches no real group reaches, each forced by changing the program's threshold behind it."""
    from pendulab.jobs.coursework import load

    p = load()
    docs = {
        "every q_k": _forced(tmp_path, EXAMPLE, ["problem 2"], [(p["problem2.py"], "Q_TOL", 1e9)], lang),
        "no return": _forced(tmp_path, EXAMPLE, ["problem 3"], [(p["problem3.py"], "SEARCH", 1.0)], lang),
        # The example's h = 0.2 bracket is [5, 5.2]: T^ moved inside it and beyond it.
        "inside": _forced(tmp_path, EXAMPLE, ["problem 3"], [(p["agm.py"], "t_hat", _with_t_hat(5.13))], lang),
        "above": _forced(tmp_path, EXAMPLE, ["problem 3"], [(p["agm.py"], "t_hat", _with_t_hat(5.47))], lang),
        "not negligible": _forced(tmp_path, EXAMPLE, ["problem 3"], [(p["problem3.py"], "NEGLIGIBLE", 1e-20)], lang),
        # t_max of half a period: the event comes after it.
        "late return": _forced(tmp_path, EXAMPLE, ["problem 3"], [(p["problem3.py"], "PLOT", 0.5)], lang),
        "late leave": _forced(tmp_path, SHORT, ["problem 3"], [(p["problem3.py"], "PLOT", 0.5)], lang),
        "within tolerance": _forced(tmp_path, EXAMPLE, ["problem 4"], [(p["problem4.py"], "TOL", 10.0)], lang),
        "not converged": _forced(tmp_path, EXAMPLE, ["problem 5"], [(p["problem5.py"], "FLOOR", -1.0)], lang),
        "real": _forced(tmp_path, EXAMPLE, None, [], lang),
    }
    return docs


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_every_catalogue_branch_is_taken_and_true(group_docs, tmp_path, lang):
    forced = _forced_docs(tmp_path, lang)
    # Each forced branch says what its data say.
    doc = forced["every q_k"]
    assert doc.choices["p2c.shown"] == "p2c.shown.all" and len(doc.tables["p2c"]) == int(doc.values["p2.qlast"]) + 1
    doc = forced["no return"]
    assert doc.choices["p3b.bracket"] == "p3b.bracket.none"
    assert doc.values["p3b.search"] in doc.entry("p3b.bracket")
    for name, side, dist in (("inside", "inside", "0.13"), ("above", "above", "0.27")):
        doc = forced[name]
        assert doc.choices["p3b.bracket"] == f"p3b.bracket.{side}" and doc.values["p3b.dist"] == dist
        assert "$t_25 = 5$" in doc.entry("p3b.bracket") and dist in doc.entry("p3b.bracket")
    for name, view in (("late return", "returns_out"), ("late leave", "leaves_out")):
        doc = forced[name]
        assert doc.choices["p3b.view"] == f"p3b.view.{view}" and float(doc.values["p3b.tmax"]) < 3
    doc = forced["not negligible"]
    assert doc.choices["p3d.verdict"] == "p3d.verdict.not_negligible" and "10#super[−20]" in doc.entry("p3d.verdict")
    doc = forced["within tolerance"]
    assert doc.choices["p4d.ii"] == "p4d.ii.yes" and doc.choices["p4.alt"] == "p4.alt.yes"
    assert "< 1 × 10#super[1]$" in doc.entry("p4d.ii")  # the threshold the data were compared with
    doc = forced["not converged"]
    assert doc.choices["p5.sub"] == "p5.sub.not_converged" and doc.values["p5.subn"] == "—"
    # The real data's branches, with the numbers they claim.
    real = forced["real"]
    r2 = problems.problem2()
    assert real.choices["p2.start"] == "p2.start.fourier" and real.choices["p2c.shown"] == "p2c.shown.cut"
    assert len(real.tables["p2c"]) == len(r2.run.q)  # every q_k, with its rounding error beside
    assert real.choices["p4d.ii"] == "p4d.ii.no" and real.choices["p4.alt"] == "p4.alt.no"
    assert real.choices["p5.sub"] == "p5.sub.converged"
    # Every alternative of every choice the template makes was taken by some document.
    taken = {c for docs in (forced.values(), [d for _, lg, d in group_docs]) for d in docs for c in d.choices.values()}
    parents = _choice_parents()
    assert parents >= {"p3b.len", "p3b.tmax", "p3b.bracket", "p3d.verdict", "p2.start", "p4d.ii", "p4.alt", "p5.sub"}
    assert _alternatives(parents | {"p3b.view"}) <= taken
    # And every entry of this language fills (no placeholder left without a value).
    real.text()


def test_problem4_601_points_beside(built):
    text = " ".join(pdf_text(built["en"]).split())
    alt = problems.problem4(t_max=6.0)
    assert alt.points == 601
    assert "601 points" in text
    for c in alt.fit.coefficients:
        assert f"{c:.10g}".replace("-", "-") in text


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_section0_sentences_are_true(tmp_path, lang):
    """Each claim of the note on (8) against the data it names, computed here independently."""

    from flint import arb, ctx

    import plain_pendulum as plain
    from pendulab.numerics.period import period_ball
    from pendulab.report.builder import section_data

    doc = section_data(EXAMPLE, lang, tmp_path, only=["AGM period"])
    text = doc.entry("agm.text")
    length, alpha = EXAMPLE_LENGTH, 4 * math.pi / 5

    def nearest(l_, a):  # the true period of the doubles (elliptic K, not the AGM), rounded once
        with mpmath.workdps(60):
            t = 4 * mpmath.sqrt(mpmath.mpf(l_) / mpmath.mpf(G)) * mpmath.ellipk(mpmath.sin(mpmath.mpf(a) / 2) ** 2)
            return mpmath.libmp.to_float(t._mpf_, rnd="n")

    # "T^ of agm.py is n ulp from the correctly rounded period of the same doubles"
    t_hat, tc = plain.t_hat(length), nearest(length, alpha)
    ulps = round(abs(t_hat - tc) / math.ulp(tc))
    assert ulps >= 1
    said = f"is {ulps} ulp from the correctly rounded period" if lang == "en" else f"é a {ulps} ulp do período corretamente arredondado"
    assert said in text
    # "the interval's two ends round to the same 20 digits": the ball contains mpmath's period
    # and is narrower than the rounding interval's half-width around the printed digits.
    digits = re.search(r"\$T = ([0-9.]+)\$ s", text).group(1)
    ball = period_ball(EXAMPLE_LENGTH_TEXT, "4pi/5", prec=int(20 * 3.33) + 64)
    old = ctx.prec
    ctx.prec = 256
    try:
        half = arb(10) ** (math.floor(math.log10(float(digits))) - 19) / 2
        assert (ball - arb(digits)).abs_upper() < half  # both ends round to the printed digits
    finally:
        ctx.prec = old
    # "7 iterations leave a truncation error below half an ulp for every alpha <= limit":
    # by the theta series, at the limit and (just) beyond it.
    limit = mpmath.mpf(re.search(r"alpha <= ([0-9.]+)\$", text).group(1))
    gap = re.search(r"pi - alpha = ([0-9.]+) × 10#super\[−(\d+)\]", text)
    with mpmath.workdps(60):
        half_ulp = mpmath.mpf(2) ** -53
        assert _nome_error(limit) <= half_ulp < _nome_error(limit + (mpmath.pi - limit) / 2)
        assert _nome_error(mpmath.pi - mpmath.mpf(f"{gap[1]}e-{gap[2]}")) <= half_ulp


@pytest.mark.parametrize("scale", ["log", "symlog"])
def test_plain_tick_labels_say_what_matplotlibs_say(scale):
    """The report's plain-text log and symlog tick labels (no mathtext to lay out) name
    the same numbers as matplotlib's own formatter, tick by tick."""
    from matplotlib.figure import Figure

    from pendulab.report.figures import power_of_ten

    ax = Figure().add_subplot()
    ax.plot([0, 1], [1e-7, 1e3] if scale == "log" else [-1e-3, 1e-3])
    ax.set_yscale(scale, **({"linthresh": 1e-5} if scale == "symlog" else {}))
    ticks = ax.yaxis.get_major_locator()()
    theirs = ax.yaxis.get_major_formatter()
    theirs.set_locs(ticks)
    superscript = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
    shown = 0
    for x in ticks:
        m = re.fullmatch(r"\$\\mathdefault\{(-?)(?:10\^\{(-?\d+)\}|(0))\}\$", theirs(x))
        expected = "" if m is None else m[3] or ("−" if m[1] else "") + "10" + m[2].translate(superscript)
        assert power_of_ten(x) == expected, x
        shown += expected != ""
    assert shown >= 5


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_report_figures_are_plain_text(lang, tmp_path, monkeypatch):
    """Every text of the report's figures is plain: one ``$...$`` label would build matplotlib's
    mathtext parser (pyparsing), a fifth of the figures' time, and lay the label out with it."""
    from matplotlib.text import Text

    from pendulab.report import figures
    from pendulab.report.builder import section_data

    drawn = []
    real = figures.draw

    def draw(paint, path, **size):
        def keep(ax):
            paint(ax)
            drawn.append(ax)

        return real(keep, path, **size)

    monkeypatch.setattr(figures, "draw", draw)
    section_data(EXAMPLE, lang, tmp_path)
    shown = [t.get_text() for ax in drawn for t in ax.figure.findobj(Text) if t.get_visible() and t.get_text()]
    assert len(drawn) == 5 and any("θ" in s for s in shown) and any("10⁻" in s for s in shown)
    assert [s for s in shown if s.count("$") >= 2] == []
