"""The one angle-wrapping convention (mechanisms.core.angles): (−π, π] and (−180°, 180°].

Expected values: the reduction done here in 60-digit decimal arithmetic with π to 60 digits (an
independent reference), and the ends of the interval by hand.
"""

from __future__ import annotations

import math
from decimal import Decimal, getcontext

import numpy as np
import pytest

from mechanisms.core.angles import wrap_angle, wrap_degrees

getcontext().prec = 60
PI = Decimal("3.14159265358979323846264338327950288419716939937510582097494459")


def _reference(angle: float) -> float:
    """``angle`` (a double, taken as exact) reduced to (−π, π] in 60-digit decimal arithmetic."""
    x = Decimal(angle)
    turns = (x / (2 * PI)).to_integral_value()
    r = x - turns * 2 * PI
    if r <= -PI:
        r += 2 * PI
    elif r > PI:
        r -= 2 * PI
    return float(r)


def test_inside_the_interval_angles_are_returned_exactly():
    inside = np.array([0.0, -0.0, 1e-300, -3.0, 3.1, math.pi, np.nextafter(-math.pi, 0.0)])
    np.testing.assert_array_equal(wrap_angle(inside), inside)


def test_the_ends():
    # π stays π; −π is the same direction and becomes π; 3π becomes π (by hand)
    assert wrap_angle(math.pi) == math.pi
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(3 * math.pi) == pytest.approx(math.pi, abs=1e-15)
    assert float(wrap_degrees(-180.0)) == 180.0 and float(wrap_degrees(180.0)) == 180.0
    assert float(wrap_degrees(540.0)) == 180.0 and float(wrap_degrees(-190.0)) == 170.0


@pytest.mark.parametrize("angle", [7.0, -7.0, 100.0, 12345.678, -9.87e6, 1e10, 1e15, -1e15, 3.3e17])
def test_large_angles_against_a_60_digit_reference(angle):
    # one unit in the last place of π (4.4e-16) plus numpy's sine and cosine: 1e-15 rad at any size;
    # subtracting multiples of the double nearest 2π would be off by ~1e-2 rad at 1e15
    assert float(wrap_angle(angle)) == pytest.approx(_reference(angle), abs=1e-15)
    assert -math.pi < float(wrap_angle(angle)) <= math.pi


def test_arrays_keep_their_shape():
    angles = np.linspace(-20.0, 20.0, 12).reshape(3, 4)
    wrapped = wrap_angle(angles)
    assert wrapped.shape == (3, 4)
    np.testing.assert_allclose(np.exp(1j * wrapped), np.exp(1j * angles), atol=1e-14)


def test_degrees_just_beyond_the_ends_stay_inside():
    # by hand: 180 + 1 ulp is −180 + 1 ulp's worth of turn, i.e. just above −180; −(2⁵³ − 1)° is −31° mod 360
    above = float(np.nextafter(180.0, 200.0))
    assert -180.0 < float(wrap_degrees(above)) <= 180.0
    assert float(wrap_degrees(-(2.0**53 - 1))) == -31.0
