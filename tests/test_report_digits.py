"""Every printed digit right (issue 32, item 5): for five groups, each number the report
prints for 2(a)-(b), 3(d) and 5(b)-(d) lies within one unit of its last digit of the true
value, computed here independently in mpmath at 50 digits (Newton's iterates, the
recurrence (3) and its divided differences, the composite Gauss sums)."""
from __future__ import annotations

import re
from decimal import Decimal

import mpmath
import pytest

from pendulab.jobs.coursework import load

GROUPS = [(262, 407, 634), (99999, 1), (83001, 91234, 77777), (45678,), (1000, 2000, 3500)]
DPS = 50


def sections(students, only):
    import tempfile
    from pathlib import Path

    from pendulab.report import document
    from pendulab.report.builder import section_data

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(document.Doc, "figure", lambda self, name, paint, **size: self.figures.update({name: name}))
        with tempfile.TemporaryDirectory() as tmp:
            return section_data(students, "en", Path(tmp), only=only)


def parsed(text: str) -> tuple[Decimal, int]:
    """A number as the report prints it (``−1.05199 × 10#super[−4]``): its value, last place."""
    text = text.replace("−", "-")
    m = re.fullmatch(r"(-?[0-9]+(?:\.([0-9]+))?)(?: × 10#super\[(-?[0-9]+)\])?", text)
    assert m, text
    exp = int(m.group(3) or 0)
    return Decimal(m.group(1)).scaleb(exp), exp - len(m.group(2) or "")


def assert_right(text: str, true) -> None:
    """Within one unit of the last printed digit of ``true`` (an mpf)."""
    value, q = parsed(text)
    with mpmath.workdps(DPS):
        off = abs(mpmath.mpf(str(value)) - true)
        assert off <= mpmath.mpf(10) ** q, (text, mpmath.nstr(true, 20), mpmath.nstr(off, 3))


def newton_mp(x0):
    """2(a): Newton's iterates in 50 digits from the program's x_0, f of (9)."""
    with mpmath.workdps(DPS):
        t0 = 2 * mpmath.pi / mpmath.sqrt(mpmath.mpf("9.80665") / mpmath.mpf("0.5"))
        x, xs = mpmath.mpf(x0), []
        for _ in range(8):
            xs.append(x)
            f = t0 * (1 + mpmath.sin(x / 2) ** 2 / 4) - mpmath.mpf("1.5")
            x = x - f / (t0 * mpmath.sin(x) / 8)
        return xs


def taylor_table_mp(l_text, nodes, h="0.001"):
    """(3) in 50 digits from the inputs as written; z2 at the nodes, t_k = k h."""
    with mpmath.workdps(DPS):
        h, c = mpmath.mpf(h), -mpmath.mpf("9.80665") / mpmath.mpf(l_text)
        z1, z2, at = 4 * mpmath.pi / 5, mpmath.mpf(0), {}
        for i in range(max(nodes) + 1):
            at[i] = z2
            s, co = mpmath.sin(z1), mpmath.cos(z1)
            z1, z2 = z1 + h * z2 + h**2 / 2 * c * s, z2 + h * c * s + h**2 / 2 * c * z2 * co
        x, y = [at[k] for k in nodes], [k * h for k in nodes]
        dd = list(y)
        for k in range(1, 5):
            for i in range(4, k - 1, -1):
                dd[i] = (dd[i] - dd[i - 1]) / (x[i] - x[i - k])
        prod = x[0] * x[1] * x[2] * x[3]  # (0 - x0)...(0 - x3)
        return x, dd, dd[4] * prod


def gauss_period_mp(n):
    """5: 4 sqrt(l/(2g)) S_n in 50 digits, l = 3.5, alpha the program's double (rule (11))."""
    with mpmath.workdps(30):
        a = mpmath.mpf(load()["problem5.py"].ALPHA)
        h = a / n
        d = mpmath.sqrt(mpmath.mpf(3) / 5) * h / 2
        f = lambda t: 1 / mpmath.sqrt(2 * mpmath.sin((a + t) / 2) * mpmath.sin((a - t) / 2))  # noqa: E731
        s = mpmath.fsum(5 * f(m - d) + 8 * f(m) + 5 * f(m + d) for m in ((i + mpmath.mpf(1) / 2) * h for i in range(n)))
        return 4 * mpmath.sqrt(mpmath.mpf("3.5") / (2 * mpmath.mpf("9.80665"))) * h / 18 * s


@pytest.mark.slow
def test_newtons_iterates_print_only_right_digits():
    doc = sections(GROUPS[0], ["problem 2"])
    rows = doc.tables["p2a"]
    p2 = load()["problem2.py"]
    a, b, _, _ = p2.interval()
    true = newton_mp(a if p2.f(a) * p2.d2f(a) > 0 else b)  # from the program's x_0, as it starts
    for row, x in zip(rows, true):
        assert_right(row[1], x)
        with mpmath.workdps(DPS):
            assert_right(row[2], x * 180 / mpmath.pi)
    assert rows[0][2] == "60.000000000000"  # never 59.99999999999999


@pytest.mark.parametrize("students", GROUPS)
@pytest.mark.slow
def test_3d_prints_only_right_digits(students):
    doc = sections(students, ["problem 3"])
    p3 = load()["problem3.py"]
    l_text = load()["length.py"].group_length(list(students))[2]
    t_hat = load()["agm.py"].t_hat(float(l_text), p3.ALPHA)
    r = p3.period(float(l_text), 1e-3, t_hat)
    nodes = [round(t / 1e-3) for t in r["t"]]
    x, dd, e0 = taylor_table_mp(l_text, nodes)
    for k, row in enumerate(doc.tables["p3d"]):
        assert_right(row[1], x[k])
        assert_right(row[3], dd[k])
    assert_right(doc.values["p3d.z4"], x[4])
    assert_right(doc.values["p3d.dd"], dd[4])
    assert_right(doc.values["p3d.errest"], e0)


@pytest.mark.slow
def test_5_prints_only_right_digits():
    doc = sections(GROUPS[0], ["problem 5"])
    rows = doc.tables["p5d"]
    for row in rows:
        n = int(row[0])
        if n <= 10**4:  # 10^5 subintervals take minutes in 50 digits
            assert_right(row[1], gauss_period_mp(n))
    assert_right(doc.values["p5.q1"], gauss_period_mp(1))


@pytest.mark.slow
def test_the_check_can_fail():
    """One more digit than the error allows is caught (c4 of 3(d) printed to 10 digits)."""
    students = GROUPS[0]
    p3 = load()["problem3.py"]
    l_text = load()["length.py"].group_length(list(students))[2]
    r = p3.period(float(l_text), 1e-3, load()["agm.py"].t_hat(float(l_text), p3.ALPHA))
    _, dd, _ = taylor_table_mp(l_text, [round(t / 1e-3) for t in r["t"]])
    from pendulab.report.markup import num

    with pytest.raises(AssertionError):
        assert_right(num(r["coef"][4], 10), dd[4])
