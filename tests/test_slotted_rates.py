"""Tests of the split of a sliding block's motion into transport, relative and Coriolis parts (chapter 5, §5.7–§5.8).

Every expected value comes from finite differences of the mechanisms' *positions* only (solved with
``order=0`` at neighbouring crank angles, eighth-order central differences), never from the velocities
and accelerations that the function under test combines.
"""

from __future__ import annotations

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis.slotted import sliding_parts
from mechanisms.core.errors import MissingDerivativeError

H = 1e-3                                                    # rad, the step of the differences
OFFSETS = np.arange(-4, 5)                                  # eight-order stencils on 9 points
FIRST = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
SECOND = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
OMEGA, ALPHA = 10.0, 3.0                                    # 1/s, 1/s² at the crank angles tested
ANGLES = np.radians([10.0, 60.0, 137.0, 250.0, 333.0])


def _rates(values):
    """d/dt and d²/dt² from values at φ + kH (rows: k = −4…4): v = ω f', a = ω² f'' + ε f'."""
    d1 = FIRST @ values / H
    d2 = SECOND @ values / H**2
    return OMEGA * d1, OMEGA**2 * d2 + ALPHA * d1


def _stencil(mechanism, read):
    """``read(solution)`` at every crank angle of ANGLES shifted by kH, k = −4…4 (positions only)."""
    return np.array([read(mechanism.solve(ANGLES + k * H, order=0)) for k in OFFSETS])


CASES = {
    # the block E of §5.7: on the coupler A → B (angle ψ), s = |AE| along it
    "slider on a coupler": (mech.SliderOnCoupler(crank=0.08, rod=0.3, guide_point=(0.2, 0.0),
                                                 guide_angle=np.radians(70.0)), "A", "coupler", "E_coupler", "E"),
    # the pin D of §5.8: in the lever's slot (angle ξ about C), s = |CD|
    "two rockers": (mech.SlottedRockers(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2),
                    "C", "lever", "D", "D"),
    # the block A of §5.3, on the lever of §5.1
    "slotted lever": (mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25)), "C", "lever", "A", "A"),
}


@pytest.mark.parametrize("name", CASES)
def test_parts_against_differences_of_positions(name):
    mechanism, origin, link, slider, block = CASES[name]
    solution = mechanism.solve(ANGLES, omega=OMEGA, alpha=ALPHA)
    parts = sliding_parts(solution.point(origin), solution.angle(link), solution.slider(slider))
    centre = mechanism.solve(ANGLES, order=0)
    s0 = centre.slider(slider).value                        # s frozen at the position itself
    unit0 = np.exp(1j * centre.angle(link).value)           # the slot's direction there
    # the block itself
    v_block, a_block = _rates(_stencil(mechanism, lambda s: s.point(block).value))
    # the link's point under the block: Q(φ) + s(φ₀) e^{iθ(φ)}, s held
    v_link, a_link = _rates(_stencil(mechanism, lambda s: s.point(origin).value
                                     + s0 * np.exp(1j * s.angle(link).value)))
    # sliding seen from the link: s(φ) along the direction held
    s_t, s_tt = _rates(_stencil(mechanism, lambda s: s.slider(slider).value))
    turn_t, _ = _rates(_stencil(mechanism, lambda s: np.exp(1j * s.angle(link).value)))   # (e^{iθ})_t
    scale = max(np.max(np.abs(a_block)), 1.0)
    assert np.max(np.abs(parts.velocity - v_block)) < 1e-9
    assert np.max(np.abs(parts.transport_velocity - v_link)) < 1e-9
    assert np.max(np.abs(parts.relative_velocity - s_t * unit0)) < 1e-9
    assert np.max(np.abs(parts.acceleration - a_block)) < 1e-6 * scale
    assert np.max(np.abs(parts.transport_acceleration - a_link)) < 1e-6 * scale
    assert np.max(np.abs(parts.relative_acceleration - s_tt * unit0)) < 1e-6 * scale
    # Coriolis: what the two parts above leave of the block's acceleration, and 2 (e^{iθ})_t s_t
    assert np.max(np.abs(parts.coriolis - (a_block - a_link - s_tt * unit0))) < 1e-6 * scale
    assert np.max(np.abs(parts.coriolis - 2.0 * turn_t * s_t)) < 1e-6 * scale


def test_coriolis_sense_by_hand():
    # A slot along +x (θ = 0) turning counter-clockwise at 2 1/s, the block sliding out at 3 m/s:
    # 2 ω × v_rel = 2·2·3 = 12 m/s² along +y, the relative velocity turned 90° with the rotation (hand).
    zero = np.zeros(1)
    origin = mech.core.motion.PointMotion(zero + 0j, zero + 0j, zero + 0j)
    direction = mech.core.motion.AngleMotion(zero, zero + 2.0, zero)
    along = mech.core.motion.Motion(zero + 0.5, zero + 3.0, zero)
    parts = sliding_parts(origin, direction, along)
    assert parts.coriolis[0] == pytest.approx(12j, abs=1e-15)
    # the lever point 0.5 m out turning at 2 1/s: centripetal −ω² s = −2 m/s² along x (hand)
    assert parts.transport_acceleration[0] == pytest.approx(-2.0, abs=1e-15)
    assert parts.velocity[0] == pytest.approx(3.0 + 1j, abs=1e-15)


def test_missing_accelerations_are_named():
    mechanism = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25))
    solution = mechanism.solve(ANGLES, omega=OMEGA, order=1)
    with pytest.raises(MissingDerivativeError, match="accelerations were not computed"):
        sliding_parts(solution.point("C"), solution.angle("lever"), solution.slider("A"))
