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


def test_b_is_the_far_end_of_the_coupler_and_c_lies_above():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    sol = m.solve(phi, omega=1.0)
    a, c, b = (sol.point(n).value for n in "ACB")
    assert np.allclose(b, 2 * c - a)                                  # C the midpoint, by definition
    assert np.allclose(np.abs(c + 5.0), 6.5) and np.all(c.imag > 0)   # on the rocker, above the frame line
    assert np.allclose(sol.point("B").velocity, 2 * sol.point("C").velocity - sol.point("A").velocity)


def test_trajectory_of_b_is_symmetric_about_the_vertical_through_d():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(0.0, 180.0, 5.0))
    b_plus = m.solve(phi, order=0).point("B").value
    b_minus = m.solve(-phi, order=0).point("B").value
    # expected: the mirror image in x = −d (A, D, B lie on a circle about C with AB a diameter)
    assert np.allclose(b_minus, -2 * 5.0 - np.conj(b_plus).real + 1j * b_plus.imag)


def test_straight_part_of_b():
    m = LambdaMechanism(2.0, 6.5, 5.0)
    phi = np.radians(np.arange(-180.0, 180.01, 0.25))
    b = m.solve(phi, order=0).point("B").value
    part = straight_part(phi, b, 720, 0.01)
    # expected: the best line is horizontal (the symmetry above), the part is symmetric about
    # φ = 0, and a brute-force check of the deviation from the horizontal through the mean
    assert abs(part.direction.imag) < 1e-9
    assert part.phi[0] == pytest.approx(-part.phi[1])
    inside = b[np.abs(phi) <= part.phi[1] + 1e-12]
    assert np.max(np.abs(inside.imag - inside.imag.mean())) == pytest.approx(part.deviation, rel=1e-9)
    assert part.length == pytest.approx(np.ptp(inside.real), rel=1e-9)
    assert part.length > 7.5 and np.degrees(part.phi[1]) > 70.0    # more than 1/3 of a turn


def test_drop_shaped_curve_at_the_change_point():
    # d = 11 = 2b − r: a change point at φ = 0 (A, C, D in line)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        drop = LambdaMechanism(2.0, 6.5, 11.0, keep_side=True).solve(np.radians(np.arange(-180.0, 181.0, 1.0)))
        smooth = LambdaMechanism(2.0, 6.5, 11.0).solve(np.radians(np.arange(-180.0, 181.0, 1.0)))
    b = drop.point("B").value
    # by hand at φ = 0: A = (2, 0), C = (−4.5, 0), B = (−11, 0): the tip of the drop at D
    assert abs(b[180] - (-11.0)) < 1e-6
    assert np.all(drop.point("C").value.imag >= -1e-9)                 # keeps its side
    assert drop.singular[180] and smooth.singular[180]
    # the smooth continuation passes into the mirror assembly: C above after φ = 0 (the stretch
    # of crank angles that holds the branch), below before it
    assert np.all(smooth.point("C").value[181:].imag > 0) and np.all(smooth.point("C").value[:180].imag < 0)


def test_errors():
    with pytest.raises(InvalidParameterError, match="half_coupler"):
        LambdaMechanism(2.0, 0.0, 5.0)
    with pytest.raises(AssemblyError, match="lambda"):
        LambdaMechanism(2.0, 3.0, 11.0).solve(np.radians([0.0, 180.0]))
