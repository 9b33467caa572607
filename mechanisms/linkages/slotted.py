"""Slotted-link mechanisms (chapter 5): a block sliding in the slot of a moving link.

* :class:`SlottedLever` — crank O–A, a block on the crank pin A sliding along a lever that turns
  about the fixed pivot C = (x_C, y_C): oscillating (|OC| > L1), rotating (|OC| < L1) or with the
  pivot on the crank circle (|OC| = L1), where the block passes through the pivot.
* :class:`RockerInBlock` — the guide with a moving axis: a slotted coupler hinged to the crank pin A
  slides through a block that swivels about the fixed point C (source 002, problem 3, calls the
  coupler a rocker and its points P₁, P₂ C and D; an oscillating hydraulic cylinder works the same way).
* :class:`Shaper` — the slotted lever of a shaping machine: the lever's end B drives the ram G
  through a rod along a horizontal guide.
* :class:`SlottedRockers` — two rockers with a slotted pair: the crank drives the slotted lever
  about C (the lecture's O₁), and the pin D of a second rocker O₂D slides in the same slot.
* :class:`SliderOnCoupler` — a crank-slider whose coupler line carries a block E (the lecture's L)
  that also runs along a second, fixed guide; and the angle between the coupler and the slider's guide.

Every joint carries the book's letter (chapter 5), so a drawing needs no relabelling.

Notation of chapter 5 (the lecture's and the textbook's letters in brackets): crank angle φ (φ₁),
lever angle ξ (φ₃), distance L from the lever's pivot to the block (L_tek, l₃), second rocker's
angle θ_O₂D, coupler angle ψ.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .chunks import solve_in_chunks
from .groups import RPR, RRP, Crank, Group, LinkPoint
from .base import Bar, Block, Ground, Guide, Mechanism, Parameter, Solution
from ..blocks.circle_line import slider_on_line
from ..blocks.crank import crank_pin
from ..blocks.lever_block import LeverBlock, lever_block, lever_through_pivot
from ..blocks.lines import angle_from_distance, circle_on_line, distance_to_line, line_intersection
from ..core.errors import InvalidParameterError
from ..core.exact import squared_distance_equals, squared_distance_exceeds
from ..core.validate import require_branch, require_coordinate, require_finite, require_length, require_pair
from ..core.motion import AngleMotion, Motion, PointMotion, fixed_point, point_on_link, polar

__all__ = ["SlottedLever", "RockerInBlock", "Shaper", "SlottedRockers", "SliderOnCoupler"]


def _scaled_pair(pair: tuple[float, float], factor: float) -> tuple[float, float]:
    return pair[0] * factor, pair[1] * factor


def _lever_part(crank: AngleMotion, radius: float, pivot: complex, kind: str) -> tuple[PointMotion, LeverBlock]:
    """The crank pin and the block on the lever, for any of the three kinds of slotted lever."""
    pin = crank_pin(crank, radius)
    if kind == "through pivot":
        return pin, lever_through_pivot(crank, radius, math.atan2(pivot.imag, pivot.real))
    return pin, lever_block(pin, pivot)


class SlottedLever(Mechanism):
    """Crank with a slotted lever: a block on the crank pin slides along a lever about C = (x_C, y_C).

    Parameters
    ----------
    crank : float
        Crank length L₁ = |OA| (m), the textbook's l₁.
    pivot : tuple of float
        The lever's fixed pivot C = (x_C, y_C) (m); the crank turns about O = (0, 0).
    lever : float, optional
        Length of the lever from C to its end B (m), for drawings; at least ``|OC| + L₁``, the
        farthest the block gets from the pivot (default: exactly that).

    Notes
    -----
    Joints: O crank pivot, A crank pin and block, C lever pivot, B lever end (and E, the end of the
    lever's other arm, when the pivot lies on the crank circle). Links: ``crank`` (O→A),
    ``lever`` (C→A, angle ξ). Slider ``A``: the distance L from C to the block (m, the lecture's
    L_tek), with the sliding velocity L_t and relative acceleration L_tt; ``sol.coriolis("A")`` is
    the Coriolis acceleration a^k = 2 ω₃ L_t (m/s², positive towards the lever's left).

    The lever oscillates when ``|OC| > L1``, rotates when ``|OC| < L1``; when ``|OC| = L1`` the block
    passes through the pivot once a revolution and the lever turns at half the crank's speed
    (then L is signed: negative on the lever's other arm).
    """

    cli_name = "slotted-lever"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1 = |OA|, m"),
        Parameter("pivot", "pair", "the lever's fixed pivot C = (x_C, y_C), m, as X,Y; the crank turns about the origin"),
    )
    links = {"crank": "O", "lever": "C"}
    benchmark = True
    always_assembles = True

    @classmethod
    def example(cls) -> "SlottedLever":
        """The benchmark's oscillating lever: L₁ = 1 m, pivot C = (0, 2) m."""
        return cls(crank=1.0, pivot=(0.0, 2.0))

    def linkage_data(self) -> dict:
        """This slotted lever as the contents of a linkage file (:mod:`~mechanisms.linkages.linkage_file`).

        The crank O → A and an RPR dyad: the block on the pin A slides along the lever through C, whose end
        B is at the lever's length from C. Loaded, it is the same linkage (for a pivot on the crank
        circle, where the block passes through the pivot, the class's own solution is the one to use).
        """
        return {"name": "Crank with a slotted lever",
                "frame": {"O": [0.0, 0.0], "C": [self.pivot[0], self.pivot[1]]},
                "crank": {"pivot": "O", "pin": "A", "length": self.crank},
                "dyad": [{"type": "RPR", "block": "A", "pivot": "C", "joint": "B", "length": self.lever,
                          "links": ["A", "lever"]}]}

    def groups(self) -> tuple[Group, ...]:
        return (Crank("O", "A"), RPR("A", "C", "lever"), LinkPoint("B", "lever"))

    def __init__(self, crank: float, pivot: Sequence[float], lever: float | None = None):
        self.crank = require_length("crank", crank)
        self.pivot = require_pair("pivot", pivot)
        self.pivot_point = complex(*self.pivot)
        self.pivot_distance = abs(self.pivot_point)
        # on the crank circle exactly (a² + b² = r² for the given doubles, core.exact): a pivot 1e-10 off it
        # is an ordinary pivot, which the general lever block solves right
        if squared_distance_equals(self.pivot, self.crank):
            self.kind = "through pivot"
        else:
            self.kind = "oscillating" if self.pivot_distance > self.crank else "rotating"
        reach = self.pivot_distance + self.crank
        if lever is None:
            self.lever = reach
        else:
            self.lever = require_length("lever", lever)
            if self.lever < reach * (1 - 1e-12):
                raise InvalidParameterError("lever", lever, f"at least |OC| + L₁ = {reach:g} m, so that the "
                                            "block stays in the slot")

    def _rescaled(self, factor: float) -> "SlottedLever":
        return SlottedLever(self.crank * factor, _scaled_pair(self.pivot, factor), self.lever * factor)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        # long arrays block by block, in the processor's cache (chapter 9)
        return solve_in_chunks(self._solve_block, crank, order, self.links)

    def _solve_block(self, crank: AngleMotion, order: int) -> Solution:
        pin, block = _lever_part(crank, self.crank, self.pivot_point, self.kind)
        xi = block.lever_angle
        points = {"O": fixed_point(0j, crank.value, order), "A": pin,
                  "C": fixed_point(self.pivot_point, crank.value, order),
                  "B": point_on_link(self.pivot_point, xi, self.lever)}
        if self.kind == "through pivot":
            points["E"] = point_on_link(self.pivot_point, xi, -self.lever)
        extras = {"A": {"coriolis": block.coriolis_magnitude}} if order >= 1 else {}
        return Solution(crank.value, order, angles={"crank": crank, "lever": xi}, points=points, links=self.links,
                        sliders={"A": block.distance}, extras=extras, singular=block.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        lever_joints = ("E", "B") if self.kind == "through pivot" else ("C", "B")
        return [Ground("O"), Ground("C"), Bar("lever", lever_joints, "lever"), Bar("crank", ("O", "A"), "crank"),
                Block("A", "lever")]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("C", "B"): self.lever}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("lever"), solution.slider("A")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        xi, s = q
        a, b = self.pivot
        return (self.crank * np.cos(phi) - a - s * np.cos(xi),
                self.crank * np.sin(phi) - b - s * np.sin(xi))

    def coriolis_vector(self, solution: Solution) -> np.ndarray:
        """The Coriolis acceleration of the block as a vector ``2 ω₃ L_t · i exp(iξ)`` (m/s², complex)."""
        xi = solution.angle("lever")
        return 2.0 * xi.omega * solution.slider("A").velocity * 1j * np.exp(1j * xi.value)


class RockerInBlock(Mechanism):
    """Crank with a rocker sliding in a swivelling block: the guide with a moving axis.

    Parameters
    ----------
    crank : float
        Crank length L₁ = |OA| (m) (source 002: r = 1/k).
    pivot : tuple of float
        The block's fixed pivot C = (x_C, y_C) (m) (source 002: (0, d)).
    reach : float, optional
        Distance u from A to each end of the slotted coupler (m): the joint ``P2`` (P₂) = A + u·exp(iψ)
        beyond the block, the joint ``P1`` (P₁) = A − u·exp(iψ) on the other side of the hinge (source 002
        calls them D and C). Default |OC| + L1, so that the block never leaves the coupler.

    Notes
    -----
    The slotted coupler (the link ``rocker``) is hinged to the crank pin A, so its axis moves with A; it
    slides through the block at the pivot (joint ``C``). Its angle ψ is the direction from A towards the
    pivot: ψ = ξ + π, where ξ is the direction from the pivot to A of
    :class:`SlottedLever` with the same crank and pivot; the lecture's slide "guide with a moving axis"
    writes ``tg ψ = (b − y_A)/(a − x_A)``. Joints O, A, C, P1, P2 (chapter 5's O, A, C, P₁, P₂); links
    ``crank`` (O→A), ``rocker`` (A→C, angle ψ; ``point_on("rocker", u)`` gives any point of it). Slider
    ``C``: the block's distance from A along the rocker (m), with ``coriolis``, the Coriolis acceleration
    2 ψ_t t_t of the block relative to the rocker (m/s², positive towards the rocker's left; the block's own centre does not move, so this
    term, the rocker point's acceleration and the relative one add up to zero). The block oscillates when
    |OC| > L1, rotates when |OC| < L1, and when |OC| = L1 the coupler turns at exactly half the crank's speed (source 002)
    and the block passes through the hinge A (the distance is then signed).
    """

    cli_name = "rocker-in-block"
    always_assembles = True
    cli_parameters = (
        Parameter("crank", "length", "crank length L1 = |OA|, m"),
        Parameter("pivot", "pair", "the block's fixed pivot C = (x_C, y_C), m, as X,Y"),
    )
    links = {"crank": "O", "rocker": "A"}

    @classmethod
    def example(cls) -> "RockerInBlock":
        """Chapter 5's rocker in a block: L₁ = 2 m, pivot (0, 4) m."""
        return cls(crank=2.0, pivot=(0.0, 4.0))

    def __init__(self, crank: float, pivot: Sequence[float], reach: float | None = None):
        self._lever = SlottedLever(crank, pivot)
        self.crank, self.pivot, self.kind = self._lever.crank, self._lever.pivot, self._lever.kind
        self.reach = self._lever.lever if reach is None else require_length("reach", reach)

    def _rescaled(self, factor: float) -> "RockerInBlock":
        return RockerInBlock(self.crank * factor, _scaled_pair(self.pivot, factor), self.reach * factor)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        pin, block = _lever_part(crank, self.crank, self._lever.pivot_point, self.kind)
        xi = block.lever_angle
        psi = AngleMotion(xi.value + np.pi, *xi.derivatives()[1:])
        points = {"O": fixed_point(0j, crank.value, order), "A": pin,
                  "C": fixed_point(self._lever.pivot_point, crank.value, order),
                  "P1": point_on_link(pin, psi, -self.reach), "P2": point_on_link(pin, psi, self.reach)}
        extras = {"C": {"coriolis": block.coriolis_magnitude}} if order >= 1 else {}
        return Solution(crank.value, order, angles={"crank": crank, "rocker": psi}, points=points, links=self.links,
                        sliders={"C": block.distance}, extras=extras, singular=block.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        return [Ground("O"), Ground("C"), Bar("rocker", ("P1", "P2"), "rocker"), Bar("crank", ("O", "A"), "crank"),
                Block("C", "rocker")]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("A", "P2"): self.reach, ("A", "P1"): self.reach}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("rocker"), solution.slider("C")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        psi, t = q
        a, b = self.pivot
        return (self.crank * np.cos(phi) + t * np.cos(psi) - a,
                self.crank * np.sin(phi) + t * np.sin(psi) - b)


class Shaper(Mechanism):
    """The slotted-lever mechanism of a shaping machine: crank, lever, rod and ram.

    Parameters
    ----------
    crank : float
        Crank length L₁ = |OA| (m); the crank turns about O = (0, 0).
    pivot : tuple of float
        The lever's pivot C = (x_C, y_C) (m), farther from O than L₁ (the lever oscillates).
    lever : float
        Lever length |CB| (m), at least ``|OC| + L₁``.
    rod : float
        Length of the rod B→G from the lever's end to the ram (m).
    ram_height : float
        The ram's guide is the horizontal line y = ``ram_height`` (m).
    branch : int
        +1: the ram G is to the right of the foot of the perpendicular from B on the guide; −1: left.

    Notes
    -----
    Joints O, A (crank pin and block), C, B (lever end), G (ram), chapter 5's letters. Links ``crank``
    (O→A), ``lever`` (C→B, angle ξ), ``rod`` (B→G). Sliders ``A`` (L, with ``coriolis``) and ``G`` (the
    ram's abscissa x_G, m). The ram's extreme positions are those of the lever, so the ram's stroke and
    time ratio follow from the lever's (:mod:`mechanisms.analysis.slotted`).
    """

    cli_name = "shaper"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1 = |OA|, m"),
        Parameter("pivot", "pair", "the lever's fixed pivot C = (x_C, y_C), m, as X,Y"),
        Parameter("lever", "length", "lever length |CB|, m"),
        Parameter("rod", "length", "rod length |BG| from the lever's end to the ram G, m"),
        Parameter("ram_height", "number", "the ram's guide is the line y = RAM_HEIGHT, m"),
        Parameter("branch", "branch", "+1: ram right of the lever's end, -1: left", 1),
    )
    links = {"crank": "O", "lever": "C", "rod": "B"}

    @classmethod
    def example(cls) -> "Shaper":
        """Chapter 5's shaper: L₁ = 0.1 m, pivot (0, −0.4) m, lever 0.6 m, rod 0.15 m, ram at y = 0.22 m."""
        return cls(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22)

    def groups(self) -> tuple[Group, ...]:
        return (Crank("O", "A"), RPR("A", "C", "lever", slider="block"), LinkPoint("B", "lever"),
                RRP("G", "B", "rod", "ram", 0.0))

    def __init__(self, crank: float, pivot: Sequence[float], lever: float, rod: float, ram_height: float,
                 branch: int = 1):
        self.crank = require_length("crank", crank)
        self.pivot = require_pair("pivot", pivot)
        self.lever = require_length("lever", lever)
        self.rod = require_length("rod", rod)
        self.ram_height = require_coordinate("ram_height", ram_height)
        self.branch = require_branch(branch)
        self.pivot_point = complex(*self.pivot)
        distance = abs(self.pivot_point)
        if not squared_distance_exceeds(self.pivot, self.crank):      # |OC| > r, exactly
            raise InvalidParameterError("pivot", pivot, f"farther from the crank centre than the crank "
                                        f"(|OC| > L₁ = {self.crank:g} m) for an oscillating lever; got |OC| = "
                                        f"{distance:g} m")
        if self.lever < (distance + self.crank) * (1 - 1e-12):
            raise InvalidParameterError("lever", lever, f"at least |OC| + L₁ = {distance + self.crank:g} m, so "
                                        "that the block stays in the slot")
        self._lever = SlottedLever(self.crank, self.pivot, self.lever)

    def _rescaled(self, factor: float) -> "Shaper":
        return Shaper(self.crank * factor, _scaled_pair(self.pivot, factor), self.lever * factor, self.rod * factor,
                      self.ram_height * factor, self.branch)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        base = self._lever._solve(crank, order)
        end = base.point("B")
        ram = slider_on_line(end, self.rod, 1j * self.ram_height, 0.0, self.branch, angles=crank.value)
        points = {name: base.point(name) for name in ("O", "A", "C", "B")} | {"G": ram.point}
        return Solution(crank.value, order, angles={"crank": crank, "lever": base.angle("lever"),
                                                    "rod": ram.rod_angle},
                        points=points, links=self.links, sliders={"A": base.slider("A"), "G": ram.travel},
                        extras=base.extras, singular=base.singular | ram.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        return [Ground("O"), Ground("C"), Guide(1j * self.ram_height, 0.0), Bar("lever", ("C", "B"), "lever"),
                Bar("crank", ("O", "A"), "crank"), Bar("rod", ("B", "G"), "coupler"), Block("A", "lever"),
                Block("G", 0.0)]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("C", "B"): self.lever, ("B", "G"): self.rod}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("lever"), solution.slider("A"), solution.angle("rod"), solution.slider("G")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        xi, s, psi, x = q
        a, b = self.pivot
        return (self.crank * np.cos(phi) - a - s * np.cos(xi),
                self.crank * np.sin(phi) - b - s * np.sin(xi),
                a + self.lever * np.cos(xi) + self.rod * np.cos(psi) - x,
                b + self.lever * np.sin(xi) + self.rod * np.sin(psi) - self.ram_height)


class SlottedRockers(Mechanism):
    """Two rockers with a slotted pair: the pin D of the rocker O₂D slides in the slot of the lever CB.

    Parameters
    ----------
    crank : float
        Crank length L1 = |OA| (m); the crank turns about O = (0, 0) and drives the lever through
        a block on its pin A.
    pivot : tuple of float
        The lever's pivot C = (x_C, y_C) (m) (the lecture's O₁ = (a, b)).
    rocker_pivot : tuple of float
        The second rocker's pivot O₂ (m) (the lecture's (m, n)).
    rocker : float
        The second rocker's length L4 = |O₂D| (m) (the lecture's R).
    branch : int
        σ = +1: D is ahead of N, the foot of the perpendicular from O₂ on the lever's line (in the
        lever's direction, from C towards A); −1: behind it.

    Notes
    -----
    Lecture slides "two rockers with a slotted pair": the signed distance h_N from O₂ to the lever's
    line, its foot N (the lecture's K), the point D and the current length |CD| (the lecture's L_tek)
    with their derivatives. Joints O, A, C (the lever's pivot), B (the lever's end), O2, D. Links ``crank``,
    ``lever`` (C→A, angle ξ), ``rocker`` (O₂→D, angle θ_O₂D). Sliders ``A`` and ``D``: distances from
    C along the lever (m), each with ``coriolis``; ``extras["O2"]`` holds h_N, its rates (m, m/s,
    m/s²), also given by :func:`mechanisms.analysis.slotted.distance_from_lever`.
    """

    cli_name = "slotted-rockers"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1 = |OA|, m"),
        Parameter("pivot", "pair", "the lever's pivot C = (x_C, y_C), m, as X,Y"),
        Parameter("rocker_pivot", "pair", "the second rocker's pivot O2, m, as X,Y"),
        Parameter("rocker", "length", "the second rocker's length |O2 D|, m"),
        Parameter("branch", "branch", "+1: D ahead of the foot N along the lever, -1: behind", 1),
    )
    links = {"crank": "O", "lever": "C", "rocker": "O2"}

    @classmethod
    def example(cls) -> "SlottedRockers":
        """Chapter 5's two rockers with a slotted pair: L₁ = 0.1 m, pivots (0, 0.3) and (0.12, 0.38) m, rocker 0.2 m."""
        return cls(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2)

    def __init__(self, crank: float, pivot: Sequence[float], rocker_pivot: Sequence[float], rocker: float,
                 branch: int = 1):
        self.crank = require_length("crank", crank)
        self.pivot = require_pair("pivot", pivot)
        self.rocker_pivot = require_pair("rocker_pivot", rocker_pivot)
        self.rocker = require_length("rocker", rocker)
        self.branch = require_branch(branch)
        self._lever = SlottedLever(self.crank, self.pivot)
        if self._lever.kind == "through pivot":
            raise InvalidParameterError("pivot", pivot, "off the crank circle (|OC| ≠ L₁)")
        self.lever = max(self._lever.lever, abs(complex(*self.rocker_pivot) - complex(*self.pivot)) + self.rocker)

    def _rescaled(self, factor: float) -> "SlottedRockers":
        return SlottedRockers(self.crank * factor, _scaled_pair(self.pivot, factor),
                              _scaled_pair(self.rocker_pivot, factor), self.rocker * factor, self.branch)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        pin, block = _lever_part(crank, self.crank, self._lever.pivot_point, self._lever.kind)
        xi = block.lever_angle
        c, o2 = complex(*self.pivot), complex(*self.rocker_pivot)
        pin_d = circle_on_line(o2, self.rocker, c, xi, self.branch, angles=crank.value)
        _, theta = polar(pin_d.point - o2)
        slot_d = pin_d.along
        points = {"O": fixed_point(0j, crank.value, order), "A": pin, "C": fixed_point(c, crank.value, order),
                  "B": point_on_link(c, xi, self.lever), "O2": fixed_point(o2, crank.value, order),
                  "D": pin_d.point}
        extras = {}
        if order >= 1:
            extras = {"A": {"coriolis": block.coriolis_magnitude},
                      "D": {"coriolis": 2.0 * xi.omega * slot_d.velocity}}
            h = pin_d.distance.distance
            extras["O2"] = {"h": h.value, "h_t": h.velocity} | ({"h_tt": h.acceleration} if order >= 2 else {})
        return Solution(crank.value, order, angles={"crank": crank, "lever": xi, "rocker": theta}, points=points,
                        links=self.links, sliders={"A": block.distance, "D": slot_d}, extras=extras,
                        singular=block.singular | pin_d.singular)

    def foot(self, solution: Solution) -> PointMotion:
        """N, the foot of the perpendicular from O₂ on the lever's line (m, m/s, m/s²)."""
        return distance_to_line(complex(*self.rocker_pivot), complex(*self.pivot), solution.angle("lever")).foot

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        return [Ground("O"), Ground("C"), Ground("O2"), Bar("lever", ("C", "B"), "lever"),
                Bar("crank", ("O", "A"), "crank"), Bar("rocker", ("O2", "D"), "rocker"), Block("A", "lever"),
                Block("D", "lever")]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("C", "B"): self.lever, ("O2", "D"): self.rocker}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("lever"), solution.slider("A"), solution.angle("rocker"), solution.slider("D")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        xi, s, theta, t = q
        a, b = self.pivot
        m, n = self.rocker_pivot
        return (self.crank * np.cos(phi) - a - s * np.cos(xi),
                self.crank * np.sin(phi) - b - s * np.sin(xi),
                m + self.rocker * np.cos(theta) - a - t * np.cos(xi),
                n + self.rocker * np.sin(theta) - b - t * np.sin(xi))


