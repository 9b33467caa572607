"""The Frenet-frame method (Pylypaka and Chepizhnyi, 2019), chapter 8.

Notation: the book's (chapter 8's table of letters). The crank angle is φ (the source's ψ); the angle
of the driven link from the tangent is ϑ (the source's φ), whose values and derivatives the fields
``phi``, ``phi_s``, ``phi_ss`` of :class:`RotationLaw` hold under the source's letter.

A driven link hinged to the crank pin A is seen from a moving frame whose origin is A: the
Frenet frame of the crank-pin circle (radius r, curvature k = 1/r). Its unit tangent τ points
along the pin's velocity for a counter-clockwise crank, its principal normal n = iτ towards the
centre O. With the crank angle φ = ks measured from +x (s is the arc length of the pin's path),

    A = O + r·exp(iφ),    τ = i·exp(iφ),    θ_τ = φ + π/2   (the tangent's angle from +x; the source's α).

The driven link makes the angle ϑ with τ; the source's γ is defined by the link's direction
θ_AB = π − γ from +x, so that ϑ = θ_AB − θ_τ = π/2 − γ − ks (the source's relation (1)). A point of
the link at the distance ρ from A (negative: on the other side of A) is

    R(s) = A + ρ·exp(i(θ_τ + ϑ)) = A + ρ(cos ϑ·τ + sin ϑ·n),

and with the Frenet formulas τ' = k n, n' = −k τ (a prime is d/ds):

    R'  = [1 − ρ(k + ϑ') sin ϑ] τ + ρ(k + ϑ') cos ϑ · n,
    R'' = −[ρ ϑ'' sin ϑ + ρ(k + ϑ')² cos ϑ] τ + [ρ ϑ'' cos ϑ − ρ(k + ϑ')² sin ϑ + k] n.

The velocity is ṡ R' and the acceleration s̈ R' + ṡ² R'', with ṡ = ωr and s̈ = εr (crank
angular velocity ω and acceleration ε). For a constant ω these are the source's (3) and (4);
its (11) turns the frame components to the fixed axes.

The source derives ϑ' and ϑ'' symbolically for each mechanism. Here they come from the
mechanism's solution instead, which already holds the driven link's angle θ with its exact time
derivatives: θ' = θ_t/ṡ, θ'' = (θ_tt − θ' s̈)/ṡ², and ϑ' = θ' − k, ϑ'' = θ''. No symbolic
differentiation is needed, so the method works for every mechanism whose driven link is hinged
to the crank (the lambda mechanism included, for which the source stopped at the trajectories).

Notes
-----
The source's trajectory formula (2) and projection (11) place the pin at r(sin ks, −cos ks),
i.e. they measure s from the lowest point of the circle, while its problems measure the crank
angle ks from +x; used together the pictures turn by −90°. This module measures φ = ks from +x
throughout: see the book's errata page.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..linkages.base import Mechanism, Solution
from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_branch, require_finite, require_finite_array, require_length
from ..core.motion import AngleMotion, PointMotion

__all__ = [
    "RotationLaw",
    "driven_link",
    "rotation_law",
    "law_from_angles",
    "crank_slider_law",
    "rocker_in_block_law",
    "lambda_mechanism_gamma",
]


def _wrap(angle: np.ndarray) -> np.ndarray:
    """An angle brought into (−π, π]."""
    return np.pi - np.mod(np.pi - angle, 2.0 * np.pi)


@dataclass(frozen=True)
class RotationLaw:
    """The law of rotation ϑ(s) of a driven link in the Frenet frame of the crank-pin circle.

    Attributes
    ----------
    s : ndarray
        Arc length of the crank pin's path, s = rφ (m), φ the crank angle from +x.
    curvature : float
        k = 1/r (1/m), the curvature of the crank-pin circle.
    phi : ndarray
        ϑ (rad): the angle from the tangent τ to the driven link, in (−π, π].
    phi_s, phi_ss : ndarray or None
        ϑ' = dϑ/ds (rad/m) and ϑ'' = d²ϑ/ds² (rad/m²); ``None`` if not computed.
    s_t, s_tt : ndarray or None
        ṡ = ωr (m/s) and s̈ = εr (m/s²), the pin's speed along its path and its rate.
    centre : complex
        The crank pivot O (m).
    singular : ndarray of bool
        Positions where the mechanism's solution is singular (a singular position: rates unbounded).

    Notes
    -----
    The methods evaluate the formulas of the module docstring for a point at the distance ρ
    from the crank pin along the driven link (chapter 8; Pylypaka and Chepizhnyi 2019, (1)–(4),
    (11)). Arrays have the shape of the crank angles.
    """

    s: np.ndarray
    curvature: float
    phi: np.ndarray
    phi_s: np.ndarray | None = None
    phi_ss: np.ndarray | None = None
    s_t: np.ndarray | None = None
    s_tt: np.ndarray | None = None
    centre: complex = 0j
    singular: np.ndarray | None = None

    @property
    def order(self) -> int:
        """0, 1 or 2: how many derivatives of ϑ are known."""
        if self.phi_s is None:
            return 0
        return 1 if self.phi_ss is None else 2

    @property
    def radius(self) -> float:
        """r = 1/k, the crank radius (m)."""
        return 1.0 / self.curvature

    @property
    def crank_angle(self) -> np.ndarray:
        """φ = ks, the crank angle from +x (rad)."""
        return self.curvature * self.s

    @property
    def tangent_angle(self) -> np.ndarray:
        """θ_τ = φ + π/2, the angle of the tangent τ from +x (rad; the source's α)."""
        return self.crank_angle + 0.5 * np.pi

    @property
    def gamma(self) -> np.ndarray:
        """The source's γ = π/2 − ϑ − ks, in (−π, π]: the driven link's direction is π − γ."""
        return _wrap(0.5 * np.pi - self.phi - self.crank_angle)

    def _require(self, order: int, what: str) -> None:
        if self.order < order:
            raise ValueError(f"the {what} need the rotation law up to order {order}; it was built with order "
                             f"{self.order}")

    def position(self, rho: float) -> np.ndarray:
        """The point at distance ρ from the crank pin along the driven link, ``x + iy`` (m).

        ``R = O + r·exp(iφ) + ρ·exp(i(θ_τ + ϑ))``; in coordinates
        ``x = r cos ks − ρ sin(ϑ + ks)``, ``y = r sin ks + ρ cos(ϑ + ks)`` (O at the origin).
        """
        psi = self.crank_angle
        return self.centre + self.radius * np.exp(1j * psi) + rho * np.exp(1j * (psi + 0.5 * np.pi + self.phi))

    def frame_velocity(self, rho: float) -> tuple[np.ndarray, np.ndarray]:
        """The velocity's components on τ and n: ``(V_τ, V_n)`` (m/s), the source's (3).

        ``V_τ = ṡ[1 − ρ(k + ϑ') sin ϑ]``, ``V_n = ṡ ρ(k + ϑ') cos ϑ`` with ṡ = ωr.
        """
        self._require(1, "velocities")
        assert self.phi_s is not None   # checked by _require
        turn = rho * (self.curvature + self.phi_s)
        assert self.s_t is not None   # checked by _require
        return self.s_t * (1.0 - turn * np.sin(self.phi)), self.s_t * turn * np.cos(self.phi)

    def frame_acceleration(self, rho: float) -> tuple[np.ndarray, np.ndarray]:
        """The acceleration's components on τ and n: ``(W_τ, W_n)`` (m/s²).

        ``W = s̈ R' + ṡ² R''``; for a constant crank speed (s̈ = 0) the source's (4):
        ``W_τ = −ṡ²[ρϑ'' sin ϑ + ρ(k + ϑ')² cos ϑ]``,
        ``W_n = ṡ²[ρϑ'' cos ϑ − ρ(k + ϑ')² sin ϑ + k]``.
        """
        self._require(2, "accelerations")
        assert self.s_t is not None and self.s_tt is not None   # checked by _require
        k, phi = self.curvature, self.phi
        c, s = np.cos(phi), np.sin(phi)
        assert self.phi_s is not None and self.phi_ss is not None
        turn = self.curvature + self.phi_s
        squared = self.s_t**2
        tangential = -squared * rho * (self.phi_ss * s + turn**2 * c)
        normal = squared * (rho * (self.phi_ss * c - turn**2 * s) + k)
        tangential = tangential + self.s_tt * (1.0 - rho * turn * s)
        normal = normal + self.s_tt * rho * turn * c
        return tangential, normal

    def to_fixed(self, tangential: np.ndarray, normal: np.ndarray) -> np.ndarray:
        """A vector given on τ and n, as ``x + iy`` on the fixed axes (the source's (11)).

        ``(x + iy) = (tangential + i·normal)·exp(iθ_τ)`` with θ_τ = ks + π/2:
        ``x = −V_τ sin ks − V_n cos ks``, ``y = V_τ cos ks − V_n sin ks``.
        """
        return (tangential + 1j * normal) * np.exp(1j * self.tangent_angle)

    def point(self, rho: float) -> PointMotion:
        """The point at distance ρ from the pin: position, velocity and acceleration on the fixed axes.

        Up to the order of the law; the velocity and acceleration are :meth:`frame_velocity`
        and :meth:`frame_acceleration` turned by :meth:`to_fixed`.
        """
        position = self.position(rho)
        if self.order == 0:
            return PointMotion(position)
        velocity = self.to_fixed(*self.frame_velocity(rho))
        if self.order == 1:
            return PointMotion(position, velocity)
        return PointMotion(position, velocity, self.to_fixed(*self.frame_acceleration(rho)))


def law_from_angles(crank: AngleMotion, link: AngleMotion, radius: float, centre: complex = 0j,
                    singular: np.ndarray | None = None) -> RotationLaw:
    """The rotation law of a driven link from the crank's angle and the link's angle.

    Parameters
    ----------
    crank : AngleMotion
        The crank angle φ (rad, from +x) with ω = φ_t (1/s) and ε = φ_tt (1/s²).
    link : AngleMotion
        The driven link's angle θ (rad, from +x, from the crank pin along the link) with θ_t and
        θ_tt, e.g. from a mechanism's solution or from the generic solver.
    radius : float
        The crank radius r (m).
    centre : complex
        The crank pivot O (m).
    singular : ndarray of bool, optional
        Singular positions, passed on.

    Returns
    -------
    RotationLaw
        Up to the lower of the two motions' orders.

    Notes
    -----
    ``s = rφ``, ``ϑ = θ − φ − π/2``, ``ṡ = rω``, ``s̈ = rε``;
    ``ϑ' = θ_t/ṡ − k`` and ``ϑ'' = (θ_tt − (ϑ' + k) s̈)/ṡ²`` from the chain rule
    ``θ_t = θ' ṡ``, ``θ_tt = θ'' ṡ² + θ' s̈`` (chapter 8). The crank must turn (ω ≠ 0) wherever
    derivatives are asked for: s is the independent variable.
    """
    radius = require_length("radius", radius)
    k = 1.0 / radius
    psi = np.asarray(crank.value, dtype=float)
    s = radius * psi
    phi = _wrap(np.asarray(link.value, dtype=float) - psi - 0.5 * np.pi)
    order = min(crank.order, link.order)
    if singular is None:
        singular = np.zeros(np.shape(psi), dtype=bool)
    if order == 0:
        return RotationLaw(s, k, phi, centre=complex(centre), singular=singular)
    omega = np.broadcast_to(np.asarray(crank.omega, dtype=float), np.shape(psi))
    if np.any(omega == 0.0):
        raise InvalidParameterError("omega", 0.0, "non-zero: the Frenet-frame method takes the arc length s of the "
                                    "crank pin as the independent variable, so the crank must turn")
    s_t = radius * omega
    theta_s = link.omega / s_t
    phi_s = theta_s - k
    if order == 1:
        return RotationLaw(s, k, phi, phi_s, None, s_t, None, complex(centre), singular)
    s_tt = radius * np.broadcast_to(np.asarray(crank.alpha, dtype=float), np.shape(psi))
    phi_ss = (link.alpha - theta_s * s_tt) / s_t**2
    return RotationLaw(s, k, phi, phi_s, phi_ss, s_t, s_tt, complex(centre), singular)


def driven_link(mechanism: Mechanism, pin: str = "A") -> str:
    """The name of the link hinged to the crank pin (the driven link of the Frenet-frame method).

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism of the package.
    pin : str
        The crank pin's joint name (``"A"`` in every mechanism of the book).

    Returns
    -------
    str
        The first link, other than the crank, whose first joint is the pin: ``"coupler"`` of a
        crank-slider, four-bar or lambda mechanism, ``"rocker"`` of :class:`~mechanisms.RockerInBlock`.

    Raises
    ------
    InvalidParameterError
        If no link starts at the crank pin (e.g. a slotted lever, whose lever turns about a
        fixed pivot: its block, not the lever, is hinged to the crank).
    """
    for name, first in mechanism.links.items():
        if name != "crank" and first == pin:
            return name
    raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                f"a mechanism with a link hinged to the crank pin {pin} (links: "
                                f"{', '.join(f'{n} from {j}' for n, j in mechanism.links.items())})")


