"""The explorer's words: ``/api/config?lang=`` hands the page the catalogue's ``web.`` entries,
and every key the page names (``data-word*`` in index.html, ``word("...")`` in its scripts)
is in both catalogues with the same ``{fields}``.

Reference: the catalogue files themselves, read here with ``json`` (not through
:mod:`pendulab.web.words`).
"""
from __future__ import annotations

import json
import os
import re
import string
from importlib import resources
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.web import create_app
from test_boundary_web import endpoints

STATIC = Path(__file__).resolve().parents[1] / "src" / "pendulab" / "web" / "static"


def _all(lang: str) -> dict[str, object]:
    """The whole catalogue of ``lang``."""
    return json.loads(resources.files("pendulab.report").joinpath(f"{lang}.json").read_text(encoding="utf-8"))


def _catalogue(lang: str) -> dict[str, str]:
    """Its ``web.`` entries, by their names without ``web.``."""
    return {k[4:]: v for k, v in _all(lang).items() if k.startswith("web.")}


EN, PT = _catalogue("en"), _catalogue("pt")


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://localhost")


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_config_hands_the_page_its_words(client, lang):
    body = client.get("/api/config", params={"lang": lang}).json()
    assert body["lang"] == lang
    assert body["words"] == (EN if lang == "en" else PT)
    assert body["words"]["page.period"] == {"en": "Period", "pt": "Período"}[lang]


@pytest.mark.parametrize("lang, words", [("en", "too large for amplitude 2.4 rad"), ("pt", "grande demais para a amplitude 2,4 rad")])
def test_a_missing_period_says_why_in_the_language_asked(client, lang, words):
    # h = 0.5 s from 2.4 rad: the discrete pendulum goes over the top (test_web_api has the time).
    q = {"length": "1", "amplitude": "2.4", "step": "0.5", "t_max": "20", "lang": lang}
    period = client.get("/api/simulate", params=q).json()["period"]
    assert period["status"] == "left_oscillation" and words in period["reason"]
    rows = client.get("/api/convergence", params=q | {"steps": "0.5"}).json()["rows"]
    assert words in rows[0]["reason"]


def test_a_launch_says_why_there_is_no_estimate_in_portuguese(client):
    q = {"length": "1", "amplitude": "1", "step": "0.01", "t_max": "2", "omega0": "1.5", "lang": "pt"}
    reason = client.get("/api/simulate", params=q).json()["period"]["reason"]
    assert reason.startswith("o período é estimado") and "θ′(0) = 1,5 rad/s" in reason


def test_config_without_lang_is_english(client):
    assert client.get("/api/config").json()["lang"] == "en"


@pytest.mark.parametrize("route", ["/api/config", "/api/simulate", "/api/motion", "/api/convergence"])
def test_an_unknown_language_is_a_422_naming_lang(client, route):
    r = client.get(route, params={"lang": "fr", "length": "1", "amplitude": "0.5", "step": "0.01", "t_max": "2"})
    assert r.status_code == 422
    err = r.json()["error"]
    assert err["field"] == "lang" and err["value"] == "fr" and err["allowed"] == "en or pt"


def _fields(text: str) -> set[str]:
    return {f for _, f, _, _ in string.Formatter().parse(text) if f}


def test_both_catalogues_hold_the_same_web_keys_and_fields():
    assert set(EN) == set(PT)
    assert {k: _fields(EN[k]) for k in EN} == {k: _fields(PT[k]) for k in PT}


#: Entries written alike in both languages: symbols, names and words that are Portuguese too.
SAME_IN_BOTH = {"page.csv", "page.amplitude", "page.run", "page.relative", "page.linear", "page.total"}


def test_every_entry_is_translated():
    """The page's, the reasons' and the flags' entries (the lab's block has its own test)."""
    same = {k for k in EN if k.split(".")[0] in ("page", "reason", "flag") and EN[k] == PT[k]}
    assert same == SAME_IN_BOTH


