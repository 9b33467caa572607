"""Tests of the classical synthesis of chapter 12 (mechanisms/analysis/synthesis.py): the crank-rocker
for a rocker swing and a time ratio, function generation by Freudenstein's equation, and motion
generation through three positions of a body.

Every design is simulated with FourBar (or with the generic solver) and compared with what was
asked: the swing and K, the precision points, the body's positions. No expected value comes from
the synthesis functions themselves.
"""

import math
import warnings

import mpmath
import numpy as np
import pytest

import mechanisms as mech
from mechanisms import InvalidParameterError
from mechanisms.analysis.four_bar import grashof_class, transmission_angle
from mechanisms.analysis.synthesis import (best_crank_rocker, body_positions, centre_point, chebyshev_spacing,
                                           check_motion, circle_point, crank_rocker_for_swing,
                                           four_bar_through_positions, free_angle_range, freudenstein_coefficients,
                                           function_generator, minimum_transmission, pole, time_ratio_angle)
from mechanisms.verify import solve_constraints


# --- helpers: simulation, independent of the design formulas -------------------------------------

def rocker_turning_points(m: mech.FourBar, positions: int = 3600) -> tuple[np.ndarray, np.ndarray]:
    """Crank angles where the simulated rocker turns back (ξ_t = 0), by bisection on ξ_t of FourBar."""
    phi = np.linspace(0.0, 2.0 * math.pi, positions + 1)

    def rate(angles):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return m.solve(angles, omega=1.0, order=1).angle("rocker").omega

    g = rate(phi)
    k = np.nonzero(np.sign(g[:-1]) != np.sign(g[1:]))[0]
    lo, hi, g_lo = phi[k], phi[k + 1], g[k]
    for _ in range(70):
        mid = 0.5 * (lo + hi)
        g_mid = rate(mid)
        left = np.sign(g_mid) == np.sign(g_lo)
        lo, g_lo = np.where(left, mid, lo), np.where(left, g_mid, g_lo)
        hi = np.where(left, hi, mid)
    turns = 0.5 * (lo + hi)
    return turns, m.solve(turns, order=0).angle("rocker").value


def simulated_swing_and_ratio(m: mech.FourBar) -> tuple[float, float]:
    turns, xi = rocker_turning_points(m)
    assert turns.size == 2, "a crank-rocker's rocker turns back twice per turn"
    stroke = turns[1] - turns[0]
    swing = abs(math.remainder(xi[1] - xi[0], 2.0 * math.pi))
    return swing, max(stroke, 2 * math.pi - stroke) / min(stroke, 2 * math.pi - stroke)


# --- the crank-rocker for a swing and a time ratio -----------------------------------------------

CASES = [(60.0, 1.2), (40.0, 1.5), (90.0, 1.1), (20.0, 2.0), (120.0, 1.3)]


@pytest.mark.parametrize("swing_deg, k", CASES)
@pytest.mark.parametrize("fraction", [-0.8, -0.3, 0.2, 0.5, 0.9])
def test_crank_rocker_reproduces_swing_and_time_ratio(swing_deg, k, fraction):
    swing = math.radians(swing_deg)
    low, high = free_angle_range(swing, k)
    if fraction < 0 and low == 0.0:
        pytest.raises(InvalidParameterError, crank_rocker_for_swing, swing, k, -1e-3)
        return
    nu = fraction * (-low if fraction < 0 else high)
    design = crank_rocker_for_swing(swing, k, nu, rocker=0.25)
    m = design.four_bar()
    # expected: the asked Δξ and K, measured on the simulated motion (bisection on ξ_t of FourBar)
    assert grashof_class(*m.lengths).name == "crank-rocker"
    reached_swing, reached_k = simulated_swing_and_ratio(m)
    assert reached_swing == pytest.approx(swing, abs=1e-9)
    assert reached_k == pytest.approx(k, abs=1e-9)


