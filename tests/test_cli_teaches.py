"""A CLI that teaches itself: examples in every command's help that run, every default shown,
suggestions for a misspelt command, one list syntax, the period's two numbers named apart."""
import json
import math
import os
import shlex
import signal
import subprocess
import sys

import click
import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import assert_one_line_error
from pendulab.cli import COMMANDS, LazyGroup, join_lists
from pendulab.cli import cli as group
from pendulab.cli.examples import EXAMPLES
from pendulab.numerics.period import agm_period, periods
from reference import G_TEXT, reference_period
from signals import default_signals

#: Examples that take seconds (Typst, a compiled sweep, the key's 2 groups): the slow tier.
SLOW = {"report", "key", "mark", "sweep", "fit", "approximations"}


def _examples():
    for command, rows in EXAMPLES.items():
        for line, _ in rows:
            marks = [pytest.mark.slow] if command in SLOW else []
            if command != "serve":
                yield pytest.param(line, marks=marks, id=line)


def test_every_command_has_examples_in_its_help(cli):
    assert set(EXAMPLES) == set(COMMANDS)
    for command in COMMANDS:
        res = cli(command, "--help")
        assert res.code == 0
        help_text = res.out
        assert "Examples:" in help_text, command
        for line, what in EXAMPLES[command]:
            assert line.startswith(f"pendulab {command}")
            assert line in help_text and what in help_text, (command, line)


@pytest.mark.parametrize("line", list(_examples()))
def test_each_example_runs(cli, tmp_path, monkeypatch, line):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "groups.txt").write_text("262 407 634\n12345, 23456, 34567\n")
    if line.startswith("pendulab mark"):  # the answers file the class fills in: the key's template
        assert cli("key", "--groups", "groups.txt", "--template", "answers", "-o", "answers.csv").code == 0
    res = cli(*shlex.split(line)[1:])
    assert res.code == 0, (line, res.err)
    assert res.out or res.err, line  # it says something


@pytest.mark.slow
@pytest.mark.parametrize("line", [row[0] for row in EXAMPLES["serve"]])
def test_each_serve_example_serves_until_ctrl_c(tmp_path, line):
    """The server starts and prints its address; Ctrl+C stops it with one line and 130."""
    import socket

    args = shlex.split(line)[1:]
    with socket.socket() as s:  # a port free now, in place of the example's own
        s.bind(("127.0.0.1", 0))
        port = str(s.getsockname()[1])
    if "--port" in args:
        args[args.index("--port") + 1] = port
    else:
        args += ["--port", port]
    proc = subprocess.Popen([sys.executable, "-m", "pendulab", *args], stderr=subprocess.PIPE, text=True,
                            env=os.environ | {"PYTHONUNBUFFERED": "1"}, preexec_fn=default_signals)
    try:
        first = proc.stderr.readline()
        assert f"http://127.0.0.1:{port}/" in first, first
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "pendulab serve: interrupted"


def _options():
    for name in COMMANDS:
        cmd = LazyGroup._load(name)
        for p in cmd.params:
            if isinstance(p, click.Option) and not p.is_flag and not p.hidden and "--help" not in p.opts:
                yield name, p


def test_every_default_is_shown_as_default(cli):
    """Each option that is not required and not a flag shows ``[default: ...]`` (or is a file
    written only when given: ``--plot F``); no default is left to the prose."""
    for name, p in _options():
        if p.required or p.multiple:
            continue
        if (p.default is None or repr(p.default) == "Sentinel.UNSET") and p.show_default in (None, False):
            # Optional outputs and choices that mean "not asked for" have nothing to show.
            assert p.name in {"plot", "phase", "output", "scheduler", "names", "template", "scheme_file"}, (name, p.name)
            continue
        assert p.show_default, (name, p.name)
        text = cli(name, "--help").out
        assert "[default:" in text
    text = " ".join(cli("period", "--help").out.split())
    assert "[default: (to convergence)]" in text and "[default: (15; none in --json)]" in text


def test_g_has_a_short_option(cli):
    for name, p in _options():
        if p.name == "g":
            assert "-g" in p.opts and "--g" in p.opts, name
    assert cli("period", "-l", "1", "-a", "1", "-g", "9.8", "--json").json["g"] == 9.8
    assert_one_line_error(cli("period", "-g", "-1"), "-g", "-1")


def test_a_misspelt_command_gets_a_suggestion(cli):
    assert_one_line_error(cli("perod"), "No such command 'perod'", "Did you mean period?")
    assert_one_line_error(cli("simulat"), "Did you mean simulate")
    res = cli("zzzz")
    assert_one_line_error(res, "No such command 'zzzz'", "pendulab --help")
    assert "Did you mean" not in res.err


def test_list_options_take_commas_or_spaces(cli):
    comma = cli("estimate", "-l", "1", "-a", "pi/4", "--step", "1e-2,1e-3", "--json").json
    spaces = cli("estimate", "-l", "1", "-a", "pi/4", "--step", "1e-2", "1e-3", "--json").json
    equals = cli("estimate", "-l", "1", "-a", "pi/4", "--step=1e-2", "1e-3", "--json").json
    assert comma == spaces == equals and [r["step"] for r in comma["rows"]] == [1e-2, 1e-3]
    a = cli("quadrature", "--n", "1", "10", "--json").json
    b = cli("quadrature", "--n", "1,10", "--json").json
    assert a == b and [r["n"] for r in a["rows"]] == [1, 10]
    # A bad item is named as typed, whichever the syntax.
    assert_one_line_error(cli("estimate", "--step", "1e-2", "-1"), "--step")


@given(st.lists(st.sampled_from(["--step", "1e-2", "1e-3", "10ms", "--json", "-l", "1", "--", "x", "--step=1"]),
                max_size=10))
