"""Kinematics of planar linkage mechanisms: the package of the book.

The folders are the layers, bottom up (a module imports only from its own layer or below):

1. :mod:`mechanisms.core` — the motion of a link and its points, angles, errors, validation;
2. :mod:`mechanisms.blocks` — the closed-form building blocks (dyads);
3. :mod:`mechanisms.linkages` — the ``Mechanism`` base class and the book's mechanisms;
4. :mod:`mechanisms.analysis` — Grashof, ranges, limit positions, plans, Frenet, energy, synthesis;
5. :mod:`mechanisms.verify` — the generic solver, numerical differentiation, the checks;
6. :mod:`mechanisms.plot` (matplotlib) and :mod:`mechanisms.present` (text) — figures and tables;
7. tools: :mod:`mechanisms.course` (assignments, grading), :mod:`mechanisms.bench`, :mod:`mechanisms.cli`.

``import mechanisms`` imports layers 1–5 and the text tables; matplotlib is imported only when
``mechanisms.plot`` is first used.
"""

from __future__ import annotations

import importlib
from typing import Any

from . import _moved, core, verify
from .core import motion
from .core.errors import (AssemblyError, DeadCentreWarning, InvalidParameterError, MechanismError,
                          MissingDerivativeError, StructureError)
from .core.links import LINK_TYPES, LinkType, harmonic, link_type
from .core.motion import (AngleMotion, Motion, PointMotion, fixed_point, lagrange_point, plane_motion, point_on_link,
                          polar, translated_point)
from .linkages import Mechanism, Solution, mechanism_classes, registry
from .linkages import groups
from .linkages.composed import Linkage
from .linkages.linkage_file import example_files, load_linkage
from .present import difference, magnitude, markdown_table

__version__ = "0.2.0"

__all__ = [
    # layer 1
    "Motion", "AngleMotion", "PointMotion", "fixed_point", "plane_motion", "point_on_link", "lagrange_point",
    "translated_point", "polar", "LINK_TYPES", "LinkType", "harmonic", "link_type",
    "MechanismError", "InvalidParameterError", "AssemblyError", "DeadCentreWarning", "MissingDerivativeError",
    "StructureError",
    # layer 3
    "Mechanism", "Solution", "registry", "Linkage", "groups", "load_linkage", "example_files",
    # layers 5 and 6
    "verify", "plot", "present", "markdown_table", "difference", "magnitude",
    "core", "motion",
]

# the mechanism classes (CrankSlider, FourBar …) as each module of mechanisms.linkages registered them
globals().update(mechanism_classes())
__all__ += sorted(mechanism_classes())

_LAZY = {"plot": "mechanisms.plot", "present": "mechanisms.present", "analysis": "mechanisms.analysis",
         "bench": "mechanisms.bench", "course": "mechanisms.course", "cli": "mechanisms.cli"}


def __getattr__(name: str) -> Any:
    """``mechanisms.plot`` and the tool packages, imported when first used (plotting imports matplotlib)."""
    if name in _LAZY:
        module = importlib.import_module(_LAZY[name])
        globals()[name] = module
        return module
    raise AttributeError(f"module 'mechanisms' has no attribute {name!r}")