def test_crank_rocker_geometry_of_the_construction():
    design = crank_rocker_for_swing(math.radians(50.0), 1.4, math.radians(25.0), rocker=0.2)
    l1, l2, l3 = design.crank, design.coupler, design.rocker
    c = complex(*design.frame)
    # the limit positions: |OB₁| = L₂ + L₁ (stretched), |OB₂| = L₂ − L₁ (folded), both on the rocker's circle
    assert abs(design.extended) == pytest.approx(l2 + l1, rel=1e-12)
    assert abs(design.folded) == pytest.approx(l2 - l1, rel=1e-12)
    assert abs(design.extended - c) == pytest.approx(l3, rel=1e-12)
    assert abs(design.folded - c) == pytest.approx(l3, rel=1e-12)
    # the chord is seen from C at Δξ and from O at θ_K = 180°(K − 1)/(K + 1) = 30° (hand: 180·0.4/2.4)
    seen_from_c = abs(np.angle((design.folded - c) / (design.extended - c)))
    seen_from_o = abs(np.angle(design.folded / design.extended))
    assert math.degrees(seen_from_c) == pytest.approx(50.0, abs=1e-10)
    assert math.degrees(seen_from_o) == pytest.approx(30.0, abs=1e-10)
    assert math.degrees(time_ratio_angle(1.4)) == pytest.approx(30.0, abs=1e-12)
    # O, B₁ and B₂ lie on the circle of the construction (radius c_B/(2 sin θ_K))
    chord = 2 * l3 * math.sin(math.radians(25.0))
    for z in (0j, design.extended, design.folded):
        assert abs(z - design.circle_centre) == pytest.approx(chord / (2 * math.sin(math.radians(30.0))), rel=1e-12)


@pytest.mark.parametrize("swing_deg, k", CASES)
def test_free_angle_range_ends_where_the_design_degenerates(swing_deg, k):
    # at either end O, C and a limit position of B come into line (the frame line is the design's
    # x axis), while the crank keeps a length: found by approaching the end, not from its formula
    swing = math.radians(swing_deg)
    low, high = free_angle_range(swing, k)
    for end in (high, low):
        if end == 0.0:
            continue
        design = crank_rocker_for_swing(swing, k, end * (1 - 1e-9))
        assert min(abs(design.extended.imag), abs(design.folded.imag)) < 1e-6
        assert design.crank > 1e-3


def test_best_crank_rocker_beats_every_sampled_free_angle():
    swing, k = math.radians(60.0), 1.2
    best = best_crank_rocker(swing, k)
    low, high = free_angle_range(swing, k)
    best_mu = minimum_transmission(best.four_bar())
    # expected: the simulated smallest transmission angle min(μ, π − μ) over a turn, on a grid of ν
    phi = np.linspace(0.0, 2.0 * math.pi, 7201)
    for nu in np.concatenate([np.linspace(low, 0.0, 41)[1:-1], np.linspace(0.0, high, 61)[1:-1]]):
        mu = transmission_angle(crank_rocker_for_swing(swing, k, nu).four_bar().solve(phi, order=0))
        assert np.min(np.minimum(mu, math.pi - mu)) <= best_mu + 1e-9
    mu = transmission_angle(best.four_bar().solve(phi, order=0))
    assert np.min(np.minimum(mu, math.pi - mu)) == pytest.approx(best_mu, abs=1e-6)


def test_crank_rocker_refuses_what_it_cannot_build():
    with pytest.raises(InvalidParameterError, match="time_ratio"):
        crank_rocker_for_swing(1.0, 1.0, 0.2)
    with pytest.raises(InvalidParameterError, match="swing"):
        crank_rocker_for_swing(math.pi, 1.2, 0.2)
    with pytest.raises(InvalidParameterError, match="free_angle"):
        crank_rocker_for_swing(1.0, 1.2, 0.0)
    with pytest.raises(InvalidParameterError, match="free_angle"):
        crank_rocker_for_swing(1.0, 1.2, float("nan"))
    with pytest.raises(InvalidParameterError, match="rocker"):
        crank_rocker_for_swing(1.0, 1.2, 0.2, rocker=-1.0)


