"""Layer 4: analysis of the four-bar — Grashof class, range of the crank, limit positions of the
rocker, time ratio, transmission angle and coupler curves (chapter 4).

Notation: L1 crank, L2 coupler, L3 rocker, d = |OC| frame; L_s, L_l the shortest and longest of
the four lengths, L_p, L_q the other two. The transmission angle μ is the angle at B between the
coupler and the rocker, 0 ≤ μ ≤ π.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .assignments import Quantity, Task, crank_speed, register_assignment, round_mm
from ..core.angles import wrap_angle
from ..linkages.base import Solution
from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_length
from ..linkages.four_bar import FourBar, _pqf
from ..core.motion import PointMotion

__all__ = [
    "GrashofClass",
    "grashof_class",
    "crank_range",
    "LimitPositions",
    "limit_positions",
    "transmission_angle",
    "transmission_extremes",
    "half_angle_terms",
    "half_angle_denominator_root",
    "coupler_curve",
    "StraightPart",
    "best_line",
    "straight_part",
]

_NAMES = {"crank": "crank-rocker", "frame": "double-crank", "coupler": "double-rocker", "rocker": "rocker-crank"}


@dataclass(frozen=True)
class GrashofClass:
    """Grashof class of a four-bar.

    Attributes
    ----------
    name : str
        ``crank-rocker`` (crank shortest), ``double-crank`` (frame shortest), ``double-rocker``
        (coupler shortest), ``rocker-crank`` (rocker shortest: the output turns fully, the
        input rocks) when L_s + L_l < L_p + L_q; ``change point`` when L_s + L_l = L_p + L_q; ``triple rocker``
        when L_s + L_l > L_p + L_q.
    shortest : str
        The role of the shortest link (``crank``, ``coupler``, ``rocker`` or ``frame``).
    margin : float
        (L_p + L_q) − (L_s + L_l) (m): positive for Grashof linkages, zero at a change point.
    crank_rotates : bool
        The crank (input) can turn a full revolution.
    """

    name: str
    shortest: str
    margin: float
    crank_rotates: bool


def grashof_class(crank: float, coupler: float, rocker: float, frame: float,
                  tolerance: float = 1e-9) -> GrashofClass:
    """Grashof's classification from the four lengths (m).

    ``tolerance`` is relative to the sum of the lengths: within it, L_s + L_l = L_p + L_q counts as a
    change-point linkage (one that passes change points). If two links are equally shortest, the first in the order crank, frame,
    coupler, rocker names the class.
    """
    lengths = {name: require_length(name, value)
               for name, value in (("crank", crank), ("frame", frame), ("coupler", coupler), ("rocker", rocker))}
    ordered = sorted(lengths.values())
    margin = (ordered[1] + ordered[2]) - (ordered[0] + ordered[3])
    shortest = min(lengths, key=lambda name: lengths[name])
    scale = sum(ordered)
    if abs(margin) <= tolerance * scale:
        name = "change-point linkage"
    elif margin > 0:
        name = _NAMES[shortest]
    else:
        name = "triple rocker"
    rotates = margin >= -tolerance * scale and shortest in ("crank", "frame")
    return GrashofClass(name, shortest, margin, rotates)


def crank_range(mechanism: FourBar) -> list[tuple[float, float]]:
    """Deprecated: ``mechanism.assembly_intervals()``, the one assembly-range API of every mechanism."""
    warnings.warn("crank_range(m) is deprecated: use m.assembly_intervals()", DeprecationWarning, stacklevel=2)
    return mechanism.assembly_intervals()


@dataclass(frozen=True)
class LimitPositions:
    """The two limit positions of the rocker of a crank-rocker.

    Attributes
    ----------
    phi : ndarray, shape (2,)
        Crank angles (rad) at the extended (crank and coupler in line, A between O and B)
        and the folded position, in [0, 2π).
    xi : ndarray, shape (2,)
        Rocker angles (rad) there.
    swing : float
        The rocker's angle of swing |ξ_ext − ξ_fold| (rad).
    forward : float
        Crank angle (rad) turned from the extended to the folded position (φ increasing).
    backward : float
        Crank angle (rad) from the folded back to the extended position, 2π − forward.
    time_ratio : float
        K = max(forward, backward)/min(forward, backward) ≥ 1 at constant crank speed.
    """

    phi: np.ndarray
    xi: np.ndarray
    swing: float
    forward: float
    backward: float
    time_ratio: float


def limit_positions(mechanism: FourBar) -> LimitPositions:
    """Limit (dead-centre) positions of the rocker and the time ratio of a crank-rocker.

    Notes
    -----
    The rocker turns back where ξ_t = 0, that is sin(ψ − φ) = 0: crank and coupler in line.
    Then |OB| = L2 + L1 (extended) or |L2 − L1| (folded), and B is an intersection of the circle
    of that radius about O with the circle of radius L3 about C; of the two intersections the
    one on the mechanism's branch is kept. When the rocker drives instead, the same positions are
    singular (toggle) positions: the crank cannot be driven through them. The time ratio is
    K = (π + θ_K)/(π − θ_K), θ_K the crank angle between the two positions less π.
    """
    if grashof_class(*mechanism.lengths).name != "crank-rocker":
        raise AssemblyError("limit positions of the rocker are defined here for a crank-rocker (shortest link "
                            f"the crank, L_s + L_l < L_p + L_q); this linkage is a {grashof_class(*mechanism.lengths).name}")
    l1, l2, l3, d = mechanism.lengths
    c = mechanism.pivot
    found: list[tuple[float, float]] = []
    for reach, sign in ((l2 + l1, 1.0), (l2 - l1, -1.0)):
        # intersections of |B| = reach and |B − C| = L3, in closed form (as in the hinge block)
        foot = (d**2 + reach**2 - l3**2) / (2.0 * d)
        height = math.sqrt(max(reach**2 - foot**2, 0.0))
        best: tuple[float, float, float] | None = None
        for side in (1.0, -1.0):
            b = (foot + 1j * side * height) * c / d
            phi = math.atan2(sign * b.imag, sign * b.real) % (2.0 * math.pi)   # in [0, 2π), as documented
            solved = mechanism.solve(np.array([phi]), order=0).point("B").value[0]
            error = abs(solved - b)
            if best is None or error < best[0]:
                best = (error, phi, math.atan2((b - c).imag, (b - c).real))
        assert best is not None
        found.append((best[1], best[2]))
    phis = np.array([f[0] for f in found])
    xi = np.array([f[1] for f in found])
    forward = (phis[1] - phis[0]) % (2.0 * math.pi)   # the angle turned forward: [0, 2π), not a wrap
    backward = 2.0 * math.pi - forward
    swing = abs(float(wrap_angle(xi[0] - xi[1])))
    return LimitPositions(phis, xi, swing, forward, backward, max(forward, backward) / min(forward, backward))


def transmission_angle(solution: Solution) -> np.ndarray:
    """Transmission angle μ (rad) at B between the coupler and the rocker, in [0, π].

    ``μ = |wrap(ψ − ξ)|``: the angle between the vectors B → A and B → C. A linkage runs well
    while μ stays away from 0 and π; 40°–140° is a common rule.
    """
    difference = solution.angle("coupler").value - solution.angle("rocker").value
    return np.abs(wrap_angle(difference))


def transmission_extremes(mechanism: FourBar) -> tuple[float, float]:
    """Smallest and largest transmission angle μ (rad) over the crank's range, analytically.

    Notes
    -----
    By the cosine law in triangle ABC, ``|AC|² = L2² + L3² − 2 L2 L3 cos μ``: μ grows with |AC|,
    which is extreme at φ = θ_OC (|AC| = |d − L1|) and φ = θ_OC + π (|AC| = d + L1), or at the limits
    of the crank range of a non-rotating crank (μ = 0 or π). Half-angle form:
    ``tan²(μ/2) = (|AC|² − (L2 − L3)²)/((L2 + L3)² − |AC|²)``.
    """
    l1, l2, l3, d = mechanism.lengths

    def mu(reach):
        inner, outer = abs(l2 - l3), l2 + l3
        reach = min(max(reach, inner), outer)   # outside the range the crank cannot go: μ = 0 or π
        return 2.0 * math.atan2(math.sqrt((reach - inner) * (reach + inner)),
                                math.sqrt((outer - reach) * (outer + reach)))

    return mu(abs(d - l1)), mu(d + l1)


def half_angle_terms(phi: ArrayLike, crank: float, coupler: float, rocker: float,
                     frame: tuple[float, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The coefficients 𝒫, 𝒬, ℱ of the four-bar's half-angle solution (the lecture's P, Q, F).

    Parameters
    ----------
    phi : array_like
        Crank angles φ (rad).
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    frame : tuple of float
        The rocker pivot C = (x_C, y_C) (m).

    Returns
    -------
    P, Q, F : ndarray
        𝒫, 𝒬, ℱ, arrays of the shape of ``phi`` (m): ``𝒫 = x_C − L1 cos φ``, ``𝒬 = y_C − L1 sin φ``,
        ``ℱ = (𝒫² + 𝒬² + L2² − L3²)/(2 L2)``.

    Notes
    -----
    Chapters 2 and 4 (Alyushin, 2008): the coupler angle ψ solves ``𝒫 cos ψ + 𝒬 sin ψ = ℱ``; the
    half-angle formula ``ψ = 2 arctan[(𝒬 ± √(𝒬² + 𝒫² − ℱ²))/(𝒫 + ℱ)]``
    (:func:`mechanisms.linkages.four_bar.half_angle_coupler_angle`) divides by ``𝒫 + ℱ``, whose root
    :func:`half_angle_denominator_root` finds (chapter 9).
    """
    return _pqf(phi, crank, coupler, rocker, frame)


