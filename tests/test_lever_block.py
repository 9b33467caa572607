"""Tests of the slotted-lever block (layer 2): a block on a moving pin sliding along a lever about a pivot.

Expected values come from a hand calculation, from the textbook relations of source 004 (5.62–5.69)
written out independently here, from numerical differentiation of positions computed in the tests,
and from the decomposition of the block's acceleration that the crank gives directly.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms.blocks.crank import crank_angle, crank_pin
from mechanisms.blocks.lever_block import LeverBlock, lever_block, lever_through_pivot
from mechanisms.core.errors import InvalidParameterError
from mechanisms.core.motion import PointMotion
from mechanisms.verify import central_difference
from strategies import finite, rates, slotted_lever_geometries

PHI = np.radians(np.arange(0.0, 360.0, 7.5))


def wrap(angle):
    return (angle + np.pi) % (2 * np.pi) - np.pi


def test_hand_calculation():
    # Crank r = 0.1 m at φ = 0 with ω1 = 10 rad/s, ε1 = 0; pivot C = (0, 0.3) m. By hand:
    # A − C = (0.1, −0.3): L = √0.1 m, ξ = atan2(−0.3, 0.1); v_A = (0, 1), a_A = (−10, 0).
    # L_t = (A − C)·v_A / L = −0.3/√0.1; ξ_t = (A − C) × v_A / L² = 0.1/0.1 = 1 rad/s;
    # L_tt = ((A − C)·a_A + |v_A|² − L_t²)/L = (−1 + 1 − 0.9)/√0.1;
    # ξ_tt = ((A − C) × a_A − 2 L L_t ξ_t)/L² with (A − C) × a_A = 0.1·0 − (−0.3)(−10) = −3 and 2 L L_t ξ_t = −0.6:
    # ξ_tt = (−3 + 0.6)/0.1 = −24 rad/s²; Coriolis 2 ξ_t L_t = −0.6/√0.1 m/s².
    pin = PointMotion(np.array([0.1 + 0j]), np.array([1j]), np.array([-10 + 0j]))
    block = lever_block(pin, 0.3j)
    assert isinstance(block, LeverBlock)
    root = np.sqrt(0.1)
    np.testing.assert_allclose(block.distance.value, [root], rtol=1e-15)
    np.testing.assert_allclose(block.lever_angle.value, [np.arctan2(-0.3, 0.1)], rtol=1e-15)
    np.testing.assert_allclose(block.distance.velocity, [-0.3 / root], rtol=1e-14)
    np.testing.assert_allclose(block.lever_angle.omega, [1.0], rtol=1e-14)
    np.testing.assert_allclose(block.distance.acceleration, [-0.9 / root], rtol=1e-14)
    np.testing.assert_allclose(block.lever_angle.alpha, [-24.0], rtol=1e-14)
    np.testing.assert_allclose(block.coriolis_magnitude, [-0.6 / root], rtol=1e-14)
    assert not block.singular.any()


@settings(max_examples=40, deadline=None)
@given(geometry=slotted_lever_geometries(), omega=rates)
def test_textbook_relations(geometry, omega):
    # expected: source 004, §5.5, derived independently: L² = l1² + d² − 2 l1 d cos(φ1 − γ) (5.62),
    # tg φ3 = (l1 sin φ1 − b)/(l1 cos φ1 − a) (5.63), v_rel = −ω1 l1 sin(φ1 − φ3) (5.68),
    # ω3 = ω1 l1 cos(φ1 − φ3)/l3 (5.69).
    r, (a, b) = geometry
    d, gamma = np.hypot(a, b), np.arctan2(b, a)
    block = lever_block(crank_pin(crank_angle(PHI, omega, 0.0), r), complex(a, b))
    l3 = np.sqrt(r**2 + d**2 - 2 * r * d * np.cos(PHI - gamma))
    phi3 = np.arctan2(r * np.sin(PHI) - b, r * np.cos(PHI) - a)
    np.testing.assert_allclose(block.distance.value, l3, rtol=1e-9, atol=1e-12 * r)
    np.testing.assert_allclose(wrap(block.lever_angle.value - phi3), 0.0, atol=1e-12)
    np.testing.assert_allclose(block.distance.velocity, -omega * r * np.sin(PHI - phi3),
                               atol=1e-11 * r * (1 + abs(omega)))
    np.testing.assert_allclose(block.lever_angle.omega, omega * r * np.cos(PHI - phi3) / l3,
                               atol=1e-11 * (1 + abs(omega)) * r / l3.min())


@settings(max_examples=40, deadline=None)
@given(geometry=slotted_lever_geometries(), omega=st.floats(-20, 20, **finite), alpha=rates)
def test_coriolis_closes_the_acceleration_of_the_block(geometry, omega, alpha):
    # expected: the block's acceleration computed directly from the crank, a_A = (iε1 − ω1²)·A, equals
    # the lever point's acceleration (iε3 − ω3²)(A − C), plus the relative L_tt·e, plus the Coriolis term.
    r, pivot = geometry
    pivot = complex(*pivot)
    pin = crank_pin(crank_angle(PHI, omega, alpha), r)
    direct = (1j * alpha - omega**2) * pin.value
    block = lever_block(pin, pivot)
    xi = block.lever_angle
    e = np.exp(1j * xi.value)
    transport = (1j * xi.alpha - xi.omega**2) * (pin.value - pivot)
    relative = block.distance.acceleration * e
    scale = (abs(alpha) + omega**2) * r * (1 + r / np.abs(pin.value - pivot).min()) ** 2
    # accelerations below about 1e-300 m/s² lose relative accuracy to underflow (the API contract)
    floor = max(1e-10 * scale, 1e-290)
    np.testing.assert_allclose(transport + relative + block.coriolis, direct, atol=floor)
    # and without the Coriolis term the balance fails wherever 2 ω3 v_rel is not negligible
    missing = np.abs(transport + relative - direct)
    np.testing.assert_allclose(missing, np.abs(2 * xi.omega * block.distance.velocity), atol=floor)


@settings(max_examples=30, deadline=None)
@given(centre=st.complex_numbers(max_magnitude=1.0, allow_nan=False, allow_infinity=False),
       radius=st.floats(0.2, 1.0, **finite), w=st.floats(-3, 3, **finite),
       v=st.complex_numbers(max_magnitude=1.0, allow_nan=False, allow_infinity=False))
def test_moving_pivot_against_numerical_differentiation(centre, radius, w, v):
    # A guide with a moving axis: the pivot C(t) = c + R exp(iwt) circles, the pin A(t) = 3 + v t moves
    # on a line far from it. Expected: central differences of |A − C| and arg(A − C) written here.
    t = np.linspace(0.0, 1.0, 9)

    def pivot_at(t):
        return centre + radius * np.exp(1j * w * t)

    def pin_at(t):
        return 3.0 + 0j + v * t

    pivot = PointMotion(pivot_at(t), 1j * w * radius * np.exp(1j * w * t), -(w**2) * radius * np.exp(1j * w * t))
    pin = PointMotion(pin_at(t), np.full_like(t, v, dtype=complex), np.zeros_like(t, dtype=complex))
    block = lever_block(pin, pivot)
    length = lambda s: np.abs(pin_at(s) - pivot_at(s))  # noqa: E731
    angle = lambda s: np.angle(pin_at(s) - pivot_at(s))  # noqa: E731
    for f, motion, is_angle in ((length, block.distance, False), (angle, block.lever_angle, True)):
        np.testing.assert_allclose(motion.velocity, central_difference(f, t, 1.0, 1e-5, 1, is_angle), atol=1e-7)
        np.testing.assert_allclose(motion.acceleration, central_difference(f, t, 1.0, 1e-4, 2, is_angle),
                                   atol=2e-5)


def test_lecture_second_derivative_of_current_length_is_a_typo():
    # Lecture slide "guide with a fixed axis": printed
    #   (L_tek)_tt = [(x_tt)_A (x_A − a) + (y_tt)_A (y_A − b) + (x_tt)_A + (y_tt)_A]/L − [...]/L² · (L_tek)_t,
    # corrected: "+ (x_t)_A² + (y_t)_A²" instead of "+ (x_tt)_A + (y_tt)_A" (see the errata).
    # Expected: numerical differentiation of L(φ) = |A(φ) − C| at constant ω.
    r, pivot, omega = 0.1, 0.05 + 0.3j, 12.0
    pin = crank_pin(crank_angle(PHI, omega, 0.0), r)
    x, y, vx, vy = pin.x, pin.y, pin.velocity.real, pin.velocity.imag
    ax, ay = pin.acceleration.real, pin.acceleration.imag
    a, b = pivot.real, pivot.imag
    length = np.hypot(x - a, y - b)
    length_t = (vx * (x - a) + vy * (y - b)) / length
    tail = (vx * (x - a) + vy * (y - b)) / length**2 * length_t
    printed = (ax * (x - a) + ay * (y - b) + ax + ay) / length - tail
    corrected = (ax * (x - a) + ay * (y - b) + vx**2 + vy**2) / length - tail
    numeric = central_difference(lambda p: np.abs(r * np.exp(1j * p) - pivot), PHI, omega, 1e-4, 2)
    np.testing.assert_allclose(corrected, numeric, atol=1e-5)
    assert np.max(np.abs(printed - numeric)) > 1.0  # m/s²: the printed form is wrong
    np.testing.assert_allclose(lever_block(pin, pivot).distance.acceleration, numeric, atol=1e-5)


def test_pin_at_the_pivot_is_marked_singular_not_silent():
    # The pin passes exactly through the pivot at φ = 0 (pivot C = (r, 0) on the crank circle).
    pin = crank_pin(crank_angle(np.array([0.0, 1.0]), 2.0, 0.0), 0.1)
    block = lever_block(pin, 0.1 + 0j)
    assert block.singular.tolist() == [True, False]
    assert np.isnan(block.lever_angle.omega[0]) and np.isnan(block.distance.velocity[0])
    assert np.all(np.isfinite(block.lever_angle.alpha[1:]))


def test_through_pivot_at_and_near_the_passage():
    # Pivot on the crank circle at γ: by the inscribed-angle theorem the lever turns at ω1/2 (hand); at the
    # passage the lever is the tangent to the circle at C (angle γ + π/2 mod π), the block's signed distance
    # is 0, its sliding velocity r·ω1 and relative acceleration r·ε1 (hand, from s = 2r sin((φ − γ)/2)).
    r, gamma, omega, alpha = 0.2, 0.7, 5.0, 3.0
    phi = gamma + np.array([0.0, 2 * np.pi, 0.4, -1.3])
    block = lever_through_pivot(crank_angle(phi, omega, alpha), r, gamma)
    assert not block.singular.any()
    np.testing.assert_allclose(block.lever_angle.omega, omega / 2)
    np.testing.assert_allclose(block.lever_angle.alpha, alpha / 2)
    tangent = (block.lever_angle.value[:2] - gamma - np.pi / 2) % np.pi
    np.testing.assert_allclose(np.minimum(tangent, np.pi - tangent), 0.0, atol=1e-15)
    np.testing.assert_allclose(block.distance.value[:2], 0.0, atol=1e-15)
    np.testing.assert_allclose(np.abs(block.distance.velocity[:2]), r * omega, rtol=1e-15)
    np.testing.assert_allclose(np.abs(block.distance.acceleration[:2]), r * alpha, rtol=1e-14)
    # away from the passage it is the general block, up to the sign of the distance and a half turn
    general = lever_block(crank_pin(crank_angle(phi[2:], omega, alpha), r), r * np.exp(1j * gamma))
    sign = np.sign(block.distance.value[2:])
    np.testing.assert_allclose(sign * block.distance.value[2:], general.distance.value, rtol=1e-13)
    np.testing.assert_allclose(sign * block.distance.velocity[2:], general.distance.velocity, rtol=1e-12)
    np.testing.assert_allclose(sign * block.distance.acceleration[2:], general.distance.acceleration, rtol=1e-12)
    np.testing.assert_allclose(block.lever_angle.omega[2:], general.lever_angle.omega, rtol=1e-12)
    np.testing.assert_allclose(block.lever_angle.alpha[2:], general.lever_angle.alpha, rtol=1e-11, atol=1e-12)
    turn = wrap(block.lever_angle.value[2:] + np.where(sign < 0, np.pi, 0.0) - general.lever_angle.value)
    np.testing.assert_allclose(turn, 0.0, atol=1e-14)


def test_bad_inputs():
    pin = crank_pin(crank_angle(PHI, 1.0), 0.1)
    with pytest.raises(InvalidParameterError, match="pivot"):
        lever_block(pin, complex(np.nan, 0.0))
    with pytest.raises(InvalidParameterError, match="radius"):
        lever_through_pivot(crank_angle(PHI, 1.0), -0.1, 0.0)


def test_order_zero_and_one():
    pin0 = crank_pin(crank_angle(PHI, 2.0, order=0), 0.1)
    block0 = lever_block(pin0, 0.3j)
    assert block0.lever_angle.order == 0 and block0.coriolis is None
    block1 = lever_block(crank_pin(crank_angle(PHI, 2.0, order=1), 0.1), 0.3j)
    assert block1.distance.order == 1 and block1.coriolis is not None
