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
    "require_non_negative",
    "require_finite_array",
    "require_branch",
    "require_order",
    "require_pair",
    "require_flag",
]


def _number(name: str, value: object, requirement: str, positive: bool) -> float:
    """``value`` as a float: a real number (Python's or numpy's, not a bool or a string), finite, > 0 if asked."""
    if isinstance(value, (bool, np.bool_, str, bytes)) or np.ndim(value) != 0 or np.iscomplexobj(value):  # type: ignore[arg-type]
        raise InvalidParameterError(name, value, requirement)
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
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


def require_non_negative(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as float, or raise if it is not a finite number ≥ 0 (in ``unit``)."""
    number = _number(name, value, f"a finite number ≥ 0{' ' + unit if unit else ''}", positive=False)
    if number < 0.0:
        raise InvalidParameterError(name, value, f"a finite number ≥ 0{' ' + unit if unit else ''}")
    return number


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
        return 1 if value == 1 else -1
    raise InvalidParameterError(name, value, "+1 or -1")


def require_order(value: object) -> int:
    """Return the derivative order as int 0, 1 or 2, or raise."""
    if value in (0, 1, 2) and not isinstance(value, bool):
        return {0: 0, 1: 1, 2: 2}[value]  # type: ignore[index]
    raise InvalidParameterError("order", value, "0 (positions), 1 (+ velocities) or 2 (+ accelerations)")


def require_pair(name: str, value: object, unit: str = "m") -> tuple[float, float]:
    """Return ``value`` as a pair of finite floats ``(x, y)`` (a point or a vector, in ``unit``), or raise.

    A string is not a pair (``"12"`` would otherwise unpack to (1, 2)); a complex number is not
    accepted either, so that a point is always written the same way, as two coordinates.
    """
    requirement = f"a pair (x, y) of finite numbers in {unit}"
    if isinstance(value, (str, bytes)):
        raise InvalidParameterError(name, value, requirement)
    x: object
    y: object
    try:
        x, y = value  # type: ignore[misc]   # any pair: unpacked, then checked
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, requirement) from None
    return _number(f"{name}[0]", x, requirement, positive=False), _number(f"{name}[1]", y, requirement, positive=False)


def require_flag(name: str, value: object) -> bool:
    """Return ``value`` as bool if it is ``True`` or ``False`` (Python's or numpy's), or raise.

    A string such as ``"False"`` is refused rather than taken as true.
    """
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise InvalidParameterError(name, value, "True or False")
