"""CLI: gravity, newton, fit, quadrature; every bad input gets one line and exit 2."""
import math
import re
import subprocess
import sys

import mpmath
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import assert_one_line_error
from pendulab.jobs.problems import problem1, problem2
from pendulab.numerics.period import FIXED_ITERATIONS_ULPS, agm_period
from reference import G_TEXT, G, reference_period, reference_period_kp


def test_gravity_json_and_units(cli):
    data = cli("gravity", "--json").json
    for key in ("g", "abs_error", "rel_error", "significant_digits", "rule"):
        assert key in data
    # The CLI prints the library's result, digit for digit (tests/test_uncertainty.py checks
    # that against the uncertainties package's derivatives).
    lib = problem1()
    assert (data["g"], data["abs_error"], data["rel_error"]) == (lib.g, lib.abs_error, lib.rel_error)
    assert data["significant_digits"] == lib.significant_digits == 2
    same = [cli("gravity", "--length", s, "--length-error", e, "--json").json
            for s, e in (("1.152m", "0.003m"), ("1.152", "0.003"), ("1152mm", "3mm"))]
    assert all(d["g"] == data["g"] and d["abs_error"] == data["abs_error"] for d in same)
    out = cli("gravity").out
    assert "significant digits guaranteed: 2" in out and "rule: x~ has n significant digits when" in out
    # the report's form of the bound: 4 digits rounded up (test_gravity_prints_only_right_digits)
    assert "|e_g| <= (4 pi^2 / T^2) dl + (8 pi^2 l / T^3) dT  = 0.02736 m/s^2" in out


def test_newton_json(cli):
    data = cli("newton", "--json").json
    for key in ("alpha", "alpha_deg", "iterates", "q", "k_max", "asymptotic_constant", "interval", "error_estimate"):
        assert key in data
    # The library's root (tests/test_newton.py checks it against brentq and mpmath).
    z = problem2().alpha
    assert data["alpha"] == z
    assert data["alpha_deg"] == math.degrees(z)
    assert data["interval"][0] < z < data["interval"][1]
    assert all(c["holds"] for c in data["interval_conditions"])
    start = cli("newton", "--x0", "50deg", "--json").json
    assert start["x0"] == pytest.approx(math.radians(50)) and start["alpha"] == pytest.approx(z, abs=4e-15)
    text = cli("newton").out
    assert "k_max = 1" in text and "deg" in text
    # The result carries codes and numbers; the CLI writes the words, with the numbers.
    lib = problem2()
    assert data["criterion"] == "rounding_level" and data["stop_reason"] == "small_correction"
    assert "; stop when |x_(k+1) - x_k| <= 4 u (|x| + S/|f'(x)|): the correction is at the rounding level" in text
    sign, *_, from_b = lib.interval.conditions
    assert f"  [ok] sign change: f(a) = {sign.values['f_a']:.6e}, f(b) = {sign.values['f_b']:.6e}: f(a) f(b) < 0" in text
    assert (f"  [ok] Newton step from b stays in [a, b]: |f(b)/f'(b)| = {from_b.values['step']:.6e} <= "
            f"b - a = {from_b.values['width']:.6e}") in text
    assert [c["name"] for c in data["interval_conditions"]] == [c.name for c in lib.interval.conditions]


def _newton_mp(length, target, x0, steps):
    """Newton's iterates of (9) in exact arithmetic (50 digits) from the double ``x0``, the
    equation from the inputs as written (``l``, the target, ``g = 9.80665`` decimals)."""
    import mpmath

    with mpmath.workdps(50):
        t0 = 2 * mpmath.pi / mpmath.sqrt(mpmath.mpf(G_TEXT) / mpmath.mpf(length))
        f = lambda a: t0 * (1 + mpmath.sin(a / 2) ** 2 / 4) - mpmath.mpf(target)  # noqa: E731
        df = lambda a: t0 * mpmath.sin(a) / 8  # noqa: E731
        xs = [mpmath.mpf(x0)]
        for _ in range(steps):
            xs.append(xs[-1] - f(xs[-1]) / df(xs[-1]))
        return xs, f


