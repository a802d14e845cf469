"""The report's sections: each runs the coursework programs and hands numbers, tables
and figures to the Doc.

The coursework's numbers come from the programs of :mod:`pendulab.jobs.coursework` (the files
the appendix prints whole), run here for this group; the engine (:mod:`pendulab.jobs.problems`,
:mod:`pendulab.numerics.period`) adds what goes beyond the coursework (certified digits, the exact
motion, in sentences opened by the catalogue's ``engine`` words); ``plots.py`` draws every figure from the
programs' data. A section decides no answer of its own: it picks the catalogue's words
for what the programs printed.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from decimal import ROUND_FLOOR, Decimal
from typing import Any

from .document import Doc
from .markup import eq, err, fixed, integer, num, sci, sci_beside, sci_up, shown, up


def programs() -> dict[str, Any]:
    """The coursework programs as modules, by file name (``"problem3.py"``)."""
    from ..jobs.coursework import load

    return load()


# ----------------------------------------------------------------------------- the AGM period
def _toward(x: float, digits: int, rounding: str) -> float:
    """``x`` to ``digits`` significant digits, rounded in the direction ``rounding``."""
    d = Decimal(x)
    return float(d.quantize(Decimal(1).scaleb(d.adjusted() - digits + 1), rounding=rounding))


def agm(doc: Doc, students: Sequence[int]) -> None:
    from ..core.cases import G_EXACT, PROBLEM3_AMPLITUDE
    from ..core.inputs import parse_number
    from ..numerics import period

    p = programs()
    l_text = p["length.py"].group_length(list(students))[2]
    length = float(l_text)
    alpha = p["problem3.py"].ALPHA
    t_hat = p["agm.py"].t_hat(length, alpha)
    tc = period.agm_period(length, alpha)  # the engine: correctly rounded
    # The inputs exactly as written: l the 10-decimal text, alpha = 4 pi/5 with the true pi.
    digits = period.period_digits(parse_number("length", l_text), PROBLEM3_AMPLITUDE, G_EXACT, digits=20)
    import mpmath

    limit = period.fixed_iterations_limit()
    gap = float(mpmath.pi - mpmath.mpf(limit))
    ulps = round(abs(t_hat - tc) / math.ulp(tc))
    doc.set(**{
        "agm.l": l_text,
        "agm.mp": digits,
        "agm.diff": integer(ulps),
        "agm.ulps7": integer(period.FIXED_ITERATIONS_ULPS),
        "agm.iter": integer(period.agm_iterations(alpha)),
        # Rounded towards the safe side: every amplitude the text names is within the limit.
        "agm.limit": num(_toward(limit, 15, ROUND_FLOOR), 15),
        "agm.gap": sci_up(gap, 2),
    })
    doc.choose("agm.same", "equal" if t_hat == tc else "one" if ulps == 1 else "many")
    doc.set(**{"agm.relation": doc.entry("agm.same")})


# ----------------------------------------------------------------------------- problem 1
def problem1(doc: Doc, students: Sequence[int]) -> None:
    from ..jobs import problems

    p1 = programs()["problem1.py"]
    r = p1.solve()
    rel_l = p1.DL / p1.L
    rel_t = 2 * p1.DT / p1.T
    k, half, half_next = problems.digit_thresholds(r["g"], r["digits"])
    doc.set(**{
        "p1.l": num(p1.L, 6), "p1.dl": num(p1.DL, 3), "p1.T": num(p1.T, 6),
        "p1.dT": sci(p1.DT, 1), "p1.g": num(r["g"], 10), "p1.dgdl": num(r["dg_dl"], 8),
        "p1.dgdT": num(r["dg_dt"], 8), "p1.abs": up(r["abs_error"], 4), "p1.rel": up(r["rel_error"], 4),
        "p1.gmin": num(r["g_min"], 8), "p1.gmax": num(r["g_max"], 8), "p1.worst": up(r["worst"], 4),
        "p1.bound": up(r["bound"], 4), "p1.digits": integer(r["digits"]),
        "p1.gtext": r["g_text"], "p1.rell": sci(rel_l, 2), "p1.relT": sci(rel_t, 2),
        "p1.ratio": num(rel_l / rel_t, 2),
        "p1.k": integer(k), "p1.half": num(half, 3), "p1.halfnext": num(half_next, 3),
    })


# ----------------------------------------------------------------------------- problem 2
def problem2(doc: Doc, students: Sequence[int]) -> None:
    p2 = programs()["problem2.py"]
    a, b, steps, holds = p2.interval()
    assert holds  # the conditions of 2(a) on [a, b]: the text states them
    x0 = a if p2.f(a) * p2.d2f(a) > 0 else b  # Fourier's condition, as the program starts
    xs, delta = p2.newton(x0)
    q, rho, k_max = p2.quotients(xs, delta)
    const = abs(p2.d2f(xs[-1]) / (2 * p2.df(xs[-1])))
    last = abs(xs[-1] - xs[-2])
    # Each iterate to the rounding level delta (degrees: plus the conversion's), as problem2.py prints.
    deg = math.degrees(delta) + 2 * p2.U * math.degrees(xs[0])
    # f(x_k) carries the rounding of its terms, S = 1.25 (2 pi/p) + 1.5 of them (at most
    # 1.3 u S against mpmath near z: 2 u S); a step x_(k+1) - x_k two iterates' delta.
    f_error = 2 * p2.U * (1.25 * p2.T0 + p2.TARGET)
    rows = []
    for k, x in enumerate(xs):
        step = err(xs[k + 1] - x, 2 * delta, 3) if k + 1 < len(xs) else "—"
        rows.append([integer(k), err(x, delta), err(math.degrees(x), deg), err(p2.f(x), f_error, 3), step])
    doc.tables["p2a"] = rows
    # Every quotient with its relative rounding error, and the digits that error allows: the
    # reader sees q_k approach the constant while that error is small, and where rounding
    # takes over (2(c)).
    doc.tables["p2c"] = [[integer(k), err(qk, r * qk), sci(r, 1)] for k, (qk, r) in enumerate(zip(q, rho))]
    closed = 2 * math.asin(2 * math.sqrt(p2.TARGET / p2.T0 - 1))  # (9) solved by hand, a check
    doc.set(**{
        "p2.l": num(p2.L, 4), "p2.target": num(p2.TARGET, 4),
        "p2.t0": num(p2.T0, 10), "p2.t1": num(1.25 * p2.T0, 10),
        "p2.a": num(math.degrees(a), 6), "p2.b": num(math.degrees(b), 6),
        "p2.fa": sci(p2.f(a), 4), "p2.fb": sci(p2.f(b), 4),
        # Below 90 degrees f' and f'' are monotone: f' least at a, f'' least at b.
        "p2.d1min": num(p2.df(a), 6), "p2.d2min": num(p2.d2f(b), 6), "p2.d2max": num(p2.d2f(a), 6),
        "p2.stepa": num(steps[0], 6), "p2.stepb": num(steps[1], 6), "p2.width": num(b - a, 6),
        "p2.x0": err(x0, delta), "p2.x0deg": err(math.degrees(x0), deg),
        "p2.alpha": err(xs[-1], delta), "p2.deg": err(math.degrees(xs[-1]), deg),
        "p2.dfz": num(p2.df(xs[-1]), 6), "p2.last": eq(err(last, 2 * delta, 3)),
        "p2.errest": sci(const * last**2 + delta, 2), "p2.delta": sci(delta, 2),
        "p2.closed": sci_up(abs(closed - xs[-1]), 2) if closed != xs[-1] else "0",
        "p2.qtol": f"{p2.Q_TOL:.0%}",
        "p2.kmax": integer(k_max),
        "p2.C": num(const, 10), "p2.qkmax": err(q[k_max], rho[k_max] * q[k_max]),
        "p2.qrel": sci(abs(q[k_max] - const) / const, 2),
        "p2.qlast": integer(len(q) - 1),
    })
    doc.choose("p2.start", "fourier")
    doc.choose("p2c.shown", "all" if k_max == len(q) - 1 else "cut")


# ----------------------------------------------------------------------------- problem 3
def problem3(doc: Doc, students: Sequence[int]) -> None:
    from .figures import words

    p = programs()
    p3, taylor, plots = p["problem3.py"], p["taylor.py"], p["plots.py"]

    # 3(a): the table of Figure 3, first and last four rows.
    t, z1, z2 = taylor.taylor(1.0, math.pi / 4, 0.1, 2.1)
    n = len(t) - 1
    rows = []
    for i in list(range(4)) + [None] + list(range(n - 3, n + 1)):
        rows.append(["⋮", "⋮", "⋮"] if i is None else [fixed(t[i], 1), num(z1[i], 12), num(z2[i], 12)])
    doc.tables["p3a"] = rows
    doc.set(**{"p3a.n": integer(n)})

    # 3(b): the group's length and the h = 0.2 simulation.
    total, digits, l_text = p["length.py"].group_length(list(students))
    length = float(l_text)
    t_hat = p["agm.py"].t_hat(length, p3.ALPHA)
    t_max, j, over, ts = p3.plot_t_max(length, t_hat)
    h = 0.2
    outcome = "returns" if j is not None else "leaves" if over is not None else "none"
    m = "".join(map(str, digits))
    doc.set(**{
        "p3b.students": " + ".join(str(s) for s in students),
        "p3b.total": integer(total),
        "p3b.digits": ", ".join(m),
        "p3b.m": m,
        "p3b.count": integer(len(digits)),
        "p3b.l": l_text,
        "p3b.t_hat": shown("t_hat", t_hat),
        "p3b.tmax": num(t_max, 6),
        "p3b.n": integer(round(t_max / h)),
        "p3b.h": num(h, 3),
        "p3b.search": num(p3.SEARCH * t_hat, 6),
    })
    doc.choose("p3b.len", "one" if len(digits) == 1 else "many")
    doc.choose("p3b.tmax", outcome)
    _trust(doc, length, p3.ALPHA, h, p3.SEARCH * t_hat, outcome)
    if outcome == "returns":
        t_lo, t_hi = ts[j], ts[j + 1]
        # Where T^ lies: inside [t_j, t_(j+1)], before it or after it (the sentence follows).
        side = "below" if t_hat < t_lo else "above" if t_hat > t_hi else "inside"
        dist = {"below": t_lo - t_hat, "above": t_hat - t_hi, "inside": t_hat - t_lo}[side]
        doc.choose("p3b.bracket", side)
        doc.set(**{"p3b.tj": num(t_lo, 6), "p3b.tj1": num(t_hi, 6),
                   "p3b.j": integer(j), "p3b.j1": integer(j + 1), "p3b.dist": num(dist, 3)})
    else:
        doc.choose("p3b.bracket", outcome)
    if outcome == "leaves":
        doc.set(**{"p3b.left": num(ts[over], 6), "p3b.ratio": num(ts[over] / t_hat, 3)})
    if outcome != "none":  # whether the figures, on [0, t_max], show the event
        event = ts[j + 1] if outcome == "returns" else ts[over]
        doc.choose("p3b.view", f"{outcome}_{'in' if event <= t_max + 1e-9 else 'out'}")
        doc.set(**{"p3b.view": doc.entry("p3b.view")})
    # Figures R1 and R2, drawn by plots.py from the run on [0, t_max].
    t, z1, z2 = taylor.taylor(length, p3.ALPHA, h, t_max)
    w = words(doc.catalogue)
    doc.figure("p3b_time", lambda ax: plots.figure1(ax, t, z1, w))
    doc.figure("p3b_phase", lambda ax: plots.figure2(ax, z1, z2, p3.ALPHA, w))

    # 3(c): the period against the step.
    estimates = [p3.period(length, step, t_hat) for step in p3.STEPS]
    rows = []
    for k, e in enumerate(estimates):
        orders_shown = ["—", "—"] if k == 0 else [
            fixed(p3.order(abs(estimates[k - 1][key] - t_hat), abs(e[key] - t_hat), p3.STEPS[k - 1], e["h"]), 2)
            for key in ("linear", "p0")]
        rows.append([
            sci(e["h"], 1), integer(e["j"]), f"[{num(e['bracket'][0], 8)}, {num(e['bracket'][1], 8)}]",
            num(e["linear"], 12), sci(abs(e["linear"] - t_hat), 3), orders_shown[0],
            num(e["p0"], 12), sci(abs(e["p0"] - t_hat), 3), orders_shown[1],
        ])
    doc.tables["p3c"] = rows
    orders: list[float] = [p3.order(abs(a["linear"] - t_hat), abs(b["linear"] - t_hat), a["h"], b["h"])
                           for a, b in zip(estimates, estimates[1:])]
    last = estimates[-1]
    doc.set(**{"p3c.order": fixed(orders[-1], 2), "p3c.error": sci(abs(last["linear"] - t_hat), 3),
               "p3c.last": num(last["linear"], 12),
               "p3c.h": sci(last["h"], 1), "p3c.first": fixed(orders[0], 2)})

    # 3(d): the inverse cubic interpolation with h = 1e-3.
    c = estimates[p3.STEPS.index(1e-3)]
    places = max(0, round(-math.log10(c["h"])))  # t_j = j h shown with the step's decimals
    # Only the digits rounding left right (measured against (3) in 30 digits, as problem3.py prints).
    e = p3.rounding_errors(l_text, c)
    # c0 = t[x0] is t_0 itself: printed as the times are
    coef = [fixed(c["t"][0], places)] + [err(c["coef"][k], e["coef"][k]) for k in range(1, 5)]
    doc.tables["p3d"] = [[integer(k), err(c["z2"][k], e["z2"][k]), fixed(c["t"][k], places), coef[k]]
                         for k in range(4)]
    prod = 1.0
    for z in c["z2"][:4]:
        prod *= 0.0 - z
    taylor_error = abs(c["p0"] - t_hat)
    bound = max(abs(c["e0"]), c["rounding"])
    ratio = bound / taylor_error if taylor_error > 0 else math.inf
    doc.set(**{
        "p3d.h": sci(c["h"], 1),
        "p3d.j": integer(c["j"]),
        "p3d.j0": integer(c["j"] - 1),
        "p3d.j3": integer(c["j"] + 2),
        "p3d.jm2": integer(c["j"] - 2),
        "p3d.value": shown("estimate", c["p0"]),
        "p3d.z4": err(c["z2"][4], e["z2"][4]),
        "p3d.t4": fixed(c["t"][4], places),
        "p3d.dd": eq(err(c["dd4"], e["coef"][4])),  # "= 1.2 × 10^−4", or "≤ 5 × 10^−4" its rounding swamps
        "p3d.prod": sci(prod, 6),
        "p3d.errest": err(c["e0"], e["e0"]),
        "p3d.errest_eq": eq(err(c["e0"], e["e0"])),
        "p3d.moved": sci_up(e["e0"], 1),
        "p3d.movedp": sci_up(e["p0"], 1),
        "p3d.t_hat": shown("t_hat", t_hat),
        "p3d.taylor": sci(taylor_error, 3),
        "p3d.ratio": _ratio(ratio, e["e0"] / taylor_error if taylor_error > 0 else math.inf, p3.NEGLIGIBLE),
        "p3d.c0": coef[0],
        "p3d.c1": err(c["coef"][1], e["coef"][1]),
        "p3d.c2": err(c["coef"][2], e["coef"][2]),
        "p3d.c3": err(c["coef"][3], e["coef"][3]),
        "p3d.x0": err(c["z2"][0], e["z2"][0]),
        "p3d.x1": err(c["z2"][1], e["z2"][1]),
        "p3d.x2": err(c["z2"][2], e["z2"][2]),
        "p3d.threshold": sci(p3.NEGLIGIBLE, 1),
        "p3d.rl": sci(c["rounding"], 2),
        "p3d.bound": sci_up(bound + e["e0"], 1),  # with e(0)'s own digits: no more than it has
    })
    doc.choose("p3d.est", "resolved" if abs(c["e0"]) > c["rounding"] else "rounding")
    doc.choose("p3d.verdict", "negligible" if ratio < p3.NEGLIGIBLE else "not_negligible")
    doc.set(**{"p3d.answer": doc.word("answers.yes" if ratio < p3.NEGLIGIBLE else "answers.no")})


def _ratio(ratio: float, error: float, limit: float) -> str:
    """3(d)'s ratio of the interpolation error to the Taylor method's: one digit, on the side
    of ``limit`` it lies (:func:`sci_beside`), unless the rounding of e(0) (``error``, the ratio's
    share of it) leaves less: then only the digits it allows (:func:`err`)."""
    if not math.isfinite(ratio):
        return "—"
    if err(ratio, error, 1) == sci(ratio, 1):
        return sci_beside(ratio, limit, 1)
    return err(ratio, error, 1)


def _trust(doc: Doc, length: float, alpha: float, h: float, search: float, outcome: str) -> None:
    """3(b), beyond the coursework: the engine's period search judges the h = 0.2 return. Near
    the separatrix it can be untrusted (a sum of 1115 gives l = 1.4953487812: the return at
    [5, 5.2] is 27 % of T off); the sentence after the bracket says so, with the search's numbers."""
    from ..core.methods import Status
    from ..numerics.crossing import search_period

    s = search_period(length, alpha, h, search) if outcome == "returns" else None
    if s is None or s.status != Status.UNTRUSTED:
        doc.choose("p3b.trust", "trusted")
    elif s.max_energy_drift is not None and s.separatrix_distance is not None \
            and s.max_energy_drift > s.separatrix_distance:
        doc.choose("p3b.trust", "energy")
        doc.set(**{"p3b.drift": sci(s.max_energy_drift, 2), "p3b.sep": sci(s.separatrix_distance, 2)})
    else:
        assert s.estimate is not None
        doc.choose("p3b.trust", "off")
        doc.set(**{"p3b.cubic": num(s.estimate.cubic, 6),
                   "p3b.off": f"{abs(s.estimate.cubic - s.period) / s.period:.0%}"})
    doc.set(**{"p3b.trust": doc.entry("p3b.trust")})


