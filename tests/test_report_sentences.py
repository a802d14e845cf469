"""The report's sentences against the data they claim, for random groups.

The sections run without typesetting (``section_data``; figures are not drawn). The
reference values come from plain Python (``plain_pendulum``, the coursework's formulas),
mpmath at high precision, or exact decimal arithmetic, never from the section itself.
"""
from __future__ import annotations

import json
import math
import re
from decimal import Decimal
from importlib import resources

import mpmath
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import plain_pendulum as plain
from pendulab.core.errors import InputError
from pendulab.core.inputs import MAX_NAME, names
from pendulab.jobs import problems
from pendulab.report import load_catalogue
from pendulab.report.markup import err, sci_beside, sci_up, up
from reference import G

EXAMPLE = (262, 407, 634)
#: Student numbers as a class has them: 1 to 4 numbers of up to 8 digits.
GROUPS = st.lists(st.integers(1, 10**8 - 1), min_size=1, max_size=4).map(tuple)
SLOW = settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def value(markup: str) -> float:
    """A number as the report's markup writes it (``2.5 × 10#super[−3]``, ``−0.5``)."""
    text = markup.replace("−", "-")
    m = re.fullmatch(r"(-?[0-9.]+)(?: × 10#super\[(-?[0-9]+)\])?", text)
    assert m, markup
    return float(Decimal(m.group(1)) * Decimal(10) ** int(m.group(2) or 0))


def sections(students, only, lang="en", tmp_path_factory=None):
    import tempfile
    from pathlib import Path

    from pendulab.report import document
    from pendulab.report.builder import section_data

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(document.Doc, "figure", lambda self, name, paint, **size: self.figures.update({name: name}))
        return section_data(students, lang, Path(tempfile.mkdtemp(prefix="pendulab-test-")), only=only)


# ----------------------------------------------------------------------------- bounds
def test_a_bound_is_rounded_up():
    assert up(0.0273622, 4) == "0.02737"  # the corner maximum of 1(b)
    assert up(0.5, 4) == "0.5000"  # exact already: unchanged
    assert up(9.99961, 4) == "10.00"
    assert sci_up(1.2e-6, 2) == "1.2 × 10#super[−6]"


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=1e-300, max_value=1e300, allow_nan=False, allow_infinity=False), st.integers(1, 6))
def test_up_is_never_below_and_within_one_unit(x, digits):
    for text in (up(x, digits), sci_up(x, digits)):
        shown = Decimal(repr(value(text))) if "#super" in text else Decimal(text)
        exact = Decimal(x)
        assert shown >= exact
        unit = Decimal(1).scaleb(exact.adjusted() - digits + 1)
        assert shown - exact < unit


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=1e-12, max_value=1e3), st.floats(min_value=1e-12, max_value=1e3))
def test_a_number_beside_a_threshold_stays_on_its_side(x, limit):
    shown = value(sci_beside(x, limit, 1))
    assert (shown < limit) == (x < limit)


# ----------------------------------------------------------------------------- section 0
def correctly_rounded_period(length: float) -> float:
    """The double nearest to the true period of the doubles l, 4pi/5, g (mpmath, 60 digits)."""
    with mpmath.workdps(60):
        alpha = mpmath.mpf(4 * math.pi / 5)
        t = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf(length) / mpmath.mpf(G)) / mpmath.agm(1, mpmath.cos(alpha / 2))
        return float(t)


@SLOW
@given(GROUPS)
def test_the_agm_note_counts_the_ulps_to_the_correctly_rounded_period(students):
    """The note on (8) says how many ulp T^ lies from the correctly rounded period, and
    prints T^ in no second form (its one form, 15 digits, is 3(b)'s)."""
    doc = sections(students, ["AGM period"])
    length = float(plain.length_text(students))
    t_hat, tc = plain.t_hat(length), correctly_rounded_period(length)
    sentence = doc.entry("agm.text")
    ulps = round(abs(t_hat - tc) / math.ulp(tc))
    if t_hat == tc:
        assert doc.choices["agm.same"] == "agm.same.equal" and "ulp" not in doc.entry("agm.same")
        assert "is the correctly rounded period" in sentence
    else:
        assert f"is {ulps} ulp from the correctly rounded period" in sentence
    # The long numbers are the amplitude limit and the true period to 20 digits: no 16- or
    # 17-digit T^ beside them.
    assert re.findall(r"[0-9]+\.[0-9]{13,}", sentence) == [doc.values["agm.limit"], doc.values["agm.mp"]]


