"""Every printed digit right (issue 32, item 5): for six groups, each number the report
prints in problems 1, 2, 3(a)-(d), 4 and 5 lies within one unit of its last digit of the
true value of the quantity the report says it is, computed here independently in mpmath
(50 digits; 30 for the long runs of (3)) or from exact decimals.

The rule, per kind of quantity:

* a *value* (``g``, an iterate, a period, a coefficient, an eigenvalue) is right when
  ``|printed - true| <= 10^q``, ``10^q`` the place of its last printed digit; the true value is
  that of the mathematics the report names: Newton's iterates and (3) in exact arithmetic from
  the inputs as written (``l`` the 10-decimal text, ``h`` a decimal, ``alpha`` with the true
  pi; problem 5's ``alpha`` the program's double, as the rule (11) is applied to it), ``T^``
  the true period (7 iterations of (7) have converged far below a double), the coefficients
  of 4(d) the exact solution of the rounded normal equations (6 decimals, as the coursework
  asks), the SVD column the exact least-squares solution;
* a *bound* (printed rounded up: ``|e_g| <=``, ``||A - A~||_2 <=``, a moved amount) is right
  when ``true <= printed <= true + 10^q``;
* a value whose error (measured or propagated) leaves no digit is not printed as digits but
  marked (``≤ b``, ``|x| + error`` rounded up to one digit, or the words of the catalogue): a
  ``≤ b`` is checked as a true upper bound of the value's size, ``|true| <= b``;
* inputs, integers (``j``, ``n``, ``k_max``) and multiples of the step are exact: equal.

Problems 1, 2, 4 and 5 do not depend on the group: their numbers are checked for every group
against truths computed once (a test checks every group prints the same for them). The pt
report prints the same numbers (checked for the example group). Not checked here: 3(b)'s
footnote's amplitude limit of 7 iterations and its distance to pi (the engine's search,
``fixed_iterations_limit``, checked in ``test_report``). The engine's numbers of an untrusted
h = 0.2 return, which none of the six groups has, are checked for a seventh (a sum of 1115).
"""
from __future__ import annotations

import functools
import math
import re
from decimal import Decimal

import mpmath
import pytest

from pendulab.jobs.coursework import load

#: (5,): 3(d)'s divided difference t[x_0..x_4] and e(0) are swamped by their rounding (printed ≤ b)
GROUPS = [(262, 407, 634), (99999, 1), (83001, 91234, 77777), (45678,), (1000, 2000, 3500), (5,)]
DPS = 50
G = "9.80665"
FIXED = ["problem 1", "problem 2", "problem 4", "problem 5"]  # not the group's: the same for all
pytestmark = pytest.mark.slow  # the sections of six groups and (3) at h = 1e-4 in mpmath: a minute


def sections(students, only=None, lang="en"):
    import tempfile
    from pathlib import Path

    from pendulab.report import document
    from pendulab.report.builder import section_data

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(document.Doc, "figure", lambda self, name, paint, **size: self.figures.update({name: name}))
        with tempfile.TemporaryDirectory() as tmp:
            return section_data(students, lang, Path(tmp), only=only)


@pytest.fixture(scope="module")
def docs():
    """The section data of each group, built once."""
    return {g: sections(g, ["AGM period", "problem 1", "problem 2", "problem 3", "problem 4", "problem 5"]) for g in GROUPS}


def parsed(text: str) -> tuple[Decimal, int]:
    """A number as the report prints it (``−1.05199 × 10#super[−4]``, ``0.880``, ``1%``): its
    value and the exponent ``q`` of its last place."""
    text = text.replace("−", "-").replace("\u2009", "").strip()
    percent = text.endswith("%")
    text = text.rstrip("%")
    m = re.fullmatch(r"(-?[0-9]+(?:\.([0-9]+))?)(?: ?[×x] ?10(?:#super\[|\^)(-?[0-9]+)\]?)?", text)
    assert m, text
    exp = int(m.group(3) or 0) - 2 * percent
    return Decimal(m.group(1)).scaleb(exp), exp - len(m.group(2) or "")


def off(text: str, true) -> tuple:
    value, q = parsed(text)
    with mpmath.workdps(DPS):
        return mpmath.mpf(str(value)) - mpmath.mpf(true), mpmath.mpf(10) ** q


def assert_right(text: str, true) -> None:
    """Within one unit of the last printed digit of ``true``."""
    d, unit = off(text, true)
    assert abs(d) <= unit, (text, mpmath.nstr(true, 20), mpmath.nstr(d, 3))


