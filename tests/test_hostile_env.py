"""Files that are not files, outputs that must not be replaced, a hostile environment: each
reproduced as a person meets it, each answered in one line before the work."""
from __future__ import annotations

import math
import os
import re
import shutil
import socket
import stat
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import assert_one_line_error
from pendulab.core import atomic, methods
from pendulab.core import validate as v
from pendulab.core.errors import InputError
from pendulab.jobs import key

CLASS = "262 407 634\n99999 1\n"


def _pendulab(*args, stdin=None, stdout=subprocess.PIPE, env=None, timeout=120, cwd=None):
    return subprocess.run([sys.executable, "-m", "pendulab", *map(str, args)], stdin=stdin, stdout=stdout,
                          stderr=subprocess.PIPE, text=True, timeout=timeout, env={**os.environ, **(env or {})},
                          cwd=cwd)


# --- Finding 2: groups that are not regular files ------------------------------------------------


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_groups_from_an_endless_device_are_refused_at_the_byte_cap(cli, device):
    res = cli("key", "--groups", device)
    assert_one_line_error(res, "--groups", device, "at most 1e+07 bytes")


@pytest.mark.slow
def test_groups_from_a_named_pipe_with_no_writer_do_not_hang(tmp_path):
    fifo = tmp_path / "groups.fifo"
    os.mkfifo(fifo)
    # A hang guard, not a speed claim: an open that waits for a writer never returns, and
    # subprocess.run's timeout then fails the test (TimeoutExpired).
    res = _pendulab("key", "--groups", fifo, timeout=120)
    assert res.returncode == 2 and len(res.stderr.strip().splitlines()) == 1, res.stderr
    assert "--groups" in res.stderr and "at least one group" in res.stderr


def test_groups_from_a_pipe_that_stays_silent_are_refused_after_the_timeout(monkeypatch, tmp_path):
    """A writer that holds the pipe open and never writes: refused after READ_TIMEOUT."""
    monkeypatch.setattr(key, "READ_TIMEOUT", 0.5)
    fifo = tmp_path / "groups.fifo"
    os.mkfifo(fifo)
    writer = os.open(fifo, os.O_RDWR)  # a writer that writes nothing (O_RDWR: no wait for a reader)
    try:
        with pytest.raises(InputError, match=r"nothing came in 0\.5 s"):
            key.read_groups(fifo)
    finally:
        os.close(writer)


@pytest.mark.slow
def test_endless_standard_input_is_capped(tmp_path):
    """``yes | pendulab key --groups -`` (and /dev/stdin): the byte cap, not memory."""
    for path in ("-", "/dev/stdin"):
        yes = subprocess.Popen(["yes", "262 407 634"], stdout=subprocess.PIPE)
        try:
            res = _pendulab("key", "--groups", path, stdin=yes.stdout, timeout=120)
        finally:
            yes.kill()
            yes.wait()
        assert res.returncode == 2 and len(res.stderr.strip().splitlines()) == 1, res.stderr
        assert "at most 1e+07 bytes" in res.stderr


@pytest.mark.slow
def test_groups_from_standard_input(tmp_path):
    res = _pendulab("key", "--groups", "-", "--json", stdin=open(_groups(tmp_path), "rb"))  # noqa: SIM115
    assert res.returncode == 0, res.stderr
    assert '"students": [\n' in res.stdout or '"students"' in res.stdout


def _groups(tmp_path: Path, text: str = CLASS, name: str = "groups.txt") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# --- Finding 3: a cap on the number of groups ----------------------------------------------------


def test_the_group_cap_is_exact():
    """MAX_GROUPS groups are read; one more is refused, naming the line where it starts
    (comments and blank lines between them do not count)."""
    lines = [f"{100 + i} {i + 1}" for i in range(key.MAX_GROUPS)]
    assert len(key.parse_groups("# class\n\n" + "\n".join(lines))) == key.MAX_GROUPS
    with pytest.raises(InputError, match=f"at most {key.MAX_GROUPS} groups \\(line {key.MAX_GROUPS + 3} "):
        key.parse_groups("# class\n\n" + "\n".join(lines) + "\n5 5\n")


