"""Tests of layer 5: the generic solver, numerical differentiation and the checks.

The known closed-form answer is the offset crank-slider solved by hand in this file; the checks
are run on the Scotch yoke of tests/mechanisms_for_tests.py and on a deliberately broken copy of it.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms import verify
from mechanisms.core.errors import AssemblyError, SingularPositionWarning
from mechanisms.core.motion import Motion
from mechanisms_for_tests import ScotchYoke

PHI = np.radians(np.arange(0, 360, 15.0))


def slider_loop(l1, l2, e):
    """Constraints of an offset crank-slider in the unknowns (ψ, s)."""
    def constraints(q, phi):
        psi, s = q
        return (l1 * np.cos(phi) + l2 * np.cos(psi) - s, l1 * np.sin(phi) + l2 * np.sin(psi) - e)
    return constraints


def slider_by_hand(l1, l2, e, phi, w, eps):
    """ψ, s and their derivatives derived by hand (the branch with the slider to the right)."""
    psi = np.arcsin((e - l1 * np.sin(phi)) / l2)
    s = l1 * np.cos(phi) + np.sqrt(l2**2 - (e - l1 * np.sin(phi)) ** 2)
    psi_t = -l1 * np.cos(phi) * w / (l2 * np.cos(psi))
    s_t = -l1 * np.sin(phi) * w - l2 * np.sin(psi) * psi_t
    psi_tt = (l1 * np.sin(phi) * w**2 - l1 * np.cos(phi) * eps + l2 * np.sin(psi) * psi_t**2) / (l2 * np.cos(psi))
    s_tt = -l1 * (np.cos(phi) * w**2 + np.sin(phi) * eps) - l2 * (np.cos(psi) * psi_t**2 + np.sin(psi) * psi_tt)
    return np.array([psi, s]), np.array([psi_t, s_t]), np.array([psi_tt, s_tt])


@settings(max_examples=30, deadline=None)
@given(l1=st.floats(0.05, 1.0), ratio=st.floats(1.2, 6.0), e_frac=st.floats(-0.15, 0.15),
       w=st.floats(-300, 300), eps=st.floats(-1e4, 1e4))
def test_generic_solver_reproduces_hand_solution(l1, ratio, e_frac, w, eps):
    l2 = ratio * l1 * 1.2
    e = e_frac * l2
    expected = slider_by_hand(l1, l2, e, PHI, w, eps)
    got = verify.solve_constraints(slider_loop(l1, l2, e), expected[0][:, 0] + 0.01, PHI, w, eps)
    for g, x in zip((got.q, got.q_t, got.q_tt), expected):
        scale = np.max(np.abs(x)) + l2
        np.testing.assert_allclose(g, x, atol=1e-12 * scale)
    assert got.residual < 1e-13 * l2


def test_one_guess_per_position_solves_at_once():
    expected = slider_by_hand(0.08, 0.3, 0.02, PHI, 215.0, 0.0)
    got = verify.solve_constraints(slider_loop(0.08, 0.3, 0.02), expected[0] + 0.02, PHI, 215.0)
    np.testing.assert_allclose(got.q, expected[0], atol=1e-14)
    np.testing.assert_allclose(got.q_tt, expected[2], rtol=1e-12, atol=1e-9)


def test_continuation_keeps_the_branch_of_the_guess():
    # expected: the mirror branch, slider to the left: ψ' = π − ψ, s' = L1 cos φ − √(...)
    l1, l2, e = 0.08, 0.3, 0.0
    right = slider_by_hand(l1, l2, e, PHI, 1.0, 0.0)[0]
    got = verify.solve_constraints(slider_loop(l1, l2, e), [np.pi - 0.01, -0.3], PHI, order=0)
    np.testing.assert_allclose(got.q[1], l1 * np.cos(PHI) - (right[1] - l1 * np.cos(PHI)), atol=1e-14)


def test_orders_are_honoured():
    got = verify.solve_constraints(slider_loop(0.08, 0.3, 0.0), [0.0, 0.38], PHI, order=0)
    assert got.q_t is None and got.q_tt is None
    got = verify.solve_constraints(slider_loop(0.08, 0.3, 0.0), [0.0, 0.38], PHI, order=1)
    assert got.q_t is not None and got.q_tt is None


def test_no_assembly_names_the_angles():
    # the rod (0.05 m) cannot reach the guide 0.12 m above the pivot when sin φ < 0.875
    with pytest.raises(AssemblyError, match="crank angle"):
        verify.solve_constraints(slider_loop(0.08, 0.05, 0.12), [1.5, 0.0], PHI, order=0)


@pytest.mark.parametrize("derivative, step", [(1, 1e-5), (2, 1e-4)])
def test_central_difference_on_a_known_function(derivative, step):
    # expected: g(φ) = sin φ at constant ω: g_t = ω cos φ, g_tt = −ω² sin φ (by hand)
    w = 3.0
    got = verify.central_difference(np.sin, PHI, w, step, derivative)
    expected = w * np.cos(PHI) if derivative == 1 else -(w**2) * np.sin(PHI)
    np.testing.assert_allclose(got, expected, atol=1e-8 if derivative == 1 else 1e-6)


def test_central_difference_wraps_angles():
    # an angle jumping from +π to −π: its rate is still ω
    got = verify.central_difference(lambda p: np.angle(np.exp(1j * p)), np.array([np.pi]), 2.0, 1e-3, 1, angle=True)
    np.testing.assert_allclose(got, [2.0])
    got = verify.central_difference(lambda p: np.angle(np.exp(1j * p)), np.array([np.pi]), 2.0, 1e-3, 2, angle=True)
    np.testing.assert_allclose(got, [0.0], atol=1e-6)


def test_checks_pass_on_the_scotch_yoke():
    yoke = ScotchYoke(0.1)
    sol = yoke.solve(PHI, 10.0)
    assert verify.constraint_residual(yoke, sol) < 1e-16
    assert verify.distance_deviation(yoke, sol) < 1e-16
    errors = verify.derivative_errors(yoke, PHI, 10.0)
    assert set(errors) == {"crank", "O", "A", "B"}
    assert max(v for v, a in errors.values()) < 1e-8   # |v| ~ 1 m/s
    assert max(a for v, a in errors.values()) < 1e-4   # |a| ~ 10 m/s²
    assert max(verify.generic_errors(yoke, PHI, 10.0, 30.0)) < 1e-13


class BrokenYoke(ScotchYoke):
    """The yoke with a sign error in its slider velocity: every check must catch it."""

    def _solve(self, crank, order):
        sol = super()._solve(crank, order)
        b = sol.slider("B")
        sol._sliders["B"] = Motion(b.value, -b.velocity if b.velocity is not None else None, b.acceleration)
        sol._points["B"] = sol.point("B").__class__(sol.point("B").value, -sol.point("B").velocity
                                                    if sol.point("B").velocity is not None else None,
                                                    sol.point("B").acceleration)
        return sol


def test_checks_catch_a_wrong_velocity():
    broken = BrokenYoke(0.1)
    assert verify.derivative_errors(broken, PHI, 10.0)["B"][0] > 0.5
    assert verify.generic_errors(broken, PHI, 10.0)[1] > 0.5


class StuckYoke(ScotchYoke):
    """Marks φ = 0 as a singular position, to test the warning."""

    def _solve(self, crank, order):
        sol = super()._solve(crank, order)
        sol.singular = np.isclose(sol.phi, 0.0)
        return sol


def test_dead_centre_warns_and_names_the_angle():
    with pytest.warns(SingularPositionWarning, match="0°"):
        sol = StuckYoke(0.1).solve(PHI, 1.0)
    assert sol.singular.sum() == 1
    StuckYoke(0.1).solve(PHI, 1.0, order=0)  # positions only: nothing unbounded, no warning


def test_newton_history_converges_quadratically():
    # expected: the hand solution; the residual at least squares (to a constant) in each step
    l1, l2, e = 0.08, 0.3, 0.0
    exact = slider_by_hand(l1, l2, e, np.radians([40.0]), 1.0, 0.0)[0][:, 0]
    history = verify.newton_history(slider_loop(l1, l2, e), exact + 0.2, np.radians(40.0), steps=5)
    residuals = [r for _, r in history]
    assert residuals[0] > 0.01 and residuals[-1] < 1e-15
    for before, after in zip(residuals[1:3], residuals[2:4]):
        assert after < 10 * before**2
    np.testing.assert_allclose(history[-1][0], exact, atol=1e-15)


def test_continuation_sub_steps_coarse_grids():
    # a coarse grid (60° steps) with a rod barely longer than the crank: without sub-steps Newton
    # lands on the mirror branch (s off by 0.17 m); expected, the hand solution on the guess's branch
    l1, l2, e = 0.08, 0.085, 0.0
    phi = np.radians(np.arange(0.0, 361.0, 60.0))
    expected = slider_by_hand(l1, l2, e, phi, 1.0, 0.0)[0]
    for max_step in (np.radians(2.0), np.radians(10.0)):
        got = verify.solve_constraints(slider_loop(l1, l2, e), expected[:, 0], phi, order=0, max_step=max_step)
        np.testing.assert_allclose(got.q[1], expected[1], atol=1e-14)
        np.testing.assert_allclose(np.angle(np.exp(1j * (got.q[0] - expected[0]))), 0.0, atol=1e-13)
    repeated = verify.solve_constraints(slider_loop(l1, l2, e), expected[:, 0], np.zeros(3), order=0)
    np.testing.assert_allclose(repeated.q, np.repeat(expected[:, :1], 3, axis=1), atol=1e-15)
