"""Tests of mechanisms.analysis.plans: velocity and acceleration plans, images, instant centres.

The plans are built from the joint positions and the crank's motion only; every expected value
here comes from elsewhere: Table 5.5 of the textbook page (example 5.2), hand calculations, the
closed-form solutions of the mechanism classes and the generic Newton solver (mechanisms.verify).
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis import plans
from mechanisms.linkages import four_bar
from mechanisms.core.errors import InvalidParameterError
from strategies import crank_rockers, crank_slider_geometries, branches, finite, slotted_lever_geometries

EXAMPLE = mech.CrankSlider(crank=0.08, rod=0.3)          # example 5.2 of the textbook page
S2 = {"S2": ("coupler", 0.09, 0.0)}                        # l_BS2 = 0.09 m from the crank pin
FAST = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _example():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0)  # position 2 of the textbook: φ = 30°
    velocity = plans.velocity_plan(EXAMPLE, sol, points=S2)
    return sol, velocity, plans.acceleration_plan(EXAMPLE, sol, points=S2, velocity=velocity)


# --- the construction's geometry ----------------------------------------------------------------------

def test_meet_finds_the_intersection_of_two_lines():
    # by hand: the line y = 1 (through i, along 1) meets the line x = 2 (through 2, along i) at 2 + i
    point, t1, t2 = plans.meet(1j, 1.0, 2.0, 1j)
    assert point == pytest.approx(2 + 1j)
    assert (t1, t2) == pytest.approx((2.0, 1.0))


def test_meet_refuses_parallel_lines():
    with pytest.raises(plans.PlanError, match="parallel"):
        plans.meet(0j, 1 + 1j, 1.0, -2 - 2j)
    with pytest.raises(InvalidParameterError):
        plans.meet(0j, 0j, 1.0, 1j)


def test_image_is_the_similar_figure():
    # by hand: the link 0 → 1 is imaged on 0 → i (turned by 90°, same size), so 1 + i goes to i(1 + i)
    assert plans.image(0j, 1j, 0j, 1.0, 1 + 1j) == pytest.approx(-1 + 1j)
    # and a point on the link at a quarter of its length goes to a quarter of the image
    assert plans.image(2j, 6j, 1.0, 5.0, 2.0) == pytest.approx(3j)


@pytest.mark.parametrize("largest, mm, expected", [
    (17.2, 100.0, 0.2),      # the crank pin of example 5.2: 17.2/100 = 0.172 → 0.2 (m/s)/mm
    (4684.0, 100.0, 50.0),   # 46.84 → 50
    (25.0, 100.0, 0.25),     # exactly a course scale
    (0.9, 120.0, 0.01),      # 0.0075 → 0.01
])
def test_nice_scale_is_the_smallest_course_scale(largest, mm, expected):
    assert plans.nice_scale(largest, mm) == pytest.approx(expected)


def test_nice_scale_rejects_a_zero_vector():
    with pytest.raises(InvalidParameterError):
        plans.nice_scale(0.0)


# --- example 5.2 and Table 5.5 --------------------------------------------------------------------------

def test_plans_of_example_5_2_give_the_analytical_values_of_table_5_5():
    _, v, a = _example()
    # Table 5.5, "analytical" row, to the digits it prints (a_C = −3713.58 is printed truncated)
    assert v.rates["coupler"] == pytest.approx(-50.1, abs=0.05)
    assert a.rates["coupler"] == pytest.approx(5881.0, abs=0.5)
    assert v.of("B").real == pytest.approx(-10.6, abs=0.05)
    assert a.of("B").real == pytest.approx(-3713.0, abs=1.0)
    speed, direction = v.read("S2")
    assert speed == pytest.approx(13.91, abs=0.005)
    assert direction == pytest.approx(131.4, abs=0.05)
    magnitude, direction = a.read("S2")
    assert magnitude == pytest.approx(3597.0, abs=0.5)
    assert direction == pytest.approx(201.1, abs=0.05)


def test_velocity_of_the_slider_by_hand():
    _, v, _ = _example()
    # chapter 3, by hand: s_t = −0.08·215·0.5 − 0.3·sin(−7.662°)·(−50.10) = −10.60 m/s; v_A = ω1·L1 = 17.2 m/s
    assert v.of("B") == pytest.approx(-10.604, abs=1e-3)
    assert abs(v.of("A")) == pytest.approx(17.2, rel=1e-12)
    # ω2 = −ω1·L1·cos φ/(L2·cos ψ) with cos ψ = √(0.26·0.34)/0.3
    assert v.rates["coupler"] == pytest.approx(-215 * 0.08 * math.cos(math.radians(30)) / math.sqrt(0.26 * 0.34),
                                               rel=1e-12)
    # the normal acceleration of B about A by hand: ω2²·L2 along B → A
    assert abs(a_n := _example()[2].vector("a^n_BA").value) == pytest.approx(v.rates["coupler"] ** 2 * 0.3)
    assert a_n.real < 0   # from B towards A: to the left


def test_plans_of_example_5_2_against_the_generic_solver():
    sol, v, a = _example()
    generic = mech.verify.solve_generic(EXAMPLE, np.radians([30.0]), omega=215.0)   # Newton, exact derivatives
    assert v.rates["coupler"] == pytest.approx(generic.q_t[0, 0], rel=1e-10)
    assert a.rates["coupler"] == pytest.approx(generic.q_tt[0, 0], rel=1e-10)
    assert v.of("B").real == pytest.approx(generic.q_t[1, 0], rel=1e-10)
    assert a.of("B").real == pytest.approx(generic.q_tt[1, 0], rel=1e-10)
    assert abs(v.of("B").imag) < 1e-12 and abs(a.of("B").imag) < 1e-9  # along the guide


def test_lettering_and_scales_of_example_5_2():
    _, v, a = _example()
    assert v.pole == "p" and a.pole == "π"
    assert {"p", "a", "b", "s2"} <= set(v.vertices)
    assert {"π", "a′", "n2", "b′", "s2′"} <= set(a.vertices)
    assert [x.name for x in v.vectors] == ["v_A", "v_BA", "v_B", "v_S2"]
    assert {"a^n_BA", "a^t_BA"} <= {x.name for x in a.vectors}
    # longest vectors: 17.2 m/s and |a_A| = ω1²·L1 = 3698 m/s² → 0.2 (m/s)/mm and 50 (m/s²)/mm
    assert v.scale == 0.2 and a.scale == 50.0
    assert v.length_mm("v_A") == pytest.approx(17.2 / 0.2)


def test_reading_with_a_ruler_rounds_the_length_and_the_angle():
    _, v, _ = _example()
    exact, direction = v.read("S2")
    coarse, rounded = v.read("S2", resolution_mm=1.0, resolution_deg=1.0)
    assert abs(coarse - exact) <= 0.5 * v.scale + 1e-12      # half a millimetre at 0.2 (m/s)/mm
    assert coarse / v.scale == pytest.approx(round(coarse / v.scale))
    assert rounded == pytest.approx(round(direction))


def test_readings_and_vectors_have_named_fields():
    _, v, a = _example()
    reading = v.read("S2")
    assert reading.magnitude == reading[0] and reading.direction_deg == reading[1]
    # Table 5.5, analytical: v_S2 = 13.91 m/s at 131.4°
    assert reading.magnitude == pytest.approx(13.91, abs=0.01)
    assert reading.direction_deg == pytest.approx(131.4, abs=0.1)
    v_a = v.vector("v_A")
    assert v_a.magnitude == pytest.approx(17.2)                 # ω1·L1 = 215·0.08
    assert v_a.direction_deg == pytest.approx(120.0)            # ⊥ OA at 30°, counter-clockwise
    assert v.length_mm("S2") == pytest.approx(reading.magnitude / v.scale)   # a point's vector too
    assert a.length_mm("B") == pytest.approx(abs(a.of("B")) / a.scale)


def test_component_of_a_vector_along_a_direction():
    _, v, _ = _example()
    # the slider's velocity lies along the guide (+x): its component is v_B, across the guide 0
    assert v.component("B", along=2.0) == pytest.approx(v.of("B").real)
    assert v.component("B", along=1j) == pytest.approx(0.0, abs=1e-12)
    # v_A = 17.2 m/s at 120°: along 30° (OA) it has no component, along 120° all of it (hand)
    assert v.component("v_A", along=np.exp(1j * np.radians(30.0))) == pytest.approx(0.0, abs=1e-12)
    assert v.component("v_A", along=np.exp(1j * np.radians(120.0))) == pytest.approx(17.2)
    with pytest.raises(InvalidParameterError):
        v.component("v_A", along=0.0)


def test_given_scale_is_kept_and_bad_scales_are_refused():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0)
    v = plans.velocity_plan(EXAMPLE, sol, scale=0.25)
    assert v.scale == 0.25 and v.length_mm("v_A") == pytest.approx(17.2 / 0.25)
    with pytest.raises(InvalidParameterError, match="scale"):
        plans.velocity_plan(EXAMPLE, sol, scale=-1.0)


def test_bad_inputs_are_refused():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0, order=1)
    with pytest.raises(InvalidParameterError, match="order"):
        plans.acceleration_plan(EXAMPLE, sol)
    with pytest.raises(InvalidParameterError, match="order"):
        plans.velocity_plan(EXAMPLE, EXAMPLE.solve(np.radians([30.0]), order=0))
    with pytest.raises(InvalidParameterError, match="index"):
        plans.velocity_plan(EXAMPLE, sol, index=3)
    with pytest.raises(InvalidParameterError, match="LINK"):
        plans.velocity_plan(EXAMPLE, sol, points={"K": ("rocker", 0.1, 0.0)})
    two = EXAMPLE.solve(np.radians([30.0, 60.0]), omega=215.0)
    with pytest.raises(InvalidParameterError, match="same position"):
        plans.acceleration_plan(EXAMPLE, two, index=1, velocity=plans.velocity_plan(EXAMPLE, two, index=0))
    lam = mech.LambdaMechanism(2.0, 6.5, 5.0)              # Chebyshev's lambda: no plan in chapter 10
    with pytest.raises(InvalidParameterError, match="mechanism"):
        plans.velocity_plan(lam, lam.solve(np.radians([30.0])))
    with pytest.raises(InvalidParameterError, match="mechanism"):
        plans.instant_centres(lam, lam.solve(np.radians([30.0])))


# --- every mechanism, random geometries: closure and agreement with the closed form --------------------------

def _close(plan_value, exact, size):
    assert abs(plan_value - exact) <= 1e-9 * size


def _check_points(plan, sol, names, quantity):
    size = max(abs(x) for x in plan.vertices.values())
    for name in names:
        exact = getattr(sol.point(name), quantity)[0]
        _close(plan.of(name), exact, size)
    assert plan.closure() <= 1e-12 * size


@FAST
@given(crank_slider_geometries(), branches, st.floats(-np.pi, np.pi, **finite), st.floats(0.5, 50.0, **finite),
       st.floats(-100.0, 100.0, **finite), st.floats(-0.5, 1.5, **finite), st.floats(-0.5, 0.5, **finite))
def test_crank_slider_plans_equal_the_closed_form(geometry, branch, phi, omega, alpha, u, v):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    sol = m.solve(np.array([phi]), omega=omega, alpha=alpha)
    extra = {"K": ("coupler", u * rod, v * rod)}
    vp = plans.velocity_plan(m, sol, points=extra)
    ap = plans.acceleration_plan(m, sol, points=extra, velocity=vp)
    _check_points(vp, sol, ["A", "B"], "velocity")
    _check_points(ap, sol, ["A", "B"], "acceleration")
    k = sol.point_on("coupler", u * rod, v * rod)
    _close(vp.of("K"), k.velocity[0], abs(vp.of("A")) + abs(vp.of("B")))
    _close(ap.of("K"), k.acceleration[0], abs(ap.of("A")) + abs(ap.of("B")))
    coupler = sol.angle("coupler")
    assert vp.rates["coupler"] == pytest.approx(coupler.omega[0], rel=1e-9, abs=1e-9 * omega)
    assert ap.rates["coupler"] == pytest.approx(coupler.alpha[0], rel=1e-9, abs=1e-9 * (omega**2 + abs(alpha)))
    assert vp.similarity("coupler") < 1e-9 and ap.similarity("coupler") < 1e-9


@FAST
@given(crank_rockers(), st.floats(-np.pi, np.pi, **finite), st.floats(0.5, 50.0, **finite),
       st.floats(-100.0, 100.0, **finite))
def test_four_bar_plans_equal_the_closed_form(geometry, phi, omega, alpha):
    crank, coupler, rocker, frame, branch = geometry
    m = mech.FourBar(crank, coupler, rocker, frame, branch)
    sol = m.solve(np.array([phi]), omega=omega, alpha=alpha)
    psi, xi = sol.angle("coupler").value[0], sol.angle("rocker").value[0]
    assume(abs(math.sin(psi - xi)) > 0.05)                  # transmission angle away from 0 and 180°
    vp = plans.velocity_plan(m, sol)
    ap = plans.acceleration_plan(m, sol, velocity=vp)
    _check_points(vp, sol, ["A", "B"], "velocity")
    _check_points(ap, sol, ["A", "B"], "acceleration")
    # the lecture's Cramer's rule, a formula of its own, for the angular rates
    psi_t, xi_t, psi_tt, xi_tt = (float(x) for x in four_bar.cramer_rates(
        phi, psi, xi, crank, coupler, rocker, omega, alpha))
    scale_w, scale_e = omega * (1 + crank / coupler + crank / rocker), omega**2 + abs(alpha)
    assert vp.rates["coupler"] == pytest.approx(psi_t, abs=1e-7 * scale_w)
    assert vp.rates["rocker"] == pytest.approx(xi_t, abs=1e-7 * scale_w)
    assert ap.rates["coupler"] == pytest.approx(psi_tt, rel=1e-6, abs=1e-6 * scale_e)
    assert ap.rates["rocker"] == pytest.approx(xi_tt, rel=1e-6, abs=1e-6 * scale_e)


@FAST
@given(slotted_lever_geometries(), st.floats(-np.pi, np.pi, **finite), st.floats(0.5, 50.0, **finite),
       st.floats(-100.0, 100.0, **finite))
def test_slotted_lever_plans_equal_the_closed_form(geometry, phi, omega, alpha):
    crank, pivot = geometry
    m = mech.SlottedLever(crank, pivot)
    sol = m.solve(np.array([phi]), omega=omega, alpha=alpha)
    vp = plans.velocity_plan(m, sol)
    ap = plans.acceleration_plan(m, sol, velocity=vp)
    _check_points(vp, sol, ["A", "B"], "velocity")
    _check_points(ap, sol, ["A", "B"], "acceleration")
    lever, block = sol.angle("lever"), sol.slider("A")
    e = np.exp(1j * lever.value[0])
    size_v, size_a = omega * crank, omega**2 * crank + abs(alpha) * crank
    # the block A2 slides relative to the lever's point A3 under it: v_A2A3 = L_t·e (chapter 5's convention)
    _close(vp.vector("v_A2A3").value, block.velocity[0] * e, size_v)
    # its Coriolis and relative terms are chapter 5's, 2iω₃L_t·e and L_tt·e
    _close(ap.vector("a^k_A2A3").value, m.coriolis_vector(sol)[0], size_a)
    _close(ap.vector("a^r_A2A3").value, block.acceleration[0] * e, size_a)
    assert abs(vp.rates["lever"] - lever.omega[0]) <= 1e-9 * omega * (1 + crank / block.value[0])
    assert abs(ap.rates["lever"] - lever.alpha[0]) <= 1e-9 * size_a / block.value[0] * 10


def test_shaper_plans_equal_the_closed_form_and_the_generic_solver():
    m = mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22)   # chapter 5's shaper
    phi = np.radians(np.arange(5.0, 360.0, 30.0))
    sol = m.solve(phi, omega=10.0, alpha=2.0)
    generic = mech.verify.solve_generic(m, phi, omega=10.0, alpha=2.0)       # q = (ξ, L, ψ, x_G)
    for k in range(len(phi)):
        vp = plans.velocity_plan(m, sol, index=k)
        ap = plans.acceleration_plan(m, sol, index=k, velocity=vp)
        assert vp.closure() < 1e-12 and ap.closure() < 1e-10
        assert vp.rates["lever"] == pytest.approx(generic.q_t[0, k], rel=1e-9, abs=1e-10)
        assert vp.rates["rod"] == pytest.approx(generic.q_t[2, k], rel=1e-9, abs=1e-10)
        assert vp.of("G").real == pytest.approx(generic.q_t[3, k], rel=1e-9, abs=1e-10)
        assert ap.rates["lever"] == pytest.approx(generic.q_tt[0, k], rel=1e-8, abs=1e-8)
        assert ap.rates["rod"] == pytest.approx(generic.q_tt[2, k], rel=1e-8, abs=1e-8)
        assert ap.of("G").real == pytest.approx(generic.q_tt[3, k], rel=1e-8, abs=1e-8)
        assert abs(vp.vector("v_A2A3").value) == pytest.approx(abs(generic.q_t[1, k]), rel=1e-9, abs=1e-10)


def test_the_velocity_image_of_a_coupler_triangle_is_similar_and_turned_by_90_degrees():
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05))                       # chapter 4's crank-rocker
    sol = m.solve(np.radians([60.0]), omega=10.0)
    vp = plans.velocity_plan(m, sol, points={"M": ("coupler", 0.2, 0.12)})
    A, B, M = (vp.positions[n] for n in "ABM")
    a, b, k = (vp.of(n) for n in "ABM")
    w = sol.angle("coupler").omega[0]
    # sides in proportion |ω2| (hand: |v_XY| = |ω2|·|XY| for a rigid link)
    for image_side, side in ((b - a, B - A), (k - a, M - A), (k - b, M - B)):
        assert abs(image_side) == pytest.approx(abs(w) * abs(side), rel=1e-12)
        # and each turned by +90° for ω2 > 0, −90° for ω2 < 0
        assert np.angle(image_side / side) == pytest.approx(math.copysign(math.pi / 2, w), abs=1e-12)
    assert vp.of("M") == pytest.approx(sol.point_on("coupler", 0.2, 0.12).velocity[0], abs=1e-13)


# --- instant centres -------------------------------------------------------------------------------------

def _velocity_as_point_of(sol, link, point):
    """Velocity of a point (m) moving with a link, from the closed form (Euler form about the link's joint)."""
    if link == "frame":
        return 0j
    if link == "slider":
        return sol.point("B").velocity[0]
    joint = {"crank": "O", "coupler": "A", "rocker": "C"}[link]
    return sol.point(joint).velocity[0] + 1j * sol.angle(link).omega[0] * (point - sol.point(joint).value[0])


@FAST
@given(crank_rockers(), st.floats(-np.pi, np.pi, **finite))
def test_four_bar_instant_centres_are_points_of_equal_velocity(geometry, phi):
    crank, coupler, rocker, frame, branch = geometry
    m = mech.FourBar(crank, coupler, rocker, frame, branch)
    sol = m.solve(np.array([phi]), omega=3.0)
    centres = plans.instant_centres(m, sol)
    assert len(centres.pairs) == 6
    assert plans.kennedy_deviation(centres) < 1e-9
    names = {number: name for name, number in centres.links.items()}
    for (i, j), point in centres.finite.items():
        assume(abs(point) < 1e3)          # nearly parallel lines put a centre very far away
        vi, vj = _velocity_as_point_of(sol, names[i], point), _velocity_as_point_of(sol, names[j], point)
        assert abs(vi - vj) <= 1e-8 * 3.0 * (crank + abs(point))


def test_coupler_centre_of_the_four_bar_is_where_the_coupler_has_no_velocity():
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05))
    sol = m.solve(np.radians(np.arange(0.0, 360.0, 15.0)), omega=10.0)
    for k in range(len(sol)):
        centres = plans.instant_centres(m, sol, index=k)
        A, vA = sol.point("A").value[k], sol.point("A").velocity[k]
        w2 = sol.angle("coupler").omega[k]
        # closed form: v_A = iω2(A − P) gives P = A + i·v_A/ω2 (the classical formula of the instant centre)
        assert centres[(0, 2)] == pytest.approx(A + 1j * vA / w2, abs=1e-10)
        omega, velocities = plans.velocities_from_centre(centres[(0, 2)], A, vA, {"B": sol.point("B").value[k]})
        assert omega == pytest.approx(w2, rel=1e-10)
        assert velocities["B"] == pytest.approx(sol.point("B").velocity[k], abs=1e-10)
        # the ratio of the angular velocities from P13 (a point common to crank and rocker)
        p13 = centres[(1, 3)]
        ratio = ((p13 - 0j) / (p13 - sol.point("C").value[k])).real
        assert 10.0 * ratio == pytest.approx(sol.angle("rocker").omega[k], rel=1e-9, abs=1e-9)