def assert_bound(text: str, true) -> None:
    """A bound rounded up: ``true <= printed <= true + 10^q``."""
    d, unit = off(text, abs(mpmath.mpf(true)))
    assert 0 <= d <= unit, (text, mpmath.nstr(true, 20), mpmath.nstr(d, 3))


def assert_right_or_under(text: str, true) -> None:
    """A value, or one its error swamps, marked ``≤ b`` (``b`` one significant digit): then a
    true upper bound of its size, ``|true| <= b``."""
    if not text.startswith("≤ "):
        assert_right(text, true)
        return
    value, _ = parsed(text[2:])
    assert len(value.normalize().as_tuple().digits) == 1, text
    with mpmath.workdps(DPS):
        assert abs(mpmath.mpf(true)) <= mpmath.mpf(str(value)), (text, mpmath.nstr(true, 20))


def assert_exact(text: str, true) -> None:
    """Exactly the value (an input, an integer, a multiple of the step): far below its last place."""
    d, unit = off(text, true)
    assert abs(d) <= unit * mpmath.mpf(10) ** -30, (text, true)


def mp(x) -> mpmath.mpf:
    """A double exactly (its binary value), a decimal text exactly to DPS digits."""
    return mpmath.mpf(x)


# ----------------------------------------------------------------------------- truths
def period_mp(l_text, alpha):
    """The true period 2 pi sqrt(l/g) / M(1, cos(alpha/2))."""
    with mpmath.workdps(DPS):
        return 2 * mpmath.pi * mpmath.sqrt(mp(l_text) / mp(G)) / mpmath.agm(1, mpmath.cos(alpha / 2))


def taylor_mp(l_text, alpha, h_text, steps=None, stop=False, dps=DPS):
    """(3) in ``dps`` digits: the lists z1, z2 for ``steps`` steps; with ``stop``, until two
    steps past the first return (z2_j > 0 >= z2_(j+1), z1_(j+1) > 0) or |z1| >= pi."""
    with mpmath.workdps(dps):
        h, c = mp(h_text), -mp(G) / mp(l_text)
        z1, z2 = [alpha], [mpmath.mpf(0)]
        j = over = None
        i = 0
        while (steps is None or i < steps) and (j is None or i < j + 3):
            s, co = mpmath.sin(z1[i]), mpmath.cos(z1[i])
            z1.append(z1[i] + h * z2[i] + h**2 / 2 * c * s)
            z2.append(z2[i] + h * c * s + h**2 / 2 * c * z2[i] * co)
            if stop and j is None and over is None:
                if abs(z1[i + 1]) >= mpmath.pi:
                    over = i + 1
                    break
                if z2[i] > 0 >= z2[i + 1] and z1[i + 1] > 0:
                    j = i
            i += 1
        return z1, z2, j, over


def cubic_mp(x, y):
    """Newton's divided differences on the five nodes, p(0) of the cubic on the first four."""
    dd = list(y)
    for k in range(1, 5):
        for i in range(4, k - 1, -1):
            dd[i] = (dd[i] - dd[i - 1]) / (x[i] - x[i - k])
    p = dd[3]
    for k in (2, 1, 0):
        p = p * (0 - x[k]) + dd[k]
    prod = x[0] * x[1] * x[2] * x[3]
    return dd, p, prod


@functools.cache
def problem3_mp(students):
    """3(b)-(d) in exact arithmetic for the group (30 digits for the runs of (3))."""
    p = load()
    l_text = p["length.py"].group_length(list(students))[2]
    with mpmath.workdps(DPS):
        alpha = 4 * mpmath.pi / 5
    t = period_mp(l_text, alpha)
    out = {"l": l_text, "T": t}
    # 3(b): h = 0.2 over 4 T^
    _, _, j, over = taylor_mp(l_text, alpha, "0.2", steps=int(4 * t / mp("0.2")) + 1, stop=True)
    out["b"] = {"j": j, "over": over}
    out["c"] = {}
    for h_text in ("0.01", "0.001", "0.0001"):
        _, z2, j, _ = taylor_mp(l_text, alpha, h_text, stop=True, dps=30)
        with mpmath.workdps(DPS):
            h = mp(h_text)
            linear = j * h + h * z2[j] / (z2[j] - z2[j + 1])
            nodes = [j - 1, j, j + 1, j + 2, j - 2]
            x, y = [z2[k] for k in nodes], [k * h for k in nodes]
            dd, p0, prod = cubic_mp(x, y)
        out["c"][h_text] = {"j": j, "h": h, "linear": linear, "p0": p0, "x": x, "y": y, "dd": dd,
                            "prod": prod, "e0": dd[4] * prod, "nodes": nodes}
    return out


