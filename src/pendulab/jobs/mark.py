"""Marking a class: every question keyed from the printed programs, with the answers every
correct method reaches, and each group's hand-in marked against them.

The key of each question is what the coursework's own programs (``programs/``, run as the
report runs them, :func:`pendulab.jobs.coursework.load`) print. The freedoms the coursework
leaves are run, not guessed: Newton from every start of a grid on the convergence interval
and stopped at the program's rule or a step earlier (2); the recursion (3) with its terms
grouped otherwise (3(a)); every 4-point table that holds the sign change and every fifth
node beside it (3(d)); the estimators of the period from a bracket (3(c)); ``t_max`` as
``ceil(T^)`` or the original's ``Y_0 .. Y_600`` (4); other solvers and rounding rules of the
rounded normal equations (4); other summations and the integrand's plain form (5). A
question accepts a value between the lowest and highest alternative (``range``) or one of
the alternatives (``choice``), widened by its ``slack`` (the rounding the alternatives do
not cover) and by half a unit of the last digit the student wrote.

Nothing here prints or reads a file but :func:`read_answers` and :func:`read_scheme`; the
words are the catalogues' ``mark.*`` (:mod:`pendulab.report.mark`).
"""
from __future__ import annotations

import csv
import functools
import io
import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from decimal import ROUND_HALF_EVEN, Decimal, InvalidOperation
from typing import Any, Literal

from ..core import inputs
from ..core.errors import InputError, NumericalError
from ..numerics.results import Result
from . import coursework
from .key import MAX_FILE_BYTES, Entry, duplicates, repeated_students

#: ``range``: any value between the lowest and highest alternative (a continuum of
#: freedoms, such as Newton's start); ``choice``: one of the alternatives; ``at_least``:
#: any value from ``low`` to ``high``, the alternatives naming its ends; ``integer`` and
#: ``text``: one of the alternatives exactly.
Kind = Literal["range", "choice", "at_least", "integer", "text"]

#: 3(c): the steps h = 10^-j, j = 2, 3, 4, as the answers' columns name them.
STEP_TAGS = {1e-2: "h1e-2", 1e-3: "h1e-3", 1e-4: "h1e-4"}
#: 3(a): the rows of Figure 3 that the coursework prints, by index j (t_j = j/10).
FIGURE3_ROWS = (1, 2, 3, 18, 19, 20, 21)
#: 2: starts on this many points of the convergence interval [a, b] (its ends included).
NEWTON_STARTS = 41
#: 4(d)(i)-(ii), 3(d): the yes/no answers read in either language.
YES, NO = ("yes", "sim", "true", "1"), ("no", "não", "nao", "false", "0")


@dataclass(frozen=True)
class Alternative:
    """One correct way to answer: ``method`` (a code, the catalogues' ``mark.method.*``),
    ``detail`` (its parameter as data: a start in degrees, a table's nodes) and the value."""

    method: str
    detail: str
    value: Any

    def to_dict(self) -> dict[str, Any]:
        return {"method": self.method, "detail": self.detail, "value": self.value}


@dataclass(frozen=True, eq=False)
class Question(Result):
    """One keyed answer: its column in the answers file, the coursework's part, whether it
    is the same for the whole ``class`` or the ``group``'s own, the key (the printed
    program's value), what is accepted and why (``freedom``: the catalogues' ``mark.freedom.*``).
    """

    column: str
    part: str
    scope: Literal["class", "group"]
    kind: Kind
    key: Any
    alternatives: tuple[Alternative, ...]
    freedom: str
    slack: float = 0.0
    relative_slack: float = 0.0
    signless: bool = False
    min_digits: int = 1
    low: float | None = None
    high: float | None = None
    #: The decimals the coursework prescribes (4(c): 6): an answer must equal the key to them,
    #: whatever digits it shows (trailing zeros dropped are the same number).
    decimals: int | None = None
    #: ``"untrusted"`` where the key is the program's result but the engine does not trust it
    #: (3(b)'s h = 0.2 return near the separatrix, as the report and key say); else ``""``.
    status: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"column": self.column, "part": self.part, "scope": self.scope, "kind": self.kind,
                "key": self.key, "key_text": key_text(self), "low": self.low, "high": self.high,
                "slack": self.slack, "decimals": self.decimals,
                "relative_slack": self.relative_slack, "signless": self.signless,
                "min_digits": self.min_digits, "freedom": self.freedom, "status": self.status,
                "alternatives": [a.to_dict() for a in self.alternatives]}


def _ulps(x: float, n: float) -> float:
    return n * math.ulp(abs(x)) if math.isfinite(x) else 0.0


def _range(column: str, part: str, scope: Literal["class", "group"], key: float, alts: list[Alternative],
           freedom: str, slack: float = 0.0, **kw: Any) -> Question:
    values = [float(a.value) for a in alts]
    return Question(column, part, scope, "range", key, tuple(alts), freedom, slack=slack,
                    low=min(values), high=max(values), **kw)


def _choice(column: str, part: str, scope: Literal["class", "group"], key: Any, alts: list[Alternative],
            freedom: str, kind: Kind = "choice", **kw: Any) -> Question:
    return Question(column, part, scope, kind, key, tuple(alts), freedom, **kw)


