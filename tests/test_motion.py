"""Tests of layer 1: the motion of a link and its points (mechanisms.core.motion, mechanisms.core.links).

Expected values come from numerical differentiation of positions written out by hand in the
tests, or from the lecture's formulas in their corrected form (see the errata page).
"""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.core.angles import constant, unit_vector_fast
from mechanisms.core.motion import (AngleMotion, Motion, PointMotion, fixed_point, lagrange_point, plane_motion,
                                    point_on_link, polar, translated_point)
from strategies import angles, coordinates, lengths, points, rates

T = np.linspace(0.0, 1.0, 11)


def quadratic_angle(theta0, w0, e0, t=T) -> AngleMotion:
    """θ(t) = θ0 + ω0 t + ε0 t²/2 with its exact derivatives (by hand)."""
    return AngleMotion(theta0 + w0 * t + 0.5 * e0 * t**2, w0 + e0 * t, np.full_like(t, e0))


def circling_pole(centre, radius, w, t=T) -> PointMotion:
    """r_P(t) = c + R·exp(iwt) with its exact derivatives (by hand)."""
    e = np.exp(1j * w * t)
    return PointMotion(centre + radius * e, 1j * w * radius * e, -(w**2) * radius * e)


def numeric_time_derivatives(position, t, h=1e-5, angle=False):
    """Central differences of a function of time: (first, second); angle differences wrapped."""
    def diff(a, b):
        d = position(a) - position(b)
        return (d + np.pi) % (2 * np.pi) - np.pi if angle else d

    def second_difference(step):
        return (diff(t + step, t) - diff(t, t - step)) / step**2

    first = diff(t + h, t - h) / (2 * h)
    # Richardson extrapolation of the second difference: truncation O(H⁴) instead of O(H²), which
    # matters where a point passes close to a pivot and the higher derivatives are large
    second = (4 * second_difference(50 * h) - second_difference(100 * h)) / 3
    return first, second


@settings(max_examples=60, deadline=None)
@given(theta0=angles, w0=rates, e0=rates, centre=points, radius=lengths, w=st.floats(-5, 5), u=coordinates,
       v=coordinates)
def test_point_on_link_matches_numerical_differentiation(theta0, w0, e0, centre, radius, w, u, v):
    # expected: the point's position r(t) = r_P(t) + (u + iv)·exp(iθ(t)) differentiated numerically
    pole = circling_pole(centre, radius, w)
    angle = quadratic_angle(theta0, w0, e0)
    got = point_on_link(pole, angle, u, v)

    def position(t):
        return circling_pole(centre, radius, w, t).value + complex(u, v) * np.exp(1j * quadratic_angle(theta0, w0, e0, t).value)

    first, second = numeric_time_derivatives(position, T)
    scale = 1 + abs(u) + abs(v) + radius
    np.testing.assert_allclose(got.value, position(T), atol=1e-12 * scale)
    rate = 1 + abs(w0) + abs(e0) + abs(w)
    # central differences: truncation O(h^2 r''') and O(H^2 r''''), round-off O(eps r/h) and O(eps r/H^2)
    np.testing.assert_allclose(got.velocity, first, atol=1e-9 * scale * rate**3)
    np.testing.assert_allclose(got.acceleration, second, atol=2e-8 * scale * rate**4 + 2e-7 * scale)


@settings(max_examples=60, deadline=None)
@given(theta0=angles, w0=rates, e0=rates, centre=points, radius=lengths, w=st.floats(-5, 5), material=points,
       material_pole=points, reference=angles)
def test_lagrange_form_equals_euler_form(theta0, w0, e0, centre, radius, w, material, material_pole, reference):
    # expected: the Euler form; both are exact, so they agree to round-off
    pole = circling_pole(centre, radius, w)
    angle = quadratic_angle(theta0, w0, e0)
    lagrange = lagrange_point(pole, angle, material, material_pole, reference)
    arm = (material - material_pole) * np.exp(1j * (angle.value - reference))
    euler = plane_motion(pole, angle, pole.value + arm)
    scale = (1 + abs(material - material_pole) + radius) * (1 + abs(w0) + abs(e0) * 1 + abs(w)) ** 2
    for a, b in zip(lagrange.derivatives(), euler.derivatives()):
        np.testing.assert_allclose(a, b, atol=1e-11 * scale)


def test_crank_point_lecture_formulas():
    # expected: the lecture's crank formulas x_t = −φ_t y, y_t = φ_t x, x_tt = −φ_tt y − φ_t y_t,
    # y_tt = φ_tt x + φ_t x_t (confirmed, not corrected), evaluated by hand here
    angle = quadratic_angle(0.3, 2.0, -1.5)
    p = point_on_link(0j, angle, 0.7, 0.2)
    x, y = p.x, p.y
    w, e = angle.omega, angle.alpha
    xt, yt = -w * y, w * x
    np.testing.assert_allclose(p.velocity, xt + 1j * yt, atol=1e-14)
    np.testing.assert_allclose(p.acceleration, (-e * y - w * yt) + 1j * (e * x + w * xt), atol=1e-13)


