"""Tests of the synthesis from time ratio and transmission angle (mechanisms/analysis/synthesis.py).

Every design is checked by simulating it with FourBar; the expected values are the asked
K_v and γ (the specification), never numbers from the synthesis itself.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms import InvalidParameterError
from mechanisms.analysis.synthesis import (check_design, closure_residual, coupler_length_asymptote,
                                           largest_rotatable_angle, return_angle, synthesize_coupler_output)
from mechanisms.verify import solve_constraints


def test_paper_example_reaches_what_was_asked():
    design = synthesize_coupler_output(1.2, math.radians(40.0))
    check = check_design(design)
    # asked: K_v = 1.2, γ = 40° in the first limit position, a rotating crank
    assert check.grashof == "crank-rocker" and check.crank_rotates and not check.singular
    assert check.time_ratio == pytest.approx(1.2, rel=1e-9)
    assert math.degrees(check.first_angle) == pytest.approx(40.0, abs=1e-7)
    # the paper: the second limit position has μ = φ_x/2 = 180°/(K_v + 1)
    assert math.degrees(check.second_angle) == pytest.approx(180.0 / 2.2, abs=1e-7)
    # the paper: the smallest transmission angle over a turn may be smaller than γ
    assert check.minimum_angle < check.first_angle


def test_coupler_turns_back_at_the_designed_positions():
    design = synthesize_coupler_output(1.5, math.radians(50.0))
    m = design.four_bar()
    phi = np.array([0.0, design.return_angle])
    sol = m.solve(phi, omega=1.0)
    # expected: ψ_t = 0 from the generic solver (Newton on the loop closure) at both positions
    generic = solve_constraints(m.constraints, np.array([sol.angle("coupler").value, sol.angle("rocker").value]) + 0.01,
                                phi, omega=1.0)
    assert np.allclose(generic.q_t[0], 0.0, atol=1e-12)
    # and B sits where the paper places it in the first position: A + L2·exp(i(π − γ))
    b = m.solve(np.array([0.0]), order=0).point("B").value[0]
    assert b == pytest.approx(design.crank + design.coupler * np.exp(1j * (math.pi - math.radians(50.0))))


@settings(max_examples=25, deadline=None)
@given(st.floats(1.05, 2.5), st.floats(0.05, 0.95))
def test_corrected_formula_holds_on_the_whole_rotatable_range(time_ratio, fraction):
    # γ anywhere in (0, φ_x/2): the corrected length gives a crank-rocker reaching K_v and γ
    gamma = fraction * 0.5 * return_angle(time_ratio)
    design = synthesize_coupler_output(time_ratio, gamma, rocker=0.3, corrected=True)
    assert closure_residual(design) < 1e-12
    check = check_design(design, positions=720)
    assert check.crank_rotates
    assert check.time_ratio == pytest.approx(time_ratio, rel=1e-8)
    assert check.first_angle == pytest.approx(gamma, abs=1e-8)


def test_printed_formula_fails_below_its_range():
    # K_v = 1.5: φ_x/2 = 72°; below γ = 90° − φ_x/2 = 18° the printed L2 lost the sign of the
    # cotangent: its two limit positions do not close (the designed linkage misses K_v)
    printed = synthesize_coupler_output(1.5, math.radians(10.0))
    corrected = synthesize_coupler_output(1.5, math.radians(10.0), corrected=True)
    assert closure_residual(printed) > 0.1 and closure_residual(corrected) < 1e-12
    assert abs(check_design(printed).time_ratio - 1.5) > 0.1
    # above 18° the two agree
    assert synthesize_coupler_output(1.5, math.radians(30.0)).coupler == pytest.approx(
        synthesize_coupler_output(1.5, math.radians(30.0), corrected=True).coupler)


def test_rotatability_limit_and_asymptote():
    for k in (1.2, 1.5, 2.0):
        phi_x = return_angle(k)
        # found by bisection on Grashof's condition of the designs; observed: γ_max = φ_x/2
        assert largest_rotatable_angle(k) == pytest.approx(0.5 * phi_x, abs=1e-7)
        # just above it the crank does not turn: the design is useless however long L2 is
        above = check_design(synthesize_coupler_output(k, 0.5 * phi_x + 0.02, corrected=True))
        assert not above.crank_rotates
        # the coupler length grows without bound at the paper's asymptote γ = π − φ_x/2
        asymptote = coupler_length_asymptote(k)
        assert asymptote == pytest.approx(math.pi - 0.5 * phi_x)
        lengths = [synthesize_coupler_output(k, asymptote - e, corrected=True).coupler for e in (1e-1, 1e-2, 1e-3)]
        assert lengths[2] / lengths[1] == pytest.approx(100.0, rel=0.02)   # L2 ~ 1/(π − φ_x/2 − γ)²


def test_bad_inputs():
    with pytest.raises(InvalidParameterError, match="time_ratio"):
        return_angle(0.8)
    with pytest.raises(InvalidParameterError, match="transmission_angle"):
        synthesize_coupler_output(1.2, 0.0)
    with pytest.raises(InvalidParameterError, match="transmission_angle"):
        synthesize_coupler_output(1.2, coupler_length_asymptote(1.2))
    with pytest.raises(InvalidParameterError, match="rocker"):
        synthesize_coupler_output(1.2, 0.5, rocker=-1.0)
    with pytest.raises(InvalidParameterError, match="K > 1"):
        synthesize_coupler_output(1.0, 0.5)          # no quick return: the crank would have no length
    with pytest.raises(InvalidParameterError, match="time_ratio"):
        largest_rotatable_angle(1.0001)


def _closed_form_time_ratio(design) -> float:
    """K from the limit positions in closed form: crank and rocker in line, B = C + s·L₃e^{iφ}
    (s = ±1) at distance L₂ from A = L₁e^{iφ}; |C + (sL₃ − L₁)e^{iφ}|² = L₂² gives
    cos(φ − θ_C) = (L₂² − |C|² − (sL₃ − L₁)²) / (2(sL₃ − L₁)|C|). Of the (up to) four roots the two
    whose B lies on the design's side of the line A → C are its limit positions."""
    l1, l2, l3, c = design.crank, design.coupler, design.rocker, complex(*design.frame)
    roots = []
    for s in (1.0, -1.0):
        k = s * l3 - l1
        r = (l2 ** 2 - abs(c) ** 2 - k ** 2) / (2.0 * k * abs(c))
        for sign in (1.0, -1.0):
            phi = math.atan2(c.imag, c.real) + sign * math.acos(max(-1.0, min(1.0, r)))
            a, b = l1 * complex(math.cos(phi), math.sin(phi)), c + s * l3 * complex(math.cos(phi), math.sin(phi))
            if ((c - a).conjugate() * (b - a)).imag * design.branch > 0:
                roots.append(phi % (2.0 * math.pi))
    assert len(roots) == 2
    stroke = abs(roots[1] - roots[0])
    return max(stroke, 2.0 * math.pi - stroke) / min(stroke, 2.0 * math.pi - stroke)


@pytest.mark.parametrize("seed", range(12))
def test_limit_positions_on_grid_points_under_one_ulp_noise(seed, monkeypatch):
    # K = 2, μ₁ = 30°: the limit positions φ = 0 and φ_x = 120° fall on grid points of the
    # 720-point grid from −30°, where sin(φ − ξ) is ~1e-16 with a sign set by round-off. numpy's
    # elementary functions one ulp off at random (tools/nudge_numpy.py: another processor) must
    # not move the time ratio. Expected: K from the closed-form limit positions (by hand: φ = 0
    # and 120°, K = 240/120 = 2).
    from test_scene import nudged_numpy
    design = synthesize_coupler_output(2.0, math.radians(30.0))
    expected = _closed_form_time_ratio(design)
    assert expected == pytest.approx(2.0, rel=1e-12)
    for name, function in nudged_numpy(seed).items():
        monkeypatch.setattr(np, name, function)
    check = check_design(design, positions=720)
    assert check.time_ratio == pytest.approx(expected, rel=1e-9)
    assert np.degrees(check.limit_angles) == pytest.approx([0.0, 120.0], abs=1e-9)
