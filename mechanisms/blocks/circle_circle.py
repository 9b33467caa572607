"""Two links meeting at a hinge: the intersection of two circles (the circle-circle dyad).

Two joints ``p`` and ``q`` move in a known way; a link of length ``length_p`` hangs from ``p``
and a link of length ``length_q`` from ``q``; the two links meet at the hinge J. J is an
intersection of the circle of radius ``length_p`` about ``p`` and the circle of radius
``length_q`` about ``q``. There are two intersections, mirror images in the line through
``p`` and ``q``; the ``branch`` picks one of them geometrically:

* ``branch = +1``: J lies to the left of the directed line p → q (counter-clockwise side);
* ``branch = -1``: J lies to the right of it.

In the four-bar (chapter 4) J is the coupler-rocker joint B, ``p`` the crank pin A and ``q`` the
rocker pivot C.
"""

from __future__ import annotations

from dataclasses import dataclass

from typing import Any, Callable

import numpy as np
from numpy.typing import ArrayLike

from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import LENGTH_MAX, LENGTH_MIN, require_branch, require_finite_array, require_length
from ..core.angles import angle_of, constant
from ..core.motion import AngleMotion, PointMotion

__all__ = ["Hinge", "DeferredAngle", "hinge", "hinge_plain", "SINGULAR_TOLERANCE", "ASSEMBLY_TOLERANCE"]

ASSEMBLY_TOLERANCE = 1e-12
"""Relative overlap of the circles accepted as touching (round-off), as a fraction of |pJ| + |qJ|."""

SINGULAR_TOLERANCE = 1e-6
"""A hinge is marked singular where |sin| of the angle between its links is below this.

At a limit of assembly the round-off of the lengths leaves |sin| of order √ε ≈ 1e-8, and rates
computed from it would be huge finite numbers; 1e-6 is reached only within about 1e-12 rad of a
limit, where the rates are indeed beyond any use."""


class DeferredAngle(AngleMotion):
    """A link's angle at order 0 computed only when first read: ``arg`` of its arm r = J − p.

    It is an :class:`~mechanisms.core.motion.AngleMotion` whose ``value`` is computed (once) when first read,
    so that a family solved for its positions does not pay for the arctangents of angles nobody reads. What
    makes a new motion from it (indexing, arithmetic) works on the computed angle.
    """

    def __init__(self, arm: np.ndarray, minus: Any = None):   # a frozen dataclass: its fields set directly
        object.__setattr__(self, "arm", arm)            # the arm r, or the point J of which r = J − minus
        object.__setattr__(self, "minus", minus)
        object.__setattr__(self, "velocity", None)
        object.__setattr__(self, "acceleration", None)

    @property
    def value(self) -> np.ndarray:
        """The angle (rad), computed on first reading."""
        if "_angle" not in self.__dict__:
            arm, minus = self.__dict__["arm"], self.__dict__["minus"]
            object.__setattr__(self, "_angle", angle_of(arm if minus is None else np.subtract(arm, minus)))
        return self.__dict__["_angle"]

    def resolved(self) -> AngleMotion:
        """The same angle as a plain :class:`~mechanisms.core.motion.AngleMotion`."""
        return AngleMotion(self.value)

    def __getitem__(self, index: Any) -> AngleMotion:      # type: ignore[override]
        return self.resolved()[index]

    def truncated(self, order: int) -> AngleMotion:        # type: ignore[override]
        return self.resolved().truncated(order)

    def _combine(self, other: Any, sign: float) -> AngleMotion:   # type: ignore[override]
        return self.resolved()._combine(other, sign)

    def __mul__(self, factor: float) -> AngleMotion:       # type: ignore[override]
        return self.resolved() * factor

    def __rmul__(self, factor: float) -> AngleMotion:      # type: ignore[override]
        return self.resolved() * factor