def newton_mp(x0, steps=8):
    """2(a): Newton's iterates in 50 digits from the program's x_0, f of (9)."""
    with mpmath.workdps(DPS):
        t0 = 2 * mpmath.pi / mpmath.sqrt(mp(G) / mp("0.5"))
        x, xs = mp(x0), []
        for _ in range(steps):
            xs.append(x)
            f = t0 * (1 + mpmath.sin(x / 2) ** 2 / 4) - mp("1.5")
            x = x - f / (t0 * mpmath.sin(x) / 8)
        return xs


def f2(x):
    with mpmath.workdps(DPS):
        t0 = 2 * mpmath.pi / mpmath.sqrt(mp(G) / mp("0.5"))
        return t0 * (1 + mpmath.sin(x / 2) ** 2 / 4) - mp("1.5"), t0 * mpmath.sin(x) / 8, t0 * mpmath.cos(x) / 8, t0


def gauss_mp(n, sub=False):
    """5: 4 sqrt(l/(2g)) S_n, l = 3.5, alpha the program's double (rule (11)); ``sub``: the
    same rule on the substituted integrand sqrt(2)/sqrt(k'^2 + k^2 sin^2 psi) over [0, pi/2]."""
    with mpmath.workdps(30):
        a = mp(load()["problem5.py"].ALPHA)
        if sub:
            k, kp, b = mpmath.sin(a / 2), mpmath.cos(a / 2), mpmath.pi / 2

            def f(t):
                return mpmath.sqrt(2) / mpmath.sqrt(kp**2 + (k * mpmath.sin(t)) ** 2)
        else:
            b = a

            def f(t):
                return 1 / mpmath.sqrt(2 * mpmath.sin((a + t) / 2) * mpmath.sin((a - t) / 2))
        h = b / n
        d = mpmath.sqrt(mpmath.mpf(3) / 5) * h / 2
        s = mpmath.fsum(5 * f(m - d) + 8 * f(m) + 5 * f(m + d) for m in ((i + mpmath.mpf(1) / 2) * h for i in range(n)))
        return 4 * mpmath.sqrt(mp("3.5") / (2 * mp(G))) * h / 18 * s


@functools.cache
def problem5_mp():
    t = period_mp("3.5", mp(load()["problem5.py"].ALPHA))  # of the alpha the rule integrates
    periods = {10**k: gauss_mp(10**k) for k in range(6)}
    # The substituted rule is O(H^6) on an analytic integrand: at n = 1000 it is within 1e-20
    # of T (checked below), so T is its exact value for n = 10^4, 10^5.
    sub = {n: gauss_mp(n, sub=True) for n in (10, 100, 1000)}
    assert abs(sub[1000] - t) < 1e-20
    sub.update({10**4: t, 10**5: t})
    return t, periods, sub


