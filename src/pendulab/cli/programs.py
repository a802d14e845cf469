"""``pendulab programs``: the coursework programs as files, the ones the report prints."""
from __future__ import annotations

import click

from ._common import choice


@click.command()
@click.option("--output", "-o", required=True, metavar="DIR",
              help="The folder to write them into (created if missing; each file written atomically).")
@click.option("--lang", type=choice("en", "pt"), default="en", show_default=True,
              help="Language of the comments: English or Portuguese (the code is the same).")
def programs(output: str, lang: str) -> None:
    """Write the coursework programs: run them with `python DIR/problem3.py 262 407 634`.

    Plain Python with numpy, scipy and mpmath is enough: they do not import pendulab.
    """
    from ..coursework import USAGE, write

    for path in write(output, lang):
        click.echo(f"{path}  ({USAGE[path.name]})")
