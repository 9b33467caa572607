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
    with pytest.raises(errors.InvalidParameterError, match="phi must be finite"):
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
