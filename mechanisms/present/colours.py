"""Layer 6: the book's colours, one home for the figures (matplotlib) and the scenes of the player (SVG).

Colours are fixed per link role; velocity vectors are always :data:`VELOCITY_COLOUR`,
accelerations :data:`ACCELERATION_COLOUR`. No matplotlib here: the scenes need the colours without it.
"""

from __future__ import annotations

import re
from typing import Mapping

from ..core.errors import InvalidParameterError
from ..linkages.base import Bar, Mechanism

__all__ = ["ROLE_COLOURS", "PATH_COLOURS", "PATH_COLOUR", "VELOCITY_COLOUR", "ACCELERATION_COLOUR", "BLOCK_FILL",
           "link_colours"]

# Every colour a line is drawn in keeps a contrast of at least 3:1 against white, the background of the
# figures and of the player in both of the site's modes (WCAG 2.1, 1.4.11 non-text contrast); the vectors'
# colours, in which their labels are also written, at least 4.5:1 (1.4.3, text). Where matplotlib's
# default ("tab10") colour was fainter, a darker shade of the same hue stands in for it
# (tests/test_colours.py computes the ratios).
ROLE_COLOURS = {
    "frame": "#4d4d4d",
    "crank": "#1f77b4",
    "coupler": "#d62728",
    "rocker": "#2ca02c",
    "lever": "#2ca02c",
    "slider": "#9467bd",
    "point": "#d96200",
}
PATH_COLOURS = ("#8c564b", "#d96200", "#7f7f7f", "#8f8f00", "#1f77b4", "#2ca02c", "#9467bd", "#d62728",
                "#17a589", "#5d6d7e")
"""Colours of trajectories, in order (distinct from the vector colours)."""
PATH_COLOUR = "#8c8c8c"
"""The grey of the path a point traces in a scene, fainter than the links drawn over it."""
VELOCITY_COLOUR = "#0b8090"
ACCELERATION_COLOUR = "#bf429e"
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