def _page_keys() -> set[str]:
    html = (STATIC / "index.html").read_text(encoding="utf-8")
    keys = set(re.findall(r'data-word(?:-aria|-title|-placeholder)?="([^"]+)"', html))
    for script in STATIC.glob("*.js"):
        if script.name.startswith("plotly"):
            continue
        keys |= set(re.findall(r'\bword\("([^"$]+)"\s*[,)]', script.read_text(encoding="utf-8")))
    return keys


def test_every_key_the_page_names_is_in_the_catalogues():
    keys = _page_keys()
    assert len(keys) > 40  # the scan finds the page's words
    assert sorted(keys - set(EN)) == []


def test_the_scan_finds_a_missing_key(tmp_path):
    """The check above can fail: a key that no catalogue has is found by the same expression."""
    assert re.findall(r'\bword\("([^"$]+)"\s*[,)]', 'x = word("page.no-such-key");') == ["page.no-such-key"]


@pytest.mark.parametrize("field, bad, en, pt", [
    ("length", "0", "length = 0 is not allowed: must be a finite number > 0, optionally with a unit: m, cm, mm (default m)",
     "comprimento = 0 não é permitido: deve ser um número finito > 0, com ou sem unidade: m, cm, mm (por omissão m)"),
    ("g", "0", "g = 0 is not allowed: must be a finite number > 0 (m/s^2), such as 9.80665",
     "g = 0 não é permitido: deve ser um número finito > 0 (m/s^2), como 9,80665"),
    ("mass", "-1", "mass = -1 is not allowed: must be a finite number > 0 (kg), such as 0.2: the bob's mass (the energies in J; not the period)",
     "massa = -1 não é permitido: deve ser um número finito > 0 (kg), como 0,2: a massa do peso (as energias em J; não o período)"),
])
def test_a_bad_input_is_refused_in_the_language_asked(client, field, bad, en, pt):
    q = {"length": "1", "amplitude": "0.5", "step": "0.01", "t_max": "2"} | {field: bad}
    for lang, message in (("en", en), ("pt", pt)):
        r = client.get("/api/simulate", params=q | {"lang": lang})
        assert r.status_code == 422
        err = r.json()["error"]
        assert err["field"] == field and err["value"] == bad and err["message"] == message


def test_the_methods_are_described_in_portuguese(client):
    body = client.get("/api/config", params={"lang": "pt"}).json()
    said = {m["name"]: m["description"] for m in body["methods"] + body["family"]}
    assert said["rk4"] == "Runge-Kutta clássico, ordem 4" and said["taylor:1"].endswith("(método de Euler)")
    assert said["taylor:7"] == "método de Taylor de ordem 7"


def test_a_bad_language_is_shown_on_one_line(client):
    # Hypothesis (test_boundary_web) found lang = "a\nb" echoed with its newline.
    err = client.get("/api/config", params={"lang": "a\nb"}).json()["error"]
    assert err["message"] == "lang = 'a\\nb' is not allowed: must be en or pt" and err["field"] == "lang"


SCALARS = st.sampled_from(["length", "amplitude", "g", "step", "t_max", "omega0", "damping", "drag", "mass"])
BASE = {"length": "1", "amplitude": "0.5", "step": "0.01", "t_max": "2", "points": "64"}


@settings(max_examples=60, deadline=None)
@given(SCALARS, st.floats(min_value=-1e3, max_value=1e3, allow_nan=False).filter(lambda x: x != int(x)))
def test_portuguese_reads_a_decimal_comma(client, field, x):
    """With ``lang=pt`` a scalar typed with a decimal comma (``0,5``) is the number with a
    point: the same answer, or the same refusal, whose message and value echo it as typed."""
    dotted = repr(x)
    if "e" in dotted:  # a comma only where a person writes one: 1,5e-05 is not how it is typed
        dotted = f"{x:.6f}"
    comma = dotted.replace(".", ",")
    q = BASE | {"lang": "pt"}
    with_point = client.get("/api/simulate", params=q | {field: dotted})
    with_comma = client.get("/api/simulate", params=q | {field: comma})
    assert with_comma.status_code == with_point.status_code
    if with_point.status_code == 200:
        assert with_comma.json()["input"] == with_point.json()["input"]
    else:
        err, ref = with_comma.json()["error"], with_point.json()["error"]
        assert err["field"] == ref["field"]
        if err["field"] == field:  # the refused value itself: as typed
            assert err["value"] == comma and f"= {comma} não é permitido" in err["message"]
        assert err["allowed"] == ref["allowed"]