class SliderOnCoupler(Mechanism):
    """A crank-slider whose coupler line carries a block E that also runs on a fixed guide.

    Parameters
    ----------
    crank : float
        Crank length L₁ = |OA| (m).
    rod : float
        Coupler length |AB| (m); B slides on the line y = ``offset``.
    offset : float
        The ordinate e of the slider B's guide (m).
    guide_point : tuple of float
        A point (x₀, y₀) of the second, fixed guide (m), on which E runs.
    guide_angle : float
        The second guide's direction β₂ (rad).

    Notes
    -----
    Lecture slides "slider on a coupler with a fixed guide" and "angle between the coupler and the
    fixed direction of the slider". E (the lecture's L; chapter 5 keeps L for a length) is the
    intersection of the coupler's line AB with the fixed guide
    (:func:`~mechanisms.blocks.lines.line_intersection`); a block hinged to a slider on the guide
    slides in a slot along the coupler. Joints O, A, B, E; links ``crank``, ``coupler`` (A→B, angle ψ);
    sliders ``B`` (x_B, m) and ``E`` (s_E, the position of E along the second guide from (x₀, y₀), m)
    and ``E_coupler`` (u = |AE|, the same block's position along the coupler from A, m): E is a pair
    of sliding pairs.
    """

    cli_name = "slider-on-coupler"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1 = |OA|, m"),
        Parameter("rod", "length", "coupler length |AB|, m"),
        Parameter("offset", "number", "the slider B runs on the line y = OFFSET, m", 0.0),
        Parameter("guide_point", "pair", "a point X0,Y0 of the fixed guide of the block E, m"),
        Parameter("guide_angle", "angle", "direction of the guide of the block E, degrees from +x"),
    )
    links = {"crank": "O", "coupler": "A"}

    @classmethod
    def example(cls) -> "SliderOnCoupler":
        """Chapter 5's slider on a coupler: L1 = 0.08 m, L2 = 0.3 m, guide through (0.2, 0) m at 70°."""
        return cls(crank=0.08, rod=0.3, guide_point=(0.2, 0.0), guide_angle=math.radians(70.0))

    def __init__(self, crank: float, rod: float, guide_point: Sequence[float], guide_angle: float,
                 offset: float = 0.0):
        self.crank = require_length("crank", crank)
        self.rod = require_length("rod", rod)
        self.offset = require_coordinate("offset", offset)
        self.guide_point = require_pair("guide_point", guide_point)
        self.guide_angle = require_finite("guide_angle", guide_angle)
        if self.rod <= self.crank + abs(self.offset):
            raise InvalidParameterError("rod", rod, f"greater than crank + |offset| = "
                                        f"{self.crank + abs(self.offset):g} m for a full revolution")

    def _rescaled(self, factor: float) -> "SliderOnCoupler":
        return SliderOnCoupler(self.crank * factor, self.rod * factor, _scaled_pair(self.guide_point, factor),
                               self.guide_angle, self.offset * factor)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        pin = crank_pin(crank, self.crank)
        slide = slider_on_line(pin, self.rod, 1j * self.offset, 0.0, 1, angles=crank.value)
        psi = slide.rod_angle
        crossing = line_intersection(pin, psi, complex(*self.guide_point), self.guide_angle, angles=crank.value)
        points = {"O": fixed_point(0j, crank.value, order), "A": pin, "B": slide.point, "E": crossing.point}
        return Solution(crank.value, order, angles={"crank": crank, "coupler": psi}, points=points, links=self.links,
                        sliders={"B": slide.travel, "E": crossing.along_second, "E_coupler": crossing.along_first},
                        singular=slide.singular | crossing.singular)

    def guide_angle_of_coupler(self, solution: Solution) -> AngleMotion:
        """The angle η between the slider B's guide and the coupler, from ``sin η = h_N / L₂``.

        h_N is the signed distance of the crank pin A from the guide of B (left positive),
        :func:`~mechanisms.blocks.lines.distance_to_line`; η follows the lecture's slide (§5.7). For
        the slider to the right of A (this mechanism) η = −ψ with ψ the coupler angle.
        """
        h = distance_to_line(solution.point("A"), 1j * self.offset, 0.0).distance
        return angle_from_distance(h, self.rod)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        x0, y0 = self.guide_point
        return [Ground("O"), Guide(complex(self.rod, self.offset), 0.0), Guide(complex(x0, y0), self.guide_angle),
                Bar("crank", ("O", "A"), "crank"), Bar("coupler", ("A", "B", "E"), "coupler"), Block("B", 0.0),
                Block("E", self.guide_angle)]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("A", "B"): self.rod}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("coupler"), solution.slider("B"), solution.slider("E_coupler"), solution.slider("E")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        psi, x, t, g = q
        x0, y0 = self.guide_point
        c, s = math.cos(self.guide_angle), math.sin(self.guide_angle)
        return (self.crank * np.cos(phi) + self.rod * np.cos(psi) - x,
                self.crank * np.sin(phi) + self.rod * np.sin(psi) - self.offset,
                self.crank * np.cos(phi) + t * np.cos(psi) - x0 - g * c,
                self.crank * np.sin(phi) + t * np.sin(psi) - y0 - g * s)