@dataclass(frozen=True)
class Hinge:
    """The solved hinge J of two links, with the angles of both links.

    Attributes
    ----------
    point : PointMotion
        J with its velocity and acceleration (m, m/s, m/s²).
    angle_p : AngleMotion or DeferredAngle
        Angle of the link p → J (rad) with ω, ε (``omega``, ``alpha``); at order 0, solved with
        ``deferred_angles=True``, a :class:`DeferredAngle` (computed when first read).
    angle_q : AngleMotion or DeferredAngle
        Angle of the link q → J (rad) with ω, ε (``omega``, ``alpha``), likewise.
    singular : ndarray of bool
        True where p, q and J are collinear: the two links are in line, the velocities of J
        are unbounded and are set to ``nan``; also where p and q coincide (possible for
        |pJ| = |qJ| only), where J itself is undefined (anywhere on a circle) and is ``nan``.
    assembled : ndarray of bool or None
        Only when solved with ``lenient=True``: True where the circles meet. Where they do not,
        J, both angles and their rates are ``nan`` and ``singular`` is False. ``None`` otherwise
        (a hinge solved strictly assembles everywhere, or raises).
    """

    point: PointMotion
    angle_p: AngleMotion
    angle_q: AngleMotion
    singular: np.ndarray
    assembled: np.ndarray | None = None


def _cramer(conjugate: np.ndarray, rhs: np.ndarray, inverse_det: np.ndarray) -> np.ndarray:
    """``(u · rhs)/det`` of Cramer's rule: the scalar product Re(conj(u)·rhs) of plane vectors given
    as complex numbers (with ``conjugate`` = conj(u)), times ``inverse_det``."""
    return np.multiply(conjugate, rhs).real * inverse_det


def _metres(value) -> str:
    """A length for a message: ``0.5 m`` for one number, ``up to 0.5 m`` for an array of them."""
    return f"{float(value):g} m" if np.ndim(value) == 0 else f"up to {float(np.max(value)):g} m"


def _assembly_failure(distance, shape, total, difference, tolerance, angles) -> None:
    """Raise the :class:`AssemblyError` of :func:`hinge`, naming the positions that fail."""
    where = None if angles is None else np.broadcast_to(np.asarray(angles, dtype=float), shape)
    far = np.broadcast_to(total - distance < -tolerance, shape)
    near = np.broadcast_to(distance - difference < -tolerance, shape)
    if far.any():
        reason = ("the two links cannot reach each other (joints farther apart than the sum of the link "
                  f"lengths {_metres(total)})")
    else:
        reason = ("one circle lies inside the other (joints closer than the difference of the link "
                  f"lengths {_metres(difference)})")
    if far.any() and near.any():
        reason += (" and, elsewhere, one circle lies inside the other (joints closer than "
                   f"{_metres(difference)})")
    raise AssemblyError(reason, None if where is None else where[far | near])


def _lengths(name: str, value: object) -> float | np.ndarray:
    """A link length (one number, :func:`~mechanisms.core.validate.require_length`) or an array of them
    (a family of linkages), each in [LENGTH_MIN, LENGTH_MAX] m; or raise naming ``name``."""
    if np.ndim(value) == 0:  # type: ignore[arg-type]
        return require_length(name, value)
    array = require_finite_array(name, value, "m")  # type: ignore[arg-type]
    bad = (array < LENGTH_MIN) | (array > LENGTH_MAX)
    if bad.any():
        raise InvalidParameterError(name, array[bad][:3].tolist(),
                                    f"lengths from {LENGTH_MIN:.3g} m to {LENGTH_MAX:.3g} m")
    return array


def _sides(branch: object) -> Any:
    """The branch as a float ±1, or an array of them (one per position or per member of a family); or raise
    naming ``branch``."""
    branch_array = np.asarray(branch)
    if branch_array.ndim == 0:
        return float(require_branch(branch))
    valid = (branch_array == 1) | (branch_array == -1)
    if not valid.all():
        require_branch(branch_array[~valid].ravel()[0].item())
    return branch_array.astype(float)


def _one_position(solve: Callable[..., Hinge], p: PointMotion, q: PointMotion, length_p: float, length_q: float,
                  branch: int | np.ndarray, angles: ArrayLike | None, lenient: bool) -> Hinge:
    """One position: solved as an array of one, returned as numbers."""
    one = solve(p[np.newaxis], q[np.newaxis], length_p, length_q, branch, angles, lenient)   # angles computed now
    return Hinge(one.point[0], one.angle_p[0], one.angle_q[0], one.singular[0],
                 None if one.assembled is None else one.assembled[0])