@functools.cache
def problem4_mp(steps):
    """4: (3) for l = 3.5, alpha = pi/4, h = 0.01 in 50 digits; A, r at t_j = j/100 exactly; the
    rounded (6 decimals) normal equations solved exactly; the exact least-squares solution."""
    with mpmath.workdps(DPS):
        z1, _, _, _ = taylor_mp("3.5", mpmath.pi / 4, "0.01", steps=steps)
        ts = [mpmath.mpf(j) / 100 for j in range(steps + 1)]
        rows = [[1, mpmath.sin(t), mpmath.cos(t), mpmath.sin(2 * t), mpmath.cos(2 * t), mpmath.sin(3 * t),
                 mpmath.cos(3 * t)] for t in ts]
        a = mpmath.matrix(7, 7)
        r = mpmath.matrix(7, 1)
        for row, y in zip(rows, z1):
            for i in range(7):
                r[i] += row[i] * y
                for k in range(7):
                    a[i, k] += row[i] * row[k]
        six = mpmath.mpf(10) ** 6
        a6 = mpmath.matrix([[mpmath.nint(a[i, k] * six) / six for k in range(7)] for i in range(7)])
        r6 = mpmath.matrix([mpmath.nint(r[i] * six) / six for i in range(7)])
        coef = mpmath.lu_solve(a6, r6)
        svd = mpmath.lu_solve(a, r)
        res = [y - sum(row[i] * coef[i] for i in range(7)) for row, y in zip(rows, z1)]
        jmax = max(range(len(res)), key=lambda j: abs(res[j]))
        low = mpmath.cholesky(a6)
        eig = sorted(mpmath.eigsy(a6, eigvals_only=True))
        moved = max(abs(e) for e in mpmath.eigsy(a6 - a, eigvals_only=True))

        def phi(s):
            return coef[0] + sum(coef[2 * i - 1] * mpmath.sin(i * s) + coef[2 * i] * mpmath.cos(i * s) for i in (1, 2, 3))
        # Between the data points (20 samples per step) against the exact motion.
        fine = [mpmath.mpf(i) / 2000 for i in range(20 * steps + 1)]
        dev = [abs(exact_theta(mpmath.pi / 4, s) - phi(s)) for s in fine]
        i = max(range(len(dev)), key=dev.__getitem__)
        taylor = max(abs(z1[j] - exact_theta(mpmath.pi / 4, ts[j])) for j in range(steps + 1))
        return {"z1": z1, "t": ts, "a": a, "r": r, "coef": coef, "svd": svd, "res": res, "jmax": jmax,
                "pivot": min(low[k, k] ** 2 for k in range(7)), "eig": eig, "moved": moved,
                "exactdev": dev[i], "exactat": fine[i], "taylor": taylor}


def exact_theta(alpha, t):
    """The exact motion theta(t) = 2 asin(k sn(K - omega t, k^2)), l = 3.5 (Jacobi)."""
    with mpmath.workdps(20):
        k = mpmath.sin(alpha / 2)
        m = k * k
        return 2 * mpmath.asin(k * mpmath.ellipfun("sn", mpmath.ellipk(m) - mpmath.sqrt(mp(G) / mp("3.5")) * t, m=m))


# ----------------------------------------------------------------------------- the tests
def test_the_fixed_problems_print_the_same_for_every_group(docs):
    first = docs[GROUPS[0]]
    keys = [k for k in first.values if k.split(".")[0] in ("p1", "p2", "p4", "p5", "p3a")]
    tables = [k for k in first.tables if k.startswith(("p2", "p4", "p5", "p3a"))]
    for g in GROUPS[1:]:
        assert {k: docs[g].values[k] for k in keys} == {k: first.values[k] for k in keys}
        assert {k: docs[g].tables[k] for k in tables} == {k: first.tables[k] for k in tables}


@pytest.mark.parametrize("students", GROUPS)
def test_the_agm_footnote_prints_only_right_digits(docs, students):
    """3(b)'s footnote: the period of the inputs as written (20 digits), and how many ulps T^ of
    (8) lies from the correctly rounded period of the same doubles."""
    v = docs[students].values
    p = load()
    l_text = p["length.py"].group_length(list(students))[2]
    with mpmath.workdps(DPS):
        assert_right(v["agm.mp"], period_mp(l_text, 4 * mpmath.pi / 5))
        length, alpha = float(l_text), p["problem3.py"].ALPHA
        rounded = float(2 * mpmath.pi * mpmath.sqrt(mp(length) / mp(9.80665)) / mpmath.agm(1, mpmath.cos(mp(alpha) / 2)))
    t_hat = p["agm.py"].t_hat(length, alpha)
    assert_exact(v["agm.diff"], round(abs(t_hat - rounded) / math.ulp(rounded)))


def test_portuguese_prints_the_same_numbers(docs):
    """The pt report's numbers are the en report's, character for character (the digits above)."""
    en = docs[GROUPS[0]]
    pt = sections(GROUPS[0], ["AGM period", "problem 1", "problem 2", "problem 3", "problem 4", "problem 5"], "pt")
    assert pt.tables == en.tables
    numeric = [k for k, x in en.values.items() if re.fullmatch(r"[−0-9.,×#super\[\] %≤]+", x)]
    assert len(numeric) > 140 and {k: pt.values[k] for k in numeric} == {k: en.values[k] for k in numeric}


