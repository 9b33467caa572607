"""Layer 6: the book's colours, one home for the figures (matplotlib) and the scenes of the player (SVG).

Colours are fixed per link role; velocity vectors are always :data:`VELOCITY_COLOUR`,
accelerations :data:`ACCELERATION_COLOUR`. No matplotlib here: the scenes need the colours without it.
"""

from __future__ import annotations

__all__ = ["ROLE_COLOURS", "PATH_COLOURS", "VELOCITY_COLOUR", "ACCELERATION_COLOUR", "BLOCK_FILL"]

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
