"""The coursework programs: they run without pendulab, and the engine matches them.

Bit for bit where both compute the same formula in the same order (the length rule, T^
of (8), the Taylor step (3), the sign change, the inverse cubic, the rounded normal
equations, Newton's iterates, problem 1's bounds); to a stated tolerance where the
engine sums differently (problem 5).
"""
from __future__ import annotations

import ast
import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pendulab.cli import main
from pendulab.jobs import coursework, problems
from pendulab.numerics.group import group_length
from pendulab.numerics.interpolation import inverse_cubic
from pendulab.numerics.lsq import least_squares
from pendulab.numerics.period import agm_period
from pendulab.numerics.simulation import simulate
from reference import EXAMPLE_LENGTH_TEXT, G

P = coursework.load()
EXAMPLE = [262, 407, 634]
ALPHA = 4 * math.pi / 5
#: Runs a program as ``python FILE ARGS`` would, with pendulab out of reach: the
#: program's folder first on the path, and ``import pendulab`` failing (checked).
BOOT = """
import runpy, sys
sys.modules["pendulab"] = None
try:
    import pendulab
except ImportError:
    pass
else:
    raise SystemExit("pendulab is importable")
path, *args = sys.argv[1:]
sys.path.insert(0, path.rsplit("/", 1)[0])
sys.argv = [path, *args]
runpy.run_path(path, run_name="__main__")
"""
groups = st.lists(st.integers(0, 10**7), min_size=1, max_size=4).filter(
    lambda g: str(sum(g)).strip("0") != "")


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    folder = tmp_path_factory.mktemp("programs") / "coursework"
    assert main(["programs", "--output", str(folder)]) == 0
    return folder


def run(folder, name, *args):
    # Run beside the folder: plots.py writes its figures into the working folder.
    done = subprocess.run([sys.executable, "-c", BOOT, str(folder / name), *map(str, args)],
                          capture_output=True, text=True, timeout=120, check=False, cwd=folder.parent)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_command_writes_exactly_the_programs(written):
    assert sorted(p.name for p in written.iterdir()) == sorted(coursework.PROGRAMS)
    for name in coursework.PROGRAMS:
        assert (written / name).read_text(encoding="utf-8") == coursework.source(name)


def test_programs_are_plain_short_and_commented():
    for name in coursework.PROGRAMS:
        text = coursework.source(name)
        tree = ast.parse(text)
        imported = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
        imported |= {n.module.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
        allowed = {"math", "sys", "decimal", "numpy", "scipy", "mpmath", "agm", "taylor", "length", "digits"}
        if name == "plots.py":  # the figures: matplotlib, on the problems' own data
            allowed |= {"matplotlib", "problem3", "problem4", "problem5"}
        assert imported <= allowed, (name, imported - allowed)
        assert ast.get_docstring(tree), name
        assert max(len(line) for line in text.splitlines()) <= 88, name  # no line wraps in the report


@pytest.mark.slow
@pytest.mark.parametrize("students", [EXAMPLE, [99999, 1]])
def test_each_program_runs_without_pendulab(written, students):
    for name in coursework.PROGRAMS:
        if name != "digits.py":  # the shared printing rule: it has nothing of its own to print
            assert run(written, name, *students).strip(), name
    assert {p.name for p in written.parent.glob("R?.png")} == {f"R{k}.png" for k in range(1, 6)}  # plots.py
    out = run(written, "problem3.py", *students)
    r = problems.problem3(tuple(students))
    assert f"l = {r.group.length_text} m, T^ = {r.t_hat:.15g} s" in out
    assert f"t_max = {r.plot_t_max:.6g} s" in out
    for e in r.estimates:
        assert f"{e.linear:.12g}" in out and f"{e.cubic:.12g}" in out
    if students == EXAMPLE:
        assert "T in [5, 5.2]" in out  # the h = 0.2 simulation returns to P
    else:
        assert "over the top at t = 4" in out  # l = 1: the step is too large


def test_plain_outputs_against_the_spec(written):
    # Figure 3 of the coursework, 12 significant digits.
    table = run(written, "taylor.py")
    for value in ("0.750726419819", "-0.693434871572", "0.796774928412", "-0.297068336875"):
        assert value in table
    assert f"l = {EXAMPLE_LENGTH_TEXT} m" in run(written, "length.py", *EXAMPLE)  # footnote 4
    assert "2 significant digits, g = 9.8 m/s^2" in run(written, "problem1.py")


# ----------------------------------------------------------------------------- bit for bit
finite = st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=False, min_value=-1e300, max_value=1e300)