# ----------------------------------------------------------------------------- problem 4
P4_NAMES = {"gamma": "$gamma$", "a0": "$a_0$", "b0": "$b_0$", "a1": "$a_1$", "b1": "$b_1$", "a2": "$a_2$", "b2": "$b_2$"}


def problem4(doc: Doc, students: Sequence[int]) -> None:
    import numpy as np

    from ..core.cases import PROBLEM4_ALT_T_MAX
    from ..jobs import problems
    from .figures import words

    p = programs()
    p4, taylor, plots = p["problem4.py"], p["taylor.py"], p["plots.py"]
    t_hat = p["agm.py"].t_hat(p4.L, p4.ALPHA)
    fits = {}
    for t_max in (math.ceil(t_hat), PROBLEM4_ALT_T_MAX):
        t, z1, z2 = taylor.taylor(p4.L, p4.ALPHA, p4.H, t_max)
        a, rhs, diag, coef, res = p4.fit(t, z1)
        j = int(np.argmax(np.abs(res)))
        low, high, cond, moved, svd = p4.checks(t, z1, a)
        fits[t_max] = {"t": t, "z1": z1, "z2": z2, "a": a, "r": rhs, "diag": diag, "coef": coef, "t_max": t_max,
                       "res": res, "ssd": math.fsum(res**2), "maxdev": abs(res[j]), "argmax": t[j],
                       "low": low, "high": high, "cond": cond, "moved": moved, "svd": svd}
    main, other = fits[math.ceil(t_hat)], fits[PROBLEM4_ALT_T_MAX]
    # Beyond the coursework, from the engine on the program's data: the eigenvalues, the
    # rounding's effect, the SVD solution, the exact motion between the data points.
    r = problems.problem4(taylor_data=(main["t"], main["z1"], main["z2"]))
    alt = problems.problem4(t_max=PROBLEM4_ALT_T_MAX, taylor_data=(other["t"], other["z1"], other["z2"]))
    n = len(main["t"]) - 1
    doc.tables["p4a"] = [[integer(j), fixed(main["t"][j], 2), num(main["z1"][j], 12)] for j in range(n - 9, n + 1)]
    doc.tables["p4c_matrix"] = [[fixed(x, 6) for x in row] for row in main["a"]]
    doc.tables["p4c_rhs"] = [fixed(x, 6) for x in main["r"]]
    doc.tables["p4d"] = [[P4_NAMES.get(nm, nm), num(c, 10), num(c_ref, 10), num(c_alt, 10)]
                         for nm, c, c_ref, c_alt in zip(p4.NAMES, main["coef"], main["svd"], other["coef"])]
    doc.set(**{
        "p4.l": num(p4.L, 4), "p4.T": shown("t_hat", t_hat), "p4.tmax": num(main["t_max"], 6), "p4.h": num(p4.H, 3),
        "p4.n": integer(n), "p4.points": integer(n + 1),
        "p4.pivot": num(float(min(main["diag"])) ** 2, 6),
        "p4.lmin": num(main["low"], 6), "p4.lmax": num(main["high"], 6), "p4.cond": num(main["cond"], 4),
        "p4.pert": sci_up(main["moved"], 2),
        "p4.shift": sci_up(float(np.max(np.abs(main["coef"] - main["svd"]))), 2),
        "p4.ssd": sci(main["ssd"], 6), "p4.maxdev": sci_beside(main["maxdev"], p4.TOL, 4), "p4.argmax": num(main["argmax"], 6),
        "p4.omega": num(2 * math.pi / t_hat, 6), "p4.exactdev": sci(r.exact_deviation, 3),
        "p4.exactat": num(r.exact_deviation_at, 6), "p4.taylor": sci(r.taylor_error, 3),
        "p4.tol": sci(p4.TOL, 1),
        "p4.alt.tmax": num(other["t_max"], 6), "p4.alt.points": integer(len(other["t"])),
        "p4.alt.n": integer(len(other["t"]) - 1),
        "p4.alt.ssd": sci(other["ssd"], 6), "p4.alt.maxdev": sci_beside(other["maxdev"], p4.TOL, 4),
        "p4.alt.argmax": num(other["argmax"], 6), "p4.alt.exactdev": sci(alt.exact_deviation, 3),
    })
    doc.choose("p4d.ii", "yes" if main["maxdev"] < p4.TOL else "no")
    doc.set(**{"p4.answer": doc.word("answers.yes" if main["maxdev"] < p4.TOL else "answers.no")})
    doc.choose("p4.alt", "yes" if other["maxdev"] < p4.TOL else "no")
    w = words(doc.catalogue)  # figures R3 and R4, drawn by plots.py from the program's fit
    doc.figure("p4d_fit", lambda ax: plots.figure3(ax, main["t"], main["z1"], main["coef"], w))
    doc.figure("p4d_residual", lambda ax: plots.figure4(ax, main["t"], main["res"], p4.TOL, w))


