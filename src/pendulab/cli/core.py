"""Commands of the foundation: ``period``, ``simulate``, ``estimate``, ``length``."""
from __future__ import annotations

import math
import os

import click

from ..core.cases import (
    EXAMPLE_GROUP,
    FIGURE3_STEP,
    FIGURE3_T_MAX,
    PROBLEM3_AMPLITUDE,
    PROBLEM3_STEPS,
    PROBLEM5,
)
from ..report.words import sentence
from ._common import (
    ANGLE,
    DURATION,
    DURATION_LIST,
    EXACT_ANGLE,
    FIGURE,
    INSTANT,
    LENGTH,
    METHOD,
    check_plot_path,
    emit_json,
    fmt,
    g_option,
    integer,
    json_option,
    save_plot,
)

_LENGTH_HELP = "Pendulum length l, m (> 0): 2.08, 75cm, 750mm."
_ANGLE_HELP = "Amplitude alpha in [0, pi): 0.785, pi/4, 4pi/5, 45deg, 45°."


#: The most rows simulate prints (table, CSV or JSON): about 100 MB of text.
MAX_PRINTED = 1_000_001


def _method_option(f):
    return click.option(
        "--method", type=METHOD, default="taylor2", show_default=True,
        help="Integrator: taylor2 (the coursework's algorithm (3)), rk4, verlet, or taylor:P (order P, 1..30).",
    )(f)


@click.command()
@click.option("-l", "--length", type=LENGTH, default=PROBLEM5.length.text, show_default=True, help=_LENGTH_HELP)
@click.option("-a", "--amplitude", type=EXACT_ANGLE, default=PROBLEM5.amplitude.text, show_default=True,
              help=_ANGLE_HELP + " Taken exactly: 0.9999999999999999999999999pi is below pi.")
@click.option("--iterations", type=integer(0, 1000), default=None, show_default="to convergence",
              help="Also (8) after this many AGM iterations on doubles (7: the coursework's T^).")
@click.option("--digits", type=integer(1, 10000), default=None, show_default="15; none in --json",
              help="Significant digits of the periods as written, each proved by ball arithmetic (Arb).")
@g_option
@json_option
def period(length, amplitude, iterations, digits, g, as_json):
    """The period by the arithmetic-geometric mean, equations (7)-(8).

    The digits printed are those of the period of the inputs as written (period_as_written),
    correctly rounded and proved by ball arithmetic (Arb). Where the inputs' doubles have
    another period (an amplitude near 180 deg: 0.9999999pi), a second line gives "period",
    the double nearest to the period (8) of the inputs' doubles, which agm_period() returns;
    --json carries both, and with --iterations N "period_iterated", (8) after N iterations on
    doubles (N = 7: the coursework's T^).
    """
    from ..numerics.period import periods

    r = periods(length, amplitude, g, iterations, digits if as_json else digits or 15)
    if as_json:
        note = {} if r.amplitude_double_below_pi else {"period_note": _period_note(r.amplitude_text)}
        emit_json(r.to_dict() | note)
        return
    lines = _period_lines(r.to_dict())
    width = max(34, *(len(label) + 1 for label, _ in lines))
    for label, text in lines:
        click.echo(f"{label:{width}}{text}")


def _period_lines(d: dict) -> list[tuple[str, str]]:
    """The text of ``pendulab period``: each period of :class:`~pendulab.numerics.period.Periods`
    under its glossary name; ``period`` beside ``period_as_written`` only where they differ in
    the digits printed."""
    digits = f"{d['period_digits']} s"
    count = len(d["period_digits"].partition("e")[0].replace(".", "").lstrip("0"))
    if d["period"] is not None and _same_digits(d["period"], d["period_as_written"], count):
        lines = [("period, AGM (7)-(8)", f"T  = {digits}")]
    else:
        lines = [("period_as_written, AGM (7)-(8)", f"T  = {digits}  (amplitude {d['amplitude_text']} as typed)")]
        if d["period"] is None:
            lines.append(("period (the doubles), AGM (7)-(8)", f"T  undefined: {_period_note(d['amplitude_text'])}"))
        else:
            lines.append(("period (the doubles), AGM (7)-(8)",
                          f"T  = {d['period']!r} s  (its double, {d['amplitude']!r}; as agm_period())"))
    lines.append(("small-angle period 2 pi sqrt(l/g)", f"T0 = {d['small_angle_period_digits']} s"))
    if d["iterations"] is not None:
        label = f"(8) after {d['iterations']} iterations, double"
        if d["period_iterated"] is None:
            lines.append((label, f"T^ undefined: {_period_note(d['amplitude_text'])}"))
        else:
            lines.append((label, f"T^ = {d['period_iterated']!r} s"))
    return lines