@settings(max_examples=400, deadline=None)
@given(finite, st.integers(1, 15), st.floats(-16, 1))
def test_programs_print_the_digit_policys_forms(x, n, log_relative_error):
    """digits.py, the programs' printing, writes each form as pendulab.core.digits does
    (the report's): scientific with order-1 values plain, bounds rounded up, and only
    the digits an error allows."""
    from pendulab.core import digits

    d = P["digits.py"]
    assert d.sci(x, n) == digits.scientific(x, n)
    assert d.sci_up(x, n) == digits.bound(x, n, sci=True)
    if abs(x) < 0.9 * 10.0 ** min(n, 6):  # the plain bounds the programs print (no 1.2e2)
        assert d.up(x, n) == digits.bound(x, n)
    error = max(abs(x), 1e-300) * 10.0**log_relative_error
    assert d.right(x, error) == digits.with_error(x, error)
    assert d.sci(0.8796, 3) == "0.880" and d.sci(11.26741, 6) == "11.2674" and d.sci(2.963e-5, 3) == "2.96e-5"


@settings(max_examples=25, deadline=None)
@given(groups)
def test_length_rule_is_the_engines(students):
    g = group_length(students)
    assert P["length.py"].group_length(students) == (g.sum, [int(d) for d in g.digits], g.length_text)


@settings(max_examples=40, deadline=None)
@given(st.floats(1e-3, 1e3), st.floats(0, 3.14159))
def test_t_hat_is_the_engines(length, alpha):
    assert P["agm.py"].t_hat(length, alpha) == agm_period(length, alpha, iterations=7)


@settings(max_examples=15, deadline=None)
@given(st.floats(0.1, 10), st.floats(0.01, 3.1), st.sampled_from([1e-3, 0.01, 0.05, 0.2]))
def test_taylor_lists_are_the_engines(length, alpha, h):
    t, z1, z2 = P["taylor.py"].taylor(length, alpha, h, 300 * h)
    tr = simulate(length, alpha, h, 300 * h)
    assert tr.t.tolist() == t and tr.theta.tolist() == z1 and tr.omega.tolist() == z2
    assert P["taylor.py"].list_i(t, z1, z2)[-1] == (t[-1], z1[-1])
    assert P["taylor.py"].list_ii(t, z1, z2)[-1] == (z1[-1], z2[-1])


def test_figure3_is_the_engines():
    t, z1, z2 = P["taylor.py"].taylor(1.0, math.pi / 4, 0.1, 2.1)
    tr = simulate(1.0, math.pi / 4, 0.1, 2.1)
    assert len(t) == 22 and tr.theta.tolist() == z1 and tr.omega.tolist() == z2


@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(groups)
def test_period_from_the_simulation_is_the_engines(students):
    """3(b)-(d): the sign change, the line's zero, p(0) and its error estimate, bit for bit."""
    _check_problem3(students)


@pytest.mark.parametrize("students", [EXAMPLE, [99999, 1]])
def test_problem3_is_the_engines(students):
    _check_problem3(students)


def _check_problem3(students):
    p3 = P["problem3.py"]
    r = problems.problem3(tuple(students))
    length = float(P["length.py"].group_length(students)[2])
    exact = P["agm.py"].t_hat(length, p3.ALPHA)
    assert exact == r.t_hat
    t_max, j, over, _ = p3.plot_t_max(length, exact)
    assert t_max == r.plot_t_max
    assert r.plot_outcome == ("returns" if j is not None else "leaves" if over is not None else "none")
    for h, e in zip(p3.STEPS, r.estimates):
        row = p3.period(length, h, exact)
        assert (row["j"], row["bracket"], row["linear"], row["p0"]) == (e.j, e.bracket, e.linear, e.cubic)
        ip = e.interpolation
        assert row["e0"] == ip.error_estimate and row["dd4"] == ip.fourth_difference
        assert row["coef"][:4] == ip.coefficients.tolist()
        assert row["rounding"] == pytest.approx(ip.rounding_level, rel=1e-12)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-1, 1).filter(lambda x: abs(x) > 1e-6), min_size=5, max_size=5, unique=True),
       st.floats(0.1, 100))
