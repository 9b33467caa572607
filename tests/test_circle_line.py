"""Tests of the circle–line block (layer 2): a rod from a moving joint to a slider on a fixed guide."""

from __future__ import annotations

from decimal import Decimal, getcontext

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms.blocks.circle_line import SliderOnLine, slider_on_line
from mechanisms.blocks.crank import crank_angle, crank_pin
from mechanisms.core.errors import AssemblyError, InvalidParameterError
from mechanisms.core.motion import PointMotion
from mechanisms.verify import central_difference, solve_constraints
from strategies import branches, finite

PHI = np.radians(np.arange(0.0, 360.0, 15.0))


def joint(position, velocity=None, acceleration=None) -> PointMotion:
    wrap = (lambda v: None if v is None else np.atleast_1d(np.asarray(v, dtype=complex)))
    return PointMotion(wrap(position), wrap(velocity), wrap(acceleration))


# --- a hand calculation ------------------------------------------------------------------------

def test_hand_calculation_axial_guide():
    # J = (0, 3) m, rod 5 m, guide the x axis: the 3-4-5 triangle puts B at x = ±4 m.
    # J moves with v = (1, 2) m/s, a = (0.5, -1) m/s². By hand, with h = y_J and s = x_J ± √(25 − h²):
    # s_t = 1 ∓ h h_t / 4 = 1 ∓ 1.5; s_tt = 0.5 ± [−(h_t² + h h_tt)/4 − h² h_t²/4³] = 0.5 ± (−0.25 − 0.5625);
    # rod angle θ with sin θ = −3/5, θ_t = −h_t/(5 cos θ) = ∓0.5 rad/s,
    # θ_tt = (−h_tt/5 + sin θ · θ_t²)/cos θ = (0.2 − 0.6·0.25)/(±0.8) = ±0.0625 rad/s².
    j = joint(3j, 1 + 2j, 0.5 - 1j)
    plus = slider_on_line(j, 5.0, branch=1)
    minus = slider_on_line(j, 5.0, branch=-1)
    assert isinstance(plus, SliderOnLine)
    np.testing.assert_allclose(plus.point.value, [4.0], atol=1e-15)
    np.testing.assert_allclose(minus.point.value, [-4.0], atol=1e-15)
    np.testing.assert_allclose(plus.travel.velocity, [-0.5], rtol=1e-14)
    np.testing.assert_allclose(minus.travel.velocity, [2.5], rtol=1e-14)
    np.testing.assert_allclose(plus.travel.acceleration, [0.5 - 0.8125], rtol=1e-14)
    np.testing.assert_allclose(minus.travel.acceleration, [0.5 + 0.8125], rtol=1e-14)
    np.testing.assert_allclose(plus.rod_angle.angle, [-np.arcsin(0.6)], rtol=1e-14)
    np.testing.assert_allclose(minus.rod_angle.angle, [-np.pi + np.arcsin(0.6)], rtol=1e-14)
    np.testing.assert_allclose(plus.rod_angle.omega, [-0.5], rtol=1e-14)
    np.testing.assert_allclose(minus.rod_angle.omega, [0.5], rtol=1e-14)
    np.testing.assert_allclose(plus.rod_angle.alpha, [0.0625], rtol=1e-13)
    np.testing.assert_allclose(minus.rod_angle.alpha, [-0.0625], rtol=1e-13)
    # the slider moves along its guide only
    assert plus.point.velocity.imag[0] == 0.0 and plus.point.acceleration.imag[0] == 0.0


def test_inclined_guide_hand_calculation():
    # Guide through P = 1 + 1j at 90° (pointing up, +y): J = (4, 5) is 3 m to the right, i.e. h = −3
    # (left of an upward guide is −x). Rod 5 m: B = (1, 5 ± 4); travel from P: s = 4 ± 4.
    j = joint(4 + 5j)
    ahead = slider_on_line(j, 5.0, through=1 + 1j, direction=np.pi / 2, branch=1)
    behind = slider_on_line(j, 5.0, through=1 + 1j, direction=np.pi / 2, branch=-1)
    np.testing.assert_allclose(ahead.point.value, [1 + 9j], atol=1e-14)
    np.testing.assert_allclose(behind.point.value, [1 + 1j], atol=1e-14)
    np.testing.assert_allclose(ahead.travel.value, [8.0], atol=1e-14)
    np.testing.assert_allclose(behind.travel.value, [0.0], atol=1e-14)
    # the rod J→B of the upper branch points up and to the left: direction (−3, 4)
    np.testing.assert_allclose(ahead.rod_angle.angle, [np.arctan2(4.0, -3.0)], rtol=1e-14)


# --- against the generic solver (Newton on the loop closure, exact derivatives) -------------------

