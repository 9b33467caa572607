"""Layer 4: analysis of the crank-slider (chapter 3).

The transmission angle, the two dead-centre
positions and the stroke, the time ratio of the offset mechanism, the extreme velocities and
accelerations of the slider, the approximate (series) slider formula of the textbooks, and the
velocity and acceleration analogues (derivatives with respect to the crank angle).
"""

from __future__ import annotations

import math
import warnings
from fractions import Fraction
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .assignments import Quantity, Task, crank_speed, register_assignment, round_mm
from ..core.angles import wrap_angle
from ..linkages.base import Solution
from ..linkages.crank_slider import CrankSlider
from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_finite, require_finite_array
from ..core.motion import Motion

__all__ = [
    "transmission_angle",
    "transmission_min",
    "DeadCentres",
    "dead_centres",
    "stroke",
    "TimeRatio",
    "time_ratio",
    "Extreme",
    "SliderExtremes",
    "slider_extremes",
    "approximate_slider",
    "Analogues",
    "analogues",
]


def full_revolution(mechanism: CrankSlider) -> bool:
    """Deprecated: ``mechanism.full_turn()``, the one assembly-range API of every mechanism."""
    warnings.warn("full_revolution(m) is deprecated: use m.full_turn()", DeprecationWarning, stacklevel=2)
    return mechanism.full_turn()


def crank_angle_range(mechanism: CrankSlider) -> list[tuple[float, float]] | None:
    """Deprecated: ``mechanism.assembly_intervals()`` (which gives ``[(−π, π)]``, not ``None``, for a full turn)."""
    warnings.warn("crank_angle_range(m) is deprecated: use m.assembly_intervals()", DeprecationWarning,
                  stacklevel=2)
    return None if mechanism.full_turn() else mechanism.assembly_intervals()


def transmission_angle(solution: Solution) -> np.ndarray:
    """The transmission angle μ (rad) of a crank-slider whose guide is parallel to x, at each position.

    μ is the angle between the rod A → B and the normal to the guide at B: ``μ = π/2 − |ψ|`` for
    the coupler angle ψ wrapped to (−π/2, π/2] about the guide's direction (chapter 3). The slider
    is driven best at μ = 90° (rod along the guide) and locks at μ = 0 (rod across it).
    """
    psi = wrap_angle(solution.angle("coupler").value)
    along = np.minimum(np.abs(psi), math.pi - np.abs(psi))     # the rod's angle with the guide's line
    return 0.5 * math.pi - along


def transmission_min(mechanism: CrankSlider) -> float:
    """The smallest transmission angle μ (rad) of a crank-slider whose crank turns fully.

    Notes
    -----
    μ = π/2 − |ψ| (ψ measured from the guide's direction); |ψ| is largest when the crank pin is
    farthest from the guide, L1 + |e|, so ``sin |ψ|_max = (L1 + |e|)/L2`` (chapter 3), computed
    here with atan2.
    """
    _require_full_revolution(mechanism, "the smallest transmission angle")
    reach = mechanism.crank + abs(mechanism.offset)
    psi_max = math.atan2(reach, math.sqrt((mechanism.rod - reach) * (mechanism.rod + reach)))
    return 0.5 * math.pi - psi_max


def _require_full_revolution(mechanism: CrankSlider, what: str) -> None:
    if not mechanism.full_turn():
        raise AssemblyError(
            f"{what} is defined here for a crank that turns fully, which needs rod ≥ crank + |offset|: got rod = "
            f"{mechanism.rod:g} m, crank + |offset| = {mechanism.crank + abs(mechanism.offset):g} m; the crank "
            "only rocks, between the ends of its assembly intervals (assembly_intervals())")