def rotation_law(mechanism: Mechanism, phi: ArrayLike, omega: float = 1.0, alpha: float = 0.0, order: int = 2,
                 link: str | None = None, solution: Solution | None = None) -> RotationLaw:
    """Solve a mechanism and return the law of rotation ϑ(s) of its driven link.

    Parameters
    ----------
    mechanism : Mechanism
        Any mechanism of the package whose driven link is hinged to the crank pin A.
    phi : array_like
        Crank angles φ (rad) (the source writes ψ = ks).
    omega, alpha : float
        Crank angular velocity ω (1/s, non-zero) and acceleration ε (1/s²).
    order : int
        0: ϑ only; 1: also ϑ'; 2: also ϑ''.
    link : str, optional
        The driven link; by default :func:`driven_link`.
    solution : Solution, optional
        A solution already computed for these angles (then ``phi``, ``omega``, ``alpha`` and
        ``order`` are taken from it).

    Returns
    -------
    RotationLaw
    """
    link = link or driven_link(mechanism)
    if solution is None:
        solution = mechanism.solve(phi, omega, alpha, order)
    pivot, pin = solution.point("O").value, solution.point("A").value
    radius = float(np.mean(np.abs(pin - pivot)))
    return law_from_angles(solution.angle("crank"), solution.angle(link), radius, complex(np.ravel(pivot)[0]),
                           solution.singular)


