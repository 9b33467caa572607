"""Tests of the slotted-link mechanisms (layer 3): SlottedLever, Shaper, SlottedRockers, SliderOnCoupler.

Expected values come from the generic solver of chapter 2 (Newton's method on each mechanism's own
constraint equations, with exact derivatives), from the lecture's formulas for two rockers with a slotted
pair (checked by hand and written out here), from hand calculations and from the crank's own acceleration.
"""

from __future__ import annotations

import warnings

import matplotlib.pyplot as plt
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.core.errors import AssemblyError, SingularPositionWarning, InvalidParameterError
from mechanisms.verify import constraint_residual, distance_deviation, generic_errors
from strategies import branches, finite, slotted_lever_geometries

PHI = np.radians(np.arange(1.0, 361.0, 10.0))


def generic_errors_from_nearby(m, phi, omega, alpha, nudge=0.02):
    """Like verify.generic_errors, but Newton starts at every position from the closed form's coordinates
    nudged by ``nudge`` (relative): needed where the lever swings fast (near the pivot), where continuation from
    one position to the next may land on the other description (ξ + π, −s) of the same configuration."""
    closed = m.solve(phi, omega, alpha)
    coords = m.coordinates(closed)
    guess = np.array([c.value * (1 + nudge) + nudge for c in coords])
    generic = mech.verify.solve_constraints(m.constraints, guess, phi, omega, alpha, order=2, tol=1e-14)
    wrap = lambda x: (x + np.pi) % (2 * np.pi) - np.pi  # noqa: E731
    return (float(np.max(np.abs(wrap(np.array([c.value for c in coords]) - generic.q)))),
            float(np.max(np.abs(np.array([c.velocity for c in coords]) - generic.q_t))),
            float(np.max(np.abs(np.array([c.acceleration for c in coords]) - generic.q_tt))))


@settings(max_examples=25, deadline=None)
@given(geometry=slotted_lever_geometries(), omega=st.floats(-20, 20, **finite), alpha=st.floats(-50, 50, **finite))
def test_slotted_lever_against_generic_solver(geometry, omega, alpha):
    # expected: the generic solver on Φ = A(φ) − C − s·exp(iξ) = 0
    r, pivot = geometry
    m = mech.SlottedLever(r, pivot)
    d = np.hypot(*pivot)
    gain = (r / abs(d - r)) ** 2  # the lever's rates grow like r/|d − r| near the pivot
    position, velocity, acceleration = generic_errors_from_nearby(m, PHI, omega, alpha)
    assert position < 1e-10 * (1 + r + d)
    assert velocity < 1e-9 * (1 + abs(omega)) * (1 + r) * gain
    assert acceleration < 1e-8 * (1 + omega**2 + abs(alpha)) * (1 + r) * gain**2


@settings(max_examples=15, deadline=None)
@given(crank=st.floats(0.05, 0.2, **finite), distance=st.floats(1.3, 3.0, **finite),
       offset=st.floats(-0.5, 0.5, **finite),
       excess=st.floats(1.1, 1.5, **finite), rod=st.floats(1.0, 3.0, **finite), branch=branches,
       omega=st.floats(-20, 20, **finite))
def test_shaper_against_generic_solver(crank, distance, offset, excess, rod, branch, omega):
    # A shaper: pivot C below O at (offset·r, −distance·r), lever (|OC| + r)·excess, the ram's guide at the height
    # of the lever's end in its middle position; expected: the generic solver on the four loop equations.
    pivot = (offset * crank, -distance * crank)
    d = np.hypot(*pivot)
    lever = (d + crank) * excess
    m = mech.Shaper(crank, pivot, lever, rod * lever, pivot[1] + lever, branch)
    position, velocity, acceleration = generic_errors(m, PHI, omega, 3.0)
    assert position < 1e-10 and velocity < 1e-9 * (1 + abs(omega)) and acceleration < 1e-8 * (1 + omega**2)
    solution = m.solve(PHI, omega)
    assert constraint_residual(m, solution) < 1e-12 and distance_deviation(m, solution) < 1e-12


@settings(max_examples=15, deadline=None)
@given(geometry=slotted_lever_geometries("oscillating"), side=st.floats(-1.0, 1.0, **finite),
       reach=st.floats(1.2, 3.0, **finite), branch=branches, omega=st.floats(-20, 20, **finite))
