"""Tests of mechanisms.analysis.frenet: the Frenet-frame method of chapter 8.

Expected values come from the direct method (each mechanism's closed form and its points by the
Euler form, ``Solution.point_on``), from the generic Newton solver of ``mechanisms.verify`` (which
differentiates the constraint equations on its own), or from hand calculation. The printed formulas
of Pylypaka and Chepizhnyi (2019) are typed here as printed, to confirm the errata.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import frenet
from mechanisms.core.motion import AngleMotion
from strategies import crank_rockers, crank_slider_geometries, finite, slotted_lever_geometries

# Pylypaka and Chepizhnyi's problems: k = 0.5 1/m, r = 2 m.
K = 0.5
R = 2.0


def generic_law(mechanism, phi, omega, alpha, index=0):
    """The rotation law built from the generic solver's angle of the driven link (coordinate ``index``)."""
    # the closed-form positions, each position by itself, are only Newton's starting guesses; the
    # angles are re-solved and their derivatives come from the differentiated constraint equations
    start = mechanism.solve(phi, omega, alpha, order=0)
    guess = np.array([c.value for c in mechanism.coordinates(start)]) + 1e-3
    generic = mech.verify.solve_generic(mechanism, phi, omega, alpha, order=2, guess=guess)
    link = AngleMotion(generic.q[index], generic.q_t[index], generic.q_tt[index])
    crank = AngleMotion(phi, np.full_like(phi, omega), np.full_like(phi, alpha))
    return frenet.law_from_angles(crank, link, mechanism.crank)


def assert_same_point(law, solution, link, rho, scale):
    """The Frenet-frame point ρ equals the direct method's point on the link, to round-off."""
    frenet_point = law.point(rho)
    direct = solution.point_on(link, rho)  # Euler form on the closed-form solution
    tolerance = 1e-8 * scale
    for ours, theirs, what in zip(frenet_point.derivatives(), direct.derivatives(), ("position", "velocity",
                                                                                     "acceleration")):
        assert np.max(np.abs(ours - theirs)) <= tolerance * max(1.0, np.max(np.abs(theirs))), what


omegas = st.floats(0.3, 20.0, **finite) | st.floats(-20.0, -0.3, **finite)
alphas = st.floats(-30.0, 30.0, **finite)
rhos = st.floats(-5.0, 5.0, **finite)
turn = np.linspace(0.0, 2.0 * np.pi, 25)[:-1] + 0.1


# --- Frenet frame against the direct method, random geometries ----------------------------------

@settings(max_examples=50, deadline=None)
@given(crank_slider_geometries(), st.sampled_from([1, -1]), omegas, alphas, rhos)
def test_crank_slider_points_equal_the_direct_method(geometry, branch, omega, alpha, rho):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    law = generic_law(m, turn, omega, alpha)
    assert_same_point(law, m.solve(turn, omega, alpha), "coupler", rho, 1.0)


@settings(max_examples=50, deadline=None)
@given(crank_rockers(), omegas, alphas, rhos)
def test_four_bar_points_equal_the_direct_method(geometry, omega, alpha, rho):
    crank, coupler, rocker, frame, branch = geometry
    m = mech.FourBar(crank, coupler, rocker, frame, branch)
    law = generic_law(m, turn, omega, alpha)
    assert_same_point(law, m.solve(turn, omega, alpha), "coupler", rho, 1.0)


@st.composite
def lambda_geometries(draw):
    """(r, b, d) of a lambda mechanism whose crank turns fully (Grashof, crank shortest) with margin."""
    r = draw(st.floats(0.2, 1.0, **finite))
    b = draw(st.floats(r + 0.3, 3.0, **finite))
    d = draw(st.floats(r + 0.3, 3.0, **finite))
    assume(r + max(b, d) < b + min(b, d) - 0.1)
    return r, b, d


@settings(max_examples=50, deadline=None)
@given(lambda_geometries(), omegas, alphas, rhos)
def test_lambda_mechanism_points_equal_the_direct_method(geometry, omega, alpha, rho):
    m = mech.LambdaMechanism(*geometry)
    law = generic_law(m, turn, omega, alpha)
    assert_same_point(law, m.solve(turn, omega, alpha), "coupler", rho, 1.0)


@settings(max_examples=50, deadline=None)
@given(slotted_lever_geometries(), omegas, alphas, rhos)
def test_rocker_in_block_points_equal_the_direct_method(geometry, omega, alpha, rho):
    crank, pivot = geometry
    m = mech.RockerInBlock(crank, pivot)
    law = generic_law(m, turn, omega, alpha)
    assert_same_point(law, m.solve(turn, omega, alpha), "rocker", rho, 1.0)


