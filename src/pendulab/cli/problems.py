"""Commands of problems 1, 2, 4, 5: ``gravity``, ``newton``, ``fit``, ``quadrature``."""
from __future__ import annotations

import math
from fractions import Fraction

import click

from ..core import cases, inputs
from ..core.digits import bound, shown, with_error
from ..core.errors import InputError
from ..numerics.newton import Condition, U
from ..numerics.period import FIXED_ITERATIONS_ULPS
from ..report.words import sentence
from ._common import (
    ANGLE,
    DURATION,
    FIGURE,
    LENGTH,
    Parsed,
    check_plot_path,
    emit_json,
    g_option,
    json_option,
)

_M = inputs.LENGTH_UNITS
_S = inputs.TIME_UNITS


def _quantity(units: dict[str, Fraction], default_unit: str, strict: bool) -> Parsed:
    """A number with an optional unit suffix, in SI (:func:`pendulab.core.inputs.quantity`)."""
    return Parsed(lambda s: float(inputs.quantity("value", s, units, default_unit, strict)), "|".join(units))


def _round(text: str) -> int | None:
    """Decimals to round the normal equations to: an integer 0..15, or ``none``."""
    from ..numerics.lsq import MAX_DECIMALS

    if text.strip().lower() in ("none", "no", "off"):
        return None
    try:
        return inputs.integer("round", text, 0, MAX_DECIMALS)
    except InputError as exc:
        raise InputError("round", exc.value, f"an integer in [0, {MAX_DECIMALS}] or 'none'") from None


def _counts(text: str) -> list[int]:
    """Numbers of subintervals: ``1,10,100`` (``1e5`` accepted), each in [1, MAX_N], MAX_TOTAL_N in all."""
    from ..numerics.quadrature import MAX_N, MAX_TOTAL_N

    ns = inputs.integer_list("n", text, 1, MAX_N)
    if sum(ns) > MAX_TOTAL_N:
        raise InputError("n", inputs.shown(text.strip()), f"a list of integers in [1, {MAX_N:.0e}] summing to at most "
                         f"{MAX_TOTAL_N:.0e} (these sum to {sum(ns):.3g})")
    return ns


LENGTH_ERROR = _quantity(_M, "m", False)
PERIOD_ERROR = _quantity(_S, "s", False)
#: A Newton start in (0, pi): 1, pi/3, 60deg.
X0 = Parsed(lambda s: float(inputs.angle("x0", s, open_low=True)), "angle")
ROUND = Parsed(_round, "0..15|none")
COUNTS = Parsed(_counts, "list")


# --------------------------------------------------------------------------- gravity
@click.command()
@click.option("-l", "--length", type=LENGTH, default="115.2cm", show_default=True,
              help="Measured length l: 1.152, 1.152m, 115.2cm.")
@click.option("--length-error", "length_error", type=LENGTH_ERROR, default="0.3cm", show_default=True,
              help="Absolute error bound of l (m, cm or mm; >= 0).")
@click.option("--period", type=DURATION, default="2.1536", show_default=True, help="Measured period T, s (> 0).")
@click.option("--period-error", "period_error", type=PERIOD_ERROR, default="2e-4", show_default=True,
              help="Absolute error bound of T, s (>= 0).")
@json_option
def gravity(length, length_error, period, period_error, as_json):
    """Problem 1: g = 4 pi^2 l / T^2 and its propagated error; guaranteed significant digits."""
    from ..jobs.problems import problem1

    r = problem1(float(length), length_error, period, period_error)
    rule, abs_formula, rel_formula = (sentence(f"p1.{k}") for k in ("rule", "abs_error_formula", "rel_error_formula"))
    if as_json:
        emit_json(r.to_dict() | {"rule": rule, "abs_error_formula": abs_formula, "rel_error_formula": rel_formula})
        return
    click.echo(f"l = {r.length!r} +- {r.length_error!r} m,  T = {r.measured_period!r} +- {r.measured_period_error!r} s")
    # The report's digits (pendulab.core.digits.POLICY): g and its range to 10 and 8 significant
    # digits, the bounds rounded up to 4; --json keeps every double.
    click.echo(f"g = 4 pi^2 l / T^2          = {shown('p1.g', r.g)} m/s^2")
    click.echo(f"absolute error (1st order)  {abs_formula}  = {shown('p1.error_bound', r.abs_error)} m/s^2")
    click.echo(f"relative error (1st order)  {rel_formula}  = {shown('p1.error_bound', r.rel_error)}")
    click.echo(f"exact range over the box    [{shown('p1.g_range', r.g_min)}, {shown('p1.g_range', r.g_max)}]  "
               f"(worst error {shown('p1.error_bound', r.worst_error)})")
    click.echo(f"significant digits guaranteed: {r.significant_digits}  (g = {r.g_text} m/s^2, error <= {shown('p1.error_bound', r.error_bound)})")
    click.echo(f"rule: {rule}")