def test_slotted_rockers_against_generic_solver(geometry, side, reach, branch, omega):
    # The second rocker's pivot O2 near O1; its length exceeds |O1O2|, so its pin always meets the slot line.
    r, pivot = geometry
    o1 = complex(*pivot)
    o2 = o1 + side * r * np.exp(0.4j)
    rocker = reach * max(abs(o2 - o1), 0.2 * r)
    m = mech.SlottedRockers(r, pivot, (o2.real, o2.imag), rocker, branch)
    d = abs(o1)
    gain = (r / abs(d - r)) ** 2 * (1 + r / rocker)
    position, velocity, acceleration = generic_errors_from_nearby(m, PHI, omega, 1.0)
    assert position < 1e-9 * (1 + d)
    assert velocity < 1e-8 * (1 + abs(omega)) * (1 + d) * gain
    assert acceleration < 1e-7 * (1 + omega**2) * (1 + d) * gain**2


@settings(max_examples=15, deadline=None)
@given(crank=st.floats(0.05, 0.5, **finite), ratio=st.floats(1.5, 5.0, **finite), x0=st.floats(-1, 1, **finite),
       y0=st.floats(0.6, 1.5, **finite), angle=st.floats(-0.6, 0.6, **finite), omega=st.floats(-20, 20, **finite))
def test_slider_on_coupler_against_generic_solver(crank, ratio, x0, y0, angle, omega):
    # The second guide: steep (70°–110°), through a point (x0·L2, y0·r), so it always crosses the coupler line
    rod = ratio * crank
    m = mech.SliderOnCoupler(crank, rod, (x0 * rod, y0 * crank), np.pi / 2 + angle)
    solution = m.solve(PHI, omega)
    cosine = np.abs(np.sin(np.pi / 2 + angle - solution.angle("coupler").value)).min()
    position, velocity, acceleration = generic_errors(m, PHI, omega, 2.0)
    gain = (1 + abs(x0) * ratio) / cosine**3
    assert position < 1e-10 * gain and velocity < 1e-9 * (1 + abs(omega)) * gain
    assert acceleration < 1e-8 * (1 + omega**2) * gain


def test_pivot_passing_case():
    # |OC| = r: the block passes through the pivot at φ = γ. Expected (hand, inscribed-angle theorem): the lever
    # turns at ω1/2 everywhere, the signed distance is s = 2r sin((φ − γ)/2); nothing is unbounded, so no
    # warning; away from the passage the generic solver agrees.
    # The pivot must lie on the crank circle exactly for the given doubles (issue 18: a pivot within rounding
    # of the circle, as (r cos γ, r sin γ) is, is an ordinary pivot): r = 5/8 m, C = (3/8, 4/8) m, exact in binary.
    r, omega = 0.625, 6.0
    m = mech.SlottedLever(r, (0.375, 0.5))
    gamma = math.atan2(0.5, 0.375)
    assert m.kind == "through pivot"
    phi = np.sort(np.append(np.radians(np.arange(0.0, 360.0, 10.0)), gamma))  # contains φ = γ exactly
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solution = m.solve(phi, omega, 2.0)
    for motion in (solution.angle("lever"), solution.slider("A")):
        assert all(np.all(np.isfinite(d)) for d in motion.derivatives())
    assert np.all(np.isfinite(solution.extras["A"]["coriolis"]))
    np.testing.assert_allclose(solution.angle("lever").omega, omega / 2)
    np.testing.assert_allclose(solution.slider("A").value, 2 * r * np.sin((phi - gamma) / 2), atol=1e-16)
    at = np.isclose(phi, gamma)
    assert at.sum() == 1 and solution.slider("A").value[at] == pytest.approx(0.0, abs=1e-16)
    away = np.abs(((phi - gamma + np.pi) % (2 * np.pi)) - np.pi) > np.radians(5)
    guess = np.array([solution.angle("lever").value[away] + 0.01, solution.slider("A").value[away] * 1.01])
    generic = mech.verify.solve_constraints(m.constraints, guess, phi[away], omega, 2.0)
    np.testing.assert_allclose(generic.q[0], solution.angle("lever").value[away], atol=1e-12)
    np.testing.assert_allclose(generic.q_t[1], solution.slider("A").velocity[away], atol=1e-11)
    np.testing.assert_allclose(generic.q_tt[0], solution.angle("lever").alpha[away], atol=1e-9)
    np.testing.assert_allclose(generic.q_tt[1], solution.slider("A").acceleration[away], atol=1e-9)


def test_pin_on_the_pivot_through_the_general_block_warns():
    # The general block used directly with the pivot on the crank circle: at the passage the direction is
    # undefined; the mechanism marks it singular and warns instead of returning NaN silently.
    m = mech.SlottedLever(0.1, (0.3, 0.0))
    m.kind = "oscillating"  # force the general block with a pin that reaches the pivot
    m.pivot_point = 0.1 + 0j
    m.pivot = (0.1, 0.0)
    with pytest.warns(SingularPositionWarning, match="0°"):
        solution = m.solve(np.array([0.0, 0.5]), 3.0)
    assert solution.singular.tolist() == [True, False]


