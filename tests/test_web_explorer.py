"""The explorer in Debian's Chromium at the five screens of ``_browser.VIEWPORTS``: axe-core
finds no accessibility violation (en and pt, with and without a bad input), the Portuguese
page has no English word left, and the boxes a classroom needs lie where it needs them (the
phone's first screen, the projector, the controls beside the swing, nothing clipped).

References: axe-core 4.10.3 (tests/vendor, its rules, not the page's); the Portuguese words
of the catalogue file ``report/pt.json`` read here with ``json``, and a fixed list of symbols,
units and proper names.
"""
from __future__ import annotations

import json
import math
import re
from importlib import resources
from pathlib import Path

import pytest

from _browser import VIEWPORTS, record_errors

AXE = Path(__file__).resolve().parent / "vendor" / "axe.min.js"
RK4_HALF = "length=1&amplitude=30&unit=deg&step=0.5&t_max=20&method=rk4"




def _open(browser, server, query: str, width: int, height: int):
    """The page at ``/?query`` once its first render and its seven plots are done."""
    context = browser.new_context(viewport={"width": width, "height": height})
    pg = record_errors(context.new_page())
    pg.goto(f"{server}/?{query}")
    pg.wait_for_function("document.body.dataset.shown === '1' && "
                         "document.querySelectorAll('.js-plotly-plot .main-svg').length >= 7", timeout=90_000)
    return context, pg


def _errors(pg) -> list[str]:
    """The page's errors, less Chromium's note of each 422 that a bad input asks for."""
    return [e for e in pg.errors if "status of 422" not in e]


def _bad_input(pg, field: str = "length", bad: str = "0") -> None:
    pg.fill(f"#{field}", bad)
    pg.wait_for_selector(f"#{field}-error:not([hidden])", timeout=90_000)


# ---------------------------------------------------------------- axe-core

AXE_RUN = """() => axe.run(document, {resultTypes: ['violations']}).then(r => r.violations.map(v =>
  ({id: v.id, impact: v.impact, help: v.help, nodes: v.nodes.map(n => n.target.join(' ') + ': ' + n.failureSummary)})))"""


def _violations(pg) -> list[dict]:
    if not pg.evaluate("typeof axe !== 'undefined'"):
        pg.add_script_tag(path=str(AXE))
    return pg.evaluate(AXE_RUN)


def _readable(found: list[dict]) -> str:
    return "\n".join(f"{v['id']} ({v['impact']}): {v['help']}\n    " + "\n    ".join(v["nodes"][:8]) for v in found)


def test_the_vendored_axe_is_the_named_release():
    head = AXE.read_text(encoding="utf-8")[:200]
    assert head.startswith("/*! axe v4.10.3") and "Mozilla Public" in head
    assert (AXE.parent / "axe-core.LICENSE.txt").read_text(encoding="utf-8").startswith("Mozilla Public License, version 2.0")


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("width, height", VIEWPORTS)
def test_axe_finds_no_violation(browser, server, width, height, lang):
    context, pg = _open(browser, server, f"lang={lang}", width, height)
    try:
        found = {"normal": _violations(pg)}
        pg.evaluate("document.getElementById('lab-details').open = true")  # the lab's controls too
        found["lab open"] = _violations(pg)
        _bad_input(pg)
        assert pg.get_attribute("#length", "aria-invalid") == "true"  # the error state is shown
        found["bad length"] = _violations(pg)
        assert all(v == [] for v in found.values()), "\n".join(f"[{k}]\n{_readable(v)}" for k, v in found.items() if v)
        assert _errors(pg) == []
    finally:
        context.close()


@pytest.mark.slow
def test_axe_finds_a_violation_it_is_shown(browser, server):
    """The check above can fail: an image without a name is one of axe's violations."""
    context, pg = _open(browser, server, "lang=en", 1400, 900)
    try:
        pg.evaluate("document.getElementById('canvas').removeAttribute('aria-label')")
        found = _violations(pg)
        assert [v["id"] for v in found] == ["role-img-alt"], _readable(found)
    finally:
        context.close()


# ---------------------------------------------------------------- no English word in Portuguese