@pytest.mark.parametrize("students, choice", [((12345, 67890), "agm.same.equal"), (EXAMPLE, "agm.same.one")])
def test_section0_the_groups_seen_on_a_page(students, choice):
    doc = sections(students, ["AGM period"])
    assert doc.choices["agm.same"] == choice


# ----------------------------------------------------------------------------- 3(b)
@pytest.mark.slow
@SLOW
@given(GROUPS)
def test_3b_says_where_t_hat_lies_against_the_bracket(students):
    from pendulab.report.markup import num

    doc = sections(students, ["problem 3"])
    length = float(plain.length_text(students))
    t_hat = plain.t_hat(length)
    event = plain.first_event(length, 0.2, 4 * t_hat)
    sentence = doc.entry("p3b.bracket")
    # 3(c): "observed orders {first} and then {last}, approaching 2", from the plain program's errors.
    errors = [abs(plain.estimate(length, h)["linear"] - t_hat) for h in (1e-2, 1e-3, 1e-4)]
    orders = [math.log10(errors[k] / errors[k + 1]) for k in range(2)]
    assert doc.values["p3c.first"] == f"{orders[0]:.2f}" and doc.values["p3c.order"] == f"{orders[1]:.2f}"
    assert abs(orders[1] - 2) < abs(orders[0] - 2)  # "approaching 2"
    if event[0] != "returns":
        assert doc.choices["p3b.bracket"] == f"p3b.bracket.{event[0]}"
        return
    lo, hi = event[1] * 0.2, (event[1] + 1) * 0.2
    side, dist = ("below", lo - t_hat) if t_hat < lo else ("above", t_hat - hi) if t_hat > hi else ("inside", t_hat - lo)
    assert doc.choices["p3b.bracket"] == f"p3b.bracket.{side}"
    assert f"{num(dist, 3)} s" in sentence
    assert ("too coarse" in sentence) == (side != "inside")


@pytest.mark.parametrize("students, side", [((45678, 53221), "inside"), (EXAMPLE, "below")])
def test_3b_the_groups_seen_on_a_page(students, side):
    doc = sections(students, ["problem 3"])
    assert doc.choices["p3b.bracket"] == f"p3b.bracket.{side}"
    text = doc.entry("p3b.bracket")
    assert ("lies inside it" in text) == (side == "inside") and ("too coarse" in text) == (side != "inside")


# ----------------------------------------------------------------------------- 1(b), 2(c), 5
def test_1b_bounds_are_bounds():
    doc = sections(EXAMPLE, ["problem 1"])
    lv, dl, tv, dt = 1.152, 0.003, 2.1536, 1e-4 * 2
    g = 4 * math.pi**2 * lv / tv**2
    corners = [4 * math.pi**2 * (lv + a) / (tv + b) ** 2 for a in (-dl, dl) for b in (-dt, dt)]
    worst = max(abs(c - g) for c in corners)  # independent: the corners of the box
    first = 4 * math.pi**2 / tv**2 * dl + 8 * math.pi**2 * lv / tv**3 * dt
    assert value(doc.values["p1.worst"]) >= worst and value(doc.values["p1.abs"]) >= first
    assert value(doc.values["p1.bound"]) >= max(worst, first)
    assert "at most 0.02737" in doc.entry("p1b")


def test_2b_the_last_correction_is_table_1s_and_the_closed_form_a_bound():
    doc = sections(EXAMPLE, ["problem 2"])
    x = problems.problem2().run.iterates
    p = math.sqrt(9.80665 / 0.5)
    closed = 2 * math.asin(2 * math.sqrt(1.5 * p / (2 * math.pi) - 1))  # independent: (9) solved
    # an estimate, printed as Table 1 prints the same step (its magnitude, the same digits)
    # (after its relation: "= " for digits, none for a bound its rounding swamps, "≤ 2 × 10^−14")
    assert doc.values["p2.last"].removeprefix("= ") == doc.tables["p2a"][-2][-1].lstrip("−")
    assert "estimates the error" in doc.entry("p2b")
    assert doc.values["p2.closed"] == "0" or value(doc.values["p2.closed"]) >= abs(closed - x[-1]) - 1e-16


