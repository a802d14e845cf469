"""Interrupted runs: long kernels cut into pieces give the same bits, and a real Ctrl+C or
SIGTERM sent to a real ``pendulab`` process ends it with one line and 130 or 143."""
from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pendulab.core.interrupt import deferred, pieces
from pendulab.engine import kernels
from reference import EXAMPLE_LENGTH, G
from signals import default_signals, python_sigint

METHODS = [(0, 2), (1, 4), (2, 2), (3, 1), (3, 5), (3, 12)]  # taylor2, rk4, verlet, taylor:1, 5, 12


@pytest.fixture
def sigint_handler():
    """Python's own SIGINT handler (KeyboardInterrupt) for the test, whatever the run inherited."""
    with python_sigint():
        yield


def _one_call(method, order, alpha, c, h, n):
    """The whole run in one call of the driver: the reference for the pieces."""
    z1, z2 = np.empty(n + 1), np.empty(n + 1)
    z1[0], z2[0] = alpha, 0.0
    kernels.drive(method, order, alpha, 0.0, c, h, 0, n, 1, n, z1[1:], z2[1:])
    return z1, z2


def _one_search(method, order, alpha, c, h, n):
    """The whole period search in one call of its kernel: the reference for the pieces."""
    z1w, z2w = np.zeros(5), np.zeros(5)
    z1w[2] = alpha
    status, j = kernels.search_return(method, order, c, h, n, 0, n, z1w, z2w)
    if status != kernels.FOUND:
        z1w[:] = 0.0
        z2w[:] = 0.0
    return status, j, z1w, z2w


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(m=st.sampled_from(METHODS), alpha=st.floats(0.01, 3.1), h=st.floats(1e-3, 0.3),
       n=st.integers(0, 700), stride=st.integers(1, 900), piece=st.integers(1, 300))
def test_pieces_give_the_same_bits_as_one_call(m, alpha, h, n, stride, piece):
    """trajectory, thinned and the period search, cut into pieces of any size (here a few
    steps, so that a run has many), equal one call of the kernel over the whole run."""
    method, order = m
    c = -G / 2.0
    ref1, ref2 = _one_call(method, order, alpha, c, h, n)
    one = _one_search(method, order, alpha, c, h, n)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(kernels, "CHUNK_COST", piece * 50)  # pieces of piece * 50 / cost steps
        _cut(method, order, alpha, c, h, n, stride, ref1, ref2, one)


def _cut(method, order, alpha, c, h, n, stride, ref1, ref2, one):
    z1, z2 = kernels.trajectory(method, order, alpha, c, h, n)
    assert np.array_equal(z1, ref1, equal_nan=True) and np.array_equal(z2, ref2, equal_nan=True)
    keep = np.r_[np.arange(0, n + 1, stride), [n] if n % stride else []].astype(int)
    t1, t2 = kernels.thinned(method, order, alpha, c, h, n, stride, len(keep))
    assert np.array_equal(t1, ref1[keep], equal_nan=True) and np.array_equal(t2, ref2[keep], equal_nan=True)
    cut = kernels.first_return(method, order, alpha, c, h, n)
    assert cut[0] == one[0] and cut[1] == one[1]
    assert np.array_equal(cut[2], one[2]) and np.array_equal(cut[3], one[3])


