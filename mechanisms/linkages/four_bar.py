"""Layer 3: the hinged four-bar (crank-rocker and its family), chapter 4.

Joints: crank pivot O at the origin, crank pin A, coupler-rocker joint B, rocker pivot C at
(x_C, y_C). Links: crank O → A (L1, angle φ), coupler A → B (L2, angle ψ), rocker C → B (L3,
angle ξ). The loop-closure equations of the lecture (Alyushin, 2008) are

    L1 cos φ + L2 cos ψ − L3 cos ξ = a,
    L1 sin φ + L2 sin ψ − L3 sin ξ = b.

Besides the mechanism class, the module holds the lecture's own formulas — the half-angle
solution for ψ and the angular velocities and accelerations by Cramer's rule — so that the
book can set them next to the stable form the class uses, and the analytic range of crank
angles in which a linkage assembles.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .chunks import solve_in_chunks
from ..core.angles import wrap_angle
from .groups import RRR, Crank, Group
from .base import (Bar, Block, Ground, Guide, Mechanism, Parameter, Solution, family_pin, family_shape, is_family,
                   member_values)
from ..blocks.circle_circle import hinge
from ..blocks.crank import crank_angle, crank_pin
from ..core.errors import AssemblyError, InvalidParameterError, describe_range
from ..core.exact import squared_distance_equals
from ..core.validate import require_branch, require_length, require_flag, require_pair
from ..core.angles import constant
from ..core.motion import AngleMotion, Motion, PointMotion, fixed_point

__all__ = [
    "FourBar",
    "CHANGE_POINT_TOLERANCE",
    "half_angle_coupler_angle",
    "stable_coupler_angle",
    "half_angle_formula",
    "stable_formula",
    "cramer_rates",
    "assembly_intervals",
    "change_point_angles",
    "FourBarFamily",
    "four_bar_family",
]

CHANGE_POINT_TOLERANCE = 0.0
"""Kept for compatibility: a linkage is a change-point linkage only where its length equalities hold
exactly for the given doubles (:func:`change_point_angles`); 1e-10 away from one it is an ordinary
linkage, whose branch the general solution keeps."""


# --- the lecture's formulas -------------------------------------------------------------------

def _pqf(phi, crank: float, coupler: float, rocker: float, frame: tuple[float, float], dtype: type = float):
    """The lecture's P = a − L1 cos φ, Q = b − L1 sin φ and F = (P² + Q² + L2² − L3²)/(2 L2).

    ``dtype`` is the number type of the arithmetic: ``float``, or ``numpy.longdouble`` for the values
    before they are rounded once to double (chapter 9).
    """
    phi = np.asarray(phi, dtype=dtype)
    p = frame[0] - crank * np.cos(phi)
    q = frame[1] - crank * np.sin(phi)
    f = (p**2 + q**2 + coupler**2 - rocker**2) / (2.0 * coupler)
    return p, q, f


def half_angle_coupler_angle(phi: ArrayLike, crank: float, coupler: float, rocker: float, frame: tuple[float, float],
                             branch: int = 1) -> np.ndarray:
    """The coupler angle ψ by the lecture's half-angle formula, as printed (for comparison).

    Parameters
    ----------
    phi : array_like
        Crank angles φ (rad).
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    frame : (float, float)
        The rocker pivot C = (x_C, y_C) (m).
    branch : int
        +1 takes the + sign before the root, −1 the − sign; it is the same geometric branch
        as :class:`FourBar`'s (B to the left of A → C for +1).

    Returns
    -------
    ndarray
        ``ψ = 2 arctan[(Q ± √(Q² + P² − F²))/(P + F)]`` (rad), in (−π, π). Where P + F = 0 the
        formula divides by zero; close to it the − root loses accuracy (cancellation), see
        chapter 4.

    Notes
    -----
    From ``P cos ψ + Q sin ψ = F`` with ``t = tan(ψ/2)``: ``(P + F)t² − 2Qt + (F − P) = 0``.
    """
    p, q, f = _pqf(phi, crank, coupler, rocker, frame)
    return half_angle_formula(p, q, f, branch)


def half_angle_formula(p: ArrayLike, q: ArrayLike, f: ArrayLike, branch: int = 1,
                       arctan: Callable[[np.ndarray], np.ndarray] = np.arctan) -> np.ndarray:
    """The lecture's half-angle formula for ψ from given 𝒫, 𝒬, ℱ (:func:`half_angle_coupler_angle`).

    Parameters
    ----------
    p, q, f : array_like
        𝒫, 𝒬, ℱ (m), double precision.
    branch : int
        +1 or −1: the sign before the root.
    arctan : callable
        The arctangent of the last step; chapter 9 passes one rounded once from extended precision.

    Returns
    -------
    ndarray
        ``ψ = 2 arctan[(𝒬 ± √(𝒬² + 𝒫² − ℱ²))/(𝒫 + ℱ)]`` (rad): the square root, subtractions and
        division in double precision, where the formula loses its digits near 𝒫 + ℱ = 0.
    """
    p, q, f = (np.asarray(v, dtype=float) for v in (p, q, f))
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (q + branch * np.sqrt(q**2 + p**2 - f**2)) / (p + f)
    return 2.0 * arctan(t)


def stable_coupler_angle(phi: ArrayLike, crank: float, coupler: float, rocker: float, frame: tuple[float, float],
                         branch: int = 1) -> np.ndarray:
    """The coupler angle ψ in stable form: ``ψ = atan2(Q, P) + branch·atan2(√(R² − F²), F)``.

    ``R = hypot(P, Q) = |AC|``; ``R² − F²`` is computed as a product of the differences of the
    lengths (Heron), so that no cancellation occurs near the limits of assembly. Result in
    (−π, π].
    """
    p, q, _ = _pqf(phi, crank, coupler, rocker, frame)
    return stable_formula(p, q, coupler, rocker, branch)


def stable_formula(p: ArrayLike, q: ArrayLike, coupler: float, rocker: float, branch: int = 1,
                   arctan2: Callable[[np.ndarray, np.ndarray], np.ndarray] = np.arctan2,
                   hypot: Callable[[np.ndarray, np.ndarray], np.ndarray] = np.hypot) -> np.ndarray:
    """The stable form of ψ from given 𝒫 and 𝒬 (:func:`stable_coupler_angle`).

    Parameters
    ----------
    p, q : array_like
        𝒫, 𝒬 (m), double precision.
    coupler, rocker : float
        L2, L3 (m).
    branch : int
        +1 or −1.
    arctan2, hypot : callable
        The two-argument arctangent and ``hypot``; chapter 9 passes ones rounded once from extended
        precision.

    Returns
    -------
    ndarray
        ``ψ = atan2(𝒬, 𝒫) + branch·atan2(√(R² − ℱ²), ℱ)`` (rad) in (−π, π], ``R = hypot(𝒫, 𝒬)``.
    """
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    r = hypot(p, q)
    total, difference = coupler + rocker, abs(coupler - rocker)
    with np.errstate(invalid="ignore"):
        # R² − F² = ((L2+L3)² − R²)(R² − (L2−L3)²)/(4 L2²)
        height = np.sqrt((total + r) * (total - r) * (r - difference) * (r + difference)) / (2.0 * coupler)
    foot = (r**2 + (coupler - rocker) * (coupler + rocker)) / (2.0 * coupler)   # = F
    psi = arctan2(q, p) + branch * arctan2(height, foot)
    return wrap_angle(psi)


def cramer_rates(phi: ArrayLike, psi: ArrayLike, xi: ArrayLike, crank: float, coupler: float, rocker: float,
                 omega: ArrayLike, alpha: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Angular velocities and accelerations of coupler and rocker by Cramer's rule (lecture).

    Parameters
    ----------
    phi, psi, xi : array_like
        Crank, coupler and rocker angles (rad) at the positions.
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    omega, alpha : float or array_like
        φ_t (1/s) and φ_tt (1/s²).

    Returns
    -------
    (psi_t, xi_t, psi_tt, xi_tt) : tuple of ndarray
        1/s and 1/s².

    Notes
    -----
    With Δ = L2 L3 sin(ψ − ξ) (corrected forms, see the errata):
    ``ψ_t = −φ_t L1 sin(φ − ξ)/(L2 sin(ψ − ξ))``, ``ξ_t = φ_t L1 sin(ψ − φ)/(L3 sin(ψ − ξ))``,
    ``ψ_tt = (f1 cos ξ + f2 sin ξ)/(L2 sin(ξ − ψ))``, ``ξ_tt = (f1 cos ψ + f2 sin ψ)/(L3 sin(ξ − ψ))``
    with ``f1 = φ_tt L1 sin φ + φ_t² L1 cos φ + ψ_t² L2 cos ψ − ξ_t² L3 cos ξ`` and
    ``f2 = −φ_tt L1 cos φ + φ_t² L1 sin φ + ψ_t² L2 sin ψ − ξ_t² L3 sin ξ``.
    """
    phi, psi, xi = (np.asarray(v, dtype=float) for v in (phi, psi, xi))
    omega, alpha = np.asarray(omega, dtype=float), np.asarray(alpha, dtype=float)
    l1, l2, l3 = crank, coupler, rocker
    with np.errstate(divide="ignore", invalid="ignore"):
        psi_t = -omega * l1 * np.sin(phi - xi) / (l2 * np.sin(psi - xi))
        xi_t = omega * l1 * np.sin(psi - phi) / (l3 * np.sin(psi - xi))
        f1 = (alpha * l1 * np.sin(phi) + omega**2 * l1 * np.cos(phi) + psi_t**2 * l2 * np.cos(psi)
              - xi_t**2 * l3 * np.cos(xi))
        f2 = (-alpha * l1 * np.cos(phi) + omega**2 * l1 * np.sin(phi) + psi_t**2 * l2 * np.sin(psi)
              - xi_t**2 * l3 * np.sin(xi))
        psi_tt = (f1 * np.cos(xi) + f2 * np.sin(xi)) / (l2 * np.sin(xi - psi))
        xi_tt = (f1 * np.cos(psi) + f2 * np.sin(psi)) / (l3 * np.sin(xi - psi))
    return psi_t, xi_t, psi_tt, xi_tt