@dataclass(frozen=True)
class DeadCentres:
    """The two dead-centre (extreme) positions of the slider.

    Attributes
    ----------
    phi_outer, phi_inner : float
        Crank angles (rad, in (−π, π]) with crank and coupler in line, stretched (outer: the slider
        farthest from the crank pivot) and folded (inner: nearest).
    s_outer, s_inner : float
        The slider's positions s = x_B there (m).
    inner_singular : bool
        True in the limiting geometry L2 = L1 + |e| (exactly, for the given doubles): the inner
        extreme is then a singular position (the coupler perpendicular to the guide), where the slider
        reverses without coming to rest, not a dead centre.
    """

    phi_outer: float
    phi_inner: float
    s_outer: float
    s_inner: float
    inner_singular: bool = False

    @property
    def stroke(self) -> float:
        """The stroke |s_outer − s_inner| (m)."""
        return abs(self.s_outer - self.s_inner)


def dead_centres(mechanism: CrankSlider) -> DeadCentres:
    """The dead-centre positions: crank and coupler in line, the slider at rest.

    Notes
    -----
    Stretched: |OB| = L1 + L2, so ``x_B = σ·√((L1 + L2 − e)(L1 + L2 + e))`` on the guide y = e and the
    crank points at B, φ_outer = atan2(e, x_B). Folded: |OB| = L2 − L1, ``x_B = σ·√((L2 − L1 − |e|)(L2 −
    L1 + |e|))`` and the crank points away from B, φ_inner = atan2(e, x_B) + π (σ is the branch).
    The products under the roots avoid cancellation.

    In the limiting geometry L2 = L1 + |e| the folded position is also the singular position where the
    coupler stands perpendicular to the guide (chapter 3): the slider is at its extreme there but
    reverses without coming to rest, so ``phi_inner`` is an extreme position, not a dead centre in the
    book's sense (``solve`` flags it singular; ``inner_singular`` says so).
    """
    _require_full_revolution(mechanism, "the pair of dead centres")
    l1, l2, e, b = mechanism.crank, mechanism.rod, mechanism.offset, mechanism.branch
    s_outer = b * math.sqrt((l1 + l2 - e) * (l1 + l2 + e))
    s_inner = b * math.sqrt(max((l2 - l1 - abs(e)) * (l2 - l1 + abs(e)), 0.0))
    phi_outer = math.atan2(e, s_outer)
    phi_inner = math.atan2(e, s_inner) + math.pi
    if phi_inner > math.pi:
        phi_inner -= 2.0 * math.pi
    limiting = Fraction(l2) == Fraction(l1) + Fraction(abs(e))   # exact: L2 = L1 + |e|
    return DeadCentres(phi_outer, phi_inner, s_outer, s_inner, limiting)


def stroke(mechanism: CrankSlider) -> float:
    """The stroke H (m): the distance between the slider's two dead-centre positions.

    Notes
    -----
    ``H = √((L1 + L2)² − e²) − √((L2 − L1)² − e²)``; for the axial mechanism H = 2 L1.
    """
    return dead_centres(mechanism).stroke


@dataclass(frozen=True)
class TimeRatio:
    """The time ratio of the crank-slider at constant crank speed.

    Attributes
    ----------
    ratio : float
        K = (slow stroke angle)/(fast stroke angle) = (π + θ_K)/(π − θ_K) ≥ 1.
    outward_angle : float
        Crank angle (rad) turned while the slider moves from the inner to the outer dead centre.
    return_angle : float
        Crank angle (rad) turned while it moves back; the two add up to 2π.
    overlap_angle : float
        θ_K = |outward − π| (rad), the crank angle between the two dead-centre positions' extensions.
    """

    ratio: float
    outward_angle: float
    return_angle: float
    overlap_angle: float


