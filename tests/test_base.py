"""Tests of the mechanism base (mechanisms.base): solutions looked up by name, points on demand."""

import numpy as np
import pytest

from mechanisms.base import registry
from mechanisms.errors import InvalidParameterError
from mechanisms_for_tests import ScotchYoke

PHI = np.radians([0.0, 90.0, 180.0])


def test_lookup_by_name_and_helpful_key_errors():
    sol = ScotchYoke(0.1).solve(PHI, 2.0)
    assert sol.angle_names == ["crank"] and sol.point_names == ["O", "A", "B"] and sol.slider_names == ["B"]
    assert len(sol) == 3
    with pytest.raises(KeyError, match="no point named 'C'; known: O, A, B"):
        sol.point("C")
    with pytest.raises(KeyError, match="no link named 'rocker'"):
        sol.point_on("rocker", 0.1)


def test_point_on_link_on_demand():
    # expected: the crank's mid-point turning at 2 rad/s: r = 0.05 e^{iφ}, v = 2i r, a = −4 r (by hand)
    sol = ScotchYoke(0.1).solve(PHI, 2.0)
    mid = sol.point_on("crank", 0.05)
    r = 0.05 * np.exp(1j * PHI)
    np.testing.assert_allclose(mid.value, r, atol=1e-17)
    np.testing.assert_allclose(mid.velocity, 2j * r, atol=1e-16)
    np.testing.assert_allclose(mid.acceleration, -4 * r, atol=1e-15)
    left = sol.point_on("crank", 0.1, 0.02)  # 2 cm to the left of the crank
    np.testing.assert_allclose(left.value, (0.1 + 0.02j) * np.exp(1j * PHI), atol=1e-17)


def test_order_zero_has_no_derivatives():
    sol = ScotchYoke(0.1).solve(PHI, order=0)
    assert sol.point("B").velocity is None and sol.slider("B").acceleration is None


def test_bad_order_and_parameters():
    with pytest.raises(InvalidParameterError, match="order"):
        ScotchYoke(0.1).solve(PHI, order=3)
    with pytest.raises(InvalidParameterError, match="crank must be a finite length"):
        ScotchYoke(-0.1)


def test_describe_and_parameters():
    yoke = ScotchYoke(0.1)
    assert yoke.parameters() == {"crank": 0.1}
    assert yoke.describe() == "ScotchYoke: crank = 0.1 m"
    assert repr(yoke) == "ScotchYoke(crank=0.1)"
    assert "ScotchYoke" not in registry  # no cli_name: not offered by the command line


def test_point_on_rejects_non_finite_coordinates():
    sol = ScotchYoke(0.1).solve(PHI, 2.0)
    with pytest.raises(InvalidParameterError, match="along must be a finite number"):
        sol.point_on("crank", np.nan)
    with pytest.raises(InvalidParameterError, match="left must be a finite number"):
        sol.point_on("crank", 0.1, np.inf)
