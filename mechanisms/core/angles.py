"""Layer 1: angles — one wrapping convention, the direction of a vector, the unit vector.

Every angle the package reduces is reduced to (−π, π] by :func:`wrap_angle` (degrees: (−180°, 180°]
by :func:`wrap_degrees`, or :func:`reduce_degrees`, which also refuses what is not a finite number);
nothing else in the package wraps angles its own way. An angle a person gives in degrees (a linkage
file, an option of the command line) is reduced in degrees, exactly, *before* it becomes radians:
``math.radians(1e20)`` is a number of radians whose reduction has nothing to do with 1e20° mod 360°.

A speed trick lives here beside the plain form the book shows (chapter 9 and the appendix on speed
measure what it buys; the tests compare the two):

* :func:`unit_vector_fast` — ``exp(iθ)`` from the tangent of the half angle, beside :func:`unit_vector`;
"""

from __future__ import annotations

import math
import numbers

import numpy as np
from numpy.typing import ArrayLike

from .errors import InvalidParameterError

__all__ = [
    "wrap_angle",
    "wrap_degrees",
    "reduce_degrees",
    "angle_of",
    "unit_vector",
    "unit_vector_fast",
    "constant",
]


def wrap_angle(angle: ArrayLike) -> np.ndarray:
    """An angle (rad) reduced to (−π, π].

    Parameters
    ----------
    angle : array_like
        Angles (rad), any finite size.

    Returns
    -------
    ndarray
        The same angles in (−π, π]: unchanged (exactly) where they are in it already, otherwise
        ``atan2(sin θ, cos θ)``, which numpy's correctly reduced sine and cosine make right to
        about one unit in the last place of π even for |θ| ~ 1e15, where subtracting multiples
        of the double nearest 2π would be off by 1e-2 rad.
    """
    a = np.asarray(angle, dtype=float)
    inside = (a > -math.pi) & (a <= math.pi)
    if np.all(inside):
        return a
    reduced = np.arctan2(np.sin(a), np.cos(a))
    reduced = np.where(reduced == -math.pi, math.pi, reduced)
    return np.where(inside, a, reduced)


def wrap_degrees(angle: ArrayLike) -> np.ndarray:
    """An angle in degrees reduced to (−180°, 180°] (the convention of :func:`wrap_angle`)."""
    a = np.asarray(angle, dtype=float)
    inside = (a > -180.0) & (a <= 180.0)
    if np.all(inside):
        return a
    reduced = np.fmod(a, 360.0)                       # exact, in (−360, 360)
    reduced = np.where(reduced > 180.0, reduced - 360.0, reduced)    # exact (Sterbenz)
    reduced = np.where(reduced <= -180.0, reduced + 360.0, reduced)
    return np.where(inside, a, reduced)


def reduce_degrees(angle: object, name: str = "angle") -> float | np.ndarray:
    """An angle given in degrees reduced exactly to (−180°, 180°], the convention of :func:`wrap_angle`.

    Parameters
    ----------
    angle : float or array_like of float
        Angles (°), finite, of any size: 1e20° is reduced as exactly as 10°, and an integer (a Python
        ``int`` of any size, as a TOML file gives it) as the integer it is, not as its nearest double.
    name : str
        The parameter's name, for the error.

    Returns
    -------
    float or ndarray
        A Python float for a scalar (a number, or a 0-d array), else an array of the same shape.
        ``fmod(x, 360)`` is exact for every double, and so is the shift by 360° into the interval
        (Sterbenz), so the result is the exact remainder; radians are taken only after it
        (``math.radians`` of the reduced value), so no work or memory grows with the angle's size.

    Raises
    ------
    InvalidParameterError
        If the angle is not a real number (a string, a bool, a complex) or is not finite (nan, ±inf).
    """
    requirement = "a finite angle in degrees"
    if isinstance(angle, (bool, np.bool_, str, bytes)):
        raise InvalidParameterError(name, angle, requirement)
    if isinstance(angle, (int, np.integer)):     # an integer (of any size) by the integers' own remainder
        remainder = int(angle) % 360
        return float(remainder - 360 if remainder > 180 else remainder)
    try:
        # a Python int beyond 2**64 would make an object array: take its float (exact to rounding)
        a = np.asarray(float(angle) if isinstance(angle, numbers.Real) else angle)
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(name, angle, requirement) from None
    if a.dtype.kind not in "iuf":
        raise InvalidParameterError(name, angle, requirement)
    try:
        a = a.astype(float)
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(name, angle, requirement) from None
    if not np.all(np.isfinite(a)):
        raise InvalidParameterError(name, angle, requirement)
    reduced = wrap_degrees(a)
    if reduced.ndim == 0:
        return float(reduced)
    return reduced


def angle_of(z: ArrayLike) -> np.ndarray:
    """The direction of plane vectors ``z = x + iy`` (rad, in (−π, π]): ``arg z = atan2(y, x)``."""
    return np.asarray(np.angle(np.asarray(z)))


def unit_vector(angle: ArrayLike, length: float = 1.0) -> np.ndarray:
    """``length·exp(iθ) = length·(cos θ + i sin θ)`` (complex, m): the book's form."""
    return length * np.exp(1j * np.asarray(angle))


def unit_vector_fast(angle: ArrayLike, length: float = 1.0) -> np.ndarray:
    """:func:`unit_vector` from the tangent of the half angle, at about half the cost.

    With ``t = tan(θ/2)``: ``exp(iθ) = (1 − t² + 2it)/(1 + t²)``. numpy evaluates the tangent in
    vector instructions, at about a ninth of the cost of a cosine and a sine; the result is within
    4e-16·|length| of ``length·exp(iθ)`` in each component (2.5 units in the last place instead of
    0.5), for angles of any size (chapter 9). ``θ/2`` is exact, and ``t`` is finite for every
    finite double θ.
    """
    angle = np.asarray(angle)
    if angle.dtype != np.float64 or angle.ndim == 0:
        return unit_vector(angle, length)
    t = np.multiply(angle, 0.5)
    np.tan(t, out=t)
    square = np.multiply(t, t)
    scale = np.add(square, 1.0)
    np.divide(length, scale, out=scale)           # length/(1 + t²)
    np.subtract(1.0, square, out=square)
    out = np.empty(angle.shape, dtype=complex)
    np.multiply(square, scale, out=out.real)      # length·(1 − t²)/(1 + t²)
    t += t
    np.multiply(t, scale, out=out.imag)           # length·2t/(1 + t²)
    return out


def constant(number: complex | float, shape: tuple[int, ...]) -> np.ndarray:
    """A read-only array of the given shape that holds one number: a view with zero strides.

    It takes no memory whatever its size, as ``np.broadcast_to`` would give, at a fifth of the cost.
    """
    base = np.array([number])
    view: np.ndarray = np.ndarray(shape, dtype=base.dtype, buffer=base, strides=(0,) * len(shape))
    view.flags.writeable = False
    return view
