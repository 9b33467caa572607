"""Markdown tables for people (present/tables.py): every expected string written by hand."""

import numpy as np
import pytest

import mechanisms as mech


def test_markdown_table_prints_numbers_in_their_formats():
    table = mech.markdown_table(["φ, °", "s, m"], [[0, 0.38], [30, "—"]], [".0f", ".3f"])
    assert table.text == "| φ, ° | s, m |\n|---:|---:|\n| 0 | 0.380 |\n| 30 | — |"


def test_markdown_table_prints_a_negative_zero_without_its_sign():
    # -0.0, -0.0001 and -4e-17 round to zero in ".3f": "0.000", as a person writes it;
    # -0.0006 rounds to -0.001 and keeps its sign
    rows = [[-0.0, -0.0001], [np.float64(-4e-17), -0.0006]]
    table = mech.markdown_table(["a", "b"], rows, ".3f")
    assert table.text == "| a | b |\n|---:|---:|\n| 0.000 | 0.000 |\n| 0.000 | -0.001 |"


def test_negative_zero_keeps_the_format_s_sign_width_and_style():
    # "+.2f" writes +0.00 for zero; "8.1f" pads to eight characters; ".0f" and "g" write 0;
    # ".1e" writes 0.0e+00; "d" on an integer is untouched
    rows = [[-0.001, -0.01, -0.2, -0.0, -0.0, -7]]
    table = mech.markdown_table(list("abcdef"), rows, ["+.2f", "8.1f", ".0f", "g", ".1e", "d"])
    assert table.text.splitlines()[2] == "| +0.00 |      0.0 | 0 | 0 | 0.0e+00 | -7 |"


def test_a_tiny_negative_number_in_exponent_form_keeps_its_sign():
    # -3e-20 in ".1e" is "-3.0e-20": not zero, so its sign stays; nan and -inf stay as they are
    table = mech.markdown_table(["a", "b", "c"], [[-3e-20, float("nan"), float("-inf")]], ".1e")
    assert table.text.splitlines()[2] == "| -3.0e-20 | nan | -inf |"


def test_number_prints_no_negative_zero_and_none_as_a_dash():
    from mechanisms import number
    assert number(-1e-17, ".4f", "m") == "0.0000 m"
    assert number(-0.0, ".3f") == "0.000"
    assert number(-0.0126, ".2f") == "-0.01"
    assert number(None) == "—"
    assert number(complex(0.3, -2e-17), ".4f") == "(0.3000, 0.0000)"
    assert number(complex(-1.5, 2.25), ".2f", "m") == "(-1.50, 2.25) m"


def test_markdown_table_prints_none_as_a_dash():
    from mechanisms import markdown_table
    assert markdown_table(["x"], [[None], [1.0]], ".1f").text.splitlines()[2:] == ["| — |", "| 1.0 |"]


def test_show_messages_prints_a_warning_and_an_error_of_the_package_and_goes_on(capsys):
    # by hand: L2 = 0.08 < L1 = 0.1 (axial), so |sin φ| ≤ 0.8: two ranges, ±53.13° and 180° ∓ 53.13°;
    # φ = 90° lies in neither
    with mech.show_messages(width=1000):
        mech.CrankSlider(crank=0.1, rod=0.08).solve(np.radians([0.0, 90.0]), omega=1.0)
    assert capsys.readouterr().out == (
        "AssemblyError: the rod cannot reach the guide (rod = 0.08 m < crank + |offset| = 0.1 m, so the crank "
        "cannot turn fully) at crank angle(s) 90°; it assembles only for crank angles in [-53.13°, 53.13°] and "
        "[126.87°, 233.13°], mod 360°\n")
    # by hand: L2 = L1 + |e| = 1.5; at φ = −90°, h_A = L1 sin φ − e = −1.5 = −L2, the coupler is
    # perpendicular to the guide (a singular position); at φ = 0°, |h_A| = 0.5 < L2
    with mech.show_messages(width=40):
        solution = mech.CrankSlider(crank=1.0, rod=1.5, offset=0.5).solve(np.radians([-90.0, 0.0]), omega=1.0)
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("SingularPositionWarning: ") and all(len(line) <= 40 for line in lines)
    assert list(solution.singular) == [True, False]


def test_show_messages_lets_other_exceptions_through():
    with pytest.raises(ZeroDivisionError):
        with mech.show_messages():
            1 / 0
