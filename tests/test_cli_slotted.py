"""Tests of the command line for the slotted lever: ``python -m mechanisms table slotted-lever``.

Expected values come from hand calculations with the textbook relations of source 004 (5.62–5.69).
"""

from __future__ import annotations

import csv
import io
import json
import math

import pytest

from mechanisms.cli import main

ARGS = ["table", "slotted-lever", "--crank", "0.1", "--pivot", "0,0.3", "--omega", "10"]


def run(capsys, args):
    status = main(args)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_json(capsys):
    status, out, _ = run(capsys, ARGS + ["--positions", "4", "--format", "json"])
    assert status == 0
    data = json.loads(out)
    assert data["mechanism"] == "slotted-lever" and data["parameters"]["pivot"] == [0.0, 0.3]
    row = data["rows"][0]
    assert set(row["links"]) == {"crank", "lever"} and {"O", "A", "C"} <= set(row["points"])
    # by hand at φ = 0: l3 = √(0.1² + 0.3²) (5.62), φ3 = atan2(−0.3, 0.1) (5.63),
    # v_rel = −ω1 l1 sin(φ1 − φ3) (5.68), ω3 = ω1 l1 cos(φ1 − φ3)/l3 (5.69), Coriolis 2 ω3 v_rel
    l3, phi3 = math.hypot(0.1, 0.3), math.atan2(-0.3, 0.1)
    v_rel, w3 = -10 * 0.1 * math.sin(-phi3), 10 * 0.1 * math.cos(-phi3) / l3
    block = row["sliders"]["A"]
    assert block["s"] == pytest.approx(l3, abs=1e-15)
    assert block["v"] == pytest.approx(v_rel, abs=1e-14)
    assert block["coriolis"] == pytest.approx(2 * w3 * v_rel, abs=1e-13)
    assert row["links"]["lever"]["angle_deg"] == pytest.approx(math.degrees(phi3), abs=1e-12)
    assert row["links"]["lever"]["omega"] == pytest.approx(w3, abs=1e-14)
    assert [r["phi_deg"] for r in data["rows"]] == [0.0, 90.0, 180.0, 270.0]


def test_csv_and_text(capsys):
    status, out, _ = run(capsys, ARGS + ["--angles", "0:60:30", "--format", "csv"])
    assert status == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 2 and {"lever.omega", "A.s", "A.v", "A.a", "A.coriolis"} <= set(rows[0])
    status, out, _ = run(capsys, ARGS + ["--positions", "12"])
    assert status == 0 and "slider A" in out and "coriolis, m/s²" in out and "link lever" in out


def test_point_on_the_lever(capsys):
    # a point on the lever 0.5 m from C: at φ = 0 it lies along (0.1, −0.3)/l3 (by hand)
    status, out, _ = run(capsys, ARGS + ["--angles", "0:1:1", "--point", "P=lever:0.5", "--format", "json"])
    p = json.loads(out)["rows"][0]["points"]["P"]
    l3 = math.hypot(0.1, 0.3)
    assert status == 0 and p["x"] == pytest.approx(0.5 * 0.1 / l3) and p["y"] == pytest.approx(0.3 - 0.5 * 0.3 / l3)


def test_bad_inputs(capsys):
    status, _, err = run(capsys, ["table", "slotted-lever", "--crank", "-0.1", "--pivot", "0,0.3", "--omega", "1"])
    assert status == 2 and "crank" in err
    status, _, err = run(capsys, ARGS + ["--point", "P=rod:0.1"])
    assert status == 2 and "lever" in err
    assert main(["table", "slotted-lever", "--crank", "0.1", "--pivot", "0.3", "--omega", "1"]) == 2


def test_other_slotted_mechanisms(capsys):
    # Shaper at φ = 90°: A = (0, 0.1) right above C = (0, −0.4), so the lever is vertical and B = (0, 0.2); the rod
    # of 0.15 m reaches the guide y = 0.22 at x_G = √(0.15² − 0.02²) (hand).
    status, out, _ = run(capsys, ["table", "shaper", "--crank", "0.1", "--pivot", "0,-0.4", "--lever", "0.6",
                                  "--rod", "0.15", "--ram-height", "0.22", "--omega", "6", "--angles", "90:91:1",
                                  "--format", "json"])
    assert status == 0
    row = json.loads(out)["rows"][0]
    assert row["sliders"]["G"]["s"] == pytest.approx(math.sqrt(0.15**2 - 0.02**2), abs=1e-15)
    assert row["links"]["lever"]["angle_deg"] == pytest.approx(90.0, abs=1e-12)
    assert set(row["sliders"]) == {"A", "G"} and "coriolis" in row["sliders"]["A"]
    # Rocker in a block (source 002, r = 2, block at (0, 2) = on the crank circle): ω = ω1/2 (hand)
    status, out, _ = run(capsys, ["table", "rocker-in-block", "--crank", "2", "--pivot", "0,2", "--omega", "0.5",
                                  "--positions", "8", "--format", "json"])
    assert status == 0
    assert all(r["links"]["rocker"]["omega"] == pytest.approx(0.25, abs=1e-15) for r in json.loads(out)["rows"])
    status, out, _ = run(capsys, ["table", "slotted-rockers", "--crank", "0.1", "--pivot", "0,0.3", "--rocker-pivot",
                                  "0.12,0.38", "--rocker", "0.2", "--omega", "10", "--format", "csv"])
    assert status == 0 and "D.coriolis" in out.splitlines()[0] and len(out.splitlines()) == 13


def test_slider_on_coupler_takes_its_guide_angle_in_degrees(capsys):
    # expected by hand: the block E is where the coupler's line A → B meets the guide through (0.2, 0.1) at 60°,
    # with A = r e^{iφ}, B = (r cos φ + √(L² − r² sin² φ), 0) (offset 0)
    args = ["table", "slider-on-coupler", "--crank", "0.08", "--rod", "0.3", "--guide-point", "0.2,0.1",
            "--guide-angle", "60", "--omega", "10", "--positions", "4", "--format", "json"]
    status, out, _ = run(capsys, args)
    assert status == 0
    data = json.loads(out)
    assert data["parameters"]["guide_angle_deg"] == pytest.approx(60.0)
    for row in data["rows"]:
        phi = math.radians(row["phi_deg"])
        a = complex(0.08 * math.cos(phi), 0.08 * math.sin(phi))
        b = complex(a.real + math.sqrt(0.3**2 - a.imag**2), 0.0)
        g, u = complex(0.2, 0.1), complex(math.cos(math.radians(60)), math.sin(math.radians(60)))
        d = (b - a) / abs(b - a)
        # solve a + t·d = g + s·u for t, s (Cramer's rule on the real and imaginary parts)
        det = d.real * (-u.imag) - d.imag * (-u.real)
        t = ((g - a).real * (-u.imag) - (g - a).imag * (-u.real)) / det
        expected = a + t * d
        point = row["points"]["E"]
        assert point["x"] == pytest.approx(expected.real, abs=1e-14)
        assert point["y"] == pytest.approx(expected.imag, abs=1e-14)