def _checked(p: PointMotion, q: PointMotion, length_p: Any, length_q: Any, branch: int | np.ndarray,
             angles: ArrayLike | None, lenient: bool = False) -> tuple[Any, Any, Any, np.ndarray, np.ndarray,
                                                                       np.ndarray, np.ndarray, np.ndarray | None]:
    """The hinge's inputs checked: the lengths, the side(s) as floats, ``d = q − p``, ``D = |d|``, the margins
    ``far = L_p + L_q − D`` and ``near = D − |L_p − L_q|`` (both ≥ 0 where the circles meet; Heron's factors,
    computed once) and, when ``lenient``, the mask of the positions where the circles meet (else None).

    ``d`` has the shape of the positions broadcast with the lengths and sides (a family of linkages: one
    row per member). Raises :class:`AssemblyError` naming the crank angles where the circles do not meet,
    unless ``lenient``.
    """
    length_p = _lengths("length_p", length_p)
    length_q = _lengths("length_q", length_q)
    side = _sides(branch)
    d = q.value - p.value
    shape = np.broadcast_shapes(np.shape(d), np.shape(length_p), np.shape(length_q), np.shape(side))
    if shape != np.shape(d):
        d = np.array(np.broadcast_to(d, shape))         # a family: one row of positions per member
    distance = np.abs(d)
    total = length_p + length_q
    difference = abs(length_p - length_q)
    tolerance = ASSEMBLY_TOLERANCE * total
    far = np.subtract(total, distance)
    near = np.subtract(distance, difference)
    if lenient:
        # the smallest margins of each row first (no array of flags): where every position assembles, as in
        # most families, the mask is one number broadcast; nan (a position left undefined) fails the test
        if far.ndim and far.size and (np.minimum.reduce(far, axis=-1, keepdims=True) >= -tolerance).all() and \
                (np.minimum.reduce(near, axis=-1, keepdims=True) >= -tolerance).all():
            return length_p, length_q, side, d, distance, far, near, constant(True, far.shape)
        assembled = far >= -tolerance
        assembled &= near >= -tolerance
        return length_p, length_q, side, d, distance, far, near, assembled
    # the smallest margins decide whether any position fails; the masks are made only then. fmin skips the
    # positions that an earlier singular position left undefined (nan), so it cannot hide a failure.
    if np.ndim(total):      # a family: each member's own limits
        failing = bool(((near < -tolerance) | (far < -tolerance)).any())
    else:
        failing = bool(distance.size) and (np.fmin.reduce(near, axis=None) < -tolerance
                                           or np.fmin.reduce(far, axis=None) < -tolerance)
    if failing:
        _assembly_failure(distance, d.shape, total, difference, tolerance, angles)
    return length_p, length_q, side, d, distance, far, near, None


def _unassembled(solved: Hinge, assembled: np.ndarray | None) -> Hinge:
    """A leniently solved hinge: ``nan`` wherever the circles do not meet, and the mask kept."""
    if assembled is None or (assembled.size and not any(assembled.strides) and assembled.flat[0]):
        return solved if assembled is None else Hinge(solved.point, solved.angle_p, solved.angle_q, solved.singular,
                                                      assembled)      # one True broadcast: all assemble
    missing = ~assembled
    if missing.any():
        for motion in (solved.point, solved.angle_p, solved.angle_q):
            # a deferred angle is marked in its arm, from which it is computed
            for array in ((motion.__dict__["arm"],) if isinstance(motion, DeferredAngle) else motion.derivatives()):
                if array is not None:
                    np.copyto(array, np.nan, where=missing)
        solved.singular[missing] = False
    return Hinge(solved.point, solved.angle_p, solved.angle_q, solved.singular, assembled)


def hinge_plain(p: PointMotion, q: PointMotion, length_p: float | np.ndarray, length_q: float | np.ndarray,
                branch: int | np.ndarray = 1, angles: ArrayLike | None = None, lenient: bool = False,
                deferred_angles: bool = False) -> Hinge:
    """:func:`hinge` written as the book writes it: the same formulas, plain numpy, no speed tricks.

    The book shows this form; :func:`hinge`, which the mechanisms use, computes the same numbers
    in place (fewer temporaries stay in the processor's cache, chapter 9's appendix) and the tests
    compare the two. Parameters, results and errors are those of :func:`hinge`.
    """
    return _solved(hinge_plain, _hinge_plain, p, q, length_p, length_q, branch, angles, lenient, deferred_angles)


