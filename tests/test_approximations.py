"""Period approximations against independent mpmath evaluations and the papers' own claims."""
import json
import math
import re

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.cli import main
from pendulab.core.errors import InputError
from pendulab.numerics.approximations import (
    FORMULAS,
    TABLE_DEGREES,
    approximate_period,
    approximation_errors,
    rounding_error,
)
from reference import G

# Each formula's T/T0 written again in mpmath, straight from the cited papers.
MP_RATIO = {
    "small-angle": lambda a: mpmath.mpf(1),
    "coursework-9": lambda a: 1 + mpmath.sin(a / 2) ** 2 / 4,  # (9)
    "kidd-fogg": lambda a: 1 / mpmath.sqrt(mpmath.cos(a / 2)),
    "lima-arun": lambda a: -mpmath.log(mpmath.cos(a / 2)) / (1 - mpmath.cos(a / 2)),
    "ganley": lambda a: mpmath.sqrt((mpmath.sqrt(3) / 2 * a) / mpmath.sin(mpmath.sqrt(3) / 2 * a)),
}


def mp_agm_n(a, n):
    x, y = mpmath.mpf(1), mpmath.cos(a / 2)
    for _ in range(n):
        x, y = (x + y) / 2, mpmath.sqrt(x * y)
    return 1 / ((x + y) / 2)


def mp_rel_error(name, alpha):
    """T_approx/T - 1 at 40 digits, T/T0 = 2 K(k)/pi (elliptic K, not the AGM)."""
    with mpmath.workdps(40):
        a = mpmath.mpf(alpha)
        exact = 2 * mpmath.ellipk(mpmath.sin(a / 2) ** 2) / mpmath.pi
        ratio = mp_agm_n(a, int(name[3:])) if name.startswith("agm") else MP_RATIO[name](a)
        return float(ratio / exact - 1)


ALPHAS = np.radians([0.5, 10, 45, 90, 135, 170, 179.5])


@pytest.mark.parametrize("name", list(FORMULAS))
def test_relative_errors_match_mpmath(name):
    table = approximation_errors(ALPHAS, [name])
    for alpha, err in zip(ALPHAS, table.errors[name]):
        ref = mp_rel_error(name, alpha)
        # Double precision: ~1e-15 absolute on a ratio near 1 (more where alpha -> pi).
        assert err == pytest.approx(ref, rel=1e-9, abs=3e-15), (name, math.degrees(alpha))


def test_papers_claims_hold():
    fine = approximation_errors(np.radians(np.linspace(0.1, 179.9, 1799)))
    deg = np.degrees(fine.amplitudes)
    # Lima-Arun (2006), abstract: error below 0.25% (up to pi/2, their Fig. 2).
    assert np.max(np.abs(fine.errors["lima-arun"][deg <= 90])) < 2.5e-3
    # Ganley (1985), abstract: better than 5% up to 160 degrees, +-0.001 for 0-100 degrees with
    # his fitted F ~ sqrt(3)/2; with F = sqrt(3)/2 exactly the 0.001 holds to 94 degrees.
    assert np.max(np.abs(fine.errors["ganley"][deg <= 94])) < 1e-3
    assert np.max(np.abs(fine.errors["ganley"][deg <= 160])) < 0.05
    # Each AGM iteration roughly squares the error (quadratic convergence of (7)).
    i = np.argmin(np.abs(deg - 150))
    e1, e2, e3 = (abs(fine.errors[f"agm{n}"][i]) for n in (1, 2, 3))
    assert e2 < 10 * e1**2 and e3 < 10 * e2**2


def test_small_angle_series():
    # T/T0 = 1 + alpha^2/16 + ... (DLMF 19.5.1): the small-angle error is -alpha^2/16 to leading order.
    a = 1e-3
    assert approximation_errors([a], ["small-angle"]).errors["small-angle"][0] == pytest.approx(-a * a / 16, rel=1e-3)


def test_approximate_period_and_bad_names():
    # Kidd-Fogg at l = 1, alpha = pi/2: 2 pi sqrt(1/g) / sqrt(cos(pi/4)) computed by hand.
    expect = 2 * math.pi / math.sqrt(G) / math.sqrt(math.cos(math.pi / 4))
    assert approximate_period("kidd-fogg", 1, math.pi / 2) == pytest.approx(expect, rel=1e-15)
    assert approximate_period("agm7", 1, 1.0) == pytest.approx(approximate_period("agm3", 1, 1.0), rel=1e-15)
    with pytest.raises(InputError, match="formula = 'huygens'"):
        approximate_period("huygens", 1, 1.0)
    with pytest.raises(InputError, match="amplitude"):
        approximation_errors([math.pi])


