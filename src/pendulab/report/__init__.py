"""The coursework report: every problem computed, then typeset with Typst into a PDF.

``build_report(students, lang, output)`` is the entry point (``pendulab report``).
"""
from .builder import LANGUAGES, build_report, load_catalogue

__all__ = ["LANGUAGES", "build_report", "load_catalogue"]