@pytest.mark.parametrize("students", GROUPS)
def test_problem1_prints_only_right_digits(docs, students):
    v = docs[students].values
    with mpmath.workdps(DPS):
        l_, dl, t_, dt = mp("1.152"), mp("0.003"), mp("2.1536"), mp("2e-4")

        def g(a, b):
            return 4 * mpmath.pi**2 * a / b**2

        gv, dgdl, dgdt = g(l_, t_), 4 * mpmath.pi**2 / t_**2, -8 * mpmath.pi**2 * l_ / t_**3
        absb, rel = abs(dgdl) * dl + abs(dgdt) * dt, dl / l_ + 2 * dt / t_
        gmin, gmax = g(l_ - dl, t_ + dt), g(l_ + dl, t_ - dt)
        worst = max(gmax - gv, gv - gmin)
        bound = max(absb, worst)
        k = int(mpmath.floor(mpmath.log10(gv)))
        n = max(n for n in range(0, 17) if bound <= mpmath.mpf(10) ** (k - n + 1) / 2)
        for key, x in (("p1.l", l_), ("p1.dl", dl), ("p1.T", t_), ("p1.dT", dt), ("p1.digits", n), ("p1.k", k)):
            assert_exact(v[key], x)
        for key, x in (("p1.g", gv), ("p1.dgdl", dgdl), ("p1.dgdT", dgdt), ("p1.gmin", gmin), ("p1.gmax", gmax),
                       ("p1.rell", dl / l_), ("p1.relT", 2 * dt / t_), ("p1.ratio", (dl / l_) / (2 * dt / t_)),
                       ("p1.gtext", gv)):
            assert_right(v[key], x)
        for key, x in (("p1.abs", absb), ("p1.rel", rel), ("p1.worst", worst), ("p1.bound", bound)):
            assert_bound(v[key], x)
        assert_exact(v["p1.half"], mpmath.mpf(10) ** (k - n + 1) / 2)
        assert_exact(v["p1.halfnext"], mpmath.mpf(10) ** (k - n) / 2)
        assert parsed(v["p1.gtext"])[1] == k - n + 1  # g to its n significant digits


@pytest.mark.parametrize("students", GROUPS)
def test_problem2_prints_only_right_digits(docs, students):
    doc = docs[students]
    v = doc.values
    p2 = load()["problem2.py"]
    a, b, _, _ = p2.interval()
    x0 = a if p2.f(a) * p2.d2f(a) > 0 else b  # from the program's x_0, as it starts
    xs = newton_mp(x0)
    rows = doc.tables["p2a"]
    with mpmath.workdps(DPS):
        deg = 180 / mpmath.pi
        root = xs[-1]
        ma, mb = mp(55) / deg, mp(60) / deg
        fa, dfa, d2fa, t0 = f2(ma)
        fb, dfb, d2fb, _ = f2(mb)
        assert_exact(v["p2.l"], mp("0.5"))
        assert_exact(v["p2.target"], mp("1.5"))
        assert_right(v["p2.t0"], t0)
        assert_right(v["p2.t1"], 5 * t0 / 4)
        assert_exact(v["p2.a"], 55)
        assert_exact(v["p2.b"], 60)
        for key, x in (("p2.fa", fa), ("p2.fb", fb), ("p2.d1min", dfa), ("p2.d2min", d2fb), ("p2.d2max", d2fa),
                       ("p2.stepa", abs(fa / dfa)), ("p2.stepb", abs(fb / dfb)), ("p2.width", mb - ma),
                       ("p2.x0", xs[0]), ("p2.x0deg", xs[0] * deg), ("p2.alpha", root), ("p2.deg", root * deg),
                       ("p2.dfz", f2(root)[1])):
            assert_right(v[key], x)
        n = len(rows) - 1
        for k, row in enumerate(rows):
            assert_exact(row[0], k)
            assert_right(row[1], xs[k])
            assert_right(row[2], xs[k] * deg)
            assert_right_or_under(row[3], f2(mp(p2.newton(x0)[0][k]))[0])  # f at the printed iterate, the double
            if k < n:
                assert_right_or_under(row[4], xs[k + 1] - xs[k])
        c = abs(f2(root)[2] / (2 * f2(root)[1]))
        last = abs(xs[n] - xs[n - 1])
        _, delta = p2.newton(x0)
        assert v["p2.last"].startswith(("= ", "≤ ")), v["p2.last"]  # its relation, then the number
        assert_right_or_under(v["p2.last"].removeprefix("= "), last)
        assert_right(v["p2.errest"], c * last**2 + mp(delta))
        assert_right(v["p2.delta"], mp(delta))
        assert_right(v["p2.C"], c)
        d = [abs(x1 - x0_) for x0_, x1 in zip(xs, xs[1:])]
        q = [d[k + 1] / d[k] ** 2 for k in range(n - 1)]
        for k, row in enumerate(doc.tables["p2c"]):
            assert_exact(row[0], k)
            assert_right_or_under(row[1], q[k])
        kmax = int(v["p2.kmax"])
        assert_right(v["p2.qkmax"], q[kmax])
        assert_right(v["p2.qrel"], abs(q[kmax] - c) / c)
        assert_exact(v["p2.qlast"], n - 2)
        assert v["p2.qtol"] == "1%"
        # "the closed form agrees to": its double against x_N's, a difference of two doubles
        closed = 2 * math.asin(2 * math.sqrt(p2.TARGET / p2.T0 - 1))
        assert_bound(v["p2.closed"], abs(mp(closed) - mp(p2.newton(x0)[0][-1])))


