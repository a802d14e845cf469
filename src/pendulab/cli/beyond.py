"""Commands beyond the coursework: ``approximations`` and ``sweep``."""
from __future__ import annotations

import re
import sys

import click

from ..core import inputs
from ..core.errors import InputError, printable
from ._common import (
    DURATION_LIST,
    FIGURE,
    LENGTH,
    Parsed,
    check_plot_path,
    emit_json,
    g_option,
    json_option,
    output,
    save_plot,
)

#: The most amplitudes in one sweep range.
MAX_COUNT = 1_000_000


def _methods(text: str) -> list[str]:
    """Integrator names separated by commas or spaces, each one of :mod:`pendulab.core.methods`."""
    from ..core import methods

    return [m.name for m in inputs.parse_list("method", text, inputs.method, methods.allowed(), 100)]


def _array(values: list[float]):
    import numpy as np

    return np.asarray(values)


def _scheduler(text: str) -> str:
    """A Dask scheduler address, ``tcp://host:port`` (or ``tls://``)."""
    s = text.strip()
    if not re.fullmatch(r"(tcp|tls)://[A-Za-z0-9.\-\[\]:]+", s, re.ASCII):
        raise InputError("scheduler", inputs.shown(s), "a Dask scheduler address such as tcp://10.0.0.1:8786")
    return s


#: ``START:STOP:COUNT`` (``1deg:179deg:1000``: COUNT evenly spaced angles, both ends
#: included) or a single angle; every angle in (0, pi).
ANGLE_RANGE = Parsed(lambda s: _array(inputs.angle_range("amplitude", s, MAX_COUNT)), "range")
METHOD_LIST = Parsed(_methods, "methods")
SCHEDULER = Parsed(_scheduler, "address")


@click.command()
@click.option("--plot", type=FIGURE,
              help="Write the relative error of every formula over [0, 180) degrees to this PNG/SVG/PDF.")
@json_option
def approximations(plot, as_json):
    """Classical period formulas against the AGM period: relative errors.

    Small angle, the coursework's (9), Kidd-Fogg, Lima-Arun, Ganley, and the AGM
    truncated after 1, 2, 3 iterations (Carvalhaes-Suppes).
    """
    from ..core.digits import with_error
    from ..numerics.approximations import REACH_TOLERANCES, approximation_errors, approximation_table, rounding_error

    if plot:
        check_plot_path("plot", plot)
    fine = approximation_errors()  # 1000 amplitudes, 0.1 to 179.9 degrees
    table = approximation_table(fine)
    if plot:
        from ..plots.beyond import approximation_errors as draw

        save_plot(lambda ax: draw(fine, ax), plot, (7.0, 4.6))
    if as_json:
        emit_json(table.to_dict())
        return
    names = [f.name for f in table.formulas]
    click.echo("relative error T_approx/T - 1 (T: AGM to convergence)")
    click.echo(f"{'alpha (deg)':>11} " + " ".join(f"{n:>12}" for n in names))
    for i, deg in enumerate(table.amplitudes_deg):
        # at most 4 significant digits, and only those its rounding leaves (<= 4e-15 where it swamps)
        click.echo(f"{deg:>11g} " + " ".join(f"{with_error(r, rounding_error(r), 4):>12}"
                                             for r in (float(f.relative_errors[i]) for f in table.formulas)))
    click.echo("")
    click.echo("largest amplitude (deg) up to which |error| stays within")
    click.echo(f"{'formula':>12} " + " ".join(f"{t:>8g}" for t in REACH_TOLERANCES))
    for f in table.formulas:
        click.echo(f"{f.name:>12} " + " ".join(f"{f.max_amplitude_deg_within[f'{t:g}']:>8.1f}" for t in REACH_TOLERANCES))
    click.echo("")
    for f in table.formulas:
        click.echo(f"{f.name}: {f.formula}  [{f.source}]")
    if plot:
        click.echo(f"wrote {printable(plot)}")


def _sweep_errors(rows: dict, summary: dict) -> tuple[str, str]:
    """The largest ``|T_cubic - T|`` and relative error of one (method, step), to at most 4
    significant digits and those the periods' rounding leaves: each ``T`` is the correctly
    rounded double, half an ulp from the true period, so a 1e-13 error of rk4 carries two."""
    import math

    import numpy as np

    from ..core.digits import with_error

    ok = rows["status"] == "found"
    if not ok.any():
        return "nan", "nan"
    largest, rel = summary["max_abs_cubic_error"], summary["max_rel_cubic_error"]
    error = 0.5 * math.ulp(float(np.max(rows["period"][ok]))) + math.ulp(largest)
    return (with_error(largest, error, 4),
            with_error(rel, error / float(np.min(rows["period"][ok])) + math.ulp(rel), 4))


@click.command()
@click.option("-a", "--amplitude", "amplitudes", type=ANGLE_RANGE, default="1deg:179deg:1000", show_default=True,
              help="Amplitudes START:STOP:COUNT (both ends included), e.g. 1deg:179deg:1000.")
@click.option("--step", "steps", type=DURATION_LIST, default="1e-3,1e-4", show_default=True,
              help="Steps h, s, separated by commas or spaces.")
@click.option("--method", "methods", type=METHOD_LIST, default="taylor2,rk4,verlet", show_default=True,
              help="Integrators, separated by commas or spaces: taylor2, rk4, verlet, taylor:P.")
@click.option("-l", "--length", type=LENGTH, default="1", show_default=True, help="Pendulum length l, m: 1, 75cm.")
@click.option("--output", "-o", type=output(".csv", ".parquet"), help="Write every pendulum's row to this .csv or .parquet.")
@click.option("--plot", type=FIGURE, help="Write |period error| against amplitude to this PNG/SVG/PDF.")
@click.option("--scheduler", type=SCHEDULER, metavar="ADDRESS", help="Run on this Dask scheduler (tcp://host:8786).")
@g_option
@json_option
def sweep(amplitudes, steps, methods, length, output, plot, scheduler, g, as_json):
    """The period error of each method over a range of amplitudes (many pendulums at once)."""
    from ..core.extras import require
    from ..jobs.sweep import sweep as run

    if output:
        require("pyarrow", f"--output {output}")
    if scheduler:
        require("dask.distributed", "--scheduler")
    if plot:
        check_plot_path("plot", plot)
    total = len(amplitudes) * len(steps) * len(methods)
    if sys.stderr.isatty():
        with click.progressbar(length=total, label="pendulums", file=sys.stderr) as bar:
            result = run(amplitudes, steps, methods, float(length), float(g), progress=bar.update, scheduler=scheduler)
    else:  # no progress lines in a log: stderr keeps to errors
        result = run(amplitudes, steps, methods, float(length), float(g), scheduler=scheduler)
    if output:
        result.write(output)
    if plot:
        from ..plots.beyond import sweep_errors

        save_plot(lambda ax: sweep_errors(result, ax), plot, (7.0, 4.6))
    d = result.to_dict()
    if as_json:  # the result, and the files written
        emit_json(d | {"output": output, "plot": plot})
        return
    click.echo(f"{'method':>10} {'h':>8} {'found':>11} {'max |T_cubic - T|':>18} {'max rel':>10} {'steps':>12}")
    for r in d["summary"]:
        abs_text, rel_text = _sweep_errors(result.select(r["method"], r["step"]), r)
        click.echo(f"{r['method']:>10} {r['step']:>8g} {r['found']:>5}/{r['pendulums']:<5} "
                   f"{abs_text:>18} {rel_text:>10} {r['pendulum_steps']:>12}")
    for path in (output, plot):
        if path:
            click.echo(f"wrote {printable(path)}")