def _right(text, true):
    """Within one unit of the last printed digit of ``true``; ``<= b`` (a value its rounding
    swamps, one significant digit): a true bound of its size, ``|true| <= b``."""
    from decimal import Decimal

    import mpmath

    with mpmath.workdps(50):
        if text.startswith("<= "):
            b = Decimal(text[3:])
            assert len(b.normalize().as_tuple().digits) == 1, text
            assert abs(true) <= mpmath.mpf(text[3:]), (text, mpmath.nstr(true, 20))
            return
        unit = mpmath.mpf(10) ** Decimal(text).as_tuple().exponent
        assert abs(mpmath.mpf(text) - true) <= unit, (text, mpmath.nstr(true, 20))


@pytest.mark.parametrize("args", [(), ("-l", "2", "--target", "3", "--x0", "80deg"), ("-l", "1", "--target", "2.1")])
def test_newton_prints_only_right_digits(cli, args):
    """Issue 32: every number of ``pendulab newton``'s table and result lines within one unit of
    its last printed digit of mpmath's (exact Newton from the same x_0, f at the printed
    iterate's double, q_k of the exact iterates, the constant at the exact root), or, where
    rounding swamps it (f(x_k) near the root, q_k after k_max), a true bound ``<= b``;
    ``--json`` keeps every double."""
    import mpmath

    data = cli("newton", *args, "--json").json
    res = cli("newton", *args)
    assert res.code == 0, res.err
    lines = res.out.splitlines()
    head = next(i for i, line in enumerate(lines) if line.split()[:2] == ["k", "x_k"])
    n = len(data["iterates"])
    rows = [re.findall(r"<= \S+|\S+", line.split("<-")[0]) for line in lines[head + 1:head + 1 + n]]
    xs, f = _newton_mp(data["length"], data["target"], data["x0"], n - 1)
    with mpmath.workdps(50):
        d = [abs(b - a) for a, b in zip(xs, xs[1:])]
        q = [d[k + 1] / d[k] ** 2 for k in range(n - 2)]
        for k, row in enumerate(rows):
            assert row[0] == str(k)
            _right(row[1], xs[k])
            _right(row[2], f(mpmath.mpf(data["iterates"][k])))  # f at the double the run holds
            if k < n - 2:
                _right(row[3], q[k])
                assert mpmath.mpf(row[4]) >= data["q_rounding"][k]  # a bound, rounded up
        root = mpmath.findroot(f, xs[-1])
        text = "\n".join(lines[head + 1 + n:])
        constant = re.search(r"\| = ([0-9.e-]+); q_kmax = ([0-9.e-]+)", text)
        _right(constant.group(1), abs(mpmath.cot(root)) / 2)
        _right(constant.group(2), q[data["k_max"]])
        alpha = re.search(r"alpha = ([0-9.]+) rad = ([0-9.]+) deg  \(error estimate ([0-9.e-]+) rad\)", text)
        _right(alpha.group(1), root)
        _right(alpha.group(2), root * 180 / mpmath.pi)
        # an estimate of |z - x_N|: C |x_N - x_(N-1)|^2 + delta, to its 2 digits
        _right(alpha.group(3), abs(mpmath.cot(root)) / 2 * d[-1] ** 2 + mpmath.mpf(data["rounding_level"]))
        # the header: p = sqrt(g/l) of the decimal inputs, [a, b] in degrees and radians, x_0
        p = re.search(r"p = sqrt\(g/l\) = (\S+)$", lines[0]).group(1)
        _right(p, mpmath.sqrt(mpmath.mpf(G_TEXT) / mpmath.mpf(str(data["length"]))))
        a, b, a_rad, b_rad = re.search(r"\[(\S+), (\S+)\] deg = \[(\S+), (\S+)\] rad", lines[1]).groups()
        for deg, rad in ((a, a_rad), (b, b_rad)):
            _right(rad, mpmath.mpf(deg) * mpmath.pi / 180)
        _right(re.match(r"x0 = (\S+) ", lines[head - 1]).group(1), xs[0])
    assert any(cell.startswith("<= ") for row in rows for cell in row[2:3])  # f(x_N): rounding
    assert "0.336133" not in res.out and len(repr(data["q"][-1])) > len(rows[-3][3])  # --json: every digit


