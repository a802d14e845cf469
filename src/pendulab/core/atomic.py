"""Atomic output: write to a temporary file beside the target, then rename.

A failed run leaves no half-written file and never destroys an older good one. The file
written keeps the old file's permission bits (a key kept at 0600 stays private), or
takes those the umask gives a new file. A symbolic link is written through: its target
is replaced and the link stays. A read-only file, a file that is not a regular file, a
file another user owns in a sticky folder such as /tmp, and a name the file system
cannot hold are refused: by :func:`check_writable`, before the work, each in one line.
"""
from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from collections.abc import Iterator, Sequence
from pathlib import Path

from .errors import InputError, shown
from .interrupt import deferred


def _real(path: str | os.PathLike) -> Path:
    """``path``, a symbolic link followed to the file it names (which may not exist yet)."""
    p = Path(path)
    return Path(os.path.realpath(p)) if p.is_symlink() else p


def _temp_name(target: Path) -> Path:
    """A temporary name beside ``target``, short whatever the target's length (a name of
    255 bytes still has room): ``.pendulab-<16 hex digits>.tmp``."""
    return target.with_name(f".pendulab-{secrets.token_hex(8)}.tmp")


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
    p = _real(given)
    folder = p.parent if str(p.parent) else Path(".")
    if not folder.is_dir():
        raise InputError(name, shown(path), f"a path in an existing folder ({shown(folder)} does not exist)")
    if not os.access(folder, os.W_OK):
        raise InputError(name, shown(path), f"a path in a writable folder ({shown(folder)} is not writable)")
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
    bits of the file it replaces, or those of a new file under the umask."""
    try:
        mode: int | None = stat.S_IMODE(os.stat(target).st_mode)
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
    target = _real(path)
    tmp = _stage(target)
    try:
        yield tmp
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_together(files: Sequence[tuple[str | os.PathLike, bytes]]) -> None:
    """Write several files as one: afterwards every file holds its new bytes, or (on an
    error) every file is as it was, and a file that did not exist is still absent.

    Every file is first written in full to a temporary file beside it; only then are they
    renamed onto their targets, one after the other, with SIGINT and SIGTERM deferred
    (:func:`pendulab.core.interrupt.deferred`) so that Ctrl+C or a ``kill`` waits for the last
    rename. A rename that fails undoes those done before it: the old bytes are written back
    (atomically), a new file is removed. What no program can prevent remains: a power cut
    or SIGKILL between two renames (there is no atomic rename of two files).
    """
    staged: list[tuple[Path, Path]] = []
    try:
        for path, data in files:
            target = _real(path)
            staged.append((_stage(target), target))
            staged[-1][0].write_bytes(data)
        before = [_old_bytes(target) for _, target in staged]
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
        for tmp, _ in staged:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)


def _old_bytes(target: Path) -> bytes | None:
    """What ``target`` holds now (``None``: no such file), to restore it if a later rename fails."""
    try:
        return target.read_bytes()
    except FileNotFoundError:
        return None


def check_not_input(name: str, path: str | os.PathLike, source_name: str, source: str | os.PathLike) -> None:
    """Refuse an output ``path`` that is the input ``source`` (the same file, through any
    link or spelling): writing it would destroy the input."""
    with contextlib.suppress(OSError):
        if os.path.samefile(_real(path), source):
            raise InputError(name, shown(path), f"a file other than the {source_name} file it is made from")


def write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)


def write_text(path: str | os.PathLike, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def save_figure(fig, path: str | os.PathLike, **kwargs) -> None:
    """Save a matplotlib figure atomically; the format follows the extension."""
    fmt = Path(path).suffix.lstrip(".").lower() or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, **kwargs)
