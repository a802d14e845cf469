"""The explorer's words: the catalogues' entries under ``web.`` (``report/en.json``, ``pt.json``).

The page and the API's sentences come from the same catalogues as the report, so a
flag reads the same in both languages; numbers are written in the language's form
(a decimal comma in Portuguese).
"""
from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import Any

from ..core.errors import InputError

#: The page's languages, the first the default.
LANGUAGES = ("en", "pt")
PREFIX = "web."


@functools.cache
def catalogue(lang: str) -> dict[str, str]:
    """The ``web.`` entries of ``lang``'s catalogue, without the prefix."""
    from ..report.document import load_catalogue

    return {k[len(PREFIX):]: v for k, v in load_catalogue(lang).items() if k.startswith(PREFIX)}


def language(params: Mapping[str, str]) -> str:
    """``lang`` of a query: ``en`` (the default) or ``pt``."""
    lang = str(params.get("lang") or LANGUAGES[0]).strip().lower()
    if lang not in LANGUAGES:
        raise InputError("lang", lang, "en or pt")
    return lang


def number(x: float, spec: str, lang: str) -> str:
    """``format(x, spec)`` in the language's form: a decimal comma in Portuguese."""
    s = format(x, spec)
    return s.replace(".", ",") if lang == "pt" else s


def say(key: str, lang: str, **values: Any) -> str:
    """The entry ``web.<key>`` of ``lang``, its ``{fields}`` filled with ``values`` (text as given)."""
    return catalogue(lang)[key].format(**values)