def test_long_fine_runs_in_pieces_give_the_same_bits(monkeypatch):
    """(3) long and fine runs, in pieces."""
    alpha, c, h, n = 2.5, -G / EXAMPLE_LENGTH, 1e-5, 501_234
    ref1, ref2 = _one_call(0, 2, alpha, c, h, n)
    one = _one_search(0, 2, alpha, c, h, n)
    assert one[0] == kernels.FOUND  # the period, about 4.8 s, within n h
    monkeypatch.setattr(kernels, "CHUNK_COST", 9973)
    z1, z2 = kernels.trajectory(0, 2, alpha, c, h, n)
    assert np.array_equal(z1, ref1) and np.array_equal(z2, ref2)
    for stride in (7, 9973, 50_000):
        keep = np.r_[np.arange(0, n + 1, stride), [n] if n % stride else []].astype(int)
        t1, t2 = kernels.thinned(0, 2, alpha, c, h, n, stride, len(keep))
        assert np.array_equal(t1, ref1[keep]) and np.array_equal(t2, ref2[keep])
    cut = kernels.first_return(0, 2, alpha, c, h, n)
    assert cut[:2] == one[:2] and np.array_equal(cut[2], one[2]) and np.array_equal(cut[3], one[3])


@given(n=st.integers(0, 500), size=st.integers(1, 60), stride=st.integers(1, 90))
def test_pieces_cover_the_run_and_never_cross_a_kept_point(n, size, stride):
    bounds = list(pieces(n, size, stride))
    assert [lo for lo, _ in bounds] == ([0] + [hi for _, hi in bounds[:-1]] if n else [])
    assert (bounds[-1][1] if bounds else 0) == n
    for lo, hi in bounds:
        assert 0 < hi - lo <= size
        if size < stride:
            assert (hi - 1) // stride == lo // stride or hi % stride == 0


def test_a_signal_inside_deferred_is_raised_after_it(sigint_handler):
    """The handler only records; the signal reaches Python's own handler on leaving."""
    ran_after = []
    with pytest.raises(KeyboardInterrupt), deferred() as got:
        signal.raise_signal(signal.SIGINT)
        ran_after.append(list(got))  # no exception inside: the work finishes its piece
    assert ran_after == [[signal.SIGINT]]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_an_ignored_signal_stays_ignored():
    """A signal ignored by the program (SIG_IGN) is not recorded: the work is not cut short."""
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with deferred() as got:
            signal.raise_signal(signal.SIGINT)
        assert got == []
    finally:
        signal.signal(signal.SIGINT, old)


# --- A real signal to a real process --------------------------------------------------------


def _handled(pid: int) -> bool:
    """Whether the process has handlers for SIGINT and SIGTERM (``SigCgt`` in /proc): from the
    first line of ``pendulab``'s entry point until Python's exit resets them. Before and after,
    the kernel acts alone (the process dies by the signal): not a run a person interrupts."""
    try:
        with open(f"/proc/{pid}/status") as f:
            mask = int(next(line for line in f if line.startswith("SigCgt:")).split()[1], 16)
    except (OSError, StopIteration):
        return False
    return all(mask >> (s - 1) & 1 for s in (signal.SIGINT, signal.SIGTERM))


