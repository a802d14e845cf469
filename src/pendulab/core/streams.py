"""One checked writer for standard output and files: every byte written, or one error.

CPython's buffered writer can lose the tail of a large write to a full disk and report
success: the file system takes 64 KiB, ``write`` returns a short count, and the rest is
dropped while ``write`` and ``flush`` both return normally (``pendulab key --json >
full/k.json`` exited 0 with 64 KiB of 300 KB). :func:`write_all` calls ``os.write`` until
every byte is taken; a short count is followed by another call, which the kernel answers
with the error (ENOSPC, EFBIG, EPIPE, EBADF, EIO). :class:`CheckedText` is standard output
built on it; :class:`WriteError` is what both raise, with the place and the reason.

:func:`adopt_standard_streams` makes the three standard descriptors safe before anything
else opens a file: a closed one is held by the null device (so no file opened later gets
descriptor 1 and receives the output), standard output then fails with EBADF at its first
write, a closed standard input reads as a closed one, and a closed standard error is silent.
"""
from __future__ import annotations

import contextlib
import errno
import io
import os
import sys
from typing import Any

#: Bytes kept before :class:`CheckedText` writes them out (a terminal: every write at once).
BUFFER = 1 << 16


class WriteError(Exception):
    """A write that did not take every byte: ``where`` (a path, or "standard output"), the
    errno and its reason. Not an ``OSError``: no handler of file errors on the way (a
    fallback that tries elsewhere) takes it for one of its own."""

    def __init__(self, where: str, code: int | None, reason: str):
        super().__init__(f"cannot write to {where}: {reason}")
        self.where = where
        self.errno = code
        self.reason = reason


def write_all(fd: int, data: bytes | bytearray | memoryview, where: str) -> None:
    """Write every byte of ``data`` to ``fd``, calling ``os.write`` again after a short count.

    An error is :class:`WriteError` naming ``where``; a call that takes no byte at all is the
    disk's ENOSPC (a device may answer 0 instead of an error).
    """
    view = memoryview(data).cast("B")
    while view:
        try:
            n = os.write(fd, view)
        except InterruptedError:  # pragma: no cover - Python retries EINTR itself (PEP 475)
            continue
        except OSError as exc:
            raise WriteError(where, exc.errno, exc.strerror or str(exc)) from None
        if n <= 0:
            raise WriteError(where, errno.ENOSPC, os.strerror(errno.ENOSPC))
        view = view[n:]


