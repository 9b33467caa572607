"""Tests of the command line's generic parts (mechanisms.cli), on a Scotch yoke registered here.

Expected values: the yoke's slider is at s = r cos φ with v = −r ω sin φ (by hand).
"""

import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

import mechanisms as mech
from mechanisms import cli
from mechanisms.cli import main
from mechanisms.linkages.base import Parameter
from mechanisms.core.errors import InvalidParameterError
from mechanisms_for_tests import ScotchYoke


class RegisteredYoke(ScotchYoke):
    """Scotch yoke (registered for the command line in this test only)."""

    cli_name = "test-yoke"
    links = {"crank": "O"}
    cli_parameters = (Parameter("crank", "length", "crank length r, m"),)


def run(*args):
    out, err = io.StringIO(), io.StringIO()
    sys_out, sys_err = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = out, err
    try:
        code = cli.main(list(args))
    finally:
        sys.stdout, sys.stderr = sys_out, sys_err
    return code, out.getvalue(), err.getvalue()


def test_help_runs_as_a_module():
    result = subprocess.run([sys.executable, "-m", "mechanisms", "--help"], capture_output=True, text=True, check=True)
    assert "table" in result.stdout and "kinematic table" in result.stdout


def test_parse_angles_in_degrees_stop_excluded():
    # as asked in degrees; in radians reduced to (−π, π] (270° is −90°, by hand)
    np.testing.assert_array_equal(cli.parse_angles_deg("0:360:90"), [0.0, 90.0, 180.0, 270.0])
    np.testing.assert_allclose(cli.parse_angles("0:360:90"), np.radians([0, 90, 180, -90]))
    for bad in ("0:360", "a:b:c", "0:360:0", "0:360:-30", "0:nan:10"):
        with pytest.raises(InvalidParameterError, match="--angles"):
            cli.parse_angles(bad)


def test_parse_point():
    assert cli.parse_point("S2=coupler:0.09") == ("S2", "coupler", 0.09, 0.0)
    assert cli.parse_point("K=coupler:0.1,-0.02") == ("K", "coupler", 0.1, -0.02)
    for bad in ("S2", "S2=coupler", "=coupler:1", "S2=coupler:x", "S2=coupler:1,2,3"):
        with pytest.raises(InvalidParameterError, match="--point"):
            cli.parse_point(bad)