def half_angle_denominator_root(low: float, high: float, crank: float, coupler: float, rocker: float,
                                frame: tuple[float, float], *, extended: bool = False) -> float:
    """The crank angle between two others where the half-angle formula's denominator 𝒫 + ℱ is zero.

    Parameters
    ----------
    low, high : float
        Crank angles φ (rad) at which 𝒫 + ℱ has opposite signs.
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    frame : tuple of float
        The rocker pivot C = (x_C, y_C) (m).
    extended : bool
        Evaluate 𝒫 + ℱ in extended precision (``numpy.longdouble``, whose sine and cosine are the C
        library's, the same on every x86-64 processor) instead of double: the root is then the same
        on every machine, where double precision's sine and cosine may differ in their last bit.

    Returns
    -------
    float
        The root φ (rad), to the last bit of double precision: the end of the final bracket at which
        𝒫 + ℱ has the sign it has at ``low``.

    Raises
    ------
    InvalidParameterError
        If 𝒫 + ℱ has the same sign at ``low`` and ``high``.

    Notes
    -----
    Bisection of [low, high] with :func:`half_angle_terms` (𝒫, 𝒬, ℱ of chapters 2 and 4): each step
    halves the bracket, keeping the half whose ends have opposite signs, until its midpoint equals one
    of its ends. Chapter 9 measures the half-angle formula's error near this root.
    """
    dtype = np.longdouble if extended else float

    def denominator(angle: float) -> float:
        p, _, f = _pqf(np.array([angle]), crank, coupler, rocker, frame, dtype)
        return float((p + f)[0])

    sign = math.copysign(1.0, denominator(low))
    if sign * denominator(high) > 0:
        raise InvalidParameterError("high", high, f"a crank angle (rad) at which P + F has the other sign "
                                    f"than at low = {low} rad")
    while True:
        middle = 0.5 * (low + high)
        if middle in (low, high):
            return low
        if sign * denominator(middle) > 0:
            low = middle
        else:
            high = middle


