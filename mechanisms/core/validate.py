"""Layer 1: one validation path for every kind of parameter.

Each ``require_*`` function returns the value in the type the model uses, or raises
:class:`~mechanisms.core.errors.InvalidParameterError` naming the parameter, the value given and
what is required.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
from numpy.typing import ArrayLike

from .errors import InvalidParameterError

__all__ = [
    "LENGTH_MIN",
    "LENGTH_MAX",
    "ANGLE_MAX",
    "OMEGA_MAX",
    "ALPHA_MAX",
    "require_length",
    "require_coordinate",
    "require_angles",
    "require_rates",
    "require_finite",
    "require_positive",
    "require_non_negative",
    "require_finite_array",
    "require_branch",
    "require_order",
    "require_pair",
    "require_flag",
]


LENGTH_MIN = 2.0**-510
"""The shortest length a mechanism may have (m), about 3.0e-154 m (a mechanism of unit size scaled by 2^-500
has its lengths above it)."""

LENGTH_MAX = 2.0**510
"""The longest length, and the largest coordinate of a point, a mechanism may have (m), about 3.4e153 m.

Between :data:`LENGTH_MIN` and :data:`LENGTH_MAX` a mechanism is solved at a scale of its own (its
lengths divided by a power of four, which is exact) and the results scaled back, so that squares of
lengths neither overflow nor underflow: the results are those of the same mechanism in metres, to
rounding (:meth:`~mechanisms.linkages.base.Mechanism.solve`)."""

ANGLE_MAX = 2.0**52
"""The largest |φ| of a crank angle (rad), about 4.5e15 rad: beyond it consecutive doubles are more
than a radian apart."""

OMEGA_MAX = 1e50
"""The largest |ω| = |φ_t| of the crank (1/s): accelerations ω²·L then stay in range for every length
between :data:`LENGTH_MIN` and :data:`LENGTH_MAX`, the growth near singular positions included. (A very small ω
is accepted; accelerations below about 1e-300 m/s² then lose relative accuracy to underflow.)"""

ALPHA_MAX = 1e100
"""The largest |α| = |φ_tt| of the crank (1/s²)."""


def _is_real_scalar(value: object) -> bool:
    """True for a real number of Python or numpy (an int or a float, not a bool, a string or a complex)."""
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim == 0 and value.dtype.kind in "iuf"
    return isinstance(value, (numbers.Real, np.integer, np.floating))


def _number(name: str, value: object, requirement: str, positive: bool) -> float:
    """``value`` as a float: a real number (Python's or numpy's, not a bool or a string), finite, > 0 if asked."""
    if not _is_real_scalar(value):
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


def _real_array(name: str, values: object, requirement: str) -> np.ndarray:
    """``values`` as an array of floats: numbers or (nested) sequences of them, not None, bools, strings or
    complex numbers (``np.asarray(None, float)`` would be ``nan`` and ``"12"`` would be 12)."""
    if values is None or isinstance(values, (str, bytes)):
        raise InvalidParameterError(name, values, requirement)
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(name, values, requirement) from None
    if raw.dtype.kind not in "iuf":
        if raw.dtype.kind != "O" or not all(_is_real_scalar(v) for v in raw.ravel().tolist()):
            raise InvalidParameterError(name, values, requirement)
    try:
        return np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(name, values, requirement) from None


def require_finite_array(name: str, values: ArrayLike, unit: str = "") -> np.ndarray:
    """Return ``values`` as an array of floats, or raise naming (up to three of) those that are not finite.

    ``values`` must be real numbers (an array, a sequence or one number); None, bools, strings and
    complex numbers are refused, not converted."""
    requirement = f"finite real numbers{' (' + unit + ')' if unit else ''}"
    array = _real_array(name, values, requirement)
    bad = ~np.isfinite(array)
    if bad.any():
        shown = array[bad][:3].tolist() if array.ndim else array.item()
        raise InvalidParameterError(name, shown, requirement)
    return array


def require_angles(name: str, values: ArrayLike) -> np.ndarray:
    """Crank angles (rad) as an array of floats: finite real numbers with |φ| ≤ :data:`ANGLE_MAX`, or raise."""
    array = require_finite_array(name, values, "crank angles in rad")
    if array.size and float(np.max(np.abs(array))) > ANGLE_MAX:
        shown = array[np.abs(array) > ANGLE_MAX][:3].tolist()
        raise InvalidParameterError(name, shown, f"crank angles of at most {ANGLE_MAX:.3g} rad in magnitude")
    return array


def require_rates(name: str, values: ArrayLike, shape: tuple[int, ...], high: float, unit: str) -> np.ndarray:
    """A crank rate (φ_t or φ_tt): one number or an array that broadcasts to ``shape`` (the crank angles'),
    each finite and of magnitude at most ``high`` (``unit``), as an array of floats; or raise naming it."""
    array = require_finite_array(name, values, unit)
    try:
        if np.broadcast_shapes(array.shape, shape) != tuple(shape):
            raise ValueError
    except ValueError:
        raise InvalidParameterError(name, f"an array of shape {array.shape}",
                                    f"one number or one per crank angle (shape {tuple(shape)})") from None
    bad = np.abs(array) > high
    if bad.any():
        shown = array[bad][:3].tolist() if array.ndim else array.item()
        raise InvalidParameterError(name, shown, f"of magnitude at most {high:g} {unit}")
    return array


def require_length(name: str, value: object) -> float:
    """Return ``value`` as float, or raise if it is not a length in [:data:`LENGTH_MIN`, :data:`LENGTH_MAX`] (m)."""
    number = _number(name, value, "a finite length > 0 m", positive=True)
    if not LENGTH_MIN <= number <= LENGTH_MAX:
        raise InvalidParameterError(name, value, f"a length from {LENGTH_MIN:.3g} m to {LENGTH_MAX:.3g} m")
    return number


def require_coordinate(name: str, value: object, unit: str = "m") -> float:
    """Return ``value`` as float, or raise if it is not a finite coordinate (or offset) of magnitude at most
    :data:`LENGTH_MAX` (``unit``)."""
    number = _number(name, value, "a finite number", positive=False)
    if abs(number) > LENGTH_MAX:
        raise InvalidParameterError(name, value, f"of magnitude at most {LENGTH_MAX:.3g} {unit}")
    return number


def _whole(value: object, allowed: tuple[int, ...]) -> int | None:
    """``value`` as an int if it is an integer of Python or numpy (not a bool) equal to one of ``allowed``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        return None
    number = int(value)
    return number if number in allowed else None


def require_branch(value: object, name: str = "branch") -> int:
    """Return the branch as int +1 or -1 (an integer of Python or numpy, not a bool, a float or an array), or raise
    :class:`InvalidParameterError`."""
    number = _whole(value, (1, -1))
    if number is None:
        raise InvalidParameterError(name, value, "+1 or -1")
    return number


def require_order(value: object) -> int:
    """Return the derivative order as int 0, 1 or 2 (an integer, not a bool, a float or an array), or raise."""
    number = _whole(value, (0, 1, 2))
    if number is None:
        raise InvalidParameterError("order", value, "0 (positions), 1 (+ velocities) or 2 (+ accelerations)")
    return number


def require_pair(name: str, value: object, unit: str = "m") -> tuple[float, float]:
    """Return ``value`` as a pair of finite floats ``(x, y)`` (a point or a vector, in ``unit``), or raise.

    A string is not a pair (``"12"`` would otherwise unpack to (1, 2)); a complex number is not
    accepted either, so that a point is always written the same way, as two coordinates.
    """
    requirement = f"a pair (x, y) of finite numbers in {unit}"
    if isinstance(value, (str, bytes, dict)) or value is None:
        raise InvalidParameterError(name, value, requirement)
    x: object
    y: object
    try:
        x, y = value  # type: ignore[misc]   # any pair: unpacked, then checked
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, requirement) from None
    pair = _number(f"{name}[0]", x, requirement, positive=False), _number(f"{name}[1]", y, requirement, positive=False)
    for index, number in enumerate(pair):
        if abs(number) > LENGTH_MAX:
            raise InvalidParameterError(f"{name}[{index}]", number, f"of magnitude at most {LENGTH_MAX:.3g} {unit}")
    return pair


def require_flag(name: str, value: object) -> bool:
    """Return ``value`` as bool if it is ``True`` or ``False`` (Python's or numpy's), or raise.

    A string such as ``"False"`` is refused rather than taken as true.
    """
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise InvalidParameterError(name, value, "True or False")