#: The report's digit policy (:data:`pendulab.core.digits.POLICY`) for each question's key:
#: its printed digits, the same in the key, the marked sheet and the report.
PRINTED = (("1b_g", "p1.g"), ("2_alpha_deg", "p2.iterate"), ("2_x0_deg", "p2.iterate"), ("2_q", "p2.quotient"),
           ("2_constant", "p2.constant"), ("2_error_estimate", "p2.error_estimate"), ("3a_", "p3.state"),
           ("3b_t_hat", "t_hat"), ("3c_T", "estimate"), ("3c_error", "error"), ("3d_p0", "estimate"),
           ("3d_divided", "p3.error_estimate"), ("3d_c", "p3.coefficient"), ("3d_z2", "p3.state"),
           ("3d_error_estimate", "p3.error_estimate"), ("4a_z1", "p3.state"),
           ("4c_", "p4.normal"), ("4d_ssd", "p4.deviation"), ("4d_max", "p4.deviation"), ("4d_", "p4.coefficient"),
           ("5d_error", "error"), ("5", "p5.estimate"))


def key_text(q: Question) -> str:
    """The key as printed: in the report's form for its quantity (the digits its rounding
    allows, for an ``error`` form: its ``slack`` and the alternatives' spread), else as is."""
    from ..core import digits

    if isinstance(q.key, bool) or not isinstance(q.key, float):
        return str(q.key)
    quantity = next((name for prefix, name in PRINTED if q.column.startswith(prefix)), None)
    if quantity is None:
        return repr(q.key)
    spread = 0.0 if q.low is None or q.high is None or q.kind != "range" else q.high - q.low
    error = max(q.slack, spread if quantity not in ("p2.iterate",) else 0.0, math.ulp(q.key))
    text = digits.shown(quantity, q.key, error)
    if q.key != 0 and (text.startswith("<=") or not any(ch in "123456789" for ch in digits.split(text)[0])):
        # the error allows no digit in the places shown (or swamps the key, "<= b"): its first digit, with its sign
        return digits.scientific(q.key, 1)
    return text


# --------------------------------------------------------------------------- the class's questions
def _problem1(p: dict) -> list[Question]:
    r = p["problem1.py"].solve()
    return [
        _choice("1b_g", "1(b)", "class", r["g"], [Alternative("program", "", r["g"])], "one_formula",
                slack=_ulps(r["g"], 4), min_digits=r["digits"]),
        _choice("1b_digits", "1(b)", "class", r["digits"], [Alternative("program", "", r["digits"])],
                "integer", kind="integer"),
    ]


def _problem2(p: dict) -> list[Question]:
    p2 = p["problem2.py"]
    a, b, _, _ = p2.interval()
    x0 = a if p2.f(a) * p2.d2f(a) > 0 else b  # the program's start (Fourier)
    starts = [x0] + [a + (b - a) * i / (NEWTON_STARTS - 1) for i in range(NEWTON_STARTS)]  # the program's first
    roots, q0, q1, kmax, est = [], [], [], [], []
    slack_q = [0.0, 0.0]
    key: dict[str, Any] = {}
    for s in starts:
        xs, delta = p2.newton(s)
        q, rho, k = p2.quotients(xs, delta)
        deg = f"{math.degrees(s):.4f}"
        c = abs(p2.d2f(xs[-1]) / (2 * p2.df(xs[-1])))
        roots.append(Alternative("newton_start", deg, math.degrees(xs[-1])))
        roots.append(Alternative("newton_stop_early", deg, math.degrees(xs[-2])))
        q0.append(Alternative("newton_start", deg, q[0]))
        q1.append(Alternative("newton_start", deg, q[1]))
        slack_q = [max(slack_q[i], rho[i] * q[i]) for i in (0, 1)]
        kmax.append(k)
        est.append(Alternative("estimate_quadratic", deg, c * (xs[-1] - xs[-2]) ** 2 + delta))
        est.append(Alternative("estimate_last_correction", deg, abs(xs[-1] - xs[-2])))
        if s == x0:
            key = {"alpha": math.degrees(xs[-1]), "q0": q[0], "q1": q[1], "k_max": k, "c": c,
                   "estimate": c * (xs[-1] - xs[-2]) ** 2 + delta}
    interval = [Alternative("interval_end", "a", math.degrees(a)), Alternative("interval_end", "b", math.degrees(b))]
    constant = key["c"]
    return [
        _range("2_x0_deg", "2(a)", "class", math.degrees(x0), interval, "newton_interval", min_digits=2),
        _range("2_alpha_deg", "2(a)", "class", key["alpha"], roots, "newton_start", slack=_ulps(key["alpha"], 8),
               min_digits=10),
        _range("2_q0", "2(c)", "class", key["q0"], q0, "newton_start", slack=slack_q[0], min_digits=3),
        _range("2_q1", "2(c)", "class", key["q1"], q1, "newton_start", slack=slack_q[1], min_digits=3),
        _choice("2_k_max", "2(c)", "class", key["k_max"],
                [Alternative("newton_start", "", k) for k in sorted(set(kmax))], "q_rounding", kind="integer"),
        _choice("2_constant", "2(c)", "class", constant, [Alternative("program", "", constant)], "one_formula",
                slack=_ulps(constant, 16), min_digits=4),
        _range("2_error_estimate", "2(b)", "class", key["estimate"], est, "error_estimate", signless=True),
    ]


