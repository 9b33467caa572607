"""Solving long arrays block by block (mechanisms.linkages.chunks) changes nothing but the time.

The expected values are the same mechanism's solution of all positions at once (``_solve_block``
on the whole array), which is what the package computed before it worked in blocks. They agree to
round-off: numpy's vector loops round some elements differently depending on where an array starts
in memory, so even two solutions of the whole array may differ in the last bit.
"""

from __future__ import annotations

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.linkages.chunks import BLOCK, solve_in_chunks
from mechanisms.blocks.crank import crank_angle
from mechanisms.core.motion import fixed_point
from mechanisms.core.errors import AssemblyError, SingularPositionWarning

N = 5 * BLOCK + 123          # several blocks and a short last one


def mechanisms_to_test():
    return [mech.CrankSlider(crank=1.0, rod=3.5, offset=0.5), mech.FourBar(1.0, 3.5, 3.0, (4.0, 0.0)),
            mech.SlottedLever(crank=1.0, pivot=(0.0, 2.0)), mech.SlottedLever(crank=1.0, pivot=(1.0, 0.0)),
            mech.FourBar(0.3, 0.35, 0.4, (0.1, 0.05), branch=-1)]     # a double crank


def assert_same(a, b):
    assert a.angle_names == b.angle_names and a.point_names == b.point_names
    assert a.slider_names == b.slider_names
    pairs = [(a.angle(n), b.angle(n)) for n in a.angle_names] + [(a.point(n), b.point(n)) for n in a.point_names]
    pairs += [(a.slider(n), b.slider(n)) for n in a.slider_names]
    for x, y in pairs:
        for u, v in zip(x.derivatives(), y.derivatives()):
            assert (u is None) == (v is None)
            if u is not None:
                scale = np.nanmax(np.abs(v)) + 1.0
                np.testing.assert_allclose(u, v, rtol=0, atol=64 * np.finfo(float).eps * scale)
    for joint, values in a.extras.items():
        for key, value in values.items():
            np.testing.assert_array_equal(value, b.extras[joint][key])
    np.testing.assert_array_equal(a.singular, b.singular)


@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("index", range(5))
def test_blocks_equal_the_whole_array(index, order):
    m = mechanisms_to_test()[index]
    phi = np.linspace(0.1, 4.0 * np.pi + 0.1, N)      # two turns
    crank = crank_angle(phi, 3.0, 0.5, order)
    whole = m._solve_block(crank, order)
    blocks = solve_in_chunks(m._solve_block, crank, order, m.links)
    assert_same(blocks, whole)
    assert blocks.phi is crank.value and blocks.angle("crank") is crank


def test_short_arrays_are_solved_at_once():
    m = mech.FourBar(1.0, 3.5, 3.0, (4.0, 0.0))
    crank = crank_angle(np.linspace(0.0, 1.0, 4 * BLOCK), 1.0, 0.0, 2)
    calls = []
    solve_in_chunks(lambda c, o: calls.append(c) or m._solve_block(c, o), crank, 2, m.links)
    assert len(calls) == 1


def test_assembly_error_names_every_failing_angle_as_before():
    m = mech.FourBar(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))     # swings in ±127.17°
    phi = np.linspace(-np.pi, np.pi, N)
    with pytest.raises(AssemblyError) as blocked:
        m.solve(phi)
    with pytest.raises(AssemblyError) as whole:
        m._solve_block(crank_angle(phi, 1.0, 0.0, 2), 2)
    assert str(blocked.value) == str(whole.value)
    np.testing.assert_array_equal(blocked.value.angles, whole.value.angles)


def test_dead_centres_in_any_block_are_flagged():
    m = mech.FourBar(1.0, 4.0, 1.0, (4.0, 0.0))       # parallelogram: change points at 0 and π
    phi = np.linspace(-np.pi, 3.0 * np.pi, 4 * N + 1)   # contains −π, 0, π, 2π, 3π exactly
    with pytest.warns(SingularPositionWarning):
        sol = m.solve(phi, omega=1.0)
    expected = np.isclose(np.sin(phi), 0.0, atol=1e-12)
    np.testing.assert_array_equal(sol.singular, expected)


def test_fixed_pivots_stay_views_of_one_number():
    # expected: the pivots O = 0 and C = (4, 0) m, at rest, at every position, without memory of their own
    sol = mech.FourBar(1.0, 3.5, 3.0, (4.0, 0.0)).solve(np.linspace(0.0, 6.0, N), 1.0)
    for name, where in (("O", 0j), ("C", 4 + 0j)):
        for array, number in zip(sol.point(name).derivatives(), (where, 0j, 0j)):
            assert array.shape == (N,) and array.strides == (0,)
            np.testing.assert_array_equal(array, number)


def test_a_number_that_changes_between_blocks_becomes_an_array():
    # expected: a made-up solution whose point P is one number per block (a broadcast view), 0 in the
    # first blocks and then 1 m: gathered, P must be 0 before the block that starts at φ ≥ 2.5 and 1 from it on
    phi = np.linspace(0.0, 5.0, N)
    starts = np.arange(0, N, BLOCK)
    first_one = starts[np.argmax(phi[starts] >= 2.5)]

    def solve(crank, order):
        number = 1.0 + 0j if crank.value[0] >= 2.5 else 0j
        point = mech.PointMotion(fixed_point(number, crank.value, 0).value)
        return mech.Solution(crank.value, order, angles={"crank": crank}, points={"P": point}, links={})

    sol = solve_in_chunks(solve, crank_angle(phi, 1.0, 0.0, 0), 0, {})
    expected = np.where(np.arange(N) >= first_one, 1.0 + 0j, 0j)
    np.testing.assert_array_equal(sol.point("P").value, expected)
    assert 0 < first_one < N - BLOCK
