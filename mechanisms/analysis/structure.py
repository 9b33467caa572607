"""Layer 4: structural analysis — degrees of freedom of a planar linkage (chapter 2), and the
structure of a composed linkage: its links, pairs and Assur groups (chapter 6)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..core.errors import InvalidParameterError, SingularPositionWarning
from ..core.motion import AngleMotion, PointMotion
from ..core.validate import require_finite_array, require_length
from ..linkages.composed import Linkage, describe_group
from ..linkages.groups import LinkPoint, Triad

__all__ = ["mobility", "Structure", "BOOK_STRUCTURES", "StructureReport", "GroupReport", "structure_of",
           "dyad_rates"]


def mobility(moving_links: int, lower_pairs: int, higher_pairs: int = 0) -> int:
    """Degrees of freedom W of a planar linkage by the structural (Kutzbach–Grübler) formula.

    Parameters
    ----------
    moving_links : int
        n, the number of moving links (the frame not counted).
    lower_pairs : int
        p1, hinges and sliding pairs: each leaves one relative degree of freedom.
    higher_pairs : int
        p2, point or line contacts (cams, gears): each leaves two.

    Returns
    -------
    int
        ``W = 3n − 2 p1 − p2``.

    Notes
    -----
    The Kutzbach–Grübler criterion of the English-language books, Chebyshev's structural formula
    of the Russian ones (chapters 2 and 6): W = 3n − 2p₁ − p₂.
    """
    for name, value in (("moving_links", moving_links), ("lower_pairs", lower_pairs),
                        ("higher_pairs", higher_pairs)):
        if not isinstance(value, int) or isinstance(value, bool) or value < 0:
            raise InvalidParameterError(name, value, "a whole number ≥ 0")
    return 3 * moving_links - 2 * lower_pairs - higher_pairs


@dataclass(frozen=True)
class Structure:
    """A mechanism of the book with its links and pairs counted."""

    name: str
    links: str
    pairs: str
    moving_links: int
    lower_pairs: int

    @property
    def mobility(self) -> int:
        """Degrees of freedom W."""
        return mobility(self.moving_links, self.lower_pairs)


BOOK_STRUCTURES: tuple[Structure, ...] = (
    Structure("crank-slider", "crank, coupler, slider", "3 hinges (O, A, B) + slider–guide", 3, 4),
    Structure("four-bar (crank-rocker)", "crank, coupler, rocker", "4 hinges (O, A, B, C)", 3, 4),
    Structure("Chebyshev's lambda mechanism", "crank, coupler, rocker", "4 hinges", 3, 4),
    Structure("crank with slotted lever", "crank, block, lever", "3 hinges (O, A, C) + block–lever", 3, 4),
    Structure("shaper", "crank, block, lever, rod, ram", "5 hinges + block–lever + ram–guide", 5, 7),
)
"""The mechanisms of chapters 3–5, counted for the structural formula."""


@dataclass(frozen=True)
class GroupReport:
    """One step of a linkage's structure: its class (I for the crank, II, III), kind and links."""

    number: int
    description: str
    assur_class: str
    kind: str
    links: tuple[str, ...]
    solved_by: str


@dataclass(frozen=True)
class StructureReport:
    """The structural analysis of a linkage: links, pairs, degrees of freedom, Assur groups in order.

    Attributes
    ----------
    name : str
        The linkage's name (and its file).
    links : dict of str to list of str
        Every link, the frame first, with the joints and points fixed to it.
    pairs : list of (str, str, str, str)
        Each kinematic pair: kind ("R" hinge, "P" sliding pair), the two links, the joint.
    moving_links, lower_pairs : int
        n and p of the structural formula.
    groups : list of GroupReport
        The crank, then the groups (and points) in the order they are solved.
    """

    name: str
    links: dict[str, list[str]]
    pairs: list[tuple[str, str, str, str]]
    moving_links: int
    lower_pairs: int
    groups: list[GroupReport]

    @property
    def mobility(self) -> int:
        """Degrees of freedom W = 3n − 2p₁ (p₁ lower pairs)."""
        return mobility(self.moving_links, self.lower_pairs)

    @property
    def mechanism_class(self) -> str:
        """The class of the mechanism: the highest class of its groups (Assur, Artobolevsky)."""
        classes = [g.assur_class for g in self.groups if g.assur_class not in ("-", "I")]
        return max(classes, key=lambda c: ("III" in c, "≥" in c, c), default="I")

    def text(self) -> str:
        """The report as the command line prints it."""
        width = max(len(name) for name in self.links)
        lines = [self.name, "", f"Links: n = {self.moving_links} moving, and the frame"]
        lines += [f"  {i:2d}  {name.ljust(width)}  {', '.join(joints)}" for i, (name, joints) in
                  enumerate(self.links.items())]
        hinges = sum(1 for p in self.pairs if p[0] == "R")
        lines += ["", f"Kinematic pairs: p₁ = {self.lower_pairs} lower pairs ({hinges} hinges R, "
                      f"{self.lower_pairs - hinges} sliding pairs P), no higher pairs"]
        lines += [f"  {kind}  {first} – {second}" + (f" at {joint}" if kind == "R" else f" (block at {joint})")
                  for kind, first, second, joint in self.pairs]
        lines += ["", "Degrees of freedom (Kutzbach–Grübler): W = 3n − 2p₁ − p₂ = "
                      f"3·{self.moving_links} − 2·{self.lower_pairs} − 0 = {self.mobility}", "",
                  "Groups in the order they are solved:"]
        for g in self.groups:
            if g.assur_class == "-":
                lines.append(f"  {g.number:2d}. {g.description}  (a point of a link)")
                continue
            head = f"class {g.assur_class}" + (f", kind {g.kind}" if g.assur_class == "II" else "")
            lines.append(f"  {g.number:2d}. {g.description}: {head}; links {', '.join(g.links)}; {g.solved_by}")
        lines += ["", f"The mechanism is of class {self.mechanism_class} (the highest class of its groups)."]
        return "\n".join(lines)

    def json(self) -> str:
        """The report as JSON."""
        import json

        return json.dumps({"name": self.name, "links": self.links,
                           "pairs": [dict(zip(("kind", "first", "second", "joint"), p)) for p in self.pairs],
                           "moving_links": self.moving_links, "lower_pairs": self.lower_pairs,
                           "mobility": self.mobility, "class": self.mechanism_class,
                           "groups": [g.__dict__ for g in self.groups]}, indent=1, ensure_ascii=False)


