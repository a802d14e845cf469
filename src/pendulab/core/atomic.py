"""Atomic output: write to a temporary file beside the target, then rename.

A failed run leaves no half-written file and never destroys an older good one. Every
byte goes through :func:`pendulab.core.streams.write_all` (a short write is followed by
another, a full disk is an error). The file written keeps the old file's permission bits
(a key kept at 0600 stays private) less setuid, setgid and sticky, or takes those the
umask gives a new file. A symbolic link of one's own is written through: its target is
replaced and the link stays. Refused by :func:`check_writable`, before the work, each in
one line: a read-only file, a file that is not a regular file, a file another user owns
in a sticky folder such as /tmp, a link another user made in a sticky folder (the kernel's
``protected_symlinks`` rule, which a rename would get around), a link to a file of
another type (``report.pdf -> notes.txt``), and a name the file system cannot hold.

Several files written as one (:func:`write_together`) are committed through a journal:
a ``.pendulab-<pid>-<hex>.journal`` beside them names each finished temporary file and
its target before the first rename, and is removed after the last. A run killed between
(SIGKILL, a power cut) leaves the journal; the next write into that folder finishes the
renames first (:func:`recover`), so the files are all new or all old. Temporary files and
folders carry their process's id: those of a process that no longer runs are removed.
"""
from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import secrets
import shutil
import stat
import tempfile
from collections.abc import Iterator, Sequence
from pathlib import Path

from .errors import InputError, shown
from .interrupt import check_signals, deferred
from .streams import WriteError, sync, write_all, write_file

#: Permission bits an output keeps from the file it replaces: never setuid, setgid or sticky.
_KEPT_BITS = 0o777


def _real(path: str | os.PathLike) -> Path:
    """``path``, a symbolic link followed to the file it names (which may not exist yet)."""
    p = Path(path)
    return Path(os.path.realpath(p)) if p.is_symlink() else p


def _temp_name(target: Path, kind: str = "tmp") -> Path:
    """A temporary name beside ``target``, short whatever the target's length (a name of
    255 bytes still has room): ``.pendulab-<pid>-<16 hex digits>.tmp``."""
    return target.with_name(f".pendulab-{os.getpid()}-{secrets.token_hex(8)}.{kind}")


_OURS = re.compile(r"\.pendulab-(\d+)-[0-9a-f]{16}\.(tmp|journal|jtmp)")


def _gone(pid: int) -> bool:
    """Whether no process ``pid`` runs (another user's counts as running)."""
    if pid == os.getpid():
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:
        return False
    return False


def _mine(st: os.stat_result) -> bool:
    return not hasattr(os, "geteuid") or st.st_uid == os.geteuid()


def recover(folder: str | os.PathLike) -> None:
    """Finish the commits that a killed run left in ``folder`` and remove its temporary files.

    A journal of a process that no longer runs names finished temporary files: each still
    there is renamed onto its target (the run had got past the point of no return), then
    the journal goes. Temporary files of such a process that no journal names are removed.
    Only regular files of this user, never through a link.
    """
    folder = Path(folder)
    try:
        names = os.listdir(folder)
    except OSError:
        return
    ours = []
    for name in names:
        m = _OURS.fullmatch(name)
        if m is None or not _gone(int(m[1])):
            continue
        try:
            st = os.lstat(folder / name)
        except OSError:
            continue
        if stat.S_ISREG(st.st_mode) and _mine(st):
            ours.append((m[2], name))
    for kind, name in sorted(ours, key=lambda x: x[0] != "journal"):  # journals first
        if kind == "journal":
            with contextlib.suppress(OSError, ValueError, TypeError):
                pairs = json.loads((folder / name).read_text(encoding="utf-8"))
                for tmp, target in pairs:
                    if _OURS.fullmatch(tmp) and "/" not in target and (folder / tmp).is_file():
                        os.replace(folder / tmp, folder / target)
                os.unlink(folder / name)
        else:
            with contextlib.suppress(OSError):
                os.unlink(folder / name)


def _check_link(name: str, path: Path) -> None:
    """Refuse a symbolic link that another user made in a sticky, world-writable folder
    (whose owner is not the link's), and a link whose target has another extension: the
    write would replace another person's file, or a file of another type."""
    try:
        lst = os.lstat(path)
    except OSError:
        return
    if not stat.S_ISLNK(lst.st_mode):
        return
    folder = path.parent if str(path.parent) else Path(".")
    with contextlib.suppress(OSError):
        fst = os.stat(folder)
        sticky = fst.st_mode & stat.S_ISVTX and fst.st_mode & stat.S_IWOTH
        euid = os.geteuid() if hasattr(os, "geteuid") else lst.st_uid
        if sticky and lst.st_uid not in (euid, fst.st_uid):
            raise InputError(name, shown(path), f"a path that is not another user's link (in the sticky folder "
                                                f"{shown(folder)} only the link's owner may write through it)")
    target = Path(os.path.realpath(path))
    if target.is_file() and target.suffix.lower() != path.suffix.lower():
        raise InputError(name, shown(path), f"a link to a file of the same type (it names {shown(target)}, "
                                            "which would be replaced)")