@pytest.mark.parametrize("students", GROUPS)
def test_3a_prints_only_right_digits(docs, students):
    rows = docs[students].tables["p3a"]
    with mpmath.workdps(DPS):
        z1, z2, _, _ = taylor_mp("1", mpmath.pi / 4, "0.1", steps=21)
    shown = list(range(4)) + [None] + list(range(18, 22))
    assert docs[students].values["p3a.n"] == "21"
    for i, row in zip(shown, rows):
        if i is not None:
            assert_exact(row[0], Decimal(i) / 10)
            assert_right(row[1], z1[i])
            assert_right(row[2], z2[i])


@pytest.mark.parametrize("students", GROUPS)
def test_3bc_prints_only_right_digits(docs, students):
    v = docs[students].values
    m = problem3_mp(students)
    t = m["T"]
    assert v["p3b.l"] == m["l"]
    assert_right(v["p3b.t_hat"], t)
    assert_right(v["p3d.t_hat"], t)
    with mpmath.workdps(DPS):
        h = mp("0.2")
        assert_exact(v["p3b.tmax"], h * mpmath.ceil(2 * t / h))
        assert_exact(v["p3b.n"], mpmath.ceil(2 * t / h))
        assert_right(v["p3b.search"], 4 * t)
        j, over = m["b"]["j"], m["b"]["over"]
        if j is not None:
            assert_exact(v["p3b.j"], j)
            assert_exact(v["p3b.tj"], j * h)
            assert_exact(v["p3b.tj1"], (j + 1) * h)
            lo, hi = j * h, (j + 1) * h
            assert_right(v["p3b.dist"], lo - t if t < lo else t - hi if t > hi else t - lo)
        else:
            assert "p3b.j" not in v
        if over is not None:
            assert_exact(v["p3b.left"], over * h)
            assert_right(v["p3b.ratio"], over * h / t)
        rows = docs[students].tables["p3c"]
        errors = {}
        for row, h_text in zip(rows, ("0.01", "0.001", "0.0001")):
            c = m["c"][h_text]
            assert_exact(row[0], c["h"])
            assert_exact(row[1], c["j"])
            lo, hi = row[2].strip("[]").split(", ")
            assert_exact(lo, c["j"] * c["h"])
            assert_exact(hi, (c["j"] + 1) * c["h"])
            assert_right(row[3], c["linear"])
            assert_right(row[4], abs(c["linear"] - t))
            assert_right(row[6], c["p0"])
            assert_right(row[7], abs(c["p0"] - t))
            errors[h_text] = (abs(c["linear"] - t), abs(c["p0"] - t), c["h"])
        for row, (a, b) in zip(rows[1:], zip(list(errors.values()), list(errors.values())[1:])):
            assert_right(row[5], mpmath.log(a[0] / b[0]) / mpmath.log(a[2] / b[2]))
            assert_right(row[8], mpmath.log(a[1] / b[1]) / mpmath.log(a[2] / b[2]))
        e = list(errors.values())
        assert_right(v["p3c.first"], mpmath.log(e[0][0] / e[1][0]) / mpmath.log(10))
        assert_right(v["p3c.order"], mpmath.log(e[1][0] / e[2][0]) / mpmath.log(10))
        assert_right(v["p3c.error"], e[2][0])
        assert_right(v["p3c.last"], m["c"]["0.0001"]["linear"])
        assert_exact(v["p3c.h"], mp("1e-4"))