def _solved(solve: Callable[..., Hinge], formulas: Callable[..., Hinge], p: PointMotion, q: PointMotion,
            length_p: Any, length_q: Any, branch: int | np.ndarray, angles: ArrayLike | None, lenient: bool,
            deferred_angles: bool) -> Hinge:
    """What :func:`hinge` and :func:`hinge_plain` share: one position solved as an array of one, the inputs
    checked, the ``formulas`` applied, and (``lenient``) the positions that do not assemble marked."""
    if np.ndim(p.value) == 0 and np.ndim(q.value) == 0 and np.ndim(length_p) == 0 and np.ndim(length_q) == 0:
        return _one_position(solve, p, q, length_p, length_q, branch, angles, lenient)
    length_p, length_q, side, d, distance, far, near, assembled = _checked(p, q, length_p, length_q, branch, angles,
                                                                           lenient)
    return _unassembled(formulas(p, q, length_p, length_q, side, d, distance, far, near, deferred_angles), assembled)


def _hinge_plain(p: PointMotion, q: PointMotion, length_p: Any, length_q: Any, side: Any, d: np.ndarray,
                 distance: np.ndarray, far: np.ndarray, near: np.ndarray, deferred_angles: bool = False) -> Hinge:
    """The formulas of :func:`hinge_plain`, on checked inputs (``far = L_p + L_q − D``, ``near = D − |L_p − L_q|``)."""
    total, difference = length_p + length_q, abs(length_p - length_q)
    # twice = 2·h·D by Heron, the small factors near a limit clipped at zero against round-off
    twice = (np.sqrt(np.maximum(far, 0.0) * (total + distance))
             * np.sqrt(np.maximum(near, 0.0) * (distance + difference)))
    singular = twice <= 2.0 * SINGULAR_TOLERANCE * length_p * length_q
    # J = p + (m + i·branch·h)·d/D: m/D = (1 + (L_p² − L_q²)/D²)/2, h/D = h·D/D²
    # (where the known joints coincide, D = 0, J is anywhere on a circle: nan, and singular)
    with np.errstate(divide="ignore", invalid="ignore"):
        foot = 0.5 * (1.0 + (length_p - length_q) * (length_p + length_q) / distance**2)
        height = 0.5 * side * twice / distance**2
        arm_p = (foot + 1j * height) * d
    point = p.value + arm_p
    order = min(p.order, q.order)
    if order == 0 and deferred_angles:
        return Hinge(PointMotion(point), DeferredAngle(arm_p), DeferredAngle(point, q.value), singular)
    arm_q = point - q.value
    theta_p, theta_q = np.angle(arm_p), np.angle(arm_q)
    if order == 0:
        return Hinge(PointMotion(point), AngleMotion(theta_p), AngleMotion(theta_q), singular)
    det = 0.5 * side * twice                             # r_p × r_q = branch·h·D

    def dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return (np.conj(u) * v).real

    with np.errstate(divide="ignore", invalid="ignore"):
        # iω_p r_p − iω_q r_q = v_q − v_p, by Cramer's rule
        rhs = q.velocity - p.velocity
        omega_p = np.where(singular, np.nan, dot(arm_q, rhs) / det)
        omega_q = np.where(singular, np.nan, dot(arm_p, rhs) / det)
        velocity = p.velocity + 1j * omega_p * arm_p
        if order == 1:
            return Hinge(PointMotion(point, velocity), AngleMotion(theta_p, omega_p),
                         AngleMotion(theta_q, omega_q), singular)
        # iα_p r_p − iα_q r_q = a_q − a_p + ω_p² r_p − ω_q² r_q
        rhs = q.acceleration - p.acceleration + omega_p**2 * arm_p - omega_q**2 * arm_q
        alpha_p, alpha_q = dot(arm_q, rhs) / det, dot(arm_p, rhs) / det
        acceleration = p.acceleration + (1j * alpha_p - omega_p**2) * arm_p
    return Hinge(PointMotion(point, velocity, acceleration), AngleMotion(theta_p, omega_p, alpha_p),
                 AngleMotion(theta_q, omega_q, alpha_q), singular)