def check_writable(name: str, path: str | os.PathLike) -> Path:
    """Fail early, before any work, where ``path`` cannot be replaced atomically; return it.

    Refused, naming ``name``: a folder; a missing or unwritable folder; a name longer than
    the file system's limit; an existing file that is read-only, not a regular file, or
    another user's in a sticky folder (where a rename over it fails). A temporary file is
    created in the folder and removed again: what the write needs, tried.
    """
    given = Path(path)
    limit = 255  # first: a longer name fails every call below
    with contextlib.suppress(OSError, ValueError):
        limit = os.pathconf(given.parent if str(given.parent) else ".", "PC_NAME_MAX")
    if len(os.fsencode(given.name)) > limit:
        raise InputError(name, shown(path), f"a file name of at most {limit} bytes on this file system")
    if given.is_dir():
        raise InputError(name, shown(path), "a file path, not a folder")
    _check_link(name, given)
    p = _real(given)
    folder = p.parent if str(p.parent) else Path(".")
    if not folder.is_dir():
        raise InputError(name, shown(path), f"a path in an existing folder ({shown(folder)} does not exist)")
    if not os.access(folder, os.W_OK):
        raise InputError(name, shown(path), f"a path in a writable folder ({shown(folder)} is not writable)")
    recover(folder)  # a killed run's commit finished first: what the work will replace is as it is now
    try:
        st = os.stat(p)
    except FileNotFoundError:
        st = None
    if st is not None:
        if not stat.S_ISREG(st.st_mode):
            raise InputError(name, shown(path), "a regular file or a new name (this is a device, pipe or socket)")
        if _read_only(p, st):
            raise InputError(name, shown(path), "a file that may be written (this one is read-only; "
                                                "chmod u+w it, or choose another name)")
        fst = os.stat(folder)
        euid = os.geteuid() if hasattr(os, "geteuid") else None
        if euid not in (None, 0, st.st_uid, fst.st_uid) and fst.st_mode & stat.S_ISVTX:
            raise InputError(name, shown(path), f"a file of yours (in the sticky folder {shown(folder)} "
                                                "only its owner may replace it)")
    tmp = _temp_name(p)
    try:
        os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
        os.unlink(tmp)
    except OSError as exc:
        raise InputError(name, shown(path), f"a path where a file can be created ({exc.strerror})") from None
    return given


def _read_only(p: Path, st: os.stat_result) -> bool:
    """Whether the file is read-only for us: by its owner bit where we own it (root's
    ``access`` says yes to anything), by ``access`` otherwise; or immutable (``chattr +i``)."""
    if hasattr(os, "geteuid") and st.st_uid == os.geteuid():
        if not st.st_mode & stat.S_IWUSR:
            return True
    elif not os.access(p, os.W_OK):
        return True
    try:  # an immutable file cannot be opened for writing, even by root (nothing is written)
        os.close(os.open(p, os.O_WRONLY | os.O_NONBLOCK | os.O_APPEND))
    except OSError as exc:
        return exc.errno in (errno.EPERM, errno.EACCES, errno.EROFS)
    return False


