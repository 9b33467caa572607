"""Tests of the four-bar analysis (mechanisms/analysis/four_bar.py)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings

from mechanisms import AssemblyError, FourBar
from mechanisms.analysis.four_bar import (best_line, coupler_curve, crank_range, grashof_class, limit_positions,
                                          straight_part, transmission_angle, transmission_extremes)
from strategies import crank_rockers, four_bar_geometries


@pytest.mark.parametrize("lengths, name, rotates", [
    # (crank, coupler, rocker, frame): classes by hand from s + l against p + q
    ((1.0, 3.5, 3.0, 4.0), "crank-rocker", True),
    ((3.0, 3.5, 4.0, 1.0), "double-crank", True),
    ((3.0, 1.0, 3.5, 3.2), "double-rocker", False),
    ((3.0, 3.5, 1.0, 3.2), "rocker-crank", False),
    ((1.0, 4.0, 1.0, 4.0), "change-point linkage", True),       # parallelogram
    ((2.0, 2.0, 2.0, 3.0), "triple rocker", False),
])
def test_grashof_classes(lengths, name, rotates):
    kind = grashof_class(*lengths)
    assert kind.name == name and kind.crank_rotates == rotates


@settings(max_examples=200, deadline=None)
@given(four_bar_geometries())
def test_assembly_range_against_a_brute_force_scan(geometry):
    crank, coupler, rocker, frame, branch = geometry
    m = FourBar(crank, coupler, rocker, frame, branch)
    phi = np.linspace(-np.pi, np.pi, 3601)
    # expected: the triangle inequality for A, B, C at every angle of a fine scan
    ac = np.abs(complex(*frame) - crank * np.exp(1j * phi))
    slack = np.minimum(coupler + rocker - ac, ac - abs(coupler - rocker))
    scanned = slack >= 0
    inside = np.zeros(phi.shape, bool)
    for lo, hi in crank_range(m):
        inside |= ((phi - lo) % (2 * np.pi) <= (hi - lo) + 1e-12) if hi - lo < 2 * np.pi - 1e-12 else True
    clear = np.abs(slack) > 1e-6 * (crank + coupler + rocker)   # away from the limits
    assert np.array_equal(scanned[clear], inside[clear])
    # and solve() assembles exactly there (positions only)
    inner = phi[scanned & clear]
    if inner.size:
        m.solve(inner, order=0)
    outer = phi[~scanned & clear]
    if outer.size:
        with pytest.raises(AssemblyError):
            m.solve(outer, order=0)


@settings(max_examples=100, deadline=None)
@given(crank_rockers())
def test_limit_positions_and_transmission_extremes_against_a_scan(geometry):
    crank, coupler, rocker, frame, branch = geometry
    m = FourBar(crank, coupler, rocker, frame, branch)
    phi = np.linspace(0.0, 2 * np.pi, 20001)
    sol = m.solve(phi, order=0)
    xi = np.unwrap(sol.angle("rocker").value)
    limits = limit_positions(m)
    # expected: the extremes of the rocker angle on a fine scan (step 0.018°)
    found = sorted([phi[np.argmax(xi)], phi[np.argmin(xi)]])
    assert np.allclose(sorted(limits.phi), found, atol=2e-3)
    assert limits.swing == pytest.approx(xi.max() - xi.min(), abs=1e-6)
    stroke = abs(phi[np.argmax(xi)] - phi[np.argmin(xi)])
    assert limits.time_ratio == pytest.approx(max(stroke, 2 * np.pi - stroke) / min(stroke, 2 * np.pi - stroke),
                                              rel=2e-3)
    mu = transmission_angle(sol)
    assert np.allclose(transmission_extremes(m), (mu.min(), mu.max()), atol=1e-6)


def test_a_worked_time_ratio_by_hand():
    # L1 = 1, L2 = 3.5, L3 = 3, C = (4, 0): the extended and folded positions, by the cosine law
    m = FourBar(1.0, 3.5, 3.0, (4.0, 0.0))
    ext = math.acos((4.0**2 + 4.5**2 - 3.0**2) / (2 * 4.0 * 4.5))
    fold = math.acos((4.0**2 + 2.5**2 - 3.0**2) / (2 * 4.0 * 2.5))
    limits = limit_positions(m)
    assert limits.phi[0] == pytest.approx(ext)
    assert limits.phi[1] == pytest.approx(math.pi + fold)
    theta = fold - ext + 0.0
    assert limits.time_ratio == pytest.approx((math.pi + theta) / (math.pi - theta))


def test_limit_positions_need_a_crank_rocker():
    with pytest.raises(AssemblyError, match="crank-rocker"):
        limit_positions(FourBar(2.0, 2.0, 2.0, (3.0, 0.0)))


def test_coupler_curve_of_a_rocking_crank_closes():
    m = FourBar(2.0, 2.0, 2.0, (3.0, 0.0))           # triple rocker: the curve runs both branches
    curve = coupler_curve(m, 1.0, 0.5, positions=201)
    assert abs(curve.value[0] - curve.value[-1]) < 1e-12
    # expected: every point at distance |1 + 0.5i| from A along the coupler, checked via B
    full = coupler_curve(FourBar(1.0, 3.5, 3.0, (4.0, 0.5)), 3.5, 0.0, positions=37)
    sol = FourBar(1.0, 3.5, 3.0, (4.0, 0.5)).solve(np.linspace(*crank_range(FourBar(1.0, 3.5, 3.0, (4.0, 0.5)))[0], 37),
                                                   order=0)
    assert np.allclose(full.value, sol.point("B").value)


def test_best_line_and_straight_part():
    t = np.linspace(-1.0, 1.0, 201)
    # expected by hand: a parabola y = 0.01 t² about the line y = mean; a straight part of
    # tolerance 0.004 ends where 0.01 t² − mean exceeds it
    points = t + 0.01j * t**2
    _, direction, length, deviation = best_line(points)
    assert abs(direction.imag) < 1e-12 and length == pytest.approx(2.0)
    assert deviation == pytest.approx(0.01 - 0.01 * np.mean(t**2))   # the end points, from the mean line
    part = straight_part(t, points, 100, 0.004)
    half = part.phi[1]
    assert 0.01 * half**2 * 2 / 3 <= 0.004 + 1e-12
    with pytest.raises(ValueError):
        straight_part(t, t + 1j * np.abs(t), 100, 1e-6)   # a corner: no straight part


def test_straight_part_centred_by_crank_angle():
    # the middle given as an angle picks the sample nearest to it: t = 0 is sample 100 (by
    # construction of t), also when the angle is given a turn away (angles compared modulo 2π)
    t = np.linspace(-1.0, 1.0, 201)
    points = t + 0.01j * t**2
    by_index = straight_part(t, points, 100, 0.004)
    for angle in (0.0, 2.0 * np.pi, 1e-4):
        assert straight_part(t, points, tolerance=0.004, centre_angle=angle) == by_index
    with pytest.raises(ValueError, match="not both"):
        straight_part(t, points, 100, 0.004, centre_angle=0.0)
    with pytest.raises(ValueError, match="not both"):
        straight_part(t, points, tolerance=0.004)


@pytest.mark.parametrize("bad", [float("nan"), 0.0, -1.0])
def test_grashof_class_rejects_bad_lengths(bad):
    from mechanisms.analysis.four_bar import grashof_class
    from mechanisms.core.errors import InvalidParameterError
    with pytest.raises(InvalidParameterError, match="crank must be a finite length"):
        grashof_class(bad, 1.0, 1.0, 1.0)


def test_half_angle_terms_by_hand():
    # P = a − L1 cos φ, Q = b − L1 sin φ, F = (P² + Q² + L2² − L3²)/(2 L2), by hand for the
    # linkage crank 1, coupler 3.5, rocker 3, frame (−2, 3):
    # φ = 0:   P = −3, Q = 3,  F = (9 + 9 + 12.25 − 9)/7 = 21.25/7
    # φ = 90°: P = −2, Q = 2,  F = (4 + 4 + 12.25 − 9)/7 = 11.25/7
    from mechanisms.analysis.four_bar import half_angle_terms
    p, q, f = half_angle_terms(np.radians([0.0, 90.0]), 1.0, 3.5, 3.0, (-2.0, 3.0))
    assert p.shape == q.shape == f.shape == (2,)
    np.testing.assert_allclose(p, [-3.0, -2.0], atol=1e-15)
    np.testing.assert_allclose(q, [3.0, 2.0], atol=1e-15)
    np.testing.assert_allclose(f, [21.25 / 7, 11.25 / 7], rtol=1e-15)


def test_half_angle_terms_satisfy_the_constraint():
    # the coupler angle of the class (solved by the hinge, not by P, Q, F) satisfies P cos ψ + Q sin ψ = F
    from mechanisms.analysis.four_bar import half_angle_terms
    m = FourBar(crank=1.0, coupler=3.5, rocker=3.0, frame=(4.0, 0.0))
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    psi = m.solve(phi, order=0).angle("coupler").value
    p, q, f = half_angle_terms(phi, 1.0, 3.5, 3.0, (4.0, 0.0))
    np.testing.assert_allclose(p * np.cos(psi) + q * np.sin(psi), f, atol=1e-13)


def test_the_half_angle_denominator_root_is_the_closed_form_root():
    # 𝒫 + ℱ = A cos φ + B sin φ + C0 with (hand algebra from 𝒫 = x_C − L1 cos φ, 𝒬 = y_C − L1 sin φ,
    # ℱ = (𝒫² + 𝒬² + L2² − L3²)/(2 L2)): A = −L1(1 + x_C/L2), B = −L1 y_C/L2,
    # C0 = x_C + (x_C² + y_C² + L1² + L2² − L3²)/(2 L2); its roots φ = atan2(B, A) ± arccos(−C0/√(A² + B²)).
    from mechanisms.analysis.four_bar import half_angle_denominator_root
    l1, l2, l3, (xc, yc) = 1.0, 3.5, 3.0, (-2.0, 3.0)      # chapter 9's linkage
    a, b = -l1 * (1 + xc / l2), -l1 * yc / l2
    c0 = xc + (xc**2 + yc**2 + l1**2 + l2**2 - l3**2) / (2 * l2)
    roots = [math.atan2(b, a) + s * math.acos(-c0 / math.hypot(a, b)) for s in (1, -1)]
    near = min(roots, key=lambda r: abs(math.remainder(r - math.radians(2.4), 2 * math.pi)))
    expected = math.remainder(near, 2 * math.pi)
    found = half_angle_denominator_root(math.radians(0.0), math.radians(5.0), l1, l2, l3, (xc, yc))
    assert found == pytest.approx(expected, abs=1e-14)


def test_the_half_angle_denominator_root_needs_a_sign_change():
    from mechanisms import InvalidParameterError
    from mechanisms.analysis.four_bar import half_angle_denominator_root
    with pytest.raises(InvalidParameterError):     # 𝒫 + ℱ keeps its sign between 10° and 20°
        half_angle_denominator_root(math.radians(10.0), math.radians(20.0), 1.0, 3.5, 3.0, (-2.0, 3.0))
