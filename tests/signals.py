"""Signal dispositions for the tests that signal a real ``pendulab`` process.

A test run in the background, under ``nohup`` or in a shell with ``trap '' INT`` starts with
SIGINT (or SIGHUP, SIGQUIT) ignored, and every child inherits that: pendulab keeps an
ignored signal ignored (``core.interrupt.install``, as ``nohup`` means it), so the signal a
test sends would never reach it. Each such test sets the child's dispositions itself.
"""
from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator

#: The signals the tests send: the ones pendulab ends a command on (``core.interrupt.ENDING``).
SENT = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP", "SIGQUIT") if hasattr(signal, n))


def default_signals() -> None:
    """``preexec_fn`` of a child that a test signals: the default action of each signal in
    :data:`SENT` (what a terminal gives), whatever the test run inherited."""
    for s in SENT:
        signal.signal(s, signal.SIG_DFL)


@contextlib.contextmanager
def python_sigint() -> Iterator[None]:
    """Python's own SIGINT handler (``KeyboardInterrupt``) in this process for the block,
    whatever the run inherited; the handler before it afterwards."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
