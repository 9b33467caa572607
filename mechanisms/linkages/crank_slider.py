"""Layer 3: the crank-slider (chapter 3), axial or offset.

The crank O→A (length L1) turns about the origin; the coupler (connecting rod) A→B (length L2)
drives the slider B along the fixed guide y = e. It is the crank block followed by the
circle–line block (:func:`~mechanisms.blocks.circle_line.slider_on_line`).
"""

from __future__ import annotations

import math
import warnings
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .chunks import solve_in_chunks
from .groups import RRP, Crank, Group
from .base import Bar, Block, Ground, Guide, Mechanism, Parameter, Solution
from ..blocks.circle_line import slider_on_line
from ..blocks.crank import crank_pin
from ..core.errors import AssemblyError
from ..core.validate import require_branch, require_coordinate, require_length
from ..core.motion import AngleMotion, Motion, fixed_point

__all__ = ["CrankSlider", "assembly_ranges"]


def assembly_ranges(crank: float, rod: float, offset: float) -> list[tuple[float, float]] | None:
    """Crank-angle intervals in which a crank-slider can be assembled.

    Parameters
    ----------
    crank, rod : float
        L1 and L2 (m), > 0.
    offset : float
        e (m): the guide is the line y = e.

    Returns
    -------
    list of (float, float) or None
        ``None`` if the crank turns a full revolution (L2 ≥ L1 + |e|); otherwise the closed
        intervals [φ_lo, φ_hi] (rad, φ_lo in (−π, π], φ_hi > φ_lo) where the crank pin is no farther
        than L2 from the guide, |L1 sin φ − e| ≤ L2; an empty list if there are none (L2 < |e| − L1).

    Notes
    -----
    From −L2 ≤ L1 sin φ − e ≤ L2: sin φ ∈ [(e − L2)/L1, (e + L2)/L1] ∩ [−1, 1]. A bound inside
    (−1, 1) cuts the circle; the arcsines are computed only of these checked ratios (chapter 3).
    """
    if rod >= crank + abs(offset):
        return None
    low, high = (offset - rod) / crank, (offset + rod) / crank
    if low > 1.0 or high < -1.0:
        return []
    if high >= 1.0:  # only the lower bound cuts: one arc through φ = 90°
        a = math.asin(low)
        return [(a, math.pi - a)]
    if low <= -1.0:  # only the upper bound cuts: one arc through φ = −90°
        b = math.asin(high)
        return [(-math.pi - b, b)]
    a, b = math.asin(low), math.asin(high)  # both cut: two arcs, around 0° and around 180°
    return [(a, b), (math.pi - b, math.pi - a)]