def test_a_large_valid_file_is_refused_before_the_work(cli, tmp_path):
    """2.5 million groups in a 9.9 MB file: one line at once, not hours."""
    text = "1 2\n" * 2_475_000
    assert len(text) < key.MAX_FILE_BYTES
    res = cli("key", "--groups", _groups(tmp_path, text))
    assert_one_line_error(res, "--groups", "at most 1000 groups")


# --- Finding 8: an output that is the input ------------------------------------------------------


@pytest.mark.parametrize("how", ["same", "spelled", "symlink", "hardlink"])
def test_the_output_may_not_be_the_groups_file(cli, tmp_path, monkeypatch, how):
    groups = _groups(tmp_path, name="g.csv")
    monkeypatch.chdir(tmp_path)
    out = {"same": "g.csv", "spelled": "./sub/../g.csv", "symlink": "link.csv", "hardlink": "hard.csv"}[how]
    (tmp_path / "sub").mkdir()
    if how == "symlink":
        os.symlink("g.csv", "link.csv")
    if how == "hardlink":
        os.link("g.csv", "hard.csv")
    res = cli("key", "--groups", "g.csv", "--output", out)
    assert_one_line_error(res, "--output", "other than the groups file")
    assert groups.read_text() == CLASS


# --- Finding 13: a byte order mark ---------------------------------------------------------------


def test_a_groups_file_with_a_byte_order_mark(cli, tmp_path):
    """Notepad's and Excel's UTF-8 files start with EF BB BF: the same groups as without it."""
    plain = tmp_path / "plain.txt"
    plain.write_bytes(CLASS.encode())
    bom = tmp_path / "bom.txt"
    bom.write_bytes(b"\xef\xbb\xbf" + CLASS.encode())
    assert key.read_groups(bom) == key.read_groups(plain) == [(262, 407, 634), (99999, 1)]
    res = cli("key", "--groups", bom, "--output", tmp_path / "k.csv")
    assert res.code == 0, res.err


# --- Findings 7 and 10: the atomic write ----------------------------------------------------------


def test_the_write_keeps_the_old_mode(tmp_path):
    target = tmp_path / "key.csv"
    target.write_text("old")
    os.chmod(target, 0o600)
    atomic.write_text(target, "new")
    assert target.read_text() == "new" and stat.S_IMODE(target.stat().st_mode) == 0o600


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o027])
def test_a_new_file_takes_the_umask(tmp_path, umask):
    old = os.umask(umask)
    try:
        atomic.write_text(tmp_path / "new.csv", "x")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "new.csv").stat().st_mode) == 0o666 & ~umask


def test_a_symlink_is_written_through(tmp_path):
    """The link stays a link; the file it names gets the new content (and keeps its mode)."""
    real = tmp_path / "real.csv"
    real.write_text("old")
    os.chmod(real, 0o640)
    link = tmp_path / "link.csv"
    os.symlink(real.name, link)
    atomic.check_writable("output", link)
    atomic.write_text(link, "new")
    assert link.is_symlink() and real.read_text() == "new" and stat.S_IMODE(real.stat().st_mode) == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.csv", "real.csv"]


def test_a_read_only_output_is_refused_before_the_work(cli, monkeypatch, tmp_path):
    from pendulab.jobs import key as answer

    groups = _groups(tmp_path)
    out = tmp_path / "key.csv"
    out.write_text("teacher's key")
    os.chmod(out, 0o444)
    worked = []
    real = answer.answer_key
    monkeypatch.setattr(answer, "answer_key", lambda *a, **k: worked.append(1) or real(*a, **k))
    res = cli("key", "--groups", groups, "--output", out)
    assert_one_line_error(res, "--output", "read-only")
    assert out.read_text() == "teacher's key"
    assert worked == []  # refused before the key was computed