def test_english_refuses_a_decimal_comma_and_a_list_keeps_its_commas(client):
    """``1,5`` is no number in English (it may mean 1500 there); ``steps`` is a list either way."""
    r = client.get("/api/simulate", params=BASE | {"length": "1,5"})
    assert r.status_code == 422 and r.json()["error"]["value"] == "1,5"
    q = {"length": "1", "amplitude": "0.5", "steps": "0.1,0.05", "lang": "pt"}
    assert [row["step"] for row in client.get("/api/convergence", params=q).json()["rows"]] == [0.1, 0.05]


def _words(texts) -> set[str]:
    return {w.lower() for t in texts for w in re.findall(r"[A-Za-z]{3,}", t if isinstance(t, str) else json.dumps(t))}


#: English words of the page's catalogue that no Portuguese entry holds: none may reach a
#: Portuguese refusal (method names, units and symbols are in both, so are not here).
ENGLISH = _words(EN.values()) - _words(_all("pt").values())
SPOKEN = endpoints()
WORDED = sorted(r for r, names in SPOKEN.items() if "lang" in names)
BAD = st.one_of(
    st.sampled_from(["", "0", "-1", "x", "nan", "inf", "1e400", "1e-320", "1e300", "1e6", "1e-9", "2.7e-215",
                     "3.2", "200deg", "4pi/5", "0,5", "0.0001,1e-9", "abc,1", ",", "1,,2", "rk9", "taylor:99",
                     "9" * 40, "1" * 300, "0E401", "1e-99999"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.text("0123456789.,-+eEpi/degmsc ", max_size=12),
)


def test_every_route_with_words_takes_lang():
    """The routes whose answers or refusals have words (all but the fixed T(alpha)/T0 curve)."""
    assert set(SPOKEN) - set(WORDED) == {"/api/period_curve"}
    assert {"smallest", "must", "such", "fits", "with", "between"} <= ENGLISH


@settings(max_examples=int(os.environ.get('PT_EXAMPLES', 250)), deadline=None)
@given(st.sampled_from([r for r in WORDED if len(SPOKEN[r]) > 1]), st.data())
def test_a_portuguese_refusal_has_no_english_word(client, route, data):
    """Any field of any route given a bad value with ``lang=pt``: a 422 (never a 500) whose
    message and allowed range hold no English word of the catalogue (the echoed value apart).
    The probe that found ``0.0001 (smallest)``, ``such that the period search ... fits`` and
    English refusals from ``/api/period`` and ``/api/trajectory.csv``."""
    names = [n for n in SPOKEN[route] if n != "lang"]
    field = data.draw(st.sampled_from(names))
    value = data.draw(BAD)
    q = {"length": "1", "amplitude": "0.5", "step": "0.01", "t_max": "2", "points": "64"}
    q = {k: v for k, v in q.items() if k in names} | {field: value, "lang": "pt"}
    r = client.get(route, params=q)
    assert r.status_code in (200, 422), (route, q, r.status_code)
    if r.status_code == 422:
        err = r.json()["error"]
        said = err["message"].replace(f"= {err['value']} ", "= ", 1)
        assert said.startswith(f"{PT.get('field.' + err['field'], err['field'])}"), said
        assert not (_words([said, err["allowed"]]) & ENGLISH), (route, q, said)