def time_ratio(mechanism: CrankSlider, direction: int = 1) -> TimeRatio:
    """Time ratio K of the (offset) crank-slider for a crank turning in ``direction`` (+1: ω > 0).

    Notes
    -----
    The strokes take the crank angles between the dead centres: counter-clockwise from φ_inner to
    φ_outer for the outward stroke. For the axial mechanism both are π and K = 1; an offset makes one
    stroke slower, ``θ_K = arcsin(e/(L2 − L1)) − arcsin(e/(L1 + L2))`` for branch +1 (computed here from
    the dead-centre angles by atan2).
    """
    if direction not in (1, -1):
        raise InvalidParameterError("direction", direction, "+1 (counter-clockwise) or -1")
    centres = dead_centres(mechanism)
    ccw = (centres.phi_outer - centres.phi_inner) % (2.0 * math.pi)   # the angle turned forward: [0, 2π), not a wrap
    outward = ccw if direction == 1 else 2.0 * math.pi - ccw
    back = 2.0 * math.pi - outward
    return TimeRatio(max(outward, back) / min(outward, back), outward, back, abs(outward - math.pi))


@dataclass(frozen=True)
class Extreme:
    """An extreme value of a quantity over a crank revolution and the crank angle (rad) where it occurs."""

    phi: float
    value: float


@dataclass(frozen=True)
class SliderExtremes:
    """Largest and smallest slider velocity (m/s) and acceleration (m/s²) over a revolution."""

    velocity_max: Extreme
    velocity_min: Extreme
    acceleration_max: Extreme
    acceleration_min: Extreme


def _golden_extremes(function, centres: np.ndarray, signs: np.ndarray, half_width: float,
                     iterations: int = 80) -> np.ndarray:
    """Golden-section search for the maxima of ``sign·f`` in [c − w, c + w], vectorized over the searches."""
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    lo, hi = centres - half_width, centres + half_width
    x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
    f1, f2 = signs * function(x1), signs * function(x2)
    for _ in range(iterations):
        left = f1 >= f2  # the maximum lies in [lo, x2]
        hi = np.where(left, x2, hi)
        lo = np.where(left, lo, x1)
        x1_new = np.where(left, hi - ratio * (hi - lo), x2)
        x2_new = np.where(left, x1, lo + ratio * (hi - lo))
        x1, x2 = x1_new, x2_new
        f1, f2 = signs * function(x1), signs * function(x2)
    return 0.5 * (lo + hi)


def slider_extremes(mechanism: CrankSlider, omega: float = 1.0, samples: int = 720) -> SliderExtremes:
    """Extreme slider velocities and accelerations at constant crank speed ω.

    Parameters
    ----------
    mechanism : CrankSlider
        A mechanism whose crank turns fully with L2 > L1 + |e| (otherwise the acceleration is unbounded).
    omega : float
        Crank speed φ_t (1/s); velocities scale with ω and accelerations with ω².
    samples : int
        Crank positions of the coarse search; each extreme is then refined by golden-section search to
        round-off.

    Notes
    -----
    The velocity is extreme where the acceleration vanishes, which has no closed form for the exact
    mechanism; the search uses the exact closed-form velocities and accelerations.
    """
    mechanism.require_one_linkage("the extreme slider velocities and accelerations")
    omega = require_finite("omega", omega)
    if omega == 0.0:
        raise InvalidParameterError("omega", omega, "a crank speed other than 0 1/s (at rest there are no extremes)")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 8:
        raise InvalidParameterError("samples", samples, "a whole number ≥ 8 of crank positions")
    if not mechanism.rod > mechanism.crank + abs(mechanism.offset):
        _require_full_revolution(mechanism, "the extreme velocity and acceleration")
        raise AssemblyError("the slider's acceleration is unbounded where the rod is perpendicular to the guide "
                            "(rod = crank + |offset|): no extreme acceleration")
    phi = np.linspace(-math.pi, math.pi, samples, endpoint=False)
    sol = mechanism.solve(phi, omega, 0.0, order=2)
    v, a = sol.slider("B").velocity, sol.slider("B").acceleration
    starts = phi[[np.argmax(v), np.argmin(v), np.argmax(a), np.argmin(a)]]
    signs = np.array([1.0, -1.0, 1.0, -1.0])

    def pick(angles):
        s = mechanism.solve(angles, omega, 0.0, order=2).slider("B")
        return np.concatenate([s.velocity[:2], s.acceleration[2:]])

    best = _golden_extremes(pick, starts, signs, 2.0 * math.pi / samples)
    values = pick(best)
    wrapped = wrap_angle(best)
    return SliderExtremes(*(Extreme(float(p), float(f)) for p, f in zip(wrapped, values)))