def test_json_round_trip():
    code, out, _ = run("table", "test-yoke", "--crank", "0.1", "--omega", "10", "--angles", "0:360:90",
                       "--point", "M=crank:0.05", "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert data["mechanism"] == "test-yoke"
    assert data["parameters"] == {"crank": 0.1, "omega": 10.0, "alpha": 0.0}
    assert [r["phi_deg"] for r in data["rows"]] == [0.0, 90.0, 180.0, 270.0]
    second = data["rows"][1]
    assert set(second) == {"phi_deg", "links", "points", "sliders"}
    # by hand at φ = 90°: s = 0, v = −r ω = −1 m/s; the crank's mid-point moves at 0.5 m/s in −x
    assert second["sliders"]["B"]["s"] == pytest.approx(0.0, abs=1e-15)
    assert second["sliders"]["B"]["v"] == pytest.approx(-1.0)
    assert second["points"]["M"]["vx"] == pytest.approx(-0.5)
    assert second["links"]["crank"] == {"angle_deg": 90.0, "omega": 10.0, "alpha": 0.0}


def test_csv_has_one_row_per_position():
    code, out, _ = run("table", "test-yoke", "--crank", "0.1", "--omega", "10", "--positions", "6", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and len(rows) == 6
    assert float(rows[3]["B.s"]) == pytest.approx(-0.1)  # φ = 180°: s = −r
    assert "crank.angle_deg" in rows[0] and "A.ay" in rows[0]


def test_text_table_is_readable():
    code, out, _ = run("table", "test-yoke", "--crank", "0.1", "--omega", "10", "--positions", "12")
    assert code == 0
    assert out.startswith("test-yoke: crank = 0.1 m; omega = 10 1/s")
    assert "slider B" in out and "s, m" in out and "v, m/s" in out
    assert len([ln for ln in out.splitlines() if ln.strip().startswith("330.0")]) == 5  # 1 link, 3 points, 1 slider
    # round-off is not printed as a number: at φ = 90° the slider is at s = 0 exactly, not 6e-18
    ninety = [ln.split() for ln in out.split("slider B")[1].splitlines() if ln.strip().startswith("90.0")][0]
    assert ninety[1] == "0"


@pytest.mark.parametrize("args, message", [
    (("--crank", "-1", "--omega", "1"), "crank must be a finite length > 0 m"),
    (("--crank", "0.1", "--omega", "1", "--positions", "0"), "--positions must be a whole number"),
    (("--crank", "0.1", "--omega", "1", "--point", "K=rocker:0.1"), "on one of the links crank"),
    (("--crank", "0.1", "--omega", "nan"), "omega must be finite"),
])
def test_bad_input_is_a_clear_error_not_a_crash(args, message):
    code, out, err = run("table", "test-yoke", *args)
    assert code == 2 and out == ""
    assert message in err


def test_negative_pairs_are_values_not_options():
    assert cli._join_negative_pairs(["--frame", "-0.4,0.05", "--crank", "1"]) == ["--frame=-0.4,0.05", "--crank", "1"]
    assert cli._join_negative_pairs(["--frame", "0.4,-0.05"]) == ["--frame", "0.4,-0.05"]
    assert cli._join_negative_pairs(["--omega", "-5"]) == ["--omega=-5"]
    # scientific notation and angle ranges, which argparse would take for options (issue 18)
    assert cli._join_negative_pairs(["--omega", "-1e3", "--angles", "-90:90:30", "--offset", "-5e-2"]) == \
        ["--omega=-1e3", "--angles=-90:90:30", "--offset=-5e-2"]
    assert cli._join_negative_pairs(["--format", "json", "--help"]) == ["--format", "json", "--help"]


def test_negative_values_in_scientific_notation_reach_the_mechanism():
    code, out, err = run("table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--offset", "-5e-2",
                         "--omega", "-1e3", "--angles", "-90:90:30", "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    assert data["parameters"]["offset"] == -0.05 and data["parameters"]["omega"] == -1000.0
    assert [r["phi_deg"] for r in data["rows"]] == [-90.0, -60.0, -30.0, 0.0, 30.0, 60.0]


def test_angles_exclude_stop_even_with_fractional_steps():
    # by hand: 1.0, 1.1, 1.2 (1.3 is the stop) and 0, 30, 60 printed without round-off
    np.testing.assert_allclose(np.degrees(cli.parse_angles("1:1.3:0.1")), [1.0, 1.1, 1.2])
    code, out, _ = run("table", "test-yoke", "--crank", "0.1", "--omega", "1", "--angles", "0:90:30", "--format", "json")
    assert [r["phi_deg"] for r in json.loads(out)["rows"]] == [0.0, 30.0, 60.0]


@pytest.mark.parametrize("args, message", [
    (("--point", "B=crank:0.05"), "--point must be a new name"),
    (("--angles", "0:1:1e-300"), "--angles must be at most"),
    (("--positions", "100000000000"), "--positions must be a whole number from 1 to"),
])
def test_more_bad_input(args, message):
    code, out, err = run("table", "test-yoke", "--crank", "0.1", "--omega", "1", *args)
    assert code == 2 and message in err


def test_table_without_a_mechanism_is_an_error():
    code, _, err = run("table")
    assert code == 2 and "name a mechanism" in err and "test-yoke" in err


def test_negative_pairs_with_exponents():
    assert cli._join_negative_pairs(["--frame", "-3e-1,-1E-2"]) == ["--frame=-3e-1,-1E-2"]
    assert cli._join_negative_pairs(["--frame", "-1e+1,0"]) == ["--frame=-1e+1,0"]


def _peak_kilobytes(positions: int, fmt: str) -> int:
    """The largest resident memory (kB) of a fresh interpreter that writes the table to a null stream."""
    code = ("import io, os, resource, sys; from mechanisms.cli import main; sys.stdout = open(os.devnull, 'w'); "
            f"main(['table', 'crank-slider', '--crank', '0.08', '--rod', '0.3', '--omega', '215', '--positions', "
            f"'{positions}', '--format', '{fmt}']); "
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return int(done.stderr.split()[-1])


@pytest.mark.parametrize("fmt", ["csv", "json", "text"])
def test_the_table_streams_its_rows(fmt):
    # five times the positions (several chunks against one), about the same memory: the rows are solved,
    # formatted and written a chunk at a time (the old table held a dict per row: 216 MB for 20,000)
    small, large = _peak_kilobytes(2_000, fmt), _peak_kilobytes(10_000, fmt)
    assert large < small + 10_000, f"peak {small / 1e3:.0f} MB for 2,000 rows, {large / 1e3:.0f} MB for 10,000"


def test_streamed_rows_equal_an_independent_solution(capsys):
    # expected: the four-bar's rocker angle from the generic solver, at positions that span two chunks
    import json as json_module

    from mechanisms.cli import CHUNK
    m = mech.FourBar(crank=0.1, coupler=0.35, rocker=0.3, frame=(0.4, 0.0))
    n = CHUNK + 5
    assert main(["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame", "0.4,0",
                 "--omega", "10", "--positions", str(n), "--format", "json"]) == 0
    rows = json_module.loads(capsys.readouterr().out)["rows"]
    assert len(rows) == n
    phi = np.radians(np.arange(n) * 360.0 / n)
    every = slice(None, None, 97)
    generic = mech.verify.solve_generic(m, phi[every], omega=10.0, order=1)
    xi = np.radians([row["links"]["rocker"]["angle_deg"] for row in rows[every]])
    np.testing.assert_allclose(np.angle(np.exp(1j * (xi - generic.q[1]))), 0.0, atol=1e-12)
    np.testing.assert_allclose([row["links"]["rocker"]["omega"] for row in rows[every]], generic.q_t[1], atol=1e-9)
