"""Tests of ``python -m mechanisms synthesize path`` (mechanisms/cli.py): the target file's checks, the report,
the written linkage file (solved by the general linkage solver) and the honest report of a poor fit."""

import math

import numpy as np
import pytest

from mechanisms import load_linkage
from mechanisms.cli import main


def run(argv, capsys):
    status = main(argv)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def write_target(path, points, minus="-"):
    path.write_text("x,y\n" + "".join(f"{float(z.real)!r},{float(z.imag)!r}\n".replace("-", minus) for z in points),
                    encoding="utf-8")
    return str(path)


def nearest(points, polyline):
    """From each point to the nearest vertex of a dense polyline (an upper bound of the distance to it)."""
    return np.min(np.abs(np.asarray(points)[:, None] - polyline[None, :]), axis=1)


def test_an_ellipse_is_fitted_and_the_file_traces_it(tmp_path, capsys):
    # an ellipse of semi-axes 0.3 m and 0.1 m about (1, 0) m, written with the Unicode minus
    t = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    ellipse = 1.0 + 0.3 * np.cos(t) + 0.1j * np.sin(t)
    target = write_target(tmp_path / "ellipse.csv", ellipse, minus="\u2212")
    out_file = tmp_path / "ellipse.toml"
    status, out, err = run(["synthesize", "path", target, "--out", str(out_file)], capsys)
    assert status == 0, err
    assert "48 points, a closed curve" in out and "the diagonal of its bounding box" in out
    assert "Grashof class:" in out and "transmission angle:" in out
    assert f"linkage file written: {out_file}" in out
    # expected: the written file, solved by the general linkage solver at 0.05° steps, against the ellipse at
    # 1000 parameters the fit never saw; size = the bounding box's diagonal √(0.6² + 0.2²) m
    path = load_linkage(out_file).solve(np.radians(np.arange(0.0, 360.0, 0.05)), omega=1.0, order=0).point("P").value
    check = 1.0 + 0.3 * np.cos(t[:1] + np.linspace(0.001, 2 * np.pi, 1000)) \
        + 0.1j * np.sin(t[:1] + np.linspace(0.001, 2 * np.pi, 1000))
    size = math.hypot(0.6, 0.2)
    assert np.sqrt(np.mean(nearest(check, path) ** 2)) <= 0.01 * size
    assert np.max(nearest(path[::10], check)) <= 0.03 * size           # no part of P's path strays


def test_an_open_stretch_with_fixed_pivots(tmp_path, capsys):
    # a stretch of a circle of radius 0.2 m about (0.05, 0.3) m: a coupler point can follow it closely
    t = np.linspace(0.2, 1.6, 25)
    arc = 0.05 + 0.3j + 0.2 * np.exp(1j * t)
    target = write_target(tmp_path / "arc.csv", arc)
    out_file = tmp_path / "arc.toml"
    status, out, err = run(["synthesize", "path", target, "--out", str(out_file), "--open",
                            "--fixed-pivots", "0,0,0.3,-0.05", "--crank-rocker"], capsys)
    assert status == 0, err
    assert "an open stretch" in out and "Grashof class: crank-rocker" in out
    linkage = load_linkage(out_file)
    solution = linkage.solve(np.radians(np.arange(0.0, 360.0, 0.05)), omega=1.0, order=0)
    # the pivots as given: O = (0, 0), C = (0.3, −0.05)
    assert solution.point("O").value[0] == 0j and solution.point("C").value[0] == 0.3 - 0.05j
    size = math.hypot(np.ptp(arc.real), np.ptp(arc.imag))
    check = 0.05 + 0.3j + 0.2 * np.exp(1j * np.linspace(0.21, 1.59, 300))
    assert np.sqrt(np.mean(nearest(check, solution.point("P").value) ** 2)) <= 0.01 * size


def test_a_square_gets_an_honest_report_and_no_file(tmp_path, capsys):
    corners = np.array([0, 1, 1 + 1j, 1j, 0])
    square = np.concatenate([corners[k] + np.linspace(0, 1, 10, endpoint=False) * (corners[k + 1] - corners[k])
                             for k in range(4)])
    target = write_target(tmp_path / "square.csv", square)
    out_file = tmp_path / "square.toml"
    status, out, _ = run(["synthesize", "path", target, "--out", str(out_file)], capsys)
    assert status == 1
    assert "no four-bar found fits better than" in out and "the tolerance is 1 %" in out
    assert "no linkage file written" in out and not out_file.exists()


@pytest.mark.parametrize("text, message", [
    ("a,b\n0,0\n1,0\n1,1\n0,1\n0.5,2\n", "line 1: the first line must be the header x,y"),
    ("x,y\n0,0\n1,0\n1,1\n0,1\n", "at least 5 distinct points"),
    ("x;y\n0;0\n1;0\n1,5;1\n0;1\n0.5;2\n", "line 4: x is not a number: '1,5' (the decimal separator is a point"),
    ("x,y\n0,0\n1,0\n1,nan\n0,1\n0.5,2\n", "line 4: y must be a finite number of metres"),
    ("x,y\n0,0\n1,0,3\n1,1\n0,1\n0.5,2\n", "line 3: expected two numbers x,y"),
    ("x,y\n0,0\n1,1\n2,2\n3,3\n4,4\n5,5\n", "not all on one straight line"),
])
def test_bad_target_files_are_named(tmp_path, capsys, text, message):
    target = tmp_path / "bad.csv"
    target.write_text(text, encoding="utf-8")
    status, out, err = run(["synthesize", "path", str(target), "--out", str(tmp_path / "o.toml")], capsys)
    assert status == 2 and out == ""
    assert str(target) in err and message in err
    assert not (tmp_path / "o.toml").exists()


@pytest.mark.parametrize("options, message", [
    (["--fixed-pivots", "0,0,1"], "--fixed-pivots"),
    (["--fixed-pivots", "0,0,0,0"], "two distinct points"),
    (["--min-transmission", "95"], "--min-transmission"),
    (["--tolerance", "0"], "--tolerance"),
])
def test_bad_options_are_named(tmp_path, capsys, options, message):
    target = write_target(tmp_path / "t.csv", np.exp(1j * np.linspace(0, 6, 8)))
    status, _, err = run(["synthesize", "path", target, "--out", str(tmp_path / "o.toml")] + options, capsys)
    assert status == 2 and message in err


def test_a_missing_file_and_a_missing_task(tmp_path, capsys):
    status, _, err = run(["synthesize", "path", str(tmp_path / "none.csv"), "--out", "x.toml"], capsys)
    assert status == 2 and "none.csv: no such file" in err
    status, _, err = run(["synthesize"], capsys)
    assert status == 2 and "name a task" in err
