"""Layer 3, linkages: the :class:`~mechanisms.linkages.base.Mechanism` base class and the book's mechanisms.

Each mechanism lives in one module and registers there everything the rest of the package needs
from it (the command line's parameters, the benchmark's example, the plans' groups, the course's
assignment): no other module lists mechanisms. :mod:`~mechanisms.linkages.chunks` solves long
arrays of crank positions in cache-sized chunks.
"""

import importlib
import pkgutil

from .base import Mechanism, Solution, registry

__all__ = ["Mechanism", "Solution", "registry", "mechanism_classes"]

# Every module of this folder is imported, so that each mechanism registers itself: adding a
# mechanism is adding a module here.
for _module in pkgutil.iter_modules(__path__):
    importlib.import_module(f"{__name__}.{_module.name}")


def mechanism_classes() -> dict[str, type[Mechanism]]:
    """The mechanism classes of the package by class name (``"FourBar"`` …), as registered."""
    return {cls.__name__: cls for cls in registry.values()}