def _stage(target: Path) -> Path:
    """A new temporary file beside ``target`` that will take its place: with the permission
    bits of the file it replaces (less setuid, setgid and sticky), or those of a new file
    under the umask."""
    try:
        mode: int | None = stat.S_IMODE(os.stat(target).st_mode) & _KEPT_BITS
    except FileNotFoundError:
        mode = None
    tmp = _temp_name(target)
    # 0o666 less the umask, as open() gives a new file (read atomically, unlike os.umask()).
    os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666 if mode is None else 0o600))
    if mode is not None:
        try:
            os.chmod(tmp, mode)
        except BaseException:
            os.unlink(tmp)
            raise
    return tmp


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``.

    The new file keeps the permission bits of the file it replaces, or takes those of a
    new file under the umask; a symbolic link's target is replaced (the link stays).
    """
    _check_link("output", Path(path))
    target = _real(path)
    recover(target.parent)
    tmp = _stage(target)
    try:
        yield tmp
        check_signals()  # a signal some code swallowed: the old file stays
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_together(files: Sequence[tuple[str | os.PathLike, bytes]]) -> None:
    """Write several files as one: afterwards every file holds its new bytes, or (on an
    error) every file is as it was, and a file that did not exist is still absent.

    Every file is first written in full to a temporary file beside it; then a journal
    naming them (files in one folder) is committed, the temporary files are renamed onto
    their targets one after the other with the ending signals deferred
    (:func:`pendulab.core.interrupt.deferred`), and the journal is removed. A run killed
    between two renames leaves the journal, and the next write into the folder finishes
    the renames (:func:`recover`). A rename that fails undoes those done before it: the
    old bytes are written back (atomically), a new file is removed.
    """
    staged: list[tuple[Path, Path]] = []
    journal: Path | None = None
    try:
        for path, data in files:
            _check_link("output", Path(path))
            target = _real(path)
            recover(target.parent)
            staged.append((_stage(target), target))
            _fill(staged[-1][0], data)
        before = [_old_bytes(target) for _, target in staged]
        check_signals()
        folders = {target.parent for _, target in staged}
        if len(folders) == 1 and staged:
            journal = _commit_journal(staged)
        with deferred():
            done = 0
            try:
                for tmp, target in staged:
                    os.replace(tmp, target)
                    done += 1
            except BaseException:
                for (_, target), old in reversed(list(zip(staged[:done], before))):
                    if old is None:
                        with contextlib.suppress(FileNotFoundError):
                            os.unlink(target)
                    else:
                        write_bytes(target, old)
                raise
            finally:
                if journal is not None:
                    with contextlib.suppress(FileNotFoundError):
                        os.unlink(journal)
    finally:
        for tmp, _ in staged:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)


def _commit_journal(staged: Sequence[tuple[Path, Path]]) -> Path:
    """The journal of a commit, written in full under another name and renamed into place:
    a journal that exists is whole."""
    folder = staged[0][1].parent
    journal = _temp_name(staged[0][1], "journal")
    draft = journal.with_suffix(".jtmp")
    text = json.dumps([[tmp.name, target.name] for tmp, target in staged])
    try:
        write_file(draft, text.encode("utf-8"))
        os.replace(draft, journal)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(draft)
        raise
    with contextlib.suppress(OSError):  # the journal's name made durable before the renames
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
    return journal


def _fill(tmp: Path, data: bytes) -> None:
    """Write ``data`` into the staged (empty) file ``tmp``, every byte checked, then to the disk."""
    fd = os.open(tmp, os.O_WRONLY | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        write_all(fd, data, os.fsdecode(tmp))
        sync(fd, os.fsdecode(tmp))
    finally:
        os.close(fd)


def _old_bytes(target: Path) -> bytes | None:
    """What ``target`` holds now (``None``: no such file), to restore it if a later rename fails."""
    try:
        return target.read_bytes()
    except FileNotFoundError:
        return None


def check_not_input(name: str, path: str | os.PathLike, source_name: str, source: str | os.PathLike) -> None:
    """Refuse an output ``path`` that is the input ``source`` (the same file, through any
    link or spelling; ``-``: the file standard input reads): writing it would destroy the input."""
    with contextlib.suppress(OSError):
        if source == "-":
            st, out = os.fstat(0), os.stat(_real(path))
            if stat.S_ISREG(st.st_mode) and (st.st_dev, st.st_ino) == (out.st_dev, out.st_ino):
                raise InputError(name, shown(path), f"a file other than the {source_name} file it is made from "
                                                    "(standard input reads it)")
            return
        if os.path.samefile(_real(path), source):
            raise InputError(name, shown(path), f"a file other than the {source_name} file it is made from")


def write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically, every byte checked."""
    with atomic_path(path) as tmp:
        _fill(tmp, data)


def write_text(path: str | os.PathLike, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def save_figure(fig, path: str | os.PathLike, **kwargs) -> None:
    """Save a matplotlib figure atomically; the format follows the extension."""
    fmt = Path(path).suffix.lstrip(".").lower() or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)


@contextlib.contextmanager
def temp_folder(prefix: str) -> Iterator[Path]:
    """A new private folder in the temporary folder, removed on leaving (an error, Ctrl+C,
    SIGTERM, SIGHUP, SIGQUIT); named ``<prefix><pid>-<random>``, so that the folders of a
    run that was killed (SIGKILL) are removed by the next one (:func:`sweep_temp_folders`)."""
    try:
        sweep_temp_folders(prefix)
        folder = Path(tempfile.mkdtemp(prefix=f"{prefix}{os.getpid()}-"))
    except OSError as exc:  # no usable temporary folder at all (TMPDIR, /tmp, /var/tmp, the current folder)
        raise WriteError("a temporary folder", exc.errno, "none is writable (TMPDIR, /tmp, /var/tmp, the current "
                                                         "folder); set TMPDIR to a writable folder") from None
    try:
        yield folder
    finally:
        with deferred():  # a second signal does not leave half the folder
            shutil.rmtree(folder, ignore_errors=True)


def sweep_temp_folders(prefix: str) -> None:
    """Remove this user's ``<prefix><pid>-*`` folders in the temporary folder whose process
    no longer runs (never through a link)."""
    base = Path(tempfile.gettempdir())  # OSError where there is none: told by temp_folder
    pattern = re.compile(re.escape(prefix) + r"(\d+)-[^/]+")
    with contextlib.suppress(OSError):
        for name in os.listdir(base):
            m = pattern.fullmatch(name)
            if m is None or not _gone(int(m[1])):
                continue
            with contextlib.suppress(OSError):
                st = os.lstat(base / name)
                if stat.S_ISDIR(st.st_mode) and _mine(st):
                    shutil.rmtree(base / name, ignore_errors=True)
