"""Lines that move: the intersection of two lines, the distance from a point to a line.

The slotted-link mechanisms of chapter 5 are made of straight lines carried by links: the slot
of a lever, the line of a coupler, a fixed guide. Three questions recur, and each is a block here,
with exact first and second time derivatives:

* where do two moving lines meet (a slider on a coupler and a fixed guide; the lecture's
  point D of two rockers with a slotted pair) — :func:`line_intersection`;
* how far is a moving point from a moving line, and where is the foot of the perpendicular
  (the lecture's h and K; the book's h_N and N) — :func:`distance_to_line`;
* where does a circle about a moving point meet a moving line (a rocker whose pin slides in the
  slot of a lever) — :func:`circle_on_line`;

and one derived quantity: the angle η between a link of length L₂ and a line from which one end
of the link is h away, ``sin η = h / L₂`` — :func:`angle_from_distance`.

A line is given by a point Q on it (a :class:`~mechanisms.motion.PointMotion` or a fixed complex
number) and its direction θ (an :class:`~mechanisms.motion.AngleMotion` or a fixed angle in rad);
its unit vector is ``ê = exp(iθ)``, with ``ê_t = iθ_t ê`` and ``ê_tt = (iθ_tt − θ_t²) ê``.
"""

from __future__ import annotations

import math

from dataclasses import dataclass

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_branch, require_length
from ..core.motion import AngleMotion, Motion, PointMotion, fixed_point

__all__ = [
    "LineIntersection",
    "PointLineDistance",
    "CircleOnLine",
    "line_intersection",
    "distance_to_line",
    "circle_on_line",
    "angle_from_distance",
    "parallel_directions",
]

# Lines closer to parallel than this (|sin| of the angle between them) are reported as singular.
_PARALLEL = 1e-12


def parallel_directions(first_angle: float, second_angle: float) -> bool:
    """True if two directions (rad) are parallel or opposite to within round-off: ``|sin(β₂ − β₁)| ≤ 1e-12``.

    Two lines of these directions have no single intersection (:func:`line_intersection` marks such
    positions singular); a linkage whose two guides on one link are parallel has no position at all.
    """
    return abs(math.sin(second_angle - first_angle)) <= _PARALLEL


def _as_point(point, like, order: int) -> PointMotion:
    """A PointMotion for a moving point, or a fixed one for a complex number."""
    if isinstance(point, PointMotion):
        return point
    point = complex(point)
    if not (np.isfinite(point.real) and np.isfinite(point.imag)):
        raise InvalidParameterError("point", point, "a finite point x + iy (m)")
    return fixed_point(point, like, order)


def _as_angle(angle, like, order: int) -> AngleMotion:
    """An AngleMotion for a moving direction, or a constant one for a number (rad)."""
    if isinstance(angle, AngleMotion):
        return angle
    value = float(angle)
    if not np.isfinite(value):
        raise InvalidParameterError("angle", angle, "a finite angle (rad)")
    shape = np.shape(like)
    zero = np.zeros(shape)
    return AngleMotion(np.full(shape, value), zero if order >= 1 else None, zero if order >= 2 else None)


def _unit(angle: AngleMotion, order: int) -> tuple:
    """``(e, e_t, e_tt)`` of the unit vector ``exp(iθ)`` up to ``order``."""
    e = np.exp(1j * angle.value)
    e_t = 1j * angle.omega * e if order >= 1 else None
    e_tt = (1j * angle.alpha - angle.omega**2) * e if order >= 2 else None
    return e, e_t, e_tt


def _product(a: tuple, b: tuple, order: int) -> tuple:
    """Leibniz's rule: derivatives of ``a·b`` from those of a and b (tuples of arrays)."""
    value = a[0] * b[0]
    first = a[1] * b[0] + a[0] * b[1] if order >= 1 else None
    second = a[2] * b[0] + 2.0 * a[1] * b[1] + a[0] * b[2] if order >= 2 else None
    return value, first, second


def _quotient(n: tuple, c: tuple, order: int) -> tuple:
    """Derivatives of ``n / c``: ``s_t = (n_t − s c_t)/c``, ``s_tt = (n_tt − 2 s_t c_t − s c_tt)/c``."""
    s = n[0] / c[0]
    s_t: Any = (n[1] - s * c[1]) / c[0] if order >= 1 else None
    s_tt = (n[2] - 2.0 * s_t * c[1] - s * c[2]) / c[0] if order >= 2 else None
    return s, s_t, s_tt


def _conj(a: tuple) -> tuple:
    return tuple(None if x is None else np.conj(x) for x in a)


def _part(a: tuple, which) -> tuple:
    return tuple(None if x is None else which(x) for x in a)


