"""Hypothesis strategies shared by the tests: random valid geometries and motions."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

finite = dict(allow_nan=False, allow_infinity=False)

lengths = st.floats(0.05, 5.0, **finite)
"""A link length, m."""

angles = st.floats(-2 * np.pi, 2 * np.pi, **finite)
"""An angle, rad."""

rates = st.floats(-50.0, 50.0, **finite)
"""An angular velocity (rad/s) or acceleration (rad/s²)."""

coordinates = st.floats(-3.0, 3.0, **finite)
"""A coordinate, m."""

points = st.builds(complex, coordinates, coordinates)
"""A point x + iy, m."""

# chapter 3 strategies -----------------------------------------------------------------


@st.composite
def crank_slider_geometries(draw, full_turn: bool = True):
    """(crank L1, rod L2, offset e) in m. ``full_turn``: L2 ≥ 1.05 (L1 + |e|), the crank turns fully;
    otherwise L2 < 0.95 (L1 + |e|) and L2 > |e| − 0.5 L1, so the crank only rocks."""
    crank = draw(st.floats(0.05, 2.0, **finite))
    offset = draw(st.floats(-1.5, 1.5, **finite)) * crank
    reach = crank + abs(offset)
    if full_turn:
        rod = reach * draw(st.floats(1.05, 6.0, **finite))
    else:
        low = max(abs(offset) - 0.5 * crank, 0.05 * crank)
        rod = draw(st.floats(low, 0.95 * reach, **finite))
    return crank, rod, offset


branches = st.sampled_from([1, -1])
"""A branch of a two-solution block."""

# chapter 4 strategies -----------------------------------------------------------------

# chapter 5 strategies -----------------------------------------------------------------
