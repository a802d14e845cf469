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
import resource
import socket
import subprocess
import sys

import click
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hostile import HOSTILE
from pendulab.cli import COMMANDS, LazyGroup, main

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
    "key": ["--groups", "groups.txt", "--output", "key.json"],
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

    import pendulab.key
    import pendulab.report

    (folder / "groups.txt").write_text("262 407 634\n", encoding="utf-8")
    with pytest.MonkeyPatch.context() as mp, contextlib.chdir(folder):
        mp.setattr(pendulab.report, "build_report", lambda *a, **k: None)
        mp.setattr(pendulab.key, "answer_key", lambda *a, **k: None)
        mp.setattr(pendulab.key, "write_key", lambda *a, **k: None)
        mp.setattr(uvicorn, "run", lambda *a, **k: None)
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


def check(args: list[str]) -> None:
    code, err = run_in_process(args)
    assert code in (0, 2), (args, code, err)
    if code == 2:
        assert err.endswith("\n") and err.count("\n") == 1, (args, err)
        assert err.startswith("pendulab") and "Traceback" not in err, (args, err)


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
        check([command, *BASE[command], value])
    else:
        check([command, *BASE[command], max(param.opts, key=len), value])


@settings(max_examples=40, deadline=30_000,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(command=st.sampled_from(sorted(COMMANDS)), values=st.lists(HOSTILE, min_size=2, max_size=3))
def test_several_hostile_values_at_once(sandbox, command, values):
    params = [p for p in value_params(command) if isinstance(p, click.Option)]
    args = [command, *BASE[command]]
    for p, value in zip(params, values):
        args += [max(p.opts, key=len), value]
    check(args)


@pytest.mark.parametrize("args", [["--bogus"], ["nosuchcommand"], ["period", "--length"], ["period", "-l", "1"],
                                  ["length"], ["sweep", "--json", "--json", "-a"]])
def test_usage_errors_are_one_line(sandbox, args):
    check(args)


def test_no_arguments_print_the_normal_help():
    with CliRunner().isolation() as (out, _err, _):
        assert main([]) == 2
    text = out.getvalue().decode()
    assert text.startswith("Usage: pendulab") and "Commands:" in text and "simulate" in text
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
    (["fit", "--t-max", "1e9"], "--step"),
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