@pytest.mark.parametrize("students", GROUPS)
def test_3d_prints_only_right_digits(docs, students):
    doc = docs[students]
    v = doc.values
    m = problem3_mp(students)
    c = m["c"]["0.001"]
    x, dd, e0, t = c["x"], c["dd"], c["e0"], m["T"]
    p3 = load()["problem3.py"]
    r = p3.period(float(m["l"]), 1e-3, load()["agm.py"].t_hat(float(m["l"]), p3.ALPHA))
    with mpmath.workdps(DPS):
        for k, row in enumerate(doc.tables["p3d"]):
            assert_exact(row[0], k)
            assert_right(row[1], x[k])
            assert_exact(row[2], c["y"][k])
            assert_right_or_under(row[3], dd[k])
        for key, k in (("p3d.x0", 0), ("p3d.x1", 1), ("p3d.x2", 2), ("p3d.z4", 4)):
            assert_right(v[key], x[k])
        for key, k in (("p3d.c0", 0), ("p3d.c1", 1), ("p3d.c2", 2), ("p3d.c3", 3)):
            assert_right(v[key], dd[k])
        assert v["p3d.dd"].startswith(("= ", "≤ ")) and v["p3d.errest_eq"].startswith(("= ", "≤ "))
        assert_right_or_under(v["p3d.dd"].removeprefix("= "), dd[4])  # a value its rounding swamps as ≤
        assert v["p3d.errest_eq"].removeprefix("= ") == v["p3d.errest"]
        assert_exact(v["p3d.t4"], c["y"][4])
        for key, k in (("p3d.j", 0), ("p3d.j0", -1), ("p3d.j3", 2), ("p3d.jm2", -2)):
            assert_exact(v[key], c["j"] + k)
        assert_exact(v["p3d.h"], mp("1e-3"))
        assert_right(v["p3d.value"], c["p0"])
        assert_right(v["p3d.prod"], c["prod"])
        assert_right_or_under(v["p3d.errest"], e0)
        assert_right(v["p3d.taylor"], abs(c["p0"] - t))
        # the rounding level of e(0): half an ulp of each t_k through the divided difference
        rounding = abs(c["prod"]) * mpmath.fsum(
            mp(math.ulp(r["t"][k])) / 2 / abs(mpmath.fprod(x[k] - x[i] for i in range(5) if i != k)) for k in range(5))
        assert_right(v["p3d.rl"], rounding)
        assert_bound(v["p3d.moved"], abs(mp(r["e0"]) - e0))
        assert_bound(v["p3d.movedp"], abs(mp(r["p0"]) - c["p0"]))
        # "the interpolation error, at most about {bound}": a bound of |e(0)| and of the rounding level
        b, _ = parsed(v["p3d.bound"])
        assert b >= max(abs(e0), rounding)
        assert_right_or_under(v["p3d.ratio"], max(abs(e0), rounding) / abs(c["p0"] - t))


@pytest.mark.parametrize("students", GROUPS)
def test_problem4_prints_only_right_digits(docs, students):
    doc = docs[students]
    v = doc.values
    main, alt = problem4_mp(400), problem4_mp(600)
    with mpmath.workdps(DPS):
        alpha = mpmath.pi / 4
        t = period_mp("3.5", alpha)
        assert_right(v["p4.T"], t)
        assert_right(v["p4.omega"], 2 * mpmath.pi / t)
        assert_exact(v["p4.tmax"], mpmath.ceil(t))
        for j, row in zip(range(391, 401), doc.tables["p4a"]):
            assert_exact(row[0], j)
            assert_exact(row[1], main["t"][j])
            assert_right(row[2], main["z1"][j])
        for i, row in enumerate(doc.tables["p4c_matrix"]):
            for k, text in enumerate(row):
                assert_right(text, main["a"][i, k])
        for i, text in enumerate(doc.tables["p4c_rhs"]):
            assert_right(text, main["r"][i])
        for i, row in enumerate(doc.tables["p4d"]):
            assert_right(row[1], main["coef"][i])
            assert_right(row[2], main["svd"][i])
            assert_right(row[3], alt["coef"][i])
        assert_right(v["p4.pivot"], main["pivot"])
        assert_right(v["p4.lmin"], main["eig"][0])
        assert_right(v["p4.lmax"], main["eig"][-1])
        assert_right(v["p4.cond"], main["eig"][-1] / main["eig"][0])
        assert_bound(v["p4.pert"], main["moved"])
        assert_bound(v["p4.shift"], max(abs(main["coef"][i] - main["svd"][i]) for i in range(7)))
        for fit, pre in ((main, "p4."), (alt, "p4.alt.")):
            assert_right(v[pre + "ssd"], mpmath.fsum(r**2 for r in fit["res"]))
            assert_right(v[pre + "maxdev"], abs(fit["res"][fit["jmax"]]))
            assert_exact(v[pre + "argmax"], fit["t"][fit["jmax"]])
        for fit, pre in ((main, "p4."), (alt, "p4.alt.")):
            assert_right(v[pre + "exactdev"], fit["exactdev"])
        assert_right(v["p4.exactat"], main["exactat"])
        assert_right(v["p4.taylor"], main["taylor"])


