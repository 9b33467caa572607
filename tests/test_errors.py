"""Tests of mechanisms.core.errors: every message names what the student can act on."""

import math

import numpy as np
import pytest

from mechanisms.core import errors, validate
from mechanisms.blocks.crank import crank_angle


@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf, "abc", None])
def test_require_length_names_parameter_and_value(value):
    with pytest.raises(errors.InvalidParameterError, match=r"rod must be a finite length > 0 m: got rod = ") as info:
        validate.require_length("rod", value)
    assert info.value.name == "rod"
    assert isinstance(info.value, ValueError)


def test_require_length_accepts_positive():
    assert validate.require_length("crank", 0.08) == 0.08


@pytest.mark.parametrize("value", [0, 2, "+1", True, 1.5])
def test_branch_must_be_plus_or_minus_one(value):
    with pytest.raises(errors.InvalidParameterError, match=r"branch must be \+1 or -1"):
        validate.require_branch(value)


def test_branch_accepts_both():
    assert validate.require_branch(1) == 1 and validate.require_branch(-1) == -1


@pytest.mark.parametrize("value", [3, -1, 1.5, True])
def test_order_must_be_0_1_or_2(value):
    with pytest.raises(errors.InvalidParameterError, match="order must be 0"):
        validate.require_order(value)


def test_assembly_error_names_angles_and_range():
    err = errors.AssemblyError("the rod cannot reach the guide", np.radians([200.0, 210.0]),
                               valid_range=(np.radians(-30.0), np.radians(180.0)))
    text = str(err)
    assert "the rod cannot reach the guide" in text
    assert "200°, 210°" in text
    assert "[-30.00°, 180.00°]" in text


def test_describe_angles_shortens_long_lists():
    text = errors.describe_angles(np.radians(np.arange(10.0)), limit=3)
    assert text.startswith("0°, 1°, 2°") and "10 angles in all" in text


def test_crank_angle_rejects_nan_and_bad_speed():
    with pytest.raises(errors.InvalidParameterError, match="phi must be finite"):  # "finite real numbers"
        crank_angle([0.0, math.nan], 1.0)
    with pytest.raises(errors.InvalidParameterError, match="omega must be finite"):
        crank_angle([0.0], math.inf)
    with pytest.raises(errors.InvalidParameterError, match="alpha must be finite"):
        crank_angle([0.0], 1.0, math.nan)


def test_crank_angle_broadcasts_and_truncates():
    a = crank_angle([0.0, 1.0], 2.0, 3.0, order=2)
    assert a.omega.tolist() == [2.0, 2.0] and a.alpha.tolist() == [3.0, 3.0]
    assert crank_angle([0.0], 2.0, order=0).omega is None
    assert crank_angle([0.0], 2.0, order=1).alpha is None


def test_a_length_beyond_the_supported_range_names_the_range():
    # the supported lengths: 2^-510 … 2^510 m (core.validate.LENGTH_MIN/MAX); outside, the parameter is named
    for value in (2.0**511, 2.0**-511):
        with pytest.raises(errors.InvalidParameterError, match=r"rod must be a length from .* m to .* m: got rod"):
            validate.require_length("rod", value)
    assert validate.require_length("rod", 2.0**510) == 2.0**510


def test_unknown_name_is_a_mechanism_error_and_a_key_error():
    error = errors.UnknownNameError("link", "rocker", ["crank", "coupler"])
    assert isinstance(error, errors.MechanismError) and isinstance(error, KeyError)
    assert str(error) == "no link named 'rocker'; known: crank, coupler"


def test_an_error_at_every_crank_angle_says_so_once_and_names_no_full_turn():
    # issue 18: "at no crank angle at crank angle(s) …" and "assembles only for [-180°, 180°]" contradicted the error
    nowhere = str(errors.AssemblyError("the links cannot reach", np.radians([0.0, 30.0]), nowhere=True))
    assert nowhere == "the links cannot reach at crank angle(s) 0°, 30°; it assembles at no crank angle"
    full = str(errors.AssemblyError("the joints coincide", np.radians([0.0]), valid_range=(-math.pi, math.pi)))
    assert "assembles only" not in full


@pytest.mark.parametrize("order", [np.array([1, 2]), np.array(2), 2.0, "2", None, [2]])
def test_an_order_that_is_not_a_whole_number_is_refused(order):
    if isinstance(order, np.ndarray) and order.ndim == 0:
        assert validate.require_order(order.item()) == 2
        return
    with pytest.raises(errors.InvalidParameterError, match="order must be 0"):
        validate.require_order(order)


@pytest.mark.parametrize("phi", [None, "0.5", True, [0.1j], [[0.1], [0.2, 0.3]], {"a": 1}, [None]])
def test_crank_angles_are_real_numbers_not_anything_numpy_converts(phi):
    # solve(None) was reported as "phi = nan" (np.asarray(None, float)); a string as its digits
    with pytest.raises(errors.InvalidParameterError, match="phi must be") as info:
        crank_angle(phi, 1.0)
    assert "nan" not in str(info.value)


def test_rates_of_the_wrong_shape_or_size_are_named():
    with pytest.raises(errors.InvalidParameterError, match=r"omega must be one number or one per crank angle"):
        crank_angle([0.1, 0.2, 0.3], [1.0, 2.0])
    with pytest.raises(errors.InvalidParameterError, match=r"omega must be of magnitude at most 1e\+50"):
        crank_angle([0.1], 1e160)
    with pytest.raises(errors.InvalidParameterError, match=r"alpha must be of magnitude at most 1e\+100"):
        crank_angle([0.1], 1.0, -1e200)
    a = crank_angle([[0.1, 0.2]], [[1.0], ], order=1)
    assert a.omega.shape == (1, 2)


def test_a_failing_angle_is_never_printed_inside_the_range_the_message_names():
    # issue 19's re-read: "at 127.169°; it assembles only for [-127.17°, 127.17°]" contradicted itself.
    # By hand: 127.1695° lies outside [-127.1694°, 127.1694°]; with three decimals the range prints
    # 127.169 and the angle (seven digits) 127.1695, which is outside it
    error = errors.AssemblyError("the links cannot reach", np.radians([127.1695]),
                                 valid_range=(np.radians(-127.1694), np.radians(127.1694)))
    assert str(error) == ("the links cannot reach at crank angle(s) 127.1695°; it assembles only for crank "
                          "angles in [-127.169°, 127.169°]")
    # a clear case keeps the short form
    plain = errors.AssemblyError("the rod cannot reach", np.radians([250.0]),
                                 valid_range=(np.radians(-44.43), np.radians(224.43)))
    assert str(plain) == ("the rod cannot reach at crank angle(s) 250°; it assembles only for crank angles in "
                          "[-44.43°, 224.43°]")
