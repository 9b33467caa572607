"""A small mechanism used to test the foundation independently of the book's chapters.

The Scotch yoke: crank O–A of length r; a yoke (slider) on the x axis whose slot is
perpendicular to it and carries the crank pin. Its closed form is elementary (by hand):
s = r cos φ, s_t = −r φ_t sin φ, s_tt = −r (φ_tt sin φ + φ_t² cos φ).
"""

import numpy as np

from mechanisms.linkages.base import Bar, Block, Ground, Guide, Mechanism, Parameter, Solution
from mechanisms.blocks.crank import crank_pin
from mechanisms.core.validate import require_length
from mechanisms.core.motion import Motion, PointMotion


class ScotchYoke(Mechanism):
    """Scotch yoke: crank O–A, a yoke B on the x axis driven by the pin in its vertical slot."""

    links = {"crank": "O"}
    cli_parameters = (Parameter("crank", "length", "crank length r, m"),)

    def __init__(self, crank: float):
        self.crank = require_length("crank", crank)

    def _solve(self, crank, order):
        a = crank_pin(crank, self.crank)
        b = PointMotion(*(None if d is None else d.real + 0j for d in a.derivatives()))
        o = PointMotion(*(None if d is None else np.zeros_like(d) for d in a.derivatives()))
        return Solution(crank.value, order, angles={"crank": crank}, points={"O": o, "A": a, "B": b},
                        links=self.links, sliders={"B": Motion(*(None if d is None else d.real for d in b.derivatives()))})

    def scheme(self):
        return (Guide(0j, 0.0), Ground("O"), Bar("crank", ("O", "A"), "crank"), Bar("yoke", ("B", "A"), "slider"),
                Block("A", np.pi / 2), Block("B", 0.0))

    def preserved_distances(self):
        return {("O", "A"): self.crank}

    def coordinates(self, solution):
        return [solution.slider("B")]

    def constraints(self, q, phi):
        (s,) = q
        return (s - self.crank * np.cos(phi),)