def _same_digits(a: float, b: float, digits: int) -> bool:
    """Whether ``a`` and ``b`` print as the same number to ``digits`` significant digits
    (beyond 17 digits, whether they are the same double)."""
    return a == b if digits >= 17 else f"{a:.{digits - 1}e}" == f"{b:.{digits - 1}e}"


def _period_note(amplitude_text: str) -> str:
    """Why (8) on doubles has no value: the amplitude is below pi, its double is not."""
    return sentence("period.note", amplitude=amplitude_text)


@click.command()
@click.option("-l", "--length", type=LENGTH, default="1", show_default=True, help=_LENGTH_HELP)
@click.option("-a", "--amplitude", type=ANGLE, default="pi/4", show_default=True, help=_ANGLE_HELP)
@click.option("--step", type=DURATION, default=str(FIGURE3_STEP), show_default=True, help="Step h, s (or 10ms).")
@click.option("--t-max", "t_max", type=INSTANT, default=str(FIGURE3_T_MAX), show_default=True, help="End time, s.")
@click.option("--t0", type=INSTANT, default="0", show_default=True, help="Start time, s.")
@click.option("--digits", type=integer(1, 17), default="12", show_default=True,
              help="Significant digits in the table.")
@click.option("--csv", "as_csv", is_flag=True, help="Print CSV (t,theta,omega) at full precision.")
@click.option("--plot", type=FIGURE, help="Write Figure 1 (t_j, z1_j) to this PNG/SVG/PDF.")
@click.option("--phase", type=FIGURE, help="Write Figure 2 (phase points, P circled) to this PNG/SVG/PDF.")
@_method_option
@g_option
@json_option
def simulate(length, amplitude, step, t_max, t0, digits, as_csv, plot, phase, method, g, as_json):
    """Simulate the pendulum by the Taylor algorithm (3): the table t (s), theta = z1 (rad), omega = z2 (rad/s)."""
    from ..core import validate as v
    from ..numerics.simulation import simulate as run

    t0_, t_max_, h = v.time_span(t0, t_max, float(step))
    v.steps_within("step", t0_, t_max_, h, MAX_PRINTED - 1, "rows printed")  # before anything is allocated
    for name, path in (("plot", plot), ("phase", phase)):
        if path:
            check_plot_path(name, path)
    if plot and phase and os.path.realpath(plot) == os.path.realpath(phase):  # Figure 1 would be overwritten
        from ..core.errors import InputError, shown

        raise InputError("phase", shown(phase), "a file other than --plot's (both figures would be written to it)")
    tr = run(float(length), float(amplitude), float(step), t_max, t0, float(g), method)
    if plot:
        save_plot(lambda ax: _plots().time_series(tr, ax), plot)
    if phase:
        save_plot(lambda ax: _plots().phase_portrait(tr, ax), phase)
    if as_json:
        emit_json(tr.to_dict())
    elif as_csv:
        lines = ["t,theta,omega"] + [f"{a!r},{b!r},{c!r}" for a, b, c in zip(tr.t.tolist(), tr.theta.tolist(), tr.omega.tolist())]
        click.echo("\n".join(lines))
    else:
        w = digits + 8
        lines = [f"{'t':>{w}} {'theta':>{w}} {'omega':>{w}}"]  # the CSV's and to_frame()'s names
        lines += [f"{fmt(a, digits):>{w}} {fmt(b, digits):>{w}} {fmt(c, digits):>{w}}"
                  for a, b, c in zip(tr.t.tolist(), tr.theta.tolist(), tr.omega.tolist())]
        click.echo("\n".join(lines))


def _plots():
    from ..plots import simulation

    return simulation


@click.command()
@click.option("-l", "--length", type=LENGTH, default=None, show_default="2.0800838231, the example group's",
              help="Pendulum length l, m (> 0): 2.08, 75cm, 750mm.")
@click.option("-a", "--amplitude", type=ANGLE, default=PROBLEM3_AMPLITUDE.text, show_default=True, help=_ANGLE_HELP)
@click.option("--step", "steps", type=DURATION_LIST, default=",".join(f"{s:g}" for s in PROBLEM3_STEPS),
              show_default=True, help="Steps h, s, separated by commas or spaces: 1e-2,1e-3 or 1e-2 1e-3.")
@click.option("--t-max", "t_max", type=INSTANT, default=None, show_default="1.5 T + 4h, T the AGM period (8)",
              help="End of the simulation, s.")