# --------------------------------------------------------------------------- newton
@click.command()
@click.option("-l", "--length", type=LENGTH, default=str(cases.NEWTON_LENGTH), show_default=True,
              help="Pendulum length l, m: 0.5, 50cm.")
@click.option("--target", type=DURATION, default=str(cases.NEWTON_TARGET), show_default=True,
              help="Target period of approximation (9), s.")
@click.option("--x0", type=X0, default=None, show_default="the end of the convergence interval where f f'' > 0",
              help="Starting value in (0, pi): 1, pi/3, 60deg.")
@g_option
@json_option
def newton(length, target, x0, g, as_json):
    """Problem 2: the amplitude with T~(alpha) = target, by Newton's method on (9)."""
    from ..jobs.problems import problem2

    r = problem2(float(length), float(target), x0, float(g))
    run, chk = r.run, r.interval
    x0_rule = sentence("p2.x0_rule" if r.x0_from_fourier else "p2.x0_given")
    justification = sentence("p2.justification." + ("positive" if r.curvature_positive else "negative"))
    if as_json:
        d = r.to_dict() | {"x0_rule": x0_rule, "justification": justification}
        for cd, c in zip(d["interval_conditions"], chk.conditions):
            cd["detail"] = condition_text(c)
        emit_json(d)
        return
    e = r.equation
    click.echo(f"f(alpha) = (2 pi/p)(1 + sin^2(alpha/2)/4) - {e.target!r},  p = sqrt(g/l) = {_rounded(e.p)}")
    # The report's digits (pendulab.core.digits): x_k to the rounding level delta, f(x_k) to the
    # rounding of its terms (2 u S), q_k to its rounding error; a value its error swamps as
    # "<= bound". --json keeps every double.
    delta, f_error = run.rounding_level, 2 * U * e.f_scale
    a, b = r.interval_deg
    click.echo(f"interval [a, b] = [{a:g}, {b:g}] deg = [{_rounded(chk.a)}, {_rounded(chk.b)}] rad:")
    for c in chk.conditions:
        click.echo(f"  [{'ok' if c.holds else 'FAILS'}] {condition_text(c)}")
    click.echo(f"x0 = {shown('p2.iterate', r.x0, delta)} ({x0_rule}); {sentence('p2.criterion.' + run.criterion, tol=run.tol)}")
    click.echo(f"{'k':>3} {'x_k (rad)':>22} {'f(x_k)':>12} {'q_k':>18} {'rounding of q_k':>16}")
    for k, x in enumerate(run.iterates):
        rho = shown("p2.relative_rounding", run.q_rounding[k]) if k < len(run.q_rounding) else ""
        qs = _quotient(run.q[k], run.q_rounding[k]) if k < len(run.q) else ""
        mark = "  <- k_max" if k == run.k_max else ""
        click.echo(f"{k:>3} {shown('p2.iterate', x, delta):>22} {shown('p2.residual', run.values[k], f_error):>12} "
                   f"{qs:>18} {rho:>16}{mark}")
    click.echo(f"k_max = {run.k_max}: the last q_k whose rounding error bound is <= 1%")
    q_kmax = (_quotient(run.q_kmax, run.q_rounding[run.k_max]) if run.k_max is not None
              else "none (no q_k free of rounding)")
    constant = "—" if run.asymptotic_constant is None else shown("p2.constant", run.asymptotic_constant)
    click.echo(f"asymptotic constant |f''(z)/(2 f'(z))| = {constant}; q_kmax = {q_kmax}")
    # degrees: delta converted, plus the conversion's own rounding
    deg = math.degrees(delta) + 2 * U * math.degrees(max(abs(r.x0), abs(r.alpha)))
    click.echo(f"alpha = {shown('p2.iterate', r.alpha, delta)} rad = {shown('p2.iterate', r.alpha_deg, deg)} deg  "
               f"(error estimate {shown('p2.error_estimate', run.error_estimate)} rad)")


