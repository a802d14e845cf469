"""Build the coursework report: compute every problem, draw, typeset with Typst.

The flow: each ``_section_*`` function calls the library (``pendulab.problems`` and the
numerics), formats the numbers into Typst markup and records tables and figures in a
:class:`Doc`; the catalogue of the chosen language (``en.json`` / ``pt.json``) supplies
the prose, whose ``{placeholders}`` are filled with those numbers; ``report.typ`` lays it
all out. Nothing in the PDF is typed in by hand: every number comes from this run.
"""
from __future__ import annotations

import ast
import inspect
import json
import math
import os
import re
import shutil
import sys
import tempfile
import textwrap
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Callable, Sequence

from ..errors import InputError

LANGUAGES = ("en", "pt")
#: A placeholder no section filled is an error (False only while drafting the catalogue).
STRICT = True
#: The document date (PDF metadata): fixed so that the same inputs give the same bytes;
#: ``SOURCE_DATE_EPOCH`` (the reproducible-builds convention) overrides it.
DEFAULT_DATE = (2020, 1, 6)  # the coursework's deadline


# ----------------------------------------------------------------------------- formatting
def _sup(exp: int) -> str:
    return f"10#super[{'−' if exp < 0 else ''}{abs(exp)}]"


def num(x: float, digits: int = 10) -> str:
    """``x`` to ``digits`` significant digits as Typst markup (``1.2 × 10^-5`` when tiny)."""
    if x is None or not math.isfinite(x):
        return "—"
    s = f"{x:.{digits}g}"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant} × {_sup(int(exp))}"
    return s.replace("-", "−")


def sci(x: float, digits: int = 3) -> str:
    """``x`` in scientific notation, ``digits`` significant digits."""
    if x is None or not math.isfinite(x):
        return "—"
    if x == 0:
        return "0"
    mant, exp = f"{x:.{digits - 1}e}".split("e")
    return f"{mant.replace('-', '−')} × {_sup(int(exp))}"


def fixed(x: float, decimals: int) -> str:
    """``x`` with ``decimals`` decimals (the rounding of ``format``: half to even on the double)."""
    return f"{x:.{decimals}f}".replace("-", "−")


def integer(n: int) -> str:
    return f"{n:d}"


# ----------------------------------------------------------------------------- the document
@dataclass
class Doc:
    """What the template needs: values for the prose, tables, figures, listings."""

    lang: str
    catalogue: dict[str, Any]
    tmp: Path
    values: dict[str, str] = field(default_factory=dict)
    choices: dict[str, str] = field(default_factory=dict)
    tables: dict[str, list[list[str]]] = field(default_factory=dict)
    figures: dict[str, str] = field(default_factory=dict)
    code: list[dict[str, str]] = field(default_factory=list)
    functions: list[Callable] = field(default_factory=list)

    def word(self, key: str) -> str:
        """A catalogue entry as one string (lists are lines)."""
        entry = self.catalogue[key]
        return "\n".join(entry) if isinstance(entry, list) else entry

    def set(self, **values: str) -> None:
        for k, v in values.items():
            self.values[k] = v

    def choose(self, key: str, option: str) -> None:
        """Pick the catalogue entry ``key.option`` for ``key`` (a conclusion that depends on numbers)."""
        self.choices[key] = f"{key}.{option}"

    def figure(self, name: str, fig) -> None:
        from .figures import save_svg

        self.figures[name] = save_svg(fig, self.tmp / f"{name}.svg")

    def listing(self, *funcs: Callable) -> None:
        """Record functions whose source goes into the appendix (the code that ran)."""
        for f in funcs:
            if f not in self.functions:
                self.functions.append(f)

    def text(self) -> dict[str, str]:
        """Every catalogue entry with its ``{placeholders}`` filled (alternatives: the chosen one)."""
        out = {}
        for key in self.catalogue:
            parent = key.rsplit(".", 1)[0]
            if parent in self.choices and self.choices[parent] != key:
                continue  # an alternative not taken: its numbers may not exist
            out[key] = self._fill(key, self.word(key))
        for key, chosen in self.choices.items():
            out[key] = out[chosen]
        return out

    def _fill(self, key: str, text: str) -> str:
        def repl(m: re.Match) -> str:
            name = m.group(1)
            if name not in self.values:
                if not STRICT:
                    return "#text(fill: red)[MISSING " + name + "]"
                raise KeyError(f"catalogue entry {key!r} ({self.lang}) uses {{{name}}}, which no section set")
            return self.values[name]

        return re.sub(r"\{([A-Za-z][A-Za-z0-9_.]*)\}", repl, text)


