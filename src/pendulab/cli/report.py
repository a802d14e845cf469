"""``pendulab report``: the PDF that answers the whole coursework."""
from __future__ import annotations

import gc

import click

from ..core import inputs
from ..core.cases import EXAMPLE_GROUP
from ..core.errors import printable
from ._common import Parsed, choice, emit_json, json_option, output

#: The example group as the option writes it: ``262,407,634``.
EXAMPLE = ",".join(map(str, EXAMPLE_GROUP))
STUDENTS = Parsed(lambda s: s, "numbers")  # checked with the extra NUMBERS, in the command


@click.command()
@click.argument("more", nargs=-1, metavar="[NUMBERS]...")
@click.option(
    "--students",
    type=STUDENTS,
    default=EXAMPLE,
    show_default=True,
    help="The group's student numbers, separated by commas or spaces; their digit sum gives the "
         "pendulum length of problem 3(b). More numbers may follow as arguments: --students 1234 5678.",
)
@click.option(
    "--lang",
    type=choice("en", "pt"),
    default="en",
    show_default=True,
    help="Language of the report: English or Portuguese (the coursework's).",
)
@click.option(
    "--output",
    "-o",
    default="report.pdf",
    show_default=True,
    type=output(".pdf"),
    help="Where to write the PDF (atomically: a failed run keeps an older file intact).",
)
@click.option(
    "--names",
    default=None,
    metavar="TEXT",
    help="The students' names for the cover, separated by ';', one per student number and in "
         "their order: --names \"Ana Sá; João Simões; Maria Luís\".",
)
@json_option
def report(more: tuple[str, ...], students: str, lang: str, output: str, names: str | None, as_json: bool) -> None:
    """Write the coursework report: every question 1(a)-5(d) answered, at most 15 A4 pages.

    --json prints what it wrote (the file, its size, its language) and the answers the
    report states, as `pendulab key --json` gives them for this group.
    """
    # The cycle collector paused for the one report, from the imports on: its passes over
    # the many objects of matplotlib's modules and figures cost several per cent of a warm
    # report's CPU time, and one report's cycles (a few figures) are small.
    was = gc.isenabled()
    gc.disable()
    try:
        from ..core.extras import require
        from ..numerics.group import group_length

        for package in ("typst", "matplotlib"):
            require(package, "pendulab report")
        from ..report import build_report

        ctx = click.get_current_context()
        given = ctx.get_parameter_source("students") is not click.core.ParameterSource.DEFAULT
        # --students 1234 5678 and 1234 5678 alone both mean the group (1234, 5678).
        numbers = inputs.students("students", ([students] if given or not more else []) + list(more))
        group_length(numbers)  # a sum with no non-zero digit fails here, before the work
        cover = None if names is None else inputs.names("names", names, len(numbers))
        written = build_report(numbers, lang=lang, output=output, progress=True, names=cover)
    finally:
        # Every object the report made moves to the oldest generation unexamined: else the
        # first collection after gc.enable() would pass over all of them (as long as a
        # figure takes). A later full collection frees them; the command line exits first.
        gc.freeze()
        gc.unfreeze()
        if was:
            gc.enable()
    click.echo(f"pendulab: wrote {printable(output)}", err=True)
    if as_json:  # the file written, and the answers: the key's document for this one group
        from ..jobs.key import Entry, answer_key
        from ..report.key import document

        answers = document(answer_key([Entry(numbers, cover)]))
        emit_json({"output": str(written), "bytes": written.stat().st_size, "lang": lang, "answers": answers})
