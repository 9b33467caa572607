"""Shared test set-up: the tests folder on the import path (for tests/strategies.py), a
non-interactive matplotlib, and hypothesis profiles.

Tests that read the built site carry ``@pytest.mark.needs_site("full")`` (or ``"student"``) and take its
folder from the ``built_site`` fixture: when a selected test needs a site that is not built, pytest stops at
collection and names the make target that builds it.

Hypothesis is derandomized by default, so ``make test`` gives the same result on every machine and
every run (the examples are drawn from a fixed seed). To explore with new random examples on every
run, as hypothesis does by default, set ``HYPOTHESIS_PROFILE=explore``.
"""

import os
import pathlib
import sys

import matplotlib
import pytest
from hypothesis import settings

matplotlib.use("Agg")
sys.path.insert(0, str(pathlib.Path(__file__).parent))

settings.register_profile("default", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("explore", deadline=None, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


# --- tests that read the built site -------------------------------------------------------------------

ROOT = pathlib.Path(__file__).resolve().parent.parent
BUILT_SITES = {
    "full": (ROOT / "_build" / "html", "make book"),
    "student": (ROOT / "_build" / "student" / "_build" / "html", "make book-student"),
}
"""Each edition of the built site: its folder and the make target that builds it (``make test`` builds both,
then runs pytest)."""


def missing_site(edition: str) -> str | None:
    """Why the edition's site cannot be read (it is not built), or None when it is there."""
    site, command = BUILT_SITES[edition]
    if (site / "index.html").is_file():
        return None
    return f"run `{command}` first: this test reads {site.relative_to(ROOT)}, which is not built"


def pytest_configure(config):
    config.addinivalue_line("markers", "needs_site(*editions): the test reads the built site of these editions "
                                       "('full': make book, 'student': make book-student); pytest stops at "
                                       "collection when one is selected and the site is not built")


@pytest.hookimpl(trylast=True)      # after -m and -k have deselected what they leave out
def pytest_collection_modifyitems(config, items):
    """Stop at once, before any test runs, when a selected test reads a site that is not built."""
    waiting: dict[str, list[str]] = {}
    for item in items:
        for mark in item.iter_markers("needs_site"):
            for edition in mark.args:
                if missing_site(edition):
                    waiting.setdefault(edition, []).append(item.nodeid)
    if waiting:
        lines = []
        for edition, ids in waiting.items():
            lines.append(f"{missing_site(edition)} ({len(ids)} test(s), e.g. {ids[0]})")
        pytest.exit("the built site is missing:\n" + "\n".join(lines)
                    + "\n`make test` builds both editions, then runs pytest; "
                      "`-m 'not needs_site'` leaves these tests out", returncode=pytest.ExitCode.USAGE_ERROR)


@pytest.fixture
def built_site():
    """``built_site(edition)`` → the folder of that edition's built site; the test fails, naming the make
    target, if it is missing (tests that use it carry ``@pytest.mark.needs_site(edition)``)."""
    def site(edition: str) -> pathlib.Path:
        why = missing_site(edition)
        if why:
            pytest.fail(why, pytrace=False)
        return BUILT_SITES[edition][0]
    return site
