"""Tests of the analysis of slotted-lever mechanisms (layer 4): swing, limit positions, time ratio, shaper stroke.

Expected values come from simulation over a fine grid of crank angles (where the lever's angular velocity
changes sign, the range of the lever angle, the range of the ram's travel) and from hand calculations.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis.slotted import half_swing, limit_positions, shaper_stroke, time_ratio
from mechanisms.core.errors import InvalidParameterError
from strategies import finite, slotted_lever_geometries

FINE = np.radians(np.arange(0.0, 360.0, 0.01))


def test_hand_calculation():
    # d = 2r: sin β = 1/2, β = 30°, the lever swings 60°; K = (180 + 60)/(180 − 60) = 2 (hand).
    assert math.degrees(half_swing(0.1, 0.2)) == pytest.approx(30.0, abs=1e-12)
    assert time_ratio(0.1, 0.2) == pytest.approx(2.0, abs=1e-14)


@settings(max_examples=20, deadline=None)
@given(geometry=slotted_lever_geometries("oscillating"))
def test_time_ratio_and_swing_by_simulation(geometry):
    # expected: the crank angles where ω3 changes sign (simulated, 0.01° grid) split the turn into the two strokes
    r, pivot = geometry
    m = mech.SlottedLever(r, pivot)
    sol = m.solve(FINE, 1.0, order=1)
    w = sol.angle("lever").omega
    turns = FINE[np.nonzero(np.sign(w) != np.sign(np.roll(w, -1)))[0]]
    assert turns.size == 2
    stroke = (turns[1] - turns[0]) % (2 * np.pi)
    simulated = max(stroke, 2 * np.pi - stroke) / min(stroke, 2 * np.pi - stroke)
    assert time_ratio(r, np.hypot(*pivot)) == pytest.approx(simulated, rel=2e-3)
    xi = np.unwrap(sol.angle("lever").value)
    assert half_swing(r, np.hypot(*pivot)) == pytest.approx((xi.max() - xi.min()) / 2, abs=1e-7)
    limits = limit_positions(m)
    at = m.solve(np.array(limits.crank_angles), 1.0)
    np.testing.assert_allclose(at.angle("lever").omega, 0.0, atol=1e-12)  # the lever is at rest there
    np.testing.assert_allclose(np.sort(limits.lever_angles), np.sort(at.angle("lever").value), atol=1e-12)
    slow = (limits.crank_angles[1] - limits.crank_angles[0]) % (2 * np.pi)
    assert slow == pytest.approx(np.pi + 2 * limits.half_swing, abs=1e-12)


@settings(max_examples=10, deadline=None)
@given(distance=st.floats(1.5, 4.0, **finite), rod=st.floats(0.5, 2.0, **finite), branch=st.sampled_from([1, -1]))
def test_shaper_stroke_by_simulation(distance, rod, branch):
    # expected: the range of the ram's simulated travel (0.01° grid) and the time ratio from where it stops
    r = 0.1
    lever = 1.2 * (distance * r + r)
    m = mech.Shaper(r, (0.0, -distance * r), lever, rod * lever, -distance * r + lever, branch)
    result = shaper_stroke(m)
    x = m.solve(FINE, 1.0, order=0).point("D").x
    # the grid's extremes fall short of the true ones by O(Δφ²) only, and never exceed them
    assert result.stroke == pytest.approx(np.ptp(x), abs=1e-6 * lever) and np.ptp(x) <= result.stroke + 1e-12
    np.testing.assert_allclose(sorted(result.positions), [x.min(), x.max()], atol=1e-6 * lever)
    assert result.time_ratio == pytest.approx(time_ratio(r, distance * r))


def test_bad_inputs():
    with pytest.raises(InvalidParameterError, match="pivot_distance"):
        half_swing(0.2, 0.1)
    with pytest.raises(InvalidParameterError, match="crank"):
        time_ratio(-1.0, 2.0)
    with pytest.raises(InvalidParameterError, match="pivot_distance"):
        limit_positions(mech.SlottedLever(0.2, (0.05, 0.0)))
