"""Renamed public names keep working for one release, with a DeprecationWarning that names the new one."""

import warnings

import pytest

import mechanisms as mech
from mechanisms.core import errors


def test_dead_centre_warning_is_the_singular_position_warning_under_its_old_name():
    with pytest.warns(DeprecationWarning, match="SingularPositionWarning"):
        old = errors.DeadCentreWarning
    assert old is errors.SingularPositionWarning
    with pytest.warns(DeprecationWarning, match="SingularPositionWarning"):
        assert mech.__getattr__("DeadCentreWarning") is mech.SingularPositionWarning
    assert "DeadCentreWarning" not in dir(mech)           # not listed: new code uses the new name


def test_the_new_name_needs_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert issubclass(mech.SingularPositionWarning, UserWarning)