def hinge(p: PointMotion, q: PointMotion, length_p: float | np.ndarray, length_q: float | np.ndarray,
          branch: int | np.ndarray = 1, angles: ArrayLike | None = None, lenient: bool = False,
          deferred_angles: bool = False) -> Hinge:
    """Solve two links meeting at a hinge: J at the lengths |pJ| = ``length_p`` and |qJ| = ``length_q``.

    Parameters
    ----------
    p, q : PointMotion
        The known joints (m, m/s, m/s²), arrays over the crank positions.
    length_p, length_q : float or ndarray
        Lengths of the links p → J and q → J (m). An array (a family of linkages, e.g. of shape
        (G, 1) against positions of shape (G, N) or (N,)) broadcasts against the positions.
    branch : int or array of int
        +1: J to the left of the directed line p → q; -1: to the right. An array (one sign per
        position, or per member of a family) lets a mechanism hold an assembly mode through a
        change point.
    angles : array_like, optional
        The crank angles φ (rad) of the positions, only to name them in an
        :class:`~mechanisms.errors.AssemblyError`.
    lenient : bool
        False (default): raise where the circles do not meet. True: mark those positions in
        :attr:`Hinge.assembled` and give ``nan`` there (a family in which some members, or some
        positions, do not assemble).
    deferred_angles : bool
        True: at order 0, the links' angles are :class:`DeferredAngle` objects, computed when called (a
        family's positions need no arctangents). False (default): they are computed now.

    Returns
    -------
    Hinge
        J and the angles of both links, up to order ``min(p.order, q.order)``, of the shape of the
        positions broadcast with the lengths and ``branch``.

    Raises
    ------
    AssemblyError
        Unless ``lenient``, where the circles do not meet: the joints are farther apart than
        |pJ| + |qJ|, or one circle lies inside the other (distance below ||pJ| − |qJ||).

    Notes
    -----
    With ``d = q − p``, ``D = |d|``, J is found in the frame of the line p → q:
    ``J = p + (m + i·branch·h)·d/D`` with the foot of the perpendicular
    ``m = (D² + |pJ|² − |qJ|²)/(2D)`` and the height
    ``h = √((|pJ| + |qJ| + D)(|pJ| + |qJ| − D))·√((D − ||pJ| − |qJ||)(D + ||pJ| − |qJ||))/(2D)`` (Heron), a
    product in which the two small factors near a limit are computed directly, and whose two roots
    keep it free of overflow for any lengths between 1e-150 m and 1e150 m; no ``arccos``.

    Velocities: differentiating ``p + r_p = q + r_q`` (r_p = J − p, r_q = J − q) in Euler form,
    ``iω_p r_p − iω_q r_q = v_q − v_p``; accelerations:
    ``iε_p r_p − iε_q r_q = a_q − a_p + ω_p² r_p − ω_q² r_q``. Both are solved by Cramer's rule
    with the determinant ``r_p × r_q`` = |pJ| |qJ| sin(θ_q − θ_p), zero where the links are in line
    (chapter 4; the lecture's crank-rocker is the case p = A, q = C).
    """
    return _solved(hinge, _hinge_in_place, p, q, length_p, length_q, branch, angles, lenient, deferred_angles)