def test_inverse_cubic_is_the_engines(x, t0):
    y = [t0 + 1e-3 * k for k in range(5)]
    ours = P["problem3.py"].inverse_cubic(x, y)
    ip = inverse_cubic(np.array(x[:4]), np.array(y[:4]), (x[4], y[4]))
    assert ours["p0"] == ip.value and ours["e0"] == ip.error_estimate


def test_normal_equations_are_the_engines():
    p4 = P["problem4.py"]
    t, z1, _ = P["taylor.py"].taylor(p4.L, p4.ALPHA, p4.H, math.ceil(P["agm.py"].t_hat(p4.L, p4.ALPHA)))
    a, r, diag, coef, res = p4.fit(t, z1)
    f = problems.problem4().fit
    assert diag.tolist() == pytest.approx(f.definiteness.cholesky_diagonal.tolist(), rel=1e-13)
    assert np.array_equal(a, f.normal_matrix) and np.array_equal(r, f.normal_rhs)
    assert np.array_equal(coef, f.coefficients)
    assert math.fsum(res**2) == pytest.approx(f.ssd, rel=1e-12)
    assert np.array_equal(least_squares(t, z1, decimals=6).normal_matrix, a)


def test_problem1_is_the_engines():
    p = P["problem1.py"].solve()
    r = problems.problem1()
    assert (p["g"], p["dg_dl"], p["dg_dt"], p["abs_error"], p["rel_error"], p["g_min"], p["g_max"]) == (
        r.g, r.dg_dl, r.dg_dT, r.abs_error, r.rel_error, r.g_min, r.g_max)
    assert (p["worst"], p["bound"]) == (r.worst_error, r.error_bound)
    assert (p["digits"], p["g_text"]) == (r.significant_digits, r.g_text)


def test_problem2_is_the_engines():
    p2 = P["problem2.py"]
    a, b, steps, holds = p2.interval()
    r = problems.problem2()
    assert holds and (math.degrees(a), math.degrees(b)) == pytest.approx(r.interval_deg, abs=1e-12)
    assert steps == (r.condition_values["step_a"]["step"], r.condition_values["step_b"]["step"])
    x0 = a if p2.f(a) * p2.d2f(a) > 0 else b
    assert x0 == r.x0
    xs, delta = p2.newton(x0)
    assert tuple(xs) == r.run.iterates and delta == r.run.rounding_level
    q, rho, k_max = p2.quotients(xs, delta)
    assert k_max == r.run.k_max and q == list(r.run.q) and rho == list(r.run.q_rounding)
    # Independent: (9) solved in closed form.
    p = math.sqrt(G / 0.5)
    assert xs[-1] == pytest.approx(2 * math.asin(2 * math.sqrt(1.5 * p / (2 * math.pi) - 1)), rel=1e-15)


def test_problem5_is_the_engines_to_rounding():
    """The engine integrates (1) in a scaled variable and sums in chunks: the same S_n
    to 1e-11 relative (the integrand's rounding near its singularity, times n)."""
    p5 = P["problem5.py"]
    rows = p5.table(P["agm.py"].t_hat(p5.L, p5.ALPHA))
    r = problems.problem5(substitution=False)
    assert [row[0] for row in rows] == [row.n for row in r.rows]
    for (n, period, error, rate), row in zip(rows, r.rows):
        assert period == pytest.approx(row.estimate, rel=1e-11), n
        assert error == pytest.approx(row.error, rel=1e-8), n
        assert (rate is None) == (row.rate is None)
        if rate is not None:
            assert rate == pytest.approx(row.rate, abs=1e-6)


# ----------------------------------------------------------------------------- Portuguese
def _code_only(text: str) -> str:
    """The program's AST without its strings (docstrings, printed words), and its lines
    without comments: what the Portuguese set may change."""
    import io
    import tokenize

    tree = ast.parse(text)
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            node.value = ""
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) and isinstance(
                getattr(body[0], "value", None), ast.Constant) and isinstance(body[0].value.value, str):
            body[0].value.value = ""
    tokens = [t.string for t in tokenize.generate_tokens(io.StringIO(text).readline)
              if t.type not in (tokenize.COMMENT, tokenize.STRING, tokenize.NL, tokenize.NEWLINE)]
    return ast.dump(tree) + "\n".join(tokens)


