"""Layer 1: the motion of a link and of the points on it.

A :class:`Motion` is a value with its first two time derivatives, each an array over the
crank positions. Angles and lengths are real arrays; points are complex arrays ``x + iy``,
so the plane-motion formulas of the lecture read as in the book (chapter 1):

* Euler form (pole P, link angle θ):
  ``v = v_P + iω(r − r_P)``, ``a = a_P + (iε − ω²)(r − r_P)``;
* Lagrange form: the point's coordinates (α, β) in the reference position, turned by Δθ
  about the moving pole.

Derivatives that were not asked for are ``None``: a trajectory needs positions only. A formula
that needs one reads it as :attr:`Motion.d1` or :attr:`Motion.d2`, an array, or
:class:`~mechanisms.core.errors.MissingDerivativeError` if it was not computed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Self

import numpy as np
from numpy.typing import ArrayLike

from .angles import angle_of, constant, unit_vector_fast
from .errors import MissingDerivativeError

__all__ = [
    "Motion",
    "AngleMotion",
    "PointMotion",
    "fixed_point",
    "plane_motion",
    "point_on_link",
    "lagrange_point",
    "translated_point",
    "polar",
]

Derivative = Any
"""A time derivative over the crank positions: an ndarray, or ``None`` where it was not computed (the
motion's :attr:`Motion.order` says which). Typed ``Any`` for now: the package computes a derivative
only under ``order ≥ 1`` (or 2) and then uses it as an array, a fact of the algorithm that the type
checker cannot follow through every block; the tests check it at every order. Code that reads a
derivative as an array reads :attr:`Motion.d1` / :attr:`Motion.d2` (typed ``ndarray``, checked);
once every block does, this alias becomes ``np.ndarray | None``."""


@dataclass(frozen=True)
class Motion:
    """A value and its first and second time derivatives over the crank positions.

    Parameters
    ----------
    value : ndarray
        Real (angle in rad, length in m) or complex (point ``x + iy`` in m).
    velocity : ndarray or None
        First time derivative (1/s or m/s), ``None`` if not computed.
    acceleration : ndarray or None
        Second time derivative (1/s² or m/s²), ``None`` if not computed.
    """

    value: Any
    velocity: Derivative = None
    acceleration: Derivative = None

    @property
    def order(self) -> int:
        """0, 1 or 2: how many time derivatives are known."""
        if self.velocity is None:
            return 0
        return 1 if self.acceleration is None else 2

    @property
    def d1(self) -> np.ndarray:
        """The first time derivative as an array (1/s or m/s: φ_t of an angle φ): :attr:`velocity`, never ``None``.

        Raises
        ------
        MissingDerivativeError
            If velocities were not computed (a motion of order 0).
        """
        if self.velocity is None:
            raise MissingDerivativeError(1, self.order)
        return self.velocity

    @property
    def d2(self) -> np.ndarray:
        """The second time derivative as an array (1/s² or m/s²: φ_tt): :attr:`acceleration`, never ``None``.

        Raises
        ------
        MissingDerivativeError
            If accelerations were not computed (a motion of order 0 or 1).
        """
        if self.acceleration is None:
            raise MissingDerivativeError(2, self.order)
        return self.acceleration

    def derivatives(self) -> tuple[np.ndarray, Derivative, Derivative]:
        """Return ``(value, velocity, acceleration)``, the missing ones as ``None``."""
        return self.value, self.velocity, self.acceleration

    def __getitem__(self, index: Any) -> Self:
        """The motion at some positions only (numpy indexing of every array; ``index`` is any numpy index)."""
        velocity, acceleration = self.velocity, self.acceleration
        return type(self)(np.asarray(self.value)[index],
                          None if velocity is None else np.asarray(velocity)[index],
                          None if acceleration is None else np.asarray(acceleration)[index])

    def truncated(self, order: int) -> Self:
        """The same motion with the derivatives above ``order`` dropped."""
        value, velocity, acceleration = self.derivatives()
        return type(self)(value, velocity if order >= 1 else None, acceleration if order >= 2 else None)

    def _combine(self, other: Motion | complex | np.ndarray, sign: float) -> Self:
        if isinstance(other, Motion):
            # the derivatives both motions have, up to the lower of their orders
            order = min(self.order, other.order)
            return type(self)(self.value + sign * other.value,
                              self.d1 + sign * other.d1 if order >= 1 else None,
                              self.d2 + sign * other.d2 if order >= 2 else None)
        # a constant: only the value changes
        return type(self)(self.value + sign * other, self.velocity, self.acceleration)

    def __add__(self, other: Motion | complex | np.ndarray) -> Self:
        return self._combine(other, 1.0)

    def __sub__(self, other: Motion | complex | np.ndarray) -> Self:
        return self._combine(other, -1.0)

    def __mul__(self, factor: float) -> Self:
        """Scale by a constant factor."""
        velocity, acceleration = self.velocity, self.acceleration
        return type(self)(self.value * factor,
                          None if velocity is None else velocity * factor,
                          None if acceleration is None else acceleration * factor)

    __rmul__ = __mul__


class AngleMotion(Motion):
    """The angle of a link (rad) with its angular velocity ω (1/s) and acceleration ε (1/s²).

    The angle is measured counter-clockwise from +x; in the book's notation φ (crank),
    ψ (coupler), ξ (rocker or lever), and ``φ_t, φ_tt`` their time derivatives.
    """

    @property
    def angle(self) -> np.ndarray:
        """The angle (rad)."""
        return self.value

    @property
    def omega(self) -> Derivative:
        """Angular velocity ω (1/s), counter-clockwise positive; ``None`` if not computed (see :attr:`d1`)."""
        return self.velocity

    @property
    def alpha(self) -> Derivative:
        """Angular acceleration ε (1/s²); ``None`` if not computed (see :attr:`d2`)."""
        return self.acceleration

    def unit(self) -> np.ndarray:
        """``exp(iθ)``, the unit vector along the link."""
        return unit_vector_fast(self.value)


class PointMotion(Motion):
    """A point ``x + iy`` (m) with its velocity (m/s) and acceleration (m/s²) as complex numbers."""

    @property
    def position(self) -> np.ndarray:
        """The point as a complex number ``x + iy`` (m)."""
        return self.value

    @property
    def x(self) -> np.ndarray:
        """Abscissa (m)."""
        return np.real(self.value)

    @property
    def y(self) -> np.ndarray:
        """Ordinate (m)."""
        return np.imag(self.value)

    @property
    def speed(self) -> np.ndarray:
        """Magnitude of the velocity (m/s).

        Raises
        ------
        MissingDerivativeError
            If velocities were not computed.
        """
        return np.abs(self.d1)


def fixed_point(position: complex, like: ArrayLike = 0.0, order: int = 2) -> PointMotion:
    """A point of the frame: constant position, zero velocity and acceleration.

    Parameters
    ----------
    position : complex
        The point ``x + iy`` (m).
    like : array_like
        An array whose shape the result takes (usually the crank angles).
    order : int
        Number of time derivatives to include (0, 1 or 2).

    Notes
    -----
    The arrays are read-only broadcast views of one number (a zero stride): they take no
    memory and cost nothing to make, however many positions there are (chapter 9).
    """
    shape = np.shape(like)
    value = constant(complex(position), shape)
    zero = constant(0j, shape) if order else None
    return PointMotion(value, zero if order >= 1 else None, zero if order >= 2 else None)


def plane_motion(pole: PointMotion, angle: AngleMotion, position: np.ndarray) -> PointMotion:
    """Velocity and acceleration of a point of a link in plane motion (Euler form).

    Parameters
    ----------
    pole : PointMotion
        A point P of the link whose motion is known (m, m/s, m/s²).
    angle : AngleMotion
        The link's angle θ with ω = θ_t and ε = θ_tt.
    position : ndarray of complex
        The point's current position r (m).

    Returns
    -------
    PointMotion
        ``r``, ``v = v_P + iω(r − r_P)``, ``a = a_P + (iε − ω²)(r − r_P)``, up to the lower
        of the orders of ``pole`` and ``angle``.

    Notes
    -----
    Chapter 1, Euler form; lecture slides "coupler" and "recommended sequence, step 5".
    With a fixed pole (v_P = a_P = 0) it is the rotation of a crank or a rocker.
    """
    order = min(pole.order, angle.order)
    if order == 0:
        return PointMotion(position)
    arm = position - pole.value
    omega = angle.d1
    velocity = pole.d1 + 1j * omega * arm
    if order == 1:
        return PointMotion(position, velocity)
    acceleration = pole.d2 + (1j * angle.d2 - omega**2) * arm
    return PointMotion(position, velocity, acceleration)


def point_on_link(pole: PointMotion | complex, angle: AngleMotion, along: float, left: float = 0.0) -> PointMotion:
    """A point fixed to a link: ``along`` metres from the pole along the link, ``left`` to its left.

    Parameters
    ----------
    pole : PointMotion or complex
        The link's first joint (a complex number for a fixed pivot).
    angle : AngleMotion
        The link's angle (direction from its first joint to its second).
    along, left : float
        The point's coordinates in the link's frame (m): ``u`` along the link, ``w`` to the
        left of it (counter-clockwise side).

    Notes
    -----
    ``r = r_P + (u + iw)·exp(iθ)``; the derivatives are those of :func:`plane_motion`.
    """
    if isinstance(pole, Motion):
        position = pole.value + complex(along, left) * angle.unit()
        return plane_motion(pole, angle, position)
    # a fixed pole: the arm r − r_P is known, and the pole's zero velocity and acceleration
    # need not be added (the same values as plane_motion's, without its temporaries)
    arm = unit_vector_fast(angle.value, along) if left == 0.0 else complex(along, left) * angle.unit()
    if angle.order == 0:
        arm += complex(pole)             # r = r_P + arm, in place
        return PointMotion(arm)
    position = arm + complex(pole)
    omega = angle.d1
    turn = 1j * omega
    velocity = turn * arm
    velocity += 0.0          # as plane_motion's v_P + …: no negative zeros
    if angle.order == 1:
        return PointMotion(position, velocity)
    acceleration = (1j * angle.d2 - omega**2) * arm
    acceleration += 0.0
    return PointMotion(position, velocity, acceleration)


def lagrange_point(pole: PointMotion | complex, angle: AngleMotion, material: complex,
                   material_pole: complex, reference_angle: float = 0.0) -> PointMotion:
    """A point of a link in plane motion, in the lecture's Lagrange form.

    Parameters
    ----------
    pole : PointMotion or complex
        The pole P of the link now (x_P, y_P) with its derivatives.
    angle : AngleMotion
        The link's angle; the link has turned by ``Δθ = θ − reference_angle``.
    material : complex
        The point's coordinates (α, β) in the reference position, as ``α + iβ`` (m).
    material_pole : complex
        The pole's coordinates (α_P, β_P) in the reference position (m).
    reference_angle : float
        The link's angle in the reference position (rad).

    Notes
    -----
    ``x = x_P + (α − α_P) cos Δθ − (β − β_P) sin Δθ``,
    ``y = y_P + (α − α_P) sin Δθ + (β − β_P) cos Δθ``, differentiated term by term
    (chapter 1). It equals the Euler form; the book shows both and the tests compare them.
    """
    if not isinstance(pole, Motion):
        pole = fixed_point(pole, angle.value, angle.order)
    da, db = (material - material_pole).real, (material - material_pole).imag
    turn = angle.value - reference_angle
    c, s = np.cos(turn), np.sin(turn)
    dx, dy = da * c - db * s, da * s + db * c  # the arm r - r_P, turned
    x, y = pole.x + dx, pole.y + dy
    order = min(pole.order, angle.order)
    if order == 0:
        return PointMotion(x + 1j * y)
    w = angle.d1
    pole_velocity = pole.d1
    vx = pole_velocity.real - w * (da * s + db * c)
    vy = pole_velocity.imag + w * (da * c - db * s)
    if order == 1:
        return PointMotion(x + 1j * y, vx + 1j * vy)
    e = angle.d2
    pole_acceleration = pole.d2
    ax = pole_acceleration.real - e * dy - w**2 * dx
    ay = pole_acceleration.imag + e * dx - w**2 * dy
    return PointMotion(x + 1j * y, vx + 1j * vy, ax + 1j * ay)


def translated_point(reference: PointMotion, offset: complex) -> PointMotion:
    """A point of a translating link (a slider): the reference point's motion, shifted.

    Notes
    -----
    In translation every point has the same velocity and acceleration (chapter 1):
    ``r = r_P + const``, ``v = v_P``, ``a = a_P``.
    """
    return reference + complex(offset)


def polar(vector: PointMotion) -> tuple[Motion, AngleMotion]:
    """Length and direction of a moving vector, with their time derivatives.

    Parameters
    ----------
    vector : PointMotion
        A vector ``d = q − p`` between two moving points (m, m/s, m/s²).

    Returns
    -------
    length : Motion
        ``L = |d|``, ``L_t = Re(d̄ d_t)/L``, ``L_tt = (Re(d̄ d_tt) + |d_t|² − L_t²)/L``, computed as
        ``Re(d̄ d_tt)/L + L θ_t²`` (the same, since ``|d_t|² = L_t² + L²θ_t²``, without the cancellation of
        ``|d_t|² − L_t²`` near the pivot).
    direction : AngleMotion
        ``θ = arg d``, ``θ_t = Im(d̄ d_t)/L²``, ``θ_tt = (Im(d̄ d_tt) − 2 L L_t θ_t)/L²``.

    Notes
    -----
    Used for the current length of a slotted link, L_tek, and the angle of a link through two
    joints (chapters 1 and 5). The lecture's formula for (L_tek)_tt has a typo: see the errata.
    Where ``L = 0`` the direction and the derivatives are undefined (inf or nan).
    """
    d = vector.value
    length = np.abs(d)
    direction = angle_of(d)
    if vector.order == 0:
        return Motion(length), AngleMotion(direction)
    with np.errstate(divide="ignore", invalid="ignore"):
        conj = np.conj(d)
        first = conj * vector.d1
        length_t = first.real / length
        direction_t = first.imag / length**2
        if vector.order == 1:
            return Motion(length, length_t), AngleMotion(direction, direction_t)
        second = conj * vector.d2
        # (Re(d̄ d_tt) + |d_t|² − L_t²)/L with |d_t|² = L_t² + L²θ_t²: the form without cancellation
        length_tt = second.real / length + length * direction_t**2
        direction_tt = (second.imag - 2.0 * length * length_t * direction_t) / length**2
    return (Motion(length, length_t, length_tt),
            AngleMotion(direction, direction_t, direction_tt))
