"""The coursework programs: short, literal Python files a student hands in.

The files in ``programs/`` (package data, not a package) answer the coursework's problems
with the standard library, numpy, scipy and mpmath only, never this package: the report
runs them for its coursework numbers and prints them whole, ``pendulab programs`` writes
them out, and the tests check the engine against them. Each runs as ``python FILE
[STUDENT ...]`` from the folder that holds them all (a problem's program imports the
shared methods ``agm``, ``taylor``, ``length`` and ``digits`` beside it; ``plots.py``, with
matplotlib, imports the problems' programs and draws the report's figures).

The Portuguese set differs from the English one in its comments and docstrings only:
``programs/pt.json`` maps each such English line to its translation.
"""
from __future__ import annotations

import functools
import importlib
import json
import os
import sys
from importlib import resources
from pathlib import Path
from types import ModuleType

from ..core.errors import InputError

#: The programs in the order the report prints them: shared methods first.
PROGRAMS = ("digits.py", "length.py", "agm.py", "taylor.py", "problem1.py", "problem2.py", "problem3.py",
            "problem4.py", "problem5.py", "plots.py")
#: How to run each one (the appendix's header line).
USAGE = {
    "digits.py": "(imported by the problems' programs)",
    "length.py": "python length.py [STUDENT ...]",
    "agm.py": "python agm.py [STUDENT ...]",
    "taylor.py": "python taylor.py",
    "problem1.py": "python problem1.py",
    "problem2.py": "python problem2.py",
    "problem3.py": "python problem3.py [STUDENT ...]",
    "problem4.py": "python problem4.py",
    "problem5.py": "python problem5.py",
    "plots.py": "python plots.py [STUDENT ...]",
}
LANGUAGES = ("en", "pt")
#: The words of :data:`USAGE` in each language other than English.
_USAGE_WORDS = {"pt": {"STUDENT": "ALUNO", "(imported by the problems' programs)": "(importado pelos programas)"}}


def usage(name: str, lang: str = "en") -> str:
    """How to run program ``name``, in ``lang`` (the appendix's header line)."""
    text = USAGE[name]
    for word, translated in _USAGE_WORDS.get(lang, {}).items():
        text = text.replace(word, translated)
    return text


def _folder():
    return resources.files("pendulab").joinpath("programs")


@functools.cache
def _translations(lang: str) -> dict[str, str]:
    if lang == "en":
        return {}
    return json.loads(_folder().joinpath(f"{lang}.json").read_text(encoding="utf-8"))


def source(name: str, lang: str = "en") -> str:
    """The text of program ``name`` in ``lang``: comment and docstring lines translated."""
    if name not in PROGRAMS:
        raise InputError("name", name, "one of " + ", ".join(PROGRAMS))
    if lang not in LANGUAGES:
        raise InputError("lang", lang, "one of " + ", ".join(LANGUAGES))
    text = _folder().joinpath(name).read_text(encoding="utf-8")
    table = _translations(lang)
    if not table:
        return text
    out = []
    for line in text.splitlines(keepends=True):
        body = line.rstrip("\n")
        out.append(table.get(body, body) + line[len(body):])
    return "".join(out)


def write(folder: str | os.PathLike, lang: str = "en") -> list[Path]:
    """Write every program into ``folder`` (created if missing), the files as one
    (:func:`pendulab.core.atomic.write_together`): all new, or all as they were."""
    from ..core.atomic import write_together
    from ..core.inputs import path_text, shown

    if lang not in LANGUAGES:
        raise InputError("lang", lang, "one of " + ", ".join(LANGUAGES))
    allowed = "a folder to write the programs into (created if missing, inside a folder that exists)"
    out = Path(path_text("output", folder, allowed))
    paths = []
    try:
        if out.exists() and not out.is_dir():
            raise InputError("output", shown(str(folder)), allowed + "; this is a file")
        out.mkdir(exist_ok=True)  # one level, as mkdir does: a mistyped path is refused, not built
        paths = [out / name for name in PROGRAMS]
        write_together([(p, source(p.name, lang).encode("utf-8")) for p in paths])
    except OSError as exc:  # not writable, a name too long, and the like
        raise InputError("output", shown(str(folder)), f"{allowed} ({exc.strerror})") from None
    return paths


@functools.cache
def load() -> dict[str, ModuleType]:
    """The programs imported as modules, by file name (``"problem3.py"``).

    Imported from their own folder, as ``python problem3.py`` would import its siblings;
    their names (``agm``, ``taylor``, ...) are taken out of ``sys.modules`` and
    ``sys.path`` again afterwards, and any module of the same name put back.
    """
    with resources.as_file(_folder()) as folder:
        names = [p.removesuffix(".py") for p in PROGRAMS]
        saved = {n: sys.modules.pop(n) for n in names if n in sys.modules}
        sys.path.insert(0, str(folder))
        try:
            modules = {f"{n}.py": importlib.import_module(n) for n in names}
        finally:
            sys.path.remove(str(folder))
            for n in names:
                sys.modules.pop(n, None)
            sys.modules.update(saved)
    return modules
