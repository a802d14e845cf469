"""The PDF report: it builds in both languages, fits 15 pages, and says what the library computed.

Reference values: the spec (Figure 3's table, the example group's l = 2.0800838231) or
an independent computation in the test (mpmath's AGM, the closed form of problem 2,
g = 4 pi^2 l / T^2); the rest are the library's own results, which the report must print.
"""
from __future__ import annotations

import math

import mpmath
import pypdf
import pytest

from pendulab import problems
from pendulab.cli import main
from pendulab.report import build_report, load_catalogue

EXAMPLE = (262, 407, 634)
OTHER = (81234, 90876)  # sum 172110 -> digits 1,7,2,1,1


def pdf_text(path) -> str:
    reader = pypdf.PdfReader(str(path))
    text = "\n".join(page.extract_text() for page in reader.pages)
    return text.replace("\u2212", "-")  # the typeset minus sign


def pages(path) -> int:
    return len(pypdf.PdfReader(str(path)).pages)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The report for the example group in English and Portuguese, and for another group."""
    d = tmp_path_factory.mktemp("report")
    out = {}
    for key, students, lang in (("en", EXAMPLE, "en"), ("pt", EXAMPLE, "pt"), ("other", OTHER, "en")):
        path = d / f"{key}.pdf"
        build_report(students, lang=lang, output=path)
        out[key] = path
    return out


def test_catalogues_have_the_same_entries():
    en, pt = load_catalogue("en"), load_catalogue("pt")
    assert en.keys() == pt.keys()
    assert en["p1.title"] != pt["p1.title"]


@pytest.mark.parametrize("key", ["en", "pt", "other"])
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
    assert "algarismos significativos" in pt and "significant digits" not in pt


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
    p = math.sqrt(9.80665 / 0.5)
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
    assert "2.0800838231" in text  # the spec's footnote 4
    # T^ of the group's pendulum, independently by mpmath's AGM.
    t_hat = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf("2.0800838231") / mpmath.mpf("9.80665")) / mpmath.agm(
        1, mpmath.cos(2 * mpmath.pi / 5))
    assert mpmath.nstr(t_hat, 12) in text
    r = problems.problem3(EXAMPLE)
    assert f"{r.cubic.cubic:.15g}" in text  # p(0) of 3(d)
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
    r = problems.problem5()
    assert f"{r.single:.12g}" in text
    assert f"{r.composite10:.12g}" in text
    for row in r.rows[1:]:
        assert f"{row.period:.12g}" in text


def test_agm_section(built):
    from pendulab.period import fixed_iterations_limit

    assert f"{fixed_iterations_limit():.16g}" in pdf_text(built["en"])


def test_appendix_lists_the_code_that_ran(built):
    text = pdf_text(built["en"])
    assert "_kernels.taylor2_step" in text
    # A line of the kernel's body, as in the source file.
    assert "z1_next = z1 + h * z2 + 0.5 * h * h * c * s" in text


def test_other_group_changes_length_and_numbers(built):
    other, en = pdf_text(built["other"]), pdf_text(built["en"])
    # 81234 + 90876 = 172110 -> digits 1, 7, 2, 1, 1: l = (14)^(1/5), independently by mpmath.
    l_other = mpmath.nstr(mpmath.root(14, 5), 11)  # 1.69521820307... to 10 decimals
    assert l_other in other and l_other not in en
    assert "2.0800838231" not in other
    r = problems.problem3(OTHER)
    assert f"{r.cubic.cubic:.15g}" in other and f"{r.cubic.cubic:.15g}" not in en


def test_same_inputs_same_bytes(built, tmp_path):
    again = tmp_path / "again.pdf"
    build_report(EXAMPLE, lang="en", output=again)
    assert again.read_bytes() == built["en"].read_bytes()


def test_cli_writes_the_report(tmp_path, capsys):
    out = tmp_path / "r.pdf"
    assert main(["report", "--students", "262,407,634", "--lang", "pt", "--output", str(out)]) == 0
    assert pages(out) <= 15
    err = capsys.readouterr().err
    assert "\x1b[" not in err  # no progress display when stderr is not a terminal


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
