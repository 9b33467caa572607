"""Shared test set-up: the tests folder on the import path (for tests/strategies.py), a
non-interactive matplotlib, and hypothesis profiles.

Locally hypothesis draws new random examples on every run (that is how it finds bugs); in CI
(``CI`` set) it is derandomized, so a submission's run is reproducible.
"""

import os
import pathlib
import sys

import matplotlib
from hypothesis import settings

matplotlib.use("Agg")
sys.path.insert(0, str(pathlib.Path(__file__).parent))

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("dev", deadline=None, print_blob=True)
settings.load_profile("ci" if os.environ.get("CI") else "dev")