@pytest.mark.parametrize("special", ["link to /dev/null", "fifo"])
def test_an_output_that_is_not_a_regular_file_is_refused(cli, tmp_path, special):
    """A named pipe, or a link to a device: refused (root's rename would replace /dev/null)."""
    out = tmp_path / "out.csv"
    if special == "fifo":
        os.mkfifo(out)
    else:
        os.symlink("/dev/null", out)
    res = cli("key", "--groups", _groups(tmp_path), "--output", out)
    assert_one_line_error(res, "--output", "a regular file or a new name")
    assert os.path.exists("/dev/null") and stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_another_users_file_in_a_sticky_folder_is_refused(tmp_path, monkeypatch):
    """/tmp-like folder (mode 1777): only the owner may replace a file there, so the rename
    after the work would fail. These tests run as root, whom the kernel lets replace it:
    the user (4242) and the file's owner (4343) are given by patching os.geteuid and os.stat."""
    sticky = tmp_path / "shared"
    sticky.mkdir()
    os.chmod(sticky, 0o1777)
    target = sticky / "key.csv"
    target.write_text("someone's")
    real_stat = os.stat

    def stat_as_owned(p, *args, **kwargs):
        st = real_stat(p, *args, **kwargs)
        return _owned(st, 4343) if Path(p) == target else st

    monkeypatch.setattr(os, "geteuid", lambda: 4242)
    monkeypatch.setattr(os, "stat", stat_as_owned)
    monkeypatch.setattr(os, "access", lambda p, mode, **k: True)  # the folder is writable to all
    with pytest.raises(InputError, match="only its owner may replace it"):
        atomic.check_writable("output", target)
    assert target.read_text() == "someone's"


def _owned(st: os.stat_result, uid: int) -> os.stat_result:
    fields = list(st)
    fields[4] = uid
    return os.stat_result(fields)


def test_names_up_to_the_file_systems_limit(cli, tmp_path):
    """255 bytes (NAME_MAX): written (the temporary name is short); 256: one line, before the work."""
    groups = _groups(tmp_path)
    longest = tmp_path / ("k" * 250 + ".json")
    res = cli("key", "--groups", groups, "--output", longest)
    assert res.code == 0, res.err
    assert longest.exists()
    res = cli("key", "--groups", groups, "--output", tmp_path / ("k" * 251 + ".json"))
    assert_one_line_error(res, "--output", "at most 255 bytes")
    # A CSV key writes NAME-class.csv beside it: that name is checked too, before the work.
    res = cli("key", "--groups", groups, "--output", tmp_path / ("k" * 250 + ".csv"))
    assert_one_line_error(res, "--output", "at most 255 bytes")


def test_an_immutable_file_is_refused_before_the_work(tmp_path):
    target = tmp_path / "key.csv"
    target.write_text("old")
    if shutil.which("chattr") is None or subprocess.run(["chattr", "+i", target]).returncode != 0:
        pytest.skip("chattr +i is not allowed here (needs CAP_LINUX_IMMUTABLE)")
    try:
        with pytest.raises(InputError, match="read-only"):
            atomic.check_writable("output", target)
    finally:
        subprocess.run(["chattr", "-i", target])


# --- Finding 11: standard output that cannot be written --------------------------------------------


@pytest.mark.slow
def test_a_full_disk_on_stdout_is_one_line():
    with open("/dev/full", "w") as full:
        res = _pendulab("simulate", "--step", "1e-3", "--t-max", "5", stdout=full)
    assert res.returncode == 1
    assert res.stderr.splitlines() == ["pendulab simulate: error: cannot write to standard output: No space left on device"]


@pytest.mark.slow
def test_a_closed_pipe_on_stdout_ends_silently():
    r, w = os.pipe()
    os.close(r)  # the reader has gone (``pendulab simulate | head -1``)
    try:
        res = _pendulab("simulate", "--step", "1e-4", "--t-max", "20", "--csv", stdout=w)
    finally:
        os.close(w)
    assert res.returncode == 141
    assert res.stderr == ""  # no "Broken pipe": the reader has gone because it has all it wanted


# --- Finding 12: a read-only install, a corrupt cache, SOURCE_DATE_EPOCH ------------------------------


