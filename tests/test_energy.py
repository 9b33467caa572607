"""Tests of mechanisms.analysis.energy: kinetic and potential energy, power, inertia forces,
reduced inertia and the power balance (chapter 7).

Expected values come from hand calculations (a rotating link, a weight, a spring), from numerical
differentiation of the energies, from quadrature of the power, and from the joint forces of
Newton–Euler (in test_kinetostatics.py); none from the function under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import energy
from mechanisms.core.errors import InvalidParameterError, MechanismError

from strategies import crank_slider_with_masses, crank_speeds, finite, four_bar_with_masses

SETTINGS = dict(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])

cases = st.one_of(crank_slider_with_masses(), four_bar_with_masses())
speeds = crank_speeds
accelerations = st.floats(-50.0, 50.0, **finite)


def _phi(count: int = 13) -> np.ndarray:
    return np.linspace(0.1, 0.1 + 2 * np.pi, count, endpoint=False)


# --- a single rotating link: the textbook formulas --------------------------------------------

def test_rotating_link_kinetic_energy_is_j_omega_squared_over_two():
    # only the crank has mass: a uniform bar O–A of length 0.08 m and 1.2 kg
    m = mech.CrankSlider(0.08, 0.3)
    bar = energy.LinkMass(1.2, along=0.04, inertia=1.2 * 0.08**2 / 12)
    sol = m.solve(_phi(), omega=215.0)
    T = energy.kinetic_energy(sol, {"crank": bar})
    # hand: J_O = m L²/3 (uniform bar about its end), T = J_O ω²/2 at every angle
    j_o = 1.2 * 0.08**2 / 3
    assert np.allclose(T.value, 0.5 * j_o * 215.0**2, rtol=1e-13, atol=0)
    assert np.allclose(T.velocity, 0.0, atol=1e-10)  # uniform rotation: T constant


def test_rotating_link_with_offset_centre_and_angular_acceleration():
    # a crank with its centre of mass off the line O–A: Steiner's theorem by hand
    m = mech.CrankSlider(0.1, 0.4)
    props = energy.LinkMass(2.0, along=0.03, left=-0.04, inertia=0.01)
    j_o = 0.01 + 2.0 * (0.03**2 + 0.04**2)  # = 0.015 kg m²
    assert props.inertia_about_joint() == pytest.approx(j_o, rel=1e-14)
    sol = m.solve(np.array([0.3, 2.0]), omega=-12.0, alpha=7.0)
    T = energy.kinetic_energy(sol, {"crank": props})
    assert np.allclose(T.value, 0.5 * 0.015 * 144.0, rtol=1e-13)
    assert np.allclose(T.velocity, 0.015 * (-12.0) * 7.0, rtol=1e-12)  # dT/dt = J_O ω α


def test_slider_kinetic_energy_is_m_v_squared_over_two():
    # a block at B: T = m v_B²/2 with v_B the slider's velocity along the guide
    m = mech.CrankSlider(0.08, 0.3)
    sol = m.solve(_phi(), omega=215.0)
    T = energy.kinetic_energy(sol, {"B": energy.LinkMass(1.5, inertia=9.0)})
    assert np.allclose(T.value, 0.5 * 1.5 * sol.slider("B").velocity ** 2, rtol=1e-13)


# --- potential energy by hand ------------------------------------------------------------------

def test_gravity_of_a_crank_by_hand():
    # centre 0.05 m along a crank at 90°: raised by 0.05 m; at 180° + 30°: lowered by 0.025 m
    m = mech.CrankSlider(0.08, 0.3)
    sol = m.solve(np.radians([90.0, 210.0]), omega=3.0)
    V = energy.potential_energy(sol, {"crank": energy.LinkMass(2.0, along=0.05)}, gravity=9.81)
    assert V.value == pytest.approx([2.0 * 9.81 * 0.05, -2.0 * 9.81 * 0.025], rel=1e-13)
    # dV/dt = m g y_t, y = 0.05 sin φ, y_t = 0.05 ω cos φ
    assert V.velocity == pytest.approx([0.0, 2.0 * 9.81 * 0.05 * 3.0 * math.cos(math.radians(210.0))],
                                       abs=1e-13)


def test_spring_energy_by_hand():
    # spring from the frame point (0, -0.2) to the crank pin A; crank 0.1 at 90°: A = (0, 0.1)
    m = mech.CrankSlider(0.1, 0.4)
    spring = energy.Spring("crank", -0.2j, stiffness=500.0, free_length=0.25, along=0.1)
    sol = m.solve(np.radians([90.0]), omega=2.0)
    V = energy.potential_energy(sol, {}, springs=[spring])
    # ℓ = 0.3 m: V = k (0.05)²/2 = 0.625 J; ℓ_t = 0 (A moves horizontally)
    assert V.value[0] == pytest.approx(0.625, rel=1e-13)
    assert V.velocity[0] == pytest.approx(0.0, abs=1e-13)
    # force on the crank: pulls A down towards the anchor with k (ℓ − ℓ0) = 25 N
    assert spring.force(sol)[0] == pytest.approx(-25.0j, abs=1e-12)


# --- power against numerical differentiation ---------------------------------------------------

def _energies(m, masses, spring, phi0, omega0, alpha, t):
    """T and V along the motion φ(t) = φ0 + ω0 t + α t²/2."""
    sol = m.solve(phi0 + omega0 * t + 0.5 * alpha * t**2, omega0 + alpha * t, alpha)
    return (energy.kinetic_energy(sol, masses).value,
            energy.potential_energy(sol, masses, 9.81, [spring]).value)


@settings(**SETTINGS)
@given(cases, speeds, accelerations, st.floats(0.0, 2 * np.pi, **finite))
def test_power_equals_numerical_time_derivative(case, omega, alpha, phi0):
    m, masses = case
    spring = energy.Spring("coupler", 0.3 + 0.2j, 200.0, 0.1, along=0.5 * m.crank)
    phi = phi0 + _phi(7)
    sol = m.solve(phi, omega, alpha)
    T = energy.kinetic_energy(sol, masses)
    V = energy.potential_energy(sol, masses, 9.81, [spring])
    # central difference in time, step h such that the crank turns by about 1e-4 rad
    h = 1e-4 / abs(omega)
    ahead = _energies(m, masses, spring, phi, omega, alpha, h)
    behind = _energies(m, masses, spring, phi, omega, alpha, -h)
    for exact, plus, minus, value in zip((T.velocity, V.velocity), ahead, behind, (T.value, V.value)):
        numeric = (plus - minus) / (2 * h)
        scale = (np.abs(value).max() + np.abs(exact).max() / abs(omega) + 1.0) * (abs(omega) + abs(alpha) / abs(omega))
        assert np.abs(exact - numeric).max() <= 1e-6 * scale


@settings(**SETTINGS)
@given(cases, st.floats(0.0, 2 * np.pi, **finite), st.floats(0.5, 3.0, **finite))
def test_work_of_the_power_equals_the_change_of_energy(case, start, span):
    # ∫ (dT/dt + dV/dt) dt over a stretch of motion at constant ω equals ΔT + ΔV:
    # the powers integrated by composite Gauss–Legendre (32 panels of 20 points, enough for the
    # sharp peaks of a rod barely longer than the crank) against the energies at the ends
    m, masses = case
    omega = 7.0
    nodes, weights = np.polynomial.legendre.leggauss(20)
    panel = span / 32
    phi = (start + panel * np.arange(32)[:, None] + 0.5 * panel * (nodes + 1.0)).ravel()
    sol = m.solve(phi, omega)
    power = energy.kinetic_energy(sol, masses).velocity + energy.potential_energy(sol, masses).velocity
    work = 0.5 * panel / omega * np.sum(np.tile(weights, 32) * power)   # dt = dφ/ω
    ends = m.solve(np.array([start, start + span]), omega)
    total = energy.kinetic_energy(ends, masses).value + energy.potential_energy(ends, masses).value
    scale = np.abs(total).max() + 1.0
    assert abs(work - (total[1] - total[0])) <= 1e-8 * scale


# --- reduced inertia ---------------------------------------------------------------------------

@settings(**SETTINGS)
@given(cases, speeds, accelerations)
def test_reduced_inertia_gives_kinetic_energy_and_its_slope(case, omega, alpha):
    m, masses = case
    phi = _phi()
    J, dJ = energy.reduced_inertia(m, masses, phi)
    # T = J_red φ_t²/2 for any φ_t, φ_tt (the kinetic energy computed at the actual speed)
    T = energy.kinetic_energy(m.solve(phi, omega, alpha), masses)
    assert np.allclose(0.5 * J * omega**2, T.value, rtol=1e-11, atol=1e-12 * np.abs(T.value).max())
    # dJ/dφ against a central difference of J_red in φ
    h = 1e-5
    numeric = (energy.reduced_inertia(m, masses, phi + h)[0] - energy.reduced_inertia(m, masses, phi - h)[0]) / (2 * h)
    assert np.abs(dJ - numeric).max() <= 1e-6 * (np.abs(J).max() + np.abs(dJ).max())


def test_reduced_inertia_of_the_crank_slider_at_dead_centre_by_hand():
    # at φ = 0 (outer dead centre) the slider stands still and the coupler turns at
    # ψ_t = −φ_t L1/L2: J_red = J_O1 + m2 |v_S2|² + J_S2 (L1/L2)² with v_S2 = iω L1 (1 − u/L2)
    m = mech.CrankSlider(0.08, 0.3)
    masses = {"crank": energy.LinkMass(1.0, inertia=0.005), "coupler": energy.LinkMass(1.2, 0.09, 0.0, 0.02),
              "B": energy.LinkMass(1.0)}
    J, _ = energy.reduced_inertia(m, masses, np.array([0.0]))
    hand = 0.005 + 1.2 * (0.08 * (1 - 0.09 / 0.3)) ** 2 + 0.02 * (0.08 / 0.3) ** 2
    assert J[0] == pytest.approx(hand, rel=1e-13)


# --- inertia forces ----------------------------------------------------------------------------

@settings(**SETTINGS)
@given(cases, speeds)
def test_inertia_forces_against_numerical_second_derivative(case, omega):
    m, masses = case
    phi = _phi(5)
    loads = energy.inertia_forces(m.solve(phi, omega), masses)
    h = 1e-4
    for body, props in masses.items():
        def centre(angles):
            return energy.centre_of_mass(m.solve(angles, omega, order=0), body, props).value
        # a = ω² r'' at constant ω, by a central second difference
        here = centre(phi)
        numeric = omega**2 * (centre(phi + h) - 2 * here + centre(phi - h)) / h**2
        # round-off floor of the second difference: ε |r| ω²/h² ≈ 2e-8 ω² |r|
        scale = props.mass * (np.abs(numeric).max() + omega**2 * np.abs(here).max() + 1.0)
        assert np.abs(loads[body].force + props.mass * numeric).max() <= 1e-5 * scale
    # moments −J_S α, α of each link by a central difference of its ω
    for body in ("crank", "coupler"):
        w = lambda angles: m.solve(angles, omega, order=1).angle(body).omega  # noqa: E731
        alpha = omega * (w(phi + h) - w(phi - h)) / (2 * h)
        assert np.allclose(loads[body].moment, -masses[body].inertia * alpha,
                           atol=1e-6 * (masses[body].inertia * np.abs(alpha).max() + 1.0))


# --- loads -------------------------------------------------------------------------------------

def test_power_of_a_torque_on_the_rocker_and_a_force_on_the_slider():
    four_bar = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.0))
    sol = four_bar.solve(_phi(), omega=10.0)
    P = energy.applied_power(sol, [energy.Torque("rocker", -4.0)])
    assert np.allclose(P, -4.0 * sol.angle("rocker").omega, rtol=1e-14)   # P = M ξ_t
    slider = mech.CrankSlider(0.08, 0.3)
    sol = slider.solve(_phi(), omega=215.0)
    P = energy.applied_power(sol, [energy.Force("B", -300.0 + 50.0j), energy.Torque("B", 7.0)])
    # P = F·v_B: only the x component works (the slider moves along x); a torque on a block does no work
    assert np.allclose(P, -300.0 * sol.slider("B").velocity, rtol=1e-13)


def test_callable_load_acts_on_one_stroke_only():
    m = mech.CrankSlider(0.08, 0.3)
    load = energy.Force("B", lambda s: np.where(s.point("B").velocity.real < 0, 1000.0, 0.0))
    phi = np.radians([90.0, 270.0])   # B moves towards the crank at 90°, away at 270°
    Q = energy.reduced_torque(m, [load], phi)
    # at 90° (axial): v_B/φ_t = −L1 sin φ − L1² sin 2φ/(2 √(L2² − L1² sin² φ)) = −L1 = −0.08 m
    assert Q == pytest.approx([-80.0, 0.0], abs=1e-10)


# --- bad input ---------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs", [dict(mass=-1.0), dict(mass=1.0, inertia=-0.1), dict(mass=float("nan")),
                                    dict(mass=1.0, along=float("inf"))])
def test_bad_mass_properties_raise(kwargs):
    with pytest.raises(InvalidParameterError):
        energy.LinkMass(**kwargs)


def test_unknown_body_and_missing_derivatives_raise():
    m = mech.CrankSlider(0.08, 0.3)
    with pytest.raises(KeyError, match="rocker"):
        energy.kinetic_energy(m.solve(_phi()), {"rocker": energy.LinkMass(1.0)})
    with pytest.raises(MechanismError, match="order=1"):
        energy.kinetic_energy(m.solve(_phi(), order=0), {"crank": energy.LinkMass(1.0)})
    with pytest.raises(MechanismError, match="order=2"):
        energy.inertia_forces(m.solve(_phi(), order=1), {"crank": energy.LinkMass(1.0)})
    with pytest.raises(InvalidParameterError, match="omega"):
        energy.driving_torque(m.solve(_phi(), omega=0.0), {"crank": energy.LinkMass(1.0)})
    with pytest.raises(InvalidParameterError, match=r"loads\[0\] must be a Force\(...\) or a Torque"):
        energy.applied_power(m.solve(_phi()), ["a load"])


# --- issue 28: bad input is the package's error naming it ---------------------------------------------------

@pytest.mark.parametrize("make, named", [
    (lambda: energy.Force("B", "100 N"), "the force on 'B'"),
    (lambda: energy.Force("B", np.nan), "the force on 'B'"),
    (lambda: energy.Force("B", None), "the force on 'B'"),
    (lambda: energy.Force(3, 1.0), "body"),
    (lambda: energy.Force("B", 1.0, along="far"), "along"),
    (lambda: energy.Torque("crank", True), "the torque on 'crank'"),
    (lambda: energy.Torque("crank", 1j), "the torque on 'crank'"),
    (lambda: energy.Spring("B", "1+2j", 10.0), "anchor"),
    (lambda: energy.Spring("B", 10**400, 10.0), "anchor"),
    (lambda: energy.Spring("B", complex(np.inf, 0), 10.0), "anchor"),
    (lambda: energy.Spring("B", 0j, -1.0), "stiffness"),
    (lambda: energy.LinkMass("1"), "mass"),
    (lambda: energy.LinkMass(-1.0), "mass"),
])
def test_bad_loads_springs_and_masses_are_refused_when_made(make, named):
    with pytest.raises(InvalidParameterError, match=named):
        make()


def test_bad_arguments_of_the_energy_functions_name_the_argument():
    m = mech.CrankSlider(0.08, 0.3)
    sol = m.solve(_phi(), omega=10.0)
    masses = {"crank": energy.LinkMass(1.0)}
    cases = [
        (lambda: energy.kinetic_energy(sol, None), "masses"),
        (lambda: energy.kinetic_energy(sol, {"crank": 1.0}), "masses"),
        (lambda: energy.kinetic_energy("solution", masses), "solution"),
        (lambda: energy.potential_energy(sol, masses, gravity="down"), "gravity"),
        (lambda: energy.potential_energy(sol, masses, springs=energy.Spring("B", 0j, 1.0)), "springs"),
        (lambda: energy.applied_power(sol, energy.Force("B", 1.0)), "loads"),
        (lambda: energy.load_values("load", sol), "load"),
        (lambda: energy.load_values(energy.Force("B", lambda s: "x"), sol), "the force on 'B'"),
        (lambda: energy.load_values(energy.Force("B", lambda s: np.ones(3)), sol), "the force on 'B'"),
        (lambda: energy.load_values(energy.Torque("crank", np.ones(4)), sol), "the torque on 'crank'"),
        (lambda: energy.body_point(sol, "B", along="x"), "along"),
        (lambda: energy.body_point(sol, ["B"]), "body"),
        (lambda: energy.centre_of_mass(sol, "crank", 1.0), "properties"),
        (lambda: energy.reduced_inertia("crank-slider", masses, _phi()), "mechanism"),
        (lambda: energy.energy_balance(sol, masses, drive="motor"), "drive"),
        (lambda: energy.energy_balance(sol, masses, drive=np.ones(5)), "drive"),
    ]
    for call, named in cases:
        with pytest.raises(InvalidParameterError, match=named):
            call()


def test_an_unknown_body_is_a_lookup_error_naming_the_bodies():
    sol = mech.CrankSlider(0.08, 0.3).solve(_phi())
    with pytest.raises(mech.UnknownNameError, match="rocker.*known: crank, coupler"):
        energy.body_point(sol, "rocker")


# --- issue 29: the bodies of a linkage file, named for this module ----------------------------------------------

def test_linkage_masses_name_blocks_by_their_joint_and_merge_two_blocks_of_one_joint():
    from mechanisms.linkages.linkage_file import linkage_from_dict
    data = {"frame": {"O": [0.0, 0.0], "C": [0.0, -0.4]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
            "dyad": [{"type": "RPR", "block": "A", "pivot": "C", "links": ["block", "lever"]},
                     {"type": "PRP", "joint": "K", "guides": [{"through": [0.0, 0.3], "angle_deg": 0.0},
                                                              {"through": [0.2, 0.0], "angle_deg": 90.0}]}],
            "mass": [{"body": "A", "mass": 1.0, "inertia": 0.5}, {"body": "K1", "mass": 1.0, "along": 0.1},
                     {"body": "K2", "mass": 3.0, "left": 0.2}],
            "load": [{"body": "K2", "force": [1.0, 2.0]}, {"body": "A", "torque": 3.0}]}
    linkage = linkage_from_dict(data)
    masses = energy.linkage_masses(linkage)
    # the block on A turns with the lever: named by its link, so that its inertia counts
    assert masses["block"] == energy.LinkMass(1.0, 0.0, 0.0, 0.5)
    # K1 and K2 translate with K: one body of 4 kg, its centre the mass-weighted mean (1·0.1 + 3·0)/4, (1·0 + 3·0.2)/4
    assert masses["K"].mass == 4.0
    assert masses["K"].along == pytest.approx(0.025, rel=1e-15) and masses["K"].left == pytest.approx(0.15, rel=1e-15)
    loads = energy.linkage_loads(linkage)
    assert [(type(load).__name__, load.body) for load in loads] == [("Force", "K"), ("Torque", "block")]
