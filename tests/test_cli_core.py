"""CLI: period, simulate, estimate, length; every bad input gets one line and exit 2."""
import math
import os
import re
import subprocess
import sys

import mpmath
import pytest

from conftest import assert_one_line_error
from pendulab.numerics.period import agm_period
from reference import (
    EXAMPLE_LENGTH,
    EXAMPLE_LENGTH_TEXT,
    G_TEXT,
    G,
    ellipk_period,
    period_mp,
    reference_period,
    reference_period_kp,
)

L3 = EXAMPLE_LENGTH


def test_period_json(cli):
    res = cli("period", "-l", "3.5", "-a", "4pi/5", "--json")
    assert res.code == 0
    data = res.json
    assert data["period"] == agm_period(3.5, 4 * math.pi / 5)
    assert data["small_angle_period"] == pytest.approx(2 * math.pi * math.sqrt(3.5 / G), rel=1e-15)


def test_period_digits_json(cli):
    data = cli("period", "-l", "3.5", "-a", "4pi/5", "--digits", "40", "--json").json
    with mpmath.workdps(60):  # reference: 4 sqrt(l/g) K(sin^2(2 pi/5))
        ref = reference_period("3.5", 4 * mpmath.pi / 5, G_TEXT, dps=60)
        assert data["period_digits"] == mpmath.nstr(ref, 40, strip_zeros=False)


def test_period_iterations_and_angle_forms(cli):
    for a in ("pi/4", "45deg", "45°", "0.7853981633974483"):
        data = cli("period", "-l", "1", "-a", a, "--iterations", "7", "--json").json
        assert data["period"] == agm_period(1, math.pi / 4, iterations=7)
        assert data["iterations"] == 7
    res = cli("period", "-l", "1", "-a", "pi/4")
    assert "T  =" in res.out and "T0 =" in res.out


def test_simulate_table_is_figure3(cli):
    out = cli("simulate").out.splitlines()
    assert len(out) == 23  # header + 22 rows, j = 0..21
    assert out[22].split() == ["2.1", "0.796774928412", "-0.297068336875"]
    assert out[3].split() == ["0.2", "0.647933915928", "-1.33755362818"]


def test_simulate_json_and_csv(cli):
    data = cli("simulate", "-l", "1", "-a", "pi/4", "--step", "0.1", "--t-max", "2.1", "--json").json
    assert len(data["t"]) == len(data["theta"]) == len(data["omega"]) == 22
    assert data["theta"][21] == pytest.approx(0.796774928412, abs=5e-13)
    csv = cli("simulate", "--csv").out.splitlines()
    assert csv[0] == "t,theta,omega" and len(csv) == 23
    assert float(csv[22].split(",")[2]) == pytest.approx(-0.297068336875, abs=5e-13)


@pytest.mark.slow
@pytest.mark.parametrize("ext, magic", [("png", b"\x89PNG"), ("svg", b"<?xml"), ("pdf", b"%PDF")])
def test_simulate_figures(cli, tmp_path, ext, magic):
    plot, phase = tmp_path / f"f1.{ext}", tmp_path / f"f2.{ext}"
    res = cli("simulate", "--plot", plot, "--phase", phase)
    assert res.code == 0, res.err
    assert plot.read_bytes().startswith(magic) and phase.read_bytes().startswith(magic)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([plot.name, phase.name])  # no temp files