def _taylor_regrouped(length: float, alpha: float, h: float, t_max: float, g: float = 9.80665):
    """(3) with its terms grouped otherwise: z1 + h (z2 + (h/2) c sin z1), z2 + h c (sin z1 +
    (h/2) z2 cos z1). The same method; a student may write it so."""
    c = -g / length
    n = round(t_max / h)
    z1, z2 = [alpha], [0.0]
    for i in range(n):
        s = math.sin(z1[i])
        z1.append(z1[i] + h * (z2[i] + h / 2 * c * s))
        z2.append(z2[i] + h * c * (s + h / 2 * z2[i] * math.cos(z1[i])))
    return z1, z2


def _problem3a(p: dict) -> list[Question]:
    _t, z1, z2 = p["taylor.py"].taylor(1.0, math.pi / 4, 0.1, 2.1)
    r1, r2 = _taylor_regrouped(1.0, math.pi / 4, 0.1, 2.1)
    out = []
    for j in FIGURE3_ROWS:
        for name, ours, theirs in (("z1", z1[j], r1[j]), ("z2", z2[j], r2[j])):
            alts = [Alternative("program", "", ours), Alternative("regrouped", "", theirs)]
            out.append(_range(f"3a_{name}_{j}", "3(a)", "class", ours, alts, "regrouped",
                              slack=_ulps(ours, 8), min_digits=10))
    return out


def _normal_variants(p4, t, y):
    """4(c)-(d): the rounded normal equations solved as the program does (Cholesky), by
    numpy.linalg.solve, and rounded half to even instead of half away from zero."""
    import numpy as np

    a, r, _, coef, res = p4.fit(t, y)
    yield "cholesky", a, r, coef, res
    yield "solver_numpy", a, r, np.linalg.solve(a, r), None
    phi = p4.basis(t)
    m = phi.T @ phi
    m = 0.5 * (m + m.T)
    q = Decimal("1e-6")
    even = np.vectorize(lambda v: float(Decimal(v).quantize(q, ROUND_HALF_EVEN)))
    a2, r2 = even(m), even(phi.T @ np.asarray(y))
    yield "half_even", a2, r2, np.linalg.solve(a2, r2), None


def _problem4(p: dict) -> list[Question]:
    import numpy as np

    p4 = p["problem4.py"]
    t_hat = p["agm.py"].t_hat(p4.L, p4.ALPHA)
    key_t_max = math.ceil(t_hat)
    cols: dict[str, list[Alternative]] = {}
    key: dict[str, Any] = {}
    for t_max, method in ((key_t_max, "t_max_ceil"), (6, "t_max_y600")):
        t, z1, _ = p4.taylor(p4.L, p4.ALPHA, p4.H, t_max)
        detail = f"{t_max}"
        vals: dict[str, Any] = {"4a_t_max": t_max}
        for k in range(1, 11):
            vals[f"4a_z1_{k}"] = z1[len(t) - 11 + k]
        for solver, a, r, coef, res in _normal_variants(p4, t, z1):
            tag = f"{t_max}"
            here = dict(vals) if solver == "cholesky" else {}
            for i in range(7):
                here[f"4c_A{i + 1}{i + 1}"] = float(a[i, i])
                here[f"4c_r{i + 1}"] = float(r[i])
            for name, c in zip(p4.NAMES, coef):
                here[f"4d_{name}"] = float(c)
            res = np.asarray(z1) - p4.basis(t) @ coef if res is None else res
            here["4d_ssd"] = math.fsum(res**2)
            here["4d_max_deviation"] = float(np.max(np.abs(res)))
            here["4d_below"] = "yes" if np.max(np.abs(res)) < p4.TOL else "no"
            for col, v in here.items():
                cols.setdefault(col, []).append(Alternative(method if solver == "cholesky" else solver,
                                                            detail if solver == "cholesky" else tag, v))
                if t_max == key_t_max and solver == "cholesky":
                    key[col] = v
    out = []
    for col, alts in cols.items():
        # the same t_max's variants differ by rounding only: each is a choice, widened by their spread
        if col in ("4a_t_max",):
            out.append(_choice(col, "4(a)", "class", key[col], alts, "t_max_rule", kind="integer"))
        elif col == "4d_below":
            out.append(_choice(col, "4(d)", "class", key[col], alts, "t_max_rule", kind="text"))
        else:
            spread = max(abs(float(x.value) - float(y.value)) for x in alts for y in alts
                         if x.detail.split(",")[0] == y.detail.split(",")[0])
            part = col[:2].replace("4a", "4(a)").replace("4c", "4(c)").replace("4d", "4(d)")
            digits = 2 if col == "4d_max_deviation" else 4 if col == "4d_ssd" else 1 if col.startswith("4c_") else 8
            out.append(_choice(col, part, "class", key[col], alts, "normal_rounding" if col[:2] in ("4c", "4d")
                               else "t_max_rule", slack=spread + _ulps(key[col], 8), min_digits=digits,
                               decimals=6 if col.startswith("4c_") else None))
    return out


