"""Every number of the report's answers is printed by a program (issue 30).

For five groups in English and Portuguese: the text of the answer sections 1(a)-5(d)
(pdftotext's text of the PDF, from problem 1's heading to the references; the appendix's
listings excluded) is cut into number tokens, and each must appear, as the
same digits, in what the printed programs write when run alone with the group's numbers
(``python problemN.py ...`` as the appendix says, the programs of the same language).
Allowed without a program: the group's student numbers, numbers written in the catalogue
itself (equation, section, figure and table numbers, the coursework's constants), and the
numbers of a sentence the engine's catalogue marker (``engine``) opens, which says that
they come from the engine. Indices written as subscripts (``t_25``) read as part of their
symbol and are not numbers here.

pdftotext reads in ``-raw`` order (the PDF's own): ``-layout`` sets a superscript on a line
of its own where its line holds taller math (``2.046 × 10`` with the ``−3`` a line below,
in 4(d)), and interleaves a paragraph with the caption beside it; ``-raw`` keeps each
power of ten glued to its ``10`` and each sentence whole.
"""
from __future__ import annotations

import functools
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from pendulab.jobs import coursework
from pendulab.report import build_report, load_catalogue
from test_programs import BOOT

GROUPS = [(262, 407, 634), (99999, 1), (83001, 91234, 77777), (45678,), (1000, 2000, 3500)]
#: A number as pdftotext writes the report's: a sign glued to it, a decimal point, and
#: ``× 10`` with its exponent (the superscript comes out glued: ``2.96 × 10-5``); not
#: glued to a letter before it (a subscript, ``t25``) nor inside a longer number.
REPORT_NUMBER = re.compile(r"(?<![\w.,])(-?\d+(?:\.\d+)?)(?: × 10(-?\d+))?(?![\d])")
#: A number as the programs print it: ``2.96e-5``, ``1e-02``, ``-0.36``.
PROGRAM_NUMBER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?)(?:e([-+]?\d+))?(?![\d])")
#: A number written in the catalogue's Typst source (placeholders removed), not a length
#: of its layout (``8.5pt``, ``1fr``).
LITERAL = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?![\d.]|pt|em|fr|cm|mm)")
#: The end of a sentence: a full stop before a space or the end (not a decimal point).
SENTENCE_END = re.compile(r"\.(?=\s|$)")


def canon(mantissa: str, exponent: str | None) -> str:
    """One spelling for one printed number: ``2.96e-5`` for ``2.96 × 10-5`` and ``2.96e-05``."""
    return f"{mantissa}e{int(exponent)}" if exponent else mantissa


def program_numbers(text: str) -> set[str]:
    return {canon(m, e) for m, e in PROGRAM_NUMBER.findall(text)}


@functools.cache
def catalogue_literals(lang: str) -> frozenset[str]:
    """The numbers the report's catalogue writes itself (not through a placeholder; not the
    explorer's words nor the references)."""
    report = {k: v for k, v in load_catalogue(lang).items() if not k.startswith("web.") and k != "refs"}
    text = re.sub(r"\{[^{}]*\}", " ", json.dumps(report, ensure_ascii=False))
    found = LITERAL.findall(text)
    return frozenset(found) | {n.lstrip("-") for n in found}  # a sign may read as an operator


def marker(lang: str) -> str:
    """The words that open a sentence of the engine's numbers, as the PDF shows them."""
    return load_catalogue(lang)["engine"].replace("_", "")