# --- assembly and change points -----------------------------------------------------------------

def _half_opening(distance: float, crank: float, reach: float) -> float:
    """The angle β ∈ [0, π] between OA and OC at which |AC| = reach (which must lie in [|d − L1|, d + L1]).

    From the cosine law |AC|² = L1² + d² − 2 L1 d cos β in half-angle form:
    ``tan²(β/2) = (reach² − (d − L1)²)/((d + L1)² − reach²)``, computed with atan2.
    """
    low, high = abs(distance - crank), distance + crank
    reach = min(max(reach, low), high)   # the callers pass reaches inside; round-off stays inside too
    return 2.0 * math.atan2(math.sqrt((reach - low) * (reach + low)), math.sqrt((high - reach) * (high + reach)))


def assembly_intervals(crank: float, coupler: float, rocker: float,
                       frame: tuple[float, float]) -> list[tuple[float, float]]:
    """Crank-angle intervals (rad) in which the four-bar assembles, analytically.

    Returns
    -------
    list of (start, stop)
        ``[(θ_OC − π, θ_OC + π)]`` for a fully rotating crank (θ_OC = direction of OC); one or two
        intervals (start < stop) otherwise; empty if it never assembles.

    Notes
    -----
    The coupler and rocker close the loop when ``|L2 − L3| ≤ |AC| ≤ L2 + L3``. |AC| grows with
    the angle |φ − θ_OC| ∈ [0, π] between OA and OC, so the conditions bound that angle from below
    (where |AC| = |L2 − L3|) and from above (where |AC| = L2 + L3), chapter 4.
    """
    # scale-free: lengths divided by a power of two (exact), so that no square overflows or underflows
    _, exponent = math.frexp(max(crank, coupler, rocker, abs(frame[0]), abs(frame[1])))
    crank, coupler, rocker = (math.ldexp(v, -exponent) for v in (crank, coupler, rocker))
    a, b = (math.ldexp(v, -exponent) for v in frame)
    distance = math.hypot(a, b)
    theta0 = math.atan2(b, a)
    low, high = abs(distance - crank), distance + crank
    inner, outer = abs(coupler - rocker), coupler + rocker
    if outer < low or inner > high:
        return []
    beta_min = 0.0 if inner <= low else _half_opening(distance, crank, inner)
    beta_max = math.pi if outer >= high else _half_opening(distance, crank, outer)
    if beta_min == 0.0 and beta_max == math.pi:
        return [(theta0 - math.pi, theta0 + math.pi)]
    if beta_min == 0.0:
        return [(theta0 - beta_max, theta0 + beta_max)]
    if beta_max == math.pi:
        return [(theta0 + beta_min, theta0 + 2.0 * math.pi - beta_min)]
    return [(theta0 + beta_min, theta0 + beta_max), (theta0 - beta_max, theta0 - beta_min)]


