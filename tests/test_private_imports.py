"""No notebook of the book or of the exercises uses a private name of the package (issue 19, item 6).

A reader copies what a notebook does. A name that starts with an underscore (``_pqf``) is the
package's own business: it may change or go without notice, and it hides what the book should say
in words. So every code cell of ``book/*.ipynb`` and ``exercises/*.ipynb`` is parsed, and it must
neither import a private name from ``mechanisms`` (``from mechanisms.x import _y``, ``import
mechanisms._x``) nor reach one through an attribute of the package (``mech._x``,
``mechanisms.linkages._y``, ``frenet._z``: any attribute access on a name bound to the package or to
one of its modules). Dunder names (``__version__``) are public.
"""

from __future__ import annotations

import ast
import json
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted([*ROOT.glob("book/**/*.ipynb"), *ROOT.glob("exercises/**/*.ipynb")])
NOTEBOOKS = [n for n in NOTEBOOKS if ".ipynb_checkpoints" not in n.parts and "_build" not in n.parts]


def private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def code_of(cell: dict) -> str:
    """The cell's source as Python: IPython's magics and shell lines are blanked out."""
    lines = "".join(cell["source"]).splitlines()
    return "\n".join("" if line.lstrip().startswith(("%", "!")) else line for line in lines)


def private_uses(source: str) -> list[str]:
    """The private names of ``mechanisms`` that a cell imports or reaches by attribute access."""
    tree = ast.parse(source)
    package_names: set[str] = set()      # local names bound to mechanisms or one of its modules
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "mechanisms":
                    if any(private(part) for part in alias.name.split(".")):
                        found.append(f"import {alias.name}")
                    package_names.add(alias.asname or "mechanisms")
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "mechanisms":
            if any(private(part) for part in node.module.split(".")):
                found.append(f"from {node.module} import …")
            for alias in node.names:
                if private(alias.name):
                    found.append(f"from {node.module} import {alias.name}")
                else:
                    package_names.add(alias.asname or alias.name)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and private(node.attr):
            base = node.value
            while isinstance(base, ast.Attribute):
                base = base.value
            if isinstance(base, ast.Name) and base.id in package_names:
                found.append(f"{ast.unparse(node)}")
    return found


def test_the_check_sees_private_names():
    # expected by hand: each of these lines uses a private name of the package, the last two do not
    assert private_uses("from mechanisms.linkages.four_bar import _pqf") == [
        "from mechanisms.linkages.four_bar import _pqf"]
    assert private_uses("import mechanisms as mech\nmech.linkages.four_bar._pqf(1)") == [
        "mech.linkages.four_bar._pqf"]
    assert private_uses("from mechanisms.analysis import frenet\nfrenet._law(1)") == ["frenet._law"]
    assert private_uses("import mechanisms._private") == ["import mechanisms._private"]
    assert private_uses("import mechanisms as mech\nprint(mech.__version__)") == []
    assert private_uses("import numpy as np\nnp._NoValue") == []


def test_there_are_notebooks():
    assert len([n for n in NOTEBOOKS if n.parts[-2] == "book"]) >= 10, NOTEBOOKS
    assert len([n for n in NOTEBOOKS if n.parts[-2] == "exercises"]) >= 10, NOTEBOOKS


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda n: n.relative_to(ROOT).as_posix())
def test_no_private_names(notebook):
    cells = json.loads(notebook.read_text(encoding="utf8"))["cells"]
    found = []
    for number, cell in enumerate(cells):
        if cell["cell_type"] == "code":
            found += [f"cell {number}: {use}" for use in private_uses(code_of(cell))]
    assert found == [], f"{notebook.relative_to(ROOT)} uses private names of the package:\n" + "\n".join(found)
