"""Tests of families of four-bars solved at once (mechanisms/linkages/four_bar.py: four_bar_family) and of the
hinge routine with arrays of link lengths and lenient assembly (mechanisms/blocks/circle_circle.py)."""

import numpy as np
import pytest

from mechanisms.blocks.circle_circle import hinge, hinge_plain
from mechanisms.core.errors import AssemblyError, InvalidParameterError
from mechanisms.core.motion import PointMotion
from mechanisms.linkages.four_bar import FourBar, four_bar_family
from mechanisms.verify import solve_constraints


def random_family(rng, g):
    l1, l2, l3 = rng.uniform(0.2, 2.0, (3, g))
    cx, cy = rng.uniform(-1.5, 1.5, (2, g))
    return l1, l2, l3, cx, cy, rng.choice([-1, 1], g)


def test_family_against_the_generic_solver():
    # members whose crank turns fully (checked: |d − L1| > |L2 − L3| and d + L1 < L2 + L3 for each)
    l1 = np.array([1.0, 0.8, 0.5])
    l2 = np.array([3.5, 3.0, 2.0])
    l3 = np.array([3.0, 2.6, 1.9])
    cx, cy = np.array([4.0, 3.2, 1.8]), np.array([0.0, 0.5, -0.4])
    branch = np.array([1, -1, 1])
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    family = four_bar_family(l1, l2, l3, cx, cy, phi, omega=12.0, alpha=-3.0, branch=branch)
    assert family.assembled.all() and family.points["B"].value.shape == (3, 24)
    for k in range(3):
        m = FourBar(l1[k], l2[k], l3[k], (cx[k], cy[k]), int(branch[k]))
        # expected: Newton on the loop-closure equations, from guesses 0.02 rad off the family's own angles
        # (the continuation keeps the branch of the guess)
        guess = np.array([family.angles["coupler"].value[k], family.angles["rocker"].value[k]]) + 0.02
        generic = solve_constraints(m.constraints, guess, phi, omega=12.0, alpha=-3.0)
        for name, index in (("coupler", 0), ("rocker", 1)):
            angle = family.angles[name]
            assert np.allclose(np.angle(np.exp(1j * (angle.value[k] - generic.q[index]))), 0.0, atol=1e-10)
            assert np.allclose(angle.omega[k], generic.q_t[index], rtol=1e-9, atol=1e-9)
            assert np.allclose(angle.alpha[k], generic.q_tt[index], rtol=1e-9, atol=1e-7)


def test_lenient_family_marks_what_does_not_assemble():
    rng = np.random.default_rng(5)
    l1, l2, l3, cx, cy, branch = random_family(rng, 40)
    phi = np.linspace(0.0, 2 * np.pi, 90, endpoint=False)
    family = four_bar_family(l1, l2, l3, cx, cy, phi, order=1, branch=branch, lenient=True)
    # expected: the loop closes where |L2 − L3| ≤ |AC| ≤ L2 + L3, |AC| = |C − L1·e^{iφ}| (away from round-off)
    reach = np.abs((cx + 1j * cy)[:, None] - l1[:, None] * np.exp(1j * phi))
    inside = (reach < (l2 + l3)[:, None] - 1e-9) & (reach > np.abs(l2 - l3)[:, None] + 1e-9)
    outside = (reach > (l2 + l3)[:, None] + 1e-9) | (reach < np.abs(l2 - l3)[:, None] - 1e-9)
    assert inside.any() and outside.any()
    assert family.assembled[inside].all() and not family.assembled[outside].any()
    for motion in (family.points["B"], family.angles["coupler"], family.angles["rocker"]):
        assert np.isnan(motion.value[outside]).all() and np.isnan(motion.velocity[outside]).all()
        assert np.isfinite(motion.value[inside]).all()
    assert not family.singular[outside].any()
    # |AB| = L2 and |CB| = L3 wherever it assembles
    a, b = family.points["A"].value, family.points["B"].value
    ok = family.assembled
    assert np.allclose(np.abs(b - a)[ok], np.broadcast_to(l2[:, None], ok.shape)[ok], rtol=1e-12)
    assert np.allclose(np.abs(b - (cx + 1j * cy)[:, None])[ok], np.broadcast_to(l3[:, None], ok.shape)[ok],
                       rtol=1e-12)


def test_strict_family_names_the_member():
    # member 1: C = (10, 0) with L1 + L2 + L3 = 4 < 10: it never assembles
    with pytest.raises(AssemblyError, match="member 1 of the family"):
        four_bar_family([1.0, 1.0], [3.5, 1.5], [3.0, 1.5], [4.0, 10.0], 0.0, np.radians([0.0, 90.0]))


@pytest.mark.parametrize("change, name", [
    ({"crank": [1.0, 0.0]}, "crank"),
    ({"rocker": [np.nan, 3.0]}, "rocker"),
    ({"frame_y": [0.0, 1.0, 2.0]}, "crank, coupler"),
    ({"branch": [1, 0]}, "branch"),
    ({"phi": np.zeros((2, 2))}, "phi"),
    ({"order": 3}, "order"),
])
def test_family_refuses_bad_input_by_name(change, name):
    arguments = dict(crank=[1.0, 0.9], coupler=3.5, rocker=3.0, frame_x=4.0, frame_y=[0.0, 0.1], phi=[0.0, 1.0])
    arguments.update(change)
    with pytest.raises(InvalidParameterError, match=name):
        four_bar_family(**arguments)


def test_hinge_with_arrays_of_lengths_plain_and_in_place():
    rng = np.random.default_rng(9)
    p = PointMotion(rng.normal(size=(6, 20)) + 1j * rng.normal(size=(6, 20)), rng.normal(size=(6, 20)) + 0j,
                    rng.normal(size=(6, 20)) + 0j)
    q = PointMotion(np.full((6, 20), 0.5 + 0.2j), np.zeros((6, 20), complex), np.zeros((6, 20), complex))
    lp, lq = rng.uniform(0.5, 2.5, (2, 6, 1))
    fast = hinge(p, q, lp, lq, -1, lenient=True)
    plain = hinge_plain(p, q, lp, lq, -1, lenient=True)
    assert np.array_equal(fast.assembled, plain.assembled) and (~fast.assembled).any() and fast.assembled.any()
    ok = fast.assembled
    assert np.allclose(fast.point.value[ok], plain.point.value[ok], rtol=1e-12, atol=1e-12)
    assert np.allclose(fast.point.acceleration[ok & ~fast.singular], plain.point.acceleration[ok & ~fast.singular],
                       rtol=1e-9, atol=1e-9)
    # J is at |pJ| = L_p and |qJ| = L_q (the definition) and on the right of p → q (branch −1)
    j = fast.point.value[ok]
    assert np.allclose(np.abs(j - p.value[ok]), np.broadcast_to(lp, ok.shape)[ok], rtol=1e-12)
    assert np.allclose(np.abs(j - q.value[ok]), np.broadcast_to(lq, ok.shape)[ok], rtol=1e-12)
    assert (np.imag((j - p.value[ok]) * np.conj(q.value[ok] - p.value[ok])) <= 1e-12).all()
    with pytest.raises(AssemblyError, match="up to"):
        hinge(p, q, lp, lq, -1)
    with pytest.raises(InvalidParameterError, match="length_p"):
        hinge(p, q, np.array([[1.0], [-1.0]]), 1.0)