def test_2c_shows_every_quotient_with_its_rounding():
    doc = sections(EXAMPLE, ["problem 2"])
    x = problems.problem2().run.iterates
    q = [abs(x[k + 2] - x[k + 1]) / abs(x[k + 1] - x[k]) ** 2 for k in range(len(x) - 2)]
    table = doc.tables["p2c"]
    assert len(table) == len(q) >= 3
    rho = problems.problem2().run.q_rounding
    for (_k, shown, _), ref, r in zip(table, q, rho):  # only the digits its rounding error allows
        assert shown == err(ref, r * ref)
    assert table[1][1] == "0.3220879"  # q_(k_max) to 7 decimals: its rounding error is 5.2e-9
    assert table[2][1] == "≤ 0.5"  # q_2 = 0.336 with a rounding error of 28 %: no digit is right, at most 0.5
    assert "$q_(2)$" in doc.entry("p2c.shown")


def test_5_the_argument_predicts_the_error():
    """5(d): panel i from the end errs by H^(1/2) E_i, E_i = O(i^(-13/2)); their sum is the error."""
    def e(i):  # the rule's error on s^(-1/2) over [i, i+1], against the exact 2(sqrt(i+1) - sqrt(i))
        with mpmath.workdps(60):
            r = mpmath.sqrt(mpmath.mpf(3) / 5)  # Gauss-Legendre, 3 points, weights 5/9, 8/9, 5/9
            rule = sum(w / 2 * (i + mpmath.mpf(1) / 2 + x / 2) ** -0.5
                       for x, w in ((-r, mpmath.mpf(5) / 9), (0, mpmath.mpf(8) / 9), (r, mpmath.mpf(5) / 9)))
            return float(2 * (mpmath.sqrt(i + 1) - mpmath.sqrt(i)) - rule)

    es = [e(i) for i in range(2000)]
    slope = math.log(es[1000] / es[500]) / math.log(1000.5 / 500.5)
    assert slope == pytest.approx(-6.5, abs=0.01)  # the neighbours: O(i^(-13/2))
    # The singular panel misses an eighth of its 2; its neighbours add 3e-5 of that, at the same order.
    assert es[0] / 2 == pytest.approx(0.1246, abs=1e-4) and 1e-5 < sum(es[1:]) / es[0] < 1e-4
    r = problems.problem5()
    row = r.rows[-1]
    h = r.amplitude / row.n
    predicted = 4 * math.sqrt(r.length / (2 * r.g)) * math.sqrt(h / math.sin(r.amplitude)) * sum(es)
    assert row.error == pytest.approx(predicted, rel=2e-3)
    doc = sections(EXAMPLE, ["problem 5"])
    assert "(E_0 + E_1 + E_2 + dots)" in doc.entry("p5d.after") and "only $O(H^6)$" not in doc.entry("p5d.after")


# ----------------------------------------------------------------------------- words
def _template_order() -> list[str]:
    template = resources.files("pendulab.report").joinpath("report.typ").read_text()
    return re.findall(r'T\("([^"]+)"\)', template)


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_every_reference_is_cited(lang):
    cat = load_catalogue(lang)
    body = json.dumps([v for k, v in cat.items() if k != "refs"], ensure_ascii=False)
    cited = {int(n) for group in re.findall(r"\[([0-9]+(?:, [0-9]+)*)\]", body) for n in group.split(", ")}
    listed = {int(n) for n in re.findall(r"\[([0-9]+)\]", " ".join(cat["refs"]))}
    assert listed == {1, 2, 3, 4, 5, 6} and listed <= cited


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_every_routine_is_justified(lang):
    import inspect

    from pendulab.numerics import group, lsq, motion, period

    intro = " ".join(load_catalogue(lang)["intro"])
    # The table of routines: each row names a routine, why, and the programs that call it.
    from pendulab.jobs.coursework import source

    rows = re.findall(r"\[`([a-z_.]+)`\], \[[^]]+\], \[([^]]+)\]", intro)
    assert {r for r, _ in rows} == {"numpy.linalg.eigvalsh", "numpy.linalg.lstsq", "mpmath", "decimal",
                                    "math.fsum", "math.ulp", "matplotlib"}
    for routine, where in rows:
        for program in re.findall(r"`([a-z0-9]+\.py)`", where):
            assert routine.rsplit(".", 1)[-1] in source(program), (routine, program)
    # Nothing about the package's machinery or tests in the hand-in.
    for word in ("numba", "Typst", "python-flint", "tests", "testes", "bit for bit", "bit a bit"):
        assert word not in intro, word
    # The uses the text states are in the code: l by mpmath, K by ellipkm1, the digits by Arb,
    # Cholesky in the program of problem 4.
    assert "mpmath" in inspect.getsource(group.group_length) and "mpmath" in source("length.py")
    assert "def cholesky" in source("problem4.py") and "np.linalg.cholesky" in inspect.getsource(lsq.definiteness)
    assert "ellipkm1" in inspect.getsource(motion.quarter_period)
    assert "flint" in inspect.getsource(period.period_ball)
    assert "Decimal" in inspect.getsource(lsq.round_half_up)
    assert "only for independent checks" not in intro and "apenas para verificações" not in intro


