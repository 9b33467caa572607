"""Tests of the two-links-at-a-hinge block (mechanisms/blocks/circle_circle.py)."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechanisms.blocks.circle_circle import hinge
from mechanisms.core.errors import AssemblyError, InvalidParameterError
from mechanisms.core.motion import PointMotion
from strategies import lengths, points


def moving_point(position, velocity, acceleration):
    return PointMotion(np.atleast_1d(np.complex128(position)), np.atleast_1d(np.complex128(velocity)),
                       np.atleast_1d(np.complex128(acceleration)))


def cross(u, v):
    return (np.conj(u) * v).imag


@settings(max_examples=300, deadline=None)
@given(points, points, lengths, lengths, st.sampled_from((1, -1)))
def test_lengths_and_side(p, q, length_p, length_q, branch):
    distance = abs(q - p)
    # assemble only well inside the range, away from the singular (collinear) positions
    assume(abs(length_p - length_q) + 0.02 < distance < length_p + length_q - 0.02)
    joint = hinge(moving_point(p, 0, 0), moving_point(q, 0, 0), length_p, length_q, branch)
    j = joint.point.value[0]
    # expected: the defining distances and the geometric side (sign of a cross product)
    assert abs(abs(j - p) - length_p) < 1e-12 * (1 + length_p)
    assert abs(abs(j - q) - length_q) < 1e-12 * (1 + length_q)
    assert np.sign(cross(q - p, j - p)) == branch
    # the angles are those of the vectors p -> J and q -> J
    assert np.isclose(np.exp(1j * joint.angle_p.value[0]), (j - p) / length_p)
    assert np.isclose(np.exp(1j * joint.angle_q.value[0]), (j - q) / length_q)


@settings(max_examples=200, deadline=None)
@given(points, points, lengths, lengths, st.sampled_from((1, -1)),
       st.tuples(*[st.floats(-5, 5)] * 8))
def test_derivatives_satisfy_differentiated_constraints(p, q, length_p, length_q, branch, motion):
    distance = abs(q - p)
    assume(abs(length_p - length_q) + 0.05 < distance < length_p + length_q - 0.05)
    vp, vq, ap, aq = (complex(motion[i], motion[i + 1]) for i in range(0, 8, 2))
    joint = hinge(moving_point(p, vp, ap), moving_point(q, vq, aq), length_p, length_q, branch)
    j, v, a = joint.point.value[0], joint.point.velocity[0], joint.point.acceleration[0]
    # expected: d/dt |J − p|² = 0 and d²/dt² |J − p|² = 0 (and the same for q), by hand
    for c, vc, ac in ((p, vp, ap), (q, vq, aq)):
        assert abs((np.conj(j - c) * (v - vc)).real) < 1e-9 * (1 + abs(v - vc))
        second = (np.conj(j - c) * (a - ac)).real + abs(v - vc) ** 2
        assert abs(second) < 1e-8 * (1 + abs(a - ac) + abs(v - vc) ** 2)
    # and J moves with the link p -> J: v = v_p + i ω_p (J − p)
    assert abs(v - (vp + 1j * joint.angle_p.omega[0] * (j - p))) < 1e-9 * (1 + abs(v))
    assert abs(v - (vq + 1j * joint.angle_q.omega[0] * (j - q))) < 1e-9 * (1 + abs(v))


def test_orders_follow_the_inputs():
    p = PointMotion(np.array([0j]), np.array([1j]))          # order 1
    q = PointMotion(np.array([3 + 0j]))                      # order 0
    assert hinge(p, q, 2.0, 2.0).point.order == 0
    q1 = PointMotion(np.array([3 + 0j]), np.array([0j]), np.array([0j]))
    joint = hinge(p, q1, 2.0, 2.0)
    assert joint.point.order == 1 and joint.angle_p.order == 1 and joint.angle_q.order == 1


def test_vectorized_with_a_branch_per_position():
    p = PointMotion(np.zeros(2, complex))
    q = PointMotion(np.full(2, 2 + 0j))
    joint = hinge(p, q, 2.0, 2.0, np.array([1, -1]))
    # expected by hand: an equilateral triangle on the segment 0..2, up and down
    assert np.allclose(joint.point.value, [1 + np.sqrt(3) * 1j, 1 - np.sqrt(3) * 1j])


def test_errors_name_the_angles_and_the_reason():
    p = PointMotion(np.zeros(3, complex))
    q = PointMotion(np.array([3 + 0j, 5 + 0j, 0.5 + 0j]))
    with pytest.raises(AssemblyError, match="cannot reach") as info:
        hinge(p, q, 2.0, 2.0, angles=np.radians([10.0, 20.0, 30.0]))
    assert "20°" in str(info.value) and "10°" not in str(info.value)
    with pytest.raises(AssemblyError, match="inside the other"):
        hinge(p, q[2:], 3.0, 1.0, angles=[0.0])
    with pytest.raises(InvalidParameterError, match="branch"):
        hinge(p, q, 2.0, 2.0, branch=0)
    with pytest.raises(InvalidParameterError, match="length_q"):
        hinge(p, q, 2.0, -1.0)


def test_singular_where_the_links_are_in_line():
    p = PointMotion(np.zeros(2, complex), np.zeros(2, complex), np.zeros(2, complex))
    q = PointMotion(np.array([4 + 0j, 3 + 0j]), np.array([1j, 1j]), np.zeros(2, complex))
    joint = hinge(p, q, 2.0, 2.0)        # |pq| = 4 = L_p + L_q: stretched; 3: a true triangle
    assert joint.singular.tolist() == [True, False]
    assert np.isnan(joint.angle_p.omega[0]) and np.isfinite(joint.angle_p.omega[1])
    # touching circles (within round-off) still assemble: J is the midpoint
    assert np.isclose(joint.point.value[0], 2.0)