def test_crank_slider_instant_centres_for_example_5_2():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0)
    centres = plans.instant_centres(EXAMPLE, sol)
    assert not centres.is_finite(0, 3) and centres.infinite[(0, 3)] == 1j
    assert plans.kennedy_deviation(centres) < 1e-12
    A, B = sol.point("A").value[0], sol.point("B").value[0]
    # by hand: P02 is on OA produced, straight above B: x = x_B, y = x_B·tan 30°
    assert centres[(0, 2)] == pytest.approx(complex(B.real, B.real * math.tan(math.radians(30.0))), abs=1e-14)
    # P13 on the vertical through O and on the line AB: y = y_A − x_A·tan ψ
    psi = sol.angle("coupler").value[0]
    assert centres[(1, 3)] == pytest.approx(complex(0.0, A.imag - A.real * math.tan(psi)), abs=1e-14)
    # P13 moves with the crank and with the slider: ω1·y_P13 = −v_B (the slider translates along x)
    assert -215.0 * centres[(1, 3)].imag == pytest.approx(sol.point("B").velocity[0].real, rel=1e-12)
    omega, v = plans.velocities_from_centre(centres[(0, 2)], A, sol.point("A").velocity[0],
                                            {"B": B, "S2": sol.point_on("coupler", 0.09).value[0]})
    assert omega == pytest.approx(-50.1, abs=0.05)                         # Table 5.5
    assert abs(v["S2"]) == pytest.approx(13.91, abs=0.005)                  # Table 5.5
    assert v["B"] == pytest.approx(sol.point("B").velocity[0], abs=1e-12)   # closed form


