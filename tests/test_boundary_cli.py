"""The CLI's input boundary: no value typed into any option of any command crashes, hangs
or exhausts memory.

Property (Hypothesis, the grammar of ``hostile.py``): for every command of ``pendulab`` and
every option or argument that takes a value (read from the click commands themselves, so
an option added later is covered), a hostile value ends in exit status 0, or in exit status
2 with exactly one line on stderr and no traceback; in process (``click.testing.CliRunner``
isolation around ``pendulab.cli.main``), within 30 s (Hypothesis deadline, generous for a loaded machine) and with less
than 1 GiB of address space more than before (``RLIMIT_AS`` lowered around each run). A
few of the reported reproductions also run as real processes under an address-space limit
of 1 GiB and a 30 s timeout.
"""
from __future__ import annotations

import contextlib
import os
import re
import resource
import socket
import subprocess
import sys
import types

import click
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hostile import HOSTILE
from pendulab.cli import COMMANDS, LazyGroup, main
from served import free_port

#: Light values for the other options, so a hostile value that happens to be valid runs fast.
BASE = {
    "period": ["-l", "1", "-a", "1"],
    "simulate": ["--t-max", "0.5", "--step", "0.1"],
    "estimate": ["--step", "1e-2"],
    "length": [],
    "gravity": [],
    "newton": [],
    "fit": ["--t-max", "2", "--step", "0.05"],
    "quadrature": ["--n", "1,10"],
    "report": [],
    "programs": ["--output", "programs"],
    "key": ["--groups", "groups.txt", "--output", "key.json"],
    "mark": ["--groups", "groups.txt", "--answers", "answers.csv", "--output", "marked.json"],
    "serve": ["--host", "127.0.0.1"],
    "approximations": [],
    "sweep": ["-a", "10deg:20deg:3", "--step", "1e-2", "--method", "taylor2"],
}
GIB = 1 << 30


def value_params(name: str) -> list[click.Parameter]:
    """The options and arguments of a command that take a value (flags have none to fuzz)."""
    cmd = LazyGroup._load(name)
    return [p for p in cmd.params if not getattr(p, "is_flag", False) and p.name not in ("help",)]


def test_every_command_has_a_base():
    assert set(BASE) == set(COMMANDS)
    assert all(value_params(c) for c in COMMANDS if c != "approximations") and value_params("approximations")


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory):
    """A scratch working folder; a report, a key and a server that do no work: the boundary is under test."""
    folder = tmp_path_factory.mktemp("cli")
    real = socket.getaddrinfo

    def numeric_only(host, port, *args, **kwargs):  # never a DNS query from a test
        kwargs["flags"] = kwargs.get("flags", 0) | socket.AI_NUMERICHOST
        return real(host, port, *args, **kwargs)

    import uvicorn

    import pendulab.jobs.key
    import pendulab.jobs.mark
    import pendulab.report
    import pendulab.report.key
    import pendulab.report.mark
    import pendulab.web.server

    (folder / "groups.txt").write_text("262 407 634\n", encoding="utf-8")
    (folder / "answers.csv").write_text("line,students\n1,262 407 634\n", encoding="utf-8")
    with pytest.MonkeyPatch.context() as mp, contextlib.chdir(folder):
        mp.setattr(pendulab.report, "build_report", lambda *a, **k: None)
        mp.setattr(pendulab.jobs.key, "answer_key", lambda *a, **k: None)
        mp.setattr(pendulab.report.key, "write_key", lambda *a, **k: None)
        mp.setattr(pendulab.jobs.mark, "mark_class", lambda *a, **k: types.SimpleNamespace(groups=()))
        mp.setattr(pendulab.report.mark, "write_marks", lambda *a, **k: None)
        mp.setattr(uvicorn, "run", lambda *a, **k: None)
        mp.setattr(pendulab.web.server, "run", lambda *a, **k: None)  # serve's own runner
        mp.setattr(socket, "getaddrinfo", numeric_only)
        for command in COMMANDS:  # imports and compiled kernels loaded before anything is timed
            run_in_process([command, *BASE[command], *(["262"] if command == "length" else [])])
        yield folder