@_method_option
@click.option("--dense", is_flag=True,
              help="Add the period from dense output (the zero of theta' on the flow's Taylor series): "
                   "the method's own order, where the cubic stops at O(h^4).")
@g_option
@json_option
def estimate(length, amplitude, steps, t_max, method, dense, g, as_json):
    """The period from simulations (problem 3(c)-(d)): bracket, linear and cubic estimates."""
    from ..core.digits import distance_of, estimate_of, shown
    from ..numerics.crossing import estimate_periods
    from ..numerics.group import group_length

    length = float(length) if length is not None else group_length(EXAMPLE_GROUP).length
    r = estimate_periods(length, float(amplitude), steps, t_max, float(g), method)
    if as_json:
        emit_json(r.to_dict())
        return
    rows, period = r.rows, r.period
    click.echo(f"l = {length!r} m, alpha = {float(amplitude)!r} rad, method {method}")
    click.echo(f"period (AGM, (7)-(8))  T = {shown('t_hat', period)} s; each estimate with the digits its error against T "
               "leaves right (--json: every digit)")
    head = f"{'h':>8} {'bracket [t_j, t_j+1]':>25} {'linear':>18} {'cubic p(0)':>18} {'interp. err. est.':>17} {'|linear - T|':>12} {'|cubic - T|':>12} {'order':>6}"
    if dense:
        head += f" {'dense output':>18} {'|dense - T|':>12}"
    click.echo(head)
    below = outside = False

    # An estimate of T carries the digits its error against T allows: a 15-digit p(0) at
    # h = 1e-2 would claim 10 digits it has not.
    def right(x: float) -> str:
        return estimate_of(x, period)

    prev: tuple[float, float] | None = None
    for e, co in zip(rows, r.cubic_orders):
        br = f"[{e.bracket[0]:.10g}, {e.bracket[1]:.10g}]"
        order = f"{'':>6}" if co is None or prev is None else f"{_order(co, prev, (e.step, e.cubic_error), period):>6}"
        prev = (e.step, e.cubic_error)
        # An estimate below the rounding level of t_k = k h is rounding, not interpolation error.
        est = f"{e.cubic_error_estimate:.3e}"
        if not e.interpolation.error_estimate_resolved:
            est, below = f"<{e.interpolation.rounding_level:.1e}*", True
        cubic = right(e.cubic)
        if not e.cubic_in_bracket:  # no estimate of the period: flagged, not hidden
            cubic, outside = cubic + "!", True
        line = (f"{e.step:>8g} {br:>25} {right(e.linear):>18} {cubic:>18} {est:>17} "
                f"{distance_of(e.linear, period):>12} {distance_of(e.cubic, period):>12} {order}")
        if dense:
            line += f" {right(e.dense):>18} {distance_of(e.dense, period):>12}"
        click.echo(line)
    if below:
        click.echo("* below the rounding level of t_k = k h: the estimate there is rounding, not interpolation error")
    if outside:
        click.echo("! outside its bracket [t_j, t_j+1], where theta' changes sign: the step is too large for this "
                   "amplitude and the cubic estimates nothing (--json: cubic_in_bracket false)")


def _order(order: float, before: tuple[float, float], now: tuple[float, float], period: float) -> str:
    """The observed order ``log(e_0/e_1)/log(h_0/h_1)`` with the digits the errors' rounding
    (``period``'s half ulp each) leaves, 2 decimals at most; ``noise`` where it leaves none."""
    from ..core.digits import with_error

    half = math.ulp(period) / 2
    (h0, e0), (h1, e1) = before, now
    error = ((half + math.ulp(e0)) / e0 + (half + math.ulp(e1)) / e1) / math.log(10) / abs(math.log10(h0 / h1))
    if not error < 0.5:
        return "noise"
    return with_error(order, error) if error > 0.005 else f"{order:.2f}"


@click.command()
@click.argument("numbers", nargs=-1, required=True)
@json_option
def length(numbers, as_json):
    """The pendulum length of a group of students, problem 3(b): 262 407 634 -> 2.0800838231.

    NUMBERS are separated by spaces, commas or both: 262 407 634, 262,407,634.
    """
    from ..core import inputs
    from ..core.errors import InputError
    from ..numerics.group import group_length

    nums = inputs.students("numbers", list(numbers))
    try:
        res = group_length(nums)
    except InputError as exc:  # the library calls them students; here they are NUMBERS
        raise InputError("numbers", exc.value, exc.allowed) from None
    if as_json:
        emit_json(res.to_dict())
        return
    click.echo(res.length_text)
