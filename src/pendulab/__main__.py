"""``python -m pendulab``, and the ``pendulab`` command's entry point (:func:`run`)."""
import sys


def run() -> int:
    """:func:`pendulab.cli.main`, with Ctrl+C while the command line loads told in one line too."""
    try:
        from .cli import main
    except KeyboardInterrupt:
        sys.stderr.write("pendulab: interrupted\n")
        return 130
    return main()


if __name__ == "__main__":  # not when a tool imports it (the docs' module walk)
    sys.exit(run())