@pytest.mark.slow
def test_fit_json_and_plot(cli, tmp_path):
    plot = tmp_path / "fit.png"
    res = cli("fit", "--plot", plot, "--json")
    assert res.code == 0, res.err
    data = res.json
    for key in ("points", "last_points", "normal_matrix", "normal_rhs", "positive_definite", "coefficients",
                "ssd", "max_deviation"):
        assert key in data
    assert data["points"] == 401 and len(data["last_points"]) == 10
    assert data["positive_definite"] is True
    assert list(data["coefficients"]) == ["gamma", "a0", "b0", "a1", "b1", "a2", "b2"]
    assert len(data["normal_matrix"]) == 7 and data["normal_matrix"][0][0] == 401.0
    assert all(abs(x * 1e6 - round(x * 1e6)) < 1e-6 for row in data["normal_matrix"] for x in row)
    assert data["max_deviation"] > 1e-5 and data["below_tolerance"] is False
    assert plot.read_bytes().startswith(b"\x89PNG")
    assert [p.name for p in tmp_path.iterdir()] == ["fit.png"]
    assert cli("fit", "--t-max", "6", "--round", "none", "--json").json["points"] == 601
    assert "normal equations" in cli("fit").out


def test_quadrature_json(cli):
    data = cli("quadrature", "--n", "1,10,100", "--json").json
    exact = agm_period(3.5, 4 * math.pi / 5, iterations=7)
    assert data["t_hat"] == exact
    assert [r["n"] for r in data["rows"]] == [1, 10, 100]
    assert all(r["error"] == abs(r["estimate"] - exact) for r in data["rows"])
    assert "substitution_estimate" not in data["rows"][0]
    sub = cli("quadrature", "--n", "10,100", "--substitution", "--json").json
    assert sub["rows"][1]["substitution_error"] < 1e-13
    assert "5(a)" in cli("quadrature", "--n", "1e1,1e2", "--substitution").out


def test_quadrature_prints_a_substituted_error_at_the_rounding_floor_as_the_floor(cli):
    """5(d)'s substituted column: an error at or below 128 u T^ is rounding, printed as the
    bound it is under (as the report and problem5.py print it), which the true error of the
    substituted S_n against mpmath's period respects; an error above it keeps its digits."""
    data = cli("quadrature", "--substitution", "--json").json
    lines = cli("quadrature", "--substitution").out.splitlines()
    rows = [re.findall(r"<= \S+|\S+", line) for line in lines[2:2 + len(data["rows"])]]
    with mpmath.workdps(50):
        true = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf("3.5") / mpmath.mpf(G_TEXT)) / mpmath.agm(
            1, mpmath.cos(mpmath.mpf(data["amplitude"]) / 2))
        for row, r in zip(rows, data["rows"]):
            assert int(row[0]) == r["n"]
            if r["substitution_error"] <= data["rounding_floor"]:
                assert row[-1].startswith("<= ") and abs(mpmath.mpf(r["substitution_estimate"]) - true) <= mpmath.mpf(row[-1][3:])
            else:
                assert row[-1] == f"{r['substitution_error']:.3e}"
    assert sum(row[-1].startswith("<= ") for row in rows) == 4  # n = 100 to 1e5 at 4pi/5


def test_quadrature_near_pi_says_t_hat_is_off_and_measures_the_substitution_against_t(cli):
    # pi - 1e-15: 7 iterations of (7) have not converged. Reference: mpmath's elliptic K at
    # 60 digits from the amplitude's exact double, rounded to a double.
    alpha = math.pi - 1e-15
    ref = float(reference_period(3.5, alpha, dps=60))
    args = ("quadrature", "-l", "3.5", "-a", repr(alpha), "--n", "100,3000", "--graded")
    data = cli(*args, "--json").json
    assert data["period"] == ref
    ulps = (data["t_hat"] - ref) / math.ulp(ref)
    assert abs(ulps) > FIXED_ITERATIONS_ULPS and data["t_hat_ulps"] == round(ulps)
    assert data["t_hat_note"] and f"{data['t_hat_ulps']:+d} ulp" in data["t_hat_note"]
    assert data["substitution_reference"] == "period"
    for row in data["rows"]:
        assert row["error"] == abs(row["estimate"] - data["t_hat"])  # the plain column: against (8)
        assert row["substitution_error"] == abs(row["substitution_estimate"] - ref)
    assert data["rows"][1]["substitution_error"] < 64 * 2.0**-52 * ref  # the rule is at rounding level
    lines = cli(*args).out.splitlines()
    assert lines[1] == data["t_hat_note"]
    assert lines[2].rstrip().endswith(" |S_n - T|") and lines[2].count("|S_n - T^|") == 1


