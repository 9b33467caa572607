"""Tests of the crank-slider analysis (layer 4): revolution condition and ranges, dead centres, stroke,
time ratio, extreme velocities and accelerations, the approximate formula and source 002's limiting
geometries. Expected values come from hand calculations and brute-force sampling of the slider position
written out in this file, never from the functions under test."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import crank_slider as analysis
from mechanisms.core.errors import AssemblyError
from mechanisms.verify import central_difference
from strategies import branches, crank_slider_geometries, finite

FINE = np.linspace(-np.pi, np.pi, 200_001)


def slider_by_hand(l1, l2, e, b, phi):
    """s = x_B = L1 cos φ + b √(L2² − (L1 sin φ − e)²), written out independently of the package."""
    return l1 * np.cos(phi) + b * np.sqrt(l2**2 - (l1 * np.sin(phi) - e) ** 2)


# --- revolution and ranges ----------------------------------------------------------------------------

@settings(max_examples=40, deadline=None)
@given(crank=st.floats(0.05, 2.0, **finite), rod=st.floats(0.05, 4.0, **finite),
       offset=st.floats(-2.0, 2.0, **finite))
def test_ranges_against_brute_force(crank, rod, offset):
    reach = np.abs(crank * np.sin(FINE[::20]) - offset) <= rod  # assembles where the pin reaches the guide
    if rod < abs(offset) - crank:
        with pytest.raises(AssemblyError, match="any crank angle"):
            mech.CrankSlider(crank, rod, offset)
        return
    m = mech.CrankSlider(crank, rod, offset)
    ranges = analysis.crank_angle_range(m)
    assert analysis.full_revolution(m) == (rod >= crank + abs(offset)) == (ranges is None)
    if ranges is None:
        assert reach.all()
        return
    phi = FINE[::20]
    inside = np.zeros_like(reach)
    for lo, hi in ranges:
        inside |= ((phi - lo) % (2 * np.pi) <= (hi - lo) + 1e-12)
    # away from the ends (where rounding decides) the intervals agree with the brute-force test
    edge = np.min([np.abs(np.angle(np.exp(1j * (phi - x)))) for r in ranges for x in r], axis=0) < 1e-9
    np.testing.assert_array_equal(inside[~edge], reach[~edge])


def test_ranges_by_hand():
    # offset 0.1, crank 0.1, rod 0.15: sin φ ≥ −1/2 → [−30°, 210°] (one arc)
    (lo, hi), = analysis.crank_angle_range(mech.CrankSlider(0.1, 0.15, 0.1))
    np.testing.assert_allclose(np.degrees([lo, hi]), [-30.0, 210.0])
    # offset −0.1: mirrored in x, sin φ ≤ 1/2 → [−210°, 30°]
    (lo, hi), = analysis.crank_angle_range(mech.CrankSlider(0.1, 0.15, -0.1))
    np.testing.assert_allclose(np.degrees([lo, hi]), [-210.0, 30.0])
    # axial, rod 0.1 < crank 0.2: |sin φ| ≤ 1/2 → two arcs
    ranges = analysis.crank_angle_range(mech.CrankSlider(0.2, 0.1))
    np.testing.assert_allclose(np.degrees(ranges), [[-30.0, 30.0], [150.0, 210.0]])


# --- dead centres, stroke, time ratio ------------------------------------------------------------------

def test_axial_dead_centres_by_hand():
    # axial: the crank along the guide, s = L2 ± L1, stroke 2 L1, K = 1
    m = mech.CrankSlider(0.08, 0.3)
    centres = analysis.dead_centres(m)
    assert centres.phi_outer == 0.0 and centres.phi_inner == pytest.approx(np.pi)
    assert centres.s_outer == pytest.approx(0.38) and centres.s_inner == pytest.approx(0.22)
    assert analysis.stroke(m) == pytest.approx(0.16, rel=1e-14)
    assert analysis.time_ratio(m).ratio == pytest.approx(1.0, rel=1e-14)


def test_offset_time_ratio_of_source_002():
    # r = 2, e = 1, L = 4 (source 002, problem 1): by hand θ = arcsin(1/2) − arcsin(1/6) = 30° − 9.594°,
    # K = (180° + θ)/(180° − θ) = 1.2557; stroke √(36 − 1) − √(4 − 1) = 4.1840 m
    theta = np.pi / 6 - np.arcsin(1 / 6)
    for offset in (1.0, -1.0):
        m = mech.CrankSlider(2.0, 4.0, offset)
        ratio = analysis.time_ratio(m)
        assert ratio.ratio == pytest.approx((np.pi + theta) / (np.pi - theta), rel=1e-14)
        assert ratio.overlap_angle == pytest.approx(theta, rel=1e-14)
        assert ratio.outward_angle + ratio.return_angle == pytest.approx(2 * np.pi)
        assert analysis.stroke(m) == pytest.approx(np.sqrt(35) - np.sqrt(3), rel=1e-14)


@settings(max_examples=40, deadline=None)
@given(geometry=crank_slider_geometries(), branch=branches)
def test_dead_centres_against_brute_force(geometry, branch):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    centres = analysis.dead_centres(m)
    s = slider_by_hand(crank, rod, offset, branch, FINE)
    far, near = (np.argmax(s), np.argmin(s)) if branch == 1 else (np.argmin(s), np.argmax(s))
    # positions: the sampled extremes (the error of sampling is second order in the step, 3e-5 rad)
    assert centres.s_outer == pytest.approx(s[far], abs=1e-8 * (crank + rod))
    assert centres.s_inner == pytest.approx(s[near], abs=1e-8 * (crank + rod))
    assert analysis.stroke(m) == pytest.approx(np.ptp(s), abs=1e-8 * (crank + rod))
    # angles: near the sampled ones (a flat extreme fixes its angle to about √(rounding) only)
    step = FINE[1] - FINE[0]
    for phi, k in ((centres.phi_outer, far), (centres.phi_inner, near)):
        assert abs(np.angle(np.exp(1j * (phi - FINE[k])))) < 1e-3 + step
    # the slider is at rest there (exact velocities of the closed form, which the generic solver checks)
    sol = m.solve([centres.phi_outer, centres.phi_inner], 1.0)
    np.testing.assert_allclose(sol.slider("B").velocity, 0.0, atol=1e-12 * (crank + rod))
    # time ratio: crank angles between the sampled extremes, counter-clockwise from inner to outer
    outward = (FINE[far] - FINE[near]) % (2 * np.pi)
    ratio = analysis.time_ratio(m)
    assert ratio.outward_angle == pytest.approx(outward, abs=2e-3)
    expected = max(outward, 2 * np.pi - outward) / min(outward, 2 * np.pi - outward)
    assert ratio.ratio == pytest.approx(expected, rel=5e-3)
    assert analysis.time_ratio(m, -1).outward_angle == pytest.approx(ratio.return_angle, rel=1e-14)


def test_dead_centres_need_a_full_revolution():
    with pytest.raises(AssemblyError, match="crank \\+ \\|offset\\|"):
        analysis.dead_centres(mech.CrankSlider(0.1, 0.15, 0.1))
    with pytest.raises(ValueError, match="direction"):
        analysis.time_ratio(mech.CrankSlider(0.08, 0.3), 0)


# --- extreme velocities and accelerations ----------------------------------------------------------------

@pytest.mark.parametrize("crank, rod, offset, branch", [(0.08, 0.3, 0.0, 1), (2.0, 4.0, 1.0, 1),
                                                        (0.1, 0.25, -0.05, -1)])
def test_slider_extremes_against_brute_force(crank, rod, offset, branch):
    omega = 215.0
    m = mech.CrankSlider(crank, rod, offset, branch)
    got = analysis.slider_extremes(m, omega)
    # brute force: numerical derivatives of the hand formula for s on a fine grid (h = 1e-4 rad)
    s = lambda p: slider_by_hand(crank, rod, offset, branch, p)  # noqa: E731
    v = central_difference(s, FINE, omega, 1e-4, 1)
    a = central_difference(s, FINE, omega, 1e-3, 2)
    scale_v, scale_a = omega * crank, omega**2 * crank
    assert got.velocity_max.value == pytest.approx(v.max(), abs=1e-6 * scale_v)
    assert got.velocity_min.value == pytest.approx(v.min(), abs=1e-6 * scale_v)
    assert got.acceleration_max.value == pytest.approx(a.max(), abs=1e-5 * scale_a)
    assert got.acceleration_min.value == pytest.approx(a.min(), abs=1e-5 * scale_a)
    # the refined maxima are not below any sampled value (they are the extremes, not samples near them)
    assert got.velocity_max.value >= v.max() - 1e-7 * scale_v
    # where the velocity is extreme the acceleration vanishes
    at = m.solve([got.velocity_max.phi, got.velocity_min.phi], omega).slider("B").acceleration
    np.testing.assert_allclose(at, 0.0, atol=1e-6 * scale_a)


def test_axial_extreme_acceleration_by_hand():
    # axial, at the outer dead centre: a = −ω² L1 (1 + λ) (hand calculation), the smallest value
    got = analysis.slider_extremes(mech.CrankSlider(0.08, 0.3), 215.0)
    assert got.acceleration_min.value == pytest.approx(-215.0**2 * 0.08 * (1 + 0.08 / 0.3), rel=1e-13)
    assert abs(got.acceleration_min.phi) < 1e-6


def test_extremes_need_a_bounded_acceleration():
    with pytest.raises(AssemblyError, match="unbounded"):
        analysis.slider_extremes(mech.CrankSlider(2.0, 3.0, -1.0))
    with pytest.raises(AssemblyError, match="turns fully"):
        analysis.slider_extremes(mech.CrankSlider(2.0, 2.5, 1.0))


# --- the approximate (series) formula ---------------------------------------------------------------

def test_approximate_formula_is_the_textbook_one_and_consistent():
    m = mech.CrankSlider(0.08, 0.3)
    lam, l1, w = 0.08 / 0.3, 0.08, 215.0
    phi = np.radians(np.arange(0, 360, 15.0))
    approx = analysis.approximate_slider(m, phi, w)
    # the textbook form for the axial mechanism (λ = L1/L2)
    np.testing.assert_allclose(approx.value, 0.3 + l1 * (np.cos(phi) - lam / 4 * (1 - np.cos(2 * phi))), atol=1e-16)
    np.testing.assert_allclose(approx.velocity, -w * l1 * (np.sin(phi) + lam / 2 * np.sin(2 * phi)), atol=1e-13)
    np.testing.assert_allclose(approx.acceleration, -w**2 * l1 * (np.cos(phi) + lam * np.cos(2 * phi)), atol=1e-10)


@pytest.mark.parametrize("offset, branch", [(0.03, 1), (-0.02, -1)])
def test_approximate_derivatives_are_derivatives_of_its_position(offset, branch):
    m = mech.CrankSlider(0.08, 0.3, offset, branch)
    phi = np.radians(np.arange(0, 360, 15.0))
    approx = analysis.approximate_slider(m, phi, 10.0)
    s = lambda p: analysis.approximate_slider(m, p, 10.0).value  # noqa: E731
    np.testing.assert_allclose(approx.velocity, central_difference(s, phi, 10.0, 1e-5, 1), atol=1e-8)
    np.testing.assert_allclose(approx.acceleration, central_difference(s, phi, 10.0, 1e-4, 2), atol=1e-5)


@pytest.mark.parametrize("lam", [0.1, 0.2, 0.3])
def test_error_of_the_approximate_formula(lam):
    # neglected term −h⁴/(8 L2³) with h = L1 sin φ: the largest error ≈ L1 λ³/8 (at φ = ±90°), to a
    # relative O(λ²) (the next term, −h⁶/(16 L2⁵))
    l1 = 0.1
    m = mech.CrankSlider(l1, l1 / lam)
    exact = slider_by_hand(l1, l1 / lam, 0.0, 1, FINE)
    error = np.max(np.abs(exact - analysis.approximate_slider(m, FINE).value))
    assert error == pytest.approx(l1 * lam**3 / 8, rel=lam**2)


# --- source 002's limiting geometries -------------------------------------------------------------------

def test_source_002_regular_geometry():
    # r = 2, e = 1, L = 4: L ≥ r + e = 3, a full revolution without a singular position
    m = mech.CrankSlider(2.0, 4.0, -1.0)
    assert analysis.full_revolution(m)
    sol = m.solve(np.radians(np.arange(0.0, 360.0, 1.0)), 0.5)
    assert not sol.singular.any()


@pytest.mark.parametrize("offset, rod", [(-2.0, 4.0), (-1.0, 3.0)])
def test_source_002_limiting_geometries(offset, rod):
    # r = 2 with L = r + |e|: a full revolution, but at φ = 90° (the pin farthest from the guide y = e < 0)
    # crank and rod stand in one vertical line, B right below O. Near φ = 90° + δ by hand: h = r cos δ − e,
    # w = √(L² − h²) ≈ √(L r)|δ|, u = −r sin δ, so on branch +1 s ≈ −r δ + √(L r)|δ|: the slider is at its
    # inner extreme s = 0 and its velocity jumps from −(r + √(L r))ω to (√(L r) − r)ω.
    r, w = 2.0, 1.0
    m = mech.CrankSlider(r, rod, offset)
    assert analysis.full_revolution(m)
    centres = analysis.dead_centres(m)
    assert centres.s_inner == 0.0 and centres.phi_inner == pytest.approx(np.pi / 2)
    # δ = 1e-4: the one-sided limits to O(δ) (a smaller δ loses digits in L − h ≈ r δ²/2, formed from sin φ)
    delta = 1e-4
    sol = m.solve(np.pi / 2 + np.array([-delta, delta]), w)
    jump = np.sqrt(rod * r) * w
    np.testing.assert_allclose(sol.slider("B").velocity, [-r * w - jump, -r * w + jump], rtol=1e-3)
    # the other continuation through the same position is branch −1: there the velocity is smooth
    other = mech.CrankSlider(r, rod, offset, -1).solve(np.pi / 2 + np.array([delta]), w)
    np.testing.assert_allclose(other.slider("B").velocity, [-r * w - jump], rtol=1e-3)


def test_bad_input_of_the_helpers_names_the_parameter():
    m = mech.CrankSlider(0.08, 0.3)
    with pytest.raises(mech.InvalidParameterError, match="phi must be finite"):
        analysis.approximate_slider(m, [0.0, np.nan])
    with pytest.raises(mech.InvalidParameterError, match="omega"):
        analysis.approximate_slider(m, [0.0, 1.0], np.inf)
    with pytest.raises(mech.InvalidParameterError, match="omega"):
        analysis.slider_extremes(m, 0.0)
    with pytest.raises(mech.InvalidParameterError, match="samples"):
        analysis.slider_extremes(m, 1.0, samples=2)


def test_the_inner_extreme_of_the_limiting_geometry_is_marked_singular():
    # by hand: L2 = L1 + |e| (1 + 1 = 2, 2 + 0.5 = 2.5) makes the folded position the coupler
    # perpendicular to the guide; 2.5 ≠ 1 + 1 is an ordinary crank-slider; the rounded float sum
    # 0.1 + 0.2 = 0.30000000000000004 exceeds the exact sum of the doubles 0.1 and 0.2 (by about
    # 2.8·10⁻¹⁷), so that rod makes an ordinary crank-slider too
    assert analysis.dead_centres(mech.CrankSlider(1.0, 2.0, 1.0)).inner_singular
    assert analysis.dead_centres(mech.CrankSlider(2.0, 2.5, -0.5)).inner_singular
    assert not analysis.dead_centres(mech.CrankSlider(1.0, 2.5, 1.0)).inner_singular
    assert not analysis.dead_centres(mech.CrankSlider(0.1, 0.1 + 0.2, 0.2)).inner_singular
