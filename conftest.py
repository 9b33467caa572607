"""Root test set-up: hooks that must reach the notebooks under book/ and exercises/ too (a conftest
applies to the folder it is in; the package's tests have theirs in tests/conftest.py)."""

import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).parent / "tests"))


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item):
    """Determinism of the notebooks on nbval's own execution (no second run): after nbval has run a
    cell, every output it produced, images and scenes included, must equal the stored one byte for
    byte (``tests/test_determinism.py``), so re-executing a notebook never changes the repository."""
    yield
    if type(item).__name__ == "IPyNbCell":
        from test_determinism import nbval_cell_changes

        problems = nbval_cell_changes(item)
        assert problems == [], "re-executing changes stored outputs:\n" + "\n".join(problems)