@st.composite
def crank_and_guide(draw):
    """A crank R about c driving the rod; a guide through P at δ; the rod always reaches the guide."""
    radius = draw(st.floats(0.05, 2.0, **finite))
    direction = draw(st.floats(-np.pi, np.pi, **finite))
    through = complex(draw(st.floats(-2, 2, **finite)), draw(st.floats(-2, 2, **finite)))
    along = draw(st.floats(-2, 2, **finite))
    distance = draw(st.floats(-1.5, 1.5, **finite)) * radius  # of the crank centre from the guide
    centre = through + (along + 1j * distance) * np.exp(1j * direction)
    rod = (radius + abs(distance)) * draw(st.floats(1.05, 5.0, **finite))
    return radius, centre, rod, through, direction


@settings(max_examples=40, deadline=None)
@given(geometry=crank_and_guide(), branch=branches, omega=st.floats(-30, 30, **finite),
       alpha=st.floats(-100, 100, **finite))
def test_against_generic_solver(geometry, branch, omega, alpha):
    radius, centre, rod, through, direction = geometry
    crank = crank_angle(PHI, omega, alpha)
    block = slider_on_line(crank_pin(crank, radius, centre), rod, through, direction, branch)
    cd, sd = np.cos(direction), np.sin(direction)

    def loop(q, phi):  # J + rod·e^{iθ} = P + s·e^{iδ}, unknowns q = (θ, s)
        theta, s = q
        return (centre.real + radius * np.cos(phi) + rod * np.cos(theta) - through.real - s * cd,
                centre.imag + radius * np.sin(phi) + rod * np.sin(theta) - through.imag - s * sd)

    # a guess near the closed form keeps Newton on the same intersection; it does not fix the values
    guess = np.array([block.rod_angle.angle + 1e-3, block.travel.value + 1e-3 * rod])
    reference = solve_constraints(loop, guess, PHI, omega, alpha)
    scale = rod + radius
    np.testing.assert_allclose(np.angle(np.exp(1j * (block.rod_angle.angle - reference.q[0]))), 0, atol=1e-10)
    np.testing.assert_allclose(block.travel.value, reference.q[1], atol=1e-10 * scale)
    np.testing.assert_allclose(block.rod_angle.omega, reference.q_t[0], atol=1e-8 * (1 + abs(omega)))
    np.testing.assert_allclose(block.travel.velocity, reference.q_t[1], atol=1e-8 * scale * (1 + abs(omega)))
    big = 1 + omega**2 + abs(alpha)
    np.testing.assert_allclose(block.rod_angle.alpha, reference.q_tt[0], atol=1e-7 * big)
    np.testing.assert_allclose(block.travel.acceleration, reference.q_tt[1], atol=1e-7 * scale * big)
    # the branch, by its definition: B ahead of (+1) or behind (−1) the foot of the perpendicular from J
    pin = centre + radius * np.exp(1j * PHI)
    ahead = np.real(np.exp(-1j * direction) * (block.point.value - pin))
    assert np.all(branch * ahead > 0)
    # B is on the guide, at the rod's length from J; its velocity and acceleration are along the guide
    e = np.exp(1j * direction)
    np.testing.assert_allclose(np.imag(np.conj(e) * (block.point.value - through)), 0, atol=1e-12 * scale)
    np.testing.assert_allclose(np.abs(block.point.value - pin), rod, rtol=1e-12)
    np.testing.assert_allclose(block.point.velocity, block.travel.velocity * e, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(block.point.acceleration, block.travel.acceleration * e, rtol=1e-12, atol=1e-12)
    assert not block.singular.any()


def test_derivatives_against_numerical_differentiation():
    # offset crank-slider, R = 0.1 m, rod 0.35 m, guide y = −0.04 m; constant ω = 20 rad/s
    omega = 20.0

    def travel(phi, order=0):
        return slider_on_line(crank_pin(crank_angle(phi, omega, 0.0, order), 0.1), 0.35, -0.04j)

    exact = travel(PHI, order=2)
    v = central_difference(lambda p: travel(p).travel.value, PHI, omega, 1e-5, 1)
    a = central_difference(lambda p: travel(p).travel.value, PHI, omega, 1e-4, 2)
    w = central_difference(lambda p: travel(p).rod_angle.angle, PHI, omega, 1e-5, 1, angle=True)
    np.testing.assert_allclose(exact.travel.velocity, v, atol=1e-7)
    np.testing.assert_allclose(exact.travel.acceleration, a, atol=2e-3)
    np.testing.assert_allclose(exact.rod_angle.omega, w, atol=1e-7)


# --- orders, shapes ------------------------------------------------------------------------------

@pytest.mark.parametrize("order", [0, 1, 2])
def test_order_follows_the_joint(order):
    pin = crank_pin(crank_angle(PHI, 3.0, 1.0, order), 0.1)
    block = slider_on_line(pin, 0.4)
    for motion in (block.point, block.rod_angle, block.travel):
        assert motion.order == order
        assert np.shape(motion.value) == PHI.shape


def test_two_dimensional_arrays():
    phi = PHI.reshape(4, 6)
    block = slider_on_line(crank_pin(crank_angle(phi, 2.0), 0.1), 0.4)
    flat = slider_on_line(crank_pin(crank_angle(PHI, 2.0), 0.1), 0.4)
    assert block.travel.value.shape == (4, 6)
    np.testing.assert_array_equal(block.travel.acceleration.ravel(), flat.travel.acceleration)


# --- assembly, singular positions, round-off -------------------------------------------------------

def test_unreachable_guide_names_the_crank_angles():
    # crank 0.1 m, rod 0.15 m, guide y = 0.1 m: the pin at φ = 270° is 0.2 m from the guide (> 0.15 m);
    # by hand |0.1 sin φ − 0.1| > 0.15 exactly for sin φ < −0.5, i.e. 210° < φ < 330°.
    phi = np.radians([0.0, 200.0, 240.0, 270.0, 300.0, 340.0])
    pin = crank_pin(crank_angle(phi, 1.0), 0.1)
    with pytest.raises(AssemblyError, match="cannot reach") as info:
        slider_on_line(pin, 0.15, 0.1j, angles=phi)
    np.testing.assert_allclose(np.degrees(info.value.angles), [240.0, 270.0, 300.0])
    assert "240°" in str(info.value) and "300°" in str(info.value) and "200°" not in str(info.value)
    with pytest.raises(AssemblyError, match=r"3 position"):  # without angles, the count is given
        slider_on_line(pin, 0.15, 0.1j)


def test_rod_perpendicular_to_guide_is_singular():
    # J exactly rod = 2 m above the guide, moving along it and towards it:
    # B is the foot of the perpendicular, s_t = ±∞ (h_t ≠ 0); where h_t = 0 the derivative is 0/0 = nan.
    j = joint([2j + 1, 2j], [1 - 1j, 1 + 0j], [0j, 0j])
    block = slider_on_line(j, 2.0)
    np.testing.assert_array_equal(block.singular, [True, True])
    np.testing.assert_allclose(block.point.value, [1.0, 0.0])
    np.testing.assert_allclose(block.rod_angle.angle, [-np.pi / 2, -np.pi / 2])
    assert np.isinf(block.travel.velocity[0]) and np.isinf(block.rod_angle.omega[0])
    assert np.isnan(block.travel.velocity[1])
    assert not np.isfinite(block.travel.acceleration).any()


def test_round_off_beyond_reach_is_singular_not_an_error():
    # a joint 2 ulp beyond reach (round-off in h) is taken as exactly at reach
    rod = 0.3
    h = np.nextafter(np.nextafter(rod, 1.0), 1.0)
    block = slider_on_line(joint(1j * h, 1.0), rod)
    assert block.singular.all()
    with pytest.raises(AssemblyError):  # but a real excess of 1e-9 m is not
        slider_on_line(joint(1j * (rod + 1e-9)), rod)


def test_half_chord_keeps_its_accuracy_near_reach():
    # h = rod(1 − 1e-12): exact w = √((rod − h)(rod + h)) by 50-digit decimal arithmetic;
    # the naive √(rod² − h²) has a relative error of about 1e-4 here, the block must not.
    rod = 0.3
    h = rod * (1 - 1e-12)
    getcontext().prec = 50
    exact = float((Decimal(rod) ** 2 - Decimal(h) ** 2).sqrt())
    block = slider_on_line(joint(1j * h), rod)
    assert abs(block.travel.value[0] - exact) <= 1e-14 * exact
    assert abs(block.travel.value[0] - exact) < abs(np.sqrt(rod**2 - h**2) - exact)


# --- bad input -------------------------------------------------------------------------------------

@pytest.mark.parametrize("rod", [0.0, -1.0, np.nan, np.inf, "long"])
def test_bad_rod(rod):
    with pytest.raises(InvalidParameterError, match="rod"):
        slider_on_line(joint(1j), rod)


@pytest.mark.parametrize("branch", [0, 2, -2, True, 0.5, "+"])
def test_bad_branch(branch):
    with pytest.raises(InvalidParameterError, match="branch"):
        slider_on_line(joint(1j), 2.0, branch=branch)


def test_bad_guide():
    with pytest.raises(InvalidParameterError, match="direction"):
        slider_on_line(joint(1j), 2.0, direction=np.nan)
    with pytest.raises(InvalidParameterError, match="through"):
        slider_on_line(joint(1j), 2.0, through=complex(np.inf, 0))
