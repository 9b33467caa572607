"""Tests of the mechanism base (mechanisms.linkages.base): solutions looked up by name, points on demand."""

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.linkages.base import registry
from mechanisms.core.errors import InvalidParameterError
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


EVERY_MECHANISM = [mech.CrankSlider(0.08, 0.3, 0.02), mech.FourBar(1.0, 3.5, 3.0, (4.0, 0.0)),
                   mech.LambdaMechanism(2.0, 6.5, 5.0), mech.SlottedLever(0.1, (0, 0.3)),
                   mech.SlottedLever(0.1, (0, 0.1)), mech.RockerInBlock(2.0, (0, 4.0)),
                   mech.Shaper(0.1, (0, -0.3), 0.5, 0.2, 0.2), mech.SlottedRockers(0.1, (0, 0.3), (0.1, 0.35), 0.2),
                   mech.SliderOnCoupler(0.08, 0.3, (0.2, 0.1), 1.2)]


@pytest.mark.parametrize("m", EVERY_MECHANISM, ids=lambda m: type(m).__name__)
def test_one_crank_angle_given_as_a_number(m):
    # expected: the same mechanism's solution of an array of angles, at the angle in question
    phi = np.radians([10.0, 37.0, 100.0])
    array = m.solve(phi, 2.0, 0.5)
    for k, angle in enumerate(phi):
        one = m.solve(angle, 2.0, 0.5)
        pairs = [(one.angle(n), array.angle(n)) for n in array.angle_names]
        pairs += [(one.point(n), array.point(n)) for n in array.point_names]
        pairs += [(one.slider(n), array.slider(n)) for n in array.slider_names]
        for single, many in pairs:
            for u, v in zip(single.derivatives(), many.derivatives()):
                assert np.ndim(u) == 0
                np.testing.assert_allclose(u, np.asarray(v)[k], rtol=1e-13, atol=1e-15)
        assert np.ndim(one.singular) == 0 and bool(one.singular) == bool(array.singular[k])
