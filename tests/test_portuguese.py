"""The Portuguese of the report and the programs: one spelling standard, European Portuguese
after the 1990 agreement (as IST writes today). A word list of the forms that agreement
retired (the silent c and p: exacto, recta, correcção, óptimo, ...) must find none in the
catalogue, the report's Typst templates, the programs' translations or the programs as
``--lang pt`` writes them (their comments, docstrings and printed words); and no English
word is left in the Portuguese text (``degrees``, ``doubles``, ``negligible``, ``STUDENT``)."""
from __future__ import annotations

import io
import json
import re
import tokenize
from importlib import resources

import pytest

from pendulab.jobs import coursework

#: Pre-1990 spellings and the forms of 1990 that replace them (European Portuguese keeps
#: the consonant it pronounces: secção, facto, contacto, óptico are not in the list).
RETIRED = {
    "exacto": "exato", "exacta": "exata", "exactos": "exatos", "exactas": "exatas",
    "exactamente": "exatamente", "exactidão": "exatidão",
    "recta": "reta", "rectas": "retas", "rectângulo": "retângulo", "rectangular": "retangular",
    "correcto": "correto", "correcta": "correta", "correctos": "corretos", "correctamente": "corretamente",
    "correcção": "correção", "correcções": "correções",
    "óptimo": "ótimo", "óptima": "ótima", "óptimos": "ótimos", "optimização": "otimização",
    "actual": "atual", "actualmente": "atualmente", "acção": "ação", "acções": "ações",
    "direcção": "direção", "efectivo": "efetivo", "efectivamente": "efetivamente", "efectuar": "efetuar",
    "efectua": "efetua", "objecto": "objeto", "objectivo": "objetivo", "projecção": "projeção",
    "selecção": "seleção", "colecção": "coleção", "excepção": "exceção", "excepto": "exceto",
    "respectivo": "respetivo", "respectiva": "respetiva", "respectivamente": "respetivamente",
    "afectar": "afetar", "afecta": "afeta", "detectar": "detetar", "eléctrico": "elétrico",
    "concepção": "conceção", "recepção": "receção", "adoptar": "adotar", "adoptado": "adotado",
    "factor": "fator", "factores": "fatores", "factorização": "fatorização", "factoriza": "fatoriza",
    "factorizar": "fatorizar", "fracção": "fração", "fracções": "frações",
    "vector": "vetor", "vectores": "vetores", "vectorial": "vetorial",
    "bissecção": "bisseção", "intersecção": "interseção", "subtracção": "subtração",
    "contracção": "contração", "reacção": "reação", "aspecto": "aspeto", "perspectiva": "perspetiva",
    "director": "diretor", "anti-simétrica": "antissimétrica", "semi-recta": "semirreta",
    "Janeiro": "janeiro", "Fevereiro": "fevereiro", "Dezembro": "dezembro",
}
WORD = re.compile(r"[A-Za-zÀ-ÿ-]+")
#: English words a Portuguese sentence has no use for (names of code, in backquotes or
#: format fields, aside).
ENGLISH = re.compile(r"\b(the|of|and|with|from|is|by|degrees|doubles?|negligible|rounding|error|"
                     r"STUDENT|below|above|steps?|points?|estimate|bound)\b")


def retired(text: str) -> list[str]:
    return sorted({w for w in WORD.findall(text) if w in RETIRED or w.lower() in RETIRED})


def _values(entry) -> str:
    return "\n".join(entry) if isinstance(entry, list) else str(entry)


def test_the_catalogue_writes_1990_spelling():
    table = json.loads(resources.files("pendulab.report").joinpath("pt.json").read_text(encoding="utf-8"))
    found = {key: retired(_values(v)) for key, v in table.items() if retired(_values(v))}
    assert found == {}


@pytest.mark.parametrize("name", coursework.PROGRAMS)
def test_the_programs_write_1990_spelling(name):
    assert retired(coursework.source(name, "pt")) == []


def test_the_templates_write_1990_spelling():
    templates = [f for f in resources.files("pendulab.report").iterdir() if f.name.endswith(".typ")]
    assert {f.name for f in templates} >= {"report.typ", "key.typ", "mark.typ"}
    assert {f.name: retired(f.read_text(encoding="utf-8")) for f in templates} == {
        f.name: [] for f in templates}


def _prose(text: str) -> str:
    """Words, without code names: backquoted code, placeholders and format fields dropped."""
    return re.sub(r"`[^`]*`|\{[^{}]*\}", " ", text)


def test_no_english_word_in_the_portuguese():
    table = json.loads(resources.files("pendulab.report").joinpath("pt.json").read_text(encoding="utf-8"))
    report = {key: ENGLISH.findall(_prose(_values(v))) for key, v in table.items()
              if not key.startswith("web.") and key != "refs"}  # the references cite English titles
    assert {k: v for k, v in report.items() if v} == {}
    programs = {}
    for name in coursework.PROGRAMS:
        text = coursework.source(name, "pt")
        words = [t.string for t in tokenize.generate_tokens(io.StringIO(text).readline)
                 if t.type in (tokenize.COMMENT, tokenize.STRING)
                 and not re.fullmatch(r"['\"]\w+['\"]", t.string)]  # a key ("error") is code
        found = ENGLISH.findall(_prose(" ".join(words)))
        if found:
            programs[name] = found
    assert programs == {}
    assert ENGLISH.findall("2(a) [55, 60] degrees") == ["degrees"]  # the check can fail


def test_the_list_finds_what_it_lists():
    """The check can fail: each retired form is found, and its 1990 form is not."""
    for old, new in RETIRED.items():
        assert retired(f"o valor {old}.") == [old]
        assert retired(f"o valor {new}.") == []
