"""Tests of ``python -m mechanisms table crank-slider``: the three formats, a JSON round trip, bad input."""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys

import numpy as np
import pytest

from mechanisms.cli import main

EXAMPLE = ["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--point", "S2=coupler:0.09",
           "--omega", "215", "--positions", "12"]


def run(capsys, args):
    status = main(args)
    out, err = capsys.readouterr()
    return status, out, err


def test_done_when_command_prints_the_12_position_table():
    # the acceptance command, run as a student runs it
    result = subprocess.run([sys.executable, "-m", "mechanisms", *EXAMPLE], capture_output=True, text=True,
                            timeout=60, check=True)
    text = result.stdout
    assert text.startswith("crank-slider: crank = 0.08 m, rod = 0.3 m, offset = 0")
    for block in ("link crank", "link coupler", "point O", "point A", "point B", "point S2", "slider B"):
        assert f"\n{block}\n" in text
    slider = text.split("\nslider B\n")[1].splitlines()
    assert len(slider) == 1 + 12  # heading and 12 positions
    # position 2 (φ = 30°), Table 5.5 of the textbook page: v_C = −10.6 m/s, a_C = −3713 m/s² (printed, truncated)
    assert slider[2].split()[:2] == ["30.0", "0.366603"]
    assert float(slider[2].split()[2]) == pytest.approx(-10.6, abs=0.05)
    assert float(slider[2].split()[3]) == pytest.approx(-3713, abs=1)


def test_csv(capsys):
    status, out, _ = run(capsys, EXAMPLE + ["--format", "csv"])
    assert status == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 12
    assert [float(r["phi_deg"]) for r in rows] == pytest.approx(np.arange(0, 360, 30))
    assert {"coupler.omega", "coupler.alpha", "S2.vx", "S2.ay", "B.s", "B.v", "B.a"} <= set(rows[0])
    # Table 5.5 (source 004), position 2: ω2 = −50.1 1/s, ε2 = 5881 1/s²
    assert float(rows[1]["coupler.omega"]) == pytest.approx(-50.1, abs=0.05)
    assert float(rows[1]["coupler.alpha"]) == pytest.approx(5881, abs=0.5)
    # by hand: at φ = 0 the slider is at L1 + L2 = 0.38 m, at φ = 180° at L2 − L1 = 0.22 m
    assert float(rows[0]["B.s"]) == pytest.approx(0.38) and float(rows[6]["B.s"]) == pytest.approx(0.22)


def test_json_round_trip(capsys):
    status, out, _ = run(capsys, EXAMPLE + ["--format", "json"])
    assert status == 0
    data = json.loads(out)
    assert data["mechanism"] == "crank-slider"
    assert data["parameters"] == {"crank": 0.08, "rod": 0.3, "offset": 0.0, "omega": 215.0, "alpha": 0.0}
    assert len(data["rows"]) == 12
    row = data["rows"][1]
    assert set(row) == {"phi_deg", "links", "points", "sliders"}
    assert set(row["links"]) == {"crank", "coupler"} and set(row["points"]) == {"O", "A", "B", "S2"}
    assert set(row["sliders"]) == {"B"} and set(row["sliders"]["B"]) == {"s", "v", "a"}
    # Table 5.5 (source 004): v_S2 = 13.91 m/s at 131.4°, a_S2 = 3597 m/s² at 201.1°
    s2 = row["points"]["S2"]
    assert np.hypot(s2["vx"], s2["vy"]) == pytest.approx(13.91, abs=0.005)
    assert np.degrees(np.arctan2(s2["vy"], s2["vx"])) == pytest.approx(131.4, abs=0.05)
    assert np.hypot(s2["ax"], s2["ay"]) == pytest.approx(3597, abs=0.5)
    assert np.degrees(np.arctan2(s2["ay"], s2["ax"])) % 360 == pytest.approx(201.1, abs=0.05)
    # round trip: the JSON text, parsed and written again, is the same document
    assert json.loads(json.dumps(data)) == data
    assert json.dumps(data, indent=1, ensure_ascii=False) == out.rstrip("\n")


def test_angles_and_offset(capsys):
    status, out, _ = run(capsys, ["table", "crank-slider", "--crank", "2", "--rod", "4", "--offset", "-1",
                                  "--omega", "0.5", "--angles", "0:360:90", "--format", "json"])
    assert status == 0
    rows = json.loads(out)["rows"]
    assert [r["phi_deg"] for r in rows] == [0.0, 90.0, 180.0, 270.0]
    # by hand at φ = 90°: A = (0, 2), B on y = −1 at x = √(16 − 9) = √7
    assert rows[1]["points"]["B"]["x"] == pytest.approx(np.sqrt(7.0), rel=1e-14)
    assert rows[1]["points"]["B"]["y"] == pytest.approx(-1.0)


def test_dead_centre_prints_as_missing(capsys):
    # source 002's limiting geometry: at φ = 90° the slider velocity is unbounded/undefined → null, not a number
    status, out, _ = run(capsys, ["table", "crank-slider", "--crank", "2", "--rod", "3", "--offset", "-1",
                                  "--omega", "1", "--angles", "0:360:90", "--format", "json"])
    assert status == 0
    rows = json.loads(out)["rows"]
    assert rows[1]["sliders"]["B"]["v"] is None and rows[0]["sliders"]["B"]["v"] is not None


@pytest.mark.parametrize("args, message", [
    (["--crank", "0", "--rod", "0.3"], "crank must be a finite length"),
    (["--crank", "-0.08", "--rod", "0.3"], "crank must be a finite length"),
    (["--crank", "nan", "--rod", "0.3"], "crank must be a finite length"),
    (["--crank", "0.08", "--rod", "0.1", "--offset", "0.1"], "cannot reach the guide"),
    (["--crank", "0.08", "--rod", "0.3", "--point", "S=crank2:0.1"], "--point"),
    (["--crank", "0.08", "--rod", "0.3", "--angles", "0:360:0"], "--angles"),
])
def test_bad_input_exits_with_status_2(capsys, args, message):
    status, out, err = run(capsys, ["table", "crank-slider", *args, "--omega", "10"])
    assert status == 2 and out == ""
    assert message in err


def test_missing_required_option(capsys):
    # a usage error is argparse's message and exit status 2, returned (not raised: main never raises)
    assert main(["table", "crank-slider", "--crank", "0.08", "--omega", "10"]) == 2
    assert "--rod" in capsys.readouterr().err
