"""Browser discovery of the site test, with fake browsers (files made here), not the machine's own."""

from __future__ import annotations

import os
import stat

import pytest

from find_browser import ENVIRONMENT_VARIABLE, NAMES, BrowserNotFound, find_browser


def _fake(path):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("#!/bin/sh\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def test_the_environment_variable_comes_first(tmp_path):
    chosen = _fake(tmp_path / "my browser" / "chrome")
    other = _fake(tmp_path / "bin" / "chromium")
    found = find_browser({ENVIRONMENT_VARIABLE: str(chosen)}, search_path=str(other.parent), use_playwright=False)
    assert found == chosen


def test_an_environment_variable_to_nothing_is_an_error_not_a_fallback(tmp_path):
    _fake(tmp_path / "bin" / "chromium")
    with pytest.raises(BrowserNotFound, match=ENVIRONMENT_VARIABLE):
        find_browser({ENVIRONMENT_VARIABLE: str(tmp_path / "missing")}, search_path=str(tmp_path / "bin"),
                     use_playwright=False)


@pytest.mark.parametrize("name", NAMES)
def test_each_usual_name_on_the_path(tmp_path, name):
    browser = _fake(tmp_path / "bin" / name)
    assert find_browser({}, search_path=str(browser.parent), paths=(), use_playwright=False) == browser


def test_an_install_path_when_no_name_is_on_the_path(tmp_path):
    app = _fake(tmp_path / "Applications" / "Google Chrome.app" / "Contents" / "MacOS" / "Google Chrome")
    found = find_browser({}, search_path=str(tmp_path / "empty"), paths=(str(tmp_path / "nothing"), str(app)),
                         use_playwright=False)
    assert found == app


def test_nothing_found_says_what_was_looked_for(tmp_path):
    with pytest.raises(BrowserNotFound) as error:
        find_browser({}, search_path=str(tmp_path), paths=(str(tmp_path / "nowhere"),), use_playwright=False)
    message = str(error.value)
    assert ENVIRONMENT_VARIABLE in message and "chromium" in message and str(tmp_path / "nowhere") in message
    assert "apt-get install chromium" in message


def test_the_site_tests_machine_has_one():
    # the machine that runs `make test` must have a browser: the site test fails without one
    assert os.path.isfile(find_browser())