def _rounded(x: float) -> str:
    """A double a few roundings from its decimal inputs (``sqrt(g/l)``, degrees in radians):
    the digits its error, at most two ulps, leaves right (a repr's 17th digit is not)."""
    return with_error(x, 2 * math.ulp(x))


def _quotient(q: float | None, rho: float) -> str:
    """``q_k`` with the digits its relative rounding error ``rho`` leaves (``<= 0.5`` where none)."""
    if q is None or not math.isfinite(rho):
        return "—"
    return shown("p2.quotient", q, rho * q)


def condition_text(c: Condition) -> str:
    """One sufficient condition of 2(a), named, with its numbers (the catalogue's ``p2.condition.*``)."""
    relation = {"sign_change": ("<", ">="), "step_from_a": ("<=", ">"), "step_from_b": ("<=", ">")}
    pair = relation.get(c.name, ("", ""))
    return sentence(f"p2.condition.{c.name}", relation=pair[0] if c.holds else pair[1], **c.values)


# --------------------------------------------------------------------------- fit
@click.command()
@click.option("-l", "--length", type=LENGTH, default=cases.PROBLEM4.length.text, show_default=True,
              help="Pendulum length l, m: 3.5, 350cm.")
@click.option("-a", "--amplitude", type=ANGLE, default=cases.PROBLEM4.amplitude.text, show_default=True,
              help="Amplitude alpha in [0, pi): 0.785, pi/4, 45deg.")
@click.option("--step", type=DURATION, default=str(cases.PROBLEM4_STEP), show_default=True, help="Taylor step h, s (or 10ms).")
@click.option("--t-max", "t_max", type=DURATION, default=None, show_default="ceil(T^), T^ of (8)",
              help="End of the data, s.")
@click.option("--round", "decimals", type=ROUND, default=str(cases.PROBLEM4_ROUND), show_default=True,
              help="Round the normal equations half away from zero to this many decimals (0..15, or none).")
@click.option("--plot", type=FIGURE, help="Write the data and the fitted phi to this PNG/SVG/PDF.")
@g_option
@json_option
def fit(length, amplitude, step, t_max, decimals, plot, g, as_json):
    """Problem 4: least-squares fit of the Taylor data by basis (10), via the normal equations."""
    from ..jobs.problems import problem4
    from ..numerics.lsq import TRIG_LABELS

    if plot:
        check_plot_path("plot", plot)
    r = problem4(float(length), float(amplitude), float(step), None if t_max is None else float(t_max),
                 decimals, float(g))
    f, d = r.fit, r.fit.definiteness
    if plot:
        from ..plots import problems as plots
        from ._common import save_plot

        save_plot(lambda ax: plots.fit(r, ax), plot)
    answer = sentence("p4.answer." + ("yes" if r.below_tolerance else "no"), deviation=r.fit.max_deviation,
                      at=r.fit.argmax_deviation, tolerance=r.tolerance, exact=r.exact_deviation)
    if as_json:
        emit_json(r.to_dict() | {"answer": answer})
        return
    click.echo(f"l = {r.length!r}, alpha = {r.amplitude!r}, h = {r.step!r}; T^ (8) = {shown('t_hat', r.t_hat)}; "
               f"t_max = {r.t_max:g} ({sentence('p4.t_max.' + r.t_max_rule, t_hat=r.t_hat)}); {r.points} points")
    click.echo("last 10 points (t_j, z1_j):")
    for t, y in r.last_points.tolist():
        click.echo(f"  {t:>8.4g} {y:>20.12f}")
    terms = " + ".join(f"{n} {lab}" if lab != "1" else n for n, lab in zip(f.names, TRIG_LABELS))
    click.echo(f"minimise E({', '.join(f.names)}) = sum_(j=0)^({r.points - 1}) (z1_j - ({terms})|_(t=t_j))^2")
    how = "not rounded" if f.decimals is None else f"rounded half away from zero to {f.decimals} decimals"
    click.echo(f"normal equations A c = r ({how}):")
    w = max(len(f"{x:.{f.decimals if f.decimals is not None else 10}f}") for x in f.normal_matrix.ravel()) + 1
    dec = f.decimals if f.decimals is not None else 10
    for name, row, rhs in zip(f.names, f.normal_matrix.tolist(), f.normal_rhs.tolist()):
        click.echo("  " + " ".join(f"{x:>{w}.{dec}f}" for x in row) + f"  | {rhs:>{w}.{dec}f}   ({name})")
    click.echo(f"symmetric: {d.symmetric}; Cholesky: {'succeeds' if d.cholesky else 'fails'}; "
               f"lambda_min = {d.min_eigenvalue:.6g}, cond_2 = {d.condition_number:.6g}; "
               f"positive definite: {d.positive_definite}")
    click.echo("coefficients:")
    for name, c in f.coefficient_dict().items():
        click.echo(f"  {name:>6} = {c:+.12f}")
    click.echo(f"rounding moves the coefficients by at most {f.coefficient_shift:.3e} (vs numpy.linalg.lstsq)")
    click.echo(f"sum of squared deviations = {f.ssd:.6e}")
    click.echo(f"max |z1_j - phi(t_j)| = {f.max_deviation:.6e} at t = {f.argmax_deviation:g}")
    click.echo(answer)


