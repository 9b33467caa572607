"""Layer 1: one validation path for every kind of parameter.

Each ``require_*`` function returns the value in the type the model uses, or raises
:class:`~mechanisms.core.errors.InvalidParameterError` naming the parameter, the value given and
what is required.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from .errors import InvalidParameterError

__all__ = [
    "require_length",
    "require_finite",
    "require_positive",
    "require_finite_array",
    "require_branch",
    "require_order",
]


def _number(name: str, value, requirement: str, positive: bool) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, requirement) from None
    if not math.isfinite(number) or (positive and number <= 0.0):
        raise InvalidParameterError(name, value, requirement)
    return number



def require_finite(name: str, value: object) -> float:
    """Return ``value`` as float, or raise :class:`InvalidParameterError` if it is not finite."""
    return _number(name, value, "a finite number", positive=False)


def require_positive(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as float, or raise if it is not a finite number > 0 (in ``unit``)."""
    return _number(name, value, f"a finite number > 0{' ' + unit if unit else ''}", positive=True)


def require_finite_array(name: str, values: ArrayLike, unit: str = "") -> np.ndarray:
    """Return ``values`` as an array of floats, or raise naming (up to three of) those that are not finite."""
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, values, "numbers") from None
    bad = ~np.isfinite(array)
    if bad.any():
        shown = array[bad][:3].tolist() if array.ndim else array.item()
        raise InvalidParameterError(name, shown, f"finite{' (' + unit + ')' if unit else ''}")
    return array


def require_length(name: str, value: object) -> float:
    """Return ``value`` as float, or raise if it is not a finite length > 0 (m)."""
    return _number(name, value, "a finite length > 0 m", positive=True)


def require_branch(value: object, name: str = "branch") -> int:
    """Return the branch as int +1 or -1, or raise :class:`InvalidParameterError`."""
    if value in (1, -1) and not isinstance(value, bool):
        return int(value)
    raise InvalidParameterError(name, value, "+1 or -1")


def require_order(value: object) -> int:
    """Return the derivative order as int 0, 1 or 2, or raise."""
    if value in (0, 1, 2) and not isinstance(value, bool):
        return int(value)
    raise InvalidParameterError("order", value, "0 (positions), 1 (+ velocities) or 2 (+ accelerations)")
