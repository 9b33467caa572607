"""Layer 3: the crank-slider (chapter 3), axial or offset.

The crank O→A (length L1) turns about the origin; the coupler (connecting rod) A→B (length L2)
drives the slider B along the fixed guide y = e. It is the crank block followed by the
circle–line block (:func:`~mechanisms.blocks.circle_line.slider_on_line`).
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .chunks import solve_in_chunks
from .groups import RRP, Crank, Group
from .base import (Bar, Block, Ground, Guide, Mechanism, Parameter, Solution, family_pin, family_shape, is_family,
                   member_values)
from ..blocks.circle_line import slider_on_line
from ..blocks.crank import crank_pin
from ..core.errors import AssemblyError, InvalidParameterError
from ..core.validate import require_branch, require_coordinate, require_flag, require_length
from ..core.motion import AngleMotion, Motion, PointMotion, fixed_point

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
    crank : float or array_like
        Crank length L1 = |OA| (m), > 0.
    rod : float or array_like
        Coupler (connecting-rod) length L2 = |AB| (m), > 0.
    offset : float or array_like
        Offset e (m): the slider's guide is the line y = e, parallel to x (0 for the axial mechanism).
    branch : int or array_like of int
        +1: the slider works on the +x side of the crank pin (B to the right of A), and so, for a crank
        that turns fully, on the +x side of the crank pivot; −1: on the −x side.
    lenient : bool
        False (default): a linkage (a member of a family, named by its index) whose rod cannot reach the
        guide raises :class:`AssemblyError`. True: those positions are marked False in
        :attr:`Solution.assembled` and are ``nan``.

    Notes
    -----
    A family of crank-sliders: any of the dimensions (and ``branch``) as arrays of one shape G (or shapes that
    broadcast to it), each member checked as one linkage is (a bad one named by its index, ``rod[2]``).
    Solving at N crank angles (one-dimensional ``phi``) gives arrays of shape G + (N,), each member as it is
    solved alone. What is defined for one linkage only (:meth:`assembly_intervals`, the dead centres, the
    stroke, a linkage file …) refuses a family with :class:`InvalidParameterError`.

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

    # one linkage: floats (and an int branch); a family: arrays of shape G (typed Any for the two)
    crank: Any
    rod: Any
    offset: Any
    branch: Any

    def __init__(self, crank: ArrayLike, rod: ArrayLike, offset: ArrayLike = 0.0, branch: ArrayLike = 1,
                 lenient: bool = False):
        self.lenient = require_flag("lenient", lenient)
        if is_family(crank, rod, offset, branch):
            self._family(crank, rod, offset, branch)
            return
        self.crank = require_length("crank", crank)
        self.rod = require_length("rod", rod)
        self.offset = require_coordinate("offset", offset)
        self.branch = require_branch(branch)
        ranges = assembly_ranges(self.crank, self.rod, self.offset)
        if ranges == [] and not self.lenient:
            raise AssemblyError(f"the rod cannot reach the guide at any crank angle: rod = {self.rod:g} m is "
                                f"shorter than |offset| − crank = {abs(self.offset) - self.crank:g} m")

    def _family(self, crank: ArrayLike, rod: ArrayLike, offset: ArrayLike, branch: ArrayLike) -> None:
        """Set a family's dimensions: arrays of one shape G, checked member by member."""
        values = {"crank": member_values("crank", crank, "length"), "rod": member_values("rod", rod, "length"),
                  "offset": member_values("offset", offset, "coordinate"),
                  "branch": member_values("branch", branch, "branch")}
        shape = family_shape(**values)
        self.family_parameters = tuple(name for name, value in values.items() if value.ndim)
        l1, l2, e, side = (np.broadcast_to(v, shape) for v in values.values())
        never = l2 < np.abs(e) - l1
        if never.any() and not self.lenient:
            index = tuple(int(i) for i in np.argwhere(never)[0])
            label = ", ".join(map(str, index))
            raise AssemblyError(f"member {label} of the family cannot be assembled at any crank angle: its rod "
                                f"({l2[index]:g} m) cannot reach the guide (|offset| − crank = "
                                f"{abs(e[index]) - l1[index]:g} m; {int(np.count_nonzero(never))} member(s) in all; "
                                "lenient=True marks them instead)")
        self.crank, self.rod, self.offset = l1, l2, e
        self.branch = side.astype(int)
        self.family_shape = shape

    benchmark = True

    @classmethod
    def example(cls) -> "CrankSlider":
        """The benchmark's offset crank-slider: L1 = 1 m, L2 = 3.5 m, e = 0.5 m."""
        return cls(crank=1.0, rod=3.5, offset=0.5)

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Crank-angle intervals (rad) of assembly: ``[(−π, π)]`` for a full revolution (L2 ≥ L1 + |e|),
        else those of :func:`assembly_ranges`."""
        self.require_one_linkage("the assembly intervals")
        ranges = assembly_ranges(self.crank, self.rod, self.offset)
        return [(-math.pi, math.pi)] if ranges is None else ranges

    def linkage_data(self) -> dict:
        """This crank-slider as the contents of a linkage file (:mod:`~mechanisms.linkages.linkage_file`).

        The crank O → A, and an RRP dyad: the coupler A → B with the slider B on the guide y = e; the
        dyad's branch is the class's (+1: B farther along +x than A). Loaded, it is the same linkage.
        """
        self.require_one_linkage("a linkage file")
        return {"name": "Crank-slider", "frame": {"O": [0.0, 0.0]},
                "crank": {"pivot": "O", "pin": "A", "length": self.crank},
                "dyad": [{"type": "RRP", "joint": "B", "from": "A", "length": self.rod,
                          "guide": {"through": [0.0, self.offset], "angle_deg": 0.0}, "branch": self.branch,
                          "links": ["coupler", "slider"]}]}

    def groups(self) -> tuple[Group, ...]:
        self.require_one_linkage("the structure (plans, instant centres)")
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
        return CrankSlider(self.crank * factor, self.rod * factor, self.offset * factor, self.branch, self.lenient)

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        if self.family_shape or self.lenient:
            return self._solve_family(crank, order)
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

    def _solve_family(self, crank: AngleMotion, order: int) -> Solution:
        """A family (or a linkage solved leniently): every member at every crank angle, arrays G + (N,)."""
        phi = crank.value
        full, (l1, l2, e, side) = self._family_columns(phi, self.crank, self.rod, self.offset, self.branch)
        pin = family_pin(crank, l1)
        block = slider_on_line(pin, l2, through=1j * e, direction=0.0, branch=side, angles=phi, lenient=True)
        assembled = np.asarray(block.assembled)
        if not self.lenient and not assembled.all():
            if not self.family_shape:
                self._solve_block(AngleMotion(phi), 0)     # one linkage: its own message, with its intervals
            first, failing = self._first_failing(assembled)
            raise AssemblyError(f"member {', '.join(map(str, first))} of the family cannot be assembled at some crank "
                                f"angles: its rod ({self.rod[first]:g} m) is shorter than crank + |offset| = "
                                f"{self.crank[first] + abs(self.offset[first]):g} m ({failing} in all; solve with "
                                "lenient=True to mark them instead)", phi[~assembled[first]])
        angle, origin = self._family_motions(crank, full, order)
        return Solution(phi, order, angles={"crank": angle, "coupler": block.rod_angle},
                        points={"O": origin, "A": pin, "B": block.point},
                        links=self.links, sliders={"B": block.travel}, singular=block.singular, assembled=assembled)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        self.require_one_linkage("a drawing")
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
        # a family's dimensions per member (a row of positions each)
        l1, l2, e = (np.asarray(v)[..., np.newaxis] if self.family_shape else v
                     for v in (self.crank, self.rod, self.offset))
        return (l1 * np.cos(phi) + l2 * np.cos(psi) - s,
                l1 * np.sin(phi) + l2 * np.sin(psi) - e)

    def __repr__(self) -> str:
        branch = f"{self.branch!r}" if self.family_shape else f"{self.branch:+d}"
        return f"CrankSlider(crank={self.crank!r}, rod={self.rod!r}, offset={self.offset!r}, branch={branch})"