def test_quadrature_at_4pi_5_has_no_note(cli):
    # 4pi/5: T^ (8) is within the loop's rounding of the period; both columns against T^.
    data = cli("quadrature", "--n", "10,100", "--substitution", "--json").json
    assert data["t_hat_note"] is None and abs(data["t_hat_ulps"]) <= FIXED_ITERATIONS_ULPS
    assert data["substitution_reference"] == "t_hat"
    assert all(r["substitution_error"] == abs(r["substitution_estimate"] - data["t_hat"]) for r in data["rows"])
    lines = cli("quadrature", "--n", "10,100", "--substitution").out.splitlines()
    assert len(lines) == 1 + 1 + 2 + 2  # T^, the header, two rows, 5(a) and the rate
    assert lines[1].count("|S_n - T^|") == 2


@pytest.mark.parametrize("gap", ["1e-6", "1e-9", "1e-12", "1e-15"])
def test_quadrature_graded_near_pi_against_mpmath(cli, gap):
    # Equal panels cannot resolve the substituted integrand's peak (width cos(alpha/2)) near
    # pi; graded panels reach the rounding level at n = 3000. Reference: mpmath's elliptic K
    # at 60 digits from the amplitude's exact double, independent of rule (11).
    import mpmath

    alpha = math.pi - float(gap)
    data = cli("quadrature", "-l", "1", "-a", repr(alpha), "--n", "100,3000", "--graded", "--json").json
    assert data["graded"] is True
    with mpmath.workdps(60):
        kp = mpmath.cos(mpmath.mpf(alpha) / 2)
        ref = float(reference_period_kp(1, kp, G))
    assert abs(data["rows"][1]["substitution_estimate"] / ref - 1) < 4e-15
    equal = cli("quadrature", "-l", "1", "-a", repr(alpha), "--n", "3000", "--substitution", "--json").json
    assert abs(equal["rows"][0]["substitution_estimate"] / ref - 1) > 1e-3  # what --graded is for
    text = cli("quadrature", "-l", "1", "-a", repr(alpha), "--n", "3000", "--graded").out
    assert "T ~ S_n (graded)" in text and f"{data['rows'][1]['substitution_estimate']:.15g}" in text


@pytest.mark.parametrize("args, fragment", [
    (("gravity", "--length-error", "-0.3cm"), "--length-error"),
    (("gravity", "--period-error", "-2e-4"), "--period-error"),
    (("gravity", "--period", "0"), "--period"),
    (("gravity", "--length", "5furlong"), "--length"),
    (("gravity", "--length", "nan"), "--length"),
    (("gravity", "--period-error", "3"), "--period-error"),
    (("quadrature", "--n", "0"), "--n"),
    (("quadrature", "--n", "10,-1"), "--n"),
    (("quadrature", "--n", "1.5"), "--n"),
    (("quadrature", "--n", "abc"), "--n"),
    (("quadrature", "--n", "1e9"), "--n = 1e9 is not allowed: must be a list of integers in [1, 1e+07]"),
    (("quadrature", "--n", "1e7,1e7,1e7"), "summing to at most 2e+07"),
    (("quadrature", "-a", "pi"), "--amplitude"),
    (("fit", "--round", "-1"), "--round"),
    (("fit", "--round", "16"), "--round"),
    (("fit", "--round", "2.5"), "--round"),
    (("fit", "--round", "six"), "--round"),
    (("fit", "--step", "0"), "--step"),
    (("fit", "--t-max", "0.005"), "--t-max = 0.005 is not allowed: must be > --step = 0.01 s"),
    (("newton", "--x0", "0"), "--x0"),
    (("newton", "--x0", "pi"), "--x0"),
    (("newton", "--x0", "4"), "--x0"),
    (("newton", "--x0", "-1deg"), "--x0"),
    (("newton", "--x0", "1deg"), "left the domain"),
    (("newton", "--target", "1.0"), "--target"),
    (("newton", "--target", "1.8"), "--target"),
    (("newton", "--length", "0"), "--length"),
])
def test_bad_inputs(cli, args, fragment):
    assert_one_line_error(cli(*args), fragment)