def _portuguese_words() -> set[str]:
    text = resources.files("pendulab.report").joinpath("pt.json").read_text(encoding="utf-8")
    values = [v for v in json.loads(text).values() if isinstance(v, str)]
    return {w.lower() for v in values for w in WORD.findall(v)}


#: A word: a run of Latin letters (Greek letters, digits and subscripts are symbols).
WORD = re.compile(r"[A-Za-zÀ-ÖØ-öø-ÿ]+")

#: Symbols, units, names and identifiers that the Portuguese page writes as the English one does.
ALLOWED = {
    "agm", "rk", "runge", "kutta", "verlet", "störmer", "taylor", "euler", "api", "csv", "png", "pendulab",
    "english", "português", "rad", "deg", "s", "ms", "m", "cm", "mm", "kg", "j", "g", "l", "h", "t", "p", "e", "x",
    "max", "sqrt", "sin", "cos", "ln", "f", "fa", "a", "pi", "omega", "gamma", "beta", "theta",
}

#: English words that would give a page left half translated away, whatever the catalogue holds.
ENGLISH = {
    "the", "of", "is", "not", "allowed", "must", "be", "with", "and", "or", "waiting", "for", "bob", "period", "step",
    "length", "second", "zoom", "pan", "reset", "download", "autoscale", "plot", "number", "unit", "default",
    "finite", "classical", "symplectic", "velocity", "form", "algorithm", "order", "photogate", "pause", "play",
    "speed", "time", "such", "between", "missing", "method", "damping", "energy", "error", "estimate",
}

#: Every text a person reads or hears: the title, the body's text (the lab opened), the labels,
#: tooltips and placeholders, the options of every menu and Plotly's own buttons.
SHOWN_TEXT = """() => {
  for (const d of document.querySelectorAll('details')) d.open = true;
  const out = [document.title, document.body.innerText];
  for (const e of document.querySelectorAll('[title], [aria-label], [placeholder], [data-title], [alt]'))
    for (const a of ['title', 'aria-label', 'placeholder', 'data-title', 'alt']) if (e.getAttribute(a)) out.push(e.getAttribute(a));
  for (const o of document.querySelectorAll('option, optgroup')) out.push(o.textContent, o.label || '');
  return out.join('\\n');
}"""


def _english_left(text: str) -> list[str]:
    portuguese = _portuguese_words() - ENGLISH
    return sorted({w for w in WORD.findall(text) if w.lower() not in portuguese and w.lower() not in ALLOWED})


def test_the_word_check_finds_english():
    """The check can fail: an English message, a Plotly button and an English tooltip are caught."""
    left = _english_left("comprimento = 0 is not allowed: must be a finite number\nZoom in\nclassical Runge-Kutta")
    assert {"is", "not", "allowed", "must", "finite", "number", "Zoom", "classical"} <= set(left)
    assert _english_left("comprimento = 0 não é permitido: deve ser um número finito > 0 (m), como 3,5 ou 75cm") == []


#: The Portuguese page at every size, and its flags (RK4 at h = 0.5 s) and a comparison on a laptop.
PT_CASES = [pytest.param(w, h, "", id=f"default-{w}x{h}") for w, h in VIEWPORTS] + [
    pytest.param(1400, 900, "&" + RK4_HALF, id="rk4-flagged"),
    pytest.param(1400, 900, "&second=1&method2=verlet&length2=1&amplitude2=80", id="compare")]


@pytest.mark.slow
@pytest.mark.parametrize("width, height, query", PT_CASES)
def test_the_portuguese_page_has_no_english_word_left(browser, server, width, height, query):
    context, pg = _open(browser, server, "lang=pt" + query, width, height)
    try:
        if "rk4" in query:  # the flags, in Portuguese
            pg.wait_for_function("document.querySelector('#flags p[data-kind=energy-decay]')", timeout=90_000)
        pg.wait_for_timeout(1500)  # the photogate's first readings
        texts = {"page": pg.evaluate(SHOWN_TEXT)}
        for field, bad in (("length", "0"), ("step", "x"), ("amplitude", "200"), ("t_max", "-1"), ("g", "x")):
            good = pg.input_value(f"#{field}")
            _bad_input(pg, field, bad)  # the server's message, in Portuguese
            texts[f"{field} = {bad}"] = pg.evaluate(SHOWN_TEXT)
            if field != "g":  # the last one stays, read below
                pg.fill(f"#{field}", good)
                pg.wait_for_selector(f"#{field}-error", state="hidden", timeout=90_000)
        left = {k: _english_left(v) for k, v in texts.items()}
        assert all(v == [] for v in left.values()), left
        assert "não é permitido" in pg.locator("#g-error").text_content()
        assert _errors(pg) == []
    finally:
        context.close()


