"""The environment numba reads at its import, checked first: a value numba would fail on
later, deep in a run (``NUMBA_NUM_THREADS=0`` raises ``ValueError`` at the first parallel
kernel), or answer with a traceback in a warning (``NUMBA_OPT=9``), is dropped with one
note line, and the work is done with numba's default."""
from __future__ import annotations

import os
from collections.abc import Callable, MutableMapping


def _whole_at_least(least: int) -> Callable[[str], bool]:
    def ok(text: str) -> bool:
        try:
            return int(text.strip()) >= least
        except ValueError:
            return False

    return ok


#: numba's settings checked: name -> (whether a text is allowed, the allowed values in words).
CHECKS: dict[str, tuple[Callable[[str], bool], str]] = {
    "NUMBA_NUM_THREADS": (_whole_at_least(1), "a whole number >= 1"),
    "NUMBA_OPT": (lambda t: t.strip() in ("0", "1", "2", "3", "max"), "0, 1, 2, 3 or max"),
}


def odd_numba_settings(environ: MutableMapping[str, str] = os.environ) -> list[str]:
    """Drop from ``environ`` each setting of :data:`CHECKS` whose value is not allowed;
    return a note line for each dropped."""
    notes = []
    for name, (allowed, words) in CHECKS.items():
        text = environ.get(name)
        if text is None or allowed(text):
            continue
        del environ[name]
        shown = text if text.isprintable() and len(text) <= 20 else repr(text[:20])
        notes.append(f"pendulab: note: {name}={shown} is not allowed ({words}): ignored, numba's default is used")
    return notes