def _where(angles, mask: np.ndarray):
    """The crank angles (rad) at the positions of ``mask``, for an error message; None if unknown."""
    if angles is None:
        return None
    angles = np.asarray(angles, dtype=float)
    shape = np.broadcast_shapes(np.shape(angles), np.shape(mask))
    return np.broadcast_to(angles, shape)[np.broadcast_to(mask, shape)]


def _order(*motions: Motion) -> int:
    return min(m.order for m in motions)


def _common_order(point, angle) -> int:
    orders = [m.order for m in (point, angle) if isinstance(m, Motion)]
    return min(orders) if orders else 2


def _like(*items) -> np.ndarray:
    for item in items:
        if isinstance(item, Motion):
            return np.asarray(item.value)
    return np.zeros(())


@dataclass(frozen=True)
class LineIntersection:
    """Where two moving lines meet.

    Attributes
    ----------
    point : PointMotion
        The intersection point (m, m/s, m/s²).
    along_first, along_second : Motion
        Signed distances s₁, s₂ of the intersection from the points Q₁, Q₂ along the two lines, in the
        directions of ``ê₁``, ``ê₂`` (m, m/s, m/s²): ``Q₁ + s₁ ê₁ = Q₂ + s₂ ê₂``.
    singular : ndarray of bool
        True where the lines are parallel (no intersection, or a whole line of them).
    """

    point: PointMotion
    along_first: Motion
    along_second: Motion
    singular: np.ndarray


def line_intersection(first_point: PointMotion | complex, first_angle: AngleMotion | float,
                      second_point: PointMotion | complex, second_angle: AngleMotion | float,
                      angles: ArrayLike | None = None) -> LineIntersection:
    """Intersection of two moving lines, with its velocity and acceleration.

    Parameters
    ----------
    first_point, second_point : PointMotion or complex
        A point Q₁, Q₂ on each line (m), moving or fixed.
    first_angle, second_angle : AngleMotion or float
        The directions β₁, β₂ of the lines (rad), moving or fixed.
    angles : array_like, optional
        Crank angles (rad), only to name positions in an :class:`AssemblyError`.

    Returns
    -------
    LineIntersection
        Where the lines are parallel to within round-off (|sin(β₂ − β₁)| ≤ 1e-12) there is no single
        intersection: those positions are flagged ``singular`` and their values are ``nan``.

    Notes
    -----
    With the cross product ``r₁ × r₂ = Im(r̄₁ r₂)`` (chapter 5), taking the cross product of
    ``Q₁ + s₁ ê₁ = Q₂ + s₂ ê₂`` with ``ê₂`` and with ``ê₁`` gives

    ``s₁ = ((Q₂ − Q₁) × ê₂) / (ê₁ × ê₂)``,  ``s₂ = ((Q₂ − Q₁) × ê₁) / (ê₁ × ê₂)``,  ``ê₁ × ê₂ = sin(β₂ − β₁)``.

    The numerators and the denominator are differentiated by Leibniz's rule and the quotients by
    the quotient rule; the point ``Q₁ + s₁ ê₁`` likewise. The lecture's slide "slider on a coupler with a
    fixed guide" writes the same point with slopes, ``x_L = (n − m)/(tg θ − tg η)``, which fails
    for a vertical line; this form has no such exception.
    """
    like = _like(first_point, first_angle, second_point, second_angle)
    order = min(_common_order(first_point, first_angle), _common_order(second_point, second_angle))
    q1, q2 = _as_point(first_point, like, order), _as_point(second_point, like, order)
    a1, a2 = _as_angle(first_angle, like, order), _as_angle(second_angle, like, order)
    order = min(order, _order(q1, q2, a1, a2))
    e1, e2 = _unit(a1, order), _unit(a2, order)
    d = tuple(None if x is None or y is None else y - x for x, y in zip(q1.derivatives(), q2.derivatives()))
    d_bar = _conj(d)
    cross = _part(_product(_conj(e1), e2, order), np.imag)
    parallel = np.abs(cross[0]) <= _PARALLEL
    with np.errstate(divide="ignore", invalid="ignore"):
        s1 = _quotient(_part(_product(d_bar, e2, order), np.imag), cross, order)
        s2 = _quotient(_part(_product(d_bar, e1, order), np.imag), cross, order)
        offset = _product(s1, e1, order)
    point = PointMotion(*(None if x is None else q + x for q, x in zip(q1.derivatives(), offset)))
    point, first, second = point.truncated(order), Motion(*s1).truncated(order), Motion(*s2).truncated(order)
    if np.any(parallel):
        # no single intersection (or a whole line of them): undefined, and flagged, not an error that
        # would lose every other position of the table
        point, first, second = (_undefined_where(m, parallel) for m in (point, first, second))
    return LineIntersection(point, first, second, parallel)


