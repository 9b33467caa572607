"""Layer 4: structural analysis — degrees of freedom of a planar linkage (chapter 2)."""

from __future__ import annotations

from dataclasses import dataclass

from ..core.errors import InvalidParameterError

__all__ = ["mobility", "Structure", "BOOK_STRUCTURES"]


def mobility(moving_links: int, lower_pairs: int, higher_pairs: int = 0) -> int:
    """Degrees of freedom W of a planar linkage by the structural (Chebyshev–Grübler) formula.

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
