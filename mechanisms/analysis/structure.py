"""Layer 4: structural analysis — degrees of freedom of a planar linkage (chapter 2), and the
structure of a composed linkage: its links, pairs and Assur groups (chapter 6)."""

from __future__ import annotations

from dataclasses import dataclass

from ..core.errors import InvalidParameterError
from ..linkages.composed import Linkage, describe_group
from ..linkages.groups import LinkPoint, Triad

__all__ = ["mobility", "Structure", "BOOK_STRUCTURES", "StructureReport", "GroupReport", "structure_of"]


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
