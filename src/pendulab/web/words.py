"""The explorer's words: the catalogues' entries under ``web.`` (``report/en.json``, ``pt.json``).

The page and the API's sentences come from the same catalogues as the report, so a
flag reads the same in both languages; numbers are written in the language's form
(a decimal comma in Portuguese).
"""
from __future__ import annotations

import functools
import re
from collections.abc import Mapping
from typing import Any

from ..core.errors import InputError, shown, shown_value

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
        raise InputError("lang", shown(lang), "en or pt")  # quoted when unprintable: one line
    return lang


def number(x: float, spec: str, lang: str) -> str:
    """``format(x, spec)`` in the language's form: a decimal comma in Portuguese."""
    s = format(x, spec)
    return s.replace(".", ",") if lang == "pt" else s


def say(key: str, lang: str, **values: Any) -> str:
    """The entry ``web.<key>`` of ``lang``, its ``{fields}`` filled with ``values`` (text as given)."""
    return catalogue(lang)[key].format(**values)


def allowed(text: str, lang: str) -> str:
    """An :class:`~pendulab.core.errors.InputError`'s allowed range (or its value's
    ``(missing)``) in ``lang``: each phrase of the catalogue's ``web.allowed.`` entries, the
    longest first, replaced by its translation, and a decimal comma in Portuguese. English
    text is returned as it is."""
    if lang == LANGUAGES[0]:
        return text
    for en, there in _phrases(lang):
        text = text.replace(en, there)
    return re.sub(r"(?<=\d)\.(?=\d)", ",", text) if lang == "pt" else text


@functools.cache
def _phrases(lang: str) -> tuple[tuple[str, str], ...]:
    en, there = catalogue(LANGUAGES[0]), catalogue(lang)
    pairs = [(en[k], there[k]) for k in en if k.startswith("allowed.")]
    return tuple(sorted(pairs, key=lambda p: -len(p[0])))


def message(exc: InputError, lang: str) -> str:
    """``exc``'s one line in ``lang``: ``length = 0 não é permitido: deve ser ...`` in
    Portuguese (the field by its word, ``field.<name>``, where the catalogue has one); in
    English ``str(exc)`` itself."""
    if lang == LANGUAGES[0]:
        return str(exc)
    name = catalogue(lang).get(f"field.{exc.name}", exc.name)
    where = name if exc.index is None else f"{name}[{', '.join(map(str, exc.index))}]"
    value = shown_value(exc.value)  # as typed; only a stand-in such as (missing) is translated,
    value = dict(_phrases(lang)).get(value, value)  # or a note after it, such as " (smallest)"
    for en, there in _phrases(lang):
        if en.startswith(" (") and value.endswith(en):
            value = value[: -len(en)] + there
            break
    return say("error.not-allowed", lang, field=where, value=value, allowed=allowed(exc.allowed, lang))


def safe_language(params: Mapping[str, object]) -> str:
    """:func:`language` of a query, or the default where ``lang`` itself is bad (its own
    error is then written in the default language)."""
    try:
        return language({"lang": str(params.get("lang") or "")})
    except InputError:
        return LANGUAGES[0]