def coupler_curve(mechanism: FourBar, along: float, left: float = 0.0, positions: int = 361) -> PointMotion:
    """Positions of a point of the coupler over the crank's range (the coupler curve).

    Parameters
    ----------
    along, left : float
        The point's coordinates on the coupler: u (m) along A → B, w (m) to its left.
    positions : int
        Number of crank positions over the range (a full turn, or each assembly interval).

    Returns
    -------
    PointMotion
        Positions only (order 0), in the order of the motion: over a full turn for a rotating
        crank; for a rocking crank from one limit of its interval to the other on the
        mechanism's branch and back on the other branch, so that the curve closes (at a limit
        of assembly the motion passes from one branch to the other). A crank with two
        separate intervals gives two closed curves, one after the other.
    """
    intervals = mechanism.assembly_intervals()
    if not intervals:
        raise AssemblyError("the four-bar assembles at no crank angle")
    pieces = []
    for lo, hi in intervals:
        phi = np.linspace(lo, hi, positions)
        if hi - lo < 2.0 * math.pi - 1e-12:
            # a rocking crank: go to the limit and come back on the other branch (the motion
            # passes the limit with the rocker and coupler in line)
            shrink = 1e-12 * (hi - lo)
            phi = np.linspace(lo + shrink, hi - shrink, positions)
            forward = mechanism.solve(phi, order=0).point_on("coupler", along, left).value
            mirror = FourBar(mechanism.crank, mechanism.coupler, mechanism.rocker, mechanism.frame,
                             -mechanism.branch)
            back = mirror.solve(phi[::-1], order=0).point_on("coupler", along, left).value
            pieces.append(np.concatenate([forward, back, forward[:1]]))
        else:
            pieces.append(mechanism.solve(phi, order=0).point_on("coupler", along, left).value)
    return PointMotion(np.concatenate(pieces))