def test_module_import_stays_light():
    code = ("import sys, pendulab.cli.problems\n"
            "print(sorted(m for m in ('numba', 'scipy', 'matplotlib') if m in sys.modules))\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.stdout.strip() == "[]", res.stderr


@pytest.mark.parametrize("amplitude", ["4pi/5", "3.14159265358979"])
def test_quadrature_rate_sentence_states_the_observed_rate(cli, amplitude):
    # The explanation names the rate the table observed (0.5 at 4pi/5; far below it near pi,
    # where the n of the table are not yet large), not a fixed 0.5.
    data = cli("quadrature", "-a", amplitude, "--n", "10,100,1000", "--json").json
    rate = data["rows"][-1]["rate"]
    assert rate == pytest.approx(math.log10(data["rows"][1]["error"] / data["rows"][2]["error"]))
    assert f"observed over the last two n here: {rate:.3f})" in data["rate_explanation"]
    assert (abs(rate - 0.5) < 0.01) == (amplitude == "4pi/5")


def _bound(text, true):
    """A bound rounded up: ``true <= printed <= true + 10^q``."""
    from decimal import Decimal

    import mpmath

    with mpmath.workdps(50):
        unit = mpmath.mpf(10) ** Decimal(text).as_tuple().exponent
        slack = abs(true) * mpmath.mpf(10) ** -40  # 50-digit binary: an exact decimal bound is equal
        assert true - slack <= mpmath.mpf(text) <= true + unit + slack, (text, mpmath.nstr(true, 20))


def _decimal(lo, hi, places):
    return st.integers(lo * 10**places, hi * 10**places).map(lambda k: f"{k / 10**places:.{places}f}")


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(_decimal(1, 5, 3), st.integers(0, 99), _decimal(1, 5, 4), st.integers(0, 99))
def test_gravity_prints_only_right_digits(cli, length, dl_percent, period, dt_percent):
    """Every number of ``pendulab gravity`` against mpmath from the decimal inputs: g and the
    box's range within one unit of their last digit, each bound rounded up (at least the true
    one, by less than a unit), never a repr's 17th digit."""
    import mpmath

    with mpmath.workdps(50):
        ell, t = mpmath.mpf(length), mpmath.mpf(period)
        dl, dt = ell * dl_percent / 1000, t * dt_percent / 1000  # up to 10 %
        dl_text, dt_text = mpmath.nstr(dl, 6), mpmath.nstr(dt, 6)
        dl, dt = mpmath.mpf(dl_text), mpmath.mpf(dt_text)
        res = cli("gravity", "--length", length, "--length-error", dl_text, "--period", period,
                  "--period-error", dt_text)
        assert res.code == 0, res.err
        out = res.out
        c = 4 * mpmath.pi ** 2

        def gravity(a, b):
            return c * a / b ** 2

        g, g_min, g_max = gravity(ell, t), gravity(ell - dl, t + dt), gravity(ell + dl, t - dt)
        first = c / t ** 2 * dl + 2 * c * ell / t ** 3 * dt
        worst = max(g_max - g, g - g_min)
        _right(re.search(r"= (\S+) m/s\^2\n", out).group(1), g)
        _bound(re.search(r"dT  = (\S+) m/s\^2", out).group(1), first)
        _bound(re.search(r"2 dT / T  = (\S+)\n", out).group(1), dl / ell + 2 * dt / t)
        lo, hi, w = re.search(r"\[(\S+), (\S+)\]  \(worst error (\S+)\)", out).groups()
        _right(lo, g_min)
        _right(hi, g_max)
        _bound(w, worst)
        _bound(re.search(r"error <= (\S+)\)", out).group(1), max(first, worst))


@pytest.mark.parametrize(("command", "pattern", "length", "alpha"), [
    (["fit"], r"T\^ \(8\) = (\S+);", "3.5", mpmath.pi / 4),
    (["quadrature"], r"T\^ \(8\) = (\S+) s", "3.5", 4 * mpmath.pi / 5),
    (["estimate", "-l", "1", "-a", "2", "--step", "0.1"], r"T = (\S+) s;", "1", mpmath.mpf(2)),
])
def test_the_period_lines_print_only_right_digits(cli, command, pattern, length, alpha):
    """T^ of (8) and the AGM period in the commands' first lines: within one unit of the last
    printed digit of mpmath's period (a repr's 17th digit is not)."""
    res = cli(*command)
    assert res.code == 0, res.err
    with mpmath.workdps(50):
        true = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(G_TEXT)) / mpmath.agm(1, mpmath.cos(alpha / 2))
        _right(re.search(pattern, res.out).group(1), true)