@FAST
@given(crank_slider_geometries(), branches, st.floats(-np.pi, np.pi, **finite))
def test_crank_slider_instant_centres_are_points_of_equal_velocity(geometry, branch, phi):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    sol = m.solve(np.array([phi]), omega=2.0)
    centres = plans.instant_centres(m, sol)
    assert plans.kennedy_deviation(centres) < 1e-9
    names = {number: name for name, number in centres.links.items()}
    for (i, j), point in centres.finite.items():
        assume(abs(point) < 1e3 * (crank + rod))
        vi, vj = _velocity_as_point_of(sol, names[i], point), _velocity_as_point_of(sol, names[j], point)
        assert abs(vi - vj) <= 1e-9 * 2.0 * (crank + rod + abs(point))


def test_parallel_crank_and_rocker_put_the_coupler_centre_at_infinity():
    m = mech.FourBar(0.1, 0.4, 0.1, (0.4, 0.0))          # a parallelogram: crank and rocker always parallel
    sol = m.solve(np.radians([50.0]), omega=1.0)
    centres = plans.instant_centres(m, sol)
    assert not centres.is_finite(0, 2)
    assert abs(centres[(0, 2)]) == math.inf
    assert abs(sol.angle("coupler").omega[0]) < 1e-12     # closed form: the coupler translates
    assert plans.kennedy_deviation(centres) < 1e-12


def test_kennedy_deviation_detects_a_misplaced_centre():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0)
    good = plans.instant_centres(EXAMPLE, sol)
    bad = plans.InstantCentres(good.links, {**good.finite, (0, 2): good.finite[(0, 2)] + 0.01}, good.infinite,
                               good.positions)
    assert plans.kennedy_deviation(bad) > 1e-3