# --- function generation --------------------------------------------------------------------------

def test_chebyshev_spacing_by_hand():
    # (1 + 2)/2 ∓ (2 − 1)/2·cos 30° = 1.5 ∓ 0.4330127…, and the midpoint 1.5
    assert chebyshev_spacing(1.0, 2.0, 3) == pytest.approx([1.5 - 0.25 * math.sqrt(3), 1.5,
                                                            1.5 + 0.25 * math.sqrt(3)], abs=1e-15)
    with pytest.raises(InvalidParameterError, match="stop"):
        chebyshev_spacing(2.0, 1.0)
    with pytest.raises(InvalidParameterError, match="count"):
        chebyshev_spacing(1.0, 2.0, 0)


def log_generator_points(count=3):
    # y = log10 x on 1 ≤ x ≤ 2: φ from 45° to 105°, ξ from 105° to 165° (chapter 12)
    x = chebyshev_spacing(1.0, 2.0, count)
    return np.radians(45.0 + 60.0 * (x - 1.0)), np.radians(105.0 + 60.0 * np.log10(x) / math.log10(2.0))


def test_freudenstein_coefficients_against_mpmath():
    phi, xi = log_generator_points()
    mpmath.mp.dps = 40
    rows = [[mpmath.cos(mpmath.mpf(b)), -mpmath.cos(mpmath.mpf(a)), 1] for a, b in zip(phi, xi)]
    rhs = [mpmath.cos(mpmath.mpf(a) - mpmath.mpf(b)) for a, b in zip(phi, xi)]
    expected = mpmath.lu_solve(mpmath.matrix(rows), mpmath.matrix(rhs))
    assert freudenstein_coefficients(phi, xi) == pytest.approx([float(v) for v in expected], rel=1e-12)


def test_function_generator_hits_its_precision_points():
    phi, xi = log_generator_points()
    m = function_generator(phi, xi, frame=0.1)
    # expected: the asked ξ at the precision points, by FourBar and by the generic solver (Newton)
    assert np.abs(np.remainder(m.solve(phi, order=0).angle("rocker").value - xi + np.pi, 2 * np.pi) - np.pi).max() < 1e-9
    guess = np.array([np.angle(m.solve(phi[:1], order=0).point("B").value[0] - m.crank * np.exp(1j * phi[0])) + 0.01,
                      xi[0] + 0.01])
    generic = solve_constraints(m.constraints, guess, phi, order=0)
    assert np.abs(np.remainder(generic.q[1] - xi + np.pi, 2 * np.pi) - np.pi).max() < 1e-9
    # between the precision points the structural error is small but not zero (log10 is no four-bar's function)
    between = np.radians(45.0 + 60.0 * np.linspace(0.0, 1.0, 101))
    wanted = np.radians(105.0 + 60.0 * np.log10(1.0 + np.linspace(0.0, 1.0, 101)) / math.log10(2.0))
    error = np.abs(m.solve(between, order=0).angle("rocker").value - wanted)
    assert 1e-5 < error.max() < math.radians(0.5)


def test_least_squares_recovers_a_linkage_that_generates_the_function_exactly():
    # pairs (φ, ξ) taken from a known linkage's simulated motion: the fit must return that linkage
    known = mech.FourBar(0.4, 1.1, 0.9, (1.0, 0.0), branch=1)
    phi = np.radians(np.linspace(40.0, 140.0, 9))
    xi = known.solve(phi, order=0).angle("rocker").value
    fitted = function_generator(phi, xi, frame=1.0)
    assert fitted.lengths == pytest.approx(known.lengths, rel=1e-10)
    assert fitted.branch == known.branch