@dataclass(frozen=True)
class StraightPart:
    """A nearly straight part of a point's path.

    Attributes
    ----------
    phi : (float, float)
        Crank angles (rad) at its ends.
    length : float
        Its length along the best line (m): the extent of the points' projections.
    deviation : float
        The largest distance of a point of the part from the best line (m).
    point, direction : complex
        The best line: through ``point`` along the unit vector ``direction``.
    """

    phi: tuple[float, float]
    length: float
    deviation: float
    point: complex
    direction: complex


def best_line(points: np.ndarray) -> tuple[complex, complex, float, float]:
    """The total-least-squares line of points ``x + iy``: (point, direction, length, deviation).

    The line passes through the centroid along the principal direction of the points (the
    singular vector of their centred coordinates); ``length`` is the extent of the projections
    on it and ``deviation`` the largest distance from it (m).
    """
    points = np.asarray(points, dtype=complex)
    centre = points.mean()
    arms = points - centre
    _, _, vt = np.linalg.svd(np.column_stack([arms.real, arms.imag]), full_matrices=False)
    direction = complex(vt[0, 0], vt[0, 1])
    along = (np.conj(direction) * arms).real
    across = (np.conj(direction) * arms).imag
    return complex(centre), direction, float(np.ptp(along)), float(np.max(np.abs(across)))


def straight_part(phi: np.ndarray, points: np.ndarray, centre: int | None = None, tolerance: float = 0.01, *,
                  centre_angle: float | None = None) -> StraightPart:
    """The longest stretch of a path, symmetric about one sample, within ``tolerance`` of a line.

    Parameters
    ----------
    phi : ndarray
        Crank angles φ (rad) of the samples, in order along the path.
    points : ndarray of complex
        The path ``x + iy`` (m) at those angles.
    centre : int, optional
        Index of the sample at the middle of the straight part (e.g. on an axis of symmetry).
    tolerance : float
        Largest distance (m) from the best line allowed; 0.01 m unless given.
    centre_angle : float, optional
        The crank angle φ (rad) at the middle of the straight part, instead of ``centre``: the
        sample whose angle is nearest to it (angles compared modulo 2π) is the middle.

    Returns
    -------
    StraightPart
        The crank angles at its ends, its length, its largest deviation and its best line.

    Raises
    ------
    ValueError
        If both or neither of ``centre`` and ``centre_angle`` are given, or if no stretch of three
        samples about the middle lies within the tolerance.

    Notes
    -----
    The window grows one sample on each side at a time while the deviation of the best line
    (:func:`best_line`, total least squares) stays within the tolerance (chapter 4, Chebyshev's
    lambda mechanism).
    """
    phi = np.asarray(phi, dtype=float)
    points = np.asarray(points, dtype=complex)
    if (centre is None) == (centre_angle is None):
        raise ValueError("give the middle of the straight part either as a sample index (centre) or as a "
                         "crank angle in rad (centre_angle), not both")
    if centre_angle is not None:
        centre = int(np.argmin(np.abs(wrap_angle(phi - centre_angle))))
    assert centre is not None
    best = None
    for half in range(1, min(centre, points.size - 1 - centre) + 1):
        window = points[centre - half:centre + half + 1]
        line = best_line(window)
        if line[3] > tolerance:
            break
        best = (half, line)
    if best is None:
        raise ValueError(f"no straight part within {tolerance:g} m around sample {centre}")
    half, (point, direction, length, deviation) = best
    return StraightPart((float(phi[centre - half]), float(phi[centre + half])), length, deviation, point, direction)