def change_point_angles(crank: float, coupler: float, rocker: float,
                        frame: tuple[float, float]) -> tuple[float, ...]:
    """Crank angles (rad, in [θ_OC, θ_OC + 2π)) at which the crank passes a change point.

    At a change point all four joints are in line, the two branches meet and the crank can
    pass on. It happens at φ = θ_OC (A on the segment towards C) when |d − L1| = |L2 − L3|, and
    at φ = θ_OC + π when d + L1 = L2 + L3 (d = |OC|, θ_OC its direction); there |AC| passes its
    extreme, so the two branches touch without the crank having to turn back.

    The equalities are decided exactly for the given doubles (d² = a² + b² in rational arithmetic,
    :mod:`mechanisms.core.exact`), never with a tolerance: a linkage 1e-10 from the change-point
    condition is an ordinary one, which keeps its side of A → C at every crank angle.
    """
    a, b = frame
    theta0 = math.atan2(b, a)
    l1, l2, l3 = (Fraction(v) for v in (crank, coupler, rocker))
    found = []
    # |d − L1| = |L2 − L3|  ⇔  d = L1 + (L2 − L3) or d = L1 − (L2 − L3), with d ≥ 0
    if any(squared_distance_equals((a, b), l1 + sign * (l2 - l3)) for sign in (1, -1)):
        found.append(theta0)
    if squared_distance_equals((a, b), l2 + l3 - l1):          # d + L1 = L2 + L3
        found.append(theta0 + math.pi)
    return tuple(found)


