"""A block on a moving pin, sliding along a lever that turns about a pivot: the slotted-lever pair.

The crank pin A carries a block (the "stone" of the slotted link); the block slides in the
slot of a lever that turns about the pivot C. The lever's line always passes through C and A, so

    A − C = L·exp(iξ)

where ξ is the lever's angle (from the pivot towards the block) and L the current distance
from the pivot to the block, the lecture's L_tek. Both follow from the vector ``A − C`` alone
(:func:`mechanisms.motion.polar`); there is no branch to choose. The pivot may itself move: that
is the lecture's "guide with a moving axis".

Velocities and accelerations split into the lever's rotation and the sliding along it:

    v_A = v_C + L_t e + iξ_t L e
    a_A = a_C + (L_tt − L ξ_t²) e + i(2 L_t ξ_t + L ξ_tt) e,

where ``e = exp(iξ)``. ``L_t`` is the block's sliding velocity relative to the lever,
``L_tt e`` its relative acceleration, and ``2 ξ_t L_t · ie`` the Coriolis acceleration: the
term that is neither the lever point's acceleration nor the relative one.

When the pin passes exactly through the pivot (a crank whose radius equals the pivot's distance),
``L = 0`` and the direction ``A − C`` is undefined at that instant; :func:`lever_through_pivot`
gives the closed form of that case, in which everything stays finite.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import InvalidParameterError
from ..core.validate import require_length
from ..core.angles import unit_vector_fast, wrap_angle
from ..core.motion import AngleMotion, Motion, PointMotion, polar

__all__ = ["LeverBlock", "lever_block", "lever_through_pivot"]

# A block closer to the pivot than this, relative to the size of the scene, is at the pivot.
_AT_PIVOT = 1e-12


@dataclass(frozen=True)
class LeverBlock:
    """The solution of the slotted-lever pair over the crank positions.

    Attributes
    ----------
    lever_angle : AngleMotion
        The lever's angle ξ (rad), the direction from the pivot C to the block, with ω₃ = ξ_t
        (1/s) and ε₃ = ξ_tt (1/s²).
    distance : Motion
        The distance L from the pivot to the block along the lever (m, the lecture's L_tek), with the sliding
        velocity ``L_t`` (m/s) and the relative acceleration ``L_tt`` (m/s²). Positive, except in
        :func:`lever_through_pivot`, where it is signed.
    coriolis : ndarray of complex or None
        The Coriolis acceleration of the block in its motion relative to the lever,
        ``2 ξ_t L_t · i exp(iξ)`` (m/s²); ``None`` for order 0.
    singular : ndarray of bool
        True where the block is at the pivot (L = 0): the lever's angle and its derivatives are
        undefined there (``nan``).
    """

    lever_angle: AngleMotion
    distance: Motion
    coriolis: np.ndarray | None
    singular: np.ndarray

    @property
    def coriolis_magnitude(self) -> np.ndarray | None:
        """The signed Coriolis acceleration ``a^k = 2 ω₃ L_t`` (m/s²), along the lever's left normal."""
        return None if self.coriolis is None else 2.0 * self.lever_angle.omega * self.distance.velocity


def _coriolis(angle: AngleMotion, distance: Motion) -> np.ndarray | None:
    if angle.order < 1:
        return None
    return (2.0 * angle.omega * distance.velocity) * (1j * unit_vector_fast(angle.value))


def lever_block(pin: PointMotion, pivot: PointMotion | complex = 0j) -> LeverBlock:
    """Solve a block on a pin sliding along a lever that turns about a pivot.

    Parameters
    ----------
    pin : PointMotion
        The pin A that carries the block (m, m/s, m/s²), e.g. the crank pin; its order sets
        the order of the result.
    pivot : PointMotion or complex
        The lever's pivot C (m): a fixed point (a, b) as a complex number ``a + ib``, or a
        moving point for a guide with a moving axis.

    Returns
    -------
    LeverBlock

    Notes
    -----
    From :func:`~mechanisms.motion.polar` of ``d = A − C`` (chapter 5):

    * ``L = |d|``, ``ξ = arg d`` (the lecture's ``tg ψ = (b − y_A)/(a − x_A)`` measures the
      opposite direction, from A to C: ψ = ξ ± π);
    * ``L_t = Re(d̄ d_t)/L``, ``ξ_t = Im(d̄ d_t)/L²``;
    * ``L_tt = (Re(d̄ d_tt) + |d_t|² − L_t²)/L``, ``ξ_tt = (Im(d̄ d_tt) − 2 L L_t ξ_t)/L²``.

    For a crank pin about O and a fixed pivot these reduce to the textbook relations (004,
    5.62–5.69): ``L² = l₁² + l_OC² − 2 l₁ l_OC cos(φ₁ − φ_C)``, ``L_t = −ω₁ l₁ sin(φ₁ − ξ)`` and
    ``ξ_t = ω₁ l₁ cos(φ₁ − ξ)/L``. Where the block is at the pivot these divide by zero: the
    positions are marked ``singular`` and their derivatives are ``nan``.
    """
    if isinstance(pivot, Motion):
        vector = pin - pivot
    else:
        pivot = complex(pivot)
        if not (np.isfinite(pivot.real) and np.isfinite(pivot.imag)):
            raise InvalidParameterError("pivot", pivot, "a finite point a + ib (m)")
        vector = pin - pivot
    vector = PointMotion(*vector.derivatives())
    scale = np.max(np.abs(pin.value), initial=0.0) + np.max(np.abs(pivot.value if isinstance(pivot, Motion)
                                                                   else pivot), initial=0.0)
    singular = np.abs(vector.value) <= _AT_PIVOT * max(scale, 1e-300)
    length, direction = polar(vector)
    if singular.any():
        nan = np.where(singular, np.nan, 1.0)
        direction = AngleMotion(*(None if d is None else d * nan for d in direction.derivatives()))
        length = Motion(length.value, *(None if d is None else d * nan for d in length.derivatives()[1:]))
    return LeverBlock(direction, length, _coriolis(direction, length), singular)


def lever_through_pivot(crank: AngleMotion, radius: float, pivot_angle: float) -> LeverBlock:
    """The slotted lever whose pivot lies on the crank circle: the block passes through the pivot.

    Parameters
    ----------
    crank : AngleMotion
        The crank angle φ with ω₁ = φ_t and ε₁ = φ_tt.
    radius : float
        The crank length L₁ (m), equal to the pivot's distance from the crank's centre O.
    pivot_angle : float
        The direction θ_OC of the pivot C seen from O (rad): ``C = L₁ exp(iθ_OC)``.

    Returns
    -------
    LeverBlock
        The lever angle ξ, continuous through the passage, and the *signed* distance s of the
        block along the lever (negative when the block is on the lever's other arm, beyond the
        pivot); ``singular`` is all False, because nothing is unbounded.

    Notes
    -----
    ``A − C = L₁(exp(iφ) − exp(iθ_OC)) = 2L₁ sin((φ − θ_OC)/2) · exp(i((φ + θ_OC)/2 + π/2))``, so

    * ``ξ = (φ + θ_OC)/2 + π/2``, ``ξ_t = ω₁/2``, ``ξ_tt = ε₁/2`` (the inscribed-angle theorem:
      the lever turns at half the crank's speed, whatever the position);
    * ``s = 2L₁ sin((φ − θ_OC)/2)``, ``s_t = L₁ ω₁ cos((φ − θ_OC)/2)``,
      ``s_tt = L₁ ε₁ cos((φ − θ_OC)/2) − (L₁ ω₁²/2) sin((φ − θ_OC)/2)``.

    At φ = θ_OC (mod 2π) the block is at the pivot: s = 0 but ``s_t = ±L₁ ω₁`` and ω₃ = ω₁/2 are
    finite.
    What is not defined there is the *unsigned* description of the general block: the direction
    from C to A jumps by π, ``|s|`` has a corner (its derivative jumps from −L₁ω₁ to +L₁ω₁) and the
    constraint Jacobian is singular, so neither the general formulas nor Newton's method apply.
    """
    radius = require_length("radius", radius)
    # φ/2 is exact and is reduced modulo 2π first (core.angles.wrap_angle, right to an ulp of π for any φ):
    # (φ ± γ)/2 formed from a crank angle of 1e15 rad would lose its last 0.06 rad to rounding
    half_phi = wrap_angle(0.5 * np.asarray(crank.value, dtype=float))
    half = half_phi - 0.5 * pivot_angle
    xi = half_phi + (0.5 * pivot_angle + 0.5 * np.pi)
    s = 2.0 * radius * np.sin(half)
    singular = np.zeros(np.shape(crank.value), dtype=bool)
    if crank.order == 0:
        return LeverBlock(AngleMotion(xi), Motion(s), None, singular)
    w = crank.omega
    angle = AngleMotion(xi, 0.5 * w, None if crank.order < 2 else 0.5 * crank.alpha)
    s_t = radius * w * np.cos(half)
    if crank.order == 1:
        distance = Motion(s, s_t)
    else:
        distance = Motion(s, s_t, radius * crank.alpha * np.cos(half) - 0.5 * radius * w**2 * np.sin(half))
    return LeverBlock(angle, distance, _coriolis(angle, distance), singular)