@settings(max_examples=20, deadline=None)
@given(geometry=slotted_lever_geometries(), omega=st.floats(-20, 20, **finite), alpha=st.floats(-50, 50, **finite))
def test_coriolis_vector_checks_against_direct_acceleration(geometry, omega, alpha):
    # expected: the crank pin's acceleration computed directly, (iε1 − ω1²)·r·exp(iφ) (chapter 1); the lever
    # point coinciding with A accelerates as (iε3 − ω3²)(A − C); the remainder is relative + Coriolis.
    r, pivot = geometry
    m = mech.SlottedLever(r, pivot)
    sol = m.solve(PHI, omega, alpha)
    direct = (1j * alpha - omega**2) * r * np.exp(1j * PHI)
    xi = sol.angle("lever")
    transport = (1j * xi.alpha - xi.omega**2) * (sol.point("A").value - complex(*pivot))
    relative = sol.slider("A").acceleration * np.exp(1j * xi.value)
    coriolis = m.coriolis_vector(sol)
    gain = (1 + r / np.abs(sol.slider("A").value).min()) ** 2
    np.testing.assert_allclose(transport + relative + coriolis, direct, atol=1e-10 * (omega**2 + abs(alpha) + 1) * gain)
    np.testing.assert_allclose(np.abs(coriolis), np.abs(sol.extras["A"]["coriolis"]), rtol=1e-12, atol=1e-300)


def test_two_rockers_lecture_formulas():
    # Lecture "two rockers with a slotted pair" (checked by hand, correct as printed):
    # x_K = 0.5(n − b) sin 2ξ + m cos²ξ + a sin²ξ, (x_t)_K = ξ_t[(n − b) cos 2ξ + (a − m) sin 2ξ],
    # (x_tt)_K = ξ_tt[…] + 2ξ_t²[(a − m) cos 2ξ + (b − n) sin 2ξ], y_K = b + tg ξ (x_K − a), and the current length
    # CD (the lecture's O1D) from the intersection of the lines CB (angle ξ) and O2D (angle θ).
    a, b, m_, n = 0.0, 0.3, 0.15, 0.4
    mech_ = mech.SlottedRockers(0.1, (a, b), (m_, n), 0.3)
    sol = mech_.solve(PHI, 8.0, 0.0)
    xi = sol.angle("lever")
    k = mech_.foot(sol)
    s2, c2 = np.sin(2 * xi.value), np.cos(2 * xi.value)
    x_k = 0.5 * (n - b) * s2 + m_ * np.cos(xi.value) ** 2 + a * np.sin(xi.value) ** 2
    x_k_t = xi.omega * ((n - b) * c2 + (a - m_) * s2)
    x_k_tt = xi.alpha * ((n - b) * c2 + (a - m_) * s2) + 2 * xi.omega**2 * ((a - m_) * c2 + (b - n) * s2)
    np.testing.assert_allclose(k.x, x_k, atol=1e-15)
    np.testing.assert_allclose(k.velocity.real, x_k_t, atol=1e-13)
    np.testing.assert_allclose(k.acceleration.real, x_k_tt, atol=1e-11)
    regular = np.abs(np.cos(xi.value)) > 0.1
    np.testing.assert_allclose(k.y[regular], (b + np.tan(xi.value) * (x_k - a))[regular], atol=1e-14)
    theta = sol.angle("rocker").value
    t_th, t_xi = np.tan(theta), np.tan(xi.value)
    x_d = (m_ * t_th - a * t_xi + b - n) / (t_th - t_xi)
    np.testing.assert_allclose(sol.point("D").x, x_d, atol=1e-12)
    h = np.hypot(x_k - m_, k.y - n)
    np.testing.assert_allclose(np.abs(sol.extras["O2"]["h"]), h, atol=1e-14)
    np.testing.assert_allclose(sol.slider("D").value, np.hypot(sol.point("D").x - a, sol.point("D").y - b)
                               * np.sign(sol.slider("D").value), atol=1e-14)


