"""``pendulab key``: the teacher's answer key for many groups."""
from __future__ import annotations

import click

from ..core import inputs
from ._common import Parsed, choice, output


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
@click.option("--template", type=choice("answers", "scheme"), is_flag=False, flag_value="answers", default=None,
              help="Instead of the key: the answers file to fill in for pendulab mark (a CSV, one row per group "
                   "of --groups, one column per question), or with 'scheme' the default marking scheme (JSON: "
                   "points and the fewest significant digits per question), on stdout or to --output.")
@click.option("--csv-dialect", "dialect", type=choice("excel", "excel-pt"), default="excel", show_default=True,
              help="The template's CSV: excel (',') or excel-pt (';' and a byte order mark).")
def key(groups_file: str, output: str | None, as_json: bool, template: str | None, dialect: str) -> None:
    """The answers of every group (problem 3) and the common answers (problems 1, 2, 4, 5) once."""
    from ..core.atomic import check_not_input, check_writable
    from ..jobs import key as answer
    from ._common import emit_json

    # Every input checked before the work: the whole file, the output path and format.
    groups = answer.read_entries(groups_file)
    if template is not None:
        _template(groups, template, output, dialect, groups_file)
        return
    if output is not None:
        fmt = answer.output_format(output)
        check_writable("output", output)
        if fmt == "csv":
            check_writable("output", answer.class_path(output))  # written beside it
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
    from ..report.key import repeated_warning

    repeated = repeated_warning(answer.repeated_students(groups))
    if repeated:
        click.echo(f"pendulab: warning: {repeated}", err=True)
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
        if p["status"] == "untrusted":  # near the separatrix: the return says nothing of the period
            shown += " untrusted"
        click.echo(f"{' '.join(map(str, g['students'])):<28} {g['length_text']:>13} {g['t_hat']:>18.15g} "
                   f"{shown:>18} " + " ".join(f"{e['cubic']:>18.15g}" for e in g["estimates"]))


def _template(groups, template: str, output: str | None, dialect: str, groups_file: str) -> None:
    """``key --template``: the answers file or the marking scheme, written or printed."""
    import sys

    from ..jobs import mark as marking
    from ..report.mark import scheme_json, template_csv

    data = (template_csv(marking.template_rows(groups), dialect) if template == "answers"  # type: ignore[arg-type]
            else scheme_json(marking.default_scheme()))
    if output is None:
        sys.stdout.write_bytes(data)  # type: ignore[union-attr]  # the command's checked stdout
        return
    from ..core.atomic import check_not_input, write_bytes

    if groups_file != "-":
        check_not_input("output", output, "groups", groups_file)
    write_bytes(output, data)
    click.echo(f"pendulab: wrote {output}", err=True)


@click.command()
@click.option("--groups", "groups_file", required=True, type=Parsed(lambda s: inputs.path_text("groups", s), "file"),
              help="The class's groups file, as for pendulab key (a header row, ';' or ',' or spaces, names).")
@click.option("--answers", "answers_file", required=True,
              type=Parsed(lambda s: inputs.path_text("answers", s), "file"),
              help="The groups' answers: a CSV with the columns of pendulab key --template, one row per group "
                   "(',' or ';' between cells; decimal commas with ';').")
@click.option("--scheme", "scheme_file", default=None, type=Parsed(lambda s: inputs.path_text("scheme", s), "file"),
              help="A marking scheme (JSON, pendulab key --template scheme); default one point per question.")
@click.option("--output", "-o", default=None, type=output(".csv", ".json", ".txt", ".pdf"),
              help="Write the marked sheet: .csv (one row per group and question), .json, .txt or .pdf "
                   "(with the class summary and a histogram of marks), atomically.")
@click.option("--json", "as_json", is_flag=True,
              help="Print one JSON document: per group its points, max_points and each answer's verdict.")
@click.option("--csv-dialect", "dialect", type=choice("excel", "excel-pt"), default="excel", show_default=True,
              help="The sheet's CSV: excel (',' and a decimal point) or excel-pt (';', a decimal comma "
                   "and a byte order mark, for a spreadsheet in a Portuguese locale).")
@click.option("--lang", type=choice("en", "pt"), default="en", show_default=True,
              help="The language of the verdicts and reasons.")
def mark(groups_file: str, answers_file: str, scheme_file: str | None, output: str | None, as_json: bool,
         dialect: str, lang: str) -> None:
    """Mark the class's answers against the key: each answer right or wrong, and why."""
    from ..core.atomic import check_not_input
    from ..jobs import key as answer
    from ..jobs import mark as marking
    from ..report import mark as sheet
    from ._common import emit_json

    groups = answer.read_entries(groups_file)
    rows = marking.read_answers(answers_file)
    scheme = None if scheme_file is None else marking.read_scheme(scheme_file)
    if output is not None:
        fmt = sheet.output_format(output)
        for name, path in (("groups", groups_file), ("answers", answers_file), ("scheme", scheme_file)):
            if path is not None and path != "-":
                check_not_input("output", output, name, path)
        if fmt == "pdf":
            from ..core.extras import require

            require("typst", "pendulab mark --output FILE.pdf")
    from ..report.key import repeated_warning

    repeated = repeated_warning(answer.repeated_students(groups), lang)
    if repeated:
        click.echo(f"pendulab: warning: {repeated}", err=True)
    marks = marking.mark_class(groups, rows, scheme, answers_file)
    if output is not None:
        sheet.write_marks(marks, output, lang, dialect)  # type: ignore[arg-type]
        click.echo(f"pendulab: wrote {output} ({len(marks.groups)} groups)", err=True)
    if as_json:
        emit_json(sheet.document(marks, lang))
    elif output is None:
        click.echo(sheet.text(marks, lang), nl=False)