def test_rotation_law_of_a_solution_matches_the_generic_solver():
    # rotation_law (from the closed form) against the law from the generic solver's derivatives
    m = mech.LambdaMechanism(2.0, 6.5, 5.0)
    ours = frenet.rotation_law(m, turn, omega=3.0, alpha=-2.0)
    reference = generic_law(m, turn, 3.0, -2.0)
    assert np.allclose(np.exp(1j * ours.phi), np.exp(1j * reference.phi), atol=1e-12)
    assert np.allclose(ours.phi_s, reference.phi_s, atol=1e-10)
    assert np.allclose(ours.phi_ss, reference.phi_ss, atol=1e-10)


# --- closed forms derived in chapter 8 --------------------------------------------------------

@settings(max_examples=60, deadline=None)
@given(crank_slider_geometries(), st.sampled_from([1, -1]))
def test_crank_slider_law_closed_form(geometry, branch):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    reference = generic_law(m, turn, 1.0, 0.0)  # the generic solver's derivatives
    phi, phi_s, phi_ss = frenet.crank_slider_law(crank * turn, 1.0 / crank, rod, offset, branch)
    assert np.allclose(np.exp(1j * phi), np.exp(1j * reference.phi), atol=1e-10)
    assert np.allclose(phi_s, reference.phi_s, rtol=1e-8, atol=1e-8 / crank)
    assert np.allclose(phi_ss, reference.phi_ss, rtol=1e-8, atol=1e-8 / crank**2)


@settings(max_examples=60, deadline=None)
@given(slotted_lever_geometries())
def test_rocker_in_block_law_closed_form(geometry):
    crank, pivot = geometry
    m = mech.RockerInBlock(crank, pivot)
    reference = generic_law(m, turn, 1.0, 0.0)  # the generic solver's derivatives
    phi, phi_s, phi_ss = frenet.rocker_in_block_law(crank * turn, 1.0 / crank, pivot)
    assert np.allclose(np.exp(1j * phi), np.exp(1j * reference.phi), atol=1e-10)
    assert np.allclose(phi_s, reference.phi_s, rtol=1e-8, atol=1e-8 / crank)
    assert np.allclose(phi_ss, reference.phi_ss, rtol=1e-8, atol=1e-8 / crank**2)


# --- the source's special cases -----------------------------------------------------------------

def test_trajectory_of_the_pin_is_the_crank_circle():
    # ρ = 0: the crank pin, on the circle of radius r = 1/k about O (hand calculation: r e^{iψ})
    m = mech.CrankSlider(R, 4.0, -1.0, -1)
    law = frenet.rotation_law(m, turn, omega=1.0)
    assert np.allclose(law.position(0.0), R * np.exp(1j * turn), atol=1e-14)
    assert np.allclose(law.point(0.0).speed, R * 1.0)  # V = ω r


def test_trajectory_of_rho_equal_l_is_the_guide_line():
    # ρ = L on the crank-slider: the slider, on the guide y = −e (hand calculation)
    for e, rod in ((1.0, 4.0), (2.0, 4.0), (1.0, 3.0)):
        m = mech.CrankSlider(R, rod, -e, -1)
        law = frenet.rotation_law(m, turn + 0.01, omega=1.0)
        path = law.point(rod)
        assert np.allclose(path.y, -e, atol=1e-12)
        assert np.allclose(path.velocity.imag, 0.0, atol=1e-12)
        assert np.allclose(path.acceleration.imag, 0.0, atol=1e-10)


def test_trajectory_of_rho_equal_b_on_the_lambda_mechanism_is_a_circle():
    # ρ = b: the joint B, on the circle of radius b about the rocker pivot C = (−d, 0)
    r, b, d = 2.0, 6.5, 5.0
    law = frenet.rotation_law(mech.LambdaMechanism(r, b, d), turn, omega=1.0)
    point = law.point(b)
    assert np.allclose(np.abs(point.position + d), b, atol=1e-12)
    # a point on a circle about a fixed centre moves along the circle: v ⊥ (B − C)
    assert np.allclose(np.real(np.conj(point.position + d) * point.velocity), 0.0, atol=1e-10)


def test_rocker_turns_at_half_the_crank_speed_when_the_pivot_is_on_the_circle():
    # d = r: the inscribed angle is half the central one, so θ' = k/2 and φ' = −k/2, φ'' = 0
    law = frenet.rotation_law(mech.RockerInBlock(R, (0.0, R)), turn, omega=1.0)
    assert np.allclose(law.phi_s, -K / 2.0, atol=1e-12)
    assert np.allclose(law.phi_ss, 0.0, atol=1e-12)


