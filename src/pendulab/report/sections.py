"""The report's sections: each calls the library and hands numbers, tables and figures to the Doc.

A section never computes a result itself: it takes the result objects of
:mod:`pendulab.problems` (and of :mod:`pendulab.period` for the AGM section), formats
them, and names the library functions whose source the appendix prints.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .builder import Doc, fixed, integer, num, sci
from .figures import new_figure


# ----------------------------------------------------------------------------- problem 1
def problem1(doc: Doc, students: Sequence[int]) -> None:
    from .. import problems, uncertainty

    r = problems.problem1()
    doc.listing(uncertainty.gravity, uncertainty.abs_error_bound, uncertainty.rel_error_bound,
                uncertainty.significant_digits)
    rel_l = r.length_error / r.length
    rel_t = 2 * r.period_error / r.period
    doc.set(**{
        "p1.l": num(r.length, 6), "p1.dl": num(r.length_error, 3), "p1.T": num(r.period, 6),
        "p1.dT": sci(r.period_error, 1), "p1.g": num(r.g, 10), "p1.dgdl": num(r.dg_dl, 8),
        "p1.dgdT": num(r.dg_dT, 8), "p1.abs": num(r.abs_error, 4), "p1.rel": num(r.rel_error, 4),
        "p1.gmin": num(r.g_min, 8), "p1.gmax": num(r.g_max, 8), "p1.worst": num(r.worst_error, 4),
        "p1.bound": num(r.error_bound, 4), "p1.digits": integer(r.significant_digits),
        "p1.gtext": r.g_text, "p1.rell": sci(rel_l, 2), "p1.relT": sci(rel_t, 2),
        "p1.ratio": num(rel_l / rel_t, 2),
    })
    # The digit rule's threshold 0.5 * 10^(k - n + 1) for n and n + 1 digits.
    k = math.floor(math.log10(abs(r.g)))
    n = r.significant_digits
    doc.set(**{"p1.k": integer(k), "p1.half": num(0.5 * 10.0 ** (k - n + 1), 3),
               "p1.halfnext": num(0.5 * 10.0 ** (k - n), 3)})


# ----------------------------------------------------------------------------- problem 2
def problem2(doc: Doc, students: Sequence[int]) -> None:
    from .. import newton, problems

    r = problems.problem2()
    doc.listing(newton.PeriodEquation.f, newton.PeriodEquation.df, newton.newton, newton.quotients,
                newton.check_interval)
    run, eq, chk = r.run, r.equation, r.interval
    cond = {c.name: c for c in chk.conditions}
    xs = run.iterates
    rows = []
    for k, x in enumerate(xs):
        step = sci(xs[k + 1] - x, 3) if k + 1 < len(xs) else "—"
        rows.append([integer(k), num(x, 16), num(math.degrees(x), 14), sci(run.values[k], 3), step])
    doc.tables["p2a"] = rows
    doc.tables["p2c"] = [[integer(k), "—" if q is None else num(q, 10)] for k, q in enumerate(run.q)]
    d2 = cond["f'' of constant sign"].values
    const = run.asymptotic_constant
    qk = run.q_kmax
    doc.set(**{
        "p2.l": num(eq.length, 4), "p2.target": num(eq.target, 4),
        "p2.t0": num(eq.small_angle_period, 10), "p2.t1": num(1.25 * eq.small_angle_period, 10),
        "p2.a": num(r.interval_degrees[0], 6), "p2.b": num(r.interval_degrees[1], 6),
        "p2.fa": sci(cond["sign change"].values["f_a"], 4), "p2.fb": sci(cond["sign change"].values["f_b"], 4),
        "p2.d1min": num(cond["f' has no zero"].values["min"], 6),
        "p2.d2min": num(d2["min"], 6), "p2.d2max": num(d2["max"], 6),
        "p2.stepa": num(cond["Newton step from a stays in [a, b]"].values["step"], 6),
        "p2.stepb": num(cond["Newton step from b stays in [a, b]"].values["step"], 6),
        "p2.width": num(chk.b - chk.a, 6),
        "p2.x0": num(r.x0, 12), "p2.x0deg": num(math.degrees(r.x0), 8),
        "p2.alpha": num(r.alpha, 15), "p2.deg": num(r.alpha_degrees, 13),
        "p2.dfz": num(run.derivatives[-1], 6), "p2.last": sci(abs(xs[-1] - xs[-2]), 3),
        "p2.errest": sci(run.error_estimate, 2), "p2.delta": sci(run.rounding_level, 2),
        "p2.closed": sci(abs(r.closed_form - r.alpha), 2) if r.closed_form != r.alpha else "0",
        "p2.qtol": f"{newton.Q_RTOL:.0%}",
        "p2.kmax": "—" if run.k_max is None else integer(run.k_max),
        "p2.C": num(const, 10), "p2.qkmax": "—" if qk is None else num(qk, 10),
        "p2.qrel": "—" if qk is None else sci(abs(qk - const) / const, 2),
    })
    doc.choose("p2.start", "fourier" if r.x0_rule != "given" else "given")


# ----------------------------------------------------------------------------- problem 3
def problem3(doc: Doc, students: Sequence[int]) -> None:
    from .. import _kernels, crossing, group, interpolation, problems, taylor
    from ..plots.simulation import phase_portrait, time_series

    r = problems.problem3(students)
    doc.listing(_kernels.taylor2_step, _kernels.step, _kernels.fill_trajectory, _kernels.trajectory,
                taylor.step_count, _kernels.first_return,
                crossing.estimate_period, interpolation.divided_differences, interpolation.newton_eval,
                interpolation.inverse_cubic, group.group_length)

    # 3(a): the table of Figure 3, first and last four rows.
    f3 = r.figure3
    rows = []
    n = f3.n_steps
    for i in list(range(4)) + [None] + list(range(n - 3, n + 1)):
        if i is None:
            rows.append(["⋮", "⋮", "⋮"])
        else:
            rows.append([fixed(f3.t[i], 1), num(f3.theta[i], 12), num(f3.omega[i], 12)])
    doc.tables["p3a"] = rows
    doc.set(**{"p3a.n": integer(n)})

    # 3(b): the group's length and the h = 0.2 simulation.
    g = r.group
    est = r.plot_estimate
    doc.set(**{
        "p3b.students": " + ".join(str(s) for s in g.numbers),
        "p3b.total": integer(g.total),
        "p3b.digits": ", ".join(g.digits),
        "p3b.m": g.digits,
        "p3b.count": integer(len(g.digits)),
        "p3b.l": g.text,
        "p3b.exact": num(r.exact, 12),
        "p3b.tmax": num(r.plot_t_max, 6),
        "p3b.n": integer(r.plot.n_steps),
        "p3b.h": num(r.plot.step, 3),
    })
    if est is not None:
        doc.choose("p3b.bracket", "found")
        doc.set(**{"p3b.tj": num(est.bracket[0], 6), "p3b.tj1": num(est.bracket[1], 6), "p3b.j": integer(est.j)})
    else:
        doc.choose("p3b.bracket", "none")
    fig, ax = new_figure()
    time_series(ax, r.plot)
    ax.set_title("")
    doc.figure("p3b_time", fig)
    fig, ax = new_figure()
    phase_portrait(ax, r.plot)
    doc.figure("p3b_phase", fig)

    # 3(c): the period against the step.
    rows = []
    for e, lo, co in zip(r.estimates, r.linear_orders, r.cubic_orders):
        rows.append([
            sci(e.step, 1), integer(e.j), f"[{num(e.bracket[0], 8)}, {num(e.bracket[1], 8)}]",
            num(e.linear, 12), sci(abs(e.linear - r.exact), 3), "—" if lo is None else fixed(lo, 2),
            num(e.cubic, 12), sci(abs(e.cubic - r.exact), 3), "—" if co is None else fixed(co, 2),
        ])
    doc.tables["p3c"] = rows
    last = r.estimates[-1]
    doc.set(**{"p3c.order": fixed(r.linear_orders[-1], 2), "p3c.error": sci(abs(last.linear - r.exact), 2),
               "p3c.h": sci(last.step, 1)})

    # 3(d): the inverse cubic interpolation with h = 1e-3.
    c = r.cubic
    ip = c.interpolation
    places = max(0, round(-math.log10(c.step)))  # t_j = j h shown with the step's decimals
    doc.tables["p3d"] = [[integer(k), num(ip.z2[k], 12), fixed(ip.t[k], places), num(ip.coefficients[k], 10)]
                         for k in range(4)]
    first = c.j - 1  # the table's nodes are j-1 .. j+2
    taylor_err = r.taylor_error
    ratio = abs(ip.error_estimate) / taylor_err if taylor_err > 0 else math.inf
    doc.set(**{
        "p3d.h": sci(c.step, 1),
        "p3d.j0": integer(first),
        "p3d.j3": integer(first + 3),
        "p3d.value": num(ip.value, 15),
        "p3d.z4": num(ip.fifth[0], 12),
        "p3d.t4": num(ip.fifth[1], 10),
        "p3d.dd": sci(ip.fourth_difference, 6),
        "p3d.prod": sci(float(np.prod(0.0 - ip.z2)), 6),
        "p3d.errest": sci(ip.error_estimate, 3),
        "p3d.exact": num(r.exact, 15),
        "p3d.taylor": sci(taylor_err, 3),
        "p3d.ratio": sci(ratio, 1),
        "p3d.c0": num(ip.coefficients[0], 10),
        "p3d.c1": num(ip.coefficients[1], 10),
        "p3d.c2": num(ip.coefficients[2], 10),
        "p3d.c3": num(ip.coefficients[3], 10),
        "p3d.x0": num(ip.z2[0], 10),
        "p3d.x1": num(ip.z2[1], 10),
        "p3d.x2": num(ip.z2[2], 10),
    })
    doc.choose("p3d.verdict", "negligible" if ratio < 1e-3 else "not_negligible")


# ----------------------------------------------------------------------------- problem 4
def problem4(doc: Doc, students: Sequence[int]) -> None:
    from .. import lsq, problems
    from .figures import fit_plot, residual_plot

    r = problems.problem4()
    f = r.fit
    doc.listing(lsq.design_matrix, lsq.normal_equations, lsq.round_half_up, lsq.definiteness, lsq.least_squares)
    n = r.points - 1
    doc.tables["p4a"] = [[integer(n - 9 + k), fixed(t, 2), num(z, 12)] for k, (t, z) in enumerate(r.last_points)]
    dec = f.decimals
    doc.tables["p4c_matrix"] = [[fixed(x, dec) for x in row] for row in f.normal_matrix]
    doc.tables["p4c_rhs"] = [fixed(x, dec) for x in f.normal_rhs]
    names = {"gamma": "$gamma$", "a0": "$a_0$", "b0": "$b_0$", "a1": "$a_1$", "b1": "$b_1$", "a2": "$a_2$", "b2": "$b_2$"}
    doc.tables["p4d"] = [[names.get(nm, nm), num(c, 10), num(c_ref, 10)]
                         for nm, c, c_ref in zip(f.names, f.coefficients, f.reference_coefficients)]
    d = f.definiteness
    doc.set(**{
        "p4.l": num(r.length, 4), "p4.T": num(r.period, 12), "p4.tmax": num(r.t_max, 6), "p4.h": num(r.step, 3),
        "p4.n": integer(n), "p4.points": integer(r.points),
        "p4.pivot": num(float(np.min(d.cholesky_diagonal)) ** 2, 6),
        "p4.lmin": num(d.min_eigenvalue, 6), "p4.lmax": num(d.max_eigenvalue, 6), "p4.cond": num(d.condition_number, 4),
        "p4.pert": sci(d.rounding_perturbation, 2), "p4.shift": sci(f.coefficient_shift, 2),
        "p4.ssd": sci(f.ssd, 6), "p4.maxdev": sci(f.max_deviation, 4), "p4.argmax": num(f.argmax_deviation, 6),
        "p4.omega": num(2 * math.pi / r.period, 6), "p4.exactdev": sci(r.exact_deviation, 3),
        "p4.exactat": num(r.exact_deviation_at, 6), "p4.taylor": sci(r.taylor_error, 3),
    })
    doc.choose("p4d.ii", "yes" if r.below_tolerance else "no")
    w = doc.catalogue
    fig, ax = new_figure()
    fit_plot(ax, r.data.t, r.data.theta, r.curve_t, r.curve_phi,
             ("t (s)", r"$z_{1,j}$, $\tilde\phi(t)$ (rad)", w["p4.fig.data"], r"$\tilde\phi$"))
    doc.figure("p4d_fit", fig)
    fig, ax = new_figure()
    residual_plot(ax, f.t, -f.residuals, ("t (s)", r"$\tilde\phi(t_j) - z_{1,j}$ (rad)"))
    doc.figure("p4d_residual", fig)


# ----------------------------------------------------------------------------- problem 5
def problem5(doc: Doc, students: Sequence[int]) -> None:
    from .. import problems, quadrature
    from .figures import convergence

    r = problems.problem5()
    doc.listing(quadrature.composite, quadrature.period_integrand, quadrature.substituted_integrand,
                quadrature.quadrature_period)
    rows = [row for row in r.rows if row.n >= 10]
    doc.tables["p5d"] = [[
        integer(row.n), num(row.period, 12), sci(row.error, 3), "—" if row.rate is None else fixed(row.rate, 4),
        num(row.substitution_period, 16), sci(row.substitution_error, 2),
    ] for row in rows]
    floor = 64 * np.finfo(float).eps * r.exact
    sub_ok = next((row for row in r.rows if row.substitution_error is not None and row.substitution_error <= floor), None)
    w = doc.catalogue
    fig, ax = new_figure(height=6.2 / 2.54)
    ns = [row.n for row in r.rows]
    convergence(ax, [
        (ns, [row.error for row in r.rows], w["p5.fig.plain"], "o"),
        (ns, [max(row.substitution_error, 1e-17) for row in r.rows], w["p5.fig.sub"], "s"),
        (ns, [r.rows[0].error * n ** -0.5 for n in ns], r"$\propto n^{-1/2}$", ""),
    ], ("n", w["p5.fig.error"]))
    ax.lines[-1].set_linestyle(":")
    ax.lines[-1].set_color("0.5")
    ax.legend(loc="best", frameon=False)
    doc.figure("p5d_conv", fig)
    last = r.rows[-1]
    doc.set(**{
        "p5.l": num(r.length, 4), "p5.exact": num(r.exact, 15),
        "p5.q1": num(r.single, 12), "p5.e1": sci(abs(r.single - r.exact), 3),
        "p5.s10": num(r.composite10, 12), "p5.e10": sci(abs(r.composite10 - r.exact), 3),
        "p5.rate": fixed(last.rate, 4) if last.rate is not None else "—",
        "p5.elast": sci(last.error, 3), "p5.nlast": integer(last.n),
        "p5.subbest": sci(sub_ok.substitution_error, 1) if sub_ok else "—",
        "p5.subn": integer(sub_ok.n) if sub_ok else "—",
        "p5.sub10": sci(next(row.substitution_error for row in r.rows if row.n == 10), 2),
    })


# ----------------------------------------------------------------------------- exact period
def agm(doc: Doc, students: Sequence[int]) -> None:
    from .. import period
    from ..cases import PROBLEM3_AMPLITUDE
    from ..group import group_length

    doc.listing(period.agm_mean, period.agm_period)
    length = group_length(students).length
    alpha = float(PROBLEM3_AMPLITUDE)
    t7 = period.agm_period(length, alpha, iterations=7)
    tc = period.agm_period(length, alpha)
    digits = period.period_digits(length, alpha, digits=20)
    rows = []
    for text, a in (("π/4", math.pi / 4), ("π/2", math.pi / 2), ("4π/5", 4 * math.pi / 5),
                    ("0.99 π", 0.99 * math.pi), ("π − 10#super[−6]", math.pi - 1e-6),
                    ("π − 10#super[−12]", math.pi - 1e-12)):
        err7 = float(period.fixed_iterations_error(a, 7))
        rows.append([text, num(a, 10), integer(period.agm_iterations(a)), sci(abs(err7), 2)])
    doc.tables["agm"] = rows
    limit = period.fixed_iterations_limit()
    doc.set(**{
        "agm.l": num(length, 11),
        "agm.t7": num(t7, 16),
        "agm.tc": num(tc, 16),
        "agm.mp": digits,
        "agm.diff": sci(abs(t7 - tc), 2) if t7 != tc else "0",
        "agm.iter": integer(period.agm_iterations(alpha)),
        "agm.limit": num(limit, 16),
        "agm.gap": sci(math.pi - limit, 2),
    })


SECTIONS = [
    ("exact period", agm),
    ("problem 1", problem1),
    ("problem 2", problem2),
    ("problem 3", problem3),
    ("problem 4", problem4),
    ("problem 5", problem5),
]
