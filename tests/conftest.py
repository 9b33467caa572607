"""Shared test set-up: the tests folder on the import path (for tests/strategies.py), a
non-interactive matplotlib, and hypothesis profiles.

Hypothesis is derandomized by default, so ``make test`` gives the same result on every machine and
every run (the examples are drawn from a fixed seed). To explore with new random examples on every
run, as hypothesis does by default, set ``HYPOTHESIS_PROFILE=explore``.
"""

import os
import pathlib
import sys

import matplotlib
from hypothesis import settings

matplotlib.use("Agg")
sys.path.insert(0, str(pathlib.Path(__file__).parent))

settings.register_profile("default", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