@pytest.mark.parametrize("lang, short", [("pt", "MAG"), ("en", "AGM")])
def test_the_abbreviation_is_defined_where_first_used(lang, short):
    cat = load_catalogue(lang)
    text = " ".join(" ".join(cat[k]) if isinstance(cat[k], list) else cat[k]
                    for k in _template_order() if k in cat)
    first = re.search(rf"\b{short}\b", text)
    # where the abbreviation is used, its first use defines it; where unused, it is never defined
    assert first is None or (text[first.start() - 1] == "(" and text[first.end()] == ")"
                             and re.search(rf"\b{short}\b", text[first.end():]))


def test_catalogues_keep_parity():
    en, pt = load_catalogue("en"), load_catalogue("pt")
    assert list(en) == list(pt)
    for key in en:  # the same placeholders on both sides
        words = lambda v: sorted(re.findall(r"\{([A-Za-z][A-Za-z0-9_.]*)\}", json.dumps(v)))  # noqa: E731
        assert words(en[key]) == words(pt[key]), key


# ----------------------------------------------------------------------------- cover
@settings(max_examples=100, deadline=None)
@given(st.lists(st.text(st.characters(blacklist_categories=("Cc", "Cs", "Co", "Cn", "Zl", "Zp", "Cf"),
                                      blacklist_characters=";"), min_size=1, max_size=MAX_NAME)
                .map(lambda s: " ".join(s.split())).filter(bool), min_size=1, max_size=5))
def test_names_round_trip(given_names):
    assert names("names", " ; ".join(given_names), len(given_names)) == tuple(given_names)


@pytest.mark.parametrize("text, count", [("A; B", 3), ("A;;B", 3), ("A", 2), ("", 1), ("x" * (MAX_NAME + 1), 1),
                                         ("A\x1b[31m", 1), ("A; B; C; D", 3)])
def test_bad_names_are_named(text, count):
    with pytest.raises(InputError) as exc:
        names("names", text, count)
    assert exc.value.name == "names" and f"{count} name" in exc.value.allowed


@pytest.mark.slow
def test_names_on_the_cover(tmp_path):
    import pypdf

    from pendulab.report import build_report

    out = tmp_path / "r.pdf"
    given_names = ("Zoë Ñúñez-O'Brien", "Αλέξανδρος Παπαδόπουλος")
    build_report((99999, 1), output=out, names=given_names)
    first = pypdf.PdfReader(str(out)).pages[0].extract_text()
    assert "Zoë Ñúñez-O'Brien (99999)" in first and "Αλέξανδρος Παπαδόπουλος (1)" in first


