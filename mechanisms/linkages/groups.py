"""Layer 3: the structure of a mechanism — its driving crank and its Assur groups, as data.

A mechanism says how it is built by :meth:`~mechanisms.linkages.base.Mechanism.groups`: the crank
first, then the groups in the order they are solved, each naming the joints it needs (already
known) and the joint it finds, and the links it adds. The upper layers read this description
instead of asking which class a mechanism is: the velocity and acceleration plans and the instant
centres (:mod:`mechanisms.analysis.plans`) build one step per group, and a
:class:`~mechanisms.linkages.composed.Linkage` is *solved* from it, group after group.

The kinds of two-link (class II) Assur groups are named by their pairs, R a turning pair and P a
sliding pair, in the order of the chain external–internal–external:

* RRR (:class:`RRR`): two links at a hinge;
* RRP (:class:`RRP`): a link ending in a slider on a guide;
* RPR (:class:`RPR`): a block hinged at a known joint, sliding on a lever about a known pivot;
* PRP (:class:`PRP`): two blocks hinged together, each sliding on its own guide;
* RPP (:class:`RPP`): a block hinged at a known joint, sliding in the slot of a yoke that slides
  on a guide (the Scotch yoke).

A group with no closed form — a class III group, three joints found together — is a
:class:`Triad` of bars, solved by Newton's method. Points fixed to a link are :class:`LinkPoint`.

A guide is a straight line carried by a link (:class:`Line`, the frame's or a moving link's). Every
link has its own frame: its first joint at the origin, its x axis at the link's angle; a point of
a link is given in that frame, ``along + i·left`` (m). The links are numbered in the order the
groups add them: the frame 0, the crank 1, and so on (:func:`link_numbers`).

The geometric fields (lengths, branches, guides) default to ``None`` where a mechanism class only
*describes* its structure; a :class:`~mechanisms.linkages.composed.Linkage` needs them all.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Union

__all__ = ["Crank", "RRR", "RRP", "RPR", "PRP", "RPP", "Triad", "Line", "LinkPoint", "Group",
           "link_numbers", "four_link", "KINDS"]


@dataclass(frozen=True)
class Line:
    """A straight line carried by a link: a guide, or the slot of a yoke.

    Parameters
    ----------
    link : str
        The link that carries the line (``"frame"`` for a fixed guide).
    point : complex
        A point of the line in the link's frame (m); for the frame, in the plane's coordinates.
    angle : float
        The line's direction (rad), from the link's x axis (for the frame, from +x).
    """

    link: str = "frame"
    point: complex = 0j
    angle: float = 0.0


@dataclass(frozen=True)
class Crank:
    """The driver: a link turning about the frame pivot ``pivot``; its end is the joint ``pin``.

    ``length`` is |pivot → pin| (m); the crank angle φ is the angle of that vector.
    """

    pivot: str
    pin: str
    link: str = "crank"
    length: float | None = None

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link,)

    @property
    def needs(self) -> tuple[str, ...]:
        return (self.pivot,)

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.pin,)


@dataclass(frozen=True)
class RRR:
    """Two links meeting at a hinge: ``joint`` at fixed distances from the known joints ``first`` and ``second``.

    ``first_link`` joins ``first`` to ``joint`` (length ``first_length``), ``second_link`` joins
    ``second`` to ``joint`` (``second_length``); for the four-bar, the coupler A → B and the rocker
    C → B. ``branch`` +1 puts the joint to the left of the directed line first → second, −1 to
    its right.
    """

    joint: str
    first: str
    second: str
    first_link: str
    second_link: str
    first_length: float | None = None
    second_length: float | None = None
    branch: int = 1

    @property
    def links(self) -> tuple[str, ...]:
        return (self.first_link, self.second_link)

    @property
    def needs(self) -> tuple[str, ...]:
        return (self.first, self.second)

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.joint,)


@dataclass(frozen=True)
class RRP:
    """A link from the known joint ``known`` to ``joint``, a slider on a straight guide.

    ``link`` is the connecting link (length ``length``), ``slider`` the sliding block (the
    crank-slider's coupler A → B and its slider B). The guide passes through ``through`` at
    ``guide_angle`` (rad), both in the frame of ``guide_link`` (the frame's by default: a fixed
    guide). ``branch`` +1 takes the solution farther along the guide's direction, −1 the nearer.
    """

    joint: str
    known: str
    link: str
    slider: str = "slider"
    guide_angle: float = 0.0
    length: float | None = None
    branch: int = 1
    through: complex = 0j
    guide_link: str = "frame"

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link, self.slider)

    @property
    def guide(self) -> Line:
        """The guide as a :class:`Line`."""
        return Line(self.guide_link, self.through, self.guide_angle)

    @property
    def guide_direction(self) -> complex:
        """The guide's unit direction ``exp(i·guide_angle)`` (in its link's frame)."""
        return complex(math.cos(self.guide_angle), math.sin(self.guide_angle))

    @property
    def needs(self) -> tuple[str, ...]:
        return (self.known,)

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.joint,)


@dataclass(frozen=True)
class RPR:
    """A block hinged at the known joint ``block`` slides on a ``lever`` that turns about the known pivot ``pivot``.

    ``slider`` is the block (the slotted lever's block on the crank pin A, its lever about C). The
    lever's angle is that of the vector pivot → block. ``joint``, if given, is the point of the
    lever at ``length`` (m) from the pivot on the block's side (the end of the shaper's lever).
    """

    block: str
    pivot: str
    lever: str
    slider: str = "slider"
    joint: str | None = None
    length: float | None = None

    @property
    def links(self) -> tuple[str, ...]:
        return (self.slider, self.lever)

    @property
    def needs(self) -> tuple[str, ...]:
        return (self.block, self.pivot)

    @property
    def finds(self) -> tuple[str, ...]:
        return () if self.joint is None else (self.joint,)


@dataclass(frozen=True)
class PRP:
    """Two blocks hinged together at ``joint``, each sliding on its own guide: ``joint`` is where the guides cross.

    ``first_slider`` slides on ``first_guide``, ``second_slider`` on ``second_guide`` (each a
    :class:`Line` carried by a known link).
    """

    joint: str
    first_guide: Line
    second_guide: Line
    first_slider: str
    second_slider: str

    @property
    def links(self) -> tuple[str, ...]:
        return (self.first_slider, self.second_slider)

    @property
    def needs(self) -> tuple[str, ...]:
        return ()

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.joint,)


@dataclass(frozen=True)
class RPP:
    """A block hinged at the known joint ``block`` slides in the slot of a ``yoke`` that slides on ``guide``.

    The slot makes the angle ``slot_angle`` (rad) with the guide and passes through the yoke's
    point ``joint``, which lies on the guide (the Scotch yoke: slot at 90° to the guide). The yoke
    translates along the guide (it turns only if the guide's link does); ``slider`` is the block.
    """

    joint: str
    block: str
    guide: Line
    slot_angle: float
    slider: str
    yoke: str

    @property
    def links(self) -> tuple[str, ...]:
        return (self.slider, self.yoke)

    @property
    def needs(self) -> tuple[str, ...]:
        return (self.block,)

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.joint,)


@dataclass(frozen=True)
class Triad:
    """A group found as a whole, with no closed form: joints held by bars of fixed length.

    Parameters
    ----------
    joints : tuple of str
        The joints the group finds (three for a class III group).
    bars : tuple of (str, str, float)
        Each bar: two joints (known or of this group) and the distance between them (m). Bars that
        form a triangle of the group's joints are one rigid (ternary) link.
    guess : tuple of complex
        The joints' positions (m), roughly, at the crank angle ``guess_angle``: they choose the
        assembly mode, which is then followed by continuation.
    guess_angle : float
        The crank angle of the guess (rad).
    names : tuple of str
        The names of the group's links, in the order of :meth:`bodies`.
    """

    joints: tuple[str, ...]
    bars: tuple[tuple[str, str, float], ...]
    guess: tuple[complex, ...]
    guess_angle: float = 0.0
    names: tuple[str, ...] = ()

    def bodies(self) -> list[tuple[str, ...]]:
        """The group's rigid links as joint tuples: each triangle of bars among its joints, then the other bars."""
        pairs = {frozenset(bar[:2]) for bar in self.bars}
        triangles: list[tuple[str, ...]] = []
        for i, a in enumerate(self.joints):
            for j, b in enumerate(self.joints[i + 1:], i + 1):
                for c in self.joints[j + 1:]:
                    if {frozenset((a, b)), frozenset((b, c)), frozenset((a, c))} <= pairs:
                        triangles.append((a, b, c))
        in_triangle = {frozenset(p) for t in triangles for p in ((t[0], t[1]), (t[1], t[2]), (t[0], t[2]))}
        singles = [(a, b) for a, b, _ in self.bars if frozenset((a, b)) not in in_triangle]
        return [*triangles, *singles]

    @property
    def links(self) -> tuple[str, ...]:
        return self.names or tuple("".join(body) for body in self.bodies())

    @property
    def needs(self) -> tuple[str, ...]:
        own = set(self.joints)
        return tuple(dict.fromkeys(j for bar in self.bars for j in bar[:2] if j not in own))

    @property
    def finds(self) -> tuple[str, ...]:
        return self.joints


@dataclass(frozen=True)
class LinkPoint:
    """A joint ``name`` fixed to a link already found (the end B of the shaper's lever).

    ``along`` and ``left`` (m) place it in the link's frame, or, with ``axis = (P, Q)`` (two joints
    of the link), ``along`` the line P → Q from P and ``left`` of it. Instead of ``along`` and
    ``left``, ``distances = (|PE|, |QE|)`` (m) with ``branch`` (+1: to the left of P → Q) place it
    as the apex of a rigid triangle. ``along`` is ``None`` where a mechanism class only describes
    its structure.
    """

    name: str
    link: str
    along: float | None = None
    left: float = 0.0
    axis: tuple[str, str] | None = None
    distances: tuple[float, float] | None = None
    branch: int = 1

    @property
    def links(self) -> tuple[str, ...]:
        return ()

    @property
    def needs(self) -> tuple[str, ...]:
        return () if self.axis is None else self.axis

    @property
    def finds(self) -> tuple[str, ...]:
        return (self.name,)


Group = Union[Crank, RRR, RRP, RPR, PRP, RPP, Triad, LinkPoint]
"""One step of a mechanism's structure."""

KINDS: dict[type, str] = {RRR: "RRR", RRP: "RRP", RPR: "RPR", PRP: "PRP", RPP: "RPP"}
"""The kind of each class II group, by its pairs in the order of the chain."""


def link_numbers(groups: Sequence[Group]) -> dict[str, int]:
    """The links numbered as the groups add them: frame 0, crank 1, … (the names of instant centres P_ij)."""
    numbers = {"frame": 0}
    for group in groups:
        for link in group.links:
            numbers.setdefault(link, len(numbers))
    return numbers


def four_link(groups: Sequence[Group]) -> tuple[Crank, RRR | RRP] | None:
    """``(crank, dyad)`` of a four-link mechanism, a crank and one RRR or RRP group (a four-bar, a
    crank-slider); ``None`` for any other structure."""
    if len(groups) == 2 and isinstance(groups[0], Crank) and isinstance(groups[1], (RRR, RRP)):
        return groups[0], groups[1]
    return None