def _undefined_where(motion, mask: np.ndarray):
    """The motion with every value and derivative set to nan at the positions of ``mask``."""
    return type(motion)(*(None if x is None else np.where(mask, np.nan, x) for x in motion.derivatives()))


@dataclass(frozen=True)
class PointLineDistance:
    """A point M and a line through Q with direction θ: distance, foot of the perpendicular.

    Attributes
    ----------
    distance : Motion
        The signed distance h of M from the line (m), positive when M is on the left of the line
        (the side of ``i·ê``), with ``h_t`` (m/s) and ``h_tt`` (m/s²).
    along : Motion
        The signed position u of the foot N along the line from Q (m, m/s, m/s²).
    foot : PointMotion
        The foot N of the perpendicular from M, ``N = Q + u ê``.
    """

    distance: Motion
    along: Motion
    foot: PointMotion


def distance_to_line(point: PointMotion | complex, through: PointMotion | complex,
                     angle: AngleMotion | float) -> PointLineDistance:
    """Signed distance from a moving point to a moving line, with derivatives.

    Parameters
    ----------
    point : PointMotion or complex
        The point M (m).
    through : PointMotion or complex
        A point Q of the line (m).
    angle : AngleMotion or float
        The line's direction θ (rad).

    Returns
    -------
    PointLineDistance

    Notes
    -----
    In the line's own frame, ``ζ = ê* (M − Q) = u + i h`` (ê* the conjugate of ê). With ``z = M − Q`` and
    ``ê*_t = −iθ_t ê*``:

    * ``ζ_t = ê* (z_t − iθ_t z)``,
    * ``ζ_tt = ê* (z_tt − 2iθ_t z_t − (iθ_tt + θ_t²) z)``,

    and ``u = Re ζ``, ``h = Im ζ`` with the real and imaginary parts of the derivatives. For a fixed
    line ``A_ℓ x + B_ℓ y + C_ℓ = 0`` this is ``h = ±(A_ℓ x_M + B_ℓ y_M + C_ℓ)/√(A_ℓ² + B_ℓ²)``
    of the lecture, and then ``h_t = ±(A_ℓ (x_t)_M + B_ℓ (y_t)_M)/√(A_ℓ² + B_ℓ²)``,
    ``h_tt = ±(A_ℓ (x_tt)_M + B_ℓ (y_tt)_M)/√(A_ℓ² + B_ℓ²)``: the constant C_ℓ does not survive differentiation (the lecture keeps it; see the errata).
    """
    like = _like(point, through, angle)
    order = _common_order(point, through)
    order = min(order, _common_order(through, angle), _common_order(point, angle))
    p, q, a = _as_point(point, like, order), _as_point(through, like, order), _as_angle(angle, like, order)
    order = min(order, _order(p, q, a))
    r = tuple(None if x is None or y is None else x - y for x, y in zip(p.derivatives(), q.derivatives()))
    e_bar = np.exp(-1j * a.value)
    w = e_bar * r[0]
    w_t = w_tt = None
    if order >= 1:
        w_t = e_bar * (r[1] - 1j * a.omega * r[0])
    if order >= 2:
        w_tt = e_bar * (r[2] - 2j * a.omega * r[1] - (1j * a.alpha + a.omega**2) * r[0])
    h = Motion(w.imag, None if w_t is None else w_t.imag, None if w_tt is None else w_tt.imag)
    u = Motion(w.real, None if w_t is None else w_t.real, None if w_tt is None else w_tt.real)
    offset = _product(u.derivatives(), _unit(a, order), order)
    foot = PointMotion(*(None if x is None else y + x for y, x in zip(q.derivatives(), offset)))
    return PointLineDistance(h, u, foot.truncated(order))


@dataclass(frozen=True)
class CircleOnLine:
    """A point at a fixed distance from a centre, held on a moving line.

    Attributes
    ----------
    point : PointMotion
        The point D (m, m/s, m/s²).
    along : Motion
        Its signed position s along the line from the line's point Q (m, m/s, m/s²); for a
        slotted lever, the current length from the pivot, the lecture's L_tek.
    distance : PointLineDistance
        The centre's distance h from the line and the foot N of the perpendicular.
    singular : ndarray of bool
        True where the radius to D is perpendicular to the line (|h| = radius): the derivatives
        are unbounded there.
    """

    point: PointMotion
    along: Motion
    distance: PointLineDistance
    singular: np.ndarray