# --- the source's printed formulas (errata) --------------------------------------------------------

def printed_crank_slider(s, k, e, rod):
    """(8), (9), (10) of the source, as printed."""
    root = np.sqrt(rod**2 * k**2 - (e * k + np.sin(k * s)) ** 2)
    phi = np.pi / 2 - k * s + np.arcsin((e * k + np.sin(k * s)) / (rod * k))
    phi_s = k * np.cos(k * s) / root - k
    phi_ss = ((2 * k**2 * (1 + e**2 * k**2 - rod**2 * k**2) * np.sin(k * s)) / (2 * root**3)
              + e * k**3 * (3 - np.cos(2 * k * s)) / (2 * root**3))
    return phi, phi_s, phi_ss


def printed_rocker(s, k, d):
    """(14), (15), (16) of the source, as printed."""
    q = 1 + k**2 * d**2 - 2 * k * d * np.sin(k * s)
    phi = np.pi / 2 - k * s - np.arccos(np.cos(k * s) / np.sqrt(q))
    phi_s = -k * (2 + d**2 * k**2 - 3 * d * k * np.sin(k * s)) / q
    phi_ss = d * k**3 * (d**2 * k**2 - 1) * np.cos(k * s) / q**2
    return phi, phi_s, phi_ss


def test_printed_crank_slider_law_is_right():
    # the source's problem 1: guide y = −e, slider left of the pin; reference: the generic solver
    for e, rod in ((1.0, 4.0), (0.5, 3.5)):
        reference = generic_law(mech.CrankSlider(R, rod, -e, -1), turn, 1.0, 0.0)
        phi, phi_s, phi_ss = printed_crank_slider(R * turn, K, e, rod)
        assert np.allclose(np.exp(1j * phi), np.exp(1j * reference.phi), atol=1e-12)
        assert np.allclose(phi_s, reference.phi_s, atol=1e-10)
        assert np.allclose(phi_ss, reference.phi_ss, atol=1e-10)


def test_printed_ordinate_6_has_the_wrong_sign():
    # (6) as printed, y_A = L sin γ − e, with γ of (7) fails; y_A = −e − L sin γ holds (hand derivation)
    e, rod = 1.0, 4.0
    s = R * turn
    gamma = -np.arcsin((e * K + np.sin(K * s)) / (rod * K))  # (7)
    y_pin = np.sin(K * s) / K  # (5)
    assert np.max(np.abs(y_pin - (rod * np.sin(gamma) - e))) > 1.0
    assert np.allclose(y_pin, -e - rod * np.sin(gamma), atol=1e-12)


def test_printed_rocker_derivatives_have_the_wrong_sign():
    # (15), (16) against the generic solver: wrong; the corrected forms of the docstring: right
    for d in (4.0, 3.0):
        reference = generic_law(mech.RockerInBlock(R, (0.0, d)), turn, 1.0, 0.0)
        phi, phi_s, phi_ss = printed_rocker(R * turn, K, d)
        assert np.allclose(np.exp(1j * phi), np.exp(1j * reference.phi), atol=1e-12)  # (14) is right for d > r
        assert np.max(np.abs(phi_s - reference.phi_s)) > 0.1
        assert np.max(np.abs(phi_ss - reference.phi_ss)) > 0.01
        # printed (15) equals −k − θ': the sign of γ' was lost; (16) is the negative of φ''
        assert np.allclose(phi_s, -2 * K - reference.phi_s, atol=1e-10)
        assert np.allclose(phi_ss, -reference.phi_ss, atol=1e-10)
        q = 1 + K**2 * d**2 - 2 * K * d * np.sin(turn)
        assert np.allclose(K**2 * d * (np.sin(turn) - K * d) / q, reference.phi_s, atol=1e-12)
        assert np.allclose(d * K**3 * (1 - K**2 * d**2) * np.cos(turn) / q**2, reference.phi_ss, atol=1e-12)


def test_printed_rocker_angle_fails_inside_the_circle():
    # (13)-(14) take γ from an arccosine, so sin γ ≥ 0: wrong where the pivot is below the pin (d < r)
    d = 1.0
    reference = generic_law(mech.RockerInBlock(R, (0.0, d)), turn, 1.0, 0.0)
    phi = printed_rocker(R * turn, K, d)[0]
    wrong = np.abs(np.angle(np.exp(1j * (phi - reference.phi)))) > 1e-9
    below = np.sin(turn) > K * d  # the pin above the pivot
    assert np.array_equal(wrong, below)


