"""Tests of Chebyshev's lambda mechanism (mechanisms/lambda_mechanism.py)."""

import warnings

import numpy as np
import pytest

from mechanisms import AssemblyError, SingularPositionWarning, InvalidParameterError, LambdaMechanism
from mechanisms.analysis.four_bar import straight_part
from mechanisms.verify import constraint_residual, distance_deviation, generic_errors


def test_against_the_generic_solver():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(0.0, 360.0, 10.0))
    # expected: Newton on the loop closure, continued from φ = 0 (the reference is independent)
    assert max(generic_errors(m, phi, omega=1.0, alpha=0.3)) < 1e-11
    sol = m.solve(phi, omega=1.0)
    assert constraint_residual(m, sol) < 1e-13 and distance_deviation(m, sol) < 1e-13


def test_the_book_letters_the_joints_o_a_b_p_c():
    # expected: chapter 4, §4.9 letters the lambda mechanism O, A, B (rocker joint), P (coupler end), C (rocker
    # pivot); the package's names are those letters (the source's B, C, D are P, B, C)
    m = LambdaMechanism(2.0, 6.5, 5.0)
    sol = m.solve(np.radians([20.0]), order=0)
    assert set(sol.point_names) == {"O", "A", "B", "P", "C"}
    assert sol.point("C").value[0] == -5.0 + 0j                       # the rocker's pivot at (−d, 0)
    assert m.links == {"crank": "O", "coupler": "A", "rocker": "C"}


def test_p_is_the_far_end_of_the_coupler_and_b_lies_above():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    sol = m.solve(phi, omega=1.0)
    a, b, p = (sol.point(n).value for n in "ABP")
    assert np.allclose(p, 2 * b - a)                                  # B the midpoint, by definition
    assert np.allclose(np.abs(b + 5.0), 6.5) and np.all(b.imag > 0)   # on the rocker, above the frame line
    assert np.allclose(sol.point("P").velocity, 2 * sol.point("B").velocity - sol.point("A").velocity)


def test_trajectory_of_p_is_symmetric_about_the_vertical_through_c():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(0.0, 180.0, 5.0))
    p_plus = m.solve(phi, order=0).point("P").value
    p_minus = m.solve(-phi, order=0).point("P").value
    # expected: the mirror image in x = −d (A, C, P lie on a circle about B with AP a diameter)
    assert np.allclose(p_minus, -2 * 5.0 - np.conj(p_plus).real + 1j * p_plus.imag)


def test_straight_part_of_p():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(-180.0, 180.01, 0.25))
    p = m.solve(phi, order=0).point("P").value
    part = straight_part(phi, p, 720, 0.01)
    # expected: the best line is horizontal (the symmetry above), the part is symmetric about
    # φ = 0, and a brute-force check of the deviation from the horizontal through the mean
    assert abs(part.direction.imag) < 1e-9
    assert part.phi[0] == pytest.approx(-part.phi[1])
    inside = p[np.abs(phi) <= part.phi[1] + 1e-12]
    assert np.max(np.abs(inside.imag - inside.imag.mean())) == pytest.approx(part.deviation, rel=1e-9)
    assert part.length == pytest.approx(np.ptp(inside.real), rel=1e-9)
    assert part.length > 7.5 and np.degrees(part.phi[1]) > 70.0    # more than 1/3 of a turn


def test_drop_shaped_curve_at_the_change_point():
    # d = 11 = 2b − r: a change point at φ = 0 (A, B, C in line)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        drop = LambdaMechanism(2.0, 6.5, 11.0, keep_side=True).solve(np.radians(np.arange(-180.0, 181.0, 1.0)))
        smooth = LambdaMechanism(2.0, 6.5, 11.0).solve(np.radians(np.arange(-180.0, 181.0, 1.0)))
    p = drop.point("P").value
    # by hand at φ = 0: A = (2, 0), B = (−4.5, 0), P = (−11, 0): the tip of the drop at C
    assert abs(p[180] - (-11.0)) < 1e-6
    assert np.all(drop.point("B").value.imag >= -1e-9)                 # keeps its side
    assert drop.singular[180] and smooth.singular[180]
    # the smooth continuation passes into the mirror assembly: B above after φ = 0 (the stretch
    # of crank angles that holds the branch), below before it
    assert np.all(smooth.point("B").value[181:].imag > 0) and np.all(smooth.point("B").value[:180].imag < 0)


def test_errors():
    with pytest.raises(InvalidParameterError, match="half_coupler"):
        LambdaMechanism(2.0, 0.0, 5.0)
    with pytest.raises(AssemblyError, match="lambda"):
        LambdaMechanism(2.0, 3.0, 11.0).solve(np.radians([0.0, 180.0]))