def circle_on_line(centre: PointMotion | complex, radius: float, through: PointMotion | complex,
                   angle: AngleMotion | float, branch: int = 1, angles: ArrayLike | None = None) -> CircleOnLine:
    """Where a circle about a (moving) centre meets a moving line: a rocker's pin in a slot.

    Parameters
    ----------
    centre : PointMotion or complex
        The centre of the circle (m), e.g. the fixed pivot O₂ of a rocker.
    radius : float
        The radius (m), e.g. the rocker's length O₂D.
    through : PointMotion or complex
        A point Q of the line (m), e.g. the lever's pivot C (the lecture's O₁).
    angle : AngleMotion or float
        The line's direction θ (rad), e.g. the lever's angle ξ.
    branch : int
        +1: D is ahead of the foot N of the perpendicular from the centre (in the direction
        ``ê``); −1: behind it.
    angles : array_like, optional
        Crank angles (rad), only to name positions in an :class:`AssemblyError`.

    Returns
    -------
    CircleOnLine

    Notes
    -----
    With h and u from :func:`distance_to_line`, the radius L₄ (§5.8), ``c_D = √((L₄ − h)(L₄ + h))`` and
    σ the branch: ``s = u + σ·c_D``, ``c_D,t = −h h_t / c_D``, ``c_D,tt = −(h_t² + h h_tt + c_D,t²)/c_D``,
    ``D = Q + s ê``
    (lecture slides "two rockers with a slotted pair").
    """
    radius = require_length("radius", radius)
    branch = require_branch(branch)
    foot = distance_to_line(centre, through, angle)
    h, u = foot.distance, foot.along
    order = min(h.order, u.order)
    reach = (radius - h.value) * (radius + h.value)
    slack = 8.0 * np.finfo(float).eps * radius * (radius + np.abs(h.value) + np.abs(u.value))  # round-off of w²
    unreachable = reach < -slack
    if np.any(unreachable):
        where = _where(angles, unreachable)
        raise AssemblyError(f"the circle of radius {radius:g} m does not reach the line: its centre is up to "
                            f"{float(np.max(np.abs(h.value))):.6g} m from it", angles=where)
    singular = reach <= 100.0 * slack   # w within round-off of 0: a singular position, rates unbounded
    w = np.where(singular, 0.0, np.sqrt(np.maximum(reach, 0.0)))
    with np.errstate(divide="ignore", invalid="ignore"):
        w_t: Any = -h.value * h.velocity / w if order >= 1 else None
        w_tt = -(h.velocity**2 + h.value * h.acceleration + w_t**2) / w if order >= 2 else None
    along = u + Motion(branch * w, None if w_t is None else branch * w_t,
                       None if w_tt is None else branch * w_tt).truncated(order)
    like = np.asarray(h.value)
    q = _as_point(through, like, order)
    a = _as_angle(angle, like, order)
    offset = _product(along.derivatives(), _unit(a, order), order)
    point = PointMotion(*(None if x is None else y + x for y, x in zip(q.derivatives(), offset)))
    return CircleOnLine(point.truncated(order), along.truncated(order), foot, singular)


def angle_from_distance(distance: Motion, length: float) -> AngleMotion:
    """The angle η of a link of length L whose end is h from a line: ``sin η = h/L``.

    Parameters
    ----------
    distance : Motion
        The signed distance h (m) with ``h_t``, ``h_tt``, e.g. of the crank pin from the guide
        of a crank-slider.
    length : float
        The link's length L (m), e.g. the coupler L₂ (the lecture's L₅).

    Returns
    -------
    AngleMotion
        η in [−π/2, π/2] with ``η_t = h_t/(L cos η)`` and
        ``η_tt = (h_tt/L + η_t² sin η)/cos η``.

    Notes
    -----
    Lecture slide "angle between the coupler and the fixed direction of the slider". Where
    ``|h| = L`` (cos η = 0) the derivatives are unbounded. ``η = atan2(h, √((L − h)(L + h)))``
    keeps full accuracy near ±π/2, where ``arcsin(h/L)`` would not.
    """
    length = require_length("length", length)
    h = distance.value
    reach = (length - h) * (length + h)
    if np.any(reach < -8.0 * np.finfo(float).eps * length**2):
        raise AssemblyError(f"the link of length {length:g} m cannot reach the line: the distance is up to "
                            f"{float(np.max(np.abs(h))):.6g} m")
    cos_mu = np.sqrt(np.maximum(reach, 0.0)) / length
    mu = np.arctan2(h, length * cos_mu)
    if distance.order == 0:
        return AngleMotion(mu)
    with np.errstate(divide="ignore", invalid="ignore"):
        mu_t = distance.velocity / (length * cos_mu)
        if distance.order == 1:
            return AngleMotion(mu, mu_t)
        mu_tt = (distance.acceleration / length + mu_t**2 * np.sin(mu)) / cos_mu
    return AngleMotion(mu, mu_t, mu_tt)
