"""The one validation path (mechanisms.core.validate): every kind of bad value gets the package's error,
naming the parameter; nothing is coerced silently. Expected behaviour is written here case by case."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis.energy import LinkMass, Spring
from mechanisms.core.errors import InvalidParameterError
from mechanisms.core.validate import (require_finite, require_flag, require_length, require_non_negative,
                                      require_pair)


@pytest.mark.parametrize("value", [True, False, np.True_, "0.5", b"1", [0.5], np.array([0.5]), 1 + 0j, 10**400,
                                   math.nan, math.inf, -math.inf, None, object()])
def test_a_number_is_a_real_number_and_nothing_else(value):
    with pytest.raises(InvalidParameterError, match="offset"):
        require_finite("offset", value)


@pytest.mark.parametrize("value, expected", [(0.5, 0.5), (2, 2.0), (np.float32(0.25), 0.25), (np.int64(3), 3.0),
                                             (np.array(1.5), 1.5)])
def test_real_numbers_of_any_kind_are_taken(value, expected):
    assert require_length("crank", value) == expected and type(require_length("crank", value)) is float


@pytest.mark.parametrize("value", [0.0, -1e-300, -1.0])
def test_a_length_is_positive(value):
    with pytest.raises(InvalidParameterError, match="crank must be a finite length > 0 m"):
        require_length("crank", value)


def test_non_negative_takes_zero_and_refuses_below():
    assert require_non_negative("mass", 0.0) == 0.0
    with pytest.raises(InvalidParameterError, match="mass must be a finite number ≥ 0 kg"):
        require_non_negative("mass", -1e-12, "kg")


@pytest.mark.parametrize("value", ["12", b"12", 1 + 2j, (1.0,), (1.0, 2.0, 3.0), (1.0, "x"), (math.nan, 0.0), None])
def test_a_pair_is_two_real_numbers(value):
    with pytest.raises(InvalidParameterError, match="frame"):
        require_pair("frame", value)


def test_pairs_of_any_sequence_kind():
    assert require_pair("frame", [0.4, 0]) == (0.4, 0.0)
    assert require_pair("frame", np.array([0.4, 0.1])) == (0.4, 0.1)


@pytest.mark.parametrize("value", ["False", "True", 0, 1, None, np.array([True])])
def test_a_flag_is_a_bool(value):
    with pytest.raises(InvalidParameterError, match="keep_side"):
        require_flag("keep_side", value)


def test_the_reviews_examples():
    # crank=True was taken as 1 m, frame='12' as (1, 2), keep_side='False' as true, mass="abc" a bare ValueError
    with pytest.raises(InvalidParameterError, match="crank"):
        mech.CrankSlider(crank=True, rod=0.3)
    with pytest.raises(InvalidParameterError, match="frame"):
        mech.FourBar(0.1, 0.35, 0.3, frame="12")
    with pytest.raises(InvalidParameterError, match="keep_side"):
        mech.FourBar(0.1, 0.35, 0.3, frame=(0.4, 0.0), keep_side="False")
    with pytest.raises(InvalidParameterError, match="mass"):
        LinkMass(mass="abc")
    with pytest.raises(InvalidParameterError, match="stiffness"):
        Spring("crank", stiffness=-1.0, anchor=0j)