def test_hand_calculation_slotted_lever():
    # r = 0.1 m, C = (0, 0.3) m, φ = 90°, ω1 = 10 rad/s, ε1 = 0, by hand: A = (0, 0.1) straight below C, so
    # ξ = −90°, L = 0.2 m; v_A = (−1, 0) m/s is across the lever: v_rel = 0 and ω3 = −1/0.2 = −5 rad/s (also 5.69:
    # ω1 r cos(φ1 − φ3)/L = 10·0.1·cos 180°/0.2). a_A = (0, −10) m/s² is along the lever, outwards, so
    # L_tt − L ω3² = 10 gives L_tt = 10 + 0.2·25 = 15 m/s², and across it 2 ω3 v_rel + L ε3 = 0 gives ε3 = 0.
    m = mech.SlottedLever(0.1, (0.0, 0.3))
    s = m.solve(np.radians([90.0]), 10.0)
    assert s.angle("lever").value[0] == pytest.approx(-np.pi / 2, abs=1e-15)
    assert s.slider("A").value[0] == pytest.approx(0.2, abs=1e-15)
    assert s.angle("lever").omega[0] == pytest.approx(-5.0, abs=1e-14)
    assert s.slider("A").velocity[0] == pytest.approx(0.0, abs=1e-15)
    assert s.slider("A").acceleration[0] == pytest.approx(15.0, abs=1e-13)
    assert s.angle("lever").alpha[0] == pytest.approx(0.0, abs=1e-13)
    assert s.extras["A"]["coriolis"][0] == pytest.approx(0.0, abs=1e-13)


def test_bad_inputs():
    with pytest.raises(InvalidParameterError, match="crank"):
        mech.SlottedLever(-0.1, (0, 0.3))
    with pytest.raises(InvalidParameterError, match="pivot"):
        mech.SlottedLever(0.1, (np.nan, 0.3))
    with pytest.raises(InvalidParameterError, match="pivot"):
        mech.SlottedLever(0.1, 0.3)
    with pytest.raises(InvalidParameterError, match="lever"):
        mech.SlottedLever(0.1, (0, 0.3), lever=0.2)
    with pytest.raises(InvalidParameterError, match="pivot"):
        mech.Shaper(0.1, (0, -0.05), 0.5, 0.2, 0.4)
    with pytest.raises(InvalidParameterError, match="lever"):
        mech.Shaper(0.1, (0, -0.3), 0.35, 0.2, 0.0)
    with pytest.raises(AssemblyError, match="cannot reach"):
        mech.Shaper(0.1, (0, -0.3), 0.5, 0.05, 0.5).solve(PHI, 1.0)
    with pytest.raises(AssemblyError, match="does not reach"):
        mech.SlottedRockers(0.1, (0, 0.3), (0.3, 0.3), 0.1).solve(PHI, 1.0)
    with pytest.raises(InvalidParameterError, match="branch"):
        mech.SlottedRockers(0.1, (0, 0.3), (0.1, 0.3), 0.2, branch=0)
    with pytest.raises(InvalidParameterError, match="rod"):
        mech.SliderOnCoupler(0.1, 0.1, (0.2, 0.2), 1.0)


def test_drawing_every_mechanism():
    for m in (mech.SlottedLever(0.1, (0, 0.3)), mech.SlottedLever(0.1, (0, 0.1)), mech.RockerInBlock(2.0, (0, 4.0)),
              mech.Shaper(0.1, (0, -0.3), 0.5, 0.2, 0.2), mech.SlottedRockers(0.1, (0, 0.3), (0.1, 0.35), 0.2),
              mech.SliderOnCoupler(0.08, 0.3, (0.2, 0.1), 1.2)):
        ax = mech.plot.draw(m, m.solve(PHI[:3], 1.0, order=0), index=1)
        assert ax.lines
        plt.close("all")


@settings(max_examples=20, deadline=None)
@given(geometry=slotted_lever_geometries(), omega=st.floats(-20, 20, **finite), alpha=st.floats(-50, 50, **finite))
def test_rocker_in_block_against_generic_solver_and_coriolis(geometry, omega, alpha):
    # expected: the generic solver on A(φ) + t·exp(iψ) − C = 0; and, since the block's centre C is fixed, the
    # acceleration of the rocker's point at C, (a_A + (iε − ω²)(C − A)), the relative t_tt·exp(iψ) and the Coriolis
    # term 2ω t_t·i·exp(iψ) must add up to zero (composition of accelerations).
    r, pivot = geometry
    m = mech.RockerInBlock(r, pivot)
    d = np.hypot(*pivot)
    gain = (r / abs(d - r)) ** 2
    position, velocity, acceleration = generic_errors_from_nearby(m, PHI, omega, alpha)
    assert position < 1e-10 * (1 + d)
    assert velocity < 1e-9 * (1 + abs(omega)) * (1 + r) * gain
    assert acceleration < 1e-8 * (1 + omega**2 + abs(alpha)) * (1 + r) * gain**2
    sol = m.solve(PHI, omega, alpha)
    psi, a = sol.angle("rocker"), sol.point("A")
    e = np.exp(1j * psi.value)
    total = (a.acceleration + (1j * psi.alpha - psi.omega**2) * (complex(*pivot) - a.value)
             + sol.slider("C").acceleration * e + sol.extras["C"]["coriolis"] * 1j * e)
    np.testing.assert_allclose(total, 0.0, atol=1e-10 * (1 + omega**2 + abs(alpha)) * (1 + r) * gain)