def _problem5(p: dict) -> list[Question]:
    import numpy as np

    p5 = p["problem5.py"]
    exact = p["agm.py"].t_hat(p5.L, p5.ALPHA)
    factor = 4 * math.sqrt(p5.L / (2 * p["agm.py"].G))

    def fsum_rule(f, a, b, n):
        h = (b - a) / n
        m = a + (np.arange(n) + 0.5) * h
        d = math.sqrt(3 / 5) * h / 2
        return h / 18 * math.fsum(5 * f(m - d) + 8 * f(m) + 5 * f(m + d))

    def plain_integrand(theta):  # (1) as written: cos(theta) - cos(alpha)
        return 1 / np.sqrt(np.cos(theta) - np.cos(p5.ALPHA))

    variants = {
        "program": lambda n: p5.period(n),
        "sum_fsum": lambda n: factor * fsum_rule(p5.integrand, 0.0, p5.ALPHA, n),
        "integrand_cos": lambda n: factor * p5.gauss3(plain_integrand, 0.0, p5.ALPHA, n),
    }
    out = []
    for n, col, part in [(1, "5b_single", "5(b)"), (10, "5c_S10", "5(c)")] + [
            (10**k, f"5d_S_{10**k}", "5(d)") for k in range(1, 6)]:
        vals = {m: f(n) for m, f in variants.items()}
        alts = [Alternative(m, "", v) for m, v in vals.items()]
        out.append(_range(col, part, "class", vals["program"], alts, "summation",
                          slack=_ulps(vals["program"], 8), min_digits=10))
        if part == "5(d)":
            errs = [Alternative(m, "", abs(v - exact)) for m, v in vals.items()]
            out.append(_range(f"5d_error_{n}", part, "class", abs(vals["program"] - exact), errs, "summation",
                              slack=_ulps(exact, 8), signless=True, min_digits=2))
    return out


@functools.cache
def class_questions() -> tuple[Question, ...]:
    """The questions whose answers are the same for every group (1, 2, 3(a), 4, 5)."""
    p = coursework.load()
    return tuple(_problem1(p) + _problem2(p) + _problem3a(p) + _problem4(p) + _problem5(p))


# --------------------------------------------------------------------------- a group's questions
def _cubic_tables(p3, t: dict[int, float], z2: dict[int, float], j: int):
    """3(d): every 4-point table of consecutive nodes holding the sign change (j, j+1) and
    every fifth node beside it: (the table's nodes, the fifth node's, whether it is the first
    fifth node of this table, its index, the program's result)."""
    for s in (-2, -1, 0):
        table = [j + s + k for k in range(4)]
        for fifth in (j + s - 1, j + s + 4):
            nodes = table + [fifth]
            r = p3.inverse_cubic([z2[k] for k in nodes], [t[k] for k in nodes])
            yield _offsets(table[0], table[-1], j), _offset(fifth, j), fifth == j + s - 1, fifth, r


def _offset(k: int, j: int) -> str:
    return "j" if k == j else f"j{k - j:+d}"


def _offsets(first: int, last: int, j: int) -> str:
    return f"{_offset(first, j)}..{_offset(last, j)}"


def group_questions(students: Sequence[int]) -> tuple[Question, ...]:
    """The questions of problem 3(b)-(d), whose answers depend on the group's length."""
    return _group_questions(tuple(students))


def _sign_change(z1, z2) -> int | None:
    """problem3.py's ``sign_change`` on arrays: the first j with z2_j > 0 >= z2_(j+1) and
    z1_(j+1) > 0, None where |z1| reaches pi at or before j+1 (over the top) or never."""
    import numpy as np

    change = np.flatnonzero((z2[:-1] > 0) & (z2[1:] <= 0) & (z1[1:] > 0))
    over = np.flatnonzero(np.abs(z1[1:]) >= math.pi)
    if not len(change) or (len(over) and over[0] <= change[0]):
        return None
    return int(change[0])