def answers_text(pdf: Path, lang: str) -> str:
    """The answer sections' text, page headers and footers dropped, lines joined."""
    assert shutil.which("pdftotext"), "pdftotext (poppler-utils) is needed to read the PDF"
    text = subprocess.run(["pdftotext", "-raw", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    cat = load_catalogue(lang)
    lines = text.replace("\u2212", "-").splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip().startswith(cat["p1.title"]))
    end = next(i for i, line in enumerate(lines) if line.strip() == cat["refs.title"])
    assert start < end
    kept = [line for line in lines[start:end]
            if not re.fullmatch(r"\s*\d+ / \d+\s*", line) and not line.strip().startswith(cat["doc.short"])]
    return " ".join(" ".join(kept).split())


def unprinted(text: str, printed: set[str], students, lang: str) -> list[str]:
    """The numbers of ``text`` that no program printed and nothing else allows."""
    allowed = printed | catalogue_literals(lang) | {str(s) for s in students}
    mark = marker(lang)
    spans = []
    for m in re.finditer(re.escape(mark), text):
        end = SENTENCE_END.search(text, m.end())
        spans.append((m.start(), end.start() if end else len(text)))
    out = []
    for m in REPORT_NUMBER.finditer(text):
        token = canon(m.group(1), m.group(2))
        if token in allowed or any(a <= m.start() < b for a, b in spans):
            continue
        out.append(f"{token!r} in ...{text[max(0, m.start() - 60):m.end() + 20]}...")
    return out


def run_alone(folder: Path, name: str, *args) -> str:
    done = subprocess.run([sys.executable, "-c", BOOT, str(folder / name), *map(str, args)],
                          capture_output=True, text=True, timeout=300, check=False, cwd=folder)
    assert done.returncode == 0, (name, done.stderr)
    return done.stdout


@functools.cache
def written(lang: str) -> Path:
    folder = Path(tempfile.mkdtemp(prefix=f"pendulab-programs-{lang}-"))
    coursework.write(folder / "programs", lang)
    return folder / "programs"


@functools.cache
def outputs(lang: str, students: tuple[int, ...]) -> str:
    """What every program prints, run alone as the appendix says (the group's numbers
    for those that take them)."""
    folder = written(lang)
    out = []
    for name in coursework.PROGRAMS:
        if name == "digits.py":
            continue
        takes_students = "[STUDENT" in coursework.USAGE[name]
        out.append(run_alone(folder, name, *(students if takes_students else ())))
    return "\n".join(out)


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("students", GROUPS, ids=lambda g: "-".join(map(str, g)))
def test_every_answer_number_is_a_programs(students, lang, tmp_path):
    pdf = tmp_path / "report.pdf"
    build_report(students, lang=lang, output=pdf)
    text = answers_text(pdf, lang)
    assert marker(lang) in text  # the engine's sentences are there, and marked
    tokens = REPORT_NUMBER.findall(text)
    assert len(tokens) > 300  # the answers were read, not an empty page
    missing = unprinted(text, program_numbers(outputs(lang, students)), students, lang)
    assert not missing, "\n".join(missing)


@pytest.mark.slow
def test_a_number_no_program_printed_is_caught(tmp_path, monkeypatch):
    """The same check on a report with one number changed: 2 pi/T^ of 4(d), printed by
    problem4.py, one unit up in its last digit; and a number in an engine sentence
    stays allowed while the same number outside it does not."""
    from pendulab.report import document

    real = document.Doc.set

    def altered(self, **values):
        if "p4.omega" in values:
            values["p4.omega"] = "1.60956"  # problem4.py prints 1.60955
        real(self, **values)

    monkeypatch.setattr(document.Doc, "set", altered)
    students = GROUPS[0]
    pdf = tmp_path / "altered.pdf"
    build_report(students, lang="en", output=pdf)
    text = answers_text(pdf, "en")
    printed = program_numbers(outputs("en", students))
    assert "1.60955" in printed and "1.60956" not in printed
    missing = unprinted(text, printed, students, "en")
    assert len(missing) == 1 and missing[0].startswith("'1.60956'")
    # The engine's marker covers its sentence only: after the full stop, a number is checked.
    assert unprinted("Engine: it is 7.25 × 10-3. The rest is 7.25 × 10-3.", printed, students, "en") == [
        "'7.25e-3' in ...Engine: it is 7.25 × 10-3. The rest is 7.25 × 10-3...."]
