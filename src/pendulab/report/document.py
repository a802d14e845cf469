"""The document model: the catalogue's prose, this run's values, tables, figures, listings.

Sections fill a :class:`Doc`; :mod:`.typeset` turns it into a PDF. Imports run one way:
``markup`` <- ``document`` <- ``sections`` <- ``builder``.
"""
from __future__ import annotations

import ast
import inspect
import json
import re
import sys
import textwrap
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from ..errors import InputError

LANGUAGES = ("en", "pt")
#: A placeholder no section filled is an error (False only while drafting the catalogue).
STRICT = True


def check_lang(lang: str) -> str:
    if lang not in LANGUAGES:
        raise InputError("lang", lang, "one of " + ", ".join(LANGUAGES))
    return lang


def load_catalogue(lang: str) -> dict[str, Any]:
    """The prose of the report in ``lang``."""
    text = resources.files(__package__).joinpath(f"{check_lang(lang)}.json").read_text(encoding="utf-8")
    return json.loads(text)


@dataclass(frozen=True)
class Constant:
    """A module-level constant whose value the report uses: listed with its comment."""

    module: str
    name: str


@dataclass
class Doc:
    """What the template needs: values for the prose, tables, figures, listings."""

    lang: str
    catalogue: dict[str, Any]
    tmp: Path
    values: dict[str, str] = field(default_factory=dict)
    choices: dict[str, str] = field(default_factory=dict)
    tables: dict[str, Any] = field(default_factory=dict)
    figures: dict[str, str] = field(default_factory=dict)
    programs: list[Callable | Constant] = field(default_factory=list)

    def word(self, key: str) -> str:
        """A catalogue entry as one string (lists are lines)."""
        entry = self.catalogue[key]
        return "\n".join(entry) if isinstance(entry, list) else entry

    def set(self, **values: str) -> None:
        self.values.update(values)

    def choose(self, key: str, option: str) -> None:
        """Pick the catalogue entry ``key.option`` for ``key`` (a conclusion that depends on numbers)."""
        if f"{key}.{option}" not in self.catalogue:
            raise KeyError(f"catalogue ({self.lang}) has no entry {key}.{option}")
        self.choices[key] = f"{key}.{option}"

    def figure(self, name: str, paint: Callable, **size: float) -> None:
        """Draw ``paint(ax)`` in the report's style (:func:`.figures.draw`) as figure ``name``."""
        from .figures import draw

        self.figures[name] = draw(paint, self.tmp / f"{name}.svg", **size)

    def listing(self, *programs: Callable | Constant) -> None:
        """Record functions and constants whose source goes into the appendix (the code that ran)."""
        for p in programs:
            if p not in self.programs:
                self.programs.append(p)

    def text(self) -> dict[str, str]:
        """Every catalogue entry with its ``{placeholders}`` filled (alternatives: the chosen one)."""
        out = {}
        for key in self.catalogue:
            if key.startswith("text."):
                continue  # plain text for other presenters (pendulab.words), not Typst
            parent = key.rsplit(".", 1)[0]
            if parent in self.choices and self.choices[parent] != key:
                continue  # an alternative not taken: its numbers may not exist
            out[key] = self._fill(key, self.word(key))
        for key, chosen in self.choices.items():
            out[key] = out[chosen]
        return out

    def entry(self, key: str) -> str:
        """One entry with its placeholders filled (for a choice: the alternative taken)."""
        chosen = self.choices.get(key, key)
        return self._fill(chosen, self.word(chosen))

    def _fill(self, key: str, text: str) -> str:
        def repl(m: re.Match) -> str:
            name = m.group(1)
            if name not in self.values:
                if not STRICT:
                    return "#text(fill: red)[MISSING " + name + "]"
                raise KeyError(f"catalogue entry {key!r} ({self.lang}) uses {{{name}}}, which no section set")
            return self.values[name]

        return re.sub(r"\{([A-Za-z][A-Za-z0-9_.]*)\}", repl, text)

    def listings(self, index_only: frozenset[str] = frozenset()) -> tuple[list[dict[str, str]], list[dict[str, str]]]:
        """The appendix: an index of every program, and the blocks of source to print.

        Each index entry has the program's ``name``, ``where`` (``file:line``) and ``printed``
        (``"no"`` for the names in ``index_only``). The constants of one module are printed
        together, in the module's order, as one block.
        """
        index, blocks = [], []
        constants: dict[str, list[tuple[int, str]]] = {}
        for p in self.programs:
            entry = program_source(p)
            shown = entry["name"] not in index_only
            index.append({"name": entry["name"], "where": entry["where"], "printed": "yes" if shown else "no"})
            if not shown:
                continue
            if entry["kind"] == "constant":
                module, line = entry["where"].split(":")
                constants.setdefault(module, []).append((int(line), entry["source"]))
            else:
                blocks.append({"title": f"{entry['name']} ({entry['where']})", "source": entry["source"]})
        for module, items in constants.items():
            blocks.append({"title": f"constants of {module}",
                           "source": "\n".join(src for _, src in sorted(set(items)))})
        return index, blocks


# ----------------------------------------------------------------------------- listings
def _trim_docstring(doc: str) -> str:
    """The docstring's first paragraph: what the program computes (the rest restates the
    signature or the references, and the 15 pages have no room for it)."""
    return doc.strip().split("\n\n")[0]


def _function_source(func: Callable) -> dict[str, str]:
    func = getattr(func, "py_func", func)  # numba dispatchers keep the Python function
    lines, first = inspect.getsourcelines(func)
    src = textwrap.dedent("".join(lines))
    node = ast.parse(src).body[0]
    body = getattr(node, "body", [])
    text = src.splitlines()
    first_stmt = body[0] if body else None
    if (isinstance(first_stmt, ast.Expr) and isinstance(first_stmt.value, ast.Constant)
            and isinstance(first_stmt.value.value, str)):
        d0, d1 = first_stmt.lineno - 1, first_stmt.end_lineno
        indent = text[d0][: len(text[d0]) - len(text[d0].lstrip())]
        doc = _trim_docstring(inspect.cleandoc(first_stmt.value.value))
        quoted = ('"""' + doc + '"""').splitlines()
        text = text[:d0] + [indent + q if q else "" for q in quoted] + text[d1:]
    module = func.__module__.removeprefix("pendulab.")
    path = Path(inspect.getsourcefile(func) or "?").name
    text = [line for line in text if line.strip()]  # blank lines: paper, not program
    return {"name": f"{module}.{func.__qualname__}", "where": f"{path}:{first}", "source": "\n".join(text),
            "kind": "function"}


def _constant_source(c: Constant) -> dict[str, str]:
    """The assignment of ``c`` in its module with the comment lines just above it."""
    module = sys.modules.get(c.module) or __import__(c.module, fromlist=["_"])
    src = inspect.getsource(module)
    lines = src.splitlines()
    for node in ast.parse(src).body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        if any(isinstance(t, ast.Name) and t.id == c.name for t in targets):
            start = node.lineno - 1
            while start > 0 and lines[start - 1].lstrip().startswith("#"):
                start -= 1
            path = Path(inspect.getsourcefile(module) or "?").name
            return {"name": f"{c.module.removeprefix('pendulab.')}.{c.name}", "where": f"{path}:{node.lineno}",
                    "source": "\n".join(lines[start:node.end_lineno]), "kind": "constant"}
    raise LookupError(f"{c.module} assigns no constant {c.name}")


def program_source(p: Callable | Constant) -> dict[str, str]:
    """Name, ``file:line`` and source (docstring trimmed of its signature sections)."""
    return _constant_source(p) if isinstance(p, Constant) else _function_source(p)
