"""Hypothesis strategies shared by the tests: random valid geometries and motions."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

finite = dict(allow_nan=False, allow_infinity=False)

lengths = st.floats(0.05, 5.0, **finite)
"""A link length, m."""

angles = st.floats(-2 * np.pi, 2 * np.pi, **finite)
"""An angle, rad."""

rates = st.one_of(st.just(0.0), st.floats(1e-3, 50.0, **finite).flatmap(lambda r: st.sampled_from([r, -r])))
"""An angular velocity (rad/s) or acceleration (rad/s²): zero, or of a magnitude from 1e-3 to 50.

Not a tiny non-zero number: tolerances scale with the rates, and a rate of 5e-324 (a subnormal)
would make such a tolerance underflow to zero while the round-off of the other terms stays."""

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

four_bar_lengths = st.floats(0.2, 3.0, **finite)
"""A link length of a four-bar, m (ratios up to 15 keep the tests well conditioned)."""


@st.composite
def four_bar_geometries(draw):
    """(crank, coupler, rocker, (a, b), branch) of a four-bar that assembles somewhere.

    Grashof and non-Grashof linkages alike; the frame C = (a, b) at a random direction.
    """
    from hypothesis import assume

    from mechanisms.linkages.four_bar import assembly_intervals

    crank, coupler, rocker, distance = (draw(four_bar_lengths) for _ in range(4))
    direction = draw(st.floats(-np.pi, np.pi, **finite))
    frame = (distance * np.cos(direction), distance * np.sin(direction))
    intervals = assembly_intervals(crank, coupler, rocker, frame)
    assume(bool(intervals) and max(hi - lo for lo, hi in intervals) > 0.05)
    return crank, coupler, rocker, frame, draw(st.sampled_from((1, -1)))


@st.composite
def crank_rockers(draw):
    """(crank, coupler, rocker, (a, b), branch) of a Grashof crank-rocker, s + l < p + q − 0.05 m."""
    from hypothesis import assume

    crank = draw(st.floats(0.2, 1.0, **finite))
    coupler, rocker, distance = (draw(st.floats(crank + 0.3, 3.0, **finite)) for _ in range(3))
    ordered = sorted((crank, coupler, rocker, distance))
    assume(ordered[0] + ordered[3] < ordered[1] + ordered[2] - 0.05)
    direction = draw(st.floats(-np.pi, np.pi, **finite))
    frame = (distance * np.cos(direction), distance * np.sin(direction))
    return crank, coupler, rocker, frame, draw(st.sampled_from((1, -1)))

# chapter 5 strategies -----------------------------------------------------------------


@st.composite
def slotted_lever_geometries(draw, kind: str = "any"):
    """(crank r, pivot (a, b)) in m with the pivot's distance d from O at least 5 % away from r
    (so that the block never comes near the pivot). ``kind``: ``"oscillating"`` (d > r),
    ``"rotating"`` (d < r) or ``"any"``."""
    crank = draw(st.floats(0.05, 2.0, **finite))
    if kind == "any":
        kind = draw(st.sampled_from(["oscillating", "rotating"]))
    ratio = draw(st.floats(1.05, 5.0, **finite) if kind == "oscillating" else st.floats(0.0, 0.95, **finite))
    direction = draw(st.floats(-np.pi, np.pi, **finite))
    return crank, (ratio * crank * np.cos(direction), ratio * crank * np.sin(direction))

# chapter 7 strategies -----------------------------------------------------------------

link_mass_values = st.floats(0.1, 5.0, **finite)
"""A mass, kg."""


@st.composite
def link_masses(draw, length: float):
    """A link's mass properties with its centre of mass anywhere near a link of this length (m)."""
    from mechanisms.analysis import energy
    return energy.LinkMass(draw(link_mass_values), draw(st.floats(-0.3, 1.3, **finite)) * length,
                           draw(st.floats(-0.5, 0.5, **finite)) * length, draw(st.floats(0.0, 0.5, **finite)))


@st.composite
def crank_slider_with_masses(draw):
    """A crank-slider of random proportions with random masses: (mechanism, {link: LinkMass})."""
    import mechanisms as mech
    from mechanisms.analysis import energy
    crank, rod, offset = draw(crank_slider_geometries())
    masses = {"crank": draw(link_masses(crank)), "coupler": draw(link_masses(rod)),
              "B": energy.LinkMass(draw(link_mass_values))}
    return mech.CrankSlider(crank, rod, offset), masses


@st.composite
def four_bar_with_masses(draw):
    """A crank-rocker of random proportions with random masses: (mechanism, {link: LinkMass})."""
    import mechanisms as mech
    crank, coupler, rocker, frame, branch = draw(crank_rockers())
    masses = {"crank": draw(link_masses(crank)), "coupler": draw(link_masses(coupler)),
              "rocker": draw(link_masses(rocker))}
    return mech.FourBar(crank, coupler, rocker, frame, branch), masses


crank_speeds = st.floats(0.5, 30.0, **finite).flatmap(lambda w: st.sampled_from([w, -w]))
"""A crank speed of either sense, 1/s."""

