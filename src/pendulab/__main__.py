"""``python -m pendulab``, and the ``pendulab`` command's entry point (:func:`run`)."""
import signal
import sys

from ._interrupt import Terminated, terminate_handler


def run() -> int:
    """:func:`pendulab.cli.main`; Ctrl+C or SIGTERM while the command line loads is one line too."""
    signal.signal(signal.SIGTERM, terminate_handler)  # before the imports: they take a while
    try:
        from .cli import main
    except KeyboardInterrupt as exc:
        term = isinstance(exc, Terminated)
        sys.stderr.write(f"pendulab: {'terminated' if term else 'interrupted'}\n")
        return 143 if term else 130
    return main()


if __name__ == "__main__":  # not when a tool imports it (the docs' module walk)
    sys.exit(run())