def approximate_slider(mechanism: CrankSlider, phi: ArrayLike, omega: float = 1.0) -> Motion:
    """The textbooks' approximate (series) slider motion at constant crank speed ω.

    Parameters
    ----------
    mechanism : CrankSlider
    phi : array_like
        Crank angles φ (rad).
    omega : float
        Crank speed φ_t (1/s).

    Returns
    -------
    Motion
        s (m), v (m/s), a (m/s²) from the expansion of the exact half-chord to second order in the
        crank pin's distance from the guide.

    Notes
    -----
    ``√(L2² − h_A²) ≈ L2 − h_A²/(2 L2)`` with h_A = L1 sin φ − e and σ the branch gives
    ``s ≈ L1 cos φ + σ [L2 − (L1 sin φ − e)²/(2 L2)]``,
    ``v ≈ −ω L1 [sin φ + σ cos φ (L1 sin φ − e)/L2]``,
    ``a ≈ −ω² L1 [cos φ + σ (L1 cos 2φ + e sin φ)/L2]``.
    For the axial mechanism (e = 0, σ = +1) with λ = L1/L2 these are the familiar
    ``s ≈ L2 + L1 (cos φ − (λ/4)(1 − cos 2φ))``, ``v ≈ −ω L1 (sin φ + (λ/2) sin 2φ)``,
    ``a ≈ −ω² L1 (cos φ + λ cos 2φ)``. The neglected term of s is −h_A⁴/(8 L2³), about L1 λ³/8.
    """
    mechanism.require_one_linkage("the series slider motion")
    phi = require_finite_array("phi", phi, "crank angles in rad")
    omega = require_finite("omega", omega)
    l1, l2, e, b = mechanism.crank, mechanism.rod, mechanism.offset, mechanism.branch
    h = l1 * np.sin(phi) - e
    s = l1 * np.cos(phi) + b * (l2 - h**2 / (2.0 * l2))
    v = -omega * l1 * (np.sin(phi) + b * np.cos(phi) * h / l2)
    a = -omega**2 * l1 * (np.cos(phi) + b * (l1 * np.cos(2.0 * phi) + e * np.sin(phi)) / l2)
    return Motion(s, v, a)


@dataclass(frozen=True)
class Analogues:
    """Velocity and acceleration analogues of the crank-slider: derivatives with respect to φ.

    Attributes
    ----------
    psi_1, psi_2 : numpy.ndarray
        ψ′ = dψ/dφ (dimensionless) and ψ″ = d²ψ/dφ² (1/rad), the coupler's analogues.
    s_1, s_2 : numpy.ndarray
        s′ = ds/dφ and s″ = d²s/dφ² (m/rad, m/rad²), the slider's analogues.

    Notes
    -----
    They depend on the geometry and φ only. At any crank speed ω = φ_t and acceleration ε = φ_tt,
    ``ψ_t = ω ψ′``, ``ψ_tt = ε ψ′ + ω² ψ″`` and likewise ``s_t = ω s′``, ``s_tt = ε s′ + ω² s″``.
    """

    psi_1: np.ndarray
    psi_2: np.ndarray
    s_1: np.ndarray
    s_2: np.ndarray