# --------------------------------------------------------------------------- quadrature
@click.command()
@click.option("-l", "--length", type=LENGTH, default=cases.PROBLEM5.length.text, show_default=True,
              help="Pendulum length l, m: 3.5, 350cm.")
@click.option("-a", "--amplitude", type=ANGLE, default=cases.PROBLEM5.amplitude.text, show_default=True,
              help="Amplitude alpha in [0, pi): 4pi/5, 144deg.")
@click.option("--n", "ns", type=COUNTS, default=",".join(map(str, (1, *cases.PROBLEM5_N))), show_default=True,
              help="Numbers of subintervals, separated by commas or spaces: 1,10,100 or 1 10 100.")
@click.option("--substitution", is_flag=True,
              help="Also integrate after sin(theta/2) = sin(alpha/2) sin(phi), which removes the singularity.")
@click.option("--graded", is_flag=True,
              help="The substituted integral (implies --substitution) on panels graded geometrically towards its "
                   "peak, of width cos(alpha/2): right near pi, where equal panels need n of about 5/cos(alpha/2).")
@g_option
@json_option
def quadrature(length, amplitude, ns, substitution, graded, g, as_json):
    """Problem 5: the period integral (1) by the composite 3-point Gauss rule (11)."""
    from ..jobs.problems import problem5

    substitution = substitution or graded
    r = problem5(float(length), float(amplitude), ns, substitution, float(g), graded=graded)
    last = r.rows[-1].rate
    answer_5a = sentence("p5.answer_5a")
    rate_text = sentence("p5.rate", observed=sentence("p5.rate_none") if last is None else f"{last:.3f}")
    if as_json:
        emit_json(r.to_dict() | {"t_hat_note": t_hat_note(r), "answer_5a": answer_5a, "rate_explanation": rate_text})
        return
    click.echo(f"l = {r.length!r}, alpha = {r.amplitude!r}; T^ (8) = {shown('t_hat', r.t_hat)} s")
    if (note := t_hat_note(r)) is not None:
        click.echo(note)
    # Each error column names its reference: T^ of (8), or T, the correctly rounded period.
    head = f"{'n':>10} {'T ~ S_n':>20} {'|S_n - T^|':>11} {'rate':>6}"
    if substitution:
        head += f" {'T ~ S_n (graded)' if graded else 'T ~ S_n (subst.)':>20} "
        head += f"{'|S_n - T^|' if r.t_hat_converged else '|S_n - T|':>11}"
    click.echo(head)
    for row in r.rows:
        rate = f"{row.rate:6.3f}" if row.rate is not None else f"{'':>6}"
        line = f"{row.n:>10} {row.estimate:>20.15g} {row.error:>11.3e} {rate}"
        if substitution:  # an error at the rounding floor is rounding: the floor it is under, as the report
            sub = (f"<= {bound(r.rounding_floor, 1, sci=True)}" if row.substitution_error <= r.rounding_floor
                   else f"{row.substitution_error:.3e}")
            line += f" {row.substitution_estimate:>20.15g} {sub:>11}"
        click.echo(line)
    click.echo(f"5(a): {answer_5a}")
    click.echo(rate_text)


def t_hat_note(r) -> str | None:
    """One line where ``T^`` (8) of a :class:`~pendulab.jobs.problems.Problem5` is not the period to
    double precision (``t_hat_converged`` false), else None (``null`` in ``--json``)."""
    if r.t_hat_converged:
        return None
    return sentence("p5.t_hat_note", period=r.period, difference=r.t_hat - r.period, ulps=r.t_hat_ulps,
                    limit=FIXED_ITERATIONS_ULPS)