def test_function_generator_refuses_bad_points():
    with pytest.raises(InvalidParameterError, match="phi"):
        freudenstein_coefficients([0.1, 0.2], [1.0, 1.1])
    with pytest.raises(InvalidParameterError, match="phi"):
        freudenstein_coefficients([0.1, 0.1, 0.1], [1.0, 1.0, 1.0])
    with pytest.raises(InvalidParameterError, match="xi"):
        freudenstein_coefficients([0.1, 0.2, 0.3], [1.0, 1.1])
    with pytest.raises(InvalidParameterError, match="xi"):
        # φ from 45° to 105°, ξ from 180° on: k₂ < 0, no positive rocker length
        x = chebyshev_spacing(1.0, 2.0)
        function_generator(np.radians(30 + 90 * (x - 1)), np.radians(180 + 60 * np.log10(x) / math.log10(2)))


# --- motion generation ----------------------------------------------------------------------------

POINTS = np.array([0.046 + 0.125j, -0.025 + 0.108j, -0.044 + 0.039j])    # chapter 12's three positions
ANGLES = np.radians([30.0, 32.0, 58.0])


def test_pole_is_the_point_that_does_not_move():
    for i, j in ((0, 1), (0, 2), (1, 2)):
        p = pole(POINTS[i], ANGLES[i], POINTS[j], ANGLES[j])
        # the body point at the pole in position i: (p − P_i) e^{−iθ_i}; in position j it is at the pole again
        local = (p - POINTS[i]) * np.exp(-1j * ANGLES[i])
        assert abs(POINTS[j] + np.exp(1j * ANGLES[j]) * local - p) < 1e-15
    with pytest.raises(InvalidParameterError, match="angle_2"):
        pole(0j, 0.3, 1 + 0j, 0.3)


def test_centre_and_circle_points():
    moving = -0.059 - 0.060j
    centre = centre_point(moving, POINTS, ANGLES)
    # expected: equidistant from the three positions of the moving point (computed here by hand)
    positions = POINTS + np.exp(1j * ANGLES) * moving
    assert np.ptp(np.abs(positions - centre)) < 1e-15
    # the circle point of that centre is the moving point again
    assert abs(circle_point(centre, POINTS, ANGLES) - moving) < 1e-12
    # two positions: the centre lies on the bisector, at the asked distance from the midpoint
    two = centre_point(moving, POINTS[:2], ANGLES[:2], along=0.05)
    assert abs(abs(two - positions[0]) - abs(two - positions[1])) < 1e-15
    assert abs(two - 0.5 * (positions[0] + positions[1])) == pytest.approx(0.05, rel=1e-12)
    assert body_positions(moving, POINTS, ANGLES) == pytest.approx(positions)
    with pytest.raises(InvalidParameterError, match="angles"):
        centre_point(moving, POINTS, ANGLES[:2])
    with pytest.raises(InvalidParameterError, match="moving"):
        # a point whose three positions are in line: the pole-free translation along x
        centre_point(0j, [0j, 1 + 0j, 2 + 0j], [0.0, 0.0, 0.0])


def designed(rocker_pin):
    crank_pin = -0.059 - 0.060j
    return four_bar_through_positions(POINTS, ANGLES, crank_pin, rocker_pin,
                                      centre_point(crank_pin, POINTS, ANGLES),
                                      centre_point(rocker_pin, POINTS, ANGLES))


def test_motion_design_carries_the_body_through_its_positions():
    design = designed(0.091 - 0.059j)
    m = design.four_bar
    check = check_motion(design)
    assert check.defect == "none" and check.grashof == "crank-rocker"
    # expected: the asked positions, by the generic solver continued from position 1 through 2 to 3
    # (Newton on the loop closure, in small steps: the motion, not three separate solutions)
    phi = design.crank_angles
    path = np.concatenate([np.linspace(phi[0], phi[1], 50), np.linspace(phi[1], phi[2], 50)[1:]])
    sol0 = m.solve(path[:1], order=0)
    generic = solve_constraints(m.constraints, np.array([sol0.angle("coupler").value[0],
                                                         sol0.angle("rocker").value[0]]), path, order=0)
    psi = generic.q[0][[0, 49, 98]]
    a = m.crank * np.exp(1j * phi)
    reached = design.origin + a + (design.along + 1j * design.left) * np.exp(1j * psi)
    assert np.abs(reached - POINTS).max() < 1e-9
    assert np.abs(np.remainder(psi + design.offset - ANGLES + np.pi, 2 * np.pi) - np.pi).max() < 1e-9


