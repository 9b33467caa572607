"""Layer 4: synthesis of four-bars (chapter 12) — a crank-rocker for a rocker swing and a time ratio,
function generation by Freudenstein's equation, motion generation through two or three positions of
a body, and the four-bar whose output is the coupler, from the time ratio K and the transmission
angle μ₁ in the first limit position (Zaitsev and Evgrafov), each with its check by simulation.

The coupler-output design (Zaitsev and Evgrafov):

The coupler of a four-bar turns back (ψ_t = 0) where crank and rocker are parallel:
ψ_t = −φ_t L₁ sin(φ − ξ)/(L₂ sin(ψ − ξ)) vanishes at φ = ξ and at φ = ξ + π. The paper places
the first limit position with the crank along +x (φ = 0) and the rocker pointing along −x
(ξ = π, antiparallel), the coupler at the angle π − μ₁, and the second at the crank angle
φ_x = 2π/(K + 1) (the return stroke) with crank and rocker parallel (ξ = φ_x). Its formulas
(rocker length L₃ given; the paper writes a, λ, K_v, γ for the book's c, Λ, K, μ₁):

    c = 2 L₃ cos(φ_x/2),  Λ = cot²(φ_x/2 + μ₁),  L₂ = c(Λ + 1) + c√(Λ(Λ + 1)),
    L₁ = √((2 L₂ c − c²)/(2(1 − cos φ_x))),  C = (L₃ − L₂ cos μ₁ + L₁, L₂ sin μ₁).

The two limit positions give one loop-closure equation for the two unknowns L₁, L₂; the
paper's formulas pick the member of that one-parameter family in which the coupler in the
second limit position lies along the chord B₀B_x of the rocker's end (so that its transmission
angle there is φ_x/2). Chapter 12 checks every design by simulating it with
:class:`~mechanisms.FourBar`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..core.angles import wrap_angle
from ..core.errors import AssemblyError, InvalidParameterError, SingularPositionWarning
from ..core.validate import require_finite, require_finite_array, require_length
from ..linkages.four_bar import FourBar
from .four_bar import grashof_class, transmission_angle, transmission_extremes

__all__ = [
    "CouplerOutputDesign",
    "return_angle",
    "synthesize_coupler_output",
    "coupler_length_asymptote",
    "closure_residual",
    "DesignCheck",
    "check_design",
    "largest_rotatable_angle",
    "time_ratio_angle",
    "CrankRockerDesign",
    "free_angle_range",
    "crank_rocker_for_swing",
    "minimum_transmission",
    "best_crank_rocker",
    "chebyshev_spacing",
    "freudenstein_coefficients",
    "function_generator",
    "pole",
    "body_positions",
    "centre_point",
    "circle_point",
    "MotionDesign",
    "four_bar_through_positions",
    "MotionCheck",
    "check_motion",
]


class _DesignedFourBar:
    """What every design of this module has: L₁, L₂, L₃, the pivot C and the branch σ (no fields of its
    own: each design is a dataclass that declares them)."""

    crank: float
    coupler: float
    rocker: float
    frame: tuple[float, float]
    branch: int

    def four_bar(self) -> FourBar:
        """The designed linkage as a :class:`~mechanisms.FourBar`."""
        return FourBar(self.crank, self.coupler, self.rocker, self.frame, self.branch)


@dataclass(frozen=True)
class CouplerOutputDesign(_DesignedFourBar):
    """A four-bar designed by the paper's formulas.

    Attributes
    ----------
    crank, coupler, rocker : float
        L₁, L₂, L₃ (m).
    frame : (float, float)
        Rocker pivot C = (x_C, y_C) (m).
    time_ratio : float
        The asked time ratio K.
    transmission_angle : float
        The asked μ₁ (rad), the transmission angle in the first limit position.
    return_angle : float
        φ_x = 2π/(K + 1) (rad).
    branch : int
        The branch of :class:`~mechanisms.FourBar` on which B is in the designed first
        limit position.
    """

    crank: float
    coupler: float
    rocker: float
    frame: tuple[float, float]
    time_ratio: float
    transmission_angle: float
    return_angle: float
    branch: int


def return_angle(time_ratio: float) -> float:
    """Crank angle of the return stroke φ_x = 2π/(K + 1) (rad) at constant crank speed."""
    k = require_finite("time_ratio", time_ratio)
    if k < 1.0:
        raise InvalidParameterError("time_ratio", time_ratio, "a time ratio K ≥ 1")
    return 2.0 * math.pi / (k + 1.0)


def coupler_length_asymptote(time_ratio: float) -> float:
    """The transmission angle μ₁ (rad) at which the paper's coupler length L₂ grows without bound.

    Λ = cot²(φ_x/2 + μ₁) → ∞ where φ_x/2 + μ₁ → π: μ₁ → π − φ_x/2 (the paper's 180° − φ_x/2).
    """
    return math.pi - 0.5 * return_angle(time_ratio)


def synthesize_coupler_output(time_ratio: float, transmission_angle: float, rocker: float = 1.0,
                              corrected: bool = False) -> CouplerOutputDesign:
    """Lengths and frame of a four-bar with the coupler as output, by the paper's formulas.

    Parameters
    ----------
    time_ratio : float
        The time ratio K > 1: working stroke over return stroke, in crank angle.
    transmission_angle : float
        μ₁ (rad), 0 < μ₁ < π: the transmission angle in the first limit position.
    rocker : float
        L₃ (m); every length scales with it.
    corrected : bool
        False: the paper's ``L₂ = c(Λ + 1) + c√(Λ(Λ + 1))`` as printed. True: the form
        ``L₂ = c/(1 + cos(φ_x/2 + μ₁))``, equal to the printed one for π/2 ≤ φ_x/2 + μ₁ < π and
        right also below π/2, where squaring the cotangent in Λ lost its sign (the errata appendix).

    Returns
    -------
    CouplerOutputDesign
        The formulas are applied as printed; whether the result is a crank-rocker that reaches
        K and μ₁ is for :func:`check_design` to say.
    """
    phi_x = return_angle(time_ratio)
    if not time_ratio > 1.0:
        raise InvalidParameterError("time_ratio", time_ratio,
                                    "a time ratio K > 1 (at K = 1 the synthesized crank has no length)")
    gamma = require_finite("transmission_angle", transmission_angle)
    if not 0.0 < gamma < math.pi:
        raise InvalidParameterError("transmission_angle", transmission_angle, "an angle μ₁ in (0, π) rad")
    l3 = require_length("rocker", rocker)
    a = 2.0 * l3 * math.cos(0.5 * phi_x)
    if abs(0.5 * phi_x + gamma - math.pi) < 1e-9:
        raise InvalidParameterError("transmission_angle", transmission_angle,
                                    "away from the asymptote μ₁ = π − φ_x/2, where the coupler length is unbounded")
    if corrected:
        l2 = a / (1.0 + math.cos(0.5 * phi_x + gamma))
    else:
        lam = 1.0 / math.tan(0.5 * phi_x + gamma) ** 2
        l2 = a * (lam + 1.0) + a * math.sqrt(lam * (lam + 1.0))
    l1 = math.sqrt((2.0 * l2 * a - a * a) / (2.0 * (1.0 - math.cos(phi_x))))
    frame = (l3 - l2 * math.cos(gamma) + l1, l2 * math.sin(gamma))
    # B in the first limit position: C − L3 (rocker along −x); its side of the line A1 → C
    a1, c = complex(l1, 0.0), complex(*frame)
    b1 = c - l3
    side = (np.conj(c - a1) * (b1 - a1)).imag
    return CouplerOutputDesign(l1, l2, l3, frame, float(time_ratio), gamma, phi_x, 1 if side >= 0 else -1)


def closure_residual(design: CouplerOutputDesign) -> float:
    """| |B_x − A_x| − L₂ | (m) in the second limit position, from the geometry alone.

    A_x = L₁ e^{iφ_x}, B_x = C + L₃ e^{iφ_x} (crank and rocker parallel). Zero when the paper's
    two limit positions belong to one linkage; an independent check of its formulas.
    """
    e = complex(math.cos(design.return_angle), math.sin(design.return_angle))
    c = complex(*design.frame)
    return abs(abs(c + design.rocker * e - design.crank * e) - design.coupler)


@dataclass(frozen=True)
class DesignCheck:
    """A synthesized design, simulated.

    Attributes
    ----------
    grashof : str
        Grashof class of the linkage.
    crank_rotates : bool
        The crank turns a full revolution.
    singular : bool
        Somewhere on the motion the coupler and rocker are in line (the linkage locks or
        branches); always the case if the crank does not rotate.
    limit_angles : ndarray
        Crank angles (rad) where the coupler turns back (ψ_t = 0), found by simulation.
    time_ratio : float
        The time ratio K reached (nan if the crank does not rotate).
    first_angle, second_angle : float
        Transmission angles μ (rad) in the two limit positions (the one nearer φ = 0 first).
    minimum_angle : float
        Smallest transmission angle min(μ, π − μ) over the whole turn (rad).
    """

    grashof: str
    crank_rotates: bool
    singular: bool
    limit_angles: np.ndarray
    time_ratio: float
    first_angle: float
    second_angle: float
    minimum_angle: float


_ROUND_OFF = 1e-12
"""|sin(φ − ξ)| at or below which a grid crank angle is itself a limit position (round-off of
φ − ξ is ~1e-15 rad; a root within 1e-12 rad of a grid point is found to that accuracy)."""


def _refine(mechanism: FourBar, lo: np.ndarray, hi: np.ndarray, g_lo: np.ndarray,
            iterations: int = 60) -> np.ndarray:
    """Bisection on g(φ) = sin(φ − ξ(φ)) (crank parallel to rocker) within brackets [lo, hi].

    ``g_lo`` are the values at ``lo`` that chose the brackets: computing them again could give
    the other sign where g(lo) is at round-off level (a limit position on the grid), and the
    bisection would then run to the wrong end of the bracket.
    """
    def g(phi):
        return np.sin(phi - mechanism.solve(phi, order=0).angle("rocker").value)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        g_mid = g(mid)
        left = np.sign(g_mid) == np.sign(g_lo)
        lo, g_lo = np.where(left, mid, lo), np.where(left, g_mid, g_lo)
        hi = np.where(left, hi, mid)
    return 0.5 * (lo + hi)


def _limit_positions(mechanism: FourBar, phi: np.ndarray, g: np.ndarray, crossing: np.ndarray) -> np.ndarray:
    """Crank angles where g = sin(φ − ξ) changes sign between ``phi[crossing]`` and the next grid
    angle: a grid angle where g is at round-off level is the limit position itself (the sign of
    g there is noise, which bracket it lands in is not), the others refined by bisection."""
    lo, hi, g_lo, g_hi = phi[crossing], phi[crossing + 1], g[crossing], g[crossing + 1]
    refined = _refine(mechanism, lo, hi, g_lo)
    return np.where(np.abs(g_lo) <= _ROUND_OFF, lo, np.where(np.abs(g_hi) <= _ROUND_OFF, hi, refined))


def check_design(design: CouplerOutputDesign, positions: int = 3600) -> DesignCheck:
    """Simulate a design over a turn of the crank and measure what it reaches.

    The limit positions of the coupler are found where sin(φ − ξ) changes sign on a grid of
    ``positions`` crank angles from −φ_x/4 (so that the designed position φ = 0 lies inside)
    and refined by bisection (a grid angle where sin(φ − ξ) is at round-off level is a limit
    position itself); the time ratio is the larger crank angle between them over the
    smaller.
    """
    mechanism = design.four_bar()
    kind = grashof_class(*mechanism.lengths)
    if not kind.crank_rotates or kind.name == "change-point linkage":
        return DesignCheck(kind.name, kind.crank_rotates, True, np.array([]), math.nan, math.nan, math.nan, 0.0)
    start = -0.25 * design.return_angle
    phi = start + np.linspace(0.0, 2.0 * math.pi, positions + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        solution = mechanism.solve(phi, order=0)
    g = np.sin(phi - solution.angle("rocker").value)
    mu = transmission_angle(solution)
    crossing = np.nonzero((g[:-1] > 0) != (g[1:] > 0))[0]
    crossing = crossing[crossing < positions]   # the last grid point repeats the first
    if crossing.size != 2:
        # not a simple oscillation of the coupler: report the turning points, no time ratio
        limits = _limit_positions(mechanism, phi, g, crossing)
        return DesignCheck(kind.name, kind.crank_rotates, bool(np.any(np.minimum(mu, math.pi - mu) < 1e-6)),
                           limits, math.nan, math.nan, math.nan, float(np.min(np.minimum(mu, math.pi - mu))))
    limits = _limit_positions(mechanism, phi, g, crossing)
    at_limits = transmission_angle(mechanism.solve(limits, order=0))
    stroke = limits[1] - limits[0]
    ratio = max(stroke, 2.0 * math.pi - stroke) / min(stroke, 2.0 * math.pi - stroke)
    singular = bool(np.any(np.minimum(mu, math.pi - mu) < 1e-6))
    return DesignCheck(kind.name, kind.crank_rotates, singular, limits, float(ratio), float(at_limits[0]),
                       float(at_limits[1]), float(np.min(np.minimum(mu, math.pi - mu))))


def largest_rotatable_angle(time_ratio: float, rocker: float = 1.0, tolerance: float = 1e-10) -> float:
    """The largest μ₁ (rad) for which the design (corrected formula) still has a fully rotating crank.

    Bisection on μ₁ in (0, π − φ_x/2) on the Grashof condition of the synthesized lengths: small
    μ₁ gives a crank-rocker, μ₁ near the asymptote a linkage whose crank cannot turn (the rocker is
    then the shortest link). The boundary is a change-point linkage.
    """
    lo, hi = 1e-3, coupler_length_asymptote(time_ratio) - 1e-9

    def rotates(gamma: float) -> bool:
        design = synthesize_coupler_output(time_ratio, gamma, rocker, corrected=True)
        kind = grashof_class(design.crank, design.coupler, design.rocker, math.hypot(*design.frame))
        return kind.crank_rotates and kind.name != "change-point linkage"

    if not rotates(lo):
        raise InvalidParameterError("time_ratio", time_ratio,
                                    "a time ratio whose designs at small μ₁ have a fully rotating crank (below "
                                    "K ≈ 1.001 the crank is too short against the tolerance of Grashof's test)")
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rotates(mid) else (lo, mid)
    return 0.5 * (lo + hi)


# --- a crank-rocker for a rocker swing and a time ratio (chapter 12) --------------------------------

def time_ratio_angle(time_ratio: float) -> float:
    """θ_K = π(K − 1)/(K + 1) (rad): the crank angle between the two limit positions, less π.

    The working stroke takes the crank angle π + θ_K, the return stroke π − θ_K, so that
    K = (π + θ_K)/(π − θ_K) at constant crank speed.
    """
    k = require_finite("time_ratio", time_ratio)
    if k < 1.0:
        raise InvalidParameterError("time_ratio", time_ratio, "a time ratio K ≥ 1")
    return math.pi * (k - 1.0) / (k + 1.0)


def _swing(swing: float) -> float:
    value = require_finite("swing", swing)
    if not 0.0 < value < math.pi:
        raise InvalidParameterError("swing", swing, "a rocker swing Δξ in (0, π) rad")
    return value


def free_angle_range(swing: float, time_ratio: float) -> tuple[float, float]:
    """The interval (ν_lo, ν_hi) (rad) of free angles ν that give a crank-rocker with this swing and K.

    ν is the angle at the extended limit position B₁ between the chord B₁ → B₂ and the line
    B₁ → O (positive towards the rocker pivot C, negative away from it); ν = 0 itself is excluded
    (O would fall on B₂). The bounds are where O, C and B₁ or B₂ come into line (beyond them B₁
    and B₂ lie on opposite sides of the frame line OC and the linkage swings otherwise; the crank
    would vanish only at |ν| = π/2 − θ_K/2, beyond these bounds):

        ν_hi = min(π/2 − Δξ/2, π/2 − θ_K + Δξ/2),  ν_lo = −max(0, π/2 − Δξ/2 − θ_K).
    """
    delta, theta = _swing(swing), time_ratio_angle(time_ratio)
    if theta <= 0.0:
        raise InvalidParameterError("time_ratio", time_ratio,
                                    "a time ratio K > 1 (at K = 1 the crank pivot lies on the line B₁B₂)")
    high = min(0.5 * math.pi - 0.5 * delta, 0.5 * math.pi - theta + 0.5 * delta)
    low = -max(0.0, 0.5 * math.pi - 0.5 * delta - theta)
    if high <= 0.0:
        raise InvalidParameterError("swing", swing, f"a swing for which some crank-rocker reaches K = {time_ratio:g} "
                                    "(Δξ/2 < π/2 and θ_K < π/2 + Δξ/2)")
    return low, high


def _circumcentre(z1: complex, z2: complex, z3: complex, name: str) -> complex:
    """Centre of the circle through three points (complex, m); raise if they are in line."""
    b, c = z2 - z1, z3 - z1
    cross = (b.conjugate() * c).imag
    scale = max(abs(b), abs(c)) ** 2
    if abs(cross) <= 1e-12 * scale:
        raise InvalidParameterError(name, "three points in line",
                                    "three positions that do not lie on one straight line")
    return z1 + 1j * (abs(c) ** 2 * b - abs(b) ** 2 * c) / (2.0 * cross)


def _side(a: complex, c: complex, b: complex) -> int:
    """+1 if B is to the left of the directed line A → C (the four-bar's branch σ), else −1."""
    return 1 if ((c - a).conjugate() * (b - a)).imag >= 0.0 else -1


@dataclass(frozen=True)
class CrankRockerDesign(_DesignedFourBar):
    """A crank-rocker designed for a rocker swing Δξ and a time ratio K (the classical construction).

    The crank pivot O is at the origin and the rocker pivot C = (d, 0) on the +x axis.

    Attributes
    ----------
    crank, coupler, rocker : float
        L₁, L₂, L₃ (m).
    frame : (float, float)
        C = (d, 0) (m).
    branch : int
        The branch σ of :class:`~mechanisms.FourBar` on which the rocker reaches B₁ and B₂.
    swing, time_ratio, free_angle : float
        The asked Δξ (rad) and K, and the chosen free angle ν (rad).
    extended, folded : complex
        B₁ (crank and coupler stretched in line, |OB₁| = L₂ + L₁) and B₂ (folded, |OB₂| = L₂ − L₁) (m).
    circle_centre : complex
        Centre of the circle through O, B₁ and B₂ on which the chord B₁B₂ is seen at the angle θ_K (m).
    circle_radius : float
        Its radius c/(2 sin θ_K), c = |B₁B₂| = 2 L₃ sin(Δξ/2) (m).
    """

    crank: float
    coupler: float
    rocker: float
    frame: tuple[float, float]
    branch: int
    swing: float
    time_ratio: float
    free_angle: float
    extended: complex
    folded: complex
    circle_centre: complex
    circle_radius: float


def crank_rocker_for_swing(swing: float, time_ratio: float, free_angle: float,
                           rocker: float = 1.0) -> CrankRockerDesign:
    """The crank-rocker whose rocker swings through Δξ with the time ratio K, for a free angle ν.

    Parameters
    ----------
    swing : float
        Δξ (rad), 0 < Δξ < π: the angle between the rocker's two limit positions.
    time_ratio : float
        K > 1.
    free_angle : float
        ν (rad) in :func:`free_angle_range`: the angle at B₁ from the chord B₁ → B₂ to the line B₁ → O.
    rocker : float
        L₃ (m); every length scales with it.

    Notes
    -----
    In the triangle O B₁ B₂ the angle at O is θ_K (:func:`time_ratio_angle`) and the angle at B₁
    is |ν|; the law of sines gives |OB₁| = c sin(θ_K + |ν|)/sin θ_K and |OB₂| = c sin|ν|/sin θ_K,
    and L₁ = (|OB₁| − |OB₂|)/2, L₂ = (|OB₁| + |OB₂|)/2, that is

        L₁ = c cos(|ν| + θ_K/2)/(2 cos(θ_K/2)),  L₂ = c sin(|ν| + θ_K/2)/(2 sin(θ_K/2)).
    """
    delta, theta = _swing(swing), time_ratio_angle(time_ratio)
    nu = require_finite("free_angle", free_angle)
    low, high = free_angle_range(delta, time_ratio)
    l3 = require_length("rocker", rocker)
    if not low < nu < high or nu == 0.0:
        raise InvalidParameterError("free_angle", free_angle,
                                    f"a free angle ν in ({low:.6g}, {high:.6g}) rad, not 0, for Δξ = {delta:.6g} rad "
                                    f"and K = {time_ratio:g}")
    chord = 2.0 * l3 * math.sin(0.5 * delta)
    l1 = chord * math.cos(abs(nu) + 0.5 * theta) / (2.0 * math.cos(0.5 * theta))
    l2 = chord * math.sin(abs(nu) + 0.5 * theta) / (2.0 * math.sin(0.5 * theta))
    # the construction with C at the origin, the chord B1 -> B2 along +x above it
    b1 = l3 * complex(math.cos(0.5 * math.pi + 0.5 * delta), math.sin(0.5 * math.pi + 0.5 * delta))
    b2 = l3 * complex(math.cos(0.5 * math.pi - 0.5 * delta), math.sin(0.5 * math.pi - 0.5 * delta))
    o = b1 + (l1 + l2) * complex(math.cos(nu), -math.sin(nu))
    # the book's frame: O at the origin, C on +x
    d = abs(o)
    turn = (-o).conjugate() / d

    def moved(z: complex) -> complex:
        return ((z - o) * turn).conjugate()    # mirrored: the rocker above the frame line

    e1, e2 = moved(b1), moved(b2)
    pin = l1 * e1 / abs(e1)
    radius = chord / (2.0 * math.sin(theta))
    return CrankRockerDesign(l1, l2, l3, (d, 0.0), _side(pin, complex(d, 0.0), e1), delta, float(time_ratio), nu,
                             e1, e2, _circumcentre(0j, e1, e2, "free_angle"), radius)


def minimum_transmission(mechanism: FourBar) -> float:
    """The smallest deviation-free transmission angle over a turn, min(μ_min, π − μ_max) (rad)."""
    low, high = transmission_extremes(mechanism)
    return min(low, math.pi - high)


def best_crank_rocker(swing: float, time_ratio: float, rocker: float = 1.0) -> CrankRockerDesign:
    """The design of :func:`crank_rocker_for_swing` whose :func:`minimum_transmission` is largest.

    The free angle ν is sampled on both sides of the chord (401 values on each) and the best
    sample refined by golden-section search between its neighbours, to about 1e-10 rad.
    """
    low, high = free_angle_range(swing, time_ratio)

    def score(nu: float) -> float:
        return minimum_transmission(crank_rocker_for_swing(swing, time_ratio, nu, rocker).four_bar())

    best: tuple[float, float, float, float] | None = None
    for lo, hi in ((low, 0.0), (0.0, high)):
        if hi - lo <= 0.0:
            continue
        grid = np.linspace(lo, hi, 403)[1:-1]
        values = [score(float(nu)) for nu in grid]
        i = int(np.argmax(values))
        left = float(grid[i - 1]) if i > 0 else lo + 1e-12 * (hi - lo)
        right = float(grid[i + 1]) if i + 1 < grid.size else hi - 1e-12 * (hi - lo)
        if best is None or values[i] > best[0]:
            best = (values[i], left, right, float(grid[i]))
    assert best is not None
    _, a, b, _ = best
    ratio = 0.5 * (math.sqrt(5.0) - 1.0)
    x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
    f1, f2 = score(x1), score(x2)
    while b - a > 1e-10:
        if f1 >= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - ratio * (b - a)
            f1 = score(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + ratio * (b - a)
            f2 = score(x2)
    return crank_rocker_for_swing(swing, time_ratio, 0.5 * (a + b), rocker)


# --- function generation by Freudenstein's equation (chapter 12) -----------------------------------

def chebyshev_spacing(start: float, stop: float, count: int = 3) -> np.ndarray:
    """Chebyshev's precision points in [start, stop]: (a + b)/2 − (b − a)/2 · cos((2j − 1)π/(2n)), j = 1 … n."""
    a, b = require_finite("start", start), require_finite("stop", stop)
    if not b > a:
        raise InvalidParameterError("stop", stop, f"a number greater than start = {a:g}")
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise InvalidParameterError("count", count, "a whole number of points ≥ 1")
    j = np.arange(1, int(count) + 1)
    return 0.5 * (a + b) - 0.5 * (b - a) * np.cos((2 * j - 1) * math.pi / (2 * int(count)))


def freudenstein_coefficients(phi: np.ndarray, xi: np.ndarray) -> np.ndarray:
    """k₁, k₂, k₃ of Freudenstein's equation k₁ cos ξ − k₂ cos φ + k₃ = cos(φ − ξ) through the pairs (φ, ξ).

    Three pairs (precision points) give the linear system's solution; more pairs its least-squares
    solution (the equation's residuals, not the angles' errors, are minimized). k₁ = d/L₁,
    k₂ = d/L₃, k₃ = (L₁² − L₂² + L₃² + d²)/(2 L₁ L₃) for the frame C = (d, 0).
    """
    phi = np.atleast_1d(require_finite_array("phi", phi, "rad"))
    xi = np.atleast_1d(require_finite_array("xi", xi, "rad"))
    if phi.ndim != 1 or phi.shape != xi.shape:
        raise InvalidParameterError("xi", f"shape {xi.shape}", f"one rocker angle per crank angle (shape {phi.shape})")
    if phi.size < 3:
        raise InvalidParameterError("phi", phi.tolist(), "at least three pairs (φ, ξ): three unknowns k₁, k₂, k₃")
    matrix = np.column_stack([np.cos(xi), -np.cos(phi), np.ones_like(phi)])
    rhs = np.cos(phi - xi)
    singular = np.linalg.svd(matrix, compute_uv=False)
    if singular[-1] <= 1e-12 * singular[0]:
        raise InvalidParameterError("phi", phi.tolist(), "pairs (φ, ξ) that determine k₁, k₂, k₃ (distinct points, "
                                    "not all at one crank or rocker angle)")
    if phi.size == 3:
        return np.linalg.solve(matrix, rhs)
    return np.linalg.lstsq(matrix, rhs, rcond=None)[0]


def function_generator(phi: np.ndarray, xi: np.ndarray, frame: float = 1.0) -> FourBar:
    """The four-bar with C = (d, 0) whose rocker angle ξ follows the crank angle φ through the pairs given.

    Parameters
    ----------
    phi, xi : array_like
        Crank and rocker angles (rad) of the precision points (three), or of more points for a
        least-squares fit (:func:`freudenstein_coefficients`).
    frame : float
        The frame length d (m); every length scales with it.

    Returns
    -------
    FourBar
        L₁ = d/k₁, L₃ = d/k₂, L₂ = √(L₁² + L₃² + d² − 2 L₁ L₃ k₃), on the branch σ that B has at the
        first pair.
    """
    d = require_length("frame", frame)
    k1, k2, k3 = freudenstein_coefficients(phi, xi)
    shown = np.asarray(xi, dtype=float)
    shown_text = f"{shown.size} rocker angles from {shown.min():.4g} to {shown.max():.4g} rad"
    if not (k1 > 0.0 and k2 > 0.0):
        raise InvalidParameterError("xi", shown_text,
                                    f"angles for which Freudenstein's equation gives positive lengths (here k₁ = "
                                    f"{k1:.6g}, k₂ = {k2:.6g}: L₁ = d/k₁ and L₃ = d/k₂ must be > 0; shift the ranges "
                                    "of φ or ξ)")
    l1, l3 = d / k1, d / k2
    square = l1 * l1 + l3 * l3 + d * d - 2.0 * l1 * l3 * k3
    if not square > 0.0:
        raise InvalidParameterError("xi", shown_text,
                                    f"angles for which Freudenstein's equation gives a coupler (L₂² = {square:.6g} m²)")
    phi0, xi0 = float(np.atleast_1d(phi)[0]), float(np.atleast_1d(xi)[0])
    a = l1 * complex(math.cos(phi0), math.sin(phi0))
    b = d + l3 * complex(math.cos(xi0), math.sin(xi0))
    return FourBar(l1, math.sqrt(square), l3, (d, 0.0), _side(a, complex(d, 0.0), b))


# --- motion generation: two or three positions of a body (chapter 12) ------------------------------

def _poses(points: object, angles: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    p = np.atleast_1d(np.asarray(points))
    if p.dtype.kind not in "iufc" or p.ndim != 1:
        raise InvalidParameterError("points", points, "positions of the body's reference point as complex numbers x + iy (m)")
    p = p.astype(complex)
    if not np.all(np.isfinite(p)):
        raise InvalidParameterError("points", points, "finite positions (m)")
    t = np.atleast_1d(require_finite_array("angles", angles, "rad"))
    if t.shape != p.shape or not 2 <= p.size <= 3:
        raise InvalidParameterError("angles", np.asarray(angles).tolist(),
                                    f"one body angle per position, two or three positions (got {p.size} points)")
    return p, t


def pole(point_1: complex, angle_1: float, point_2: complex, angle_2: float) -> complex:
    """The pole Π₁₂ (the textbooks' P₁₂) of the displacement of a body from position 1 to position 2 (m, as x + iy).

    A body point z (in the body's frame) lies at P_j + e^{iθ_j} z in position j. The pole is the
    point that does not move: Π₁₂ = (P₂ − e^{iΔθ} P₁)/(1 − e^{iΔθ}), Δθ = θ₂ − θ₁. A pure
    translation (Δθ a multiple of 2π) has no pole at a finite distance.
    """
    turn = float(wrap_angle(require_finite("angle_2", angle_2) - require_finite("angle_1", angle_1)))
    if abs(turn) < 1e-12:
        raise InvalidParameterError("angle_2", angle_2, "a body angle other than angle_1: a translation has no pole")
    rotation = complex(math.cos(turn), math.sin(turn))
    return (complex(point_2) - rotation * complex(point_1)) / (1.0 - rotation)


def body_positions(local: complex, points: object, angles: ArrayLike) -> np.ndarray:
    """Positions (m, x + iy) of the body point ``local`` (in the body's frame) in each given position."""
    p, t = _poses(points, angles)
    return p + np.exp(1j * t) * complex(local)


def centre_point(moving: complex, points: object, angles: ArrayLike, along: float = 0.0) -> complex:
    """The centre point (fixed pivot) for the circle point ``moving`` (body frame): its positions' circle centre.

    Three positions: the centre of the circle through the three positions of the point. Two
    positions: a point of the perpendicular bisector of its two positions, ``along`` (m) from their
    midpoint (to the left of the direction from the first to the second position).
    """
    z = body_positions(moving, points, angles)
    if z.size == 3:
        return _circumcentre(complex(z[0]), complex(z[1]), complex(z[2]), "moving")
    chord = complex(z[1] - z[0])
    if abs(chord) <= 1e-12 * max(1.0, abs(complex(z[0]))):
        raise InvalidParameterError("moving", moving, "a body point that moves between the two positions (not the pole)")
    return complex(0.5 * (z[0] + z[1])) + require_finite("along", along) * 1j * chord / abs(chord)


def circle_point(fixed: complex, points: object, angles: ArrayLike, along: float = 0.0) -> complex:
    """The circle point (body frame) whose positions lie on a circle about the fixed point ``fixed``.

    The inverse of :func:`centre_point`: seen from the body, the fixed point takes the positions
    e^{−iθ_j}(fixed − P_j); the circle point is their circle's centre (three positions), or a point
    of their bisector ``along`` (m) from their midpoint (two positions).
    """
    p, t = _poses(points, angles)
    inverse_points = -np.exp(-1j * t) * p
    return centre_point(complex(fixed), inverse_points, -t, along)


@dataclass(frozen=True)
class MotionDesign:
    """A four-bar that carries a body through given positions.

    Attributes
    ----------
    four_bar : FourBar
        The linkage, with the crank pivot O at the origin of its own frame (the body's positions
        shifted by −``origin``) and the branch σ that B has in the first position.
    origin : complex
        Where O is in the positions' frame (m).
    along, left : float
        The body's reference point in the coupler's frame: u along A → B and w to its left (m).
    offset : float
        Body angle minus coupler angle, θ − ψ (rad).
    crank_angles : ndarray
        φ_j of the crank in the given positions (rad).
    points, angles : ndarray
        The positions asked for: the reference point P_j (m, x + iy) and the body angle θ_j (rad).
    """

    four_bar: FourBar
    origin: complex
    along: float
    left: float
    offset: float
    crank_angles: np.ndarray
    points: np.ndarray
    angles: np.ndarray


def four_bar_through_positions(points: object, angles: ArrayLike, crank_pin: complex, rocker_pin: complex,
                               crank_pivot: complex, rocker_pivot: complex) -> MotionDesign:
    """The four-bar with circle points A, B (body frame) on centre points O, C, carrying the body.

    ``crank_pin`` and ``rocker_pin`` are body points (the coupler's joints A and B, in the body's
    frame), ``crank_pivot`` and ``rocker_pivot`` fixed points (O and C) equidistant from each pin's
    positions (:func:`centre_point`).
    """
    p, t = _poses(points, angles)
    o, c = complex(crank_pivot), complex(rocker_pivot)
    a = body_positions(crank_pin, p, t)
    b = body_positions(rocker_pin, p, t)
    for name, pin, centre in (("crank_pivot", a, o), ("rocker_pivot", b, c)):
        radii = np.abs(pin - centre)
        if float(np.ptp(radii)) > 1e-9 * max(1.0, float(radii.max())):
            raise InvalidParameterError(name, centre, "a centre point: equally far from its pin's positions (the "
                                        f"distances differ by {float(np.ptp(radii)):.3g} m)")
    a1, b1 = complex(a[0]), complex(b[0])
    psi = math.atan2((b1 - a1).imag, (b1 - a1).real)
    frame = c - o
    m = FourBar(abs(a1 - o), abs(b1 - a1), abs(b1 - c), (frame.real, frame.imag), _side(a1, c, b1))
    local = (complex(p[0]) - a1) * complex(math.cos(psi), -math.sin(psi))
    phi = np.angle(a - o)
    return MotionDesign(m, o, local.real, local.imag, float(wrap_angle(t[0] - psi)), phi, p, t)


@dataclass(frozen=True)
class MotionCheck:
    """A motion design, simulated.

    Attributes
    ----------
    sides : ndarray
        The branch σ (±1) of B in each asked position.
    grashof : str
        Grashof class of the linkage.
    defect : str
        ``"none"``; ``"circuit"`` (the linkage would have to be taken apart between the positions: B
        on both sides of A → C with a crank that turns fully, or crank angles in separate intervals
        of a limited crank range); ``"branch"`` (one interval of the crank's range, but B on both
        sides of A → C: the motion passes a position where coupler and rocker are in line and the
        crank must turn back); ``"order"`` (one side, one interval, but the crank, turning one way,
        meets the positions in another order than 1, 2, 3).
    position_error, angle_error : float
        Largest distance (m) and body-angle difference (rad) between the asked positions and the
        linkage's, solved on the branch of the first position (``inf`` where it does not assemble).
    """

    sides: np.ndarray
    grashof: str
    defect: str
    position_error: float
    angle_error: float


def check_motion(design: MotionDesign) -> MotionCheck:
    """Simulate a motion design with :class:`~mechanisms.FourBar` and name its defect, if any."""
    m = design.four_bar
    phi = design.crank_angles
    a = m.crank * np.exp(1j * phi)
    b = design.points - design.origin          # the body's reference point, asked, in the linkage's frame
    psi = design.angles - design.offset        # the coupler's angle in the asked positions
    pins_b = a + m.coupler * np.exp(1j * psi)
    sides = np.array([_side(complex(ai), m.pivot, complex(bi)) for ai, bi in zip(a, pins_b)])
    kind = grashof_class(*m.lengths)
    intervals = m.assembly_intervals()
    defect = "none"
    if len(intervals) == 1 and intervals[0][1] - intervals[0][0] >= 2.0 * math.pi - 1e-12:
        if np.any(sides != sides[0]):
            defect = "circuit"         # a crank that turns fully: each side of A -> C is a circuit of its own
    else:
        turns = [lo + (phi - lo) % (2.0 * math.pi) for lo, _ in intervals]
        home = [next((k for k, (lo, hi) in enumerate(intervals) if turns[k][j] <= hi + 1e-12), -1)
                for j in range(phi.size)]
        if -1 in home or len(set(home)) > 1:
            defect = "circuit"         # crank angles in separate intervals of its range
        elif np.any(sides != sides[0]):
            defect = "branch"          # one interval, both sides: through a position with coupler and rocker in line
        else:
            inside = turns[home[0]]
            if phi.size == 3 and not min(inside[0], inside[2]) <= inside[1] <= max(inside[0], inside[2]):
                defect = "order"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SingularPositionWarning)
            solution = FourBar(m.crank, m.coupler, m.rocker, m.frame, int(sides[0])).solve(phi, order=0)
        reached = solution.point_on("coupler", design.along, design.left).value
        position_error = float(np.max(np.abs(reached - b)))
        angle_error = float(np.max(np.abs(wrap_angle(solution.angle("coupler").value + design.offset
                                                      - design.angles))))
    except AssemblyError:
        position_error = angle_error = math.inf
    return MotionCheck(sides, kind.name, defect, position_error, angle_error)
