"""Ctrl+C, SIGTERM, SIGHUP and SIGQUIT around compiled kernels: recorded while a kernel runs, raised after it.

Python runs a signal's handler in the main thread at the next point where the interpreter
checks for one, and numba's conversion of a kernel's result to Python objects is such a
point: a ``KeyboardInterrupt`` raised there leaves the result half built (a
``SystemError``, or a crash). :func:`deferred` replaces the handlers of SIGINT and SIGTERM
(and of SIGHUP, SIGQUIT) by one that only records the signal, the drivers run their kernels in chunks and look at
the record between them (:func:`run_pieces`), and on leaving the original handlers are
put back and the signal is delivered again, in plain Python code.

The first call of a kernel compiles it (seconds, with an empty numba cache), and LLVM
calls back into Python through ``ctypes`` as it finishes each object: a signal that came
while LLVM worked is handled in that callback, where a ``KeyboardInterrupt`` is printed as
"Exception ignored" and lost (the command runs on and exits 0). So every call of a kernel
in the main thread is made inside :func:`deferred` (:func:`run_pieces` for the long runs),
its compilation included.

:class:`Terminated` is what the CLI's SIGTERM, SIGHUP and SIGQUIT handler raises (:func:`terminate_handler`):
like Ctrl+C it unwinds, so ``finally`` blocks and temporary folders are cleaned up.

A thread that serves someone else (the web explorer's worker) stops its work the same way
when asked: inside :func:`stop_when`, :func:`run_pieces` raises :class:`Stopped` between two
pieces once the event is set (the request's client has gone).
"""
from __future__ import annotations

import contextlib
import signal
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from typing import Any

#: The signals that end a command: Ctrl+C, ``kill``, a closed terminal (SIGHUP), Ctrl+\\ (SIGQUIT).
ENDING = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT") if hasattr(signal, n))
_SIGNALS = ENDING

#: The signals received by :func:`terminate_handler` and :func:`interrupt_handler`, first
#: first. A ``KeyboardInterrupt`` raised where some code swallows it (a callback, an
#: ``except BaseException``) is not forgotten: :func:`check_signals` raises it again at the
#: next commit point (an output's rename), and the command's status still tells it.
received: list[int] = []


class Terminated(KeyboardInterrupt):
    """SIGTERM, SIGHUP or SIGQUIT, raised like Ctrl+C's ``KeyboardInterrupt`` so that the same
    cleanup runs; ``signum`` is the signal."""

    def __init__(self, signum: int = signal.SIGTERM):
        super().__init__(signum)
        self.signum = int(signum)


def signal_of(exc: BaseException) -> int:
    """The signal a ``KeyboardInterrupt`` stands for (SIGINT unless it is a :class:`Terminated`)."""
    return exc.signum if isinstance(exc, Terminated) else int(signal.SIGINT)


def word(signum: int) -> str:
    """How a command a signal ended says so: ``interrupted`` (Ctrl+C), ``terminated``,
    ``hung up`` (the terminal closed), ``quit`` (Ctrl+\\)."""
    return {signal.SIGINT: "interrupted", getattr(signal, "SIGHUP", -1): "hung up",
            getattr(signal, "SIGQUIT", -1): "quit"}.get(signum, "terminated")


def terminate_handler(signum: int, frame: object) -> None:
    """A handler of SIGTERM, SIGHUP and SIGQUIT that raises :class:`Terminated` (installed by the CLI)."""
    received.append(int(signum))
    raise Terminated(signum)


def interrupt_handler(signum: int, frame: object) -> None:
    """Ctrl+C's handler in the CLI: Python's ``KeyboardInterrupt``, and the signal recorded."""
    received.append(int(signum))
    raise KeyboardInterrupt


def install() -> None:
    """The CLI's handlers of every ending signal (main thread only); an ignored signal
    (``nohup``'s SIGHUP) stays ignored. Also :func:`unraisable`, for the signals raised
    where Python cannot propagate them."""
    for s in ENDING:
        if signal.getsignal(s) is signal.SIG_IGN:
            continue
        signal.signal(s, interrupt_handler if s == signal.SIGINT else terminate_handler)
    if sys.unraisablehook is not unraisable:
        _hooks[:] = [sys.unraisablehook]
        sys.unraisablehook = unraisable


#: The unraisable hook :func:`unraisable` hands every other exception to.
_hooks: list[Callable[[Any], object]] = []