@pytest.mark.parametrize("students", GROUPS)
def test_problem5_prints_only_right_digits(docs, students):
    doc = docs[students]
    v = doc.values
    t, periods, sub = problem5_mp()
    with mpmath.workdps(DPS):
        assert_right(v["p5.t_hat"], t)
        assert_right(v["p5.q1"], periods[1])
        assert_right(v["p5.e1"], abs(periods[1] - t))
        assert_right(v["p5.s10"], periods[10])
        assert_right(v["p5.e10"], abs(periods[10] - t))
        err = {n: abs(p - t) for n, p in periods.items()}
        for row in doc.tables["p5d"]:
            n = int(row[0])
            assert_right(row[1], periods[n])
            assert_right(row[2], err[n])
            assert_right(row[3], mpmath.log10(err[n // 10] / err[n]))
            assert_right(row[4], sub[n])
            if row[5].startswith("≤ "):  # marked as rounding: at most the floor, whose bound it prints
                assert_bound(row[5][2:], 64 * mpmath.mpf(2) ** -52 * mp(float(v["p5.t_hat"])))
                assert abs(sub[n] - t) <= 64 * mpmath.mpf(2) ** -52 * t
            else:
                assert_right(row[5], abs(sub[n] - t))
        assert_right(v["p5.rate"], mpmath.log10(err[10**4] / err[10**5]))
        assert_right(v["p5.elast"], err[10**5])
        assert_exact(v["p5.nlast"], 10**5)
        assert_right(v["p5.floor"], 64 * mpmath.mpf(2) ** -52 * t)
        assert_right(v["p5.sub10"], abs(sub[10] - t))


@pytest.mark.parametrize("students", GROUPS[:1])
def test_the_check_can_fail(docs, students):
    """One more digit than the error allows is caught (c4 of 3(d) printed to 10 digits)."""
    from pendulab.report.markup import num

    m = problem3_mp(students)
    p3 = load()["problem3.py"]
    r = p3.period(float(m["l"]), 1e-3, load()["agm.py"].t_hat(float(m["l"]), p3.ALPHA))
    with pytest.raises(AssertionError):
        assert_right(num(r["coef"][4], 10), m["c"]["0.001"]["dd"][4])
    with pytest.raises(AssertionError):  # a bound rounded down is caught
        assert_bound("0.02736", mpmath.mpf("0.027362"))
    with pytest.raises(AssertionError):  # a mark of rounding noise below the value's size is caught
        assert_right_or_under("≤ 1 × 10#super[−15]", mpmath.mpf("-1.2e-15"))


def test_an_untrusted_return_prints_only_right_digits():
    """3(b)'s untrusted sentence (a sum of 1115, l = 1.4953487812): the engine's estimate p(0)
    of the h = 0.2 return and how far it is off the period, against (3) and the inverse cubic
    in mpmath; more than a quarter period, as the sentence says."""
    v = sections((1115,), ["problem 3"]).values
    assert "p3b.cubic" in v, v.get("p3b.trust")  # the sentence of an estimate off the period
    with mpmath.workdps(DPS):
        alpha = 4 * mpmath.pi / 5
    t = period_mp(v["p3b.l"], alpha)
    _, z2, j, _ = taylor_mp(v["p3b.l"], alpha, "0.2", steps=int(4 * t / mp("0.2")) + 1, stop=True)
    with mpmath.workdps(DPS):
        h = mp("0.2")
        nodes = [j - 1, j, j + 1, j + 2, j - 2]
        _, p0, _ = cubic_mp([z2[k] for k in nodes], [k * h for k in nodes])
        off_by = abs(p0 - t) / t
        assert_exact(v["p3b.j"], j)
        assert_right(v["p3b.cubic"], p0)
        assert v["p3b.off"].endswith("%") and off_by > 0.25
        assert_right(v["p3b.off"][:-1], 100 * off_by)