@settings(max_examples=300, deadline=None)
def test_join_lists_keeps_every_other_word(words):
    """Joining changes nothing but the separators after a list option: every word is kept, in order."""
    cmd = LazyGroup._load("estimate")
    out = join_lists(cmd, words)
    assert ",".join(out).split(",") == ",".join(words).split(",")
    assert len(out) <= len(words)

    def options(ws):  # the options click sees, each a word of its own
        return [w.partition("=")[0] for w in ws if w.startswith("-") and not w[1:2].isdigit()]

    assert options(out) == options(words)[:len(options(out))]


def test_join_lists_examples():
    cmd = LazyGroup._load("estimate")
    assert join_lists(cmd, ["--step", "1e-2", "1e-3", "--json"]) == ["--step", "1e-2,1e-3", "--json"]
    assert join_lists(cmd, ["--step=1e-2", "1e-3"]) == ["--step=1e-2,1e-3"]
    assert join_lists(cmd, ["-l", "1", "2"]) == ["-l", "1", "2"]  # not a list option: click refuses the 2
    assert join_lists(cmd, ["--", "--step", "1", "2"]) == ["--", "--step", "1", "2"]


def test_period_names_both_numbers_where_they_differ(cli):
    """Near 180 deg the period of the amplitude as typed and of its double differ from the
    11th digit: the text shows both, each under its glossary name, and JSON carries both."""
    res = cli("period", "-l", "3.5", "-a", "0.9999999pi", "--iterations", "7")
    lines = res.out.splitlines()
    with mpmath.workdps(50):  # the period of 0.9999999 pi exactly, and of its double
        typed = reference_period("3.5", mpmath.mpf("0.9999999") * mpmath.pi, G_TEXT, dps=50)
        double = reference_period("3.5", mpmath.mpf(0.9999999 * math.pi), G_TEXT, dps=50)
    assert lines[0].startswith("period_as_written") and mpmath.nstr(typed, 15, strip_zeros=False) in lines[0]
    assert lines[1].startswith("period (the doubles)")
    assert repr(agm_period(3.5, 0.9999999 * math.pi)) in lines[1]
    assert float(lines[1].split("=")[1].split()[0]) == pytest.approx(float(double), rel=1e-15)
    assert lines[3].startswith("(8) after 7 iterations")
    data = cli("period", "-l", "3.5", "-a", "0.9999999pi", "--json").json
    assert data["period"] == agm_period(3.5, 0.9999999 * math.pi)
    assert data["period_as_written"] == float(typed)
    # Where they agree to the digits shown, one line: the README's example.
    out = cli("period", "-l", "75cm", "-a", "30deg").out.splitlines()
    assert out[0].startswith("period, AGM (7)-(8)") and len(out) == 2


@given(st.floats(1e-3, 1e3), st.floats(0, math.pi, exclude_max=True))
@settings(max_examples=200, deadline=None)
def test_periods_period_is_agm_period(length, amplitude):
    """``periods().period`` (by Arb) is the double ``agm_period`` returns (by mpmath, the
    double-double kernel): both the double nearest to the period of the doubles."""
    assert periods(length, amplitude).period == agm_period(length, amplitude)


def test_the_cubic_outside_its_bracket_is_flagged(cli):
    # h = 0.45 at pi/4: p(0) = 2.27 lies outside its bracket [1.8, 2.25], within a quarter
    # period of T = 2.087 (h = 0.5 is further off: untrusted, a status, not a row).
    res = cli("estimate", "-l", "1", "-a", "pi/4", "--step", "0.45", "0.01")
    rows = res.out.splitlines()
    assert rows[3].split()[4].endswith("!") and not rows[4].split()[4].endswith("!")
    assert rows[-1].startswith("! outside its bracket")
    data = cli("estimate", "-l", "1", "-a", "pi/4", "--step", "0.45", "0.01", "--json").json
    flags = [(r["bracket"][0] <= r["cubic"] <= r["bracket"][1], r["cubic_in_bracket"]) for r in data["rows"]]
    assert flags == [(False, False), (True, True)]


def test_trajectory_columns_are_the_glossarys(cli):
    names = ["t", "theta", "omega"]
    assert cli("simulate").out.splitlines()[0].split() == names
    assert cli("simulate", "--csv").out.splitlines()[0].split(",") == names
    assert list(json.loads(cli("simulate", "--json").out))[:3] == names


def test_gravity_json_names_the_measured_period(cli):
    data = cli("gravity", "--json").json
    assert data["measured_period"] == 2.1536 and data["measured_period_error"] == 2e-4
    assert "period" not in data


def test_help_groups_every_command():
    with click.Context(group) as ctx:
        text = group.get_help(ctx)
    for name in COMMANDS:
        assert f"  {name}" in text


def test_the_web_api_takes_units_as_the_cli_does():
    from starlette.testclient import TestClient

    from pendulab.web import create_app

    client = TestClient(create_app(), base_url="http://localhost")
    with_units = client.get("/api/period", params={"length": "75cm", "amplitude": "30deg"}).json()
    plain = client.get("/api/period", params={"length": "0.75", "amplitude": "30", "unit": "deg"}).json()
    assert with_units == plain and with_units["length"] == 0.75
    q = {"length": "1", "amplitude": "pi/4", "t_max": "2.1"}
    ms = client.get("/api/trajectory.csv", params=q | {"step": "100ms"}).text
    assert ms == client.get("/api/trajectory.csv", params=q | {"step": "0.1"}).text
    assert ms.splitlines()[0] == "t,theta,omega" and len(ms.splitlines()) == 23
    bad = client.get("/api/period", params={"length": "75furlong", "amplitude": "1"})
    assert bad.status_code == 422 and "75furlong" in bad.text
