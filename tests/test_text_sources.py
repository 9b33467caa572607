"""Every chapter and exercise notebook has its text committed beside it as MyST Markdown, in sync.

The ``.ipynb`` (with outputs) is what nbval tests and the site shows; the paired ``.md`` (jupytext,
format ``md:myst``) is what a reviewer reads in a diff. Both are committed; this test fails when a
pair is missing or when its cells differ (cell types, sources and tags), and says how to fix it.
"""

from __future__ import annotations

import pathlib

import jupytext
import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted(list((ROOT / "book").glob("[0-9][0-9]-*.ipynb")) + list((ROOT / "exercises").glob("[0-9][0-9]-*.ipynb")))
FIX = "run `make sources` (jupytext --sync: the newer of the two files wins) and commit both files"


def _cells(notebook) -> list[tuple[str, str, tuple[str, ...]]]:
    return [(cell.cell_type, cell.source.strip(), tuple(cell.metadata.get("tags", ()))) for cell in notebook.cells]


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 18


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: str(p.relative_to(ROOT)))
def test_each_notebook_has_its_text_in_sync(notebook):
    text = notebook.with_suffix(".md")
    name = notebook.relative_to(ROOT)
    assert text.exists(), f"{name} has no paired text {text.name}: {FIX}"
    pair = jupytext.read(notebook)
    assert pair.metadata.get("jupytext", {}).get("formats") == "ipynb,md:myst", (
        f"{name} is not paired with its text (jupytext formats ipynb,md:myst): `jupytext --set-formats "
        f"ipynb,md:myst {name}`")
    ours, theirs = _cells(pair), _cells(jupytext.read(text))
    if ours != theirs:
        differ = next(i for i, (a, b) in enumerate(zip(ours, theirs)) if a != b) if len(ours) == len(theirs) \
            else min(len(ours), len(theirs))
        pytest.fail(f"{name} and {text.relative_to(ROOT)} differ (first at cell {differ}; {len(ours)} cells against "
                    f"{len(theirs)}): {FIX}", pytrace=False)
