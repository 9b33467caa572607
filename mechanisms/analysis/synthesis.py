"""Layer 4: synthesis of a four-bar whose output is the coupler, from the time ratio K and the
transmission angle μ₁ in the first limit position (Zaitsev and Evgrafov), and its check by simulation.

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
angle there is φ_x/2). Chapter 4 checks every design by simulating it with
:class:`~mechanisms.FourBar`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..core.errors import SingularPositionWarning, InvalidParameterError
from ..core.validate import require_finite, require_length
from ..linkages.four_bar import FourBar
from .four_bar import grashof_class, transmission_angle

__all__ = [
    "CouplerOutputDesign",
    "return_angle",
    "synthesize_coupler_output",
    "coupler_length_asymptote",
    "closure_residual",
    "DesignCheck",
    "check_design",
    "largest_rotatable_angle",
]


@dataclass(frozen=True)
class CouplerOutputDesign:
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

    def four_bar(self) -> FourBar:
        """The designed linkage as a :class:`~mechanisms.FourBar`."""
        return FourBar(self.crank, self.coupler, self.rocker, self.frame, self.branch)


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
        right also below π/2, where squaring the cotangent in Λ lost its sign (chapter 4).

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
