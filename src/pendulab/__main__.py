"""``python -m pendulab``: the same as the ``pendulab`` command."""
import sys

from .cli import main

if __name__ == "__main__":  # not when a tool imports it (the docs' module walk)
    sys.exit(main())