def _hinge_in_place(p: PointMotion, q: PointMotion, length_p: Any, length_q: Any, side: Any, d: np.ndarray,
                    distance: np.ndarray, far: np.ndarray, near: np.ndarray, deferred_angles: bool = False) -> Hinge:
    """The formulas of :func:`hinge`, on checked inputs (``far = L_p + L_q − D``, ``near = D − |L_p − L_q|``, arrays
    of its own that it overwrites), computed in place."""
    order = min(p.order, q.order)
    total, difference = length_p + length_q, abs(length_p - length_q)
    # Heron's product h·D, its two small factors near a limit computed directly and clipped at
    # zero against round-off (the limits were checked above); two square roots of products of
    # two lengths each keep it in range for lengths from 1e-150 m to 1e150 m. twice = 2·h·D.
    # The arrays are computed in place: fewer temporaries stay in the processor's cache (the plain
    # form of the same formulas is hinge_plain; chapter 9's appendix measures what this buys).
    np.maximum(far, 0.0, out=far)
    scratch = np.add(distance, total)
    far *= scratch
    np.maximum(near, 0.0, out=near)
    near *= np.add(distance, difference, out=scratch)
    twice = np.sqrt(far, out=far)
    twice *= np.sqrt(near, out=near)
    # |sin| of the angle between the links is h·D/(L_p·L_q); the mask uses that ratio
    singular = twice <= 2.0 * SINGULAR_TOLERANCE * length_p * length_q
    # r_p = J − p = (m + i·branch·h)·d/D with m/D = (1 + (L_p² − L_q²)/D²)/2 and h/D = h·D/D²; where the
    # known joints coincide (D = 0, possible only for L_p = L_q) J is anywhere on a circle: nan, and singular
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse_square = np.divide(1.0, distance, out=near)
        inverse_square *= inverse_square
        arm_p = np.empty(d.shape, dtype=complex)
        np.multiply(inverse_square, 0.5 * (length_p - length_q) * (length_p + length_q), out=arm_p.real)
        arm_p.real += 0.5
        np.multiply(twice, inverse_square, out=arm_p.imag)
        arm_p.imag *= 0.5 * side
        arm_p *= d
    point = p.value + arm_p
    if order == 0 and deferred_angles:                 # r_q = J − q too is computed only if its angle is read
        return Hinge(PointMotion(point), DeferredAngle(arm_p), DeferredAngle(point, q.value), singular)
    arm_q = np.subtract(point, q.value, out=d)          # r_q = J − q (d is not needed any more)
    theta_p, theta_q = angle_of(arm_p), angle_of(arm_q)
    if order == 0:
        return Hinge(PointMotion(point), AngleMotion(theta_p), AngleMotion(theta_q), singular)
    any_singular = singular.any()
    with np.errstate(divide="ignore", invalid="ignore"):
        # Solve i·x·r_p − i·y·r_q = rhs for real x, y by Cramer's rule: dotting with r_q removes y,
        # with r_p removes x, so x = (r_q · rhs)/(r_p × r_q), y = (r_p · rhs)/(r_p × r_q). The
        # determinant r_p × r_q is branch·h·D of the geometry above, free of cancellation.
        inverse_det = np.divide(2.0 * side, twice, out=twice)
        conjugate_p, conjugate_q = np.conjugate(arm_p), np.conjugate(arm_q)
        rhs = q.velocity - p.velocity
        omega_p, omega_q = _cramer(conjugate_q, rhs, inverse_det), _cramer(conjugate_p, rhs, inverse_det)
        if any_singular:
            np.copyto(omega_p, np.nan, where=singular)
            np.copyto(omega_q, np.nan, where=singular)
        velocity = 1j * omega_p
        velocity *= arm_p
        velocity += p.velocity                           # v_J = v_p + iω_p r_p
        if order == 1:
            return Hinge(PointMotion(point, velocity), AngleMotion(theta_p, omega_p),
                         AngleMotion(theta_q, omega_q), singular)
        square_p, square_q = omega_p * omega_p, omega_q * omega_q
        rhs = square_p * arm_p
        rhs -= square_q * arm_q
        rhs += q.acceleration
        rhs -= p.acceleration
        alpha_p, alpha_q = _cramer(conjugate_q, rhs, inverse_det), _cramer(conjugate_p, rhs, inverse_det)
        turn = np.empty(d.shape, dtype=complex)          # iα_p − ω_p²
        np.negative(square_p, out=turn.real)
        turn.imag = alpha_p
        acceleration = np.multiply(turn, arm_p, out=turn)
        acceleration += p.acceleration                   # a_J = a_p + (iα_p − ω_p²) r_p
    return Hinge(PointMotion(point, velocity, acceleration), AngleMotion(theta_p, omega_p, alpha_p),
                 AngleMotion(theta_q, omega_q, alpha_q), singular)
