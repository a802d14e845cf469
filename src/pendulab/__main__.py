"""``python -m pendulab``: the same as the ``pendulab`` command."""
import sys

from .cli import main

sys.exit(main())