@functools.cache
def _group_questions(students: tuple[int, ...]) -> tuple[Question, ...]:
    from ..core.cases import PROBLEM3_PLOT_STEP
    from ..numerics.simulation import simulate
    from .problems import plot_outcome

    p = coursework.load()
    p3, agm = p["problem3.py"], p["agm.py"]
    total, digits, l_text = p["length.py"].group_length(list(students))
    length = float(l_text)
    exact = agm.t_hat(length, p3.ALPHA)
    out = [
        _choice("3b_sum", "3(b)", "group", total, [Alternative("program", "", total)], "integer", kind="integer"),
        _choice("3b_digits", "3(b)", "group", "".join(map(str, digits)), [Alternative("program", "", "".join(map(str, digits)))],
                "length_rule", kind="text"),
        _choice("3b_length", "3(b)", "group", l_text, [Alternative("program", "", float(l_text))], "length_rule",
                min_digits=len(l_text.replace(".", "").lstrip("0"))),
    ]
    # (8) with the geometric mean as sqrt(a) sqrt(b): the same 7 iterations, other roundings
    a, b = 1.0, math.cos(p3.ALPHA / 2)
    for _ in range(7):
        a, b = (a + b) / 2, math.sqrt(a) * math.sqrt(b)
    other = 2 * math.pi * math.sqrt(length / agm.G) / ((a + b) / 2)
    out.append(_range("3b_t_hat", "3(b)", "group", exact, [Alternative("program", "", exact),
                                                           Alternative("agm_sqrt_product", "", other)],
                      "agm_order", slack=_ulps(exact, 8), min_digits=10))
    t_max, j, over, t = p3.plot_t_max(length, exact)
    outcome = "returns" if j is not None else "leaves" if over is not None else "none"
    # The engine's word on that return, as the key's plot.status: an "untrusted" return (a sum of
    # 1115) is still the program's answer, and a student's is marked against it, with the status.
    status = "untrusted" if plot_outcome(length, p3.ALPHA, PROBLEM3_PLOT_STEP, exact)[4] == "untrusted" else ""
    out.append(_choice("3b_outcome", "3(b)", "group", outcome, [Alternative("program", "", outcome)],
                       "h02_outcome", kind="text", status=status))
    search = p3.SEARCH * exact
    event = t[j + 1] if j is not None else t[over] if over is not None else search
    out.append(Question("3b_t_max", "3(b)", "group", "at_least", round(t_max, 9),  # as the program prints it
                        (Alternative("event_seen", "", event), Alternative("search_limit", "", search)),
                        "t_max_shows", low=min(event, t_max), high=search, min_digits=1))
    if j is not None:
        for col, v in (("3b_bracket_lo", t[j]), ("3b_bracket_hi", t[j + 1])):
            out.append(_choice(col, "3(b)", "group", v, [Alternative("program", "", v)], "grid_times",
                               slack=_ulps(v, 4), status=status))
    cubic_part: list[Question] = []
    for h, tag in STEP_TAGS.items():
        # the lists of taylor.py's (3), by the engine's taylor2 kernel: the same doubles, bit for
        # bit (tests/test_mark.py), 5 to 10 times faster at h = 1e-4
        run = simulate(length, p3.ALPHA, h, 1.5 * exact + 8 * h)
        found = _sign_change(run.theta, run.omega)
        if found is None:
            raise NumericalError(f"no return to P within 1.5 T^ at h = {h:g}")
        # the nodes around the change, as lists of floats: the program's j is an index of them
        lo = max(found - 4, 0)
        window = slice(lo, found + 6)
        tt = dict(enumerate(run.t[window].tolist(), start=lo))
        z2 = dict(enumerate(run.omega[window].tolist(), start=lo))
        jj = found
        linear = tt[jj] + h * z2[jj] / (z2[jj] - z2[jj + 1])
        cubic = p3.inverse_cubic([z2[k] for k in (jj - 1, jj, jj + 1, jj + 2, jj - 2)],
                                 [tt[k] for k in (jj - 1, jj, jj + 1, jj + 2, jj - 2)])["p0"]
        ests = {"bracket_lo": tt[jj], "bracket_hi": tt[jj + 1], "linear": linear, "cubic": cubic}
        part = "3(c)"
        out.append(_choice(f"3c_j_{tag}", part, "group", jj, [Alternative("program", "", jj)], "integer",
                           kind="integer"))
        out.append(_choice(f"3c_T_{tag}", part, "group", linear, [Alternative(m, "", v) for m, v in ests.items()],
                           "estimator", slack=_ulps(exact, 64), min_digits=6))
        out.append(_choice(f"3c_error_{tag}", part, "group", abs(linear - exact),
                           [Alternative(m, "", abs(v - exact)) for m, v in ests.items()], "estimator",
                           slack=_ulps(exact, 64), signless=True, min_digits=2))
        if h == 1e-3:
            p0s, fifths, dds, e0s, levels, negl = [], [], [], [], [], []
            tables: dict[str, list[Alternative]] = {}
            coef_slack: dict[int, float] = {}
            key: dict[str, Any] = {}
            for table, fifth_label, first, fifth, r in _cubic_tables(p3, tt, z2, jj):
                detail = f"{table}, {fifth_label}"
                if first:  # p(0), the table and p's coefficients are the table's, whatever the fifth node
                    p0s.append(Alternative("table", table, r["p0"]))
                    start = jj + {"j-2": -2, "j-1": -1, "j": 0}[table.split("..")[0]]
                    nodes = [start + k for k in range(4)]
                    for k, node in enumerate(nodes):
                        tables.setdefault(f"3d_t{k}", []).append(Alternative("table", table, tt[node]))
                        tables.setdefault(f"3d_z2_{k}", []).append(Alternative("table", table, z2[node]))
                        tables.setdefault(f"3d_c{k}", []).append(Alternative("table", table, r["coef"][k]))
                        # c_k = t[x_0..x_k]: each t_i's half ulp over the products of its differences
                        bound = 4 * math.fsum(math.ulp(tt[nodes[i]]) / 2 / abs(math.prod(
                            z2[nodes[i]] - z2[nodes[m]] for m in range(k + 1) if m != i)) for i in range(k + 1))
                        coef_slack[k] = max(coef_slack.get(k, 0.0), bound)
                fifths.append(Alternative("table_fifth", detail, tt[fifth]))
                dds.append(Alternative("table_fifth", detail, r["dd4"]))
                e0s.append(Alternative("table_fifth", detail, r["e0"]))
                levels.append(Alternative("table_fifth", detail, r["rounding"]))
                small = max(abs(r["e0"]), r["rounding"]) < p3.NEGLIGIBLE * abs(r["p0"] - exact)
                negl.append(Alternative("table_fifth", detail, "yes" if small else "no"))
                if (table, fifth_label) == ("j-1..j+2", "j-2"):  # the program's own choice
                    key = {"p0": r["p0"], "fifth": tt[fifth], "dd": r["dd4"], "e0": r["e0"],
                           "rounding": r["rounding"], "negligible": "yes" if small else "no"}
            level = max(float(x.value) for x in levels)
            cubic_part += [
                *[_choice(col, "3(d)", "group", next(float(a.value) for a in alts if a.detail == "j-1..j+2"), alts,
                          "tables", slack=(coef_slack[int(col[-1])] if col.startswith("3d_c")
                                           else _ulps(float(alts[0].value), 4)),
                          min_digits=3 if col.startswith("3d_c") else 10)
                  for col, alts in sorted(tables.items(), key=lambda ca: (ca[0][:4], ca[0][-1]))],
                _choice("3d_p0", "3(d)", "group", key["p0"], p0s, "tables", slack=_ulps(exact, 64), min_digits=10),
                _choice("3d_fifth_t", "3(d)", "group", key["fifth"], fifths, "fifth_node", slack=_ulps(exact, 4)),
                _choice("3d_divided_difference", "3(d)", "group", key["dd"], dds, "fifth_node",
                        slack=level / max(abs(key["e0"]), 1e-300) * abs(key["dd"]), min_digits=3),
                _choice("3d_error_estimate", "3(d)", "group", key["e0"], e0s, "fifth_node", slack=level,
                        signless=True, min_digits=2),
                _choice("3d_rounding_level", "3(d)", "group", key["rounding"], levels, "rounding_level",
                        relative_slack=1.0),
                _choice("3d_negligible", "3(d)", "group", key["negligible"], negl, "fifth_node", kind="text"),
            ]
    return tuple(out + cubic_part)