@pytest.mark.slow
def test_figures_leave_matplotlib_global_state_alone(cli, tmp_path):
    # The CLI draws on a Figure object: no backend switch, no rcParams edit, no pyplot figure.
    code = (
        "import matplotlib, sys\n"
        "matplotlib.use('svg')\n"
        "rc = dict(matplotlib.rcParams)\n"
        "from pendulab.cli import main\n"
        "try:\n"
        f"    main(['simulate', '--plot', {str(tmp_path / 'a.png')!r}, '--phase', {str(tmp_path / 'b.pdf')!r}])\n"
        "except SystemExit as e:\n"
        "    assert not e.code, e.code\n"
        "import matplotlib.pyplot as plt\n"
        "print(matplotlib.get_backend(), dict(matplotlib.rcParams) == rc, plt.get_fignums())\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=os.environ)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-1].split() == ["svg", "True", "[]"]
    assert (tmp_path / "a.png").read_bytes().startswith(b"\x89PNG")


def test_failed_figure_keeps_the_old_file(cli, tmp_path):
    old = tmp_path / "fig.png"
    old.write_bytes(b"old")
    res = cli("simulate", "--step", "0", "--plot", old)
    assert res.code == 2 and old.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["fig.png"]


def test_estimate_json(cli):
    data = cli("estimate", "-l", L3, "-a", "4pi/5", "--step", "1e-2,1e-3,1e-4", "--json").json
    exact = agm_period(L3, 4 * math.pi / 5)
    assert data["period"] == exact
    assert [r["step"] for r in data["rows"]] == [1e-2, 1e-3, 1e-4]
    for r in data["rows"]:
        assert r["bracket"][0] <= r["cubic"] <= r["bracket"][1]
        assert abs(r["cubic"] - exact) < r["step"] ** 2
        assert set(r) >= {"step", "bracket", "linear", "cubic", "cubic_error_estimate"}
    assert abs(data["rows"][2]["cubic_order"] - 2) < 0.1


def test_estimate_table_defaults_to_problem3(cli):
    res = cli("estimate")
    assert res.code == 0
    # The period printed to 15 significant digits, each right (mpmath's AGM); --json: the double.
    assert EXAMPLE_LENGTH_TEXT in res.out
    text = re.search(r"T = (\S+) s;", res.out).group(1)
    true = period_mp(EXAMPLE_LENGTH_TEXT, 4 * mpmath.pi / 5)
    assert len(text.replace(".", "")) == 15 and abs(mpmath.mpf(text) - true) <= mpmath.mpf(10) ** -14, text
    assert cli("estimate", "--json").json["period"] == ellipk_period(EXAMPLE_LENGTH, 4 * math.pi / 5)


def test_length(cli):
    assert cli("length", "262", "407", "634").out.strip() == EXAMPLE_LENGTH_TEXT
    assert cli("length", "262,407,634", "--json").json["length"] == EXAMPLE_LENGTH


@pytest.mark.parametrize(
    "args, fragments",
    [
        (["period", "-l", "0", "-a", "1"], ["--length", "0", "> 0"]),
        (["period", "-l", "-2", "-a", "1"], ["--length", "-2", "> 0"]),
        (["period", "-l", "abc", "-a", "1"], ["--length", "abc"]),
        (["period", "-l", "nan", "-a", "1"], ["--length", "nan"]),
        (["period", "-l", "1", "-a", "pi"], ["--amplitude", "pi", "[0, pi)"]),
        (["period", "-l", "1", "-a", "-0.1"], ["--amplitude", "-0.1", "[0, pi)"]),
        (["period", "-l", "1", "-a", "200deg"], ["--amplitude", "200deg"]),
        (["period", "-l", "1", "-a", "4pi//5"], ["--amplitude", "4pi//5"]),
        (["period", "-l", "1", "-a", "1", "--g", "0"], ["--g", "0"]),
        (["simulate", "--step", "0"], ["--step", "0"]),
        (["simulate", "--step", "-0.1"], ["--step", "-0.1"]),
        (["simulate", "--step", "3"], ["--step = 3 ", "< --t-max = 2.1 s"]),
        (["simulate", "--t-max", "0"], ["--t-max = 0 ", "> 0 s"]),
        (["simulate", "--t-max", "1", "--t0", "2"], ["--t-max = 1 ", "> --t0 = 2 s"]),
        (["simulate", "--t-max", "-1", "--t0", "0"], ["--t-max", "-1"]),
        (["simulate", "--method", "euler"], ["--method", "euler"]),
        (["estimate", "--step", "0"], ["0", "numbers > 0"]),
        (["estimate", "--step", "1e-2,x"], ["x"]),
        (["estimate", "--t-max", "3"], ["does not return", "--t-max"]),
        (["estimate", "-a", "3", "--step", "0.5"], ["over the top"]),
        (["estimate", "-l", "1", "-a", "3.14159265358979", "--step", "1e-3", "--method", "rk4"],
         ["cannot be trusted near the separatrix", "energy error", "distance to the separatrix"]),
        (["estimate", "-a", "0"], ["--amplitude", "0"]),
        (["length", "0"], ["NUMBERS", "positive integers"]),
        (["length", "12a"], ["NUMBERS", "12a"]),
        (["length", "1,,2"], ["NUMBERS", "empty item"]),
        (["simulate", "--plot", "/no/such/dir/f.png"], ["--plot", "/no/such/dir"]),
    ],
)
def test_bad_input_one_line_exit_2(cli, args, fragments):
    assert_one_line_error(cli(*args), *fragments)


def test_no_return_suggestion_works(cli):
    res = cli("estimate", "--step", "1e-2", "--t-max", "3")
    suggested = res.err.rsplit("--t-max = ", 1)[1].split()[0]  # "--t-max = 7.224 s holds the return"
    assert cli("estimate", "--step", "1e-2", "--t-max", suggested).code == 0


def _subprocess(code):
    env = dict(os.environ, PYTHONWARNINGS="ignore")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)


