"""The report's sections: each takes a result of the library and hands numbers, tables and
figures to the Doc.

A section computes no result and decides no answer: the result objects of
:mod:`pendulab.problems` (and :mod:`pendulab.period` for the exact period) carry both,
and a section picks the catalogue's words for them. It also names the programs whose
source the appendix prints.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

from .document import Constant, Doc
from .markup import distinct, fixed, integer, num, sci, sci_beside, sci_mp, sci_up, up


def _c(module: str, *names: str) -> list[Constant]:
    return [Constant(f"pendulab.{module}", n) for n in names]


# ----------------------------------------------------------------------------- exact period
#: Table 1's amplitudes: (label, how to get alpha exactly at a given precision).
AGM_ROWS = (
    ("π/4", "pi/4"), ("π/2", "pi/2"), ("4π/5", "4pi/5"), ("0.99 π", "0.99pi"),
    ("π − 10#super[−6]", 1e-6), ("π − 10#super[−12]", 1e-12),
)


def _below_pi(gap: float):
    """``pi - gap`` as an mpmath number at 600 digits (``gap`` a power of ten, exact as written)."""
    import mpmath

    with mpmath.workdps(600):
        return mpmath.pi - mpmath.mpf(repr(gap))


def agm(doc: Doc, students: Sequence[int]) -> None:
    from .. import period
    from ..cases import G_EXACT, PROBLEM3_AMPLITUDE
    from ..group import group_length
    from ..inputs import parse_angle, parse_number

    doc.listing(period.agm_mean, period.agm_period, period.agm_iterations, period.fixed_iterations_error,
                period.fixed_iterations_limit, period.period_mp, period.period_digits, period.period_ball,
                *_c("period", "FIXED_ITERATIONS_ULPS"), *_c("cases", "G_TEXT", "G", "G_EXACT", "PROBLEM3_AMPLITUDE"))
    group = group_length(students)
    length = group.length
    alpha = float(PROBLEM3_AMPLITUDE)
    t7 = period.agm_period(length, alpha, iterations=7)
    tc = period.agm_period(length, alpha)
    # The inputs exactly as written: l the 10-decimal text, alpha = 4 pi/5 with the true pi.
    digits = period.period_digits(parse_number("length", group.text), PROBLEM3_AMPLITUDE, G_EXACT, digits=20)
    rows = []
    for text, a in AGM_ROWS:
        exact_alpha = parse_angle("amplitude", a) if isinstance(a, str) else _below_pi(a)
        err7 = period.fixed_iterations_error(exact_alpha, 7)
        rows.append([text, num(float(exact_alpha), 10), integer(period.agm_iterations(float(exact_alpha))),
                     sci_mp(abs(err7), 2)])
    doc.tables["agm"] = rows
    limit = period.fixed_iterations_limit()
    t7_text, tc_text = distinct(t7, tc)  # never the same digits beside "N ulp from"
    ulps = round(abs(t7 - tc) / math.ulp(tc))
    doc.set(**{
        "agm.l": group.text,
        "agm.t7": t7_text,
        "agm.tc": tc_text,
        "agm.mp": digits,
        "agm.diff": integer(ulps),
        "agm.ulps7": integer(period.FIXED_ITERATIONS_ULPS),
        "agm.iter": integer(period.agm_iterations(alpha)),
        "agm.limit": num(limit, 16),
        "agm.gap": sci_up(math.pi - limit, 2),
    })
    doc.choose("agm.same", "equal" if t7 == tc else "one" if ulps == 1 else "many")
    doc.set(**{"agm.relation": doc.entry("agm.same")})


# ----------------------------------------------------------------------------- problem 1
def problem1(doc: Doc, students: Sequence[int]) -> None:
    from .. import problems, uncertainty

    r = problems.problem1()
    doc.listing(problems.problem1, uncertainty.gravity_estimate, uncertainty.gravity, uncertainty.abs_error_bound,
                uncertainty.rel_error_bound, uncertainty.significant_digits, uncertainty.round_significant,
                problems.digit_thresholds,
                *_c("cases", "GRAVITY_LENGTH", "GRAVITY_LENGTH_ERROR", "GRAVITY_PERIOD", "GRAVITY_PERIOD_ERROR"))
    rel_l = r.length_error / r.length
    rel_t = 2 * r.period_error / r.period
    k, half, half_next = problems.digit_thresholds(r.g, r.significant_digits)
    doc.set(**{
        "p1.l": num(r.length, 6), "p1.dl": num(r.length_error, 3), "p1.T": num(r.period, 6),
        "p1.dT": sci(r.period_error, 1), "p1.g": num(r.g, 10), "p1.dgdl": num(r.dg_dl, 8),
        "p1.dgdT": num(r.dg_dT, 8), "p1.abs": up(r.abs_error, 4), "p1.rel": up(r.rel_error, 4),
        "p1.gmin": num(r.g_min, 8), "p1.gmax": num(r.g_max, 8), "p1.worst": up(r.worst_error, 4),
        "p1.bound": up(r.error_bound, 4), "p1.digits": integer(r.significant_digits),
        "p1.gtext": r.g_text, "p1.rell": sci(rel_l, 2), "p1.relT": sci(rel_t, 2),
        "p1.ratio": num(rel_l / rel_t, 2),
        "p1.k": integer(k), "p1.half": num(half, 3), "p1.halfnext": num(half_next, 3),
    })


# ----------------------------------------------------------------------------- problem 2
def problem2(doc: Doc, students: Sequence[int]) -> None:
    from .. import newton, problems

    r = problems.problem2()
    doc.listing(problems.problem2, newton.PeriodEquation.f, newton.PeriodEquation.df, newton.newton,
                newton.quotients, newton.check_interval, *_c("cases", "NEWTON_LENGTH", "NEWTON_TARGET"))
    run, eq, cond = r.run, r.equation, r.condition_values
    xs = run.iterates
    rows = []
    for k, x in enumerate(xs):
        step = sci(xs[k + 1] - x, 3) if k + 1 < len(xs) else "—"
        rows.append([integer(k), num(x, 16), num(math.degrees(x), 14), sci(run.values[k], 3), step])
    doc.tables["p2a"] = rows
    # Every quotient with its relative rounding error: the reader sees q_k approach the
    # constant while that error is small, and where rounding takes over (2(c)).
    doc.tables["p2c"] = [[integer(k), "—" if q is None else num(q, 10), sci(rho, 1)]
                         for k, (q, rho) in enumerate(zip(run.q, run.q_rounding))]
    qk = run.q_kmax
    const = run.asymptotic_constant
    doc.set(**{
        "p2.l": num(eq.length, 4), "p2.target": num(eq.target, 4),
        "p2.t0": num(eq.small_angle_period, 10), "p2.t1": num(1.25 * eq.small_angle_period, 10),
        "p2.a": num(r.interval_degrees[0], 6), "p2.b": num(r.interval_degrees[1], 6),
        "p2.fa": sci(cond["sign"]["f_a"], 4), "p2.fb": sci(cond["sign"]["f_b"], 4),
        "p2.d1min": num(cond["df"]["min"], 6),
        "p2.d2min": num(cond["d2f"]["min"], 6), "p2.d2max": num(cond["d2f"]["max"], 6),
        "p2.stepa": num(cond["step_a"]["step"], 6), "p2.stepb": num(cond["step_b"]["step"], 6),
        "p2.width": num(cond["step_a"]["width"], 6),
        "p2.x0": num(r.x0, 12), "p2.x0deg": num(math.degrees(r.x0), 8),
        "p2.alpha": num(r.alpha, 15), "p2.deg": num(r.alpha_degrees, 13),
        "p2.dfz": num(run.derivatives[-1], 6), "p2.last": sci(abs(xs[-1] - xs[-2]), 3),
        "p2.errest": sci(run.error_estimate, 2), "p2.delta": sci(run.rounding_level, 2),
        "p2.closed": sci(abs(r.closed_form - r.alpha), 2) if r.closed_form != r.alpha else "0",
        "p2.qtol": f"{newton.Q_RTOL:.0%}",
        "p2.kmax": "—" if run.k_max is None else integer(run.k_max),
        "p2.C": num(const, 10), "p2.qkmax": "—" if qk is None else num(qk, 10),
        "p2.qrel": "—" if qk is None or const is None else sci(abs(qk - const) / const, 2),
        "p2.qlast": integer(len(run.q) - 1),
    })
    doc.choose("p2.start", "fourier" if r.x0_from_fourier else "given")
    doc.choose("p2c.shown", "all" if run.k_max is None or run.k_max == len(run.q) - 1 else "cut")


# ----------------------------------------------------------------------------- problem 3
def problem3(doc: Doc, students: Sequence[int]) -> None:
    from .. import _kernels, crossing, group, interpolation, problems, taylor
    from ..plots.simulation import phase_portrait, time_series

    r = problems.problem3(students)
    doc.listing(problems.problem3, problems.plot_outcome, problems.plot_t_max, _kernels.taylor2_step,
                _kernels.step, _kernels.fill_trajectory, _kernels.trajectory, taylor.step_count,
                _kernels.first_return, crossing.estimate_period, crossing.observed_orders,
                interpolation.divided_differences, interpolation.newton_eval, interpolation.inverse_cubic,
                group.group_length,
                *_c("problems", "NEGLIGIBLE_RATIO", "PLOT_SEARCH_PERIODS"),
                *_c("cases", "FIGURE3", "FIGURE3_STEP", "FIGURE3_T_MAX", "PROBLEM3_PLOT_STEP", "PROBLEM3_STEPS",
                    "PROBLEM3_CUBIC_STEP"))

    # 3(a): the table of Figure 3, first and last four rows.
    f3 = r.figure3
    n = f3.n_steps
    rows = []
    for i in list(range(4)) + [None] + list(range(n - 3, n + 1)):
        rows.append(["⋮", "⋮", "⋮"] if i is None else [fixed(f3.t[i], 1), num(f3.theta[i], 12), num(f3.omega[i], 12)])
    doc.tables["p3a"] = rows
    doc.set(**{"p3a.n": integer(n)})

    # 3(b): the group's length and the h = 0.2 simulation.
    g = r.group
    doc.set(**{
        "p3b.students": " + ".join(str(s) for s in g.numbers),
        "p3b.total": integer(g.total),
        "p3b.digits": ", ".join(g.digits),
        "p3b.m": g.digits,
        "p3b.count": integer(len(g.digits)),
        "p3b.l": g.text,
        "p3b.t_hat": num(r.t_hat, 12),
        "p3b.tmax": num(r.plot_t_max, 6),
        "p3b.n": integer(r.plot.n_steps),
        "p3b.h": num(r.plot.step, 3),
        "p3b.search": num(problems.PLOT_SEARCH_PERIODS * r.t_hat, 6),
    })
    doc.choose("p3b.len", "one" if len(g.digits) == 1 else "many")
    doc.choose("p3b.tmax", r.plot_outcome)
    if r.plot_outcome == problems.RETURNS:
        est = r.plot_estimate
        assert est is not None
        t_lo, t_hi = est.bracket
        # Where T^ lies: inside [t_j, t_(j+1)], before it or after it (the sentence follows).
        side = "below" if r.t_hat < t_lo else "above" if r.t_hat > t_hi else "inside"
        dist = {"below": t_lo - r.t_hat, "above": r.t_hat - t_hi, "inside": r.t_hat - t_lo}[side]
        doc.choose("p3b.bracket", side)
        doc.set(**{"p3b.tj": num(t_lo, 6), "p3b.tj1": num(t_hi, 6),
                   "p3b.j": integer(est.j), "p3b.j1": integer(est.j + 1), "p3b.dist": num(dist, 3)})
    else:
        doc.choose("p3b.bracket", r.plot_outcome)
    if r.plot_outcome == problems.LEAVES:
        assert r.plot_left_at is not None
        doc.set(**{"p3b.left": num(r.plot_left_at, 6), "p3b.ratio": num(r.plot_left_at / r.t_hat, 3)})
    doc.figure("p3b_time", lambda ax: time_series(ax, r.plot, title=False))
    doc.figure("p3b_phase", lambda ax: phase_portrait(ax, r.plot))

    # 3(c): the period against the step.
    rows = []
    for e, lo, co in zip(r.estimates, r.linear_orders, r.cubic_orders):
        rows.append([
            sci(e.step, 1), integer(e.j), f"[{num(e.bracket[0], 8)}, {num(e.bracket[1], 8)}]",
            num(e.linear, 12), sci(abs(e.linear - r.t_hat), 3), "—" if lo is None else fixed(lo, 2),
            num(e.cubic, 12), sci(abs(e.cubic - r.t_hat), 3), "—" if co is None else fixed(co, 2),
        ])
    doc.tables["p3c"] = rows
    last = r.estimates[-1]
    orders = [o for o in r.linear_orders if o is not None]
    doc.set(**{"p3c.order": fixed(orders[-1], 2), "p3c.error": sci(abs(last.linear - r.t_hat), 2),
               "p3c.h": sci(last.step, 1), "p3c.first": fixed(orders[0], 2)})

    # 3(d): the inverse cubic interpolation with h = 1e-3.
    c = r.cubic
    ip = c.interpolation
    places = max(0, round(-math.log10(c.step)))  # t_j = j h shown with the step's decimals
    first = c.j - 1  # the table's nodes are j-1 .. j+2
    doc.tables["p3d"] = [[integer(k), num(ip.z2[k], 12), fixed(ip.t[k], places), num(ip.coefficients[k], 10)]
                         for k in range(4)]
    prod = 1.0
    for z in ip.z2:
        prod *= 0.0 - z
    doc.set(**{
        "p3d.h": sci(c.step, 1),
        "p3d.j": integer(c.j),
        "p3d.j0": integer(first),
        "p3d.j3": integer(first + 3),
        "p3d.jm2": integer(c.j - 2),
        "p3d.value": num(ip.value, 15),
        "p3d.z4": num(ip.fifth[0], 12),
        "p3d.t4": fixed(ip.fifth[1], places),
        "p3d.dd": sci(ip.fourth_difference, 6),
        "p3d.prod": sci(prod, 6),
        "p3d.errest": sci(ip.error_estimate, 3),
        "p3d.t_hat": num(r.t_hat, 15),
        "p3d.taylor": sci(r.taylor_error, 3),
        "p3d.ratio": sci_beside(r.interpolation_ratio, problems.NEGLIGIBLE_RATIO, 1),
        "p3d.c0": num(ip.coefficients[0], 10),
        "p3d.c1": num(ip.coefficients[1], 10),
        "p3d.c2": num(ip.coefficients[2], 10),
        "p3d.c3": num(ip.coefficients[3], 10),
        "p3d.x0": num(ip.z2[0], 10),
        "p3d.x1": num(ip.z2[1], 10),
        "p3d.x2": num(ip.z2[2], 10),
        "p3d.threshold": sci(problems.NEGLIGIBLE_RATIO, 1),
        "p3d.rl": sci(ip.rounding_level, 2),
        "p3d.bound": sci_up(r.interpolation_bound, 2),
    })
    doc.choose("p3d.est", "resolved" if r.interpolation_resolved else "rounding")
    doc.choose("p3d.verdict", "negligible" if r.interpolation_negligible else "not_negligible")


# ----------------------------------------------------------------------------- problem 4
P4_NAMES = {"gamma": "$gamma$", "a0": "$a_0$", "b0": "$b_0$", "a1": "$a_1$", "b1": "$b_1$", "a2": "$a_2$", "b2": "$b_2$"}


def problem4(doc: Doc, students: Sequence[int]) -> None:
    from .. import lsq, motion, problems
    from ..cases import PROBLEM4_ALT_T_MAX
    from ..plots.problems import fit, fit_residuals

    r = problems.problem4()
    alt = problems.problem4(t_max=PROBLEM4_ALT_T_MAX)
    f = r.fit
    doc.listing(problems.problem4, lsq.design_matrix, lsq.normal_equations, lsq.round_half_up, lsq.definiteness,
                lsq.least_squares, motion.exact_motion, motion.quarter_period, motion.jacobi, motion.jacobi_agm,
                *_c("lsq", "TRIG_BASIS"), *_c("problems", "PROBLEM4_TOLERANCE", "PROBLEM4_FINE"),
                *_c("cases", "PROBLEM4", "PROBLEM4_STEP", "PROBLEM4_ROUND", "PROBLEM4_ALT_T_MAX"))
    n = r.points - 1
    doc.tables["p4a"] = [[integer(n - 9 + k), fixed(t, 2), num(z, 12)] for k, (t, z) in enumerate(r.last_points)]
    dec = f.decimals if f.decimals is not None else 15
    doc.tables["p4c_matrix"] = [[fixed(x, dec) for x in row] for row in f.normal_matrix]
    doc.tables["p4c_rhs"] = [fixed(x, dec) for x in f.normal_rhs]
    doc.tables["p4d"] = [[P4_NAMES.get(nm, nm), num(c, 10), num(c_ref, 10), num(c_alt, 10)]
                         for nm, c, c_ref, c_alt in zip(f.names, f.coefficients, f.reference_coefficients,
                                                        alt.fit.coefficients)]
    d = f.definiteness
    doc.set(**{
        "p4.l": num(r.length, 4), "p4.T": num(r.t_hat, 12), "p4.tmax": num(r.t_max, 6), "p4.h": num(r.step, 3),
        "p4.n": integer(n), "p4.points": integer(r.points),
        "p4.pivot": num(float(min(d.cholesky_diagonal)) ** 2, 6),
        "p4.lmin": num(d.min_eigenvalue, 6), "p4.lmax": num(d.max_eigenvalue, 6), "p4.cond": num(d.condition_number, 4),
        "p4.pert": sci_up(d.rounding_perturbation, 2), "p4.shift": sci_up(f.coefficient_shift, 2),
        "p4.ssd": sci(f.ssd, 6), "p4.maxdev": sci(f.max_deviation, 4), "p4.argmax": num(f.argmax_deviation, 6),
        "p4.omega": num(2 * math.pi / r.t_hat, 6), "p4.exactdev": sci(r.exact_deviation, 3),
        "p4.exactat": num(r.exact_deviation_at, 6), "p4.taylor": sci(r.taylor_error, 3),
        "p4.tol": sci(r.tolerance, 1),
        "p4.alt.tmax": num(alt.t_max, 6), "p4.alt.points": integer(alt.points), "p4.alt.n": integer(alt.points - 1),
        "p4.alt.ssd": sci(alt.fit.ssd, 6), "p4.alt.maxdev": sci(alt.fit.max_deviation, 4),
        "p4.alt.argmax": num(alt.fit.argmax_deviation, 6), "p4.alt.exactdev": sci(alt.exact_deviation, 3),
    })
    doc.choose("p4d.ii", "yes" if r.below_tolerance else "no")
    doc.choose("p4.alt", "yes" if alt.below_tolerance else "no")
    w = doc.catalogue
    doc.figure("p4d_fit", lambda ax: fit(ax, r, title=False, labels={"data": w["p4.fig.data"], "fit": r"$\tilde\phi$"}))
    doc.figure("p4d_residual", lambda ax: fit_residuals(ax, r))


# ----------------------------------------------------------------------------- problem 5
def problem5(doc: Doc, students: Sequence[int]) -> None:
    from .. import problems, quadrature
    from ..plots.problems import GUIDE_OFFSET, quadrature_convergence

    r = problems.problem5()
    doc.listing(problems.problem5, quadrature.Rule, quadrature.composite, quadrature.period_integrand,
                quadrature.substituted_integrand, quadrature.period_prefactor, quadrature.quadrature_period,
                quadrature.convergence_table, quadrature.observed_rates,
                *_c("quadrature", "GAUSS3"), *_c("problems", "ROUNDING_FLOOR"),
                *_c("cases", "PROBLEM5", "PROBLEM5_N"))
    rows = [row for row in r.rows if row.n >= 10]
    doc.tables["p5d"] = [[
        integer(row.n), num(row.estimate, 16), sci(row.error, 3), "—" if row.rate is None else fixed(row.rate, 4),
        num(row.substitution_estimate, 16), sci(row.substitution_error, 2),
    ] for row in rows]
    w = doc.catalogue
    doc.figure("p5d_conv", lambda ax: quadrature_convergence(ax, r, labels={
        "plain": w["p5.fig.plain"], "sub": w["p5.fig.sub"], "x": "n", "y": w["p5.fig.error"]}),
        height=6.2 / 2.54)
    last = r.rows[-1]
    conv = r.substitution_converged_n
    doc.set(**{
        "p5.l": num(r.length, 4), "p5.t_hat": num(r.t_hat, 15),
        "p5.q1": num(r.single, 12), "p5.e1": sci(abs(r.single - r.t_hat), 3),
        "p5.s10": num(r.composite10, 12), "p5.e10": sci(abs(r.composite10 - r.t_hat), 3),
        "p5.rate": fixed(last.rate, 4) if last.rate is not None else "—",
        "p5.elast": sci(last.error, 3), "p5.nlast": integer(last.n),
        "p5.floor": sci(r.rounding_floor, 1),
        "p5.subbest": "—" if conv is None else sci(next(row.substitution_error for row in r.rows if row.n == conv), 1),
        "p5.subn": "—" if conv is None else integer(conv),
        "p5.sub10": sci(next(row.substitution_error for row in r.rows if row.n == 10), 2),
        "p5.offset": num(GUIDE_OFFSET, 2),
    })
    doc.choose("p5.sub", "converged" if conv is not None else "not_converged")


#: Programs the appendix lists by name and place only: the 15-page limit leaves room for
#: about 700 lines of code at 8 pt; these assemble result objects, check arguments or
#: wrap a library call around the methods printed in full.
INDEX_ONLY = frozenset({
    "uncertainty.gravity_estimate", "lsq.least_squares", "newton.check_interval", "problems.problem2",
    "problems.problem4", "problems.problem5", "quadrature.Rule", "quadrature.convergence_table",
    "motion.jacobi", "motion.jacobi_agm", "motion.quarter_period", "problems.problem1", "uncertainty.round_significant",
    "lsq.definiteness", "lsq.round_half_up", "period.period_mp", "period.period_ball", "quadrature.quadrature_period",
})

SECTIONS = [
    ("exact period", agm),
    ("problem 1", problem1),
    ("problem 2", problem2),
    ("problem 3", problem3),
    ("problem 4", problem4),
    ("problem 5", problem5),
]