def columns(students: Sequence[int] = (262, 407, 634)) -> list[str]:
    """The answers file's question columns, in their order (the class's, then the group's)."""
    return [q.column for q in class_questions()] + [q.column for q in group_questions(students)]


# --------------------------------------------------------------------------- the marking scheme
@dataclass(frozen=True)
class Scheme:
    """Points per question and the fewest significant digits an answer must show
    (``min_digits``; a question's own, derived, where the scheme says nothing)."""

    points: dict[str, float] = field(default_factory=dict)
    min_digits: dict[str, int] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {"points": dict(self.points), "min_digits": dict(self.min_digits)}


def default_scheme() -> Scheme:
    """One point per question; the digits each question's key derives (editable as JSON)."""
    qs = list(class_questions()) + list(group_questions((262, 407, 634)))
    return Scheme(dict.fromkeys(columns(), 1.0), {q.column: q.min_digits for q in qs})


def parse_scheme(text: str, source: str = "scheme") -> Scheme:
    """A scheme file: JSON ``{"points": {column: number >= 0}, "min_digits": {column: 1..17}}``;
    a column it leaves out keeps its default."""
    known = set(columns())
    try:
        d = json.loads(text)
    except ValueError as exc:
        raise InputError("scheme", source, f"a JSON document ({exc})") from None
    if not isinstance(d, dict) or set(d) - {"points", "min_digits"}:
        raise InputError("scheme", source, 'a JSON object with "points" and "min_digits"')
    base = default_scheme()
    points, digits = dict(base.points), dict(base.min_digits)
    for name, table, ok, allowed in (("points", points, lambda v: isinstance(v, (int, float)) and not
                                      isinstance(v, bool) and math.isfinite(v) and v >= 0, "a number >= 0"),
                                     ("min_digits", digits, lambda v: isinstance(v, int) and not
                                      isinstance(v, bool) and 1 <= v <= 17, "an integer 1..17")):
        given = d.get(name, {})
        if not isinstance(given, dict):
            raise InputError("scheme", f"{source}: {name}", "an object {column: value}")
        for col, v in given.items():
            if col not in known:
                raise InputError("scheme", f"{source}: {name}.{inputs.shown(col)}", "a column of the answers file "
                                 "(pendulab key --template)")
            if not ok(v):
                raise InputError("scheme", f"{source}: {name}.{col} = {inputs.shown(str(v))}", allowed)
            table[col] = v
    return Scheme(points, digits)


def _read_text(path: str | os.PathLike, name: str) -> str:
    shown = inputs.shown(str(path))
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise InputError(name, shown, f"a readable file ({exc.strerror})") from None
    if len(data) > MAX_FILE_BYTES:
        raise InputError(name, shown, f"a file of at most {MAX_FILE_BYTES:.0e} bytes")
    try:
        return data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError:
        raise InputError(name, shown, "a UTF-8 text file") from None


def read_scheme(path: str | os.PathLike) -> Scheme:
    return parse_scheme(_read_text(path, "scheme"), str(path))


# --------------------------------------------------------------------------- the answers
@dataclass(frozen=True)
class AnswerRow:
    """One group's hand-in: its student numbers, the file's row and each column's text."""

    students: tuple[int, ...]
    row: int
    answers: dict[str, str]


def parse_answers(text: str, source: str = "answers") -> list[AnswerRow]:
    """The answers CSV (``pendulab key --template``): a header row with ``students`` and the
    question columns, one row per group, ``,`` or ``;`` between cells (decimal commas with
    ``;``). Unknown columns and a group answered twice are refused."""
    text = text.removeprefix("\ufeff")
    first = text.split("\n", 1)[0]
    delimiter = ";" if first.count(";") > first.count(",") else ","
    rows = list(csv.reader(io.StringIO(text), delimiter=delimiter))
    if not rows or "students" not in [c.strip() for c in rows[0]]:
        raise InputError("answers", source, "a CSV whose header row names the column students "
                         "(pendulab key --template writes one)")
    header = [c.strip() for c in rows[0]]
    known = set(columns()) | {"line", "students", "names"}
    for c in header:
        if c and c not in known:
            raise InputError("answers", f"{source}: column {inputs.shown(c)}",
                             "the columns of pendulab key --template")
    out: list[AnswerRow] = []
    seen: dict[tuple[int, ...], int] = {}
    for number, row in enumerate(rows[1:], start=2):
        if not any(c.strip() for c in row):
            continue
        cells = dict(zip(header, (c.strip() for c in row)))
        try:
            students = inputs.students("answers", cells.get("students", "").replace(";", ","))
        except InputError as exc:
            raise InputError("answers", f"{source} row {number}: students = {inputs.shown(cells.get('students', ''))}",
                             exc.allowed) from None
        key = tuple(sorted(students))
        if key in seen:
            raise InputError("answers", f"{source} row {number}: {' '.join(map(str, students))}",
                             f"one row per group (row {seen[key]} answers it)")
        seen[key] = number
        out.append(AnswerRow(students, number, {c: v for c, v in cells.items() if c in known - {"line", "students",
                                                                                                 "names"}}))
    return out


