"""Tests of the command line for the four-bar and the lambda mechanism (mechanisms/cli.py)."""

import csv
import io
import json

import numpy as np
import pytest

from mechanisms.cli import main
from mechanisms.verify import solve_constraints
from mechanisms import FourBar, LambdaMechanism

FOUR_BAR = ["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame", "0.4,0.05",
            "--omega", "10"]


def run(argv, capsys):
    status = main(argv)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_json_against_the_generic_solver(capsys):
    status, out, _ = run(FOUR_BAR + ["--branch", "-1", "--angles", "0:360:45", "--format", "json"], capsys)
    assert status == 0
    table = json.loads(out)
    assert table["mechanism"] == "four-bar"
    assert table["parameters"]["frame"] == [0.4, 0.05] and table["parameters"]["branch"] == -1
    phi = np.radians([row["phi_deg"] for row in table["rows"]])
    assert phi.size == 8
    m = FourBar(0.1, 0.35, 0.3, (0.4, 0.05), -1)
    start = m.solve(phi, order=0)
    # expected: Newton on the loop closure from guesses 0.02 rad off, per position
    generic = solve_constraints(m.constraints, np.array([start.angle("coupler").value, start.angle("rocker").value])
                                + 0.02, phi, omega=10.0)
    rocker = np.array([[r["links"]["rocker"][k] for k in ("angle_deg", "omega", "alpha")] for r in table["rows"]])
    assert np.allclose(np.radians(rocker[:, 0]), generic.q[1])
    assert np.allclose(rocker[:, 1], generic.q_t[1]) and np.allclose(rocker[:, 2], generic.q_tt[1])
    assert set(table["rows"][0]["points"]) == {"O", "A", "B", "C"}
    assert set(table["rows"][0]["links"]) == {"crank", "coupler", "rocker"}


def test_lambda_text_and_csv(capsys):
    args = ["table", "lambda", "--crank", "2", "--half-coupler", "6.5", "--ground", "5", "--omega", "1"]
    status, out, _ = run(args + ["--positions", "12"], capsys)
    assert status == 0 and out.startswith("lambda: crank = 2 m, half_coupler = 6.5 m, ground = 5 m")
    assert "point P" in out and "point C" in out          # the book's letters (§4.9): coupler end P, pivot C
    status, out, _ = run(args + ["--positions", "4", "--format", "csv", "--point", "M=coupler:6.5"], capsys)
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 4
    sol = LambdaMechanism(2.0, 6.5, 5.0).solve(np.radians([0.0, 90.0, 180.0, 270.0]), omega=1.0)
    # a point at u = b on the coupler is the joint B (by definition of the mechanism)
    assert np.allclose([float(r["M.x"]) for r in rows], sol.point("B").x)
    assert np.allclose([float(r["P.y"]) for r in rows], sol.point("P").y)


def test_assembly_error_is_reported(capsys):
    status, _, err = run(["table", "four-bar", "--crank", "2", "--coupler", "2", "--rocker", "2", "--frame", "3,0",
                          "--omega", "1"], capsys)
    assert status == 2 and "cannot be assembled" in err and "104.48°" in err


def test_bad_branch_and_frame(capsys):
    status, _, err = run(FOUR_BAR + ["--branch", "0"], capsys)
    assert status == 2 and "branch" in err
    assert main(FOUR_BAR[:8] + ["--frame", "1", "--omega", "1"]) == 2     # argparse's usage error
    status, _, err = run(["table", "lambda", "--crank", "-2", "--half-coupler", "6.5", "--ground", "5",
                          "--omega", "1"], capsys)
    assert status == 2 and "crank" in err


def test_negative_frame_coordinates_with_an_equals_sign(capsys):
    # argparse reads "-0.4,0.05" as an option; "--frame=-0.4,0.05" passes it as a value
    status, out, _ = run(["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3",
                          "--frame=-0.4,0.05", "--omega", "1", "--positions", "3", "--format", "json"], capsys)
    assert status == 0 and json.loads(out)["parameters"]["frame"] == [-0.4, 0.05]