# ----------------------------------------------------------------------------- listings
def _source(func: Callable) -> dict[str, str]:
    """The source of ``func`` as it ran, docstring left out (it is prose, not program)."""
    func = getattr(func, "py_func", func)  # numba dispatchers keep the Python function
    lines, first = inspect.getsourcelines(func)
    src = textwrap.dedent("".join(lines))
    tree = ast.parse(src)
    node = tree.body[0]
    drop: set[int] = set()
    body = getattr(node, "body", [])
    if body and isinstance(body[0], ast.Expr) and isinstance(getattr(body[0], "value", None), ast.Constant):
        if isinstance(body[0].value.value, str):
            drop = set(range(body[0].lineno - 1, body[0].end_lineno))
    kept = [line for i, line in enumerate(src.splitlines()) if i not in drop]
    module = func.__module__.removeprefix("pendulab.")
    path = Path(inspect.getsourcefile(func)).name
    return {"name": f"{module}.{func.__qualname__}", "where": f"{path}:{first}", "source": "\n".join(kept)}


# ----------------------------------------------------------------------------- build
def _check_lang(lang: str) -> str:
    if lang not in LANGUAGES:
        raise InputError("lang", lang, "one of " + ", ".join(LANGUAGES))
    return lang


def load_catalogue(lang: str) -> dict[str, Any]:
    """The prose of the report in ``lang``."""
    text = resources.files(__package__).joinpath(f"{_check_lang(lang)}.json").read_text(encoding="utf-8")
    return json.loads(text)


def _timestamp() -> int:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch and epoch.strip().isdigit():
        return int(epoch)
    import calendar

    return calendar.timegm((*DEFAULT_DATE, 12, 0, 0))


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


def _progress(show: bool):
    if not (show and sys.stderr.isatty()):
        return _Quiet()
    from rich.console import Console
    from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    return Progress(
        SpinnerColumn(),
        TextColumn("[bold]report[/bold] {task.description}"),
        BarColumn(),
        TimeElapsedColumn(),
        console=Console(stderr=True),
        transient=True,
    )


def compile_pdf(doc: Doc, students: Sequence[int]) -> bytes:
    """Write ``data.json`` and the template into ``doc.tmp`` and typeset them."""
    import typst

    doc.code = [_source(f) for f in doc.functions]
    data = {
        "lang": doc.lang,
        "students": ", ".join(str(s) for s in students),
        "t": doc.text(),
        "tables": doc.tables,
        "figures": doc.figures,
        "code": doc.code,
    }
    (doc.tmp / "data.json").write_text(json.dumps(data, ensure_ascii=False, indent=1), encoding="utf-8")
    template = resources.files(__package__).joinpath("report.typ")
    shutil.copyfile(str(template), doc.tmp / "report.typ")
    return typst.compile(
        str(doc.tmp / "report.typ"),
        root=str(doc.tmp),
        ignore_system_fonts=True,  # the embedded fonts only: the same PDF on every machine
        timestamp=_timestamp(),
    )


def build_report(
    students: Sequence[int],
    lang: str = "en",
    output: str | os.PathLike = "report.pdf",
    progress: bool = False,
) -> Path:
    """Compute every problem for the group ``students`` and write the PDF to ``output``.

    The inputs are checked before any work (a bad ``output`` folder fails at once); the
    PDF is written atomically, so a failed run leaves an older ``output`` intact.

    Returns
    -------
    Path
        ``output``.
    """
    from .._atomic import check_writable, write_bytes
    from ..group import group_length
    from . import sections

    _check_lang(lang)
    out = check_writable("output", output)
    students = tuple(students)
    group_length(students)  # bad student numbers fail before the work
    steps = sections.SECTIONS
    with tempfile.TemporaryDirectory(prefix="pendulab-report-") as tmp, _progress(progress) as bar:
        task = bar.add_task("starting", total=len(steps) + 1)
        doc = Doc(lang, load_catalogue(lang), Path(tmp))
        doc.set(students=", ".join(map(str, students)), **{"students.csv": ",".join(map(str, students))})
        for label, section in steps:
            bar.update(task, description=label)
            section(doc, students)
            bar.advance(task)
        bar.update(task, description="typesetting")
        pdf = compile_pdf(doc, students)
        bar.advance(task)
    write_bytes(out, pdf)
    return out