def write_file(path: str | os.PathLike, data: bytes, mode: int = 0o600) -> None:
    """Write ``data`` to the new file ``path`` (which must not exist), through :func:`write_all`;
    the file is flushed to the disk before it is closed (a full disk answers here, not at close)."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), mode)
    try:
        write_all(fd, data, os.fsdecode(path))
        sync(fd, os.fsdecode(path))
    finally:
        os.close(fd)


def sync(fd: int, where: str) -> None:
    """``fsync``: the bytes on the disk before the file is renamed into place (a full disk or
    a quota answers here at the latest); a file system without it is left as it is."""
    try:
        os.fsync(fd)
    except OSError as exc:
        if exc.errno not in (errno.EINVAL, errno.EROFS, errno.ENOTSUP):
            raise WriteError(where, exc.errno, exc.strerror or str(exc)) from None


class CheckedText(io.TextIOBase):
    """A text stream on a file descriptor whose every byte goes through :func:`write_all`.

    Text is encoded as the stream it replaces encodes it, kept up to :data:`BUFFER` bytes
    (none on a terminal) and written out on :meth:`flush`. A descriptor that cannot be
    written raises :class:`WriteError` naming ``where``. ``closed_fd``: the descriptor was
    closed when the program started (it holds the null device): every write is EBADF.
    """

    def __init__(self, fd: int, where: str, *, encoding: str = "utf-8", errors: str = "strict",
                 closed_fd: bool = False):
        super().__init__()
        self._fd = fd
        self._where = where
        self._encoding = encoding
        self._errors = errors
        self._closed_fd = closed_fd
        self._pending = bytearray()
        self._tty = False
        if not closed_fd:
            with contextlib.suppress(OSError):
                self._tty = os.isatty(fd)

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return self._encoding

    @property
    def errors(self) -> str:  # type: ignore[override]
        return self._errors

    def fileno(self) -> int:
        return self._fd

    def isatty(self) -> bool:
        return self._tty

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        if self._closed_fd:
            raise WriteError(self._where, errno.EBADF, os.strerror(errno.EBADF))
        self._pending += text.encode(self._encoding, self._errors)
        if self._tty or len(self._pending) >= BUFFER:
            self.flush()
        return len(text)

    def write_bytes(self, data: bytes) -> None:
        """Bytes as they are (a CSV with its BOM), after the text already written."""
        if self._closed_fd:
            raise WriteError(self._where, errno.EBADF, os.strerror(errno.EBADF))
        self._pending += data
        self.flush()

    def flush(self) -> None:
        if self._pending:
            data, self._pending = bytes(self._pending), bytearray()
            write_all(self._fd, data, self._where)

    def discard(self) -> None:
        """Forget what is buffered (after a failed write: nothing more is tried)."""
        self._pending = bytearray()


class Silent(io.TextIOBase):
    """Standard error when it is gone (closed, or every write fails): text goes nowhere."""

    encoding = "utf-8"
    errors = "strict"

    def __init__(self, fd: int | None = None):
        super().__init__()
        self._fd = fd

    def write(self, text: str) -> int:
        return len(text)

    def writable(self) -> bool:
        return True

    def fileno(self) -> int:
        if self._fd is None:
            raise io.UnsupportedOperation("fileno")
        return self._fd


class ClosedInput(io.RawIOBase):
    """Standard input that was closed when the program started: every read is EBADF."""

    def readable(self) -> bool:
        return True

    def readinto(self, b: Any) -> int:
        raise OSError(errno.EBADF, os.strerror(errno.EBADF))


def _is_open(fd: int) -> bool:
    try:
        os.fstat(fd)
    except OSError:
        return False
    return True


def _hold(fd: int, flags: int) -> None:
    """Open the null device on the closed descriptor ``fd`` (the lowest free one is ``fd``)."""
    got = os.open(os.devnull, flags)
    if got != fd:
        os.dup2(got, fd)
        os.close(got)


def adopt_standard_streams() -> None:
    """Hold every closed standard descriptor with the null device and give ``sys`` streams
    that say so: standard output fails at its first write (EBADF), standard input reads as
    closed, standard error is silent. Standard output becomes a :class:`CheckedText`.

    Call it first, before anything opens a file.
    """
    closed = [fd for fd in (0, 1, 2) if not _is_open(fd)]
    for fd in closed:  # lowest first: each os.open takes the lowest free descriptor
        _hold(fd, os.O_RDONLY if fd == 0 else os.O_WRONLY)
    if 0 in closed:
        sys.stdin = io.TextIOWrapper(io.BufferedReader(ClosedInput()), encoding="utf-8")
    sys.stderr = Silent(2) if 2 in closed or sys.stderr is None else Forgiving(sys.stderr)
    old = sys.stdout
    encoding = getattr(old, "encoding", None) or "utf-8"
    errors = getattr(old, "errors", None) or "strict"
    if old is not None:
        with contextlib.suppress(OSError, ValueError):
            old.flush()
    sys.stdout = CheckedText(1, "standard output", encoding=encoding, errors=errors, closed_fd=1 in closed)


class Forgiving(io.TextIOBase):
    """Standard error that falls silent at its first failed write (a full disk, a closed
    pipe): the message is lost either way, and the command's status still tells."""

    def __init__(self, stream: Any):
        super().__init__()
        self._stream = stream

    def write(self, text: str) -> int:
        if self._stream is not None:
            try:
                self._stream.write(text)
                self._stream.flush()
            except (OSError, ValueError):
                self._stream = None
        return len(text)

    def flush(self) -> None:
        if self._stream is not None:
            try:
                self._stream.flush()
            except (OSError, ValueError):
                self._stream = None

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return getattr(self._stream, "encoding", None) or "utf-8"

    @property
    def errors(self) -> str:  # type: ignore[override]
        return getattr(self._stream, "errors", None) or "strict"

    def writable(self) -> bool:
        return True

    def isatty(self) -> bool:
        return self._stream is not None and bool(getattr(self._stream, "isatty", lambda: False)())

    def fileno(self) -> int:
        return 2

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream if self._stream is not None else sys.__stderr__, name)
