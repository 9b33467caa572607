"""The command line on linkage files: ``table FILE.toml`` in three formats and ``structure FILE``."""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
import pytest

from mechanisms import cli
from mechanisms.linkages.linkage_file import example_file, example_files


def run(capsys, *argv):
    status = cli.main(list(argv))
    out = capsys.readouterr()
    return status, out.out, out.err


@pytest.mark.parametrize("name", example_files())
def test_table_of_every_shipped_file_in_three_formats(capsys, name):
    path = str(example_file(name))
    status, text, _ = run(capsys, "table", path, "--omega", "2", "--positions", "6", "--format", "json")
    assert status == 0
    data = json.loads(text)
    assert data["parameters"]["file"] == path and len(data["rows"]) == 6
    status, table, _ = run(capsys, "table", path, "--omega", "2", "--positions", "6", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(table)))
    assert status == 0 and len(rows) == 6
    status, text_table, _ = run(capsys, "table", path, "--omega", "2", "--positions", "6")
    assert status == 0 and text_table.startswith(data["mechanism"])
    # every joint and point of the file is under points, in every row
    from mechanisms.linkages.linkage_file import load_linkage

    joints = {j for js in load_linkage(path).link_joints().values() for j in js}
    assert set(data["rows"][0]["points"]) == joints
    assert float(rows[3]["phi_deg"]) == 180.0


def test_table_of_the_crank_slider_file_matches_the_formula(capsys, tmp_path):
    """x_B = r cos φ + √(L² − (r sin φ − e)²), by hand, against the file's table."""
    path = tmp_path / "slider.toml"
    path.write_text('[frame]\nO = [0, 0]\n[crank]\npivot = "O"\npin = "A"\nlength = 0.1\n'
                    '[[dyad]]\ntype = "RRP"\njoint = "B"\nfrom = "A"\nlength = 0.35\n'
                    'guide = { through = [0.0, 0.02], angle_deg = 0.0 }\n')
    status, text, err = run(capsys, "table", str(path), "--omega", "-1e2", "--angles", "-90:90:30", "--format", "json")
    assert status == 0, err
    for row in json.loads(text)["rows"]:
        phi = math.radians(row["phi_deg"])
        x = 0.1 * math.cos(phi) + math.sqrt(0.35**2 - (0.1 * math.sin(phi) - 0.02) ** 2)
        assert row["points"]["B"]["x"] == pytest.approx(x, rel=1e-14)
        assert row["sliders"]["B"]["s"] == pytest.approx(x, rel=1e-14)


def test_table_of_a_file_with_an_extra_point(capsys):
    status, text, _ = run(capsys, "table", "watt-six-bar", "--omega", "1", "--positions", "2",
                          "--point", "S=coupler:0.1", "--format", "json")
    assert status == 0 and "S" in json.loads(text)["rows"][0]["points"]
    status, _, err = run(capsys, "table", "watt-six-bar", "--omega", "1", "--point", "S=frame:0.1")
    assert status == 2 and "on one of the links" in err


def test_structure_command(capsys):
    status, text, _ = run(capsys, "structure", "jansen")
    assert status == 0
    assert "W = 3n − 2p₁ − p₂ = 3·7 − 2·10 − 0 = 1" in text and "class II" in text
    status, text, _ = run(capsys, "structure", "shaper", "--format", "json")
    data = json.loads(text)
    assert data["mobility"] == 1 and [g["kind"] for g in data["groups"]] == ["crank", "RPR", "RRP"]


def test_bad_files_exit_2_with_the_file_named(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[frame]\nO = [0, 0]\n[crank]\npivot = "O"\npin = "A"\nlength = -1\n')
    for command in (["structure", str(bad)], ["table", str(bad), "--omega", "1"]):
        status, out, err = run(capsys, *command)
        assert status == 2 and out == ""
        assert err.startswith(f"error: {bad}: [crank]: key 'length': must be a length > 0 m")
    status, _, err = run(capsys, "table", str(tmp_path / "none.toml"), "--omega", "1")
    assert status == 2 and "no such file" in err


def test_a_file_that_does_not_assemble_everywhere_prints_nothing_half_computed(capsys, tmp_path):
    path = tmp_path / "short.toml"
    path.write_text('[frame]\nO = [0, 0]\nC = [4, 0]\n[crank]\npivot = "O"\npin = "A"\nlength = 1\n'
                    '[[dyad]]\ntype = "RRR"\njoint = "B"\nfrom = ["A", "C"]\nlengths = [2.5, 1.0]\n')
    status, out, err = run(capsys, "table", str(path), "--omega", "1", "--positions", "4")
    assert status == 2 and out == ""
    assert "RRR B (from A, C) cannot be assembled" in err and "90°, 180°, 270°" in err
    assert np.isclose(float(err.split("[")[-1].split("°")[0]), -math.degrees(math.acos(0.59375)), atol=0.01)


def test_table_help_documents_the_format(capsys):
    assert cli.main(["table", "--help"]) == 0
    text = capsys.readouterr().out
    for key in ('type = "RRR"', "[[point]]", "[[triad]]", "[[mass]]", "guide"):
        assert key in text
