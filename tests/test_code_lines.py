"""Every line of a notebook's code cells is at most 88 characters (CONTRIBUTING.md, "Notebooks").

The site shows a code cell in a box of the text's width; a longer line wraps or scrolls, and a
reader who copies the cell meets the same line in an editor. Characters are counted, not bytes
(``φ`` and ``²`` are one character each). Folded cells (``hide-input``) count too: a reader opens them.
"""

from __future__ import annotations

import json
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
LIMIT = 88
NOTEBOOKS = sorted([*ROOT.glob("book/**/*.ipynb"), *ROOT.glob("exercises/**/*.ipynb")])
NOTEBOOKS = [n for n in NOTEBOOKS if ".ipynb_checkpoints" not in n.parts and "_build" not in n.parts]


def long_lines(notebook: dict) -> list[str]:
    """``"cell N: <length> characters: <line>"`` for every code line longer than the limit."""
    found = []
    for number, cell in enumerate(notebook["cells"]):
        if cell["cell_type"] != "code":
            continue
        for line in "".join(cell["source"]).splitlines():
            if len(line) > LIMIT:
                found.append(f"cell {number}: {len(line)} characters: {line.strip()[:60]}")
    return found


def test_the_rule_counts_characters_not_bytes():
    cell = {"cell_type": "code", "source": ["x = 1  # " + "φ" * 79 + "\n", "y = 2 # " + "a" * 81]}
    assert long_lines({"cells": [cell]}) == ["cell 0: 89 characters: y = 2 # " + "a" * 52]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: str(p.relative_to(ROOT)))
def test_code_lines_fit_88_characters(path: pathlib.Path):
    found = long_lines(json.loads(path.read_text(encoding="utf-8")))
    assert not found, "\n".join(found)
