"""The document model: the catalogue's prose, this run's values, tables and figures.

Sections fill a :class:`Doc`; :mod:`.typeset` turns it into a PDF. Imports run one way:
``markup`` <- ``document`` <- ``sections`` <- ``builder``.
"""
from __future__ import annotations

import json
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from ..core.errors import InputError

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


@dataclass
class Doc:
    """What the template needs: values for the prose, tables, figures."""

    lang: str
    catalogue: dict[str, Any]
    tmp: Path
    values: dict[str, str] = field(default_factory=dict)
    choices: dict[str, str] = field(default_factory=dict)
    tables: dict[str, Any] = field(default_factory=dict)
    figures: dict[str, str] = field(default_factory=dict)

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

    def text(self) -> dict[str, str]:
        """Every catalogue entry with its ``{placeholders}`` filled (alternatives: the chosen one)."""
        out = {}
        for key in self.catalogue:
            if key.startswith(("text.", "web.")):
                continue  # plain text for other presenters (pendulab.report.words, the explorer), not Typst
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
