"""Tests of the hand equations of an RRR dyad whose two outer joints both move (chapter 6, ``dyad_rates``).

Expected values: finite differences (eighth order) of the link angles that the package's position
solution gives at neighbouring crank angles, solved with ``order=0``; and, for a dyad with one fixed
outer joint, the four-bar's closed form and a hand calculation.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis.structure import dyad_rates
from mechanisms.core.errors import InvalidParameterError, MissingDerivativeError, SingularPositionWarning
from mechanisms.core.motion import PointMotion
from mechanisms.linkages.linkage_file import linkage_from_dict

H = 1e-3
OFFSETS = np.arange(-4, 5)
FIRST = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
SECOND = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
OMEGA, ALPHA = 10.0, 3.0
ANGLES = np.radians([0.0, 60.0, 150.0, 222.0, 300.0])

# The six-bar of chapter 6, §6.6: a four-bar O-A-B-C, a point E of its coupler, a point H of its rocker,
# and a second dyad E-F-H whose outer joints E and H both move.
SIX_BAR = {"name": "six-bar", "frame": {"O": [0.0, 0.0], "C": [0.4, 0.05]},
           "crank": {"pivot": "O", "pin": "A", "length": 0.1},
           "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [0.35, 0.3], "branch": 1,
                     "links": ["coupler", "rocker"]},
                    {"type": "RRR", "joint": "F", "from": ["E", "H"], "lengths": [0.3, 0.25], "branch": 1,
                     "links": ["link 4", "link 5"]}],
           "point": [{"name": "E", "link": ["A", "B"], "along": 0.2, "left": 0.12},
                     {"name": "H", "link": ["C", "B"], "along": 0.45, "left": 0.05}]}


def _unwrapped(values):
    return np.unwrap(values, axis=0)


def test_both_outer_joints_moving_against_differences():
    linkage = linkage_from_dict(SIX_BAR)
    solution = linkage.solve(ANGLES, omega=OMEGA, alpha=ALPHA)
    fourth, fifth = dyad_rates(solution.point("E"), solution.point("H"), solution.angle("link 4").value,
                               solution.angle("link 5").value, 0.3, 0.25)
    for link, rates in (("link 4", fourth), ("link 5", fifth)):
        angles = _unwrapped(np.array([linkage.solve(ANGLES + k * H, order=0).angle(link).value
                                      for k in OFFSETS]))
        d1, d2 = FIRST @ angles / H, SECOND @ angles / H**2
        expected_omega = OMEGA * d1                          # θ_t = ω dθ/dφ
        expected_alpha = OMEGA**2 * d2 + ALPHA * d1          # θ_tt = ω² θ'' + ε θ'
        assert np.max(np.abs(rates.omega - expected_omega)) < 1e-8
        assert np.max(np.abs(rates.alpha - expected_alpha)) < 1e-5


def test_fixed_second_joint_is_the_four_bar_by_hand():
    # Chapter 4's worked example: L1 = 0.1, L2 = 0.35, L3 = 0.3 m, C = (0.4, 0) m, φ = 90°, φ_t = 10 1/s,
    # φ_tt = 0: by hand ψ_t = −0.985 1/s, ξ_t = 2.905 1/s, ψ_tt = 20.28 1/s², ξ_tt = 17.15 1/s².
    psi, xi = np.radians([31.4084]), np.radians([109.7293])   # hand: ψ = 31.41°, ξ = 109.73°
    pin = PointMotion(np.array([0.1j]), np.array([-1.0 + 0j]), np.array([-10j]))   # A, v_A, a_A by hand
    pivot = PointMotion(np.array([0.4 + 0j]), np.zeros(1, complex), np.zeros(1, complex))
    coupler, rocker = dyad_rates(pin, pivot, psi, xi, 0.35, 0.3)
    assert coupler.omega[0] == pytest.approx(-0.985, abs=2e-3)
    assert rocker.omega[0] == pytest.approx(2.905, abs=2e-3)
    assert coupler.alpha[0] == pytest.approx(20.28, abs=2e-2)
    assert rocker.alpha[0] == pytest.approx(17.15, abs=2e-2)


def test_singular_position_warns():
    # both links along +x: in line, the determinant a b sin(θ₂ − θ₁) vanishes
    p = PointMotion(np.zeros(1, complex), np.array([1j]), np.zeros(1, complex))
    q = PointMotion(np.array([2.0 + 0j]), np.zeros(1, complex), np.zeros(1, complex))
    with pytest.warns(SingularPositionWarning, match="in line"):
        dyad_rates(p, q, [0.0], [np.pi], 1.0, 1.0)


def test_bad_inputs_are_named():
    linkage = linkage_from_dict(SIX_BAR)
    slow = linkage.solve(ANGLES, omega=OMEGA, order=1)
    with pytest.raises(MissingDerivativeError):
        dyad_rates(slow.point("E"), slow.point("H"), slow.angle("link 4").value, slow.angle("link 5").value,
                   0.3, 0.25)
    full = linkage.solve(ANGLES, omega=OMEGA)
    with pytest.raises(InvalidParameterError, match="second_length"):
        dyad_rates(full.point("E"), full.point("H"), full.angle("link 4").value, full.angle("link 5").value,
                   0.3, -0.25)
    with pytest.raises(InvalidParameterError, match="first_angle"):
        dyad_rates(full.point("E"), full.point("H"), [np.nan] * 5, full.angle("link 5").value, 0.3, 0.25)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        dyad_rates(full.point("E"), full.point("H"), full.angle("link 4").value, full.angle("link 5").value,
                   0.3, 0.25)                               # no warning away from singular positions
