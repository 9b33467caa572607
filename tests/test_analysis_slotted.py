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
from mechanisms.analysis.slotted import (distance_from_lever, half_swing, limit_positions, shaper_stroke,
                                         time_ratio)
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
    x = m.solve(FINE, 1.0, order=0).point("G").x
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


def test_distance_from_lever_by_hand_and_against_the_solution():
    # expected (hand): at φ = 90° the pin A = (0, 0.1) is straight below C = (0, 0.3), so the lever points
    # down (ξ = −90°), its left is +x, and O₂ = (0.12, 0.38) is h_N = 0.12 m from its line
    rockers = mech.SlottedRockers(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2)
    at = rockers.solve(np.radians([90.0]), omega=10.0)
    assert distance_from_lever(rockers, at).value[0] == pytest.approx(0.12, abs=1e-15)
    # expected: the solution's own record of h_N and its derivatives (same computation, kept under extras)
    sol = rockers.solve(np.radians(np.arange(0.0, 360.0, 7.0)), omega=10.0, alpha=3.0)
    h = distance_from_lever(rockers, sol)
    for mine, kept in zip((h.value, h.velocity, h.acceleration), ("h", "h_t", "h_tt")):
        np.testing.assert_array_equal(mine, sol.extras["O2"][kept])
    # expected: (h_N)_t against central differences of h_N in the crank angle (ω1 = 1, ε1 = 0)
    step = 1e-6
    phi = np.radians(np.arange(3.0, 360.0, 11.0))
    ahead = distance_from_lever(rockers, rockers.solve(phi + step, omega=1.0, order=0)).value
    behind = distance_from_lever(rockers, rockers.solve(phi - step, omega=1.0, order=0)).value
    rate = distance_from_lever(rockers, rockers.solve(phi, omega=1.0)).velocity
    np.testing.assert_allclose(rate, (ahead - behind) / (2 * step), atol=1e-8)
