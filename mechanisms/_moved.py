"""Old module paths of version 0.1, importable for one more release (with a DeprecationWarning).

Version 0.2 moved the modules into folders that are the layers (``mechanisms.four_bar`` is now
:mod:`mechanisms.linkages.four_bar` …). ``import mechanisms.four_bar`` still works and gives the
module at its new place; the warning names that place. This table is removed in version 0.3.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from types import ModuleType
from typing import Sequence

MOVED: dict[str, str | tuple[str, ...]] = {
    "mechanisms.motion": ("mechanisms.core.motion", "mechanisms.core.angles"),
    "mechanisms.links": "mechanisms.core.links",
    "mechanisms.errors": ("mechanisms.core.errors", "mechanisms.core.validate"),
    "mechanisms.base": "mechanisms.linkages.base",
    "mechanisms._blocks_of_positions": "mechanisms.linkages.chunks",
    "mechanisms.crank_slider": "mechanisms.linkages.crank_slider",
    "mechanisms.four_bar": "mechanisms.linkages.four_bar",
    "mechanisms.lambda_mechanism": "mechanisms.linkages.lambda_mechanism",
    "mechanisms.slotted": "mechanisms.linkages.slotted",
    "mechanisms.jet": "mechanisms.verify.jet",
    "mechanisms.plot_plans": "mechanisms.plot.plans",
    "mechanisms.assign": "mechanisms.course.assign",
    "mechanisms.grading": "mechanisms.course.grading",
}
"""Old module name → new module name, or the new modules whose names the old module held together
(``mechanisms.errors`` held the errors and the validators, now ``core.errors`` and ``core.validate``)."""


class _Loader(importlib.abc.Loader):
    def __init__(self, new: str | tuple[str, ...]):
        self.new = (new,) if isinstance(new, str) else new

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        warnings.warn(f"{spec.name} moved to {' and '.join(self.new)}; the old name goes in version 0.3",
                      DeprecationWarning, stacklevel=2)
        modules = [importlib.import_module(name) for name in self.new]
        if len(modules) == 1:
            return modules[0]
        merged = ModuleType(spec.name, modules[0].__doc__)
        for module in reversed(modules):   # the first module's names win
            merged.__dict__.update({k: v for k, v in vars(module).items() if not k.startswith("__")})
        return merged

    def exec_module(self, module: ModuleType) -> None:
        """The new module is executed already."""


class _Finder(importlib.abc.MetaPathFinder):
    def find_spec(self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None):
        if fullname in MOVED:
            return importlib.util.spec_from_loader(fullname, _Loader(MOVED[fullname]))
        return None


if not any(isinstance(finder, _Finder) for finder in sys.meta_path):
    sys.meta_path.append(_Finder())