def analogues(mechanism: CrankSlider, phi: ArrayLike) -> Analogues:
    """The velocity and acceleration analogues ψ′, ψ″, s′, s″ at the crank angles φ.

    Parameters
    ----------
    mechanism : CrankSlider
    phi : array_like
        Crank angles φ (rad).

    Returns
    -------
    Analogues
        ``ψ′ = −L1 cos φ / (L2 cos ψ)``, ``ψ″ = (L1 sin φ + L2 sin ψ ψ′²) / (L2 cos ψ)``,
        ``s′ = −L1 sin φ − L2 sin ψ ψ′``, ``s″ = −L1 cos φ − L2 (cos ψ ψ′² + sin ψ ψ″)``: the closed
        form of chapter 3 at the unit crank speed φ_t = 1 1/s and φ_tt = 0, where the time
        derivatives equal the derivatives with respect to φ.

    Raises
    ------
    InvalidParameterError
        Naming ``phi`` if it is not finite.
    AssemblyError
        Naming the crank angles at which the mechanism cannot be assembled.
    """
    phi = require_finite_array("phi", phi, "crank angles in rad")
    sol = mechanism.solve(phi, 1.0, 0.0, order=2)
    coupler, slider = sol.angle("coupler"), sol.slider("B")
    return Analogues(coupler.omega, coupler.alpha, slider.velocity, slider.acceleration)


# --- the crank-slider's assignment (python -m mechanisms assign crank-slider) ------------------------------------------------------------------------------------

CRANK_SLIDER_MIN_TRANSMISSION_DEG = 45.0
"""Smallest transmission angle μ of a crank-slider variant (degrees), see :func:`transmission_min`."""


def _sample_crank_slider(rng: np.random.Generator) -> tuple[CrankSlider, float]:
    crank = round_mm(rng.uniform(0.040, 0.120))
    rod = round_mm(crank / rng.uniform(0.20, 0.35))         # λ = L1/L2 of engines and compressors
    offset = 0.0 if rng.random() < 0.5 else round_mm(rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 0.30) * crank)
    return CrankSlider(crank=crank, rod=rod, offset=offset), crank_speed(rng, 50, 300)


def _check_crank_slider(mechanism: CrankSlider) -> list[str]:
    problems = []
    if not (mechanism.full_turn() and mechanism.rod > mechanism.crank + abs(mechanism.offset)):
        problems.append("the crank does not turn a full revolution (L2 > L1 + |e| is needed)")
    elif math.degrees(transmission_min(mechanism)) < CRANK_SLIDER_MIN_TRANSMISSION_DEG:
        problems.append("the smallest transmission angle is below "
                        f"{CRANK_SLIDER_MIN_TRANSMISSION_DEG:g}°")
    return problems


def _data_crank_slider(m: CrankSlider) -> list[tuple[str, str, str, str]]:
    return [("L_1", "crank length |OA|", f"{m.crank:.3f}", "m"),
            ("L_2", "coupler (connecting-rod) length |AB|", f"{m.rod:.3f}", "m"),
            ("e", "offset: the guide is the line y = e", f"{m.offset:.3f}", "m"),
            ("", "assembly", "the slider B to the right of the crank pin A (x_B > x_A)", "")]


register_assignment(Task(
    "crank-slider", "Crank-slider", _sample_crank_slider, _check_crank_slider, _data_crank_slider,
    (Quantity("B.s", "x_B", "position of the slider B on its guide (its x coordinate)", "m"),
     Quantity("B.v", "v_B", "velocity of the slider (positive towards +x)", "m/s"),
     Quantity("B.a", "a_B", "acceleration of the slider (positive towards +x)", "m/s²"),
     Quantity("coupler.omega", "ψ_t", "angular velocity of the coupler (positive counter-clockwise)", "1/s"),
     Quantity("coupler.alpha", "ψ_tt", "angular acceleration of the coupler (positive counter-clockwise)",
              "1/s²")),
    f"the crank turns a full revolution (L2 > L1 + |e|) and the transmission angle, between the rod and the "
    f"normal to the guide, never falls below {CRANK_SLIDER_MIN_TRANSMISSION_DEG:g}°; L1/L2 between 0.2 and 0.35"))