@pytest.mark.slow
def test_a_read_only_install_falls_back_and_a_corrupt_cache_is_rebuilt(tmp_path):
    """The package where numba cannot write beside it (``__pycache__`` is not a folder) and a
    HOME whose cache folder cannot be made: the kernels are cached in the temporary folder,
    with one line saying so. Then every cache file there is overwritten with garbage: the
    next run compiles again and gives the same answer."""
    import pendulab

    pkg = tmp_path / "site"
    shutil.copytree(Path(pendulab.__file__).parent, pkg / "pendulab",
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    for folder in [pkg / "pendulab", *[p for p in (pkg / "pendulab").rglob("*") if p.is_dir()]]:
        (folder / "__pycache__").write_text("")  # numba's makedirs fails: no in-tree cache
    home = tmp_path / "home"
    home.mkdir()
    (home / ".cache").write_text("")  # nor a user-wide one
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = {"PYTHONPATH": str(pkg), "HOME": str(home), "TMPDIR": str(tmp), "XDG_CACHE_HOME": str(home / ".cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    args = ("estimate", "-l", "1", "-a", "1", "--step", "1e-2", "--json")
    first = _pendulab(*args, env=env, timeout=600)
    assert first.returncode == 0, first.stderr
    assert first.stderr.splitlines() == [line for line in first.stderr.splitlines() if line.startswith("pendulab: note:")]
    assert len(first.stderr.splitlines()) == 1 and str(tmp) in first.stderr
    files = [p for p in tmp.rglob("*") if p.suffix in (".nbi", ".nbc")]
    assert files
    for p in files:
        p.write_bytes(os.urandom(64))
    second = _pendulab(*args, env=env, timeout=600)
    assert second.returncode == 0 and "Traceback" not in second.stderr, second.stderr
    assert second.stdout == first.stdout


@pytest.mark.parametrize("value", ["abc", "-1", "1e9", "99999999999999999999", " 12x", "١٢٣"])
def test_a_malformed_source_date_epoch_is_one_line(cli, monkeypatch, value):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", value)
    res = cli("period", "-l", "1", "-a", "1")
    assert_one_line_error(res, "SOURCE_DATE_EPOCH", "seconds since 1970")


@pytest.mark.parametrize("value", ["", "0", "1700000000", "253402300799"])
def test_a_valid_source_date_epoch_is_taken(cli, monkeypatch, value):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", value)
    assert cli("period", "-l", "1", "-a", "1").code == 0


# --- Finding 6 (CLI): a scheduler address where no Dask scheduler listens ---------------------------


@pytest.mark.slow
@pytest.mark.parametrize("reply", [b"", b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n" * 4])
def test_a_scheduler_port_that_is_not_dask_is_one_line(cli, monkeypatch, reply):
    """A server that accepts and says nothing (Dask would wait for ever), or answers HTTP
    (whose bytes Dask reads as a frame length of exabytes): one line within the timeout."""
    pytest.importorskip("dask.distributed")
    from pendulab.jobs.sweep import cluster

    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", 1)
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    held = []

    def serve():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            held.append(conn)
            if reply:
                conn.sendall(reply)

    threading.Thread(target=serve, daemon=True).start()
    try:
        res = cli("sweep", "--amplitude", "0.1:1:3", "--step", "1e-2", "--method", "taylor2",
                  "--scheduler", f"tcp://127.0.0.1:{server.getsockname()[1]}")
    finally:
        server.close()
        for c in held:
            c.close()
    # without the bound the call never returns (a hang, not a failure): the bound is what answers
    assert_one_line_error(res, "--scheduler", "reachable Dask scheduler")


# --- Finding 5 (CLI): work weighed by the method's cost --------------------------------------------


def test_a_list_of_tiny_steps_is_refused_before_the_work(cli):
    """800 items of 4e-9 s (about 10 hours): one line at once."""
    res = cli("estimate", "-a", "1", "--step", ",".join(["4e-9"] * 800))
    assert_one_line_error(res, "--step", "must be larger or fewer steps (at most", "in all; these need")


def test_limits_weigh_steps_by_the_methods_cost(cli):
    """What taylor2 may run is refused for taylor:30, whose steps cost 40 times more: one run
    of 10^9 steps, and a list of two runs each within one run's limit, too many together."""
    limit = v.steps_for("taylor:30", 2e9)  # about 5e7 steps of taylor:30
    assert 4e7 < limit < 6e7
    res = cli("estimate", "-a", "1", "-l", "1", "--t-max", "1000", "--step", "1e-6", "--method", "taylor:30")
    assert_one_line_error(res, "--step", "steps of taylor:30")
    res = cli("estimate", "-a", "1", "-l", "1", "--t-max", "40", "--step", "1e-6,2e-6", "--method", "taylor:30")
    assert_one_line_error(res, "--step = 1e-6 ", "of taylor:30", "these need 6e+07")
    assert v.work_within("steps", "1e-6,2e-6", 40 / 1e-6 + 40 / 2e-6, "taylor2", 2e9)


@settings(max_examples=200, deadline=None)
@given(name=st.sampled_from([m.name for m in methods.menu()] + [f"taylor:{p}" for p in range(1, 31)]),
       budget=st.floats(1, 1e12), frac=st.floats(0.5, 2.0))
def test_the_budget_refuses_exactly_above_it(name, budget, frac):
    """work_within accepts ``steps`` iff steps x cost <= budget; steps_for is the largest whole
    count within it. Searched around the boundary (frac near 1), where an off-by-one hides."""
    cost = methods.cost_per_step(name)
    steps = frac * budget / cost
    if steps * cost <= budget:
        assert v.work_within("steps", "x", steps, name, budget) == steps
    else:
        with pytest.raises(InputError):
            v.work_within("steps", "x", steps, name, budget)
    n = v.steps_for(name, budget)
    assert n * cost <= budget * (1 + 1e-12) or n == 1
    assert (n + 1) * cost > budget


def test_the_cost_model():
    """Relative to taylor2; every method of the menu has a measured cost, and every kernel is
    on the menu or is the Taylor family's; rising with the Taylor order (measured in
    benchmarks/method_cost.py)."""
    assert methods.cost_per_step("taylor2") == 1.0
    menu = methods.menu()
    assert set(methods.STEP_COST) == {m.code for m in menu} == set(methods.Kernel) - {methods.Kernel.TAYLOR}
    for m in menu:
        assert 1.0 <= methods.cost_per_step(m) < 10, m.name
    costs = [methods.cost_per_step(f"taylor:{p}") for p in range(1, methods.MAX_TAYLOR_ORDER + 1)]
    assert all(b > a for a, b in zip(costs, costs[1:]))
    assert 30 < costs[-1] < 50 and 1 < methods.cost_per_step("rk4") < 3
    with pytest.raises(InputError):
        methods.cost_per_step("euler")
    assert math.isfinite(methods.cost_per_step(methods.resolve("verlet")))


@pytest.mark.parametrize("kind", ["regular", "pipe"])
def test_the_byte_cap_is_exact_for_files_and_pipes(monkeypatch, tmp_path, kind):
    """At the cap exactly: read; one byte more: refused, for a regular file (by its size)
    and for a pipe (``/dev/fd/N``, by what it gave). The cap lowered to 64 bytes for the search."""
    monkeypatch.setattr(key, "MAX_FILE_BYTES", 64)
    line = b"262 407 634\n"
    for size, ok in ((64, True), (65, False), (63, True), (1000, False)):
        data = (line * 100)[:size - 1] + b"\n"
        if kind == "regular":
            path = tmp_path / f"g{size}.txt"
            path.write_bytes(data)
            r = None
        else:
            r, w = os.pipe()  # the data waits in the pipe; its only writer closed: then EOF
            os.write(w, data)
            os.close(w)
            path = Path(f"/dev/fd/{r}")
        try:
            if ok:
                assert key.read_groups(path)[0] == (262, 407, 634)
            else:
                with pytest.raises(InputError, match="at most 6e\\+01 bytes"):
                    key.read_groups(path)
        finally:
            if r is not None:
                os.close(r)


def test_the_sweeps_cap_weighs_steps_by_cost():
    """A sweep whose steps are a tenth of the cap (counted with scipy's K, not the library's
    AGM) is refused for taylor:30, whose steps cost 40 times those of taylor2."""
    from scipy.special import ellipk

    from pendulab.jobs.sweep import MAX_TOTAL_STEPS, sweep

    amplitudes = np.linspace(0.1, 3.0, 2000)
    periods = 4 * np.sqrt(1.0 / 9.80665) * ellipk(np.sin(amplitudes / 2) ** 2)
    h = float(np.sum(1.5 * periods)) / (MAX_TOTAL_STEPS / 10)
    steps = float(np.sum(1.5 * periods + 4 * h)) / h
    assert steps < MAX_TOTAL_STEPS < steps * methods.cost_per_step("taylor:30")
    with pytest.raises(InputError, match="weighed by their cost") as err:
        sweep(amplitudes, h, "taylor:30")
    need = float(re.search(r"these need ([0-9.e+]+)", str(err.value))[1])
    assert need == pytest.approx(steps * methods.cost_per_step("taylor:30"), rel=1e-3)
