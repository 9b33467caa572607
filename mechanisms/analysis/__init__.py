"""Layer 4: analysis — Grashof, ranges, limit positions, time ratio, transmission angle, coupler
curves, synthesis, plans and instant centres, the Frenet-frame method, energy and power, and the
assignments a course can set on each mechanism.

Every module of this folder is imported with the package, so that each mechanism's analysis
module registers its assignment (:mod:`mechanisms.analysis.assignments`).
"""

import importlib
import pkgutil

for _module in pkgutil.iter_modules(__path__):
    importlib.import_module(f"{__name__}.{_module.name}")
