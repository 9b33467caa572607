"""Analysis of slotted-lever mechanisms (chapter 5): swing, limit positions, time ratio, shaper stroke,
and the distance h_N of the second rocker's pivot from the lever (two rockers with a slotted pair).

For an oscillating lever (pivot C at distance d from the crank centre O, crank length L₁ < d) the
lever is at an extreme position when it is tangent to the crank circle, OA ⊥ CA. Then

    sin β_s = L₁ / d

where β_s is half the lever's swing, and the crank angles between the two extremes are π − 2β_s
(the quick stroke, on the side of the pivot) and π + 2β_s (the slow stroke). The time ratio (the
coefficient of the change of the mean speed) of a crank turning at constant speed is

    K = (π + 2β_s) / (π − 2β_s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .assignments import Quantity, Task, crank_speed, register_assignment, round_mm
from ..core.errors import InvalidParameterError
from ..core.validate import require_length
from ..blocks.lines import distance_to_line
from ..core.motion import AngleMotion, Motion, PointMotion
from ..linkages.base import Solution
from ..linkages.slotted import Shaper, SlottedLever, SlottedRockers

__all__ = ["half_swing", "time_ratio", "LimitPositions", "limit_positions", "ShaperStroke", "shaper_stroke",
           "distance_from_lever", "SlidingParts", "sliding_parts"]


def half_swing(crank: float, pivot_distance: float) -> float:
    """Half the swing β_s of an oscillating slotted lever (rad): ``sin β_s = L₁/d``.

    Parameters
    ----------
    crank : float
        Crank length L₁ (m).
    pivot_distance : float
        Distance d = |OC| from the crank centre to the lever's pivot (m), greater than L₁.

    Notes
    -----
    ``β_s = atan2(L₁, √((d − L₁)(d + L₁)))`` (accurate also when L₁ is close to d).
    """
    r = require_length("crank", crank)
    d = require_length("pivot_distance", pivot_distance)
    if d <= r:
        raise InvalidParameterError("pivot_distance", pivot_distance, f"greater than the crank r = {r:g} m for an "
                                    "oscillating lever (otherwise the lever rotates and has no swing)")
    return math.atan2(r, math.sqrt((d - r) * (d + r)))


def time_ratio(crank: float, pivot_distance: float) -> float:
    """Time ratio K of an oscillating slotted lever: ``K = (π + 2β_s)/(π − 2β_s)``, ``sin β_s = L₁/d``."""
    beta = half_swing(crank, pivot_distance)
    return (math.pi + 2.0 * beta) / (math.pi - 2.0 * beta)


@dataclass(frozen=True)
class LimitPositions:
    """The two extreme positions of an oscillating slotted lever.

    Attributes
    ----------
    crank_angles : tuple of float
        The crank angles φ (rad) of the two extremes, in [0, 2π); the crank turns from the first
        to the second through the slow stroke (π + 2β_s) when it turns counter-clockwise.
    lever_angles : tuple of float
        The lever angles ξ (rad) at the two extremes.
    half_swing : float
        β_s (rad).
    time_ratio : float
        K.
    """

    crank_angles: tuple[float, float]
    lever_angles: tuple[float, float]
    half_swing: float
    time_ratio: float


def limit_positions(mechanism: SlottedLever | Shaper) -> LimitPositions:
    """The extreme positions of an oscillating slotted lever (also of a shaper's lever).

    Notes
    -----
    With θ_OC the direction of the pivot C seen from O, the lever is tangent to the crank circle
    at ``φ = θ_OC ± (π/2 − β_s)``, and the lever angle there is ``ξ = arg(A − C)``.
    Counter-clockwise, the crank goes from ``θ_OC + π/2 − β_s`` to ``θ_OC − π/2 + β_s + 2π`` through
    ``π + 2β_s`` (slow) and back through ``π − 2β_s`` (quick).
    """
    pivot = complex(*mechanism.pivot)
    r, d = mechanism.crank, abs(pivot)
    beta = half_swing(r, d)
    gamma = math.atan2(pivot.imag, pivot.real)
    first = (gamma + 0.5 * math.pi - beta) % (2.0 * math.pi)    # crank angles in [0, 2π), as documented
    second = (gamma - 0.5 * math.pi + beta) % (2.0 * math.pi)
    lever = tuple(float(np.angle(r * np.exp(1j * phi) - pivot)) for phi in (first, second))
    return LimitPositions((first, second), (lever[0], lever[1]), beta, time_ratio(r, d))


@dataclass(frozen=True)
class ShaperStroke:
    """The ram's extreme positions and stroke.

    Attributes
    ----------
    positions : tuple of float
        The ram's abscissa x_G (m; of the joint G) at the lever's two extremes (same order as
        :class:`LimitPositions`).
    stroke : float
        H, the distance between the two (m).
    time_ratio : float
        K, the lever's (the ram is at rest exactly when the lever is).
    """

    positions: tuple[float, float]
    stroke: float
    time_ratio: float


def shaper_stroke(shaper: Shaper) -> ShaperStroke:
    """The ram's stroke of a shaper from the lever's extreme positions, in closed form.

    Notes
    -----
    At an extreme lever angle ξ the lever's end is ``B = C + L₃ exp(iξ)``; the ram is where the rod
    of length l_BG from B meets the line y = y_G (``ram_height``):
    ``x_G = x_B + σ·√((l_BG − (y_B − y_G))(l_BG + (y_B − y_G)))``, σ the shaper's ``branch``.
    The ram's velocity ``v_G`` vanishes only where B's velocity is perpendicular to the rod, that is where
    ξ_t = 0 (or the rod is along the lever, which the assembly excludes), so these are its extremes.
    """
    limits = limit_positions(shaper)
    c = complex(*shaper.pivot)
    xs = []
    for xi in limits.lever_angles:
        b = c + shaper.lever * complex(math.cos(xi), math.sin(xi))
        dy = b.imag - shaper.ram_height
        xs.append(b.real + shaper.branch * math.sqrt((shaper.rod - dy) * (shaper.rod + dy)))
    return ShaperStroke((xs[0], xs[1]), abs(xs[0] - xs[1]), limits.time_ratio)


def distance_from_lever(rockers: SlottedRockers, solution: Solution) -> Motion:
    """h_N: the signed distance of the second rocker's pivot O₂ from the lever's line, with derivatives.

    Parameters
    ----------
    rockers : SlottedRockers
        The two rockers with a slotted pair (the lever turns about C, the second rocker about O₂).
    solution : Solution
        Its solution (``rockers.solve(...)``).

    Returns
    -------
    Motion
        h_N (m), positive when O₂ is on the lever's left (seen from C along the direction ξ), with
        (h_N)_t (m/s) and (h_N)_tt (m/s²) up to the solution's order. The same values as the
        solution's ``extras["O2"]["h"]``, ``["h_t"]``, ``["h_tt"]``.

    Notes
    -----
    ``h_N = Im(e^{−iξ}(O₂ − C))`` and its derivatives (:func:`mechanisms.blocks.lines.distance_to_line`).
    """
    return distance_to_line(complex(*rockers.rocker_pivot), complex(*rockers.pivot), solution.angle("lever")).distance


@dataclass(frozen=True)
class SlidingParts:
    """The velocity and acceleration of a block sliding along a moving link, split into their parts.

    All are complex vectors ``x + iy`` over the positions (m/s, m/s²).

    Attributes
    ----------
    transport_velocity : ndarray
        Velocity of the link's point under the block (the block welded to the link).
    relative_velocity : ndarray
        ``s_t e^{iθ}``: the block's velocity along the slot, seen from the link.
    transport_acceleration : ndarray
        Acceleration of the link's point under the block.
    relative_acceleration : ndarray
        ``s_tt e^{iθ}``, along the slot.
    coriolis : ndarray
        ``2 i θ_t s_t e^{iθ}``, the Coriolis acceleration 2 ω × v_rel, across the slot.
    """

    transport_velocity: np.ndarray
    relative_velocity: np.ndarray
    transport_acceleration: np.ndarray
    relative_acceleration: np.ndarray
    coriolis: np.ndarray

    @property
    def velocity(self) -> np.ndarray:
        """The block's absolute velocity, the sum of the transport and relative parts (m/s)."""
        return self.transport_velocity + self.relative_velocity

    @property
    def acceleration(self) -> np.ndarray:
        """The block's absolute acceleration, transport + relative + Coriolis (m/s²)."""
        return self.transport_acceleration + self.relative_acceleration + self.coriolis


def sliding_parts(origin: PointMotion, direction: AngleMotion, along: Motion) -> SlidingParts:
    """Split the motion of a block at ``origin + s e^{iθ}`` on a moving link into transport, relative and Coriolis parts.

    Parameters
    ----------
    origin : PointMotion
        A point Q of the link that carries the slot, with velocity and acceleration (m, m/s, m/s²),
        for example the lever's pivot C or the crank pin A at the end of a slotted coupler.
    direction : AngleMotion
        The slot's direction θ on that link with its angular velocity and acceleration (rad, 1/s, 1/s²):
        the link's angle, since the slot turns with the link.
    along : Motion
        The block's distance s from Q along the slot, with s_t and s_tt (m, m/s, m/s²).

    Returns
    -------
    SlidingParts
        The parts of ``v = v_Q + iθ_t s e^{iθ} + s_t e^{iθ}`` and
        ``a = a_Q + (iθ_tt − θ_t²) s e^{iθ} + s_tt e^{iθ} + 2iθ_t s_t e^{iθ}`` (chapter 5, §5.7–§5.8).

    Raises
    ------
    MissingDerivativeError
        If any of the three motions lacks accelerations (solve with ``order=2``).

    Notes
    -----
    The Coriolis part is 2 ω × v_rel with ω = θ_t: the relative velocity turned by 90° in the sense
    of the link's rotation and doubled, the convention of chapter 5.
    """
    unit = np.exp(1j * np.asarray(direction.value, dtype=float))
    arm = np.asarray(along.value, dtype=float) * unit          # s e^{iθ}, from Q to the block
    omega, alpha = direction.d1, direction.d2
    return SlidingParts(
        transport_velocity=origin.d1 + 1j * omega * arm,
        relative_velocity=along.d1 * unit,
        transport_acceleration=origin.d2 + (1j * alpha - omega**2) * arm,
        relative_acceleration=along.d2 * unit,
        coriolis=2j * omega * along.d1 * unit)


# --- the slotted lever's assignment (python -m mechanisms assign slotted-lever) -------------------------------------------------------------------------------------

SLOTTED_MIN_PIVOT_RATIO = 1.3
"""The lever's pivot is at least this many crank radii from the crank's centre (oscillating lever)."""


def _sample_slotted_lever(rng: np.random.Generator) -> tuple[SlottedLever, float]:
    crank = round_mm(rng.uniform(0.050, 0.150))
    distance = rng.uniform(1.4, 2.5) * crank
    direction = math.radians(rng.uniform(-110.0, -70.0))   # the pivot below the crank, as in a shaper
    pivot = (round_mm(distance * math.cos(direction)), round_mm(distance * math.sin(direction)))
    return SlottedLever(crank=crank, pivot=pivot), crank_speed(rng, 10, 60)


def _check_slotted_lever(mechanism: SlottedLever) -> list[str]:
    if mechanism.kind != "oscillating" or mechanism.pivot_distance < SLOTTED_MIN_PIVOT_RATIO * mechanism.crank:
        return [f"the pivot is closer than {SLOTTED_MIN_PIVOT_RATIO:g} crank radii: the lever would swing too far "
                "or rotate"]
    return []


def _data_slotted_lever(m: SlottedLever) -> list[tuple[str, str, str, str]]:
    return [("L_1", "crank length |OA| (the block is on the crank pin A)", f"{m.crank:.3f}", "m"),
            ("(x_C, y_C)", "the lever's fixed pivot C", f"({m.pivot[0]:.3f}, {m.pivot[1]:.3f})", "m"),
            ("K", "time ratio of the lever (for reference)",
             f"{time_ratio(m.crank, m.pivot_distance):.3f}", "")]


register_assignment(Task(
    "slotted-lever", "Crank with an oscillating slotted lever", _sample_slotted_lever, _check_slotted_lever,
    _data_slotted_lever,
    (Quantity("lever.angle_deg", "ξ", "lever angle, of the vector C→A from +x, counter-clockwise", "°"),
     Quantity("lever.omega", "ξ_t", "angular velocity of the lever (positive counter-clockwise)", "1/s"),
     Quantity("lever.alpha", "ξ_tt", "angular acceleration of the lever", "1/s²"),
     Quantity("A.s", "L", "distance from the pivot C to the block A", "m"),
     Quantity("A.v", "L_t", "sliding velocity of the block along the lever (positive away from C)", "m/s"),
     Quantity("A.a", "L_tt", "relative acceleration of the block along the lever (positive away from C)",
              "m/s²"),
     Quantity("A.coriolis", "a^k", "Coriolis acceleration, twice the lever's angular velocity times the sliding "
              "velocity (positive towards the lever's left)", "m/s²")),
    f"the lever oscillates, its pivot at least {SLOTTED_MIN_PIVOT_RATIO:g} crank radii from the crank's centre"))
