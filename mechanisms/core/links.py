"""Layer 1: the types of links of a linkage mechanism and their motion.

The first table of chapter 1 is generated from :data:`LINK_TYPES`, so the book and the code
use one set of definitions (after the lecture of Alyushin, 2008, and the glossary).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .motion import Motion

__all__ = ["LinkType", "LINK_TYPES", "link_type", "harmonic"]


@dataclass(frozen=True)
class LinkType:
    """A type of link: its name in three languages, its motion and its definition."""

    name: str
    russian: str
    ukrainian: str
    motion: str
    definition: str
    role: str
    """The colour role of the link in the book's figures."""


LINK_TYPES: tuple[LinkType, ...] = (
    LinkType("frame", "стойка", "стояк", "none (fixed)",
             "the fixed link that carries the pivots and guides of all the others", "frame"),
    LinkType("crank", "кривошип", "кривошип", "rotation about a fixed axis, full turns",
             "a link that makes full revolutions about a fixed axis", "crank"),
    LinkType("rocker", "коромысло", "коромисло", "rotation about a fixed axis, oscillating",
             "a link that swings through less than a full turn about a fixed axis", "rocker"),
    LinkType("coupler", "шатун", "шатун", "plane-parallel (rotation about a moving pole)",
             "a link hinged to two or more moving links, not to the frame", "coupler"),
    LinkType("slider", "ползун", "повзун", "straight-line translation",
             "a link that translates along a guide fixed to the frame", "slider"),
    LinkType("slotted link", "кулиса", "куліса", "rotation (or plane motion) carrying a guide",
             "a moving link with a guide along which a block (another moving link) slides", "lever"),
)


def link_type(name: str) -> LinkType:
    """Look up a link type by its English name (``"crank"`` …)."""
    for item in LINK_TYPES:
        if item.name == name:
            return item
    raise KeyError(f"no link type {name!r}; known: {', '.join(t.name for t in LINK_TYPES)}")


def harmonic(mean: float, amplitude: float, frequency: float, t: ArrayLike, phase: float = 0.0) -> Motion:
    """A harmonic law ``q = mean + amplitude·sin(frequency·t + phase)`` with its derivatives.

    Parameters
    ----------
    mean, amplitude : float
        Mean value and amplitude (rad for an angle, m for a displacement).
    frequency : float
        Circular frequency (1/s).
    t : array_like
        Times (s).

    Notes
    -----
    Used in chapter 1 to prescribe the swing of a rocker or the travel of a slider before
    any mechanism drives them.
    """
    arg = frequency * np.asarray(t, dtype=float) + phase
    s, c = np.sin(arg), np.cos(arg)
    return Motion(mean + amplitude * s, amplitude * frequency * c, -amplitude * frequency**2 * s)