# ----------------------------------------------------------------------------- problem 5
def problem5(doc: Doc, students: Sequence[int]) -> None:
    from .figures import words

    p5, plots = programs()["problem5.py"], programs()["plots.py"]
    t_hat = programs()["agm.py"].t_hat(p5.L, p5.ALPHA)
    table = p5.table(t_hat)  # (n, period by S_n, error, rate) for n = 1, 10, ..., 10^5
    # The substituted integral by the same rule, as problem5.py prints it; the rounding floor.
    sub = {n: p5.substituted(n) for n, *_ in table[1:]}
    floor = p5.FLOOR * p5.U * t_hat
    conv = next((n for n, s in sub.items() if abs(s - t_hat) <= floor), None)

    def sub_error(e: float) -> str:
        """An error at or below the rounding floor is rounding: its digits say nothing (against
        T^, itself a double), so it prints as the floor it is under (as problem5.py does)."""
        return f"≤ {sci_up(floor, 1)}" if e <= floor else sci(e, 2)

    doc.tables["p5d"] = [[
        integer(n), err(period, p5.rounding_error(n)), sci(error, 3), fixed(rate, 4),
        num(sub[n], 15), sub_error(abs(sub[n] - t_hat)),
    ] for n, period, error, rate in table[1:]]
    w = words(doc.catalogue)  # figure R5, drawn by plots.py from the program's table
    doc.figure("p5d_conv", lambda ax: plots.figure5(ax, [row[0] for row in table[1:]], [row[2] for row in table[1:]], w),
               height=6.2 / 2.54)
    single, ten, last = table[0], table[1], table[-1]
    doc.set(**{
        "p5.l": num(p5.L, 4), "p5.t_hat": shown("t_hat", t_hat),
        "p5.q1": err(single[1], p5.rounding_error(1)), "p5.e1": sci(single[2], 3),
        "p5.s10": err(ten[1], p5.rounding_error(10)), "p5.e10": sci(ten[2], 3),
        "p5.rate": fixed(last[3], 4),
        "p5.elast": sci(last[2], 3), "p5.nlast": integer(last[0]),
        "p5.floor": sci(floor, 1),
        "p5.subn": "—" if conv is None else integer(conv),
        "p5.sub10": sub_error(abs(sub[10] - t_hat)),
        "p5.offset": num(plots.GUIDE, 2),
    })
    doc.choose("p5.sub", "converged" if conv is not None else "not_converged")


SECTIONS = [
    ("AGM period", agm),
    ("problem 1", problem1),
    ("problem 2", problem2),
    ("problem 3", problem3),
    ("problem 4", problem4),
    ("problem 5", problem5),
]
