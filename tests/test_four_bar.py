"""Tests of the four-bar (mechanisms/four_bar.py): closed forms, branches, continuation, errors."""

import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings

from mechanisms import AssemblyError, SingularPositionWarning, FourBar, InvalidParameterError
from mechanisms.linkages.four_bar import (assembly_intervals, cramer_rates, half_angle_coupler_angle,
                                 stable_coupler_angle)
from mechanisms.verify import constraint_residual, derivative_errors, distance_deviation, solve_constraints
from strategies import four_bar_geometries


def wrap(angle):
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi


def inner_angles(mechanism, count=7):
    """Crank angles well inside the first assembly interval (away from its limits)."""
    lo, hi = mechanism.assembly_intervals()[0]
    margin = 0.1 * (hi - lo) if hi - lo < 2 * np.pi - 1e-9 else 0.0
    return np.linspace(lo + margin, hi - margin, count, endpoint=hi - lo < 2 * np.pi - 1e-9)


def well_conditioned(mechanism, phi):
    """True if the coupler and rocker are nowhere nearly in line (|sin μ| > 0.1) and A ≠ C."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", SingularPositionWarning)
            sol = mechanism.solve(phi, order=0)
    # A passes through C when L2 = L3 and d = L1 (an indeterminate position): an error when exact,
    # flagged singular when d is L1 only within round-off, as for frame = (cos 1, sin 1) and L1 = 1
    except (AssemblyError, SingularPositionWarning):
        return False
    return np.all(np.abs(np.sin(sol.angle("coupler").value - sol.angle("rocker").value)) > 0.1)


@settings(max_examples=200, deadline=None)
@given(four_bar_geometries())
def test_closed_form_against_the_generic_solver(geometry):
    crank, coupler, rocker, frame, branch = geometry
    m = FourBar(crank, coupler, rocker, frame, branch)
    assume(not m.change_points())         # tested on their own below
    phi = inner_angles(m)
    assume(well_conditioned(m, phi))
    closed = m.solve(phi, omega=2.0, alpha=-0.7)
    q = np.array([closed.angle("coupler").value, closed.angle("rocker").value])
    # expected: Newton on the loop-closure equations from a guess 0.01 rad off, one per position
    generic = solve_constraints(m.constraints, q + 0.01, phi, omega=2.0, alpha=-0.7)
    scale = max(crank, coupler, rocker) / min(crank, coupler, rocker)
    assert np.max(np.abs(wrap(generic.q - q))) < 1e-10
    rates = np.array([closed.angle("coupler").omega, closed.angle("rocker").omega])
    accelerations = np.array([closed.angle("coupler").alpha, closed.angle("rocker").alpha])
    assert np.max(np.abs(generic.q_t - rates)) < 1e-9 * scale * (1 + np.max(np.abs(rates)))
    assert np.max(np.abs(generic.q_tt - accelerations)) < 1e-8 * scale * (1 + np.max(np.abs(accelerations)))
    # the branch is the geometric side of B with respect to A -> C
    a, b = closed.point("A").value, closed.point("B").value
    side = np.sign((np.conj(m.pivot - a) * (b - a)).imag)
    assert np.all(side == branch)


@settings(max_examples=200, deadline=None)
@given(four_bar_geometries())
def test_half_angle_and_cramer_formulas_of_the_lecture(geometry):
    crank, coupler, rocker, frame, branch = geometry
    m = FourBar(crank, coupler, rocker, frame, branch)
    assume(not m.change_points())
    phi = inner_angles(m)
    assume(well_conditioned(m, phi))
    with warnings.catch_warnings():     # a geometry within round-off of a change point is flagged singular
        warnings.simplefilter("ignore", SingularPositionWarning)
        sol = m.solve(phi, omega=1.5, alpha=0.4)
    assume(not sol.singular.any())
    psi, xi = sol.angle("coupler").value, sol.angle("rocker").value
    # P + F away from zero: the half-angle form is accurate there
    p = frame[0] - crank * np.cos(phi)
    f = (p**2 + (frame[1] - crank * np.sin(phi))**2 + coupler**2 - rocker**2) / (2 * coupler)
    assume(np.all(np.abs(p + f) > 0.05 * coupler))
    # expected: the generic solver, started from the closed form 0.01 rad off
    generic = solve_constraints(m.constraints, np.array([psi, xi]) + 0.01, phi, omega=1.5, alpha=0.4)
    assert np.max(np.abs(wrap(half_angle_coupler_angle(phi, crank, coupler, rocker, frame, branch)
                              - generic.q[0]))) < 1e-8
    assert np.max(np.abs(wrap(stable_coupler_angle(phi, crank, coupler, rocker, frame, branch)
                              - generic.q[0]))) < 1e-10
    psi_t, xi_t, psi_tt, xi_tt = cramer_rates(phi, generic.q[0], generic.q[1], crank, coupler, rocker, 1.5, 0.4)
    scale = 1 + np.max(np.abs(generic.q_t)) + np.max(np.abs(generic.q_tt))
    assert np.max(np.abs(psi_t - generic.q_t[0])) < 1e-8 * scale
    assert np.max(np.abs(xi_t - generic.q_t[1])) < 1e-8 * scale
    assert np.max(np.abs(psi_tt - generic.q_tt[0])) < 1e-7 * scale
    assert np.max(np.abs(xi_tt - generic.q_tt[1])) < 1e-7 * scale


def test_the_printed_lecture_velocity_has_the_wrong_sign():
    # the lecture prints ψ_t = φ_t L1 sin(φ − ξ)/(L2 sin(ψ − ξ)); numerical differentiation of
    # the positions (independent of any formula for ψ_t) gives the opposite sign
    m = FourBar(1.0, 3.5, 3.0, (4.0, 0.5))
    phi = np.radians(np.arange(5.0, 360.0, 30.0))
    sol = m.solve(phi, omega=1.0, order=0)
    psi, xi = sol.angle("coupler").value, sol.angle("rocker").value
    h = 1e-6
    numeric = wrap(m.solve(phi + h, order=0).angle("coupler").value
                   - m.solve(phi - h, order=0).angle("coupler").value) / (2 * h)
    printed = np.sin(phi - xi) / (3.5 * np.sin(psi - xi))
    assert np.allclose(numeric, -printed, atol=1e-7)
    assert not np.allclose(numeric, printed, atol=1e-3)


def test_half_angle_form_loses_accuracy_where_p_plus_f_vanishes():
    geometry = (1.0, 3.0, 2.0, (-2.5, 1.0))
    # on branch +1 the coupler passes ψ = π near φ = 204.9° (P + F = 0 there); find that angle by
    # bisection on sin ψ, with ψ from the generic solver
    upper = FourBar(*geometry, branch=1)

    def sin_psi(phi):
        start = upper.solve(np.array([phi]), order=0)
        q = solve_constraints(upper.constraints, [start.angle("coupler").value[0] + 0.01,
                                                  start.angle("rocker").value[0] + 0.01], [phi], order=0).q
        return np.sin(q[0, 0])

    lo, hi = np.radians(204.0), np.radians(205.0)
    assert sin_psi(lo) * sin_psi(hi) < 0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sin_psi(mid) * sin_psi(lo) > 0 else (lo, mid)
    star = 0.5 * (lo + hi)
    lower = FourBar(*geometry, branch=-1)
    errors = []
    for delta in (1e-2, 1e-6, 1e-10):
        phi = np.array([star + delta])
        start = lower.solve(phi, order=0)
        # expected: the generic solver on branch -1, the root that stays finite as P + F → 0
        generic = solve_constraints(lower.constraints, [start.angle("coupler").value[0] + 0.01,
                                                        start.angle("rocker").value[0] + 0.01], phi, order=0)
        errors.append(abs(wrap(half_angle_coupler_angle(phi, *geometry, -1)[0] - generic.q[0, 0])))
        assert abs(wrap(stable_coupler_angle(phi, *geometry, -1)[0] - generic.q[0, 0])) < 1e-14
    # the half-angle form's error grows like 1/(P + F); the stable form's does not
    assert errors[0] < 1e-12
    assert errors[1] > 1e-11 and errors[2] > 1e-8 and errors[2] > 100 * errors[1]


@pytest.mark.parametrize("step_deg", [0.1, 7.0, 45.0, 90.0])
def test_parallelogram_keeps_its_mode_through_the_change_points(step_deg):
    m = FourBar(1.0, 4.0, 1.0, (4.0, 0.0), branch=1)
    phi = np.radians(np.arange(-720.0, 720.0 + step_deg / 2, step_deg))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        sol = m.solve(phi, omega=1.0)
    # expected by hand: B = C + L1·exp(iφ), the rocker parallel to the crank, coupler along +x
    assert np.max(np.abs(sol.point("B").value - (4.0 + np.exp(1j * phi)))) < 1e-6
    regular = ~sol.singular
    assert np.allclose(sol.angle("rocker").omega[regular], 1.0, atol=1e-6)
    assert np.array_equal(sol.singular, np.isclose(np.degrees(phi) % 180.0, 0.0, atol=1e-6)
                          | np.isclose(np.degrees(phi) % 180.0, 180.0, atol=1e-6))


def test_antiparallelogram_on_the_other_branch():
    m = FourBar(1.0, 4.0, 1.0, (4.0, 0.0), branch=-1)
    phi = np.radians(np.arange(10.0, 360.0, 20.0))
    sol = m.solve(phi, order=0)
    b, a = sol.point("B").value, sol.point("A").value
    # expected: the crossed form — the reflection of the parallelogram's B in the line A C
    parallelogram = 4.0 + np.exp(1j * phi)
    u = (4.0 - a) / np.abs(4.0 - a)
    mirror = a + u * np.conj((parallelogram - a) / u)
    assert np.allclose(b, mirror)
    assert np.all(np.abs(b - parallelogram) > 1e-3)


def test_deltoid_does_not_fold_at_its_change_points():
    # kite: crank = coupler = 1, rocker = frame = 3; its folded mode is B ≡ O
    m = FourBar(1.0, 1.0, 3.0, (3.0, 0.0), branch=1)
    phi = np.radians(np.arange(-360.0, 360.0, 5.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        sol = m.solve(phi, order=0)
    a = sol.point("A").value
    # expected by hand: the kite mode, B = reflection of O in the line A C
    u = (3.0 - a) / np.abs(3.0 - a)
    assert np.allclose(sol.point("B").value, a + u * np.conj(-a / u), atol=1e-7)


def test_keep_side_holds_the_geometric_side():
    m = FourBar(1.0, 4.0, 1.0, (4.0, 0.0), branch=1, keep_side=True)
    phi = np.radians([30.0, 150.0, 210.0, 330.0])
    b = m.solve(phi, order=0).point("B").value
    assert np.all(b.imag > 0)     # the crossed form below the x axis, by hand


def test_checks_of_the_analysis_sequence():
    m = FourBar(0.1, 0.35, 0.3, (0.4, 0.05))
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    sol = m.solve(phi, omega=10.0)
    assert constraint_residual(m, sol) < 1e-14
    assert distance_deviation(m, sol) < 1e-14
    errors = derivative_errors(m, phi, omega=10.0)
    assert max(v for v, _ in errors.values()) < 1e-6
    assert max(a for _, a in errors.values()) < 1e-3


def test_assembly_error_names_angles_and_range():
    m = FourBar(2.0, 2.0, 2.0, (3.0, 0.0))            # triple rocker (2 + 3 > 2 + 2)
    (lo, hi), = m.assembly_intervals()
    with pytest.raises(AssemblyError) as info:
        m.solve(np.radians([0.0, 90.0, 180.0]))
    assert info.value.valid_range == pytest.approx((lo, hi))
    assert "180°" in str(info.value) and "assembles only" in str(info.value)
    assert set(np.round(np.degrees(info.value.angles))) == {180.0}


def test_bad_parameters():
    with pytest.raises(InvalidParameterError, match="coupler"):
        FourBar(1.0, -2.0, 1.0, (1.0, 0.0))
    with pytest.raises(InvalidParameterError, match="frame"):
        FourBar(1.0, 2.0, 1.0, (0.0, 0.0))
    with pytest.raises(InvalidParameterError, match="frame"):
        FourBar(1.0, 2.0, 1.0, (1.0,))
    with pytest.raises(InvalidParameterError, match="branch"):
        FourBar(1.0, 2.0, 1.0, (1.0, 0.0), branch=2)
    with pytest.raises(InvalidParameterError, match="frame"):
        FourBar(1.0, 2.0, 1.0, (math.nan, 0.0))


def test_points_on_the_coupler_on_demand():
    m = FourBar(1.0, 3.5, 3.0, (4.0, 0.5))
    sol = m.solve(np.radians([0.0, 60.0]), omega=2.0)
    p = sol.point_on("coupler", 3.5, 0.0)
    assert np.allclose(p.value, sol.point("B").value)
    assert np.allclose(p.velocity, sol.point("B").velocity)
    assert np.allclose(p.acceleration, sol.point("B").acceleration)


def test_assembly_intervals_cover_a_full_turn_for_a_crank_rocker():
    (lo, hi), = assembly_intervals(1.0, 3.5, 3.0, (4.0, 0.5))
    assert hi - lo == pytest.approx(2 * np.pi)


def test_a_pin_passing_within_round_off_of_the_pivot_is_flagged_singular():
    # L2 = L3 and d = |(cos 1, sin 1)| = 1 = L1 only within round-off: exactly, no change point, but at
    # φ = 1 rad the pin A comes within about 1e-16 m of C and the coupler angle is not determined there
    m = FourBar(1.0, 0.5, 0.5, (math.cos(1.0), math.sin(1.0)))
    assert m.change_points() == ()
    with pytest.warns(SingularPositionWarning):
        sol = m.solve(np.array([0.5, 1.0, 1.5]), order=0)
    assert sol.singular.tolist() == [False, True, False]
    # away from it the positions close the loop: |AB| = L2, |CB| = L3
    a, b = sol.point("A").value[[0, 2]], sol.point("B").value[[0, 2]]
    assert np.allclose(np.abs(b - a), 0.5, atol=1e-14)
    assert np.allclose(np.abs(b - m.pivot), 0.5, atol=1e-14)