def test_rocker_in_block_source_002_special_case():
    # Source 002, problem 3: r = 1/k = 2 m, the block at (0, d). With d = r the rocker turns at exactly half the
    # crank's speed (its angular acceleration is zero for a uniform crank), by the inscribed-angle theorem (hand).
    m = mech.RockerInBlock(2.0, (0.0, 2.0))
    sol = m.solve(np.radians(np.arange(0, 360, 5.0)), 0.5)
    np.testing.assert_allclose(sol.angle("rocker").omega, 0.25)
    np.testing.assert_allclose(sol.angle("rocker").alpha, 0.0)
    assert np.all(np.isfinite(sol.point_on("rocker", 4.0).acceleration))


def test_slider_on_coupler_guide_angle():
    # μ from sin μ = h/L2 (lecture) equals −ψ, the coupler angle of the circle–line block (another method),
    # for the slider on the right of the crank pin; and the block E lies on both lines (hand: cross products vanish).
    m = mech.SliderOnCoupler(0.08, 0.3, (0.2, 0.0), np.radians(70.0))
    sol = m.solve(PHI, 10.0, 3.0)
    mu, psi = m.guide_angle_of_coupler(sol), sol.angle("coupler")
    np.testing.assert_allclose(mu.value, -psi.value, atol=1e-15)
    np.testing.assert_allclose(mu.omega, -psi.omega, atol=1e-12)
    np.testing.assert_allclose(mu.alpha, -psi.alpha, atol=1e-10)
    E, A = sol.point("E").value, sol.point("A").value
    np.testing.assert_allclose(np.imag(np.conj(np.exp(1j * psi.value)) * (E - A)), 0.0, atol=1e-15)
    np.testing.assert_allclose(np.imag(np.exp(-1j * np.radians(70.0)) * (E - 0.2)), 0.0, atol=1e-15)


@pytest.mark.parametrize("m", [mech.SlottedLever(0.1, (0, 0.3)), mech.SlottedLever(0.1, (0, 0.1)),
                               mech.RockerInBlock(2.0, (0, 1.0)), mech.Shaper(0.1, (0, -0.3), 0.5, 0.2, 0.2),
                               mech.SlottedRockers(0.1, (0, 0.3), (0.1, 0.35), 0.2),
                               mech.SliderOnCoupler(0.08, 0.3, (0.2, 0.1), 1.2)])
def test_orders_compute_only_what_is_asked(m):
    # order 0: positions only (no derivatives anywhere); order 1: velocities equal those of order 2 (same formulas)
    s0, s1, s2 = (m.solve(PHI, 3.0, 1.0, order=k) for k in (0, 1, 2))
    for s, k in ((s0, 0), (s1, 1), (s2, 2)):
        assert all(s.angle(n).order == k for n in s.angle_names) and all(s.slider(n).order == k for n in s.slider_names)
    for name in s2.angle_names:
        np.testing.assert_array_equal(s1.angle(name).omega, s2.angle(name).omega)
    for name in s2.point_names:
        np.testing.assert_array_equal(s0.point(name).value, s2.point(name).value)


def test_coriolis_by_name_equals_the_hand_calculation():
    # r = 0.1, C = (0, 0.3), φ = 0, ω = 10: L = √0.1, φ − ξ = atan2(0.3, 0.1), so
    # L_t = −ωr sin(φ − ξ) = −3/√10 and ω3 = ωr cos(φ − ξ)/L = 1: 2ω3·L_t = −6/√10 along the left normal.
    lever = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.3))
    sol = lever.solve([0.0], omega=10.0)
    assert sol.coriolis("A")[0] == pytest.approx(-6 / math.sqrt(10), rel=1e-14)


def test_coriolis_of_an_unknown_pair_or_a_position_solution_names_the_cause():
    lever = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.3))
    with pytest.raises(mech.UnknownNameError, match="sliding pair on a rotating guide named 'B'; known: A"):
        lever.solve([0.0], omega=10.0).coriolis("B")
    with pytest.raises(mech.UnknownNameError, match="known: none"):
        lever.solve([0.0], order=0).coriolis("A")
