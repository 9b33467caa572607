"""Zhukovsky's lever (kinetostatics.zhukovsky_torque): the balancing torque from the velocity plan turned by 90°.

Every expected value comes from another route: statics by hand, or the power balance of
:func:`mechanisms.analysis.energy.driving_torque` (kinetic and potential energy rates from the
solution, no plan), and the group-by-group forces of :func:`~mechanisms.analysis.kinetostatics.joint_forces`.
"""

import math
import pathlib

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import energy, kinetostatics, plans
from mechanisms.core.errors import InvalidParameterError, UnknownNameError

ROOT = pathlib.Path(__file__).resolve().parent.parent
PRESS = ROOT / "book" / "course-project.toml"   # the six-bar press of chapter 11, with its masses
CENTRES = {"coupler": "S2", "rocker": "S3", "rod": "S4"}


def test_crank_pushed_at_its_pin_by_hand():
    # A crank of 1 m at φ = 90°, ω₁ = 1 1/s, F = −10 N along x at A = (0, 1): F's moment about O is
    # (0, 1) × (−10, 0) = +10 N·m, so the frame must hold the crank with M_d = −10 N·m (statics by hand).
    bar = mech.FourBar(crank=1.0, coupler=3.5, rocker=3.0, frame=(4.0, 0.0))
    solution = bar.solve([math.pi / 2], omega=1.0)
    lever = kinetostatics.zhukovsky_torque(plans.velocity_plan(bar, solution), {"A": -10.0})
    assert lever.torque == pytest.approx(-10.0, rel=1e-12)
    # the image of A on the plan turned by +90°: i v_A = i (−1) = −i m/s (v_A = iω₁·i = −1 by hand)
    assert lever.images["A"] == pytest.approx(-1j, abs=1e-12)


@pytest.mark.parametrize("degrees", [15.0, 100.0, 250.0])
def test_torque_on_the_rocker_against_the_power_balance(degrees):
    # Only a torque M₃ = 5 N·m on the rocker: M_d = −M₃ ω₃/ω₁, from energy.driving_torque (no masses)
    bar = mech.FourBar(crank=0.1, coupler=0.35, rocker=0.3, frame=(0.4, 0.0))
    solution = bar.solve(np.radians([degrees]), omega=7.0)
    expected = energy.driving_torque(solution, {}, [energy.Torque("rocker", 5.0)])[0]
    lever = kinetostatics.zhukovsky_torque(plans.velocity_plan(bar, solution), {}, {"rocker": 5.0})
    assert lever.torque == pytest.approx(expected, rel=1e-12)
    assert lever.couples["rocker"] == pytest.approx(-5.0 * solution.angle("rocker").omega[0], rel=1e-12)


@pytest.fixture(scope="module")
def press():
    return mech.load_linkage(PRESS)


def test_press_with_inertia_weights_and_load_against_power_balance_and_joint_forces(press):
    # The six-bar press of chapter 11 at 12 positions, crank accelerating: inertia forces and moments,
    # weights and a 2 kN load on the ram. Expected: the power balance and the group-by-group forces.
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    solution = press.solve(phi, omega=10.0, alpha=3.0)
    masses = energy.linkage_masses(press)          # the ram by its joint F, the links by name
    load = [energy.Force("F", 2000j)]
    g = press.gravity
    balance = energy.driving_torque(solution, masses, load, gravity=g)
    groups = kinetostatics.joint_forces(press, solution, masses, load, gravity=g).driving_torque
    inertia = energy.inertia_forces(solution, masses)
    points = {CENTRES[name]: (name, masses[name].along, masses[name].left) for name in CENTRES}
    scale = np.abs(balance).max()
    for k in range(len(phi)):
        plan = plans.velocity_plan(press, solution, index=k, points=points)
        forces = {CENTRES.get(name, "O" if name == "crank" else name):
                  inertia[name].force[k] - 1j * masses[name].mass * g for name in masses}
        forces["F"] += 2000j
        torques = {name: inertia[name].moment[k] for name in masses if name != "F"}
        lever = kinetostatics.zhukovsky_torque(plan, forces, torques)
        assert abs(lever.torque - balance[k]) < 1e-10 * scale
        assert abs(lever.torque - groups[k]) < 1e-10 * scale
        # each force's moment on the lever is −F · v at its point (the velocity from the solution)
        v_F = solution.point("F").velocity[k]
        assert lever.moments["F"] == pytest.approx(-(forces["F"].conjugate() * v_F).real, rel=1e-12)


def test_bad_inputs_are_the_package_errors(press):
    solution = press.solve(np.radians([120.0]), omega=10.0)
    plan = plans.velocity_plan(press, solution)
    with pytest.raises(UnknownNameError, match="'S9'.*known: O, A"):
        kinetostatics.zhukovsky_torque(plan, {"S9": 1.0})
    with pytest.raises(InvalidParameterError, match=r"forces\['F'\]"):
        kinetostatics.zhukovsky_torque(plan, {"F": complex("nan")})
    with pytest.raises(InvalidParameterError, match=r"forces\['F'\]"):
        kinetostatics.zhukovsky_torque(plan, {"F": "2000"})
    with pytest.raises(InvalidParameterError, match=r"torques\['rod'\]"):
        kinetostatics.zhukovsky_torque(plan, {}, {"rod": math.inf})
    with pytest.raises(UnknownNameError, match="'lever'"):
        kinetostatics.zhukovsky_torque(plan, {}, {"lever": 1.0})
    with pytest.raises(UnknownNameError, match="'shaft'"):
        kinetostatics.zhukovsky_torque(plan, {}, crank="shaft")
    with pytest.raises(InvalidParameterError, match="velocity plan"):
        kinetostatics.zhukovsky_torque(plans.acceleration_plan(press, solution, velocity=plan), {})
    with pytest.raises(InvalidParameterError, match="forces"):
        kinetostatics.zhukovsky_torque(plan, [("F", 1.0)])
