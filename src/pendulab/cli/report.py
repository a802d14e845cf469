"""``pendulab report``: the PDF that answers the whole coursework."""
from __future__ import annotations

import click

from ..cases import EXAMPLE_GROUP
from ..errors import InputError

#: The example group as the option writes it: ``262,407,634``.
EXAMPLE = ",".join(map(str, EXAMPLE_GROUP))


class StudentsType(click.ParamType):
    """Comma-separated student numbers: positive integers, e.g. the example group's."""

    name = "numbers"

    def convert(self, value, param, ctx):
        if isinstance(value, tuple):
            return value
        items = [s.strip() for s in str(value).split(",")]
        if not items or any(not s.isdigit() or int(s) <= 0 for s in items):
            self.fail(
                f"--students = {value!r} is not allowed: must be comma-separated positive integers, e.g. {EXAMPLE}",
                param,
                ctx,
            )
        return tuple(int(s) for s in items)


@click.command()
@click.option(
    "--students",
    type=StudentsType(),
    default=EXAMPLE,
    show_default=True,
    help="The group's student numbers; their digit sum gives the pendulum length of problem 3(b).",
)
@click.option(
    "--lang",
    type=click.Choice(["en", "pt"]),
    default="en",
    show_default=True,
    help="Language of the report: English or Portuguese (the coursework's).",
)
@click.option(
    "--output",
    "-o",
    default="report.pdf",
    show_default=True,
    type=click.Path(dir_okay=False),
    help="Where to write the PDF (atomically: a failed run keeps an older file intact).",
)
def report(students: tuple[int, ...], lang: str, output: str) -> None:
    """Write the coursework report: every question 1(a)-5(d) answered, at most 15 A4 pages."""
    from .._atomic import check_writable
    from .._extras import require
    from ..group import group_length

    for package in ("typst", "matplotlib"):
        require(package, "pendulab report")
    from ..report import build_report

    check_writable("output", output)  # before the work
    if not students:
        raise InputError("students", "", "comma-separated positive integers")
    group_length(students)  # a sum with no non-zero digit fails here, before the work
    build_report(students, lang=lang, output=output, progress=True)
    click.echo(f"pendulab: wrote {output}", err=True)