def read_answers(path: str | os.PathLike) -> list[AnswerRow]:
    return parse_answers(_read_text(path, "answers"), str(path))


@dataclass(frozen=True)
class Number:
    """A number as a student wrote it: its value, significant digits and half a unit of its last digit."""

    value: float
    digits: int
    half_unit: float


def read_number(text: str) -> Number | None:
    """``2.0523``, ``2,0523`` (a decimal comma), ``1.2e-5``, ``1,2E-05``, ``-3``; None if not a number."""
    s = text.strip().replace(" ", "").replace("−", "-")
    if "," in s and "." not in s:
        s = s.replace(",", ".")
    try:
        d = Decimal(s)
    except InvalidOperation:
        return None
    if not d.is_finite():
        return None
    _sign, digits, exp = d.as_tuple()
    assert isinstance(exp, int)
    shown = "".join(map(str, digits)).lstrip("0") or "0"
    return Number(float(d), len(shown), 0.5 * 10.0**exp)


def _digits(x: float) -> int:
    """The significant digits of ``x`` to 15 digits: a time ``t_j = 6.58`` needs three."""
    n = read_number(f"{x:.15g}")
    return 17 if n is None else n.digits


# --------------------------------------------------------------------------- the verdicts
#: Why an answer is right or wrong: the catalogues' ``mark.code.*``.
Code = Literal["matches", "in_range", "at_least", "missing", "not_a_number", "too_few_digits", "outside"]


@dataclass(frozen=True)
class Verdict:
    """One answer marked: the text written, the key, right or wrong, and why (``code`` and,
    where an alternative explains it, its ``method`` and ``detail``)."""

    column: str
    part: str
    answer: str
    key: Any
    right: bool
    code: Code
    method: str | None
    detail: str | None
    points: float
    max_points: float
    freedom: str = ""
    digits: int = 1
    low: float | None = None
    high: float | None = None
    key_text: str = ""
    #: The question's :attr:`Question.status` (``"untrusted"``: the key is not to be trusted).
    status: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"column": self.column, "part": self.part, "answer": self.answer, "key": self.key,
                "key_text": self.key_text,
                "right": self.right, "code": self.code, "method": self.method, "detail": self.detail,
                "points": self.points, "max_points": self.max_points, "freedom": self.freedom,
                "min_digits": self.digits, "low": self.low, "high": self.high, "status": self.status}


def judge(q: Question, text: str, min_digits: int | None = None) -> tuple[bool, Code, Alternative | None]:
    """Whether ``text`` answers ``q`` correctly, why, and the alternative it matches."""
    if not text.strip():
        return False, "missing", None
    if q.kind == "text":
        word = text.strip().lower()
        word = "yes" if word in YES else "no" if word in NO else word
        hit = next((a for a in q.alternatives if str(a.value) == word), None)
        return hit is not None, "matches" if hit else "outside", hit
    n = read_number(text)
    if n is None:
        return False, "not_a_number", None
    if q.kind == "integer":
        hit = next((a for a in q.alternatives if n.value == a.value), None)
        return hit is not None, "matches" if hit else "outside", hit
    value = abs(n.value) if q.signless else n.value
    alts = [(a, abs(float(a.value)) if q.signless else float(a.value)) for a in q.alternatives]
    nearest, v = min(alts, key=lambda av: abs(av[1] - value))
    width = (n.half_unit if q.decimals is None else 0.5 * 10.0**-q.decimals) + q.slack
    if q.kind == "at_least":
        assert q.low is not None and q.high is not None
        ok = q.low - width <= value <= q.high + width
        code: Code = "at_least"
        hit = None
    elif abs(value - v) <= width + q.relative_slack * abs(v):
        # of the alternatives the answer matches, the program's own where it is one of them
        within = [(a, x) for a, x in alts if abs(value - x) <= width + q.relative_slack * abs(x)]
        exact = [a for a, x in within if _digits(x) <= n.digits]  # a grid time written whole: t_j = 4.79
        spread = max(x for _, x in within) - min(x for _, x in within)
        if exact:
            hit = exact[0]
        elif n.half_unit >= spread:  # the answer cannot tell them apart: the program's, if it is one
            hit = next((a for a, _ in within if a.value == q.key), nearest)
        else:
            hit = nearest
        ok, code = True, "matches"
    elif q.kind == "range":
        assert q.low is not None and q.high is not None
        lo, hi = (min(abs(q.low), abs(q.high)), max(abs(q.low), abs(q.high))) if q.signless else (q.low, q.high)
        ok = lo - width <= value <= hi + width
        code, hit = "in_range", nearest
    else:
        ok = False
    if not ok:
        return False, "outside", nearest
    if n.digits < (q.min_digits if min_digits is None else min_digits) and not (
            hit is not None and n.digits >= _digits(float(hit.value))):  # right, but too roughly
        return False, "too_few_digits", hit
    return True, code, hit