def _sides(phi: np.ndarray, branch: int, theta0: float, flips: Sequence[float]) -> np.ndarray | int:
    """The geometric side of B at each crank angle for a linkage that keeps its assembly mode.

    ``branch`` holds for φ − θ_OC in (0, π); each change point passed between there and φ
    (counted on the unwrapped crank angle) changes the side.
    """
    if not flips:
        return branch
    u = (phi - theta0) / math.pi      # change points at even u (φ = θ_OC) and odd u (φ = θ_OC + π)
    count = np.zeros(np.shape(phi), dtype=int)
    for flip in flips:
        offset = 0.0 if math.isclose(flip, theta0) else 1.0
        count += np.abs(np.floor((u + offset) / 2.0)).astype(int)
    return branch * np.where(count % 2 == 0, 1, -1)


def _require_frame(value: object) -> tuple[float, float]:
    a, b = require_pair("frame", value)
    if a == 0.0 and b == 0.0:
        raise InvalidParameterError("frame", value, "a rocker pivot (x_C, y_C) other than the crank pivot (0, 0)")
    return a, b


def _frame_pair(frame: Any) -> tuple[Any, Any] | None:
    """``frame`` as its two coordinates (each a number or a family's array), or None if it is not a pair (the
    check of one linkage's frame then names it)."""
    if isinstance(frame, (str, bytes, dict)) or frame is None or (isinstance(frame, np.ndarray) and frame.ndim != 1):
        return None
    try:
        parts: tuple[Any, ...] = tuple(frame)
    except TypeError:
        return None
    return (parts[0], parts[1]) if len(parts) == 2 else None


@functools.lru_cache(maxsize=1024)
def _change_points_of(crank: float, coupler: float, rocker: float, frame: tuple[float, float]) -> tuple[float, ...]:
    """:func:`change_point_angles`, kept for each geometry: deciding a change point is exact (rational
    arithmetic) and costs as much as a small solve, and a mechanism asks at every solve."""
    return tuple(change_point_angles(crank, coupler, rocker, frame))