def test_portuguese_programs_differ_in_comments_docstrings_and_printed_words_only(tmp_path):
    import json
    from importlib import resources

    assert main(["programs", "--output", str(tmp_path), "--lang", "pt"]) == 0
    table = json.loads(resources.files("pendulab").joinpath("programs/pt.json").read_text(encoding="utf-8"))
    english = {line for name in coursework.PROGRAMS for line in coursework.source(name).splitlines()}
    assert set(table) <= english  # no translation of a line that is gone
    for name in coursework.PROGRAMS:
        en, pt = coursework.source(name), (tmp_path / name).read_text(encoding="utf-8")
        assert _code_only(en) == _code_only(pt), name
        assert max(len(line) for line in pt.splitlines()) <= 88, name
        # Every docstring and comment line with words in it is translated.
        for line_en, line_pt in zip(en.splitlines(), pt.splitlines()):
            if line_en in table:
                assert line_pt == table[line_en] != line_en
    assert "Problema 3(b)-(d)" in (tmp_path / "problem3.py").read_text(encoding="utf-8")


def test_every_comment_has_a_translation():
    """Each English comment or docstring line with prose is in pt.json (formulas aside)."""
    import io
    import json
    import re
    import tokenize
    from importlib import resources

    table = json.loads(resources.files("pendulab").joinpath("programs/pt.json").read_text(encoding="utf-8"))
    prose = re.compile(r"\b(the|of|and|with|from|for|is|by|to|at)\b")
    for name in coursework.PROGRAMS:
        text = coursework.source(name)
        lines = text.splitlines()
        spans = set()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Module, ast.FunctionDef)) and ast.get_docstring(node):
                spans.update(range(node.body[0].lineno - 1, node.body[0].end_lineno))
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            if tok.type == tokenize.COMMENT:
                spans.add(tok.start[0] - 1)
        for i in sorted(spans):
            if prose.search(lines[i].split("#", 1)[-1]):
                assert lines[i] in table, (name, lines[i])


def test_problem4_on_the_programs_data_is_the_engines():
    """The report hands the program's Taylor data to the engine (no compiled kernel): the
    same doubles, so the same fit; data of the wrong length is refused."""
    from pendulab.core.errors import InputError

    p4 = P["problem4.py"]
    t, z1, z2 = P["taylor.py"].taylor(p4.L, p4.ALPHA, p4.H, 4)
    given, own = problems.problem4(taylor_data=(t, z1, z2)), problems.problem4()
    assert np.array_equal(given.data.theta, own.data.theta) and np.array_equal(given.data.t, own.data.t)
    assert np.array_equal(given.fit.coefficients, own.fit.coefficients)
    assert given.exact_deviation == own.exact_deviation and given.taylor_error == own.taylor_error
    with pytest.raises(InputError, match="taylor_data"):
        problems.problem4(taylor_data=(t[:-1], z1[:-1], z2[:-1]))


def test_programs_refuse_a_folder_whose_parent_is_missing(tmp_path, capsys):
    """A mistyped path is refused in one line, and nothing is created on the way."""
    target = tmp_path / "no" / "such" / "dir"
    assert main(["programs", "--output", str(target)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "--output" in lines[0] and "inside a folder that exists" in lines[0]
    assert not (tmp_path / "no").exists()


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 9), st.integers(0, 2**32 - 1), st.floats(-12, 0))
def test_program_cholesky_is_lapacks_and_refuses_what_is_not_positive_definite(n, seed, log_shift):
    """problem4.py's Cholesky factor and solve against numpy's (LAPACK) and scipy's
    cho_solve, on random symmetric positive definite matrices down to a condition of
    about 10^12; a matrix with a non-positive eigenvalue raises."""
    import scipy.linalg

    p4 = P["problem4.py"]
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    lam = np.logspace(log_shift, 0, n)
    a = (q * lam) @ q.T
    a = 0.5 * (a + a.T)
    cond = 10.0 ** -log_shift
    low = p4.cholesky(a)
    assert np.allclose(low, np.linalg.cholesky(a), rtol=1e-14 * cond, atol=1e-15)
    assert np.array_equal(np.triu(low, 1), np.zeros((n, n)))
    r = rng.standard_normal(n)
    from pendulab.numerics.lsq import cholesky_solve

    c = cholesky_solve(a, r)
    expected = scipy.linalg.cho_solve(scipy.linalg.cho_factor(a, lower=True), r)
    assert np.allclose(c, expected, rtol=0, atol=1e-14 * cond * np.abs(expected).max())
    bad = (q * np.concatenate(([-lam[0]], lam[1:]))) @ q.T
    with pytest.raises(ValueError, match="not positive definite"):
        p4.cholesky(0.5 * (bad + bad.T))