def _launch(args, tmp_path, more_env):
    """Start ``pendulab ARGS`` with its own TMPDIR (and ``more_env``) and wait until its entry
    point has started (its handlers in place; 60 s at most, a hang guard): (process, TMPDIR)."""
    tmpdir = tmp_path / "tmp"
    tmpdir.mkdir(exist_ok=True)
    env = {**os.environ, "TMPDIR": str(tmpdir), "PYTHONUNBUFFERED": "1", **more_env}
    proc = subprocess.Popen([sys.executable, "-m", "pendulab", *map(str, args)], preexec_fn=default_signals,
                            cwd=tmp_path, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    start = time.monotonic()
    while not _handled(proc.pid) and proc.poll() is None and time.monotonic() - start < 60:
        time.sleep(0.005)
    return proc, tmpdir


def _signal_run(args, delay, sig, tmp_path, **more_env):
    """Start ``pendulab ARGS`` with its own TMPDIR (and ``more_env``); ``delay`` s after its
    entry point started, send ``sig`` if it still runs; return (exit status, stderr)."""
    proc, tmpdir = _launch(args, tmp_path, more_env)
    time.sleep(delay)
    if _handled(proc.pid):
        proc.send_signal(sig)
    # a hang guard: a run the signal did not stop goes on to its end
    _, err = proc.communicate(timeout=300)
    assert list(tmpdir.iterdir()) == [], "a temporary file or folder was left"
    return proc.returncode, err


def _run_seconds(args, tmp_path, **more_env):
    """The seconds a whole run of ``pendulab ARGS`` lasts on this machine, now, from its entry
    point's start to its exit (status 0): the span over which a test spreads its signals."""
    proc, tmpdir = _launch(args, tmp_path, more_env)
    start = time.monotonic()
    _, err = proc.communicate(timeout=600)  # a hang guard
    seconds = time.monotonic() - start
    assert proc.returncode == 0 and list(tmpdir.iterdir()) == [], err
    return seconds


def _assert_stopped(code, err, sig, command):
    """One line, the exit status of the signal, no traceback (or the run had finished)."""
    if code == 0:  # finished before the signal: nothing to check
        return False
    word, status = ("interrupted", 130) if sig == signal.SIGINT else ("terminated", 143)
    assert code == status, (code, err)
    # "pendulab: interrupted" where Ctrl+C came while the command line was loading
    assert err.splitlines() in ([f"pendulab {command}: {word}"], [f"pendulab: {word}"]), err
    return True


ESTIMATE = ["estimate", "-l", "1", "-a", "2", "--step", "1e-3,2e-8"]  # about 4 * 10^8 steps (3.5 s here)
#: Ten times the steps of ESTIMATE (about 30 s here): work that outlasts a signal sent within
#: a few seconds even on a machine several times faster, so that every try stops a running run.
ESTIMATE_LONG = ESTIMATE[:-1] + ["1e-3,2e-9"]


@pytest.mark.slow
@pytest.mark.parametrize(("args", "tries"), [
    (ESTIMATE, 12),
    (ESTIMATE[:-1] + ["1e-3,5e-8", "--method", "rk4", "--dense"], 6),
    (["simulate", "--step", "1e-6", "--t-max", "1", "--json"], 4),  # 10^6 rows in JSON (6 s here)
    (["sweep", "--amplitude", "0.1:3:200", "--step", "1e-5", "--method", "taylor:8"], 4),  # 6 s here
])
def test_ctrl_c_mid_run_ends_with_one_line_and_130(tmp_path, args, tries):
    """Ctrl+C at varied moments (while Python starts, while the kernel runs, while its result
    is converted): exit 130 and one line, never a crash (139) or a SystemError."""
    # The moments are fractions of a whole run timed here first, not fixed seconds: on a
    # machine twice as fast as ours fixed delays land after the run (exit 0, nothing tested),
    # on a slow one never near its end (the conversion).
    whole = _run_seconds(args, tmp_path)
    stopped = 0
    for i in range(tries):
        code, err = _signal_run(args, 0.9 * whole * i / tries, signal.SIGINT, tmp_path)
        stopped += _assert_stopped(code, err, signal.SIGINT, args[0])
    # The first half of the tries come before 0.45 of the timed run: a run 2x faster than it
    # still had them all mid-run.
    assert stopped >= tries // 2, (stopped, tries, whole)


@pytest.mark.slow
def test_sigterm_mid_run_ends_with_one_line_and_143(tmp_path):
    for i in range(6):
        code, err = _signal_run(ESTIMATE_LONG, 0.8 * i, signal.SIGTERM, tmp_path)
        assert _assert_stopped(code, err, signal.SIGTERM, "estimate"), (i, code, err)  # the run outlasts 4 s


@pytest.mark.slow
def test_an_interrupted_key_keeps_the_old_output_and_leaves_no_temporary_file(tmp_path):
    """key on many groups, stopped by SIGINT or SIGTERM: the older key and its class file intact
    (or both new, where the run had finished), nothing left beside them."""
    groups = tmp_path / "groups.txt"
    groups.write_text("\n".join(f"{10000 + i} {20000 + 3 * i} {50000 + 7 * i}" for i in range(1000)) + "\n")  # no student twice
    out, side = tmp_path / "key.csv", tmp_path / "key-class.csv"
    for i, sig in enumerate([signal.SIGINT, signal.SIGTERM] * 3):
        out.write_text("old key\n")
        side.write_text("old class\n")
        code, err = _signal_run(["key", "--groups", groups, "--output", out], 0.6 * i, sig, tmp_path)
        pair = out.read_text() == "old key\n", side.read_text() == "old class\n"
        assert pair == ((True, True) if _assert_stopped(code, err, sig, "key") else (False, False)), (code, err)
        left = {p.name for p in tmp_path.iterdir()}  # no temporary file beside the key
        assert left == {"groups.txt", "key.csv", "key-class.csv", "tmp"}, left


@pytest.mark.slow
def test_sigterm_during_report_leaves_no_temporary_folder(tmp_path):
    pytest.importorskip("typst")
    out = tmp_path / "report.pdf"
    out.write_bytes(b"old report")
    for delay in (1.0, 4.0, 8.0):
        code, err = _signal_run(["report", "--output", out], delay, signal.SIGTERM, tmp_path)
        if _assert_stopped(code, err, signal.SIGTERM, "report"):
            assert out.read_bytes() == b"old report"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["report.pdf", "tmp"]
        out.write_bytes(b"old report")


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_between_the_key_and_its_class_file_waits_for_both(tmp_path, sig):
    """Ctrl+C (or SIGTERM) that comes after key.csv has been renamed into place and before
    key-class.csv has: a real signal to a real ``pendulab key``, sent from inside the first
    rename. The pair is written as one, so the run ends with its one line and 130 (143)
    after both files are new; never a new key beside the old class file."""
    groups = tmp_path / "groups.txt"
    groups.write_text("262 407 634\n")
    out, side = tmp_path / "key.csv", tmp_path / "key-class.csv"
    out.write_text("old key\n")
    side.write_text("old class\n")
    code = (
        "import os, signal, sys\n"
        "real = os.replace\n"
        "def replace(src, dst):\n"
        "    real(src, dst)\n"
        "    if os.path.basename(dst) == 'key.csv':\n"
        f"        os.kill(os.getpid(), {int(sig)})\n"
        "os.replace = replace\n"
        f"sys.argv = ['pendulab', 'key', '--groups', {str(groups)!r}, '--output', {str(out)!r}]\n"
        "from pendulab.__main__ import run\n"
        "sys.exit(run())\n"
    )
    res = subprocess.run([sys.executable, "-c", code], preexec_fn=default_signals,
                         cwd=tmp_path, capture_output=True, text=True, timeout=300,
                         env={**os.environ, "TMPDIR": str(tmp_path)})
    word, status = ("interrupted", 130) if sig == signal.SIGINT else ("terminated", 143)
    assert (res.returncode, res.stderr.splitlines()) == (status, [f"pendulab key: {word}"]), res.stderr
    assert out.read_text().startswith("line,students") and side.read_text().startswith("problem,answer,value")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["groups.txt", "key-class.csv", "key.csv"]


@pytest.mark.slow
def test_ctrl_c_while_the_command_line_loads_is_one_line():
    """Ctrl+C in the first milliseconds of ``python -m pendulab``: ``-X importtime`` writes a
    line as each module finishes loading, and SIGINT goes at several delays after the line of
    ``signal``, which the entry point loads first, after the package's own first lines. Each
    try ends with the one line and 130, never a traceback."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    for delay in (0.0, 0.0005, 0.001, 0.002, 0.004, 0.008, 0.016):
        proc = subprocess.Popen([sys.executable, "-X", "importtime", "-m", "pendulab", "length", "262", "407", "634"],
                                preexec_fn=default_signals,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
        assert proc.stderr is not None
        loaded = []
        for line in proc.stderr:
            loaded.append(line.rsplit("|", 1)[-1].strip())
            if loaded[-1] == "signal":
                break
        time.sleep(delay)
        proc.send_signal(signal.SIGINT)
        rest = proc.stderr.read()
        code = proc.wait(timeout=60)
        assert loaded[-1] == "signal" and "pendulab" in loaded, loaded  # the package, then the entry point
        said = [line for line in rest.splitlines() if not line.startswith("import time:")]
        assert code == 130 and said in (["pendulab: interrupted"], ["pendulab length: interrupted"]), (delay, code, rest)


# --- A signal while numba compiles a kernel ------------------------------------------------

#: Run ``pendulab`` with the signal ``SIG`` sent from inside LLVM's callback into Python
#: (numba's "object compiled" hook, through ``ctypes``) at the ``K``-th kernel object the main
#: thread compiles: where a signal that came while LLVM worked is handled. Python's own
#: handler raises there, and ``ctypes`` prints the exception and goes on.
_IN_COMPILE = """\
import os, signal, sys, threading
from numba.core import codegen
hook = codegen.CPUCodeLibrary._object_compiled_hook.__func__
seen = [0]
def notify(cls, ll_module, buf):
    if threading.current_thread() is threading.main_thread():
        seen[0] += 1
        if seen[0] == {k}:
            os.kill(os.getpid(), {sig})
    hook(cls, ll_module, buf)
codegen.CPUCodeLibrary._object_compiled_hook = classmethod(notify)
sys.argv = ["pendulab", *{args!r}]
from pendulab.__main__ import run
sys.exit(run())
"""

SWEEP = ["sweep", "--amplitude", "0.1:3:40", "--step", "1e-2", "--method", "rk4", "--output", "out.csv"]


@pytest.mark.slow
@pytest.mark.parametrize(("args", "k", "sig"), [
    (SWEEP, 1, signal.SIGINT),  # the periods' AGM kernel, compiled before the sweep's threads start
    (SWEEP, 5, signal.SIGTERM),
    (["simulate", "--t-max", "1", "--step", "1e-3", "--plot", "out.png"], 1, signal.SIGINT),
    (["estimate", "-l", "1", "-a", "2", "--step", "1e-3"], 3, signal.SIGTERM),
])
def test_a_signal_while_a_kernel_compiles_ends_the_run(tmp_path, args, k, sig):
    """With an empty numba cache (each kernel compiled on first use), SIGINT or SIGTERM
    that reaches Python while a kernel compiles in the main thread: exit 130 (143) and one
    line, after the compilation; never "Exception ignored" and a run that goes on to exit 0.
    No output file is written, no temporary file left."""
    code = _IN_COMPILE.format(k=k, sig=int(sig), args=args)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "TMPDIR": str(tmp_path)}
    res = subprocess.run([sys.executable, "-c", code], preexec_fn=default_signals,
                         cwd=tmp_path, capture_output=True, text=True,
                         timeout=600, env=env)
    word, status = ("interrupted", 130) if sig == signal.SIGINT else ("terminated", 143)
    assert (res.returncode, res.stderr.splitlines()) == (status, [f"pendulab {args[0]}: {word}"]), res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["numba"]


@pytest.mark.slow
def test_ctrl_c_while_a_cold_sweep_compiles_ends_with_one_line(tmp_path):
    """A real Ctrl+C from outside at several moments of a sweep's first run after an install
    (an empty numba cache: seconds of compiling, in the main thread and on the sweep's
    threads, then the sweep itself): each try ends with 130 and one line, and writes no output file."""
    # h = 1e-7: the sweep itself lasts well past the last try (about 30 s on two cores) even
    # where compiling is fast, so every try stops a running sweep, never one that has finished.
    cold = [*SWEEP[:4], "1e-7", *SWEEP[5:]]
    for i, delay in enumerate((0.5, 1.5, 2.5, 3.5)):
        code, err = _signal_run(cold, delay, signal.SIGINT, tmp_path, NUMBA_CACHE_DIR=str(tmp_path / f"numba{i}"),
                                NUMBA_NUM_THREADS="2")
        assert _assert_stopped(code, err, signal.SIGINT, "sweep"), (delay, code, err)
        assert not (tmp_path / "out.csv").exists()


@pytest.mark.slow
@pytest.mark.parametrize("method", ["rk4", "taylor2"])  # the scalar searches; the lock-step lanes of (3)
def test_a_signal_stops_a_long_sweep_on_threads_within_seconds(tmp_path, method):
    """A sweep on two threads whose every block of 16 pendulums is minutes of work (h = 1e-7
    near the top): SIGINT or SIGTERM in the middle stops every thread within a piece, and the
    run ends with its one line and 130 (143), with no output file."""
    env = {**os.environ, "NUMBA_NUM_THREADS": "2", "TMPDIR": str(tmp_path)}
    warm = ["sweep", "--amplitude", "1:2:2", "--step", "1e-2", "--method", method]  # kernels compiled first
    subprocess.run([sys.executable, "-m", "pendulab", *warm], preexec_fn=default_signals,
                   env=env, capture_output=True, timeout=600, check=True)
    args = ["sweep", "--amplitude", "170deg:179deg:32", "--step", "1e-7", "--method", method, "--output", "out.csv"]
    for delay, sig in ((1.0, signal.SIGINT), (3.0, signal.SIGTERM), (5.0, signal.SIGINT)):
        proc = subprocess.Popen([sys.executable, "-m", "pendulab", *args], preexec_fn=default_signals,
                                cwd=tmp_path, env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        start = time.monotonic()
        while not _handled(proc.pid) and proc.poll() is None and time.monotonic() - start < 60:
            time.sleep(0.005)
        time.sleep(delay)
        assert proc.poll() is None, proc.stderr.read() if proc.stderr else ""  # still at work: minutes of it
        proc.send_signal(sig)
        # A hang guard, not a speed claim: the sweep's work is minutes, and a thread that went
        # on past its piece would hold the process beyond it (TimeoutExpired fails the test).
        _, err = proc.communicate(timeout=60)
        word, status = ("interrupted", 130) if sig == signal.SIGINT else ("terminated", 143)
        assert (proc.returncode, err.splitlines()) == (status, [f"pendulab sweep: {word}"]), err
        assert sorted(p.name for p in tmp_path.iterdir()) == [], "an output or temporary file was left"


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_during_the_servers_warm_up_stops_it_with_its_line(tmp_path, sig):
    """``pendulab serve`` with an empty numba cache compiles its kernels on warm-up threads
    while it starts serving: SIGINT or SIGTERM then stops it with its one line and 130
    (143), the compilation on those threads notwithstanding."""
    pytest.importorskip("uvicorn")
    import socket

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "TMPDIR": str(tmp_path), "PYTHONUNBUFFERED": "1"}
    word, status = ("interrupted", 130) if sig == signal.SIGINT else ("terminated", 143)
    for delay in (0.2, 1.5, 3.0):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        proc = subprocess.Popen([sys.executable, "-m", "pendulab", "serve", "--port", str(port)], preexec_fn=default_signals,
                                cwd=tmp_path, env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        assert proc.stderr is not None
        banner = proc.stderr.readline()
        assert banner.startswith("pendulab explorer: "), banner
        time.sleep(delay)
        assert proc.poll() is None
        proc.send_signal(sig)
        rest = proc.stderr.read()  # to its end: the process has exited (or closed stderr)
        code = proc.wait(timeout=120)  # a hang guard: a server that went on serving never exits
        assert (code, rest.splitlines()) == (status, [f"pendulab serve: {word}"]), rest
        shutil.rmtree(tmp_path / "numba", ignore_errors=True)  # each try compiles afresh


@pytest.mark.slow
def test_ctrl_c_while_serve_imports_on_a_cold_cache_ends_it_with_its_line(tmp_path):
    """``pendulab serve`` on an empty numba cache: Ctrl+C at moments spread over its imports
    (the web app's, while the warm-up thread imports and compiles the kernels), before the
    banner. A KeyboardInterrupt that Python raised inside a callback there (a module lock's
    weak reference) cannot propagate: ``core.interrupt.unraisable`` keeps it silent and the
    command's ``check_signals`` ends it before the server starts. Each try: 130 and one line,
    no "Exception ignored", no traceback, and the process ends by itself (never serves on)."""
    pytest.importorskip("uvicorn")
    import socket

    def launch(i):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / f"numba{i}"), "TMPDIR": str(tmp_path),
               "PYTHONUNBUFFERED": "1"}
        proc = subprocess.Popen([sys.executable, "-m", "pendulab", "serve", "--port", str(port)],
                                preexec_fn=default_signals, cwd=tmp_path, env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        began = time.monotonic()
        while not _handled(proc.pid) and proc.poll() is None and time.monotonic() - began < 60:
            time.sleep(0.002)
        return proc

    # The moments are fractions of the imports' span (entry point to banner, half a second
    # here), timed on this machine first: fixed delays all land after the banner on a
    # machine a few times faster, and the imports go untested.
    proc = launch("-timed")
    try:
        timed = time.monotonic()
        assert proc.stderr is not None and proc.stderr.readline().startswith("pendulab explorer: ")
        imports = time.monotonic() - timed
        proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=120)  # a hang guard
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    early = 0
    for i, fraction in enumerate((0.0, 0.1, 0.2, 0.4, 0.6, 0.9, 1.2, 1.6, 2.0)):
        delay = fraction * imports
        proc = launch(i)
        try:
            time.sleep(delay)
            proc.send_signal(signal.SIGINT)
            # a hang guard, not a speed claim: a swallowed Ctrl+C would leave the server serving
            _, err = proc.communicate(timeout=120)
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
        lines = err.splitlines()
        assert proc.returncode == 130, (delay, proc.returncode, err)
        assert "Traceback" not in err and "Exception ignored" not in err, (delay, err)
        if lines and lines[0].startswith("pendulab explorer: "):  # the imports were over: serving
            assert lines[1:] == ["pendulab serve: interrupted"], (delay, err)
        else:
            early += 1
            assert lines in (["pendulab serve: interrupted"], ["pendulab: interrupted"]), (delay, err)
    assert early >= 3, ("too few tries landed before the banner to test the imports", imports)


@pytest.mark.slow
def test_a_daemon_thread_still_at_work_ends_the_process_without_pythons_shutdown():
    """After the command, a daemon thread still running (serve's warm-up compiling a kernel
    when Ctrl+C stopped the server) ends the process at once with the command's status and
    its output flushed: Python's shutdown, which tore the interpreter down under LLVM and
    aborted (SIGABRT), never runs (its atexit hooks neither)."""
    code = (
        "import atexit, sys, threading, time\n"
        "threading.Thread(target=time.sleep, args=(60,), daemon=True).start()\n"
        "atexit.register(lambda: print('shutdown ran', flush=True))\n"
        "sys.argv = ['pendulab', 'period', '-l', '1', '-a', 'pi/4']\n"
        "from pendulab.__main__ import run\n"
        "sys.exit(run())\n"
    )
    res = subprocess.run([sys.executable, "-c", code], preexec_fn=default_signals,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.startswith("period, AGM (7)-(8)"), res.stdout
    assert "shutdown ran" not in res.stdout
    # Without a daemon thread at work, the shutdown runs as usual.
    plain = code.replace("threading.Thread(target=time.sleep, args=(60,), daemon=True).start()\n", "")
    res = subprocess.run([sys.executable, "-c", plain], preexec_fn=default_signals,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0 and "shutdown ran" in res.stdout, res.stderr