def test_help_and_period_do_not_import_heavy_modules():
    code = (
        "import sys, contextlib, io\n"
        "from pendulab.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    main(['--help']); main(['period', '-l', '1', '-a', 'pi/4'])\n"
        "print(sorted(m for m in ('numba', 'scipy', 'matplotlib') if m in sys.modules))\n"
    )
    res = _subprocess(code)
    assert res.stdout.strip() == "[]", res.stderr


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="threads counted in /proc (Linux)")
@pytest.mark.parametrize(("given", "threads"), [(None, 1), ("2", 2)])
def test_entry_point_loads_blas_with_one_thread_unless_the_user_says(given, threads):
    """OpenBLAS starts a worker thread per further thread it is given (each spinning as it
    loads): the command line's entry point gives it one, or what OPENBLAS_NUM_THREADS says."""
    code = (
        "import os, sys\n"
        "from pendulab.__main__ import run\n"
        "sys.argv = ['pendulab', 'period', '-l', '1', '-a', '1']\n"
        "run()\n"
        "import numpy\n"
        "print(len(os.listdir('/proc/self/task')))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.split()[-1] == str(threads)


def test_console_script_bad_input_has_no_traceback():
    res = subprocess.run([sys.executable, "-m", "pendulab", "period", "-l", "-1", "-a", "1"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2
    assert res.stderr.count("\n") == 1 and "Traceback" not in res.stderr


def test_period_text_prints_only_correct_digits(cli):
    # The double AGM can be a few ulps off; the printed 15 digits are the true period's
    # (reference: 4 sqrt(l/g) K(sin^2(alpha/2)) and 2 pi sqrt(l/g) in mpmath, 50 digits).
    out = cli("period", "-l", "1", "-a", "pi/4").out.splitlines()
    with mpmath.workdps(50):
        t = reference_period("1", mpmath.pi / 4, G_TEXT, dps=50)
        t0 = 2 * mpmath.pi * mpmath.sqrt(1 / mpmath.mpf(G_TEXT))
        assert out[0].split("=")[1].split()[0] == mpmath.nstr(t, 15, strip_zeros=False)
        assert out[1].split("=")[1].split()[0] == mpmath.nstr(t0, 15, strip_zeros=False)


def test_estimate_flags_rounding_level_and_offers_dense_output(cli):
    res = cli("estimate", "-a", "4pi/5", "--step", "1e-3,1e-4", "--dense")
    assert res.code == 0, res.err
    lines = res.out.splitlines()
    assert "dense output" in lines[2]
    row3, row4 = lines[3], lines[4]
    assert "-1.550e-15" in row3 and "*" not in row3  # interpolation error, above rounding
    assert "<1.2e-16*" in row4  # the README's 4.449e-17 is below the rounding of t_k = k h
    assert lines[5].startswith("* below the rounding level")
    data = cli("estimate", "-a", "4pi/5", "--step", "1e-4", "--json").json["rows"][0]
    assert abs(data["cubic_error_estimate"]) <= data["cubic_error_estimate_rounding_level"]
    assert data["dense_error"] == abs(data["dense"] - cli("period", "-l", EXAMPLE_LENGTH_TEXT, "-a", "4pi/5", "--json").json["period"])


def test_period_needs_neither_numpy_nor_numba():
    # The text prints Arb's proved digits without mpmath; --json adds the double by mpmath.
    # Neither imports numpy, numba or scipy (start-up time).
    code = ("import sys; from pendulab.cli import main; main(['period', '-l', '3.5', '-a', '4pi/5']); "
            "assert not {'numpy', 'numba', 'scipy', 'mpmath'} & set(sys.modules), sorted(sys.modules); "
            "main(['period', '-l', '3.5', '-a', '4pi/5', '--json']); "
            "assert not {'numpy', 'numba', 'scipy'} & set(sys.modules), sorted(sys.modules)")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert res.returncode == 0, res.stderr
    assert "6.21265033491832 s" in res.stdout


def _near_pi_texts():
    """Amplitudes within 10^-60 .. 10^-1 of pi, exactly below or at/above it: as multiples
    of pi (``0.99..9pi``) and as radians (pi's decimal expansion cut, or cut and rounded up)."""
    from hypothesis import strategies as st

    with mpmath.workdps(120):
        pi_text = mpmath.nstr(mpmath.pi, 110, strip_zeros=False)  # 3.14159... (110 digits, rounded)
    pi_cut = pi_text[:-5]  # the first 100 decimals, cut: below pi (pi is irrational)

    def multiple(k, d, above):
        text = "0." + "9" * (k - 1) + str(d)  # 1 - (10 - d) 10^-k, exactly below 1
        return ("1." + "0" * (k - 1) + str(d) if above else text) + "pi", not above

    def radians(k, above):
        cut = pi_cut[: 2 + k]  # pi cut after k decimals: below pi
        if above:  # the next decimal up: above pi
            cut = str(mpmath.mpf(cut) + mpmath.mpf(10) ** -k) if k < 15 else cut[:-1] + str(int(cut[-1]) + 1)
        return cut, not above

    return st.one_of(
        st.builds(multiple, st.integers(1, 60), st.integers(1, 9), st.booleans()),
        st.builds(radians, st.integers(1, 60).filter(lambda k: pi_cut[1 + k] != "9"), st.booleans()),  # 64 characters at most
    )


def test_period_takes_the_amplitude_exactly_near_pi(cli):
    # The range check runs on the exact amplitude: below pi by 1e-60 is accepted (its double
    # may be pi), pi or above is refused; the digits and the correctly rounded double are
    # those of mpmath's K from the exact input, independent of Arb.
    from fractions import Fraction

    from hypothesis import given, settings

    @settings(max_examples=40, deadline=None, derandomize=True)
    @given(_near_pi_texts())
    def check(case):
        text, below = case
        res = cli("period", "-l", "1", "-a", text, "--digits", "5", "--json")
        if not below:
            assert_one_line_error(res, "--amplitude", text[:30], "[0, pi)")  # long values are shown cut
            return
        assert res.code == 0, res.err
        data = __import__("json").loads(res.out)
        with mpmath.workdps(250):
            if text.endswith("pi"):
                c = Fraction(text[:-2])
                kp = mpmath.sinpi(mpmath.mpf(1 - c) / 2)  # cos(c pi/2) = sin((1 - c) pi/2), no cancellation
            else:
                kp = mpmath.cos(mpmath.mpf(text) / 2)
            t = reference_period_kp(1, kp, G_TEXT)
            assert data["period_digits"] == mpmath.nstr(t, 5, strip_zeros=False)
            assert data["period_as_written"] == mpmath.libmp.to_float(t._mpf_, rnd="n")
        on_doubles = data["amplitude"] < math.pi
        assert (data["period"] is None) == (not on_doubles) == ("period_note" in data)
        if on_doubles:
            assert data["period"] == agm_period(1.0, data["amplitude"])

    check()


@pytest.mark.parametrize("length, amplitude, steps, method", [
    (EXAMPLE_LENGTH_TEXT, "4pi/5", "1e-2,1e-3,1e-4", "taylor2"), ("1", "pi/4", "1e-2,1e-3", "taylor2"),
    ("3.5", "2", "2e-3,5e-4", "taylor2"), ("1", "2", "1e-2,1e-3,1e-4", "rk4")])  # rk4: errors near T's ulp
def test_estimate_prints_only_the_digits_its_error_against_t_allows(cli, length, amplitude, steps, method):
    """Each estimate of T in the table (linear, cubic, dense) within one unit of its last printed
    digit of the true period (mpmath's K, the amplitude's double): no digit beyond its error;
    so are the errors |linear - T|, |cubic - T|, |dense - T| (T's half ulp moves a 1e-15 error
    by a fifth) and the observed order ("noise" where their rounding leaves no digit of it)."""
    from decimal import Decimal

    res = cli("estimate", "-l", length, "-a", amplitude, "--step", steps, "--dense", "--method", method)
    assert res.code == 0, res.err
    alpha = cli("period", "-l", length, "-a", amplitude, "--json").json["amplitude"]
    true = reference_period(length, alpha, dps=50)
    rows = [line.split() for line in res.out.splitlines()[3:] if line.split()[0][0].isdigit()]
    assert len(rows) == len(steps.split(","))
    data = cli("estimate", "-l", length, "-a", amplitude, "--step", steps, "--method", method, "--dense", "--json").json

    def right(text, want):
        if text.startswith("<= "):
            assert abs(want) <= mpmath.mpf(text[3:]), (text, want)
            return
        with mpmath.workdps(50):
            unit = mpmath.mpf(10) ** Decimal(text).as_tuple().exponent
            assert abs(mpmath.mpf(text) - want) <= unit, (text, mpmath.nstr(want, 8))

    errors = []
    for row, r in zip(rows, data["rows"]):
        row = re.findall(r"<= \S+|\S+", " ".join(row))
        for text in (row[3], row[4].rstrip("!"), row[-2]):  # linear, cubic, dense
            right(text, true)
        with mpmath.workdps(50):
            e = {k: abs(mpmath.mpf(r[k]) - true) for k in ("linear", "cubic", "dense")}
        right(row[6], e["linear"])
        right(row[7], e["cubic"])
        right(row[-1], e["dense"])
        errors.append((r["step"], e["cubic"]))
        if len(row) == 11:  # the observed order of the cubic's error, against the row above
            (h0, e0), (h1, e1) = errors[-2], errors[-1]
            with mpmath.workdps(50):
                order = mpmath.log(e0 / e1) / mpmath.log(mpmath.mpf(h0) / mpmath.mpf(h1))
            if row[8] != "noise":
                right(row[8], order)
    # the full doubles stay in --json
    assert any(len(repr(r["cubic"])) > len(row[4]) for r, row in zip(data["rows"], rows))