def structure_of(linkage: Linkage) -> StructureReport:
    """Structural analysis of a composed linkage (chapter 6): what ``python -m mechanisms structure`` prints."""
    groups = []
    for number, group in enumerate(linkage.groups(), 1):
        assur_class, kind = linkage.group_kind(group)
        if isinstance(group, Triad):
            solved_by = "no closed form: solved by Newton's method, continued from the guess"
        elif isinstance(group, LinkPoint):
            solved_by = ""
        else:
            solved_by = "closed form"
        groups.append(GroupReport(number, describe_group(group), assur_class, kind, group.links, solved_by))
    pairs = [(p.kind, p.first, p.second, p.joint) for p in linkage.pairs()]
    links = linkage.link_joints()
    return StructureReport(linkage.describe(), links, pairs, len(links) - 1, len(pairs), groups)


SINGULAR_SINE = 1e-12
"""|sin(θ₅ − θ₄)| below which :func:`dyad_rates` warns that the dyad's links are in line."""


def dyad_rates(first: PointMotion, second: PointMotion, first_angle: ArrayLike, second_angle: ArrayLike,
               first_length: float, second_length: float) -> tuple[AngleMotion, AngleMotion]:
    """Angular velocities and accelerations of an RRR dyad whose outer joints both move, by hand (chapter 6).

    The dyad's links run from the outer joints E (``first``) and H (``second``) to their common hinge F,
    of lengths L₄ and L₅ and at the angles θ₄ and θ₅, so that ``E + L₄ e^{iθ₄} = H + L₅ e^{iθ₅}``
    (chapter 6, §6.6, whose letters these are).

    Parameters
    ----------
    first, second : PointMotion
        The outer joints E and H with their velocities and accelerations (m, m/s, m/s²): solve with
        ``order=2``.
    first_angle, second_angle : array_like
        θ₄ and θ₅ (rad), the directions from E and from H to the hinge F, at the same positions.
    first_length, second_length : float
        L₄ = |EF| and L₅ = |HF| (m).

    Returns
    -------
    (AngleMotion, AngleMotion)
        θ₄ and θ₅ with their angular velocities (1/s) and accelerations (1/s²).

    Raises
    ------
    MissingDerivativeError
        If ``first`` or ``second`` lacks accelerations.

    Warns
    -----
    SingularPositionWarning
        Where the two links are in line, |sin(θ₅ − θ₄)| < :data:`SINGULAR_SINE`: the rates there are
        infinite or undetermined, and the values returned are meaningless.

    Notes
    -----
    Differentiating the loop equation, with Δv = v_H − v_E and Δa = a_H − a_E,
    ``i L₄ θ₄ₜ e^{iθ₄} − i L₅ θ₅ₜ e^{iθ₅} = Δv``; its component along link 5 (multiply by e^{−iθ₅},
    take the real part) removes θ₅ₜ, and along link 4 removes θ₄ₜ:
    ``θ₄ₜ = Re(Δv e^{−iθ₅}) / (L₄ sin(θ₅ − θ₄))``, ``θ₅ₜ = Re(Δv e^{−iθ₄}) / (L₅ sin(θ₅ − θ₄))``.
    The accelerations solve the same system with ``f = Δa + L₄ θ₄ₜ² e^{iθ₄} − L₅ θ₅ₜ² e^{iθ₅}`` in place
    of Δv. For a fixed H this is the four-bar's Cramer's rule (chapter 4).
    """
    theta_1 = require_finite_array("first_angle", first_angle, "rad")
    theta_2 = require_finite_array("second_angle", second_angle, "rad")
    a = require_length("first_length", first_length)
    b = require_length("second_length", second_length)
    dv = second.d1 - first.d1
    da = second.d2 - first.d2
    e1, e2 = np.exp(1j * theta_1), np.exp(1j * theta_2)
    sine = np.sin(theta_2 - theta_1)
    if np.any(np.abs(sine) < SINGULAR_SINE):
        warnings.warn("the dyad's two links are in line at some positions: their rates are infinite or "
                      "undetermined there", SingularPositionWarning, stacklevel=2)
    with np.errstate(divide="ignore", invalid="ignore"):
        omega_1 = np.real(dv * np.conj(e2)) / (a * sine)
        omega_2 = np.real(dv * np.conj(e1)) / (b * sine)
        f = da + a * omega_1**2 * e1 - b * omega_2**2 * e2
        alpha_1 = np.real(f * np.conj(e2)) / (a * sine)
        alpha_2 = np.real(f * np.conj(e1)) / (b * sine)
    return AngleMotion(theta_1, omega_1, alpha_1), AngleMotion(theta_2, omega_2, alpha_2)
