"""The command `plan`: both plans of a linkage file at one crank angle, vector by vector (issue 29, item 2).

Expected values are hand calculations of the crank's vectors and the package's solution of the
linkage (Linkage.solve), not the plan code's own output.
"""

import json
import math

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.cli import main


def test_plan_prints_each_vector_with_its_length_at_the_scale(capsys):
    assert main(["plan", "watt-six-bar", "--angle", "390", "--omega", "10", "--scale-v", "0.02"]) == 0
    out = capsys.readouterr().out
    # by hand: 390° is the crank at 30°; v_A = ω₁ l_OA = 10 × 0.1 = 1 m/s at 120°, 1 / 0.02 = 50 mm from p to a
    row = next(line for line in out.splitlines() if " v_A " in line)
    assert row.split()[1:] == ["v_A", "pa", "50.00", "1", "m/s", "120.00"]
    assert "μ_v = 0.02 (m/s)/mm" in out and "a^t_FD" in out


def test_plan_json_matches_the_solution(capsys):
    assert main(["plan", "jansen", "--angle", "75", "--omega", "10", "--alpha", "2", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    solution = mech.load_linkage("jansen").solve(np.radians([75.0]), 10.0, 2.0)
    foot = next(row for row in data["vectors"] if row["name"] == "v_G")
    assert foot["magnitude"] == pytest.approx(abs(solution.point("G").velocity[0]), rel=1e-9)
    assert foot["length_mm"] == pytest.approx(foot["magnitude"] / data["scale_v"])
    assert data["epsilon"]["lower triangle"] == pytest.approx(solution.angle("lower triangle").alpha[0], rel=1e-9)


@pytest.mark.parametrize("suffix", [".png", ".svg"])
def test_plan_draws_into_a_png_or_an_svg(tmp_path, capsys, suffix):
    out = tmp_path / f"plan{suffix}"
    assert main(["plan", "shaper", "--angle", "30", "--omega", "10", "--out", str(out)]) == 0
    head = out.read_bytes()[:200]
    assert head.startswith(b"\x89PNG") if suffix == ".png" else b"<svg" in out.read_bytes()[:2000]


@pytest.mark.parametrize("arguments, message", [
    (["--out", "plan.pdf"], "--out must be a file name ending in .png or .svg"),
    (["--out", "/no/such/folder/plan.svg"], "--out must be a file that can be written"),
    (["--scale-v", "0"], "scale_v"),
])
def test_plan_refuses_bad_options_with_a_message(tmp_path, capsys, arguments, message):
    assert main(["plan", "shaper", "--angle", "30", "--omega", "10", *arguments]) == 2
    captured = capsys.readouterr()
    assert message in captured.err and "Traceback" not in captured.err
    assert not (tmp_path / "plan.pdf").exists()
