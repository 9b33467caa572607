"""Layer 3: Chebyshev's lambda mechanism (Pylypaka and Chepizhnyi, 2019, problem 4), chapter 4.

A four-bar whose coupler is extended beyond the rocker joint: crank O → A of length r about
O = (0, 0); coupler A → P of length 2b; rocker C → B of length b about C = (−d, 0), hinged to
the coupler at its midpoint B (AB = BP = CB = b). The point P traces a curve with a nearly
straight part: the lambda mechanism is a straight-line guide. The joints carry the book's letters
(chapter 4, §4.9); the source's B, C, D are the book's P, B, C.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .base import Bar, Block, Ground, Guide, Mechanism, Parameter, Solution
from ..core.errors import AssemblyError
from ..core.validate import require_branch, require_length
from .four_bar import FourBar
from ..core.motion import AngleMotion, Motion, point_on_link

__all__ = ["LambdaMechanism"]


class LambdaMechanism(Mechanism):
    """Chebyshev's lambda mechanism: crank r, coupler A→P of length 2b, rocker C→B of length b.

    Parameters
    ----------
    crank : float
        Crank length r = OA (m).
    half_coupler : float
        b = AB = BP = CB (m): half the coupler, and the rocker (the book's L₂ = L₃).
    ground : float
        d (m): the rocker pivot C is at (−d, 0).
    branch : int
        Side of the directed line A → C on which B lies: −1 (default) puts B above the frame
        line, as in the source's figure; +1 is the mirror assembly.

    Notes
    -----
    Joints O, A, B, P, C, the book's letters (chapter 4, §4.9; the source's B, C, D are P, B, C);
    links ``crank`` (O→A, angle φ), ``coupler`` (A→P, angle ψ of the chapter; the source measures
    γ = π − ψ from −x) and ``rocker`` (C→B, angle ξ). It is the four-bar O-A-B-C of chapter 4 with
    P = A + 2(B − A), so the four-bar's continuation rule holds at a change point (d + r = 2b).
    """

    cli_name = "lambda"
    cli_parameters = (
        Parameter("crank", "length", "crank length r = OA, m"),
        Parameter("half_coupler", "length", "b = AB = BP = CB, m (coupler A->P has length 2b)"),
        Parameter("ground", "length", "d, m: the rocker pivot C is at (-d, 0)"),
    )
    links = {"crank": "O", "coupler": "A", "rocker": "C"}

    @classmethod
    def example(cls) -> "LambdaMechanism":
        """Chebyshev's lambda mechanism of chapter 4: crank 2 m, half coupler 6.5 m, ground 5 m."""
        return cls(crank=2.0, half_coupler=6.5, ground=5.0)

    def __init__(self, crank: float, half_coupler: float, ground: float, branch: int = -1,
                 keep_side: bool = False):
        self.crank = require_length("crank", crank)
        self.half_coupler = require_length("half_coupler", half_coupler)
        self.ground = require_length("ground", ground)
        self.branch = require_branch(branch)
        self.four_bar = FourBar(self.crank, self.half_coupler, self.half_coupler, (-self.ground, 0.0), self.branch,
                                 keep_side)
        self.keep_side = self.four_bar.keep_side

    def _rescaled(self, factor: float) -> "LambdaMechanism":
        return LambdaMechanism(self.crank * factor, self.half_coupler * factor, self.ground * factor, self.branch,
                               self.keep_side)

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Those of its four-bar O–A–B–C (see :meth:`FourBar.assembly_intervals`)."""
        return self.four_bar.assembly_intervals()

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        try:
            inner = self.four_bar._solve(crank, order)
        except AssemblyError as error:
            raise AssemblyError(error.reason.replace("four-bar", "lambda mechanism"), error.angles,
                                error.valid_range, error.nowhere) from None
        coupler = inner.angle("coupler")
        end = point_on_link(inner.point("A"), coupler, 2.0 * self.half_coupler)
        return Solution(crank.value, order,
                        angles={"crank": crank, "coupler": coupler, "rocker": inner.angle("rocker")},
                        points={"O": inner.point("O"), "A": inner.point("A"), "B": inner.point("B"), "P": end,
                                "C": inner.point("C")},
                        links=self.links, singular=inner.singular)

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        return [Ground("O"), Ground("C"), Bar("crank", ("O", "A"), "crank"),
                Bar("coupler", ("A", "B", "P"), "coupler"), Bar("rocker", ("C", "B"), "rocker")]

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        b = self.half_coupler
        return {("O", "A"): self.crank, ("A", "B"): b, ("B", "P"): b, ("A", "P"): 2.0 * b, ("C", "B"): b,
                ("O", "C"): self.ground}

    def coordinates(self, solution: Solution) -> list[Motion]:
        return [solution.angle("coupler"), solution.angle("rocker")]

    def constraints(self, q: Sequence, phi: ArrayLike) -> tuple:
        psi, epsilon = q
        r, b, d = self.crank, self.half_coupler, self.ground
        return (r * np.cos(phi) + b * np.cos(psi) - b * np.cos(epsilon) + d,
                r * np.sin(phi) + b * np.sin(psi) - b * np.sin(epsilon))
