"""pendulab.core.inputs, the one parser of every typed value, and pendulab.core.methods, the registry.

Reference values are exact rationals written by hand from the literals (``115.2cm`` is
1152/1000 m) or mpmath at 50 digits for multiples of pi.
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hostile import HOSTILE
from pendulab.core import inputs, methods
from pendulab.core.errors import InputError, NumericalError, PendulabError
from reference import EXAMPLE_LENGTH_TEXT

M = {"m": Fraction(1), "cm": Fraction(1, 100), "mm": Fraction(1, 1000)}


@pytest.mark.parametrize("text, coef", [("3.5", Fraction(7, 2)), ("-2e-3", Fraction(-1, 500)), ("1/3", Fraction(1, 3)),
                                        (".5", Fraction(1, 2)), ("5.", Fraction(5)), (" 7 / 2 ", Fraction(7, 2)),
                                        (EXAMPLE_LENGTH_TEXT, Fraction(20800838231, 10**10)), ("1e-400", Fraction(1, 10**400))])
def test_real_is_exact(text, coef):
    x = inputs.real("x", text)
    assert x.coef == coef and x.pi_power == 0 and x.text == text.strip()


@pytest.mark.parametrize("text, coef, pi_power", [
    ("pi/4", Fraction(1, 4), 1), ("4pi/5", Fraction(4, 5), 1), ("4*pi/5", Fraction(4, 5), 1), ("π/4", Fraction(1, 4), 1),
    ("-pi/4", Fraction(-1, 4), 1), ("0.5pi", Fraction(1, 2), 1), ("pi*2/3", Fraction(2, 3), 1),
    ("45deg", Fraction(1, 4), 1), ("45°", Fraction(1, 4), 1), ("45 degrees", Fraction(1, 4), 1),
    ("90/2deg", Fraction(1, 4), 1), ("0.5rad", Fraction(1, 2), 0), ("0.785", Fraction(785, 1000), 0),
])
def test_angle_forms_are_exact(text, coef, pi_power):
    x = inputs.angle_value("a", text)
    assert (x.coef, x.pi_power) == (coef, pi_power)


def test_angles_round_correctly():
    with mpmath.workdps(50):
        assert float(inputs.angle("a", "4pi/5")) == float(4 * mpmath.pi / 5)
        assert float(inputs.angle("a", "179.99deg")) == float(mpmath.mpf(17999) / 18000 * mpmath.pi)


@pytest.mark.parametrize("text", ["pi", "180deg", "4pi/4", "3.1415926536", "-0.1", "-pi/4", "1e400", "nan"])
def test_angle_range_is_judged_on_the_exact_value(text):
    with pytest.raises(InputError, match=r"\[0, pi\)"):
        inputs.angle("amplitude", text)


def test_open_low_angle():
    assert float(inputs.angle("x0", "0")) == 0
    with pytest.raises(InputError, match=r"\(0, pi\)"):
        inputs.angle("x0", "0", open_low=True)


@pytest.mark.parametrize("text", ["１", "²", "١٢", "𝟏", "½", "٣.٥", "1٢"])
def test_unicode_digits_are_refused_everywhere(text):
    for parse in (lambda s: inputs.real("v", s), lambda s: inputs.angle("v", s),
                  lambda s: inputs.integer("v", s, 0, 10**6), lambda s: inputs.positive_list("v", s),
                  lambda s: inputs.students("v", s), lambda s: inputs.quantity("v", s, M, "m", True)):
        with pytest.raises(InputError, match=r"digits 0-9|integers"):
            parse(text)


@pytest.mark.parametrize("text", ["1e99999999", "1e-99999999", "1e401", "9" * 400, "1e99999999/3", "1e99999999pi"])
def test_huge_literals_are_refused_at_once(monkeypatch, text):
    """Refused on their exponent, before any exact value is made: Fraction("1e99999999")
    would compute 10**99999999 (minutes). What reaches Fraction is recorded."""
    made = []
    real = inputs.Fraction

    def recording(*args):
        made.extend(a for a in args if isinstance(a, str))
        return real(*args)

    monkeypatch.setattr(inputs, "Fraction", recording)
    with pytest.raises(InputError):
        inputs.real("v", text)
    with pytest.raises(InputError):
        inputs.angle("v", text)
    assert not [m for m in made if "e" in m.lower() and abs(int(m.lower().split("e")[1])) > inputs.MAX_EXPONENT], made


@pytest.mark.parametrize("text, why", [("1e400", "between"), ("1e-320", "between"), ("0", "> 0"), ("-1", "> 0"),
                                       ("inf", "> 0"), ("1,5", "> 0"), ("0x10", "> 0"), ("", "(empty)")])
def test_positive(text, why):
    with pytest.raises(InputError) as exc:
        inputs.positive("length", text)
    assert why in str(exc.value) and str(exc.value).startswith("length = ")


def test_quantity_units():
    assert inputs.quantity("l", "115.2cm", M, "m", True).coef == Fraction(1152, 1000)
    assert inputs.quantity("l", "1.152", M, "m", True).coef == Fraction(1152, 1000)
    assert inputs.quantity("l", "0mm", M, "m", False).coef == 0
    for bad in ("5furlong", "0", "-1cm", "1e-99999999", "cm"):
        with pytest.raises(InputError, match="in m or cm or mm"):
            inputs.quantity("l", bad, M, "m", True)


@pytest.mark.parametrize("text", ["1e-2,1e-3", "1e-2 1e-3", "1e-2, 1e-3", " 1e-2 ,1e-3 "])
def test_lists_take_commas_and_spaces(text):
    assert inputs.positive_list("step", text) == [1e-2, 1e-3]


@pytest.mark.parametrize("text", ["1e-2,,1e-3", "1e-2,", ",1e-2", "1e-2, ,1e-3", ","])
def test_lists_refuse_empty_items(text):
    with pytest.raises(InputError, match="empty item"):
        inputs.positive_list("step", text)


def test_list_item_error_names_the_item():
    with pytest.raises(InputError) as exc:
        inputs.positive_list("step", "1e-2,x")
    assert exc.value.value == "x" and exc.value.name == "step"


def test_integers():
    assert inputs.integer("n", "1e5", 1, 10**9) == 100_000
    assert inputs.integer_list("n", "1, 10 1e2", 1, 10**9) == [1, 10, 100]
    for bad in ("2.5", "0", "1e10", "ten"):
        with pytest.raises(InputError, match=r"\[1, "):
            inputs.integer("n", bad, 1, 10**9)


def test_students_both_forms():
    assert inputs.students("s", "262,407,634") == inputs.students("s", "262 407 634") == (262, 407, 634)
    assert inputs.students("s", ["1234", "5678"]) == (1234, 5678)
    for bad in ("0", "-3", "12a", "1" * 19, "1,,2", "²"):
        with pytest.raises(InputError, match="student numbers"):
            inputs.students("s", bad)


def test_output_paths(tmp_path):
    assert inputs.output_path("plot", tmp_path / "f.PNG", (".png", ".svg")) == tmp_path / "f.PNG"
    for bad, why in ((tmp_path / "f.xyz", "ending in .png or .svg"), ("", "(empty)"),
                     (tmp_path / "no" / "f.png", "existing folder"), (tmp_path, "not a folder"),
                     (tmp_path / ("x" * 300 + ".png"), "at most 255 bytes")):
        with pytest.raises(InputError) as exc:
            inputs.output_path("plot", bad, (".png", ".svg"))
        assert why in str(exc.value) or "accepts" in str(exc.value)


def test_angle_range_is_numpy_linspace():
    import numpy as np

    got = inputs.angle_range("a", "1deg:179deg:1000", 10**6)
    assert got == np.linspace(math.radians(1), float(inputs.angle("a", "179deg")), 1000).tolist()
    with pytest.raises(InputError, match="empty or reversed"):
        inputs.angle_range("a", "10deg:10deg:9", 10**6)


# ------------------------------------------------------------------ properties

def _one_line_input_error(parse, text):
    try:
        parse(text)
    except InputError as exc:
        msg = str(exc)
        assert "\n" not in msg and msg.startswith("v = ") and len(msg) < 400, msg
        return False
    return True


PARSERS = {
    "real": lambda s: inputs.real("v", s),
    "positive": lambda s: inputs.positive("v", s),
    "non_negative": lambda s: inputs.non_negative("v", s),
    "angle": lambda s: inputs.angle("v", s),
    "integer": lambda s: inputs.integer("v", s, 0, 10**9),
    "quantity": lambda s: inputs.quantity("v", s, M, "m", True),
    "positive_list": lambda s: inputs.positive_list("v", s),
    "integer_list": lambda s: inputs.integer_list("v", s, 1, 10**9),
    "students": lambda s: inputs.students("v", s),
    "method": lambda s: inputs.method("v", s),
    "angle_range": lambda s: inputs.angle_range("v", s, 1000),
}


@pytest.mark.slow
@settings(max_examples=400, deadline=5000)
@given(parser=st.sampled_from(sorted(PARSERS)), text=st.one_of(HOSTILE, st.text()))
def test_every_parser_returns_or_raises_one_line(parser, text):
    if _one_line_input_error(PARSERS[parser], text) and parser in ("real", "positive", "non_negative", "angle"):
        x = PARSERS[parser](text)
        assert math.isfinite(float(x))  # whatever is accepted has a finite double


@settings(max_examples=200, deadline=5000)
@given(mantissa=st.integers(-10**30, 10**30), exponent=st.integers(-300, 270))  # |value| < 1e301
def test_decimal_literals_are_exact(mantissa, exponent):
    x = inputs.real("v", f"{mantissa}e{exponent}")
    assert x.coef == Fraction(mantissa) * Fraction(10) ** exponent
    assert float(x) == float(Fraction(mantissa) * Fraction(10) ** exponent)  # correctly rounded


@settings(max_examples=200, deadline=5000)
@given(value=st.floats(min_value=2.3e-308, max_value=1.7e308))
def test_a_double_written_back_reads_as_itself(value):
    assert float(inputs.positive("v", repr(value))) == value


# ------------------------------------------------------------------ the method registry

def test_registry():
    assert list(methods.METHODS) == ["taylor2", "rk4", "verlet"] == [m.name for m in methods.menu()]
    m = methods.resolve("taylor:4")
    assert (m.name, m.code, m.order) == ("taylor:4", methods.Kernel.TAYLOR, 4)
    assert methods.resolve("rk4").order == 4 and methods.resolve("verlet").code == methods.Kernel.VERLET
    with pytest.raises(AttributeError):
        m.order = 5  # frozen
    for bad in ("taylor:0", "taylor:31", "taylor:１", "taylor:0004", "RK4", "", "taylor:"):
        with pytest.raises(InputError, match="taylor2, rk4, verlet, taylor:P"):
            methods.resolve(bad)


def test_kernels_share_the_registry_codes():
    from pendulab.engine import kernels
    from pendulab.jobs import sweep

    assert tuple(methods.Kernel) == (kernels.TAYLOR2, kernels.RK4, kernels.VERLET, kernels.TAYLOR)
    # the kernels' four; NODES_COINCIDE (two nodes z2 equal) and UNTRUSTED are search_period's own
    assert tuple(methods.Status)[:4] == (kernels.FOUND, kernels.NO_RETURN, kernels.LEFT_OSCILLATION, kernels.TOO_EARLY)
    assert tuple(methods.Status)[4:] == (methods.Status.NODES_COINCIDE, methods.Status.UNTRUSTED)
    assert sweep.STATUS == ("found", "no_return", "left_oscillation", "too_early", "nodes_coincide", "untrusted")


def test_numerical_errors_are_not_value_errors():
    # A failed computation must not be swallowed by code that catches ValueError for bad input.
    assert not issubclass(NumericalError, ValueError) and issubclass(NumericalError, PendulabError)
    assert issubclass(InputError, ValueError)
