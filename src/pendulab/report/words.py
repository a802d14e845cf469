"""The library's sentences in plain text, from the report's catalogues (``report/en.json``, ``pt.json``).

Results carry decisions (booleans, numbers); the words for them live in one place, the
catalogues, whose entries under ``text.`` are plain text with ``str.format`` fields. The
command line shows them in English; the PDF has its own Typst entries.
"""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

#: The catalogues, beside this module and the report's template.
CATALOGUES = Path(__file__).resolve().parent


@functools.cache
def _catalogue(lang: str) -> dict[str, Any]:
    return json.loads((CATALOGUES / f"{lang}.json").read_text(encoding="utf-8"))


def sentence(key: str, lang: str = "en", **values: Any) -> str:
    """The plain-text entry ``text.<key>`` of the ``lang`` catalogue, its fields filled with ``values``."""
    entry = _catalogue(lang)[f"text.{key}"]
    return ("\n".join(entry) if isinstance(entry, list) else entry).format(**values)
