"""Circle–line: a link of known length from a moving joint to a slider on a fixed straight guide.

The rod of the crank-slider (chapter 3), the connecting rod from a slotted lever to the ram of a
shaper (chapter 5) and every "link ending in a slider" of the lecture are this block: the joint
J moves, the rod J→B has a fixed length, and B is held on a fixed line. B is where the circle of
radius ``rod`` about J meets the line; of the two intersections, ``branch`` picks one.

Geometry, in the guide's own frame (unit vector ``ê = exp(iβ)`` along the guide, β its direction, ``i·ê`` to its
left, origin at the point ``P`` the guide passes through)::

    u   = Re(ê* (J − P))           position of the foot of the perpendicular from J
    h_J = Im(ê* (J − P))           signed distance of J from the guide (left positive; h_A of ch. 3)
    c_B = √((rod − h_J)(rod + h_J)) half-chord: distance from the foot to B
    s   = u + σ · c_B              position of B along the guide (σ = ``branch``)
    B   = P + s ê

The product ``(rod − h_J)(rod + h_J)`` instead of ``rod² − h_J²`` keeps full relative accuracy when
|h_J| is close to ``rod`` (no cancellation of two large squares).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_branch, require_finite, require_length
from .circle_circle import _lengths, _metres, _sides
from ..core.motion import AngleMotion, Motion, PointMotion

__all__ = ["SliderOnLine", "slider_on_line"]

# A joint this much (relative to the rod) beyond the reach of the rod is taken as just reaching it:
# a few units of round-off in h, e.g. from sin(φ) at a crank angle that is exactly a singular position.
_REACH_TOLERANCE = 8.0 * np.finfo(float).eps
_SINGULAR_FACTOR = 100.0
"""c_B² below this many times its round-off is a singular position (c_B ≲ 6e-7·rod for unit sizes)."""
_STILL_FACTOR = 64.0 * np.finfo(float).eps
"""At a singular position, a velocity of J across the guide below this fraction of J's speed is zero
to round-off: J then moves along the guide and the rates are 0/0, undetermined (``nan``), not unbounded."""


@dataclass(frozen=True)
class SliderOnLine:
    """The solution of the circle–line block over the crank positions.

    Attributes
    ----------
    point : PointMotion
        The slider joint B ``x + iy`` (m) with its velocity (m/s) and acceleration (m/s²).
    rod_angle : AngleMotion
        The angle of the rod, the vector from the joint J to B (rad), with ω (1/s) and
        ε (1/s²); for the crank-slider this is the coupler angle ψ.
    travel : Motion
        The signed position s of B along the guide (m), measured from the guide's point
        ``through`` in the guide's direction, with ``s_t`` (m/s) and ``s_tt`` (m/s²).
    singular : ndarray of bool
        True where the rod is perpendicular to the guide (|h_J| = rod): B's velocity along the
        guide is unbounded there, and the derivatives are ``inf`` or ``nan`` on purpose.
    assembled : ndarray of bool or None
        Only when solved with ``lenient=True``: True where the rod reaches the guide; elsewhere every value is
        ``nan`` and ``singular`` is False. ``None`` otherwise.
    """

    point: PointMotion
    rod_angle: AngleMotion
    travel: Motion
    singular: np.ndarray
    assembled: np.ndarray | None = None


def slider_on_line(joint: PointMotion, rod: float | np.ndarray, through: complex | np.ndarray = 0j,
                   direction: float = 0.0, branch: int | np.ndarray = 1, angles: ArrayLike | None = None,
                   lenient: bool = False) -> SliderOnLine:
    """Solve a rod from a moving joint J to a slider B on a fixed straight guide.

    Parameters
    ----------
    joint : PointMotion
        The joint J at the rod's other end (m, m/s, m/s²); its order (0, 1 or 2) sets the order of
        the result. Arrays of any shape (one entry per crank position).
    rod : float or ndarray
        The rod's length |JB| (m), finite and > 0. In the book's notation L2 (or l_BC in source 004). An
        array (a family of linkages, e.g. of shape (G, 1) against positions of shape (G, N)) broadcasts
        against the positions.
    through : complex or ndarray of complex
        A point of the guide ``x + iy`` (m); the slider's travel s is measured from it (one per member of a
        family, likewise).
    direction : float
        The guide's direction β (rad), counter-clockwise from +x; s grows in this direction.
    branch : int or ndarray of int
        +1: B lies ahead of the foot of the perpendicular from J (in the guide's direction);
        −1: behind it. For the crank-slider with the guide along +x, +1 puts the slider on the
        right of the crank pin. An array: one per member of a family (or per position).
    angles : array_like, optional
        The crank angles (rad) of the positions, used only to name them in an
        :class:`~mechanisms.errors.AssemblyError`.
    lenient : bool
        False (default): raise where the rod cannot reach the guide. True: mark those positions in
        :attr:`SliderOnLine.assembled` and give ``nan`` there.

    Returns
    -------
    SliderOnLine
        B's motion, the rod's angle, the travel s along the guide and the mask of positions where
        the rod is perpendicular to the guide.

    Raises
    ------
    InvalidParameterError
        If ``rod`` is not a finite length > 0, ``through`` or ``direction`` is not finite, or
        ``branch`` is not ±1.
    AssemblyError
        Where J is farther from the guide than the rod is long (|h_J| > rod): the rod cannot reach it.

    Notes
    -----
    With the guide frame of the module docstring, ``c_B = √((rod − h_J)(rod + h_J))`` and σ the
    branch:

    * positions: ``s = u + σ·c_B``, ``B = P + s·ê``, rod angle ``ψ = β + atan2(−h_J, σ·c_B)``;
    * velocities: ``u_t = Re(ê* J_t)``, ``h_J,t = Im(ê* J_t)``, ``c_B,t = −h_J h_J,t / c_B``,
      ``s_t = u_t + σ·c_B,t``, ``ψ_t = −σ·h_J,t / c_B``;
    * accelerations: ``c_B,tt = −(h_J,t² + h_J h_J,tt + c_B,t²) / c_B``, ``s_tt = u_tt + σ·c_B,tt``,
      ``ψ_tt = −(σ·h_J,tt + ψ_t c_B,t) / c_B``,

    from differentiating ``c_B² + h_J² = rod²`` and ``rod·sin(ψ − β) = −h_J`` (chapter 3). Where
    ``c_B = 0`` (the rod perpendicular to the guide) the derivatives divide by zero: they are unbounded
    (``±inf``) or undefined (``nan`` if J moves along the guide there, its velocity across the guide
    zero to round-off, so that the rates are 0/0), and ``singular`` marks
    them; so does a c_B² within 100 times its round-off of zero, where the computed c_B is mostly
    round-off and would give huge finite rates (the crank angles of a limit of assembly, found
    by an arcsin, land there). A joint beyond reach by more than the round-off of
    ``c_B²`` (``8ε_mach·rod·(rod + |J − P|)``) is an assembly error; one within it is taken as at reach.
    """
    # one linkage's numbers take the short way (no array checks): a solve of few positions is mostly this
    rod = require_length("rod", rod) if type(rod) is float else _lengths("rod", rod)
    branch = require_branch(branch) if type(branch) is int or np.ndim(branch) == 0 else _sides(branch)
    direction = require_finite("direction", direction)
    if type(through) is complex or np.ndim(through) == 0:
        through = complex(through)
        if not (np.isfinite(through.real) and np.isfinite(through.imag)):
            raise InvalidParameterError("through", through, "a finite point x + iy (m)")
    else:       # a family: one guide per member
        through = np.asarray(through, dtype=complex)
        if not np.isfinite(through).all():
            raise InvalidParameterError("through", through, "finite points x + iy (m)")
    e = np.exp(1j * direction)
    e_conj = np.conj(e)

    local = e_conj * (np.asarray(joint.value, dtype=complex) - through)
    u, h = local.real, local.imag
    reach = (rod - h) * (rod + h)  # w², free of cancellation near |h| = rod
    # the round-off of w²: h carries that of the joint's coordinates, so it scales with |J − P| too
    slack = _REACH_TOLERANCE * rod * (rod + np.abs(local))
    unreachable = reach < -slack
    assembled = None
    if lenient:
        assembled = ~unreachable
    elif np.any(unreachable):
        worst = float(np.max(np.abs(h)))
        where = None if angles is None else np.broadcast_to(np.asarray(angles, dtype=float), h.shape)[unreachable]
        reason = (f"the rod cannot reach its guide: the rod is {_metres(rod)} long but its far joint is up to "
                  f"{worst:.6g} m from the guide")
        if where is None:
            reason += f" (at {int(np.count_nonzero(unreachable))} position(s))"
        raise AssemblyError(reason, angles=where)
    # within round-off of the rod standing perpendicular to the guide, w itself is unknown: the
    # position is that limit (w = 0) and its derivatives are unbounded, not large finite numbers
    singular = reach <= _SINGULAR_FACTOR * slack
    w = np.where(singular, 0.0, np.sqrt(np.maximum(reach, 0.0)))
    if assembled is not None and not assembled.all():
        # where the rod does not reach, nothing is defined: nan runs through every value below
        w = np.where(assembled, w, np.nan)
        singular &= assembled

    s = u + branch * w
    position = through + s * e
    rod_angle = direction + np.arctan2(-h, branch * w)
    order = joint.order
    if order == 0:
        return SliderOnLine(PointMotion(position), AngleMotion(rod_angle), Motion(s), singular, assembled)

    with np.errstate(divide="ignore", invalid="ignore"):
        local_t = e_conj * joint.velocity
        u_t, h_t = local_t.real, local_t.imag
        # at a singular position where J moves along the guide (h_t zero to round-off: h passes its
        # extreme there, the limiting geometry L2 = L1 + |e|) the rates are 0/0: the constraints do not
        # fix them, and the one-sided limits differ; nan says so, where a round-off h_t would give ±inf
        still = singular & (np.abs(h_t) <= _STILL_FACTOR * np.abs(joint.velocity))
        h_t = np.where(still, np.nan, h_t)
        w_t = -h * h_t / w
        s_t = u_t + branch * w_t
        theta_t = -branch * h_t / w
        if order == 1:
            point = PointMotion(position, s_t * e)
            return SliderOnLine(point, AngleMotion(rod_angle, theta_t), Motion(s, s_t), singular, assembled)
        local_tt = e_conj * joint.acceleration
        u_tt, h_tt = local_tt.real, local_tt.imag
        w_tt = -(h_t**2 + h * h_tt + w_t**2) / w
        s_tt = u_tt + branch * w_tt
        theta_tt = -(branch * h_tt + theta_t * w_t) / w
        point = PointMotion(position, s_t * e, s_tt * e)
    return SliderOnLine(point, AngleMotion(rod_angle, theta_t, theta_tt), Motion(s, s_t, s_tt), singular, assembled)