# ---------------------------------------------------------------- the boxes a classroom needs

def _box(pg, selector: str) -> dict:
    return pg.evaluate("""(s) => { const e = document.querySelector(s), r = e.getBoundingClientRect(), cs = getComputedStyle(e);
        return {left: r.left, top: r.top, right: r.right, bottom: r.bottom, width: r.width, height: r.height,
                visible: cs.visibility !== 'hidden' && cs.display !== 'none' && r.width > 0 && r.height > 0,
                text: e.textContent.trim(), font: parseFloat(cs.fontSize)}; }""", selector)


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "pt"])
def test_the_phones_first_screen_holds_the_period_and_the_estimate(browser, server, lang):
    context, pg = _open(browser, server, f"lang={lang}", 390, 844)
    try:
        pg.evaluate("window.scrollTo(0, 0)")
        for sel in ("#strip-period", "#strip-estimate"):
            b = _box(pg, sel)
            assert b["visible"] and b["top"] >= 0 and b["bottom"] <= 844 and b["right"] <= 390, (sel, b)
            assert re.fullmatch(r"\d+[.,]\d+( s)?", b["text"]), (sel, b["text"])  # a number, not the dash of no value
        assert pg.locator("#strip-period").text_content() == pg.locator("#period-agm").text_content()
    finally:
        context.close()


#: Every element that shows its own text in the projector's view, and its computed size (a
#: subscript, set smaller as type sets it, is part of its label's text).
PROJECTOR_TEXT = """() => [...document.querySelectorAll('main *')].filter(e => {
  const r = e.getBoundingClientRect(), cs = getComputedStyle(e);
  return r.width > 0 && r.height > 0 && cs.visibility !== 'hidden' && !e.closest('.sr-only') && !['SUB', 'SUP'].includes(e.tagName) &&
         [...e.childNodes].some(n => n.nodeType === 3 && n.textContent.trim());
}).map(e => [e.id || e.className || e.tagName, e.textContent.trim().slice(0, 40), parseFloat(getComputedStyle(e).fontSize)])"""


@pytest.mark.slow
def test_the_projector_is_large(browser, server):
    context, pg = _open(browser, server, "view=projector&" + "length=1&amplitude=30&unit=deg&speed=4", 1920, 1080)
    try:
        assert _box(pg, "#canvas")["width"] >= 960
        pg.wait_for_function("document.getElementById('gate').dataset.period", timeout=90_000)  # a reading shown
        for sel in ("#period-agm", "#strip-period", "#strip-estimate", "#gate"):
            b = _box(pg, sel)
            assert b["visible"] and b["font"] >= 24 and b["bottom"] <= 1080, (sel, b)
        small = [t for t in pg.evaluate(PROJECTOR_TEXT) if t[2] < 24]
        assert small == []
        assert not pg.locator("#inputs").is_visible() and not pg.locator("#plots").is_visible()
    finally:
        context.close()


@pytest.mark.slow
def test_the_controls_are_beside_the_swing_at_1024x768(browser, server):
    context, pg = _open(browser, server, "", 1024, 768)
    try:
        swing, controls = _box(pg, "#animation"), _box(pg, "#inputs")
        assert swing["right"] <= controls["left"] or controls["right"] <= swing["left"], (swing, controls)
        assert controls["top"] < 768 and swing["top"] < 768
    finally:
        context.close()


#: Each select whose chosen option's text is wider than the select leaves for it (padding and arrow).
CLIPPED_SELECTS = """() => [...document.querySelectorAll('select')].filter(s => s.offsetParent).map(s => {
  const cs = getComputedStyle(s), c = document.createElement('canvas').getContext('2d');
  c.font = `${cs.fontWeight} ${cs.fontSize} ${cs.fontFamily}`;
  const text = s.selectedOptions[0] ? s.selectedOptions[0].textContent : '';
  const room = s.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight) - 14;
  return [s.id, text, c.measureText(text).width, room];
}).filter(([, , need, room]) => need > room)"""


