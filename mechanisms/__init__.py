"""Kinematics of planar linkage mechanisms: the package of the book.

The folders are the layers, bottom up (a module imports only from its own layer or below):

1. :mod:`mechanisms.core` — the motion of a link and its points, angles, errors, validation;
2. :mod:`mechanisms.blocks` — the closed-form building blocks (dyads);
3. :mod:`mechanisms.linkages` — the ``Mechanism`` base class and the book's mechanisms;
4. :mod:`mechanisms.analysis` — Grashof, ranges, limit positions, plans, Frenet, energy, synthesis;
5. :mod:`mechanisms.verify` — the generic solver, numerical differentiation, the checks;
6. :mod:`mechanisms.plot` (matplotlib) and :mod:`mechanisms.present` (text) — figures and tables;
7. tools: :mod:`mechanisms.course` (assignments, grading), :mod:`mechanisms.bench`, :mod:`mechanisms.cli`.

``import mechanisms`` is quick: it imports nothing but this file. Every public name (``mechanisms.CrankSlider``, ``mechanisms.Motion``, ``mechanisms.verify`` …)
imports its module, and numpy with it, when it is first used (module ``__getattr__``, PEP 562), so
that the command line and scripts pay only for what they use; ``mechanisms.plot`` imports matplotlib
when something is first drawn. ``from mechanisms import *`` and ``dir(mechanisms)`` list every name.
"""

from __future__ import annotations

import importlib
import sys
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:   # what the names are, for type checkers and editors; nothing is imported at run time
    from . import core, plot, present, verify  # noqa: F401
    from .core import motion  # noqa: F401
    from .core.errors import (AssemblyError, SingularPositionWarning, InvalidParameterError,  # noqa: F401
                              MechanismError, MissingDerivativeError, StructureError, UnknownNameError)
    from .core.links import LINK_TYPES, LinkType, harmonic, link_type  # noqa: F401
    from .core.motion import (AngleMotion, Motion, PointMotion, fixed_point, lagrange_point,  # noqa: F401
                              plane_motion, point_on_link, polar, translated_point)
    from .linkages import Mechanism, Solution, groups, mechanism_classes, registry  # noqa: F401
    from .linkages.composed import Linkage  # noqa: F401
    from .linkages.linkage_file import example_files, load_linkage  # noqa: F401
    from .present import difference, magnitude, markdown_table, number, show_messages  # noqa: F401

__version__ = "0.2.0"

_NAMES: dict[str, tuple[str, ...]] = {
    # layer 1
    "mechanisms.core.motion": ("Motion", "AngleMotion", "PointMotion", "fixed_point", "plane_motion",
                               "point_on_link", "lagrange_point", "translated_point", "polar"),
    "mechanisms.core.links": ("LINK_TYPES", "LinkType", "harmonic", "link_type"),
    "mechanisms.core.errors": ("MechanismError", "InvalidParameterError", "AssemblyError", "SingularPositionWarning",
                               "MissingDerivativeError", "StructureError", "UnknownNameError"),
    # layer 3
    "mechanisms.linkages": ("Mechanism", "Solution", "registry", "mechanism_classes", "groups"),
    "mechanisms.linkages.composed": ("Linkage",),
    "mechanisms.linkages.linkage_file": ("load_linkage", "example_files"),
    # layer 6
    "mechanisms.present": ("markdown_table", "number", "difference", "magnitude", "show_messages"),
}
"""The public names of the package by the module that defines them (imported when first used)."""

_MODULES = {"core": "mechanisms.core", "motion": "mechanisms.core.motion", "verify": "mechanisms.verify",
            "plot": "mechanisms.plot", "present": "mechanisms.present", "analysis": "mechanisms.analysis",
            "bench": "mechanisms.bench", "course": "mechanisms.course", "cli": "mechanisms.cli"}
"""Modules reached as attributes: ``mechanisms.verify`` …; ``mechanisms.plot`` imports matplotlib."""

class _OldModulePaths:
    """Finds the module paths of version 0.1 (``mechanisms.four_bar`` …, :mod:`mechanisms._moved`), asked
    only for a module of this package that is not found where it is: the table of moved names (and the
    import machinery it needs) is imported when an old path is first used, not with the package."""

    @staticmethod
    def find_spec(fullname: str, path: Any, target: Any = None) -> Any:
        if fullname.partition(".")[0] != __name__ or fullname == f"{__name__}._moved":
            return None
        return importlib.import_module(f"{__name__}._moved")._Finder().find_spec(fullname, path, target)


if not any(isinstance(finder, _OldModulePaths) for finder in sys.meta_path):
    sys.meta_path.append(_OldModulePaths())

_HOME = {name: module for module, names in _NAMES.items() for name in names}
_PUBLIC = [name for names in _NAMES.values() for name in names if name != "mechanism_classes"]
_PUBLIC += ["verify", "plot", "present", "core", "motion"]


def _mechanism_classes() -> dict[str, type]:
    """The mechanism classes (``CrankSlider``, ``FourBar`` …) as each module of :mod:`mechanisms.linkages`
    registered them (importing that folder imports every mechanism's module)."""
    return importlib.import_module("mechanisms.linkages").mechanism_classes()


_DEPRECATED = {"DeadCentreWarning": "mechanisms.core.errors"}
"""Old names kept for one release (their module warns when they are used)."""


def __getattr__(name: str) -> Any:
    """A public name of the package, imported from its module when first used, then kept here."""
    if name in _DEPRECATED:
        return getattr(importlib.import_module(_DEPRECATED[name]), name)
    if name in _MODULES:
        value: Any = importlib.import_module(_MODULES[name])
    elif name in _HOME:
        value = getattr(importlib.import_module(_HOME[name]), name)
    elif name == "__all__":
        value = _PUBLIC + sorted(_mechanism_classes())
    elif not name.startswith("_") and name in (classes := _mechanism_classes()):
        value = classes[name]
    else:
        raise AttributeError(f"module 'mechanisms' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """Every public name, the mechanism classes included (their modules are imported to list them)."""
    return sorted(set(globals()) | set(_PUBLIC) | set(_MODULES) | set(_mechanism_classes()))
