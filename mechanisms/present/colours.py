"""Layer 6: the book's colours, one home for the figures (matplotlib) and the scenes of the player (SVG).

Colours are fixed per link role; velocity vectors are always :data:`VELOCITY_COLOUR`,
accelerations :data:`ACCELERATION_COLOUR`. No matplotlib here: the scenes need the colours without it.
"""

from __future__ import annotations

import re
from typing import Mapping

from ..core.errors import InvalidParameterError
from ..linkages.base import Bar, Mechanism

__all__ = ["ROLE_COLOURS", "PATH_COLOURS", "VELOCITY_COLOUR", "ACCELERATION_COLOUR", "BLOCK_FILL",
           "link_colours"]

ROLE_COLOURS = {
    "frame": "#4d4d4d",
    "crank": "#1f77b4",
    "coupler": "#d62728",
    "rocker": "#2ca02c",
    "lever": "#2ca02c",
    "slider": "#9467bd",
    "point": "#ff7f0e",
}
PATH_COLOURS = ("#8c564b", "#ff7f0e", "#7f7f7f", "#bcbd22", "#1f77b4", "#2ca02c", "#9467bd", "#d62728",
                "#17a589", "#5d6d7e")
"""Colours of trajectories, in order (distinct from the vector colours)."""
VELOCITY_COLOUR = "#17becf"
ACCELERATION_COLOUR = "#e377c2"
BLOCK_FILL = "#efe7f7"
"""The fill of a sliding block (its outline is the slider's colour)."""


_HEX = re.compile(r"#[0-9a-fA-F]{6}")


def link_colours(mechanism: Mechanism, colours: Mapping[str, str] | None = None) -> dict[str, str]:
    """Each link's colour in a drawing or a scene: its role's colour unless ``colours`` names it.

    Parameters
    ----------
    mechanism : Mechanism
        Whose links (the bars of its :meth:`~mechanisms.linkages.base.Mechanism.scheme`).
    colours : mapping, optional
        ``{link name: "#rrggbb"}`` for the links drawn in a colour of their own, e.g. the second of
        two rockers (``{"rocker": PATH_COLOURS[0]}``).

    Returns
    -------
    dict
        ``{link name: "#rrggbb"}`` for every link of the scheme.

    Raises
    ------
    InvalidParameterError
        ``colours`` names a link the mechanism does not have, or a colour not written ``#rrggbb``.
    """
    found = {item.link: ROLE_COLOURS.get(item.role, "#000000")
             for item in mechanism.scheme() if isinstance(item, Bar)}
    for link, colour in (colours or {}).items():
        if link not in found:
            raise InvalidParameterError("colours", dict(colours or {}),
                                        f"a mapping of this mechanism's links ({', '.join(found)}) "
                                        f"to colours; it has no link {link!r}")
        if not isinstance(colour, str) or not _HEX.fullmatch(colour):
            raise InvalidParameterError("colours", dict(colours or {}),
                                        f"colours written \"#rrggbb\"; {link!r} has {colour!r}")
        found[link] = colour.lower()
    return found