@pytest.mark.slow
@pytest.mark.parametrize("width, height", VIEWPORTS)
def test_no_clipped_column_or_control(browser, server, width, height):
    context, pg = _open(browser, server, "method2=verlet&" + "length=1&amplitude=30&unit=deg&step=1e-2&t_max=20", width, height)
    try:
        tables = pg.evaluate("[...document.querySelectorAll('#tables table')].map(t => [t.scrollWidth, t.clientWidth,"
                             " t.parentElement.scrollWidth, t.parentElement.clientWidth])")
        assert len(tables) >= 2
        for table in tables:
            assert table[0] <= table[1] + 1 and table[2] <= table[3] + 1, tables
        assert pg.evaluate(CLIPPED_SELECTS) == []
    finally:
        context.close()


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "pt"])
def test_the_page_prints_only_the_estimates_right_digits(browser, server, lang):
    """Verlet at h = 0.05 (an error near 1e-3 s): the strip and the table print the API's
    ``shown`` (the digits the error against the AGM period leaves right), in the page's
    decimal form, not the double's twelve digits; the AGM period keeps its twelve."""
    context = browser.new_context(viewport={"width": 1400, "height": 900})
    pg = record_errors(context.new_page())
    answers = []
    pg.on("response", lambda r: answers.append(r) if "/api/simulate" in r.url else None)
    try:
        pg.goto(f"{server}/?lang={lang}&length=1&amplitude=2&unit=rad&step=0.05&method=verlet")
        pg.wait_for_function("document.body.dataset.shown === '1'", timeout=90_000)
        e = answers[-1].json()["period"]["estimate"]
        assert e["errors"]["cubic"] > 1e-4  # the case: three digits right, not twelve

        def local(text):
            return text.replace(".", ",") if lang == "pt" else text

        assert pg.locator("#est-cubic").text_content() == local(e["shown"]["cubic"])
        assert pg.locator("#est-linear").text_content() == local(e["shown"]["linear"])
        assert pg.locator("#strip-estimate").text_content() == local(e["shown"]["cubic"]) + " s"
        for k in ("linear", "cubic"):  # the errors too: 3 digits at most, those the period's half ulp leaves
            assert pg.locator(f"#err-{k}").text_content() == local(e["shown"][f"{k}_error"])
            assert pg.locator(f"#rel-{k}").text_content() == local(e["shown"][f"{k}_relative"])
        assert len(re.sub(r"\D", "", pg.locator("#period-agm").text_content())) == 12
        assert _errors(pg) == []
    finally:
        context.close()


@pytest.mark.slow
def test_the_portuguese_page_writes_and_reads_a_decimal_comma(browser, server):
    """In Portuguese the fields show 3,5 (the URL keeps 3.5), and 1,5 typed is 1.5 m: the
    period of l = 1.5 m (mpmath), the slider moved, the URL written with a point, no error."""
    import mpmath

    context, pg = _open(browser, server, "lang=pt&length=3.5&amplitude=30&unit=deg&step=0.01&g=9.80665", 1400, 900)
    try:
        assert pg.input_value("#length") == "3,5" and pg.input_value("#g") == "9,80665"
        pg.fill("#length", "1,5")
        mpmath.mp.dps = 30
        t = 2 * mpmath.pi * mpmath.sqrt(mpmath.mpf("1.5") / mpmath.mpf("9.80665")) / mpmath.agm(1, mpmath.cos(mpmath.pi / 12))
        want = mpmath.nstr(t, 12, strip_zeros=False).replace(".", ",")
        pg.wait_for_function("(w) => document.getElementById('period-agm').textContent === w", arg=want, timeout=90_000)
        assert "length=1.5" in pg.url and pg.locator("#length-error").is_hidden()
        assert float(pg.input_value("#length-slider")) == pytest.approx(math.log10(1.5), abs=0.05)
        assert _errors(pg) == []
    finally:
        context.close()
