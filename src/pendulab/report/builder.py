"""Build the coursework report: compute every problem, draw, typeset with Typst.

The flow: each section of :mod:`.sections` runs the coursework programs
(:mod:`pendulab.jobs.coursework`; the engine for what goes beyond the coursework), formats
their numbers (:mod:`.markup`) and records values, tables and figures in a
:class:`~.document.Doc`; the catalogue of the chosen language
(``en.json`` / ``pt.json``) supplies the prose, whose ``{placeholders}`` are filled with
those numbers; ``report.typ`` lays it all out (:mod:`.typeset`), the programs whole in
the appendix. Nothing in the PDF is typed in by hand: every number comes from this run.
"""
from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from . import sections
from .document import LANGUAGES, Doc, check_lang, load_catalogue
from .typeset import breakable, needs_system_fonts, typeset

__all__ = ["LANGUAGES", "build_report", "compile_pdf", "load_catalogue", "section_data"]


class _Quiet:
    """A stand-in for the progress bar when stderr is not a terminal."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def add_task(self, *a, **k):
        return 0

    def update(self, *a, **k):
        pass

    def advance(self, *a, **k):
        pass


class _Bar:
    """The report's progress on stderr: click's bar, the same as ``pendulab sweep``'s."""

    def __init__(self) -> None:
        self._label = ""
        self._bar: Any = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._bar is not None:
            self._bar.__exit__(*exc)
        return False

    def add_task(self, description: str, total: int) -> int:
        import click

        self._label = description
        self._bar = click.progressbar(length=total, label="report", file=sys.stderr,
                                      item_show_func=lambda _: self._label)
        self._bar.__enter__()
        return 0

    def update(self, task: int, description: str) -> None:
        self._label = description
        self._bar.render_progress()

    def advance(self, task: int) -> None:
        self._bar.update(1)


def _progress(show: bool) -> _Quiet | _Bar:
    return _Bar() if show and sys.stderr.isatty() else _Quiet()


def new_doc(students: Sequence[int], lang: str, folder: Path) -> Doc:
    doc = Doc(lang, load_catalogue(lang), folder)
    doc.set(students=", ".join(map(str, students)), **{"students.csv": ",".join(map(str, students))})
    doc.set(engine=doc.word("engine"))  # the words that open a sentence of the engine's numbers
    return doc


def section_data(students: Sequence[int], lang: str, folder: Path, only: Sequence[str] | None = None) -> Doc:
    """Run the sections (those labelled in ``only``, default all) for ``students``: the Doc, not typeset."""
    doc = new_doc(tuple(students), check_lang(lang), Path(folder))
    for label, section in sections.SECTIONS:
        if only is None or label in only:
            section(doc, tuple(students))
    return doc


def appendix(lang: str) -> list[dict[str, str]]:
    """The programs the sections ran, whole, in ``lang``: file name, how to run it, source."""
    from ..jobs import coursework

    return [{"name": name, "run": coursework.usage(name, lang), "source": coursework.source(name, lang)}
            for name in coursework.PROGRAMS]


def compile_pdf(doc: Doc, students: Sequence[int], names: Sequence[str] | None = None) -> bytes:
    """Typeset ``doc``: its text filled, tables, figures, and the programs in the appendix;
    ``names`` (one per student number) go on the cover beside the numbers."""
    data = {
        "lang": doc.lang,
        "students": ", ".join(str(s) for s in students),
        # Plain strings, never markup: a name is printed as typed, whatever its characters.
        "cover": [{"name": breakable(n), "number": str(s)} for n, s in zip(names or (), students)],
        "t": doc.text(),
        "tables": doc.tables,
        "figures": doc.figures,
        "code": appendix(doc.lang),
    }
    return typeset(doc.tmp, "report.typ", data, system_fonts=needs_system_fonts(names or ()))


def build_report(
    students: Sequence[int],
    lang: str = "en",
    output: str | os.PathLike = "report.pdf",
    progress: bool = False,
    names: Sequence[str] | None = None,
) -> Path:
    """Compute every problem for the group ``students`` and write the PDF to ``output``.

    ``names``, one per student number and in their order, go on the cover.

    The inputs are checked before any work (a bad ``output`` folder fails at once); the
    PDF is written atomically, so a failed run leaves an older ``output`` intact.

    Returns
    -------
    Path
        ``output``.
    """
    from ..core.atomic import check_writable, temp_folder, write_bytes
    from ..numerics.group import group_length

    check_lang(lang)
    out = check_writable("output", output)
    students = tuple(students)
    group_length(students)  # bad student numbers fail before the work
    if names is not None:
        from ..core.inputs import names as parse_names

        names = parse_names("names", ";".join(names), len(students))
    steps = sections.SECTIONS
    with temp_folder("pendulab-report-") as tmp, _progress(progress) as bar:
        task = bar.add_task("starting", total=len(steps) + 1)
        doc = new_doc(students, lang, Path(tmp))
        for label, section in steps:
            bar.update(task, description=label)
            section(doc, students)
            bar.advance(task)
        bar.update(task, description="typesetting")
        pdf = compile_pdf(doc, students, names)
        bar.advance(task)
    write_bytes(out, pdf)
    return out