class FourBar(Mechanism):
    """Hinged four-bar: crank O→A, coupler A→B, rocker C→B with pivots O = (0, 0), C = (x_C, y_C).

    Parameters
    ----------
    crank, coupler, rocker : float or array_like
        L1, L2, L3 (m).
    frame : (float, float)
        The rocker pivot C = (x_C, y_C) (m); each coordinate a number or an array (a family).
    branch : int or array_like of int
        +1: B to the left of the directed line A → C; −1: to the right.
    keep_side : bool
        False (default): at a change point the linkage keeps its assembly mode (smooth
        continuation, see Notes). True: B stays on the side ``branch`` of A → C at every crank
        angle, so at a change point the linkage turns back into its own mode with a jump of the
        angular velocities (the source's drop-shaped lambda curve at d = 11 is drawn so).
    lenient : bool
        False (default): :meth:`solve` raises :class:`AssemblyError` where the linkage (a member of a
        family: named by its index) does not assemble. True: those positions are marked False in
        :attr:`Solution.assembled`, their angles and points are ``nan`` and they are not singular.

    Notes
    -----
    A family of four-bars: give any of the dimensions (and ``branch``) as arrays of one shape G (or shapes
    that broadcast to it). Each member is checked as one linkage is (a bad one is named by its index,
    ``crank[3]``); solving at N crank angles (a one-dimensional ``phi``) gives arrays of shape G + (N,), every
    member exactly as it is solved alone, at the cost per member and position of one linkage's solve per
    position. What is defined for one linkage only (:meth:`assembly_intervals`, :attr:`lengths`, the
    analysis functions built on them, a linkage file) refuses a family with :class:`InvalidParameterError`.
    At order 0 the link angles of a family are computed when first read. A family of more than some
    :data:`~mechanisms.linkages.chunks.BLOCK` member-positions is fastest solved in parts of about that many
    (the benchmark's family row does so): the temporaries of a part stay in the processor's cache.

    Continuation rule (chapter 4). Outside change points the geometric side of B is the same
    at every crank angle, so ``branch`` says it once and for all. A change-point linkage
    (s + l = p + q: parallelogram, deltoid …) has crank angles where the two branches meet (all
    joints in line); there the linkage keeps its assembly mode, i.e. it continues smoothly, with
    continuous angular velocities, and its geometric side changes. For such a linkage
    ``branch`` is the side on the stretch of crank angles between change points that contains
    φ = θ_OC + π/2 (θ_OC = direction of OC; φ taken as it is, not modulo 2π), and the side at any
    other crank angle follows by counting the change points passed. The rule depends on the
    crank angle only, not on the step or the order of the array: a parallelogram stays a
    parallelogram whatever the step. With one change point per turn the motion repeats only
    after two turns of the crank (the second turn is the mirror assembly). At the change point itself
    the velocities are not determined by the constraints and are marked singular.
    """

    cli_name = "four-bar"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1, m"),
        Parameter("coupler", "length", "coupler length L2 (A to B), m"),
        Parameter("rocker", "length", "rocker length L3 (C to B), m"),
        Parameter("frame", "pair", "rocker pivot C = (x_C, y_C), m, as X,Y"),
        Parameter("branch", "branch", "+1: B left of the line A->C, -1: right of it", 1),
    )
    links = {"crank": "O", "coupler": "A", "rocker": "C"}

    # one linkage: floats (and an int branch); a family: arrays of shape G (typed Any for the two)
    crank: Any
    coupler: Any
    rocker: Any
    frame: Any
    branch: Any

    def __init__(self, crank: ArrayLike, coupler: ArrayLike, rocker: ArrayLike,
                 frame: tuple[ArrayLike, ArrayLike], branch: ArrayLike = 1, keep_side: bool = False,
                 lenient: bool = False):
        self.keep_side = require_flag("keep_side", keep_side)
        self.lenient = require_flag("lenient", lenient)
        pair = _frame_pair(frame)
        if pair is not None and is_family(crank, coupler, rocker, branch, *pair):
            self._family(crank, coupler, rocker, pair, branch)
            return
        self.crank = require_length("crank", crank)
        self.coupler = require_length("coupler", coupler)
        self.rocker = require_length("rocker", rocker)
        self.frame = _require_frame(frame)
        self.branch = require_branch(branch)

    def _family(self, crank: ArrayLike, coupler: ArrayLike, rocker: ArrayLike, frame: tuple[Any, Any],
                branch: ArrayLike) -> None:
        """Set a family's dimensions: arrays of one shape G, checked member by member."""
        values = {"crank": member_values("crank", crank, "length"),
                  "coupler": member_values("coupler", coupler, "length"),
                  "rocker": member_values("rocker", rocker, "length"),
                  "frame[0]": member_values("frame[0]", frame[0], "coordinate"),
                  "frame[1]": member_values("frame[1]", frame[1], "coordinate"),
                  "branch": member_values("branch", branch, "branch")}
        shape = family_shape(**values)
        self.family_parameters = tuple(name for name, value in values.items() if value.ndim)
        l1, l2, l3, x, y, side = (np.broadcast_to(v, shape) for v in values.values())
        at_origin = (x == 0.0) & (y == 0.0)
        if at_origin.any():
            index = ", ".join(str(int(i)) for i in np.argwhere(at_origin)[0])
            raise InvalidParameterError(f"frame[..][{index}]", (0.0, 0.0),
                                        "a rocker pivot (x_C, y_C) other than the crank pivot (0, 0)")
        self.crank, self.coupler, self.rocker = l1, l2, l3
        self.frame = (x, y)
        self.branch = side.astype(int)
        self.family_shape = shape

    @property
    def pivot(self) -> complex:
        """The rocker pivot C as ``x_C + i y_C`` (m) (an array of them for a family)."""
        if self.family_shape:
            return self.frame[0] + 1j * self.frame[1]
        return complex(*self.frame)

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        """(L1, L2, L3, d): crank, coupler, rocker and frame |OC| (m).

        Raises
        ------
        InvalidParameterError
            For a family (the analysis built on the four lengths is defined for one linkage).
        """
        self.require_one_linkage("the four lengths (L1, L2, L3, d)")
        return self.crank, self.coupler, self.rocker, abs(self.pivot)

    benchmark = True

    @classmethod
    def example(cls) -> "FourBar":
        """The benchmark's crank-rocker: L1 = 1 m, L2 = 3.5 m, L3 = 3 m, C = (4, 0) m, branch +1."""
        return cls(crank=1.0, coupler=3.5, rocker=3.0, frame=(4.0, 0.0), branch=1)

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Crank-angle intervals (rad) in which the linkage assembles (see the module function)."""
        self.require_one_linkage("the assembly intervals")
        return assembly_intervals(self.crank, self.coupler, self.rocker, self.frame)

    def _rescaled(self, factor: float) -> "FourBar":
        return FourBar(self.crank * factor, self.coupler * factor, self.rocker * factor,
                       (self.frame[0] * factor, self.frame[1] * factor), self.branch, self.keep_side, self.lenient)

    def linkage_data(self) -> dict:
        """This four-bar as the contents of a linkage file (:mod:`~mechanisms.linkages.linkage_file`).

        The crank O → A and an RRR dyad: B at L₂ from A and L₃ from C, on the side σ of the directed line
        A → C (the class's branch). Loaded, it is the same linkage (a file has no ``keep_side``: at a
        change point it keeps the geometric side).
        """
        self.require_one_linkage("a linkage file")
        return {"name": "Four-bar", "frame": {"O": [0.0, 0.0], "C": [self.frame[0], self.frame[1]]},
                "crank": {"pivot": "O", "pin": "A", "length": self.crank},
                "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [self.coupler, self.rocker],
                          "branch": self.branch, "links": ["coupler", "rocker"]}]}

    def groups(self) -> tuple[Group, ...]:
        self.require_one_linkage("the structure (plans, instant centres)")
        return (Crank("O", "A"), RRR("B", "A", "C", "coupler", "rocker"))

    def change_points(self) -> tuple[float, ...]:
        """Crank angles (rad) of the change points the crank passes (empty for most linkages)."""
        self.require_one_linkage("the change points")
        return _change_points_of(float(self.crank), float(self.coupler), float(self.rocker),
                                 (float(self.frame[0]), float(self.frame[1])))

    def sides(self, phi: ArrayLike) -> np.ndarray:
        """The geometric side (+1/−1) of B relative to A → C at each crank angle (continuation rule)."""
        phi = np.asarray(phi, dtype=float)
        if self.keep_side:
            return np.full(phi.shape, self.branch)
        side = _sides(phi, self.branch, math.atan2(self.frame[1], self.frame[0]), self.change_points())
        return np.broadcast_to(side, phi.shape).copy()

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        if self.family_shape or self.lenient:
            return self._solve_family(crank, order)
        # long arrays block by block, in the processor's cache (chapter 9)
        return solve_in_chunks(self._solve_block, crank, order, self.links)

    def _family_sides(self, phi: np.ndarray) -> np.ndarray | int:
        """The side of B per member (shape G + (1,)) or per member and position (G + (N,), where some member
        passes change points): the continuation rule of one linkage, member by member."""
        if not self.family_shape:
            return self.branch if self.keep_side or not self.change_points() else self.sides(phi)
        side = self.branch[..., np.newaxis]
        if self.keep_side:
            return side
        # a change point needs |d − L1| = |L2 − L3| or d + L1 = L2 + L3, decided exactly; only the members
        # within round-off of one are asked (rational arithmetic costs as much as a small solve)
        l1, l2, l3, (x, y) = self.crank, self.coupler, self.rocker, self.frame
        d = np.hypot(x, y)
        near = 1e-9 * (l1 + l2 + l3 + d)
        candidates = np.argwhere((np.abs(np.abs(d - l1) - np.abs(l2 - l3)) <= near) | (np.abs(d + l1 - l2 - l3) <= near))
        if not len(candidates):
            return side
        sides = np.array(np.broadcast_to(side, self.family_shape + phi.shape))
        for index in map(tuple, candidates):
            flips = _change_points_of(float(l1[index]), float(l2[index]), float(l3[index]),
                                      (float(x[index]), float(y[index])))
            if flips:
                sides[index] = _sides(phi, int(self.branch[index]), math.atan2(y[index], x[index]), flips)
        return sides

    def _solve_family(self, crank: AngleMotion, order: int) -> Solution:
        """A family (or a linkage solved leniently): every member at every crank angle, arrays G + (N,)."""
        phi = crank.value
        full, (l1, l2, l3, x, y) = self._family_columns(phi, self.crank, self.coupler, self.rocker, *self.frame)
        pin = family_pin(crank, l1)
        angle, origin = self._family_motions(crank, full, order)
        pivot = PointMotion(np.broadcast_to(x + 1j * y, full), *origin.derivatives()[1:order + 1])
        # the link angles of a family's positions are computed only if asked for (arctangents cost)
        joint = hinge(pin, pivot, l2, l3, self._family_sides(phi), phi, lenient=True, deferred_angles=True)
        assembled = np.asarray(joint.assembled)
        if not self.lenient and not assembled.all():
            self._family_failure(assembled, phi)
        return Solution(phi, order, angles={"crank": angle, "coupler": joint.angle_p, "rocker": joint.angle_q},
                        points={"O": origin, "A": pin, "B": joint.point, "C": pivot},
                        links=self.links, singular=joint.singular, assembled=assembled)

    def _family_failure(self, assembled: np.ndarray, phi: np.ndarray) -> None:
        """Raise the :class:`AssemblyError` of a family solved strictly, naming the first member that fails."""
        if not self.family_shape:
            self._solve_block(AngleMotion(phi), 0)     # one linkage: its own message, with its intervals
        first, failing = self._first_failing(assembled)
        member = FourBar(float(self.crank[first]), float(self.coupler[first]), float(self.rocker[first]),
                         (float(self.frame[0][first]), float(self.frame[1][first])), int(self.branch[first]))
        intervals = member.assembly_intervals()
        where = ("it assembles at no crank angle" if not intervals else "it assembles for crank angles in "
                 + " and ".join(describe_range(lo, hi) for lo, hi in intervals))
        label = ", ".join(map(str, first))
        raise AssemblyError(f"member {label} of the family cannot be assembled at some crank angles ({where}; "
                            f"{failing} in all; solve with lenient=True to mark "
                            "them instead)", phi[~assembled[first]])

    def _solve_block(self, crank: AngleMotion, order: int) -> Solution:
        phi = crank.value
        pin = crank_pin(crank, self.crank)
        pivot = fixed_point(self.pivot, phi, order)
        try:
            # one side for all positions unless the crank passes change points
            side = self.branch if self.keep_side or not self.change_points() else self.sides(phi)
            joint = hinge(pin, pivot, self.coupler, self.rocker, side, phi)
        except AssemblyError as error:
            intervals = self.assembly_intervals()
            reason = f"the four-bar cannot be assembled: {error.reason}"
            valid = None
            if len(intervals) == 1:
                valid = intervals[0]
            elif intervals:
                reason += " (it assembles for crank angles in " + " and ".join(
                    describe_range(lo, hi) for lo, hi in intervals) + ")"
            raise AssemblyError(reason, error.angles, valid, nowhere=not intervals) from None
        origin = fixed_point(0.0, phi, order)
        return Solution(phi, order,
                        angles={"crank": crank, "coupler": joint.angle_p, "rocker": joint.angle_q},
                        points={"O": origin, "A": pin, "B": joint.point, "C": pivot},
                        links=self.links, singular=joint.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        self.require_one_linkage("a drawing")
        return [Ground("O"), Ground("C"), Bar("crank", ("O", "A"), "crank"),
                Bar("coupler", ("A", "B"), "coupler"), Bar("rocker", ("C", "B"), "rocker")]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("A", "B"): self.coupler, ("C", "B"): self.rocker,
                ("O", "C"): abs(self.pivot)}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("coupler"), solution.angle("rocker")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        psi, xi = q
        # a family's dimensions per member (a row of positions each)
        l1, l2, l3, a, b = (np.asarray(v)[..., np.newaxis] if self.family_shape else v
                            for v in (self.crank, self.coupler, self.rocker, *self.frame))
        return (l1 * np.cos(phi) + l2 * np.cos(psi) - l3 * np.cos(xi) - a,
                l1 * np.sin(phi) + l2 * np.sin(psi) - l3 * np.sin(xi) - b)


# --- a family of four-bars solved at once --------------------------------------------------------------

@dataclass(frozen=True)
class FourBarFamily:
    """The kinematics of a family of four-bars (:func:`four_bar_family`): arrays of shape G + (N,), one row of
    N crank positions per member.

    Attributes
    ----------
    phi : ndarray, shape (N,)
        The crank angles φ (rad), the same for every member.
    angles : dict of AngleMotion
        ``crank`` (φ), ``coupler`` (ψ) and ``rocker`` (ξ) with their rates (1/s, 1/s²).
    points : dict of PointMotion
        ``A`` and ``B`` (m, m/s, m/s²; O and each member's C are fixed).
    assembled : ndarray of bool
        True where the member assembles at that crank angle; elsewhere every value is ``nan``.
    singular : ndarray of bool
        True where coupler and rocker are in line (rates unbounded, ``nan``).
    """

    phi: np.ndarray
    angles: dict[str, AngleMotion]
    points: dict[str, PointMotion]
    assembled: np.ndarray
    singular: np.ndarray


def four_bar_family(crank: ArrayLike, coupler: ArrayLike, rocker: ArrayLike, frame_x: ArrayLike, frame_y: ArrayLike,
                    phi: ArrayLike, omega: ArrayLike = 1.0, alpha: ArrayLike = 0.0, order: int = 2,
                    branch: ArrayLike = 1, lenient: bool = False) -> FourBarFamily:
    """Solve a family of four-bars at once: every member at every crank angle, one call.

    Parameters
    ----------
    crank, coupler, rocker : array_like
        L1, L2, L3 (m), positive: arrays of one shape G, or numbers (broadcast together).
    frame_x, frame_y : array_like
        The rocker pivot C = (x_C, y_C) of each member (m), likewise.
    phi : array_like
        The N crank angles φ (rad), one-dimensional, the same for every member.
    omega, alpha : float or array_like
        φ_t (1/s) and φ_tt (1/s²): one number or one per crank angle.
    order : int
        0, 1 or 2 time derivatives.
    branch : int or array_like of int
        σ = ±1 for every member, or one per member: B to the left (+1) or right (−1) of A → C, held at
        every crank angle (as ``FourBar(..., keep_side=True)``; change points are not continued).
    lenient : bool
        False: a member that does not assemble at some crank angle raises :class:`AssemblyError` naming
        it. True: those positions are marked in :attr:`FourBarFamily.assembled` and are ``nan``.

    Returns
    -------
    FourBarFamily
        Arrays of shape G + (N,).

    Notes
    -----
    It is ``FourBar(crank, coupler, rocker, (frame_x, frame_y), branch, keep_side=True, lenient=lenient)``
    solved at ``phi``: a family of :class:`FourBar`, whose blocks work on whole arrays, so that a family costs
    as much per member and position as one linkage does per position.
    """
    family = FourBar(crank, coupler, rocker, (frame_x, frame_y), branch, keep_side=True, lenient=lenient)
    solution = family.solve(phi, omega, alpha, order)
    return FourBarFamily(solution.phi, {name: solution.angle(name) for name in ("crank", "coupler", "rocker")},
                         {name: solution.point(name) for name in ("A", "B")}, solution.assembled, solution.singular)