def unraisable(info: Any) -> None:
    """``sys.unraisablehook``: a ``KeyboardInterrupt`` (or :class:`Terminated`) of a signal
    in :data:`received` is kept silent, anything else goes to the hook before it.

    A handler's exception raised while Python runs a callback (a weak reference's, such as
    the import system's module locks' while another thread imports, or a ``__del__``) cannot
    propagate: Python prints "Exception ignored" and goes on. The signal is in
    :data:`received`, and :func:`check_signals` raises it again where the command can end.
    """
    if isinstance(info.exc_value, KeyboardInterrupt) and received:
        return
    (_hooks[0] if _hooks else sys.__unraisablehook__)(info)


def check_signals() -> None:
    """Raise again a signal that was received and swallowed by some code on the way: called
    before an output is committed, so that no output is replaced after a signal."""
    if received:
        signum = received[0]
        raise KeyboardInterrupt if signum == signal.SIGINT else Terminated(signum)


@contextlib.contextmanager
def deferred() -> Iterator[list[int]]:
    """Inside, SIGINT and SIGTERM are only recorded (in the list yielded); on leaving, the
    original handlers are restored and the first recorded signal is raised again.

    Only the handlers that end the work are replaced (Python's ``KeyboardInterrupt``,
    :func:`terminate_handler`, the default action): a recorded signal always ends it.

    Outside the main thread (a web server's worker) signals never run there: nothing changes.
    """
    got: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield got
        return

    def record(signum: int, frame: object) -> None:
        got.append(signum)

    old = {}
    try:
        for s in _SIGNALS:
            if signal.getsignal(s) in (signal.default_int_handler, terminate_handler, interrupt_handler,
                                       signal.SIG_DFL):
                old[s] = signal.signal(s, record)  # only handlers that end the work: an ignored
        yield got  # signal, or a handler of the program's own, is left as it is
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        if got:  # delivered again to the original handler, now in plain Python code
            signal.raise_signal(got[0])


#: Steps of (3) per piece of a long kernel run (:func:`run_pieces`): 4 * 10^6 steps, tens
#: of ms (``benchmarks/method_cost.py``); a Python call per piece is nothing beside it.
CHUNK_COST = 1 << 22


def pieces(n: int, size: int, stride: int = 1) -> Iterator[tuple[int, int]]:
    """``[0, n)`` cut into ``(lo, hi)`` of at most ``size`` steps; where ``size < stride``,
    no piece crosses a multiple of ``stride`` (a thinned run keeps the point there)."""
    lo = 0
    while lo < n:
        hi = min(lo + size, n)
        if size < stride:
            hi = min(hi, (lo // stride + 1) * stride)
        yield lo, hi
        lo = hi


class Stopped(Exception):
    """The work of a :func:`stop_when` block was stopped between two pieces: nobody wants it now."""


_asked = threading.local()


@contextlib.contextmanager
def stop_when(event: threading.Event) -> Iterator[None]:
    """Inside (in this thread), a run in pieces raises :class:`Stopped` between two pieces
    once ``event`` is set."""
    before = getattr(_asked, "event", None)
    _asked.event = event
    try:
        yield
    finally:
        _asked.event = before


def stopping() -> None:
    """Raise :class:`Stopped` if this thread's :func:`stop_when` event is set (a check between pieces)."""
    event = getattr(_asked, "event", None)
    if event is not None and event.is_set():
        raise Stopped


class Tally:
    """A count that threads add to (the pieces run in this process): what a test reads to
    show that work stopped, by what it did rather than by the time it took."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.value = 0

    def add(self, n: int = 1) -> None:
        with self._lock:
            self.value += n


#: Pieces of kernel work run by :func:`run_pieces` in this process, every thread together.
pieces_run = Tally()


def run_pieces(bounds: Iterable[tuple[int, int]], run: Callable[[int, int], bool]) -> None:
    """Call ``run(lo, hi)`` for each piece, under :func:`deferred`: a signal stops the loop
    between two pieces (one piece's time at most) and is raised then. ``run`` returns True
    when the work is finished early (a period search that found the return). Inside
    :func:`stop_when`, a set event stops it too, raising :class:`Stopped`."""
    with deferred() as got:
        for lo, hi in bounds:
            stopping()
            if got:
                return
            finished = run(lo, hi)
            pieces_run.add()
            if finished:
                return
