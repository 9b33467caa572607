"""Tests of the moving-line blocks (layer 2): intersection of two lines, distance from a point to a line,
a circle meeting a moving line, and the angle from a distance.

Expected values come from hand calculations, from the lecture's slope formulas (written out here, in their
corrected form where the lecture has a typo), from a 2×2 linear solve in the test, and from numerical
differentiation of positions computed in the tests.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms.blocks.circle_line import slider_on_line
from mechanisms.blocks.crank import crank_angle, crank_pin
from mechanisms.blocks.lines import (CircleOnLine, LineIntersection, PointLineDistance, angle_from_distance,
                                     circle_on_line, distance_to_line, line_intersection)
from mechanisms.core.errors import AssemblyError, InvalidParameterError
from mechanisms.core.motion import AngleMotion, PointMotion
from mechanisms.verify import central_difference
from strategies import finite

T = np.linspace(0.0, 1.0, 7)
small = st.floats(-1.0, 1.0, **finite)


def moving_point(p0, v, a, t=T):
    """P(t) = p0 + v t + a t²/2 with exact derivatives (by hand)."""
    return PointMotion(p0 + v * t + 0.5 * a * t**2, v + a * t + 0j * t, a + 0j * t)


def moving_angle(th0, w, e, t=T):
    return AngleMotion(th0 + w * t + 0.5 * e * t**2, w + e * t, e + 0 * t)


def test_hand_calculation_intersection():
    # The x axis and the line through (0, −1) at 45°: they meet at (1, 0) (by hand); s1 = 1, s2 = √2.
    cut = line_intersection(0j, 0.0, -1j, np.pi / 4)
    assert isinstance(cut, LineIntersection)
    np.testing.assert_allclose(cut.point.value, 1.0, atol=1e-15)
    np.testing.assert_allclose(cut.along_first.value, 1.0, atol=1e-15)
    np.testing.assert_allclose(cut.along_second.value, np.sqrt(2), atol=1e-15)
    np.testing.assert_allclose(cut.point.velocity, 0.0)


def test_lecture_slope_formula_for_the_slider_on_a_coupler():
    # Lecture: coupler line y = n + x tg η through A and B, guide y = m + x tg θ;
    # x_L = (n − m)/(tg θ − tg η), y_L = (n tg θ − m tg η)/(tg θ − tg η) (checked correct by hand).
    a, b = 0.1 + 0.2j, 0.5 - 0.1j
    m, theta = 0.05, 0.3
    tan_eta = (b.imag - a.imag) / (b.real - a.real)
    n = a.imag - a.real * tan_eta
    x_l = (n - m) / (np.tan(theta) - tan_eta)
    y_l = (n * np.tan(theta) - m * tan_eta) / (np.tan(theta) - tan_eta)
    cut = line_intersection(a, np.angle(b - a), 1j * m, theta)
    np.testing.assert_allclose(cut.point.value, x_l + 1j * y_l, rtol=1e-13)


@settings(max_examples=40, deadline=None)
@given(p1=st.complex_numbers(max_magnitude=2, allow_nan=False), p2=st.complex_numbers(max_magnitude=2, allow_nan=False),
       v1=st.complex_numbers(max_magnitude=1, allow_nan=False), v2=st.complex_numbers(max_magnitude=1, allow_nan=False),
       th1=st.floats(-np.pi, np.pi, **finite), gap=st.floats(0.4, np.pi - 0.4, **finite), w1=small, w2=small,
       e1=small, e2=small)
def test_intersection_against_linear_solve_and_differences(p1, p2, v1, v2, th1, gap, w1, w2, e1, e2):
    # expected: K from solving [e1, −e2]·(s1, s2) = Q2 − Q1 as a real 2×2 system, differentiated numerically.
    # The lines keep an angle between them (gap ± 2 rad of turning over the time span stays off 0 and π
    # only if the relative turn is small, so the relative rate is bounded below).
    w2, e2 = w1 + 0.1 * w2, e1 + 0.1 * e2
    th2 = th1 + gap
    q1, q2 = moving_point(p1, v1, 0.3 * v2), moving_point(p2, v2, -0.2 * v1)
    a1, a2 = moving_angle(th1, w1, e1), moving_angle(th2, w2, e2)
    cut = line_intersection(q1, a1, q2, a2)

    def solve(t):
        Q1 = p1 + v1 * t + 0.15 * v2 * t**2
        Q2 = p2 + v2 * t - 0.1 * v1 * t**2
        t1 = th1 + w1 * t + 0.5 * e1 * t**2
        t2 = th2 + w2 * t + 0.5 * e2 * t**2
        out = []
        for q1_, q2_, a_, b_ in zip(np.atleast_1d(Q1), np.atleast_1d(Q2), np.atleast_1d(t1), np.atleast_1d(t2)):
            matrix = np.array([[np.cos(a_), -np.cos(b_)], [np.sin(a_), -np.sin(b_)]])
            s1, _ = np.linalg.solve(matrix, [(q2_ - q1_).real, (q2_ - q1_).imag])
            out.append(q1_ + s1 * np.exp(1j * a_))
        return np.array(out)

    np.testing.assert_allclose(cut.point.value, solve(T), atol=1e-9)
    np.testing.assert_allclose(cut.point.velocity, central_difference(solve, T, 1.0, 1e-5, 1), atol=1e-5)
    np.testing.assert_allclose(cut.point.acceleration, central_difference(solve, T, 1.0, 1e-4, 2), atol=2e-3)


def test_parallel_lines_are_a_singular_position_not_an_error():
    # Issue 18: one position with parallel lines must not cost the others. Expected (by hand): the lines
    # through 0 and i at 0.3 and 0.3 + π are parallel (no intersection): flagged, nan; those at 0.3 and 1.3
    # meet where the cross products say, finite.
    phi = np.array([0.0, 1.0])
    second = AngleMotion(np.array([0.3 + np.pi, 1.3]), np.zeros(2), np.zeros(2))
    cut = line_intersection(0j, 0.3, PointMotion(np.array([1j, 1j]), np.zeros(2, complex), np.zeros(2, complex)),
                            second, angles=phi)
    assert cut.singular.tolist() == [True, False]
    assert np.isnan(cut.point.value[0]) and np.isfinite(cut.point.value[1])
    # K = 0 + s1·e^{0.3i} = i + s2·e^{1.3i}: s1 = Im(conj(i)·e^{1.3i})/sin(1.0) ... checked against the two lines
    k = cut.point.value[1]
    assert abs(((k - 0j) * np.exp(-0.3j)).imag) < 1e-15 and abs(((k - 1j) * np.exp(-1.3j)).imag) < 1e-15


def test_distance_to_a_fixed_line_lecture_form():
    # Lecture: guide y = m + x tg θ; foot N of the perpendicular from D:
    # x_N = (x_D + (y_D − m) tg θ)/(1 + tg²θ), y_N = (m + x_D tg θ + y_D tg²θ)/(1 + tg²θ) (checked by hand);
    # h = |DN|. The block gives the signed h (left of the line positive).
    m, theta = 0.2, 0.4
    d = np.array([0.3 + 0.9j, -0.5 - 0.7j])
    t = np.tan(theta)
    x_n = (d.real + (d.imag - m) * t) / (1 + t**2)
    y_n = (m + d.real * t + d.imag * t**2) / (1 + t**2)
    result = distance_to_line(PointMotion(d), 1j * m, theta)
    assert isinstance(result, PointLineDistance)
    np.testing.assert_allclose(result.foot.value, x_n + 1j * y_n, rtol=1e-14)
    np.testing.assert_allclose(np.abs(result.distance.value), np.hypot(x_n - d.real, y_n - d.imag), rtol=1e-14)
    assert result.distance.value[0] > 0 > result.distance.value[1]  # the first point is above the line


def test_lecture_distance_derivatives_keep_a_constant_that_must_vanish():
    # Lecture: h = −sign(C)(A x_P + B y_P + C)/√(A² + B²) with printed h_t = (A x_t + B y_t + C)/√(A² + B²) and
    # h_tt = (A x_tt + B y_tt + C)/√(A² + B²). Corrected (see the errata): the constant C drops out on
    # differentiation, h_t = −sign(C)(A x_t + B y_t)/√(A² + B²), likewise h_tt. Expected: numerical
    # differentiation of the printed h itself.
    A, B, C = 0.5, -1.0, 0.3          # the line 0.5 x − y + 0.3 = 0, i.e. y = 0.3 + 0.5 x
    omega, phi = 7.0, np.radians(np.arange(0, 360, 20.0))
    pin = crank_pin(crank_angle(phi, omega, 0.0), 0.1)
    norm = np.hypot(A, B)

    def h(p):
        point = 0.1 * np.exp(1j * p)
        return -np.sign(C) * (A * point.real + B * point.imag + C) / norm

    printed_t = (A * pin.velocity.real + B * pin.velocity.imag + C) / norm
    printed_tt = (A * pin.acceleration.real + B * pin.acceleration.imag + C) / norm
    corrected_t = -np.sign(C) * (A * pin.velocity.real + B * pin.velocity.imag) / norm
    corrected_tt = -np.sign(C) * (A * pin.acceleration.real + B * pin.acceleration.imag) / norm
    numeric_t = central_difference(h, phi, omega, 1e-5, 1)
    numeric_tt = central_difference(h, phi, omega, 1e-4, 2)
    np.testing.assert_allclose(corrected_t, numeric_t, atol=1e-8)
    np.testing.assert_allclose(corrected_tt, numeric_tt, atol=1e-5)
    assert np.max(np.abs(printed_t - numeric_t)) > 0.1 and np.max(np.abs(printed_tt - numeric_tt)) > 0.1
    # the block: the line through (0, 0.3) at atan(0.5); the origin is below it, on its right, where both the
    # lecture's h and the block's left-positive distance are negative, so the two are equal
    block = distance_to_line(pin, 0.3j, np.arctan(0.5)).distance
    np.testing.assert_allclose(block.value, h(phi), atol=1e-15)
    np.testing.assert_allclose(block.velocity, numeric_t, atol=1e-8)
    np.testing.assert_allclose(block.acceleration, numeric_tt, atol=1e-5)


@settings(max_examples=40, deadline=None)
@given(p=st.complex_numbers(max_magnitude=2, allow_nan=False), q=st.complex_numbers(max_magnitude=2, allow_nan=False),
       vp=st.complex_numbers(max_magnitude=1, allow_nan=False), vq=st.complex_numbers(max_magnitude=1, allow_nan=False),
       th=st.floats(-np.pi, np.pi, **finite), w=small, e=small)
def test_distance_to_a_moving_line_against_differences(p, q, vp, vq, th, w, e):
    # expected: h(t) = Im(exp(−iθ(t))(P(t) − Q(t))) written here, differentiated numerically.
    pm, qm, am = moving_point(p, vp, vq), moving_point(q, vq, -vp), moving_angle(th, w, e)
    got = distance_to_line(pm, qm, am)

    def h(t):
        P = p + vp * t + 0.5 * vq * t**2
        Q = q + vq * t - 0.5 * vp * t**2
        return np.imag(np.exp(-1j * (th + w * t + 0.5 * e * t**2)) * (P - Q))

    np.testing.assert_allclose(got.distance.value, h(T), atol=1e-12)
    np.testing.assert_allclose(got.distance.velocity, central_difference(h, T, 1.0, 1e-5, 1), atol=1e-7)
    np.testing.assert_allclose(got.distance.acceleration, central_difference(h, T, 1.0, 1e-4, 2), atol=1e-4)
    # the foot is on the line and PK is perpendicular to it
    e_line = np.exp(1j * am.value)
    np.testing.assert_allclose(np.imag(np.conj(e_line) * (got.foot.value - qm.value)), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.real(np.conj(e_line) * (pm.value - got.foot.value)), 0.0, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(centre=st.complex_numbers(max_magnitude=0.3, allow_nan=False), radius=st.floats(0.6, 2.0, **finite),
       th=st.floats(-np.pi, np.pi, **finite), w=small, e=small, branch=st.sampled_from([1, -1]))
def test_circle_on_a_turning_line(centre, radius, th, w, e, branch):
    # A line through the origin turns; D on it at distance `radius` from `centre` (which is within 0.3 of the
    # origin, so the circle always meets the line). Expected: |D − centre| = radius, D on the line, and its
    # derivatives by differentiating numerically the intersection written out here.
    angle = moving_angle(th, w, e)
    got = circle_on_line(centre, radius, 0j, angle, branch)
    assert isinstance(got, CircleOnLine) and not got.singular.any()
    np.testing.assert_allclose(np.abs(got.point.value - centre), radius, rtol=1e-13)
    np.testing.assert_allclose(np.imag(np.exp(-1j * angle.value) * got.point.value), 0.0, atol=1e-13)

    def position(t):
        u = np.exp(1j * (th + w * t + 0.5 * e * t**2))
        foot = np.real(np.conj(u) * centre)
        h = np.imag(np.conj(u) * centre)
        return (foot + branch * np.sqrt(radius**2 - h**2)) * u

    np.testing.assert_allclose(got.point.velocity, central_difference(position, T, 1.0, 1e-5, 1), atol=1e-7)
    np.testing.assert_allclose(got.point.acceleration, central_difference(position, T, 1.0, 1e-4, 2), atol=1e-4)


def test_circle_that_cannot_reach_the_line():
    with pytest.raises(AssemblyError, match="does not reach"):
        circle_on_line(2j, 1.0, 0j, moving_angle(0.0, 0.0, 0.0), angles=T)
    with pytest.raises(InvalidParameterError, match="radius"):
        circle_on_line(0j, 0.0, 0j, 0.0)


@settings(max_examples=40, deadline=None)
@given(crank=st.floats(0.05, 0.5, **finite), ratio=st.floats(1.2, 5.0, **finite), omega=st.floats(-20, 20, **finite),
       alpha=st.floats(-50, 50, **finite))
def test_angle_between_coupler_and_guide(crank, ratio, omega, alpha):
    # The crank-slider's coupler from A to B on the x axis: sin μ = h/L2 with h = y_A (lecture). Expected: the
    # coupler angle ψ from the circle–line block (another method): μ = −ψ, μ_t = −ψ_t, μ_tt = −ψ_tt; and the
    # lecture's μ_tt = h_tt/(L cos μ) + μ_t sin μ h_t/(L cos² μ), which is correct as printed.
    rod = ratio * crank
    phi = np.radians(np.arange(0, 360, 15.0))
    pin = crank_pin(crank_angle(phi, omega, alpha), crank)
    psi = slider_on_line(pin, rod).rod_angle
    h = distance_to_line(pin, 0j, 0.0).distance
    mu = angle_from_distance(h, rod)
    scale = (1 + abs(omega)) ** 2 + abs(alpha)
    np.testing.assert_allclose(mu.value, -psi.value, atol=1e-14)
    np.testing.assert_allclose(mu.omega, -psi.omega, atol=1e-12 * scale)
    np.testing.assert_allclose(mu.alpha, -psi.alpha, atol=1e-12 * scale)
    lecture_tt = (h.acceleration / (rod * np.cos(mu.value))
                  + mu.omega * np.sin(mu.value) * h.velocity / (rod * np.cos(mu.value) ** 2))
    np.testing.assert_allclose(mu.alpha, lecture_tt, atol=1e-12 * scale)


def test_angle_from_distance_out_of_reach():
    from mechanisms.core.motion import Motion
    with pytest.raises(AssemblyError, match="cannot reach"):
        angle_from_distance(Motion(np.array([0.5, 1.5])), 1.0)