class CrankSlider(Mechanism):
    """Crank-slider: crank O–A, coupler A–B, slider B on the guide y = offset.

    Parameters
    ----------
    crank : float
        Crank length L1 = |OA| (m), > 0.
    rod : float
        Coupler (connecting-rod) length L2 = |AB| (m), > 0.
    offset : float
        Offset e (m): the slider's guide is the line y = e, parallel to x (0 for the axial mechanism).
    branch : int
        +1: the slider works on the +x side of the crank pin (B to the right of A), and so, for a crank
        that turns fully, on the +x side of the crank pivot; −1: on the −x side.

    Notes
    -----
    Joints ``O`` (crank pivot, the origin), ``A`` (crank pin), ``B`` (slider); links ``crank``
    (angle φ) and ``coupler`` (angle ψ of the vector A→B); slider ``B``: its position s = x_B along
    the guide. Constraints (chapter 3): ``L1 cos φ + L2 cos ψ = s``, ``L1 sin φ + L2 sin ψ = e``.
    """

    cli_name = "crank-slider"
    cli_parameters = (
        Parameter("crank", "length", "crank length L1, m"),
        Parameter("rod", "length", "coupler (connecting-rod) length L2, m"),
        Parameter("offset", "number", "offset e of the guide y = e, m (default 0: axial)", 0.0),
    )
    links = {"crank": "O", "coupler": "A"}

    def __init__(self, crank: float, rod: float, offset: float = 0.0, branch: int = 1):
        self.crank = require_length("crank", crank)
        self.rod = require_length("rod", rod)
        self.offset = require_coordinate("offset", offset)
        self.branch = require_branch(branch)
        ranges = assembly_ranges(self.crank, self.rod, self.offset)
        if ranges == []:
            raise AssemblyError(f"the rod cannot reach the guide at any crank angle: rod = {self.rod:g} m is "
                                f"shorter than |offset| − crank = {abs(self.offset) - self.crank:g} m")

    benchmark = True

    @classmethod
    def example(cls) -> "CrankSlider":
        """The benchmark's offset crank-slider: L1 = 1 m, L2 = 3.5 m, e = 0.5 m."""
        return cls(crank=1.0, rod=3.5, offset=0.5)

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Crank-angle intervals (rad) of assembly: ``[(−π, π)]`` for a full revolution (L2 ≥ L1 + |e|),
        else those of :func:`assembly_ranges`."""
        ranges = assembly_ranges(self.crank, self.rod, self.offset)
        return [(-math.pi, math.pi)] if ranges is None else ranges

    def linkage_data(self) -> dict:
        """This crank-slider as the contents of a linkage file (:mod:`~mechanisms.linkages.linkage_file`).

        The crank O → A, and an RRP dyad: the coupler A → B with the slider B on the guide y = e; the
        dyad's branch is the class's (+1: B farther along +x than A). Loaded, it is the same linkage.
        """
        return {"name": "Crank-slider", "frame": {"O": [0.0, 0.0]},
                "crank": {"pivot": "O", "pin": "A", "length": self.crank},
                "dyad": [{"type": "RRP", "joint": "B", "from": "A", "length": self.rod,
                          "guide": {"through": [0.0, self.offset], "angle_deg": 0.0}, "branch": self.branch,
                          "links": ["coupler", "slider"]}]}

    def groups(self) -> tuple[Group, ...]:
        return (Crank("O", "A"), RRP("B", "A", "coupler", "slider", 0.0))

    @property
    def full_revolution(self) -> bool:
        """Deprecated: :meth:`full_turn`."""
        warnings.warn("CrankSlider.full_revolution is deprecated: use full_turn()", DeprecationWarning, stacklevel=2)
        return self.full_turn()

    @property
    def assembly_ranges(self) -> list[tuple[float, float]] | None:
        """Deprecated: :meth:`assembly_intervals` (which gives ``[(−π, π)]``, not ``None``, for a full turn)."""
        warnings.warn("CrankSlider.assembly_ranges is deprecated: use assembly_intervals()", DeprecationWarning,
                      stacklevel=2)
        return assembly_ranges(self.crank, self.rod, self.offset)

    def _rescaled(self, factor: float) -> "CrankSlider":
        return CrankSlider(self.crank * factor, self.rod * factor, self.offset * factor, self.branch)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        # long arrays block by block, in the processor's cache (chapter 9)
        return solve_in_chunks(self._solve_block, crank, order, self.links)

    def _solve_block(self, crank: AngleMotion, order: int) -> Solution:
        phi = crank.value
        pin = crank_pin(crank, self.crank)
        try:
            block = slider_on_line(pin, self.rod, through=1j * self.offset, direction=0.0, branch=self.branch,
                                   angles=phi)
        except AssemblyError as error:
            ranges = self.assembly_intervals()
            reason = (f"the rod cannot reach the guide (rod = {self.rod:.10g} m < crank + |offset| = "
                      f"{self.crank + abs(self.offset):.10g} m, so the crank cannot turn fully)")
            one = len(ranges) == 1
            raise AssemblyError(reason, angles=error.angles, valid_range=ranges[0] if one else None,
                                valid_ranges=None if one else ranges) from None
        pivot = fixed_point(0j, phi, order)
        return Solution(phi, order, angles={"crank": crank, "coupler": block.rod_angle},
                        points={"O": pivot, "A": pin, "B": block.point}, links=self.links,
                        sliders={"B": block.travel}, singular=block.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        # the guide is drawn centred near the middle of the stroke
        return (Guide(complex(self.branch * self.rod, self.offset), 0.0), Ground("O"),
                Bar("crank", ("O", "A"), "crank"), Bar("coupler", ("A", "B"), "coupler"), Block("B", 0.0))

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        return {("O", "A"): self.crank, ("A", "B"): self.rod}

    def coordinates(self, solution: Solution) -> list[Motion]:
        """q = (ψ, s): the coupler angle and the slider's position."""
        return [solution.angle("coupler"), solution.slider("B")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        """Φ = (L1 cos φ + L2 cos ψ − s, L1 sin φ + L2 sin ψ − e): the loop O→A→B closes on the guide."""
        psi, s = q
        return (self.crank * np.cos(phi) + self.rod * np.cos(psi) - s,
                self.crank * np.sin(phi) + self.rod * np.sin(psi) - self.offset)

    def __repr__(self) -> str:
        return (f"CrankSlider(crank={self.crank!r}, rod={self.rod!r}, offset={self.offset!r}, "
                f"branch={self.branch:+d})")
