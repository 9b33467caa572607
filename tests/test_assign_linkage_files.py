"""Tests of ``assign FILE.toml``: variants of any linkage file, their own files, the key and its tolerances."""

from __future__ import annotations

import csv
import json
import math
import pathlib
import re

import numpy as np
import pytest

from mechanisms import load_linkage, verify
from mechanisms.cli import main
from mechanisms.core.errors import InvalidParameterError, StructureError
from mechanisms.course.assign import assignment_task, make_variants
from mechanisms.course.grading import parse_tolerance, tolerance_rules
from mechanisms.course.variants import linkage_document, read_assignment_file, transmission_angles
from mechanisms.linkages.linkage_file import example_files


@pytest.mark.parametrize("name", example_files())
def test_thirty_students_get_thirty_distinct_valid_loadable_variants(name, tmp_path):
    task = read_assignment_file(name).task()
    variants = make_variants(task, 30, seed=11)
    texts = [linkage_document(v.mechanism) for v in variants]
    assert len({(t, v.omega, v.positions_deg) for t, v in zip(texts, variants)}) == 30
    for variant, text in zip(variants, texts):
        path = tmp_path / f"{variant.student}.toml"
        path.write_text(text, encoding="utf-8")
        linkage = load_linkage(path)             # the variant's own file is a linkage file
        solution = linkage.solve(np.radians(variant.positions_deg), variant.omega)
        assert not np.any(solution.singular)
        # the transmission angle at every asked position, by hand from the joints: ≥ 40°
        for group, mu in transmission_angles(linkage, solution).items():
            assert np.all(mu >= 40.0 - 1e-9), (name, group, mu)


def test_transmission_angle_of_a_crank_slider_is_chapter_3s(tmp_path):
    # an axial crank-slider as a file: by hand μ = 90° − |ψ| with sin ψ = −L1 sin φ / L2
    (tmp_path / "cs.toml").write_text('[frame]\nO = [0.0, 0.0]\n[crank]\npivot = "O"\npin = "A"\nlength = 0.1\n'
                                      '[[dyad]]\ntype = "RRP"\njoint = "B"\nfrom = "A"\nlength = 0.3\n'
                                      'guide = { through = [0.0, 0.0], angle_deg = 0.0 }\n')
    linkage = load_linkage(tmp_path / "cs.toml")
    phi = np.radians([0.0, 30.0, 90.0, 200.0])
    mu = transmission_angles(linkage, linkage.solve(phi, 1.0, order=0))["RRP B"]
    expected = 90.0 - np.degrees(np.abs(np.arcsin(0.1 * np.sin(phi) / 0.3)))
    assert mu == pytest.approx(expected, abs=1e-9)


def _written(tmp_path, name, *extra):
    out = tmp_path / "out"
    assert main(["assign", name, "--students", "3", "--seed", "4", "--out", str(out), *extra]) == 0
    key = list(csv.DictReader((out / "key.csv").open(encoding="utf-8")))
    record = json.loads((out / "variants.json").read_text(encoding="utf-8"))
    return out, key, {v["student"]: v for v in record["variants"]}


@pytest.mark.parametrize("name", ["watt-six-bar", "shaper", "four-bar", "slotted-lever", "crank-slider"])
def test_the_key_agrees_with_the_generic_solver_on_each_students_file(tmp_path, name):
    # a named mechanism's variants are linkage files underneath too: the key (the named closed form) against
    # Newton's method on the file's constraint equations
    out, key, variants = _written(tmp_path, name)
    for student, variant in variants.items():
        linkage = load_linkage(out / variant["file"])
        text = (out / variant["file"]).read_text(encoding="utf-8")
        assert f"omega = {variant['omega']!r} 1/s" in text          # the file says how the crank turns
        rows = [r for r in key if r["student"] == student]
        phi = np.radians([float(r["phi_deg"]) for r in rows])
        # independent: Newton's method on the linkage's own constraint equations, one global system
        generic = verify.solve_generic(linkage, phi, variant["omega"], 0.0, order=2)
        groups = [g for g in linkage.groups() if type(g).__name__ in ("RRR", "RRP", "RPR")]
        checked: list[str] = []
        index = 0
        for group in groups:
            first = {"RRR": "first_link", "RRP": "link", "RPR": "lever"}[type(group).__name__]
            links = [getattr(group, first)] + ([group.second_link] if type(group).__name__ == "RRR" else [])
            for k, link in enumerate(links):
                column = f"{link}.omega"
                if column in rows[0]:
                    checked.append(column)
                    assert [float(r[column]) for r in rows] == pytest.approx(generic.q_t[index + k], rel=1e-9,
                                                                             abs=1e-9)
                    assert [float(r[f"{link}.alpha"]) for r in rows] == pytest.approx(
                        generic.q_tt[index + k], rel=1e-8, abs=1e-8)
            index += 2
        assert checked, "no link's rates compared"
        # the output joint's position keeps its distances to the joints it is found from (from the file's lengths)
        data = load_linkage(out / variant["file"])
        last = data.groups()[-1]
        joint = last.joint
        found = data.solve(phi, 1.0, order=0)
        for r, i in zip(rows, range(len(rows))):
            if f"{joint}.x" not in r:           # a named mechanism's key asks for its links' rates only
                continue
            where = complex(float(r[f"{joint}.x"]), float(r[f"{joint}.y"]))
            if type(last).__name__ == "RRR":
                for other, length in ((last.first, last.first_length), (last.second, last.second_length)):
                    assert abs(where - found.point(other).value[i]) == pytest.approx(length, rel=1e-12)