@contextlib.contextmanager
def address_space(extra: int = GIB):
    """Lower this process's address-space limit to what it uses now plus ``extra`` bytes."""
    with open("/proc/self/statm") as f:
        used = int(f.read().split()[0]) * resource.getpagesize()
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    resource.setrlimit(resource.RLIMIT_AS, (used + extra, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def run_in_process(args: list[str]) -> tuple[int, str]:
    """``pendulab ARGS`` in process, with 1 GiB of address space to spare: exit status, stderr."""
    with CliRunner().isolation() as (_out, err, _), address_space():
        code = main(args)
    return code, err.getvalue().decode("utf-8", "replace")


#: A name as the library spells it (``t_max``, ``length_error``, ``t0``, ``x0``): in a CLI
#: message every argument is named as an option (``--t-max``, ``--t0``). Not part of an
#: option, a number, a path or a file name (the lookarounds), nor a subscript of the
#: mathematics (``x_1``, ``t_j``).
LIBRARY_NAME = re.compile(r"(?<![-\w./\\])(?:[a-z]+(?:_[a-z][a-z0-9]+)+|t0|x0)(?![-\w./\\])")
#: The head of an input error: the option or argument, then the value as it echoes it.
HEAD = re.compile(r"pendulab \S+: error: (\S+) = (.*?) is not allowed: must be ")


def as_typed(echo: str, typed: str) -> bool:
    """Whether ``echo`` shows ``typed`` (or one of its list items) as typed: verbatim,
    or quoted by :func:`pendulab.core.inputs.shown` where unprintable or long, never a repr of
    printable text or a float's rendering (``1e9`` shown as ``1000000000``)."""
    from pendulab.core import inputs

    items = re.split(r"\s*,\s*|\s+", typed.strip())
    candidates = [typed, *items, *(part for item in items for part in item.split(":"))]
    return (echo in ("(empty)", "(missing)", inputs.shown(typed)) or re.fullmatch(r"\d+ items", echo) is not None
            or any(echo in (inputs.shown(c), inputs.shown(c.strip())) for c in candidates if c.strip()))


def check(args: list[str], typed: dict[str, str] | None = None) -> None:
    """Exit 0, or exit 2 with one line in the CLI's words; ``typed``: option -> the hostile text given it.

    The line names no argument by the library's spelling (the typed values aside), and
    an error about one of the ``typed`` options echoes its value as typed.
    """
    code, err = run_in_process(args)
    assert code in (0, 2), (args, code, err)
    if code == 2:
        assert err.endswith("\n") and err.count("\n") == 1, (args, err)
        assert err.startswith("pendulab") and "Traceback" not in err, (args, err)
        rest = err
        for value in args:  # what was typed may hold anything, t_max included
            rest = rest.replace(value, " ") if value.strip() else rest
        assert not LIBRARY_NAME.search(rest), (args, err)
        head = HEAD.match(err)
        if head and typed and head[1] in typed:
            assert as_typed(head[2], typed[head[1]]), (args, err)


#: Examples per command; approximations has one option, --plot, whose valid values draw a figure.
EXAMPLES = dict.fromkeys(COMMANDS, 25) | {"approximations": 8}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_hostile_value_in_any_option(sandbox, command):
    settings(max_examples=EXAMPLES[command], deadline=30_000,
             suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])(
        given(data=st.data())(_one_hostile_value))(command)


def _one_hostile_value(command, data):
    param = data.draw(st.sampled_from(value_params(command)), label="parameter")
    value = data.draw(HOSTILE, label="value")
    if isinstance(param, click.Argument):
        check([command, *BASE[command], value], {param.name.upper(): value})
    else:
        option = max(param.opts, key=len)
        check([command, *BASE[command], option, value], {option: value})


def integer_ranges() -> list[tuple[str, str, int]]:
    """(command, option, bound) for both ends of every integer option's range, read from click."""
    ends = []
    for command in sorted(COMMANDS):
        for p in value_params(command):
            bounds = re.fullmatch(r"(-?\d+)\.\.(\d+)", getattr(p.type, "name", "") or "")
            if bounds and isinstance(p, click.Option):
                ends += [(command, max(p.opts, key=len), int(b)) for b in bounds.groups()]
    return ends


@pytest.mark.parametrize("command, option, bound", integer_ranges())
def test_both_ends_of_every_integer_range_run(sandbox, command, option, bound):
    # --digits 10000 (the top of its range) crashed: str() of an integer of 10000 digits.
    assert len(integer_ranges()) >= 8  # period --iterations/--digits, simulate --digits, serve --port
    code, err = run_in_process([command, *BASE[command], option, str(bound)])
    assert code == 0, (command, option, bound, err)


@settings(max_examples=60, deadline=30_000,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(n=st.one_of(st.integers(-3, 515), st.integers(-10**12, 10**12), st.sampled_from([0, 1, 512, 513])))
def test_serve_per_address_takes_1_to_512_and_hands_it_to_the_server(sandbox, n):
    import pendulab.web.server

    ran: dict = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(pendulab.web.server, "run", lambda *a, **k: ran.update(k))
        code, err = run_in_process(["serve", "--port", str(free_port()), "--per-address", str(n)])
    if 1 <= n <= pendulab.web.server.MAX_CONNECTIONS:
        assert code == 0 and ran["max_per_client"] == n, (n, err)
    else:  # one line naming the option, the value as typed and the range; the server never starts
        assert code == 2 and not ran, (n, err)
        assert err == f"pendulab serve: error: --per-address = {n} is not allowed: must be an integer in [1, 512]\n"


def test_serve_without_per_address_leaves_the_servers_default(sandbox):
    import pendulab.web.server
    from pendulab.cli import serve as serve_cmd

    ran: dict = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(pendulab.web.server, "run", lambda *a, **k: ran.update(k))
        code, err = run_in_process(["serve", "--port", str(free_port())])
    assert code == 0 and ran["max_per_client"] is None, err  # the protocol's per_address_cap
    assert serve_cmd._MOST_PER_ADDRESS == pendulab.web.server.MAX_CONNECTIONS


@settings(max_examples=40, deadline=30_000,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(command=st.sampled_from(sorted(COMMANDS)), values=st.lists(HOSTILE, min_size=2, max_size=3))
def test_several_hostile_values_at_once(sandbox, command, values):
    params = [p for p in value_params(command) if isinstance(p, click.Option)]
    args = [command, *BASE[command]]
    typed = {}
    for p, value in zip(params, values):
        args += [max(p.opts, key=len), value]
        typed[max(p.opts, key=len)] = value
    check(args, typed)


@pytest.mark.parametrize("args", [["--bogus"], ["nosuchcommand"], ["period", "--length"], ["period", "-l", "1", "-a"],
                                  ["length"], ["sweep", "--json", "--json", "-a"]])
def test_usage_errors_are_one_line(sandbox, args):
    check(args)


def test_no_arguments_print_the_normal_help():
    with CliRunner().isolation() as (out, _err, _):
        assert main([]) == 0  # a person's first try: the help, not an error
    text = out.getvalue().decode()
    assert text.startswith("Usage: pendulab") and "Coursework commands:" in text and "simulate" in text
    assert len(text.splitlines()) > 10 and "error:" not in text


# ------------------------------------------------------------------ real processes, 1 GiB, 10 s

def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (GIB, GIB))


REPRODUCTIONS = [
    (["period", "-l", "1e400", "-a", "pi/4"], "--length"),
    (["estimate", "-a", "1e400"], "--amplitude"),
    (["simulate", "--g", "1e400"], "--g"),
    (["gravity", "--length", "1e-99999999"], "--length"),
    (["simulate", "--step", "1e-8", "--t-max", "100"], "--step"),
    (["simulate", "--t-max", "1e9"], "--t-max"),
    (["simulate", "--step", "1e-300"], "--step"),
    (["fit", "--t-max", "1e9"], "--t-max = 1e9 "),
    (["report", "--students", "²"], "--students"),
    (["approximations", "--plot", "x.xyz"], "--plot"),
]


@pytest.mark.parametrize("args, option", REPRODUCTIONS)
def test_reproductions_in_a_real_process(tmp_path, args, option):
    env = dict(os.environ, PYTHONWARNINGS="ignore")
    res = subprocess.run([sys.executable, "-m", "pendulab", *args], capture_output=True, text=True, timeout=30,
                         preexec_fn=_limit_memory, cwd=tmp_path, env=env)
    assert res.returncode == 2, res.stderr
    assert res.stderr.count("\n") == 1 and "Traceback" not in res.stderr and option in res.stderr, res.stderr
    assert list(tmp_path.iterdir()) == []  # refused before any work: nothing written


def test_a_run_that_works_fits_in_the_limits(tmp_path):
    res = subprocess.run([sys.executable, "-m", "pendulab", "simulate", "--step", "1e-3", "--t-max", "5", "--csv"],
                         capture_output=True, text=True, timeout=30, preexec_fn=_limit_memory, cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert len(res.stdout.splitlines()) == 1 + 5001


# ------------------------------------------------------------------ the CLI's words, case by case

@pytest.mark.parametrize("args, head, hint", [
    # The limit on the step count blames the option typed, the other left at its default.
    (["fit", "--t-max", "1e9"], "--t-max = 1e9 ", "or a larger --step"),
    (["fit", "--step", "1e-9"], "--step = 1e-9 ", "or a shorter --t-max"),
    (["fit", "--step", "1"], "--step = 1 ", "<= --t-max/6"),
    (["fit", "--t-max", "0.05", "--step", "0.01"], "--step = 0.01 ", "<= --t-max/6"),  # both typed: the step
    (["simulate", "--t-max", "1e9"], "--t-max = 1e9 ", "or a larger --step"),
    (["simulate", "--step", "1e-8", "--t-max", "100"], "--step = 1e-8 ", "or a shorter --t-max"),
    (["simulate", "--t-max", "0.01"], "--t-max = 0.01 ", "> --step = 0.1 s"),
    (["estimate", "--t-max", "1e9"], "--t-max = 1e9 ", "or a larger --step"),
    (["estimate", "--step", "1e-2,1e-12"], "--step = 1e-12 ", "or a shorter --t-max"),
    (["estimate", "--t-max", "-3"], "--t-max = -3 ", "> 0 s"),
    (["sweep", "-a", "10deg:20deg:3", "--step", "1e-2,1e-12"], "--step = 1e-12 ", ">= "),
    (["gravity", "--length-error", "2m"], "--length-error = 2m ", "< --length = 1.152 m"),
    # Values as typed, a method name too (foo, not its repr 'foo').
    (["sweep", "--method", "foo"], "--method = foo ", "taylor:P"),
    (["sweep", "--method", "rk4,foo"], "--method = foo ", "taylor:P"),
    (["simulate", "--method", "foo"], "--method = foo ", "taylor:P"),
    # The range with its bounds, also for a number beyond the exponent cap.
    (["gravity", "--length", "1e-99999999"], "--length = 1e-99999999 ", "between 2.225e-308 m and 1.798e+308 m"),
    (["gravity", "--length", "1e-320"], "--length = 1e-320 ", "between 2.225e-308 m and 1.798e+308 m"),
    (["gravity", "--length", "1e-306mm"], "--length = 1e-306mm ", "between 2.225e-308 m"),
    (["gravity", "--period-error", "1e-330"], "--period-error = 1e-330 ", "0 or between 2.225e-308 s"),
    (["period", "-l", "1e-99999999", "-a", "1"], "--length = 1e-99999999 ", "between 2.225e-308 m and 1.798e+308 m"),
    (["simulate", "--t-max", "1e999"], "--t-max = 1e999 ", "between 1e-400 s and 1.798e+308 s"),
])
def test_messages_in_the_cli_words(sandbox, args, head, hint):
    code, err = run_in_process(args)
    assert code == 2 and err.count("\n") == 1, err
    assert err.split(": error: ", 1)[1].startswith(head) and hint in err, err
    assert not LIBRARY_NAME.search(err) and "'" not in err, err