# Closed forms of the laws for two mechanisms, derived in chapter 8 (corrected where the
# source's print differs; see the errata). They serve as a check of the general route.

def crank_slider_law(s: ArrayLike, curvature: float, rod: float, offset: float = 0.0,
                     branch: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ϑ, ϑ', ϑ'' of the coupler of a crank-slider in closed form.

    Parameters
    ----------
    s : array_like
        Arc length of the crank pin (m), s = rφ.
    curvature : float
        k = 1/r (1/m).
    rod : float
        The coupler length L (m).
    offset : float
        The guide is the line y = ``offset`` (m), as in :class:`~mechanisms.CrankSlider`; the
        source's problem 1 has its guide at y = −e, so ``offset = −e``.
    branch : int
        +1: the slider to the right of the pin; −1: to the left (the source's problem 1).

    Returns
    -------
    phi, phi_s, phi_ss : ndarray
        ϑ (rad, in (−π, π]), ϑ' (rad/m), ϑ'' (rad/m²).

    Notes
    -----
    With h = e − r sin ks (the guide's height above the pin) and w = √(L² − h²):
    θ = atan2(h, b·w), θ' = −b cos ks / w, θ'' = b (k sin ks · w² + h cos² ks) / w³,
    ϑ = θ − ks − π/2, ϑ' = θ' − k, ϑ'' = θ''. For b = −1, e = −e_source these are the source's
    (8), (9), (10) (chapter 8). Unbounded where w = 0 (the rod perpendicular to the guide).
    """
    k = require_length("curvature", curvature)
    rod = require_length("rod", rod)
    offset = require_finite("offset", offset)
    b = require_branch(branch)
    psi = k * require_finite_array("s", s, "arc lengths in m")
    sin, cos = np.sin(psi), np.cos(psi)
    h = offset - sin / k
    reach = (rod - h) * (rod + h)
    if np.any(reach < 0.0):
        raise AssemblyError("the rod cannot reach the guide (the pin is farther than the rod from it)",
                            psi[reach < 0.0])
    w = np.sqrt(reach)
    theta = np.arctan2(h, b * w)
    with np.errstate(divide="ignore", invalid="ignore"):
        theta_s = -b * cos / w
        theta_ss = b * (k * sin * w**2 + h * cos**2) / w**3
    return _wrap(theta - psi - 0.5 * np.pi), theta_s - k, theta_ss


def rocker_in_block_law(s: ArrayLike, curvature: float,
                        pivot: tuple[float, float] = (0.0, 1.0)) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ϑ, ϑ', ϑ'' of a rocker hinged to the crank pin and sliding through a block at a fixed pivot.

    Parameters
    ----------
    s : array_like
        Arc length of the crank pin (m), s = rφ.
    curvature : float
        k = 1/r (1/m).
    pivot : tuple of float
        The block's pivot C = (x_C, y_C) (m); the source's problem 3 has it at (0, d) (and calls it B).

    Returns
    -------
    phi, phi_s, phi_ss : ndarray
        ϑ (rad, in (−π, π]), ϑ' (rad/m), ϑ'' (rad/m²).

    Notes
    -----
    The rocker points from A to C: with X = x_C − r cos ks, Y = y_C − r sin ks and Q = X² + Y² (= R²),
    θ = atan2(Y, X), θ' = −(X cos ks + Y sin ks)/Q, θ'' = (X sin ks − Y cos ks)(kQ + 2(X cos ks
    + Y sin ks))/Q². For C = (0, d) they reduce to ϑ' = k²d(sin ks − kd)/(1 + k²d² − 2kd sin ks)
    and ϑ'' = dk³(1 − k²d²) cos ks/(1 + k²d² − 2kd sin ks)², the corrected (15), (16) of the
    source (chapter 8). Undefined where the block is at the pin (Q = 0).
    """
    k = require_length("curvature", curvature)
    a, b = (require_finite("pivot", value) for value in pivot)
    psi = k * require_finite_array("s", s, "arc lengths in m")
    sin, cos = np.sin(psi), np.cos(psi)
    x, y = a - cos / k, b - sin / k
    q = x * x + y * y
    along = x * cos + y * sin
    with np.errstate(divide="ignore", invalid="ignore"):
        theta_s = -along / q
        theta_ss = (x * sin - y * cos) * (k * q + 2.0 * along) / q**2
    return _wrap(np.arctan2(y, x) - psi - 0.5 * np.pi), theta_s - k, theta_ss


def lambda_mechanism_gamma(psi: ArrayLike, crank: float, half_coupler: float, ground: float) -> np.ndarray:
    """The source's closed form (21) of the coupler angle γ of the lambda mechanism (rad).

    Parameters
    ----------
    psi : array_like
        Crank angle φ = ks (rad).
    crank, half_coupler, ground : float
        r, b, d (m), as in :class:`~mechanisms.LambdaMechanism`.

    Returns
    -------
    ndarray
        γ in [0, π]; the coupler's direction is π − γ.

    Notes
    -----
    With R² = r² + d² + 2rd cos φ (the squared distance between the pin and the rocker pivot; the
    source's A), ``cos γ = [d³ + r(r² + 3d²) cos φ + r²d(2 + cos 2φ) + r sin φ √(R²(4b² − R²))] / (2bR²)``:
    the joint B (the source's C) is the intersection of the circles of radius b about A and about the
    pivot C = (−d, 0) (the source's D) on the left of C→A. Being an arccosine, it holds only while
    B is above A (sin γ ≥ 0).
    """
    r = require_length("crank", crank)
    b = require_length("half_coupler", half_coupler)
    d = require_length("ground", ground)
    psi = np.asarray(psi, dtype=float)
    big_a = r * r + d * d + 2.0 * r * d * np.cos(psi)
    reach = 4.0 * b * b - big_a
    if np.any(reach < 0.0):
        raise AssemblyError("the lambda mechanism cannot be assembled: the pin is farther than 2b from the "
                            "rocker pivot", angles=np.atleast_1d(psi)[np.atleast_1d(reach < 0.0)])
    numerator = (d**3 + r * (r * r + 3.0 * d * d) * np.cos(psi) + r * r * d * (2.0 + np.cos(2.0 * psi))
                 + r * np.sin(psi) * np.sqrt(big_a * reach))
    ratio = numerator / (2.0 * b * big_a)
    # |ratio| ≤ 1 holds exactly; only round-off can exceed it, and only that is clamped
    if np.any(np.abs(ratio) > 1.0 + 1e-9):
        raise ValueError("cos γ out of [−1, 1] beyond round-off: the formula does not apply")
    return np.arccos(np.clip(ratio, -1.0, 1.0))
