"""Tests of the crank-slider's velocity and acceleration analogues (chapter 3).

Expected values come from a hand calculation (the textbook's Example 5.2 at φ = 30°), from
differentiating the slider position s(φ) = L1 cos φ + σ√(L2² − (L1 sin φ − e)²) and the coupler angle
ψ(φ) = atan2(e − L1 sin φ, s − L1 cos φ), both written out here, in 50-digit arithmetic (mpmath), and
from chapter 2's generic solver at a non-uniform crank speed: never from the function under test.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import crank_slider as analysis
from mechanisms.core.errors import AssemblyError, InvalidParameterError

mpmath.mp.dps = 50


def position_by_hand(l1, l2, e, branch, phi):
    """(ψ, s) at the crank angle phi, in mpmath, from the loop closure alone."""
    h = l1 * mpmath.sin(phi) - e
    s = l1 * mpmath.cos(phi) + branch * mpmath.sqrt(l2**2 - h**2)
    return mpmath.atan2(-h, s - l1 * mpmath.cos(phi)), s


def test_example_5_2_by_hand():
    # φ = 30°: h_A = 0.04 m, c_B = √(0.26·0.34) = 0.2973214 m, ψ = −7.6623°;
    # ψ′ = −0.08 cos 30° / 0.2973214 = −0.2330207; ψ′·215 = −50.0994 1/s (Table 5.5: −50.1);
    # ψ″ = (0.08·0.5 + (−0.04)(0.0542987)) / 0.2973214 = 0.1272295;
    # s′ = −0.08·0.5 − (−0.04)(−0.2330207) = −0.0493208 m; s′·215 = −10.604 m/s;
    # s″ = −0.08 cos 30° − (0.2973214·0.0542987 + (−0.04)(0.1272295)) = −0.0803370 m;
    # s″·215² = −3713.58 m/s² (Table 5.5: −3713).
    result = analysis.analogues(mech.CrankSlider(crank=0.08, rod=0.3), np.radians([30.0]))
    assert result.psi_1[0] == pytest.approx(-0.2330207, abs=2e-7)
    assert result.psi_2[0] == pytest.approx(0.1272295, abs=2e-7)
    assert result.s_1[0] == pytest.approx(-0.0493208, abs=2e-7)
    assert result.s_2[0] == pytest.approx(-0.0803370, abs=2e-7)


@pytest.mark.parametrize("l1, l2, e, branch", [(0.08, 0.3, 0.0, 1), (0.1, 0.22, -0.03, 1),
                                                (2.0, 4.0, -1.0, -1), (0.05, 0.2, 0.04, -1)])
def test_against_high_precision_differentiation(l1, l2, e, branch):
    m = mech.CrankSlider(crank=l1, rod=l2, offset=e, branch=branch)
    phi = np.radians(np.arange(-175.0, 180.0, 25.0))
    result = analysis.analogues(m, phi)
    for k, angle in enumerate(phi):
        def psi(x):
            return position_by_hand(l1, l2, e, branch, x)[0]

        def s(x):
            return position_by_hand(l1, l2, e, branch, x)[1]

        x = mpmath.mpf(float(angle))
        expected = [mpmath.diff(psi, x, 1), mpmath.diff(psi, x, 2),
                    mpmath.diff(s, x, 1), mpmath.diff(s, x, 2)]
        got = [result.psi_1[k], result.psi_2[k], result.s_1[k], result.s_2[k]]
        for value, reference in zip(got, expected):
            assert value == pytest.approx(float(reference), rel=1e-10, abs=1e-12)


def test_time_derivatives_from_analogues_match_the_generic_solver():
    # ψ_t = ω ψ′, ψ_tt = ε ψ′ + ω² ψ″ (and the same for s) against Newton's method on the constraints
    m = mech.CrankSlider(crank=0.1, rod=0.22, offset=-0.03)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    omega, epsilon = 120.0, -4000.0
    result = analysis.analogues(m, phi)
    generic = mech.verify.solve_generic(m, phi, omega=omega, alpha=epsilon)
    np.testing.assert_allclose(omega * result.psi_1, generic.q_t[0], rtol=1e-11, atol=1e-9)
    np.testing.assert_allclose(omega * result.s_1, generic.q_t[1], rtol=1e-11, atol=1e-10)
    np.testing.assert_allclose(epsilon * result.psi_1 + omega**2 * result.psi_2, generic.q_tt[0],
                               rtol=1e-10, atol=1e-7)
    np.testing.assert_allclose(epsilon * result.s_1 + omega**2 * result.s_2, generic.q_tt[1],
                               rtol=1e-10, atol=1e-8)


def test_slider_analogue_vanishes_at_the_dead_centres():
    # the derivative-properties check: s′ = 0 where s is extreme, at φ = arcsin(e/(L1 + L2)) (outer)
    # and π + arcsin(e/(L2 − L1)) (inner), written out by hand for L1 = 0.1, L2 = 0.22, e = −0.03
    m = mech.CrankSlider(crank=0.1, rod=0.22, offset=-0.03)
    outer, inner = np.arcsin(-0.03 / 0.32), np.pi + np.arcsin(-0.03 / 0.12)
    result = analysis.analogues(m, [outer, inner])
    np.testing.assert_allclose(result.s_1, 0.0, atol=1e-15)
    assert result.s_2[0] < 0.0 < result.s_2[1]   # a maximum of s, then a minimum


def test_bad_inputs_are_named():
    m = mech.CrankSlider(crank=0.08, rod=0.3)
    with pytest.raises(InvalidParameterError, match="phi"):
        analysis.analogues(m, [0.0, float("nan")])
    short = mech.CrankSlider(crank=0.1, rod=0.12, offset=0.05)
    with pytest.raises(AssemblyError):
        analysis.analogues(short, np.radians([270.0]))
