"""Tests of mechanisms.analysis.kinetostatics: joint forces of the crank-slider and the four-bar
by Newton–Euler (chapter 7).

Expected values: the power balance of mechanisms.analysis.energy (an independent route to the
driving torque), the momentum and angular-momentum balance of the whole mechanism (which the
internal joint forces drop out of), and hand calculations of statics.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import energy, kinetostatics
from mechanisms.core.errors import InvalidParameterError, MechanismError

from strategies import crank_slider_with_masses, crank_speeds, finite, four_bar_with_masses

SETTINGS = dict(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])

forces = st.builds(complex, st.floats(-500, 500, **finite), st.floats(-500, 500, **finite))
torques = st.floats(-50.0, 50.0, **finite)


@st.composite
def crank_slider_cases(draw):
    m, masses = draw(crank_slider_with_masses())
    rod = m.rod
    loads = [energy.Force("B", draw(forces)), energy.Force("coupler", draw(forces), 0.3 * rod, 0.1 * rod),
             energy.Torque("coupler", draw(torques))]
    springs = [energy.Spring("coupler", complex(rod, rod), 100.0, 0.5 * rod, along=0.5 * rod)]
    return m, masses, loads, springs


@st.composite
def four_bar_cases(draw):
    m, masses = draw(four_bar_with_masses())
    coupler, rocker = m.coupler, m.rocker
    loads = [energy.Torque("rocker", draw(torques)), energy.Force("coupler", draw(forces), 0.5 * coupler, 0.2),
             energy.Force("rocker", draw(forces), rocker)]
    springs = [energy.Spring("rocker", complex(*m.frame) + 1j * rocker, 100.0, 0.2, along=0.5 * rocker)]
    return m, masses, loads, springs


cases = st.one_of(crank_slider_cases(), four_bar_cases())
speeds = crank_speeds


def _phi(count=12):
    return np.linspace(0.2, 0.2 + 2 * np.pi, count, endpoint=False)


def _cross(a, b):
    return np.imag(np.conj(a) * b)


@settings(**SETTINGS)
@given(cases, speeds, st.floats(-50.0, 50.0, **finite), st.floats(0.0, 12.0, **finite))
def test_newton_euler_driving_torque_equals_power_balance(case, omega, alpha, gravity):
    m, masses, loads, springs = case
    sol = m.solve(_phi(), omega, alpha)
    result = kinetostatics.joint_forces(m, sol, masses, loads, gravity, springs)
    # independent route: M_d = (dT/dt + dV/dt − P_loads)/φ_t
    expected = energy.driving_torque(sol, masses, loads, gravity, springs)
    scale = np.abs(expected).max() + 1.0
    assert np.abs(result.driving_torque - expected).max() <= 1e-9 * scale
    # and so the energy balance closes with the Newton–Euler torque
    residual = energy.energy_balance(sol, masses, result.driving_torque, loads, gravity, springs)
    assert np.abs(residual).max() <= 1e-9 * scale * abs(omega)


@settings(**SETTINGS)
@given(cases, speeds, st.floats(-50.0, 50.0, **finite))
def test_whole_mechanism_momentum_and_angular_momentum_balance(case, omega, alpha):
    # the internal joint forces cancel: the frame's reactions, the loads, the weights and the
    # springs make the total force Σ m a_S and the total moment about O Σ (r_S × m a_S + J_S α)
    m, masses, loads, springs = case
    g = 9.81
    sol = m.solve(_phi(), omega, alpha)
    result = kinetostatics.joint_forces(m, sol, masses, loads, g, springs)
    external = {"O": (0j, result.force("O"))}
    if isinstance(m, mech.FourBar):
        external["C"] = (m.pivot, result.force("C"))
    else:
        external["guide"] = (sol.point("B").value, result.force("guide"))
    total_force = sum(f for _, f in external.values())
    total_moment = sum(_cross(p, f) for p, f in external.values()) + result.driving_torque
    for body, props in masses.items():
        centre = energy.centre_of_mass(sol, body, props)
        weight = -1j * props.mass * g
        total_force = total_force + weight - props.mass * centre.acceleration
        total_moment = total_moment + _cross(centre.value, weight - props.mass * centre.acceleration)
        if body != "B":
            total_moment = total_moment - props.inertia * sol.angle(body).alpha
    for load in loads:
        if isinstance(load, energy.Force):
            point = energy.body_point(sol, load.body, load.along, load.left).value
            total_force = total_force + load.force
            total_moment = total_moment + _cross(point, np.broadcast_to(load.force, point.shape))
        else:
            total_moment = total_moment + load.torque
    for spring in springs:
        point = energy.body_point(sol, spring.body, spring.along, spring.left).value
        total_force = total_force + spring.force(sol)
        total_moment = total_moment + _cross(point, spring.force(sol))
    scale = sum(np.abs(f).max() for _, f in external.values()) + np.abs(result.driving_torque).max() + 1.0
    assert np.abs(total_force).max() <= 1e-9 * scale
    assert np.abs(total_moment).max() <= 1e-9 * scale * (1.0 + max(np.abs(p).max() for p, _ in external.values()))


@pytest.mark.parametrize("phi_deg", [30.0, 90.0, 135.0, 250.0])
def test_static_crank_slider_by_hand(phi_deg):
    # massless links at rest, a force of P = 1000 N along −x (towards the crank) on the slider.
    # Hand statics: the coupler is a two-force member, its force on the slider c·exp(iψ) balances
    # P along x, so c = P/cos ψ; the guide takes −c sin ψ; the crank needs
    # M_d = A × R_A = L1 c sin(ψ − φ) = −P L1 sin(φ − ψ)/cos ψ.
    m = mech.CrankSlider(0.1, 0.35, 0.02)
    sol = m.solve(np.radians([phi_deg]), omega=0.0, alpha=0.0)
    P = 1000.0  # magnitude, acting along −x
    result = kinetostatics.joint_forces(m, sol, {}, [energy.Force("B", -P)], gravity=9.81)
    phi, psi = math.radians(phi_deg), sol.angle("coupler").angle[0]
    assert result.driving_torque[0] == pytest.approx(-P * 0.1 * math.sin(phi - psi) / math.cos(psi), rel=1e-12)
    c = P / math.cos(psi)
    assert result.force("B")[0] == pytest.approx(c * complex(math.cos(psi), math.sin(psi)), rel=1e-12)
    assert result.force("guide")[0] == pytest.approx(-1j * c * math.sin(psi), abs=1e-9)
    assert result.force("A")[0] == pytest.approx(result.force("B")[0], rel=1e-12)
    assert result.force("O")[0] == pytest.approx(result.force("A")[0], rel=1e-12)


def test_massless_four_bar_coupler_is_a_two_force_member():
    # with loads only on the rocker, the coupler's joint forces are equal and along A–B
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.0))
    masses = {"crank": energy.LinkMass(2.0, 0.05, 0.0, 0.003), "rocker": energy.LinkMass(1.0, 0.15, 0.0, 0.008)}
    sol = m.solve(_phi(), omega=20.0, alpha=5.0)
    result = kinetostatics.joint_forces(m, sol, masses, [energy.Torque("rocker", -8.0)])
    A, B = result.force("A"), result.force("B")
    assert np.allclose(A, B, rtol=0, atol=1e-10 * np.abs(A).max())
    along = sol.point("B").value - sol.point("A").value
    assert np.abs(_cross(along / np.abs(along), A)).max() <= 1e-10 * np.abs(A).max()


def test_weight_of_a_balanced_crank_goes_to_its_pivot():
    # only a crank with its centre of mass on the axis, turning uniformly: R_O carries its weight, M_d = 0
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.0))
    sol = m.solve(_phi(), omega=15.0)
    result = kinetostatics.joint_forces(m, sol, {"crank": energy.LinkMass(3.0, inertia=0.01)}, gravity=9.81)
    assert np.allclose(result.force("O"), 3.0j * 9.81, atol=1e-12)
    assert np.allclose(result.driving_torque, 0.0, atol=1e-12)
    assert np.allclose(result.force("C"), 0.0, atol=1e-12)


def test_singular_positions_give_nan_and_bad_input_raises():
    # a change-point four-bar (parallelogram) has singular positions at φ = 0 and π
    m = mech.FourBar(0.1, 0.4, 0.1, (0.4, 0.0))
    with pytest.warns(mech.SingularPositionWarning):
        sol = m.solve(np.array([0.0, 1.0]), omega=1.0)
    result = kinetostatics.joint_forces(m, sol, {"crank": energy.LinkMass(1.0)})
    assert np.isnan(result.driving_torque[0]) and np.isfinite(result.driving_torque[1])
    slider = mech.CrankSlider(0.08, 0.3)
    with pytest.raises(InvalidParameterError, match="rocker"):
        kinetostatics.joint_forces(slider, slider.solve(_phi()), {"rocker": energy.LinkMass(1.0)})
    with pytest.raises(InvalidParameterError, match="body"):
        kinetostatics.joint_forces(slider, slider.solve(_phi()), {}, [energy.Torque("rocker", 1.0)])
    with pytest.raises(MechanismError, match="order=2"):
        kinetostatics.joint_forces(slider, slider.solve(_phi(), order=1), {})
    lam = mech.LambdaMechanism(2.0, 2.5, 2.0)
    with pytest.raises(InvalidParameterError, match="describes its structure"):
        kinetostatics.joint_forces(lam, lam.solve(_phi()), {})


# --- issue 28: bad input is the package's error naming it ---------------------------------------------------

def test_bad_arguments_of_joint_forces_name_the_argument():
    m = mech.CrankSlider(0.08, 0.3)
    sol = m.solve(np.linspace(0.0, 6.0, 7), omega=10.0)
    masses = {"crank": energy.LinkMass(1.0)}
    cases = [
        (lambda: kinetostatics.joint_forces("crank-slider", sol, masses), "mechanism"),
        (lambda: kinetostatics.joint_forces(m, None, masses), "solution"),
        (lambda: kinetostatics.joint_forces(m, sol, [1.0]), "masses"),
        (lambda: kinetostatics.joint_forces(m, sol, masses, loads=["push"]), r"loads\[0\]"),
        (lambda: kinetostatics.joint_forces(m, sol, masses, springs="none"), "springs"),
        (lambda: kinetostatics.joint_forces(m, sol, masses, gravity="down"), "gravity"),
        (lambda: kinetostatics.joint_forces(m, sol, masses, loads=[energy.Torque("rocker", 1.0)]), "body"),
    ]
    for call, named in cases:
        with pytest.raises(InvalidParameterError, match=named):
            call()
    with pytest.raises(mech.UnknownNameError, match="no joint named 'Z'"):
        kinetostatics.joint_forces(m, sol, masses).force("Z")
    with pytest.raises(mech.UnknownNameError, match="joint"):
        kinetostatics.joint_forces(m, sol, masses).force(["A"])