@dataclass(frozen=True, eq=False)
class GroupMark(Result):
    """One group marked: its line in the groups file, students, names, flags (repeated
    students, listed again) and each question's :class:`Verdict`."""

    line: int
    students: tuple[int, ...]
    names: tuple[str, ...] | None
    duplicate_of: int | None
    repeated: tuple[dict[str, Any], ...]
    answered: bool
    verdicts: tuple[Verdict, ...]

    @property
    def points(self) -> float:
        return math.fsum(v.points for v in self.verdicts)

    @property
    def max_points(self) -> float:
        return math.fsum(v.max_points for v in self.verdicts)

    def to_dict(self) -> dict[str, Any]:
        return {"line": self.line, "students": list(self.students),
                "names": None if self.names is None else list(self.names), "duplicate_of": self.duplicate_of,
                "repeated": list(self.repeated), "answered": self.answered, "points": self.points,
                "max_points": self.max_points, "verdicts": [v.to_dict() for v in self.verdicts]}


#: The class summary's histogram: marks in tenths of the maximum.
BINS = 10


@dataclass(frozen=True, eq=False)
class ClassMarks(Result):
    """A class marked: every group's :class:`GroupMark`, the scheme and the summary."""

    groups: tuple[GroupMark, ...]
    scheme: Scheme

    @property
    def max_points(self) -> float:
        return self.groups[0].max_points if self.groups else 0.0

    def summary(self) -> dict[str, Any]:
        """Mean, median, lowest and highest points; a histogram of marks in tenths of the
        maximum (``counts[i]``: ``i/10 <= points/max < (i+1)/10``, the last bin closed); the
        share of groups right on each question."""
        import statistics

        pts = [g.points for g in self.groups]
        top = self.max_points
        counts = [0] * BINS
        for p in pts:
            counts[min(BINS - 1, int(BINS * p / top)) if top > 0 else 0] += 1
        right: dict[str, int] = {}
        for g in self.groups:
            for v in g.verdicts:
                right[v.column] = right.get(v.column, 0) + v.right
        return {"groups": len(pts), "max_points": top, "mean": statistics.fmean(pts) if pts else None,
                "median": statistics.median(pts) if pts else None, "lowest": min(pts, default=None),
                "highest": max(pts, default=None), "histogram": counts,
                "right_per_question": right}

    def to_dict(self) -> dict[str, Any]:
        return {"summary": self.summary(), "scheme": self.scheme.to_dict(),
                "groups": [g.to_dict() for g in self.groups]}


def mark_group(entry: Entry, row: AnswerRow | None, scheme: Scheme, duplicate_of: int | None = None,
               repeated: Sequence[dict[str, Any]] = ()) -> GroupMark:
    """One group's answers marked against its questions."""
    answers = {} if row is None else row.answers
    verdicts = []
    for q in list(class_questions()) + list(group_questions(entry.students)):
        text = answers.get(q.column, "")
        digits = scheme.min_digits.get(q.column, q.min_digits)
        right, code, alt = judge(q, text, digits)
        worth = float(scheme.points.get(q.column, 1.0))
        verdicts.append(Verdict(q.column, q.part, text, q.key, right, code, None if alt is None else alt.method,
                                None if alt is None else alt.detail, worth if right else 0.0, worth,
                                q.freedom, digits, q.low, q.high, key_text(q), q.status))
    if not any(q.column == "3b_bracket_lo" for q in group_questions(entry.students)):
        for col in ("3b_bracket_lo", "3b_bracket_hi"):  # no return at h = 0.2: nothing to bracket
            text = answers.get(col, "")
            worth = float(scheme.points.get(col, 1.0))
            ok = not text.strip()
            verdicts.append(Verdict(col, "3(b)", text, None, ok, "matches" if ok else "outside", "no_bracket", "",
                                    worth if ok else 0.0, worth, "h02_outcome"))
    line = entry.line if entry.line is not None else 0
    return GroupMark(line, entry.students, entry.names, duplicate_of, tuple(repeated), row is not None,
                     tuple(verdicts))


def mark_class(entries: Sequence[Entry], rows: Sequence[AnswerRow], scheme: Scheme | None = None,
               source: str = "answers") -> ClassMarks:
    """Every group of ``entries`` marked with its row of ``rows`` (matched by the student
    numbers in any order); a row of no group is refused, a group without a row scores 0."""
    scheme = default_scheme() if scheme is None else scheme
    by_group = {tuple(sorted(e.students)) for e in entries}
    for r in rows:
        if tuple(sorted(r.students)) not in by_group:
            raise InputError("answers", f"{source} row {r.row}: {' '.join(map(str, r.students))}",
                             "the student numbers of a group of the groups file")
    answers = {tuple(sorted(r.students)): r for r in rows}
    dup = duplicates(entries)
    repeated: dict[int, list[dict[str, Any]]] = {}
    for rep in repeated_students(entries):
        repeated.setdefault(rep.line, []).append(rep.to_dict())
    marks = []
    for i, e in enumerate(entries, start=1):
        e = e if e.line is not None else Entry(e.students, e.names, i)
        assert e.line is not None
        marks.append(mark_group(e, answers.get(tuple(sorted(e.students))), scheme, dup.get(e.line),
                                repeated.get(e.line, [])))
    return ClassMarks(tuple(marks), scheme)


def template_rows(entries: Sequence[Entry]) -> list[list[str]]:
    """``pendulab key --template``: the header row and one empty row per group."""
    cols = columns()
    out = [["line", "students", "names"] + cols]
    for i, e in enumerate(entries, start=1):
        out.append([str(e.line or i), " ".join(map(str, e.students)), "; ".join(e.names or ())] + [""] * len(cols))
    return out
