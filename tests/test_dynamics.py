"""Tests of mechanisms.analysis.dynamics: the equation of motion with J_red, its integration,
the speed fluctuation and the flywheel estimate (chapter 7).

Expected values: conservation of energy by the exact motion, the closed-form motion of a single
rotating link under a constant torque, Newton–Euler joint forces (kinetostatics), hand
calculations.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import dynamics, energy, kinetostatics
from mechanisms.core.errors import InvalidParameterError

from strategies import crank_rockers, crank_slider_geometries, finite

CRANK_SLIDER = mech.CrankSlider(0.08, 0.3)
MASSES = {"crank": energy.LinkMass(1.5, 0.01, 0.0, 0.005),
          "coupler": energy.LinkMass(1.2, 0.09, 0.0, 1.2 * 0.09 * 0.21),
          "B": energy.LinkMass(1.0)}


def _total_energy(m, masses, run, gravity):
    sol = m.solve(run.phi, run.omega, order=1)
    return energy.kinetic_energy(sol, masses).value + energy.potential_energy(sol, masses, gravity).value


def _free_run_drift(steps_per_revolution, gravity=9.81):
    """Largest relative change of T + V over 3 revolutions of a free run at about 100 rad/s."""
    revolutions = 3
    run = dynamics.simulate(CRANK_SLIDER, MASSES, 0.0, duration=revolutions * 2 * math.pi / 100.0,
                            steps=revolutions * steps_per_revolution, omega0=100.0, gravity=gravity)
    total = _total_energy(CRANK_SLIDER, MASSES, run, gravity)
    return np.abs(total - total[0]).max() / abs(total[0])


def test_free_run_conserves_energy_within_the_stated_error():
    # no driving torque, no load: the exact motion keeps T + V constant (docstring: < 1e-7 at
    # 200 steps per revolution over 3 revolutions, about 16 times less per halving of the step)
    coarse, fine = _free_run_drift(200), _free_run_drift(400)
    assert coarse < 1e-7
    assert 10.0 < coarse / fine < 25.0   # fourth order: 2⁴ = 16


def test_free_four_bar_run_conserves_kinetic_energy_without_gravity():
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.0))
    masses = {"crank": energy.LinkMass(1.0, 0.05, 0.0, 0.002), "coupler": energy.LinkMass(1.0, 0.175, 0.02, 0.01),
              "rocker": energy.LinkMass(1.0, 0.15, 0.0, 0.0075)}
    run = dynamics.simulate(m, masses, 0.0, duration=2 * 2 * math.pi / 20.0, steps=800, omega0=20.0, gravity=0.0)
    total = _total_energy(m, masses, run, 0.0)
    assert np.abs(total - total[0]).max() <= 1e-7 * total[0]
    assert run.omega.std() > 0.05 * abs(run.omega.mean())   # the speed does vary: J_red is not constant


def test_single_link_under_constant_torque_follows_the_closed_form():
    # only a balanced crank with J = 0.02 kg m²: φ = φ0 + ω0 t + (M/J) t²/2, a polynomial of degree 2,
    # which RK4 integrates exactly (up to round-off)
    masses = {"crank": energy.LinkMass(2.0, inertia=0.02)}
    run = dynamics.simulate(CRANK_SLIDER, masses, 3.0, duration=0.5, steps=50, phi0=0.3, omega0=-4.0, gravity=9.81)
    t = run.t
    assert np.allclose(run.phi, 0.3 - 4.0 * t + 0.5 * (3.0 / 0.02) * t**2, rtol=0, atol=1e-11)
    assert np.allclose(run.omega, -4.0 + (3.0 / 0.02) * t, rtol=0, atol=1e-10)


def test_several_runs_side_by_side_equal_separate_runs():
    # flywheels as an array: each column must be the run with that flywheel alone
    drive = lambda t, p, w: 40.0 * (1.0 - w / 60.0)  # noqa: E731  (a motor: 40 N m at rest, 60 rad/s idle)
    together = dynamics.simulate(CRANK_SLIDER, MASSES, drive, duration=0.2, steps=80, flywheel=[0.0, 0.05])
    alone = dynamics.simulate(CRANK_SLIDER, MASSES, drive, duration=0.2, steps=80, flywheel=0.05)
    assert together.omega.shape == (81, 2)
    assert np.allclose(together.omega[:, 1], alone.omega, rtol=1e-14, atol=0)
    assert together.omega[-1, 1] < together.omega[-1, 0]   # the heavier one runs up more slowly


@st.composite
def cases(draw):
    if draw(st.booleans()):
        crank, rod, offset = draw(crank_slider_geometries())
        m = mech.CrankSlider(crank, rod, offset)
        masses = {"crank": energy.LinkMass(1.0, 0.3 * crank, 0.1 * crank, 0.01),
                  "coupler": energy.LinkMass(2.0, 0.4 * rod, 0.0, 0.02), "B": energy.LinkMass(1.5)}
        loads = [energy.Force("B", -200.0 + 30j)]
    else:
        crank, coupler, rocker, frame, branch = draw(crank_rockers())
        m = mech.FourBar(crank, coupler, rocker, frame, branch)
        masses = {"crank": energy.LinkMass(1.0, 0.5 * crank, 0.0, 0.01),
                  "coupler": energy.LinkMass(2.0, 0.5 * coupler, 0.1, 0.05),
                  "rocker": energy.LinkMass(1.5, 0.5 * rocker, 0.0, 0.03)}
        loads = [energy.Torque("rocker", -20.0)]
    return m, masses, loads


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases(), st.floats(-30.0, 30.0, **finite), st.floats(-100.0, 100.0, **finite))
def test_lagrange_driving_torque_equals_newton_euler(case, omega, alpha):
    # J_red φ_tt + ½ J_red' φ_t² + M_c against the joint forces; φ_t = 0 (start from rest) included
    m, masses, loads = case
    phi = np.linspace(0.0, 2 * np.pi, 9, endpoint=False)
    torque = dynamics.required_torque(m, masses, phi, omega, alpha, loads)
    newton_euler = kinetostatics.joint_forces(m, m.solve(phi, omega, alpha), masses, loads).driving_torque
    assert np.abs(torque - newton_euler).max() <= 1e-9 * (np.abs(newton_euler).max() + 1.0)
    # and the acceleration that this torque gives back is φ_tt
    back = dynamics.angular_acceleration(m, masses, phi, omega, torque, loads=loads)
    assert np.allclose(back, alpha, rtol=0, atol=1e-8 * (abs(alpha) + 1.0))


def test_speed_fluctuation_of_a_given_run_by_hand():
    # ω = 100 + 5 sin(φ) over three revolutions: ω_max 105, ω_min 95, ω_m 100, δ = 0.1
    phi = np.linspace(0.0, 6 * math.pi, 3601)
    run = dynamics.Run(phi / 100.0, phi, 100.0 + 5.0 * np.sin(phi))
    f = dynamics.speed_fluctuation(run)
    assert (f.maximum, f.minimum, f.mean) == pytest.approx((105.0, 95.0, 100.0), abs=1e-5)
    assert f.coefficient == pytest.approx(0.1, abs=1e-7)
    with pytest.raises(InvalidParameterError):
        dynamics.speed_fluctuation(run, revolutions=4)


def test_energy_swing_by_hand():
    # M = M0 sin φ over a revolution: W = M0 (1 − cos φ), from 0 to 2 M0
    phi = np.linspace(0.0, 2 * math.pi, 2001)
    assert dynamics.energy_swing(phi, 3.0 * np.sin(phi)) == pytest.approx(6.0, rel=1e-6)
    # a constant part is removed (the driving torque that balances the resistance)
    assert dynamics.energy_swing(phi, 3.0 * np.sin(phi) - 7.0) == pytest.approx(6.0, rel=1e-6)
    # J = ΔE/(δ ω_m²): 6 J at 100 rad/s and δ = 0.01 need 0.06 kg m²
    assert dynamics.flywheel_inertia(6.0, 100.0, 0.01) == pytest.approx(0.06, rel=1e-14)


def test_flywheel_estimate_agrees_with_simulation():
    # a heavy flywheel and a constant driving torque equal to the mean resistance: the simulated δ
    # must agree with ΔE/(J ω_m²) when the swing includes the variable inertia at the mean speed
    load = energy.Force("B", lambda s: np.where(s.point("B").velocity.real < 0, 2000.0, 0.0))
    phi = np.linspace(0.0, 2 * math.pi, 721)
    model = dynamics.reduced_model(CRANK_SLIDER, MASSES, phi, [load])
    mean = model.resistance[:-1].mean()   # trapezoid rule over the period (both ends in phi)
    flywheel = 0.5
    run = dynamics.simulate(CRANK_SLIDER, MASSES, mean, duration=4 * 2 * math.pi / 215.0, steps=400,
                            omega0=215.0, loads=[load], flywheel=flywheel)
    f = dynamics.speed_fluctuation(run, revolutions=2)
    swing = dynamics.energy_swing(phi, mean - model.resistance - 0.5 * model.slope * f.mean**2)
    estimate = swing / ((flywheel + model.inertia.mean()) * f.mean**2)
    assert f.coefficient == pytest.approx(estimate, rel=0.03)


def test_bad_simulation_input_raises():
    with pytest.raises(InvalidParameterError, match="duration"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1.0, duration=-1.0, steps=10)
    with pytest.raises(InvalidParameterError, match="steps"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1.0, duration=1.0, steps=0)


def test_bad_flywheel_input_names_the_parameter():
    with pytest.raises(InvalidParameterError, match="torque"):
        dynamics.energy_swing([0.0, 1.0, 2.0], [1.0, 2.0])            # one torque missing
    with pytest.raises(InvalidParameterError, match="torque must be finite"):
        dynamics.energy_swing([0.0, 1.0, 2.0], [1.0, np.nan, 2.0])
    with pytest.raises(InvalidParameterError, match="phi"):
        dynamics.energy_swing([0.0, 2.0, 1.0], [1.0, 2.0, 3.0])       # not increasing
    with pytest.raises(InvalidParameterError, match="torque"):
        dynamics.energy_swing([0.0], [1.0])                             # no period at all
    with pytest.raises(InvalidParameterError, match="mean_speed"):
        dynamics.flywheel_inertia(10.0, -5.0, 0.02)
    with pytest.raises(InvalidParameterError, match="coefficient"):
        dynamics.flywheel_inertia(10.0, 5.0, 0.0)
    with pytest.raises(InvalidParameterError, match="swing"):
        dynamics.flywheel_inertia(np.nan, 5.0, 0.02)
    # by hand: J = ΔE/(δ ω_m²) = 10/(0.02·25) = 20 kg·m²
    assert dynamics.flywheel_inertia(10.0, 5.0, 0.02) == pytest.approx(20.0)


# --- issue 28: every input a right answer or the package's error -------------------------------------------

def test_a_negative_flywheel_is_refused_by_name():
    with pytest.raises(InvalidParameterError, match="flywheel"):
        dynamics.reduced_model(CRANK_SLIDER, MASSES, [0.0, 1.0], flywheel=-10.0)
    with pytest.raises(InvalidParameterError, match="flywheel"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1.0, duration=0.1, steps=2, flywheel=[0.1, -1.0])


def test_zero_revolutions_is_refused_by_name():
    phi = np.linspace(0.0, 6 * math.pi, 601)
    run = dynamics.Run(phi / 100.0, phi, 100.0 + 5.0 * np.sin(phi))
    for bad in (0, -1, 1.5, "one", None, True, np.nan):
        with pytest.raises(InvalidParameterError, match="revolutions"):
            dynamics.speed_fluctuation(run, revolutions=bad)


def test_a_clockwise_run_has_the_fluctuation_of_its_mirror_image():
    # by hand: the mirror image of ω = 100 + 5 sin φ (counter-clockwise) is φ → −φ, ω → −ω. Its speed |ω| takes the
    # same values, 95 … 105, so δ = (105 − 95)/100 = 0.1 again; in the run's sense ω_max = −105 (the fastest),
    # ω_min = −95, ω_m = −100, and (ω_max − ω_min)/ω_m = (−10)/(−100) = 0.1.
    phi = np.linspace(0.0, 6 * math.pi, 3601)
    mirrored = dynamics.Run(phi / 100.0, -phi, -(100.0 + 5.0 * np.sin(phi)))
    f = dynamics.speed_fluctuation(mirrored, revolutions=2)
    assert (f.maximum, f.minimum, f.mean) == pytest.approx((-105.0, -95.0, -100.0), abs=1e-5)
    assert f.coefficient == pytest.approx(0.1, abs=1e-7)


def test_a_simulated_clockwise_run_mirrors_the_counter_clockwise_one():
    # the axial crank-slider without gravity is symmetric about the x axis: J_red(−φ) = J_red(φ) and
    # J_red'(−φ) = −J_red'(φ), so J φ_tt + ½ J' φ_t² = M_d is unchanged by φ → −φ, M_d → −M_d. The clockwise run
    # is the mirror image of the counter-clockwise one, and its δ the same.
    drive = 3.0
    ccw = dynamics.simulate(CRANK_SLIDER, MASSES, drive, duration=0.25, steps=250, omega0=60.0, gravity=0.0)
    cw = dynamics.simulate(CRANK_SLIDER, MASSES, -drive, duration=0.25, steps=250, omega0=-60.0, gravity=0.0)
    assert np.allclose(cw.omega, -ccw.omega, rtol=1e-12, atol=0)
    a, b = dynamics.speed_fluctuation(ccw), dynamics.speed_fluctuation(cw)
    assert b.coefficient == pytest.approx(a.coefficient, rel=1e-9)
    assert a.coefficient > 0.01                      # the speed does fluctuate
    assert (b.maximum, b.minimum, b.mean) == pytest.approx((-a.maximum, -a.minimum, -a.mean), rel=1e-9)


def test_a_run_whose_crank_turns_back_has_no_fluctuation_coefficient():
    t = np.linspace(0.0, 10.0, 2001)
    phi = 10.0 * t + 3.0 * np.sin(5.0 * t)          # φ_t = 10 + 15 cos 5t < 0 at times: it turns back
    with pytest.raises(InvalidParameterError, match="run"):
        dynamics.speed_fluctuation(dynamics.Run(t, phi, 10.0 + 15.0 * np.cos(5.0 * t)))
    with pytest.raises(InvalidParameterError, match="run"):
        dynamics.speed_fluctuation("a run")
    with pytest.raises(InvalidParameterError, match="run.omega"):
        dynamics.speed_fluctuation(dynamics.Run(t, phi, np.full_like(t, np.nan)))


@pytest.mark.parametrize("keyword, value", [
    ("steps", "ten"), ("steps", None), ("steps", True), ("steps", 2.5), ("steps", 0), ("steps", -3),
    ("steps", np.nan), ("steps", 1e12), ("steps", [10]), ("duration", "1"), ("duration", np.inf),
    ("duration", 0.0), ("duration", None), ("phi0", np.nan), ("phi0", "0"), ("omega0", 1e300), ("omega0", "fast"),
    ("flywheel", "heavy"), ("flywheel", np.inf), ("gravity", "down"), ("gravity", np.nan), ("loads", "none"),
    ("loads", [1.0]), ("springs", [None]), ("masses", None), ("masses", {"crank": 1.0}), ("drive", "motor"),
    ("drive", np.nan), ("drive", [1.0, 2.0, 3.0]), ("mechanism", "crank-slider"),
])
def test_bad_simulation_input_names_the_parameter(keyword, value):
    arguments = dict(mechanism=CRANK_SLIDER, masses=MASSES, drive=1.0, duration=0.01, steps=3)
    arguments[keyword] = value
    with pytest.raises(InvalidParameterError, match=keyword):
        dynamics.simulate(**arguments)


def test_a_huge_number_of_steps_is_refused_before_any_allocation():
    # 1e12 steps would be 16 TB of states; with 4 runs side by side the bound is on the states kept in all
    with pytest.raises(InvalidParameterError, match="steps"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1.0, duration=1.0, steps=10**12)
    with pytest.raises(InvalidParameterError, match="steps"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1.0, duration=1.0, steps=dynamics.MAX_SAMPLES // 2,
                          flywheel=[0.0, 0.1, 0.2, 0.3])


def test_a_motion_that_runs_away_is_an_error_not_nan():
    with pytest.raises(mech.MechanismError, match="unbounded"):
        dynamics.simulate(CRANK_SLIDER, MASSES, 1e300, duration=1.0, steps=4)


def test_no_inertia_is_refused_where_the_motion_is_undetermined():
    # only the slider has mass: J_red = m (ds/dφ)² = 0 at the dead centres φ = 0, π (by hand)
    with pytest.raises(InvalidParameterError, match="J_red = 0"):
        dynamics.angular_acceleration(CRANK_SLIDER, {"B": energy.LinkMass(1.0)}, [0.0, 1.0], 10.0, 1.0)


@pytest.mark.parametrize("function, keyword, value", [
    ("required_torque", "omega", "fast"), ("required_torque", "omega", [1.0, 2.0, 3.0]),
    ("required_torque", "alpha", None), ("required_torque", "omega", 1e300), ("required_torque", "flywheel", -1.0),
    ("angular_acceleration", "omega", "fast"), ("angular_acceleration", "drive", "motor"),
    ("angular_acceleration", "t", "now"), ("reduced_model", "phi", "zero"), ("reduced_model", "masses", [1.0]),
    ("reduced_model", "gravity", "down"), ("reduced_model", "loads", [energy.LinkMass(1.0)]),
])
def test_bad_input_of_the_equation_of_motion_names_the_parameter(function, keyword, value):
    arguments = dict(mechanism=CRANK_SLIDER, masses=MASSES, phi=[0.0, 1.0])
    if function != "reduced_model":
        arguments["omega"] = 10.0
    if function == "angular_acceleration":
        arguments["drive"] = 1.0
    arguments[keyword] = value
    with pytest.raises(InvalidParameterError, match=keyword):
        getattr(dynamics, function)(**arguments)


def test_energy_swing_and_flywheel_beyond_the_numbers_are_refused():
    with pytest.raises(InvalidParameterError, match="torque"):
        dynamics.energy_swing([0.0, 1e300, 2e300], [1e308, 1e307, 1e308])   # work ~1e608 J
    with pytest.raises(InvalidParameterError, match="mean_speed"):
        dynamics.flywheel_inertia(1.0, 1e-200, 0.01)     # ω_m² underflows to 0