def test_printed_trajectory_2_and_projection_11_are_turned_by_minus_90_degrees():
    # (2) and (11) as printed, with φ from (8), give the mechanism of (5)-(7) turned by −90° about O
    e, rod = 1.0, 4.0
    m = mech.CrankSlider(R, rod, -e, -1)
    solution = m.solve(turn, omega=1.0)
    s = R * turn
    phi = printed_crank_slider(s, K, e, rod)[0]
    for rho in (0.0, 2.0, 4.0, -4.0):
        printed = rho * np.exp(1j * (phi + K * s)) + (np.sin(K * s) - 1j * np.cos(K * s)) / K  # (2)
        direct = solution.point_on("coupler", rho)
        assert np.allclose(printed, -1j * direct.position, atol=1e-12)
        law = frenet.rotation_law(m, turn, omega=1.0, solution=solution)
        v_tau, v_n = law.frame_velocity(rho)
        printed_v = (v_tau * np.cos(K * s) - v_n * np.sin(K * s)) + 1j * (v_tau * np.sin(K * s) + v_n * np.cos(K * s))
        assert np.allclose(printed_v, -1j * direct.velocity, atol=1e-12)


def test_printed_lambda_gamma_21_is_right():
    # (21) against the lambda mechanism's closed form (the four-bar of chapter 4): γ = π − θ
    for r, b, d in ((2.0, 6.5, 5.0), (2.0, 5.0, 5.0), (2.0, 6.5, 11.0)):
        m = mech.LambdaMechanism(r, b, d)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", mech.SingularPositionWarning)
            theta = m.solve(turn, order=0).angle("coupler").angle
        gamma = frenet.lambda_mechanism_gamma(turn, r, b, d)
        assert np.allclose(np.exp(1j * gamma), np.exp(1j * (np.pi - theta)), atol=1e-10)


# --- inputs and edge cases ---------------------------------------------------------------------

def test_a_crank_at_rest_is_refused():
    with pytest.raises(mech.InvalidParameterError, match="omega"):
        frenet.rotation_law(mech.CrankSlider(R, 4.0), turn, omega=0.0)


def test_positions_only_law_refuses_velocities():
    law = frenet.rotation_law(mech.CrankSlider(R, 4.0), turn, order=0)
    assert law.order == 0 and law.point(1.0).order == 0
    with pytest.raises(ValueError, match="order 1"):
        law.frame_velocity(1.0)
    law1 = frenet.rotation_law(mech.CrankSlider(R, 4.0), turn, order=1)
    assert law1.point(1.0).order == 1
    with pytest.raises(ValueError, match="order 2"):
        law1.frame_acceleration(1.0)


def test_driven_link_names():
    assert frenet.driven_link(mech.CrankSlider(R, 4.0)) == "coupler"
    assert frenet.driven_link(mech.LambdaMechanism(2.0, 6.5, 5.0)) == "coupler"
    assert frenet.driven_link(mech.RockerInBlock(R, (0.0, 4.0))) == "rocker"
    with pytest.raises(mech.InvalidParameterError, match="hinged to the crank pin"):
        frenet.driven_link(mech.SlottedLever(R, (0.0, 4.0)))


def test_gamma_and_tangent_angle_by_hand():
    # at ψ = 0 with the coupler pointing along −x (θ = π): α = 90°, φ = θ − α = 90°, γ = π − θ = 0
    crank = AngleMotion(np.array([0.0]), np.array([1.0]), np.array([0.0]))
    link = AngleMotion(np.array([np.pi]), np.array([0.5]), np.array([0.0]))
    law = frenet.law_from_angles(crank, link, 2.0)
    assert np.allclose(law.tangent_angle, np.pi / 2)
    assert np.allclose(law.phi, np.pi / 2)
    assert np.allclose(law.gamma, 0.0)
    assert np.allclose(law.phi_s, 0.5 / 2.0 - 0.5)  # θ' = θ_t/(ωr) = 0.25, minus k
    # the point ρ = 1: A = (2, 0), one metre along −x: (1, 0)
    assert np.allclose(law.position(1.0), 1.0 + 0j)


def test_closed_forms_reject_what_has_no_linkage():
    with pytest.raises(mech.InvalidParameterError, match="s must be finite"):
        frenet.crank_slider_law([0.0, np.nan], 10.0, 0.3)
    # r = 0.1 m and a rod of 0.01 m: the pin is farther than the rod from the guide y = 0 except near ψ = 0, π
    with pytest.raises(mech.AssemblyError, match="rod cannot reach"):
        frenet.crank_slider_law([0.0, 0.1], 10.0, 0.01)
    with pytest.raises(mech.InvalidParameterError, match="s must be finite"):
        frenet.rocker_in_block_law([np.inf], 1.0)