def test_check_gives_full_marks_to_the_key_and_names_a_perturbed_answer(tmp_path, capsys):
    out, key, _ = _written(tmp_path, "stephenson-six-bar")
    columns = list(key[0])
    key[1]["F.vy"] = repr(float(key[1]["F.vy"]) * 1.05)      # 5 % off: beyond its 1 % tolerance
    with (tmp_path / "answers.csv").open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns)
        writer.writeheader()
        writer.writerows(key)
    capsys.readouterr()
    assert main(["check", str(out / "key.csv"), str(out / "key.csv")]) == 0
    assert "s01: 42 of 42 right (100 %)" in capsys.readouterr().out    # 3 positions × (6 + 4 links × 2) quantities
    assert main(["check", str(out / "key.csv"), str(tmp_path / "answers.csv")]) == 0
    text = capsys.readouterr().out
    assert "s01: 41 of 42 right (98 %)" in text
    assert re.search(r"wrong +position 2 \(φ = \d+°\) F\.vy: .*, [+-]5 %", text)


def test_the_tolerance_file_states_each_values_tolerance(tmp_path):
    out, key, _ = _written(tmp_path, "beam-pump", "--tolerance", "U.vx=2%", "--tolerance", "angular-velocity=0.05")
    tolerances = list(csv.DictReader((out / "key-tolerances.csv").open(encoding="utf-8")))
    for row, tol in zip(key, tolerances):
        # by hand: max(2 % |key|, 5 mm/s) for U.vx, max(1 % |key|, 0.05 1/s) for the rates, max(1 %, 0.05) for U.ax
        assert float(tol["U.vx"]) == max(0.02 * abs(float(row["U.vx"])), 0.005)
        assert float(tol["beam.omega"]) == max(0.01 * abs(float(row["beam.omega"])), 0.05)
        assert float(tol["U.ax"]) == max(0.01 * abs(float(row["U.ax"])), 0.05)
    sheet = (out / "s01.md").read_text(encoding="utf-8")
    assert "| `U.vx` | $x_{Ut}$ | velocity of joint U, x component | m/s | 2 %, at least 0.005 m/s |" in sheet


def test_plan_mode_reads_tolerances_off_a_drawing(tmp_path):
    out, key, _ = _written(tmp_path, "shaper", "--plan")
    tolerances = list(csv.DictReader((out / "key-tolerances.csv").open(encoding="utf-8")))
    for row, tol in zip(key, tolerances):
        # chapter 10: 1 mm of a plan within 100 mm is at least 1 % of its largest vector; 3 % relative
        assert float(tol["G.vx"]) >= 0.03 * abs(float(row["G.vx"]))
        assert float(tol["G.vx"]) >= 0.01 * math.hypot(float(row["G.vx"]), float(row["G.vy"])) * 0.999
    assert "3 %, at least 1 mm of the drawing" in (out / "s01.md").read_text(encoding="utf-8")


@pytest.mark.parametrize(("text", "expected"), [
    ("B.vx=2%", (["B.vx"], 0.02, None)),
    ("angle=0.5deg", (["coupler.angle_deg"], None, 0.5)),
    ("B.x=0.5mm", (["B.x"], None, 0.0005)),
    ("velocity=3%,0.01", (["B.vx"], 0.03, 0.01)),
])
def test_tolerance_options(text, expected):
    columns = ["B.x", "B.vx", "coupler.angle_deg"]
    chosen, relative, floor = parse_tolerance(text, columns)
    assert chosen == expected[0] and relative == pytest.approx(expected[1]) if expected[1] else relative is None
    assert (floor == pytest.approx(expected[2])) if expected[2] is not None else floor is None