def test_motion_defects_named_and_confirmed_by_simulation():
    # circuit: B on the other side of A → C in some position of a crank that turns fully; the
    # linkage assembled on the first position's side misses the others (checked by FourBar)
    circuit = designed(-0.10 + 0.0j)
    check = check_motion(circuit)
    m = circuit.four_bar
    assert check.defect == "circuit" and grashof_class(*m.lengths).crank_rotates
    assert check.position_error > 0.01
    other = mech.FourBar(m.crank, m.coupler, m.rocker, m.frame, -m.branch)
    reached_other = circuit.origin + other.solve(circuit.crank_angles, order=0).point_on(
        "coupler", circuit.along, circuit.left).value
    assert np.abs(reached_other - POINTS).min() < 1e-9      # some position is on the other circuit
    # order: one side, reachable, but the crank meets position 2 outside the stretch from 1 to 3
    order = designed(0.0 - 0.01j)
    assert check_motion(order).defect == "order"
    phi = order.crank_angles
    (lo, hi), = order.four_bar.assembly_intervals()
    inside = lo + np.remainder(phi - lo, 2 * np.pi)
    assert not min(inside[0], inside[2]) < inside[1] < max(inside[0], inside[2])
    # branch: a non-Grashof linkage with B on both sides of A → C
    branch = designed(-0.10 - 0.07j)
    assert check_motion(branch).defect == "branch"
    assert grashof_class(*branch.four_bar.lengths).name == "triple rocker"


def test_motion_design_refuses_a_wrong_centre():
    with pytest.raises(InvalidParameterError, match="crank_pivot"):
        four_bar_through_positions(POINTS, ANGLES, -0.059 - 0.060j, 0.091 - 0.059j, 0j,
                                   centre_point(0.091 - 0.059j, POINTS, ANGLES))


def test_coupler_output_design_only_rescales_with_the_rocker():
    # chapter 12, §12.5.1: every length is L3 times a function of K and μ₁ (and the errata's point on
    # the paper's advice to shorten the rocker); expected: the design at L3 = 1 m, scaled by hand
    from mechanisms.analysis.synthesis import check_design, synthesize_coupler_output
    unit = synthesize_coupler_output(1.2, math.radians(40.0), rocker=1.0, corrected=True)
    short = synthesize_coupler_output(1.2, math.radians(40.0), rocker=0.3, corrected=True)
    assert (short.crank, short.coupler) == pytest.approx((0.3 * unit.crank, 0.3 * unit.coupler), rel=1e-14)
    assert short.frame == pytest.approx((0.3 * unit.frame[0], 0.3 * unit.frame[1]), rel=1e-14)
    # the angles do not change: the simulated K and μ₁ are those asked, at either scale
    for design in (unit, short):
        check = check_design(design, positions=720)
        assert check.time_ratio == pytest.approx(1.2, abs=1e-9)
        assert math.degrees(check.first_angle) == pytest.approx(40.0, abs=1e-7)
    # at the end of the rotatable range μ₁ = φx/2 the coupler is L3/cos(φx/2) ≈ 7.03 L3 (K = 1.2)
    end = synthesize_coupler_output(1.2, math.pi / 2.2, rocker=1.0, corrected=True)
    assert end.coupler == pytest.approx(1.0 / math.cos(math.pi / 2.2), rel=1e-12)