@pytest.mark.slow
def test_cli_approximations(tmp_path, capsys):
    out = tmp_path / "errors.png"
    assert main(["approximations", "--plot", str(out)]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")  # what it draws: test_plot_draws_each_formulas_errors
    text = capsys.readouterr().out
    assert "lima-arun" in text and "Ganley, Am. J. Phys. 53, 73 (1985)" in text
    assert main(["approximations", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    names = [f["name"] for f in doc["formulas"]]
    assert names[:5] == ["small-angle", "coursework-9", "kidd-fogg", "lima-arun", "ganley"]
    assert main(["approximations", "--plot", str(tmp_path / "no" / "x.png")]) == 2
    assert "--plot" in capsys.readouterr().err


@pytest.mark.slow
def test_plot_draws_each_formulas_errors():
    """One line per formula through (degrees, |error|), rounding-level errors left out (NaN)."""
    from pendulab.plots.beyond import approximation_errors as draw

    table = approximation_errors(np.radians([0.5, 10, 45, 90, 170]))
    import matplotlib.pyplot as plt

    fig, given = plt.subplots()
    ax = draw(table, given)
    plt.close(fig)
    assert ax is given
    assert [line.get_label().split(":")[0] for line in ax.lines[:len(table.formulas)]] == [f.name for f in table.formulas]
    rounding = 4 * np.finfo(float).eps
    for f, line in zip(table.formulas, ax.lines):
        x, y = line.get_data()
        assert np.array_equal(x, np.degrees(table.amplitudes))
        err = np.abs(table.errors[f.name])
        assert np.array_equal(np.isnan(y), err < rounding)
        assert np.array_equal(y[~np.isnan(y)], err[err >= rounding])
    assert ax.get_yscale() == "log"


def test_period_ratio_is_the_agm_period_over_the_small_angle_one():
    # T/T0 = 2 K(sin^2(alpha/2)) / pi, mpmath's complete elliptic integral at 30 digits.
    alpha = np.radians([0.5, 45, 144, 179.9])
    table = approximation_errors(alpha)
    assert "period_ratio" in table.to_frame().columns
    for a, r in zip(alpha, table.period_ratio):
        with mpmath.workdps(30):
            ref = 2 * mpmath.ellipk(mpmath.sin(mpmath.mpf(a) / 2) ** 2) / mpmath.pi
        assert r == pytest.approx(float(ref), rel=4e-16)


def _printed_right(text: str, ref: float) -> bool:
    """``text`` within one unit of its last digit of ``ref``, or ``<= b`` with ``|ref| <= b``."""
    from pendulab.core import digits

    if text.startswith("<= "):
        return abs(ref) <= float(text[3:])
    mant, exp = digits.split(text)
    place = (exp or 0) - (len(mant.split(".")[1]) if "." in mant else 0)
    with mpmath.workdps(40):
        return abs(mpmath.mpf(text) - mpmath.mpf(ref)) <= mpmath.mpf(10) ** place


@settings(max_examples=300, deadline=None)
@given(st.sampled_from(list(FORMULAS)), st.floats(min_value=1e-3, max_value=math.radians(179.999)))
def test_the_tables_digits_are_right_at_every_amplitude(name, alpha):
    """``pendulab approximations`` prints ``T_approx/T - 1`` to at most 4 significant digits and
    the digits :func:`rounding_error` leaves: right against mpmath's K at any amplitude."""
    from pendulab.core.digits import with_error

    r = float(approximation_errors([alpha], [name]).errors[name][0])
    text = with_error(r, rounding_error(r), 4)
    assert _printed_right(text, mp_rel_error(name, alpha)), (name, math.degrees(alpha), text)


def test_the_table_prints_what_it_claims(capsys):
    """Each cell of the printed table is the digits rule above at the table's amplitudes
    (agm2 at 60 deg: -4e-14, where 4 digits would print the rounding, -4.363e-14; true -4.354e-14)."""
    assert main(["approximations"]) == 0
    lines = capsys.readouterr().out.splitlines()
    names = lines[1].split()[2:]
    rows = [re.findall(r"<= \S+|\S+", line) for line in lines[2:2 + len(TABLE_DEGREES)]]
    for row, deg in zip(rows, TABLE_DEGREES):
        assert float(row[0]) == deg
        for name, text in zip(names, row[1:]):
            assert _printed_right(text, mp_rel_error(name, math.radians(deg))), (name, deg, text)
    assert rows[TABLE_DEGREES.index(60)][1 + names.index("agm2")] == "-4e-14"
