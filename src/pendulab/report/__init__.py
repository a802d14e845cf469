"""The coursework report: every problem computed, then typeset with Typst into a PDF.

``build_report(students, lang, output)`` is the entry point (``pendulab report``). The
names load :mod:`.builder` on first use (PEP 562), so the command line's sentences
(:mod:`.words`) cost no import of the report's machinery.
"""
from __future__ import annotations

from ..core.extras import lazy

TYPE_CHECKING = False
if TYPE_CHECKING:
    from .builder import LANGUAGES, build_report, load_catalogue

_WHERE = {"LANGUAGES": "builder", "build_report": "builder", "load_catalogue": "builder"}
__all__ = ["LANGUAGES", "build_report", "load_catalogue"]
__getattr__, __dir__ = lazy(__name__, _WHERE, __all__)
