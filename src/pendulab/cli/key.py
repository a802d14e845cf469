"""``pendulab key``: the teacher's answer key for many groups."""
from __future__ import annotations

import click

from ..core import inputs
from ._common import Parsed, output


@click.command()
@click.option("--groups", "groups_file", required=True, type=Parsed(lambda s: inputs.path_text("groups", s), "file"),
              help="A text file, one group per line: student numbers separated by commas or spaces, "
                   "optionally followed by '|' and the students' names separated by ';' "
                   "(262, 407, 634 | Ana Sá; João Simões; Maria Luís). Blank lines and # comments allowed; "
                   "- reads standard input. At most 1000 groups.")
@click.option("--output", "-o", default=None, type=output(".csv", ".json", ".pdf"),
              help="Write the key to this file: .csv (one row per group; the class-wide answers and "
                   "the marking tolerances go to NAME-class.csv beside it), .json or .pdf (atomically).")
@click.option("--json", "as_json", is_flag=True, help="Print the key as one JSON document on stdout.")
def key(groups_file: str, output: str | None, as_json: bool) -> None:
    """The answers of every group (problem 3) and the common answers (problems 1, 2, 4, 5) once."""
    from ..core.atomic import check_not_input, check_writable
    from ..jobs import key as answer
    from ._common import emit_json

    # Every input checked before the work: the whole file, the output path and format.
    groups = answer.read_entries(groups_file)
    if output is not None:
        fmt = answer.output_format(output)
        check_writable("output", output)
        if fmt == "csv":
            check_writable("output", answer.class_path(output))  # written beside it
        if groups_file != "-":
            for path in (output, answer.class_path(output)) if fmt == "csv" else (output,):
                check_not_input("output", path, "groups", groups_file)
        if fmt == "pdf":
            from ..core.extras import require

            require("typst", "pendulab key --output FILE.pdf")
    again = answer.listed_again(groups)
    if again:
        from ..report.words import sentence

        listed = "; ".join(sentence("key.listed_again.group", students=" ".join(map(str, students)),
                                    lines=", ".join(map(str, lines))) for students, lines in again)
        warning = sentence("key.listed_again." + ("one" if len(again) == 1 else "many"), count=len(again), groups=listed)
        click.echo(f"pendulab: warning: {warning}", err=True)
    repeated = answer.repeated_students(groups)
    if repeated:
        from ..report.key import repeated_words

        for r in repeated:
            for words in repeated_words(r.to_dict()):
                click.echo(f"pendulab: warning: {words}", err=True)
    k = answer.answer_key(groups)
    if output is not None:
        from ..report.key import write_key

        write_key(k, output)
        from ..core.errors import printable

        also = f" and {printable(answer.class_path(output))}" if fmt == "csv" else ""
        click.echo(f"pendulab: wrote {printable(output)}{also} ({len(groups)} groups)", err=True)
    if as_json:
        from ..report.key import document

        emit_json(document(k))
    elif output is None:
        _table(k)


def _table(k) -> None:
    """A plain-text summary: one line per group."""
    for name, answers in k.common.items():
        click.echo(f"# {name}: " + ", ".join(f"{a}={v}" for a, v in answers.items() if not isinstance(v, list)))
    click.echo(f"{'students':<28} {'l':>13} {'T^':>18} {'3(b) h=0.2':>18} " +
               " ".join(f"{'p(0) h=' + format(e['step'], 'g'):>18}" for e in k.groups[0]["estimates"]))
    for g in k.groups:
        p = g["plot"]
        shown = (f"[{p['bracket'][0]:.4g}, {p['bracket'][1]:.4g}]" if p["outcome"] == "returns"
                 else f"leaves at {p['left_at']:.4g}" if p["outcome"] == "leaves" else "no return")
        click.echo(f"{' '.join(map(str, g['students'])):<28} {g['length_text']:>13} {g['t_hat']:>18.15g} "
                   f"{shown:>18} " + " ".join(f"{e['cubic']:>18.15g}" for e in g["estimates"]))
