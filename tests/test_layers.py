"""The house: the folders of the package are its layers, and the README's layer table is the tree.

Checked from the source files themselves (their import statements, read with :mod:`ast`), not from
the package's own description of itself:

* no module imports a module of a higher layer (function-level imports included);
* the README's layer table names exactly the package's folders and top-level modules;
* ``import mechanisms`` imports neither matplotlib nor the tool packages (a fresh interpreter);
* no module outside the mechanisms' own modules lists mechanisms (names two or more of their classes:
  a module about one mechanism, like the four-bar's synthesis, may name that one).
"""

from __future__ import annotations

import ast
import pathlib
import re
import subprocess
import sys

import pytest

import mechanisms as mech

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "mechanisms"

LAYERS = {
    "core": 1,
    "blocks": 2,
    "linkages": 3,
    "analysis": 4,
    "verify": 5,
    "plot": 6,
    "present": 6,
    "course": 7,
    "bench": 7,
    "cli": 7,
}
"""The layer of each folder (and of the top-level module cli.py), bottom up."""

ROOT_MODULES = {"__init__", "__main__", "_moved"}
"""Top-level modules that gather the layers (the package's front door), exempt from the rule."""


def _modules() -> list[pathlib.Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def _part(path: pathlib.Path) -> str:
    """The folder (or top-level module) of the package a file belongs to."""
    rel = path.relative_to(PACKAGE)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _imported_parts(path: pathlib.Path) -> set[str]:
    """The package folders a module imports from (relative and absolute imports, at any depth)."""
    tree = ast.parse(path.read_text(), filename=str(path))
    package = path.relative_to(PACKAGE).parent.parts
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = list(package[: len(package) - (node.level - 1)])
                target = base + (node.module.split(".") if node.module else [])
                if not target:  # from . import x at the top: x is the part
                    found.update(alias.name for alias in node.names)
                else:
                    found.add(target[0])
            elif node.module and node.module.split(".")[0] == "mechanisms":
                parts = node.module.split(".")[1:]
                found.update([parts[0]] if parts else [alias.name for alias in node.names])
        elif isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] == "mechanisms" and len(parts) > 1:
                    found.add(parts[1])
    return found


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_module_imports_a_higher_layer(path):
    part = _part(path)
    if part in ROOT_MODULES:
        return
    assert part in LAYERS, f"{path.relative_to(ROOT)} is in no layer: add its folder to the README's table"
    upward = {other for other in _imported_parts(path) if LAYERS.get(other, 0) > LAYERS[part]}
    assert not upward, f"{path.relative_to(ROOT)} (layer {LAYERS[part]}) imports from a higher layer: {sorted(upward)}"


def test_readme_layer_table_is_the_tree():
    readme = (ROOT / "README.md").read_text()
    named = set(re.findall(r"`mechanisms/([\w]+)(?:/|\.py)`", readme))
    tree = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    tree |= {p.stem for p in PACKAGE.glob("*.py")} - ROOT_MODULES
    assert named == tree, (f"README's layer table names {sorted(named)}; the tree has {sorted(tree)}")
    assert tree == set(LAYERS), f"this test's layers {sorted(LAYERS)} differ from the tree {sorted(tree)}"


def test_import_mechanisms_imports_no_plotting_and_no_tools():
    code = ("import sys, mechanisms; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib' or "
            "m.split('.')[:2] in (['mechanisms', 'plot'], ['mechanisms', 'course'], ['mechanisms', 'bench'], "
            "['mechanisms', 'cli'])))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]", f"import mechanisms imported: {out}"


def test_plot_is_imported_when_first_used():
    code = "import mechanisms, sys; mechanisms.plot.draw; print('matplotlib.pyplot' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "True"


def test_all_names_the_public_api():
    for name in mech.__all__:
        assert getattr(mech, name) is not None, name
    for cls in mech.registry.values():
        if cls.__module__.startswith("mechanisms."):   # tests may register classes of their own
            assert cls.__name__ in mech.__all__


def _own_modules(cls: type) -> set[pathlib.Path]:
    """A mechanism's own modules: the module that defines it and its analysis module of the same name."""
    defined = pathlib.Path(sys.modules[cls.__module__].__file__ or "")
    return {defined, PACKAGE / "analysis" / defined.name}


def test_no_list_of_mechanisms_outside_their_own_modules():
    # the names of the registered classes used as names in code outside their own modules
    # (docstrings and comments may mention them: strings and comments are dropped first)
    classes = [cls for cls in mech.registry.values() if cls.__module__.startswith("mechanisms.")]
    offenders = []
    for path in _modules():
        tree = ast.parse(path.read_text())
        names = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
        names |= {alias.asname or alias.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                  for alias in node.names}
        named = {cls.__name__ for cls in classes if cls.__name__ in names and path not in _own_modules(cls)}
        # a mechanism defined from another one (the lambda mechanism is a four-bar) may name it
        named -= {base.__name__ for cls in classes if path in _own_modules(cls) for base in classes
                  if base is not cls}
        if len(named) >= 2:
            offenders.append(f"{path.relative_to(ROOT)}: {sorted(named)}")
    assert not offenders, "mechanism classes named outside their own modules:\n" + "\n".join(offenders)
