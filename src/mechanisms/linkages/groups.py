"""Layer 3: the structure of a mechanism — its driving crank and its Assur groups, as data.

A mechanism says how it is built by :meth:`~mechanisms.linkages.base.Mechanism.groups`: the crank
first, then the groups in the order they are solved, each naming the joints it needs (already
known) and the joint it finds, and the links it adds. The upper layers read this description
instead of asking which class a mechanism is: the velocity and acceleration plans and the instant
centres (:mod:`mechanisms.analysis.plans`) build one step per group.

The kinds of two-link (class II) Assur groups are named by their pairs, R a turning pair and P a
sliding pair, in the order of the chain: RRR (two links at a hinge), RRP (a link ending in a slider
on a fixed guide), RPR (a block hinged at a known joint, sliding on a lever about a frame pivot).
The links are numbered in the order the groups add them: the frame 0, the crank 1, and so on
(:func:`link_numbers`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Union

__all__ = ["Crank", "RRR", "RRP", "RPR", "LinkPoint", "Group", "link_numbers", "four_link"]


@dataclass(frozen=True)
class Crank:
    """The driver: a link turning about the frame pivot ``pivot``; its end is the joint ``pin``."""

    pivot: str
    pin: str
    link: str = "crank"

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link,)


@dataclass(frozen=True)
class RRR:
    """Two links meeting at a hinge: ``joint`` at fixed distances from the known joints ``first`` and ``second``.

    ``first_link`` joins ``first`` to ``joint``, ``second_link`` joins ``second`` to ``joint``
    (for the four-bar: the coupler A → B and the rocker C → B about the frame pivot C).
    """

    joint: str
    first: str
    second: str
    first_link: str
    second_link: str

    @property
    def links(self) -> tuple[str, ...]:
        return (self.first_link, self.second_link)


@dataclass(frozen=True)
class RRP:
    """A link from the known joint ``known`` to ``joint``, a slider on a fixed straight guide at ``guide_angle`` (rad).

    ``link`` is the connecting link, ``slider`` the sliding block (the crank-slider's coupler A → B
    and its slider B on the x axis).
    """

    joint: str
    known: str
    link: str
    slider: str = "slider"
    guide_angle: float = 0.0

    @property
    def links(self) -> tuple[str, ...]:
        return (self.link, self.slider)

    @property
    def guide_direction(self) -> complex:
        """The guide's unit direction ``exp(i·guide_angle)``."""
        return complex(math.cos(self.guide_angle), math.sin(self.guide_angle))


@dataclass(frozen=True)
class RPR:
    """A block hinged at the known joint ``block`` slides on a ``lever`` that turns about the frame pivot ``pivot``.

    ``slider`` is the block (the slotted lever's block on the crank pin A, its lever about C).
    """

    block: str
    pivot: str
    lever: str
    slider: str = "slider"

    @property
    def links(self) -> tuple[str, ...]:
        return (self.slider, self.lever)


@dataclass(frozen=True)
class LinkPoint:
    """A joint ``name`` fixed to a link already found (the end B of the shaper's lever)."""

    name: str
    link: str

    @property
    def links(self) -> tuple[str, ...]:
        return ()


Group = Union[Crank, RRR, RRP, RPR, LinkPoint]
"""One step of a mechanism's structure."""


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