@pytest.mark.parametrize("text", ["B.vx", "psi=2%", "angle=2%", "B.vx=2mm", "B.x=1%,2%", "B.x=abc", "B.x=150%"])
def test_bad_tolerance_options_name_the_option(text):
    with pytest.raises(InvalidParameterError, match="--tolerance"):
        tolerance_rules(["B.x", "B.vx", "coupler.angle_deg"], [text])


def test_a_variants_table_sets_ranges_and_fixes_keys(tmp_path):
    from mechanisms.linkages.linkage_file import example_file

    text = tmp_path / "w.toml"

    text.write_text(example_file("watt-six-bar").read_text(encoding="utf-8") + (
        '\n[variants]\nomega = 30.0\nfixed = ["frame.C", "frame.D", "point.E.along", "point.E.left"]\n'
        '"crank.length" = [0.09, 0.11]\n"dyad.F.lengths" = [[0.38, 0.42], 0.5]\n'), encoding="utf-8")
    for variant in make_variants(assignment_task(str(text)), 10, seed=2):
        data = variant.mechanism
        assert variant.omega == 30.0
        crank, rrr_b, point, rrr_f = data.groups()
        assert 0.09 <= crank.length <= 0.11
        assert 0.38 <= rrr_f.first_length <= 0.42 and rrr_f.second_length == 0.5
        assert data.frame["C"] == complex(0.40, 0.05) and point.along == 0.45


@pytest.mark.parametrize(("table", "message"), [
    ('"crank.lenght" = [0.1, 0.2]', "unknown key(s) 'crank.lenght'"),
    ('"crank.length" = [0.2, 0.1]', "low ≤ high"),
    ('"frame.C" = [0.3]', "one number or range [low, high] per element"),
    ('spread = 2', "spread"),
    ('omega = -3', "omega"),
])
def test_a_bad_variants_table_is_refused_by_key(tmp_path, table, message):
    from mechanisms.linkages.linkage_file import example_file

    path = tmp_path / "w.toml"
    path.write_text(example_file("watt-six-bar").read_text(encoding="utf-8") + f"\n[variants]\n{table}\n",
                    encoding="utf-8")
    with pytest.raises(StructureError, match=re.escape(message)):
        read_assignment_file(path)
    assert main(["assign", str(path), "--students", "2", "--out", str(tmp_path / "o")]) == 2


def test_ask_chooses_the_columns_and_refuses_unknown_ones(tmp_path, capsys):
    out, key, _ = _written(tmp_path, "jansen", "--ask", "G.x,G.y,f.omega")
    assert list(key[0]) == ["student", "position", "phi_deg", "G.x", "G.y", "f.omega"]
    assert main(["assign", "jansen", "--students", "1", "--ask", "G.q", "--out", str(tmp_path / "x")]) == 2
    assert "G.q" in capsys.readouterr().err


def test_force_columns_of_a_file_with_masses_agree_with_one_system_of_all_bodies(tmp_path, monkeypatch):
    # the course project's press (masses, gravity): the key's driving torque and hinge force |F_B| against one
    # Newton–Euler system of every body at once (tests/test_forces_any_linkage.py), solved for each student's file
    import test_forces_any_linkage as global_system

    project = str(pathlib.Path(__file__).resolve().parent.parent / "book" / "course-project.toml")
    out, key, variants = _written(tmp_path, project, "--ask", "driving_torque,B.F,F.x")
    assert {"driving_torque", "B.F", "F.x"} <= set(key[0])
    for student, variant in variants.items():
        linkage = load_linkage(out / variant["file"])
        rows = [r for r in key if r["student"] == student]
        phi = np.radians([float(r["phi_deg"]) for r in rows])
        monkeypatch.setattr(global_system, "PHI", phi)
        torque, hinges, _ = global_system.newton_euler(linkage, linkage.solve(phi, variant["omega"], 0.0))
        at_b = [force for (joint, _, _), force in hinges.items() if joint == "B"]
        assert len(at_b) == 1
        scale = np.abs(at_b[0]).max()
        assert [float(r["B.F"]) for r in rows] == pytest.approx(np.abs(at_b[0]), rel=1e-9, abs=1e-9 * scale)
        assert [float(r["driving_torque"]) for r in rows] == pytest.approx(torque, rel=1e-9,
                                                                           abs=1e-9 * np.abs(torque).max())
