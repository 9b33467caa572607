"""Shared test set-up: the tests folder on the import path (for tests/strategies.py)."""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
sys.path.insert(0, str(pathlib.Path(__file__).parent))
