"""``python -m mechanisms``: the command-line tool (see :mod:`mechanisms.cli`)."""
import sys

from .cli import main

sys.exit(main())