# --- the four-bar's assignment (python -m mechanisms assign four-bar) ---------------------------------------------------------------------------

FOUR_BAR_TRANSMISSION_DEG = (35.0, 145.0)
"""The transmission angle μ of a four-bar variant stays within these bounds (degrees)."""
FOUR_BAR_GRASHOF_MARGIN = 0.02
"""(L_p + L_q) − (L_s + L_l) of a four-bar variant is at least this fraction of the sum of the lengths."""


def _sample_four_bar(rng: np.random.Generator) -> tuple[FourBar, float]:
    d = rng.uniform(0.20, 0.40)
    direction = math.radians(rng.uniform(-15.0, 15.0))
    frame = (round_mm(d * math.cos(direction)), round_mm(d * math.sin(direction)))
    crank = round_mm(rng.uniform(0.15, 0.35) * d)
    coupler = round_mm(rng.uniform(0.70, 1.40) * d)
    rocker = round_mm(rng.uniform(0.50, 1.20) * d)
    branch = int(rng.choice([1, -1]))
    return FourBar(crank=crank, coupler=coupler, rocker=rocker, frame=frame, branch=branch), crank_speed(rng, 20, 120)


def _check_four_bar(mechanism: FourBar) -> list[str]:
    problems = []
    grashof = grashof_class(*mechanism.lengths)
    if grashof.name != "crank-rocker":
        problems.append(f"it is a {grashof.name}, not a crank-rocker")
    elif grashof.margin < FOUR_BAR_GRASHOF_MARGIN * sum(mechanism.lengths):
        problems.append("it is too close to a change-point linkage (Grashof margin)")
    else:
        low, high = (math.degrees(mu) for mu in transmission_extremes(mechanism))
        if low < FOUR_BAR_TRANSMISSION_DEG[0] or high > FOUR_BAR_TRANSMISSION_DEG[1]:
            problems.append(f"its transmission angle ranges over [{low:.1f}°, {high:.1f}°], outside "
                            f"[{FOUR_BAR_TRANSMISSION_DEG[0]:g}°, {FOUR_BAR_TRANSMISSION_DEG[1]:g}°]")
    return problems


def _data_four_bar(m: FourBar) -> list[tuple[str, str, str, str]]:
    side = "left" if m.branch == 1 else "right"
    return [("L_1", "crank length |OA|", f"{m.crank:.3f}", "m"),
            ("L_2", "coupler length |AB|", f"{m.coupler:.3f}", "m"),
            ("L_3", "rocker length |CB|", f"{m.rocker:.3f}", "m"),
            ("(x_C, y_C)", "rocker pivot C", f"({m.frame[0]:.3f}, {m.frame[1]:.3f})", "m"),
            ("", "assembly (branch)", f"{m.branch:+d}: B to the {side} of the line from A to C", "")]


register_assignment(Task(
    "four-bar", "Crank-rocker four-bar", _sample_four_bar, _check_four_bar, _data_four_bar,
    (Quantity("coupler.angle_deg", "ψ", "coupler angle, of the vector A→B from +x, counter-clockwise", "°"),
     Quantity("rocker.angle_deg", "ξ", "rocker angle, of the vector C→B from +x, counter-clockwise", "°"),
     Quantity("coupler.omega", "ψ_t", "angular velocity of the coupler (positive counter-clockwise)", "1/s"),
     Quantity("rocker.omega", "ξ_t", "angular velocity of the rocker (positive counter-clockwise)", "1/s"),
     Quantity("coupler.alpha", "ψ_tt", "angular acceleration of the coupler", "1/s²"),
     Quantity("rocker.alpha", "ξ_tt", "angular acceleration of the rocker", "1/s²")),
    "Grashof's condition holds with the crank the shortest link (a crank-rocker), at least "
    f"{100 * FOUR_BAR_GRASHOF_MARGIN:g} % of the sum of the lengths away from a change point, and the "
    f"transmission angle stays between {FOUR_BAR_TRANSMISSION_DEG[0]:g}° and {FOUR_BAR_TRANSMISSION_DEG[1]:g}° "
    "over the whole revolution"))