def test_cli_names_count_is_checked_before_the_work(tmp_path, capsys, monkeypatch):
    from pendulab.cli import main
    from pendulab.report import builder

    def no_work(*a, **k):
        raise AssertionError("the work started")

    monkeypatch.setattr(builder, "build_report", no_work)
    monkeypatch.chdir(tmp_path)
    assert main(["report", "--students", "1,2,3", "--names", "Ana; Rui"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--names" in err and "3 names" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


# ----------------------------------------------------------------------------- figures 3 and 4
def test_figure3_points_over_the_curve_and_figure4_band_visible():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pendulab.plots.problems import fit, fit_residuals

    r = problems.problem4()
    fig, (a, b) = plt.subplots(1, 2)
    fit(r, a)
    curve, points = a.lines[0], a.lines[1]
    assert len(points.get_xdata()) == r.points and points.get_zorder() > curve.get_zorder()
    fit_residuals(r, b)
    assert b.get_yscale() == "symlog"
    # The band +-tolerance takes a visible share of the axis height (1/200 of it on a linear axis).
    lo, hi = b.get_ylim()
    tr = b.transData.transform
    band = abs(tr((0, r.tolerance))[1] - tr((0, -r.tolerance))[1])
    full = abs(tr((0, hi))[1] - tr((0, lo))[1])
    assert band / full > 0.15 and max(abs(lo), abs(hi)) >= r.fit.max_deviation
    plt.close(fig)


def test_names_beyond_the_embedded_fonts_search_the_system_fonts():
    from pendulab.report.typeset import needs_system_fonts

    assert not needs_system_fonts(["Zoë Ñúñez-O'Brien", "Αλέξανδρος", "Дмитрий", "Łukasz Żółć"])
    assert all(needs_system_fonts([n]) for n in ("李明", "שרה כהן", "محمد", "अनिल"))


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_an_untrusted_h02_return_is_said_untrusted(lang):
    """A sum of 1115 gives l = 5^(1/4) = 1.4953487812: the h = 0.2 simulation returns at [5, 5.2],
    but the engine's search finds it untrusted (its p(0) more than a quarter period off the
    period); 3(b) says so after the bracket, with the search's numbers, in each language. The
    example group's return is trusted: no such sentence. The key marks the same return."""
    from pendulab.core.methods import Status
    from pendulab.jobs.key import group_answers
    from pendulab.numerics.crossing import search_period
    from pendulab.numerics.period import agm_period

    length, alpha = 1.4953487812, 4 * math.pi / 5
    s = search_period(length, alpha, 0.2, 4 * agm_period(length, alpha, iterations=7))
    assert s.status == Status.UNTRUSTED and s.max_energy_drift <= s.separatrix_distance
    off = abs(s.estimate.cubic - s.period) / s.period
    assert off > 0.25  # independent of the search's rule: mpmath's period, below
    with mpmath.workdps(30):
        true = 4 * mpmath.sqrt(mpmath.mpf("1.4953487812") / mpmath.mpf(G)) * mpmath.ellipk(mpmath.sin(mpmath.mpf(alpha) / 2) ** 2)
    assert abs(s.estimate.cubic - float(true)) / float(true) > 0.25
    doc = sections((1115,), ["problem 3"], lang)
    assert doc.values["p3b.l"] == "1.4953487812" and doc.choices["p3b.tmax"] == "p3b.tmax.returns"
    assert doc.choices["p3b.trust"] == "p3b.trust.off"
    text = doc.entry("p3b.bracket")
    assert text.endswith(doc.entry("p3b.trust")) and ("separatrix" if lang == "en" else "separatriz") in text
    assert f"{off:.0%}" in text and value(doc.values["p3b.cubic"]) == pytest.approx(s.estimate.cubic, abs=1e-4)
    example = sections(EXAMPLE, ["problem 3"], lang)
    assert example.choices["p3b.trust"] == "p3b.trust.trusted" and example.values["p3b.trust"] == ""
    assert group_answers((1115,))["plot"]["status"] == "untrusted" and group_answers(EXAMPLE)["plot"]["status"] == "found"


def test_an_untrusted_return_by_its_energy_names_both_energies(monkeypatch):
    """The other reason (no real group's h = 0.2 return has it): the energy error at the return
    beyond the distance to the separatrix, forced on the 1115 group's search."""
    import dataclasses

    from pendulab.numerics import crossing

    real = crossing.search_period

    def forced(*args, **kwargs):
        s = real(*args, **kwargs)
        return dataclasses.replace(s, max_energy_drift=2 * s.separatrix_distance)

    monkeypatch.setattr(crossing, "search_period", forced)
    doc = sections((1115,), ["problem 3"])
    assert doc.choices["p3b.trust"] == "p3b.trust.energy"
    from pendulab.report.markup import sci

    distance = G / 1.4953487812 * (1 + math.cos(4 * math.pi / 5))  # (g/l)(1 + cos alpha) = 1.2525 1/s^2
    assert (doc.values["p3b.drift"], doc.values["p3b.sep"]) == (sci(2 * distance, 2), sci(distance, 2))
    assert doc.values["p3b.drift"] in doc.entry("p3b.bracket") and doc.values["p3b.sep"] in doc.entry("p3b.bracket")