def test_rocker_acceleration_erratum():
    # expected: y_tt = +ξ_tt (x − a) + ξ_t x_t (corrected); the lecture prints −ξ_tt (x − a) − ξ_t x_t
    a, b = 0.4, -0.3
    xi = quadratic_angle(1.1, -3.0, 7.0)
    p = point_on_link(complex(a, b), xi, 0.5)
    x, y, xt, yt = p.x, p.y, p.velocity.real, p.velocity.imag
    corrected = xi.alpha * (x - a) + xi.omega * xt
    printed = -xi.alpha * (x - a) - xi.omega * xt
    np.testing.assert_allclose(p.acceleration.imag, corrected, atol=1e-13)
    assert np.max(np.abs(p.acceleration.imag - printed)) > 1.0
    # the confirmed components of the same slide
    np.testing.assert_allclose(p.velocity, -xi.omega * (y - b) + 1j * xi.omega * (x - a), atol=1e-14)
    np.testing.assert_allclose(p.acceleration.real, -xi.alpha * (y - b) - xi.omega * yt, atol=1e-13)


def test_coupler_acceleration_erratum():
    # expected: y_tt = (y_tt)_P + ψ_tt (x − x_P) + ψ_t [x_t − (x_t)_P] = (y_tt)_P + ψ_tt (x − x_P) − ψ_t² (y − y_P);
    # the lecture prints −ψ_t [x_t − (x_t)_P] in the first form and −ψ_tt (x − x_P) in the second
    pole = circling_pole(0.2 + 0.1j, 0.3, 4.0)
    psi = quadratic_angle(-0.4, 5.0, 20.0)
    p = point_on_link(pole, psi, 0.9, -0.1)
    dx, dy = p.x - pole.x, p.y - pole.y
    dvx = p.velocity.real - pole.velocity.real
    w, e = psi.omega, psi.alpha
    first_form = pole.acceleration.imag + e * dx + w * dvx
    second_form = pole.acceleration.imag + e * dx - w**2 * dy
    np.testing.assert_allclose(p.acceleration.imag, first_form, atol=1e-12)
    np.testing.assert_allclose(p.acceleration.imag, second_form, atol=1e-12)
    printed_first = pole.acceleration.imag + e * dx - w * dvx
    printed_second = pole.acceleration.imag - e * dx - w**2 * dy
    assert np.max(np.abs(p.acceleration.imag - printed_first)) > 1.0
    assert np.max(np.abs(p.acceleration.imag - printed_second)) > 1.0
    # x_tt as printed is right: (x_tt)_P − ψ_tt (y − y_P) − ψ_t² (x − x_P)
    np.testing.assert_allclose(p.acceleration.real, pole.acceleration.real - e * dy - w**2 * dx, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(centre=points, radius=lengths, w=st.floats(-5, 5), pivot=points)
@example(centre=2 + 2j, radius=4.5, w=-2.0, pivot=-2j)   # passes 0.157 m from the pivot: large rates
def test_polar_matches_numerical_differentiation(centre, radius, w, pivot):
    # expected: |r_A − r_C| and arg(r_A − r_C) differentiated numerically (the slotted link's L_tek and angle)
    a = circling_pole(centre, radius, w)
    if np.min(np.abs(a.value - pivot)) < 0.05:
        return  # the direction is undefined where the block passes through the pivot
    length, direction = polar(a - pivot)

    def dist(t):
        return np.abs(circling_pole(centre, radius, w, t).value - pivot)

    def ang(t):
        return np.angle(circling_pole(centre, radius, w, t).value - pivot)

    for motion, fn, wrap in ((length, dist, False), (direction, ang, True)):
        first, second = numeric_time_derivatives(fn, T, angle=wrap)
        reach = (1 + abs(w)) ** 2 * (1 + radius) / max(np.min(dist(T)), 0.05) ** 2
        np.testing.assert_allclose(motion.velocity, first, atol=1e-8 * reach)
        # plus the round-off of the second difference: about 4 ulp of the value over H² = 1e-8
        floor = 1e-7 * (1 + np.max(np.abs(motion.value)))
        np.testing.assert_allclose(motion.acceleration, second, atol=1e-6 * reach * (1 + abs(w)) ** 2 + floor)


def test_slotted_link_length_erratum():
    # expected: (L)_tt = [(x_tt)(x − a) + (y_tt)(y − b) + x_t² + y_t² − L_t²] / L (derived by
    # differentiating L² = (x−a)² + (y−b)² twice); the lecture prints (x_tt)_A + (y_tt)_A instead of x_t² + y_t²
    a = circling_pole(0.0, 0.1, 30.0)
    pivot = 0.25 + 0.05j
    length, _ = polar(a - pivot)
    dx, dy = a.x - pivot.real, a.y - pivot.imag
    xt, yt, xtt, ytt = a.velocity.real, a.velocity.imag, a.acceleration.real, a.acceleration.imag
    lt = (xt * dx + yt * dy) / length.value
    corrected = (xtt * dx + ytt * dy + xt**2 + yt**2) / length.value - lt**2 / length.value
    printed = (xtt * dx + ytt * dy + xtt + ytt) / length.value - lt**2 / length.value
    np.testing.assert_allclose(length.velocity, lt, atol=1e-12)
    np.testing.assert_allclose(length.acceleration, corrected, rtol=1e-12, atol=1e-9)
    assert np.max(np.abs(length.acceleration - printed)) > 1.0


def test_translation_keeps_velocity():
    # expected: in translation every point has the reference point's velocity and acceleration
    ref = circling_pole(0.0, 1.0, 2.0)
    p = translated_point(ref, 0.3 - 0.2j)
    np.testing.assert_array_equal(p.velocity, ref.velocity)
    np.testing.assert_array_equal(p.acceleration, ref.acceleration)
    np.testing.assert_allclose(p.value - ref.value, 0.3 - 0.2j)


def test_orders_follow_the_inputs():
    angle = quadratic_angle(0.0, 1.0, 0.0).truncated(1)
    p = point_on_link(0j, angle, 1.0)
    assert p.order == 1 and p.acceleration is None
    assert point_on_link(0j, angle.truncated(0), 1.0).order == 0
    assert polar(p - 2.0)[0].order == 1


def test_motion_arithmetic_and_indexing():
    m = Motion(np.arange(3.0), np.ones(3), np.zeros(3))
    n = Motion(np.ones(3), np.ones(3))
    total = m + n
    assert total.order == 1  # the lower order wins
    np.testing.assert_array_equal(total.value, [1, 2, 3])
    np.testing.assert_array_equal((m - 1.0).value, [-1, 0, 1])
    np.testing.assert_array_equal((2 * m).velocity, [2, 2, 2])
    assert m[1:].value.tolist() == [1.0, 2.0]


def test_fixed_point():
    p = fixed_point(1 + 2j, np.zeros(4))
    assert p.value.shape == (4,) and not p.velocity.any() and not p.acceleration.any()
    np.testing.assert_array_equal(p.value, [1 + 2j] * 4)
    assert fixed_point(0j, np.zeros(2), order=0).order == 0


def test_constant_is_a_read_only_view_of_one_number():
    c = constant(2.5, (3, 4))
    assert c.shape == (3, 4) and c.strides == (0, 0) and not c.flags.writeable
    np.testing.assert_array_equal(c, np.full((3, 4), 2.5))
    with pytest.raises(ValueError):
        c[0, 0] = 1.0


@pytest.mark.parametrize("span", [7.0, 1e3, 1e9, 1e300])
@pytest.mark.parametrize("length", [1.0, -0.3, 1e-150])
def test_unit_vector_from_the_half_angle_is_round_off(span, length):
    # expected: cosine and sine in extended precision (64-bit mantissa), an independent evaluation
    phi = np.random.default_rng(8).uniform(-span, span, 200_000)
    phi[:4] = [0.0, np.pi, -np.pi / 2, np.nextafter(np.pi, 0.0)]
    u = unit_vector_fast(phi, length)
    exact = np.longdouble(phi)
    bound = 4e-16 * abs(length)
    assert np.max(np.abs(u.real - length * np.cos(exact))) <= bound
    assert np.max(np.abs(u.imag - length * np.sin(exact))) <= bound
    assert unit_vector_fast(np.float64(1.0), length) == pytest.approx(length * np.exp(1j), abs=bound)


def test_harmonic_law_against_hand_derivatives():
    # expected: q = m + A sin(ωt + p), q_t = Aω cos(ωt + p), q_tt = −Aω² sin(ωt + p) (by hand)
    t = np.array([0.0, 0.25])
    q = mech.harmonic(0.5, 0.2, 2 * np.pi, t)
    np.testing.assert_allclose(q.value, [0.5, 0.7])
    np.testing.assert_allclose(q.velocity, [0.2 * 2 * np.pi, 0.0], atol=1e-15)
    np.testing.assert_allclose(q.acceleration, [0.0, -0.2 * (2 * np.pi) ** 2], atol=1e-12)


def test_link_types_cover_the_lecture():
    names = [t.name for t in mech.LINK_TYPES]
    assert names == ["frame", "crank", "rocker", "coupler", "slider", "slotted link"]
    assert mech.link_type("slider").russian == "ползун"
    with pytest.raises(KeyError, match="known: frame"):
        mech.link_type("cam")


def test_derivatives_read_as_arrays_or_a_clear_error():
    # d1 and d2 are the velocity and acceleration themselves when computed, and the package's error
    # (also a TypeError, as arithmetic on a missing None would raise) when not; omega/alpha stay None
    from mechanisms.core.errors import MissingDerivativeError
    rates = np.array([1.0, 2.0])
    full = AngleMotion(np.array([0.1, 0.2]), rates, rates * 3)
    assert full.d1 is full.velocity and full.d2 is full.acceleration
    positions_only = AngleMotion(np.array([0.1]))
    with pytest.raises(MissingDerivativeError, match="order ≥ 1"):
        positions_only.d1
    with pytest.raises(TypeError):
        positions_only.d1
    with pytest.raises(MissingDerivativeError, match="order=2"):
        AngleMotion(np.array([0.1]), np.array([1.0])).d2
    assert positions_only.omega is None and positions_only.alpha is None
