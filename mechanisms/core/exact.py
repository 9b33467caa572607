"""Layer 1: exact decisions of special cases — the one rule for near-degenerate geometry.

A special-case formula (a slotted lever whose pivot lies on the crank circle, a four-bar that passes
a change point) is used only where the special case holds *exactly* for the given doubles. The
decision is made once, when the mechanism is made, in exact rational arithmetic
(:class:`fractions.Fraction` holds every double exactly, and sums and products of fractions are
exact), never with a tolerance: a geometry 1e-10 away from a special case is a general one, and the
general formula, which is valid there, gives its true answer. Where the general formula's answer is
dominated by round-off (within about 1e-6, relative, of the degenerate configuration), the position
is flagged ``singular`` instead of being given a confident wrong number.
"""

from __future__ import annotations

from fractions import Fraction

__all__ = ["squared_distance_equals", "squared_distance_exceeds"]


def _square_sum(x: float, y: float) -> Fraction:
    fx, fy = Fraction(x), Fraction(y)
    return fx * fx + fy * fy


def squared_distance_equals(point: tuple[float, float], length: Fraction | float) -> bool:
    """True if the point (x, y) is exactly ``length`` from the origin: x² + y² = length², length ≥ 0.

    Parameters
    ----------
    point : (float, float)
        The point's coordinates (m), doubles taken as the exact numbers they are.
    length : Fraction or float
        A distance (m), exact; a negative one is never equal to a distance.
    """
    length = Fraction(length)
    return length >= 0 and _square_sum(*point) == length * length


def squared_distance_exceeds(point: tuple[float, float], length: Fraction | float) -> bool:
    """True if the point (x, y) is farther than ``length`` ≥ 0 from the origin, exactly: x² + y² > length²."""
    length = Fraction(length)
    return _square_sum(*point) > length * length
