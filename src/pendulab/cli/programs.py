"""``pendulab programs``: the coursework programs as files, the ones the report prints."""
from __future__ import annotations

import click

from ._common import choice, emit_json, json_option


@click.command()
@click.option("--output", "-o", required=True, metavar="DIR",
              help="The folder to write them into (created if missing, inside a folder that exists; each file written atomically).")
@click.option("--lang", type=choice("en", "pt"), default="en", show_default=True,
              help="Language of the comments: English or Portuguese (the code is the same).")
@json_option
def programs(output: str, lang: str, as_json: bool) -> None:
    """Write the coursework programs: run them with `python DIR/problem3.py 262 407 634`.

    Plain Python with numpy, scipy and mpmath is enough: they do not import pendulab.
    """
    from ..jobs.coursework import USAGE, write

    written = write(output, lang)
    if as_json:  # the files written, each with how to run it
        emit_json({"output": output, "lang": lang,
                   "files": [{"path": str(path), "usage": USAGE[path.name]} for path in written]})
        return
    for path in written:
        click.echo(f"{path}  ({USAGE[path.name]})")
