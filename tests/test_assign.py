"""Tests of mechanisms.course.assign: variants are valid and reproducible, the key is right, the sheets are complete."""

from __future__ import annotations

import base64
import csv
import json
import math
import re

import numpy as np
import pytest

from mechanisms import CrankSlider, verify
from mechanisms.course.assign import (STEP_DEG, TASKS, Variant, answer_key, make_variant, make_variants, sheet_html,
                               sheet_markdown, student_ids, write_assignment)
from mechanisms.cli import main as cli_main
from mechanisms.core.errors import InvalidParameterError

FULL_TURN = np.radians(np.arange(0.0, 360.0, 0.5))
SEEDS = range(8)


def whole_millimetres(value: float) -> bool:
    return abs(value * 1000 - round(value * 1000)) < 1e-9


@pytest.mark.parametrize("seed", SEEDS)
def test_crank_slider_variants_are_valid(seed):
    for v in make_variants("crank-slider", 5, seed):
        m = v.mechanism
        assert all(whole_millimetres(x) for x in (m.crank, m.rod, m.offset))
        # a full revolution needs L2 > L1 + |e| (by hand: the pin is at most L1 + |e| from the guide)
        assert m.rod > m.crank + abs(m.offset)
        assert 0.2 - 0.01 <= m.crank / m.rod <= 0.35 + 0.01
        # transmission angle μ = 90° − |ψ| with sin ψ = (e − L1 sin φ)/L2 (loop closure in y), over a turn
        psi = np.arcsin((m.offset - m.crank * np.sin(FULL_TURN)) / m.rod)
        assert np.degrees(0.5 * np.pi - np.abs(psi)).min() >= 45.0
        solution = m.solve(FULL_TURN, v.omega)          # assembles everywhere, no singular position
        assert not solution.singular.any()
        assert 50 <= v.omega <= 300


@pytest.mark.parametrize("seed", SEEDS)
def test_four_bar_variants_are_crank_rockers_with_good_transmission(seed):
    for v in make_variants("four-bar", 5, seed):
        m = v.mechanism
        a, b = m.frame
        d = math.hypot(a, b)
        lengths = sorted([m.crank, m.coupler, m.rocker, d])
        # Grashof by hand: s + l < p + q, and the crank is the shortest link
        assert lengths[0] + lengths[3] < lengths[1] + lengths[2]
        assert m.crank == lengths[0]
        assert all(whole_millimetres(x) for x in (m.crank, m.coupler, m.rocker, a, b))
        # transmission angle from the cosine law in triangle ABC, |AC|² = L2² + L3² − 2 L2 L3 cos μ
        ac2 = np.abs(m.crank * np.exp(1j * FULL_TURN) - complex(a, b)) ** 2
        mu = np.degrees(np.arccos((m.coupler**2 + m.rocker**2 - ac2) / (2 * m.coupler * m.rocker)))
        assert mu.min() >= 35.0 and mu.max() <= 145.0
        solution = m.solve(FULL_TURN, v.omega)
        assert not solution.singular.any()
        # the rocker rocks: its angle stays within less than half a turn
        xi = np.unwrap(solution.angle("rocker").value)
        assert np.ptp(xi) < np.pi


@pytest.mark.parametrize("seed", SEEDS)
def test_slotted_lever_variants_oscillate(seed):
    for v in make_variants("slotted-lever", 5, seed):
        m = v.mechanism
        assert math.hypot(*m.pivot) >= 1.3 * m.crank
        xi = np.unwrap(m.solve(FULL_TURN, v.omega).angle("lever").value)
        # an oscillating lever swings through 2β with sin β = r/d (by hand), never a full turn
        assert np.ptp(xi) == pytest.approx(2 * math.asin(m.crank / math.hypot(*m.pivot)), abs=1e-4)


@pytest.mark.parametrize("name", sorted(TASKS))
def test_positions_are_distinct_multiples_of_the_step(name):
    for v in make_variants(name, 6, seed=3, positions=4):
        assert len(v.positions_deg) == 4 == len(set(v.positions_deg))
        assert list(v.positions_deg) == sorted(v.positions_deg)
        assert all(p % STEP_DEG == 0 and 0 <= p < 360 for p in v.positions_deg)


@pytest.mark.parametrize("name", sorted(TASKS))
def test_variants_are_reproducible_from_the_seed(name):
    first = [v.record() for v in make_variants(name, 4, seed=11)]
    again = [v.record() for v in make_variants(name, 4, seed=11)]
    other = [v.record() for v in make_variants(name, 4, seed=12)]
    assert first == again
    assert all(a["parameters"] != b["parameters"] for a, b in zip(first, other))
    # variant i depends on the seed and i only: a larger class keeps the variants already handed out
    assert [v.record() for v in make_variants(name, 6, seed=11)][:4] == first
    # and the students' variants differ from one another
    assert len({json.dumps(r["parameters"]) for r in first}) == 4


def test_student_ids():
    assert student_ids(3) == ["s01", "s02", "s03"]
    assert student_ids(120)[-1] == "s120" and student_ids(120)[0] == "s001"


def test_key_by_hand_for_an_axial_crank_slider_at_90_degrees():
    # hand calculation, axial (e = 0), φ = 90°: x_B = √(L2² − L1²); ẋ_B = −ω L1;
    # ẍ_B = ω² L1²/√(L2² − L1²)
    # (differentiate x = L1 cos φ + √(L2² − L1² sin² φ) twice); sin ψ = −L1 sin φ/L2, so ψ_t = 0 there and
    # ψ_tt = ω² L1/(L2 cos ψ) = ω² L1/√(L2² − L1²).
    l1, l2, omega = 0.08, 0.3, 215.0
    root = math.sqrt(l2**2 - l1**2)
    variant = Variant("s01", CrankSlider(crank=l1, rod=l2), omega, (90.0,))
    row = answer_key("crank-slider", [variant])[0]
    assert row["phi_deg"] == 90.0 and row["student"] == "s01" and row["position"] == 1
    assert row["B.s"] == pytest.approx(root, rel=1e-12)
    assert row["B.v"] == pytest.approx(-omega * l1, rel=1e-12)
    assert row["B.a"] == pytest.approx(omega**2 * l1**2 / root, rel=1e-10)
    assert row["coupler.omega"] == pytest.approx(0.0, abs=1e-9)
    assert row["coupler.alpha"] == pytest.approx(omega**2 * l1 / root, rel=1e-10)


@pytest.mark.parametrize("name", ["four-bar", "slotted-lever"])
def test_key_agrees_with_the_generic_solver(name):
    # independent reference: Newton's method on the mechanism's own constraint equations (verify.solve_generic)
    variants = make_variants(name, 3, seed=21, positions=5)
    rows = answer_key(name, variants)
    for variant in variants:
        phi = np.radians(variant.positions_deg)
        generic = verify.solve_generic(variant.mechanism, phi, variant.omega)
        mine = [r for r in rows if r["student"] == variant.student]
        angle = "coupler" if name == "four-bar" else "lever"
        if name == "four-bar":
            expected = {"coupler.angle_deg": np.degrees(generic.q[0]) % 360,
                        "rocker.angle_deg": np.degrees(generic.q[1]) % 360,
                        "coupler.omega": generic.q_t[0], "rocker.omega": generic.q_t[1],
                        "coupler.alpha": generic.q_tt[0], "rocker.alpha": generic.q_tt[1]}
        else:
            expected = {"lever.angle_deg": np.degrees(generic.q[0]) % 360, "lever.omega": generic.q_t[0],
                        "lever.alpha": generic.q_tt[0], "A.s": generic.q[1], "A.v": generic.q_t[1],
                        "A.a": generic.q_tt[1],
                        # Coriolis acceleration 2 ξ_t v_rel (its definition)
                        "A.coriolis": 2 * generic.q_t[0] * generic.q_t[1]}
        assert angle + ".omega" in expected
        for column, values in expected.items():
            got = np.array([r[column] for r in mine])
            if column.endswith("angle_deg"):
                got = (got - values + 180) % 360 - 180 + values   # compare angles modulo 360°
            np.testing.assert_allclose(got, values, rtol=1e-9, atol=1e-9, err_msg=f"{variant.student} {column}")


def test_key_columns_mean_what_the_table_command_prints(capsys):
    # the key's column names are the `table --format csv` columns: same numbers for the same variant
    variant = make_variant("four-bar", seed=5, index=0, positions=3)
    m = variant.mechanism
    status = cli_main(["table", "four-bar", "--crank", str(m.crank), "--coupler", str(m.coupler), "--rocker",
                       str(m.rocker), "--frame", f"{m.frame[0]},{m.frame[1]}", "--branch", str(m.branch),
                       "--omega", str(variant.omega), "--format", "csv", "--angles", f"0:360:{STEP_DEG}"])
    assert status == 0
    table = {float(r["phi_deg"]): r for r in csv.DictReader(capsys.readouterr().out.splitlines())}
    for row in answer_key("four-bar", [variant]):
        printed = table[row["phi_deg"]]
        for column in ("coupler.omega", "rocker.omega", "coupler.alpha", "rocker.alpha"):
            assert float(printed[column]) == pytest.approx(row[column], rel=1e-5, abs=1e-6)
        for column in ("coupler.angle_deg", "rocker.angle_deg"):   # the same angle, modulo 360°
            assert abs((float(printed[column]) - row[column] + 180) % 360 - 180) < 1e-4


def test_bad_requests():
    with pytest.raises(InvalidParameterError, match="mechanism"):
        make_variants("gear-train", 3, seed=1)
    with pytest.raises(InvalidParameterError, match="students"):
        make_variants("four-bar", 0, seed=1)
    for positions in (0, 25, 2.5):
        with pytest.raises(InvalidParameterError, match="positions"):
            make_variant("four-bar", seed=1, index=0, positions=positions)


def test_written_assignment(tmp_path):
    variants = make_variants("crank-slider", 3, seed=8)
    written = write_assignment("crank-slider", variants, tmp_path, seed=8)
    assert sorted(p.name for p in written["sheets"]) == ["s01.html", "s01.md", "s02.html", "s02.md", "s03.html",
                                                         "s03.md"]
    key = list(csv.DictReader((tmp_path / "key.csv").open()))
    assert len(key) == 3 * 3
    assert list(key[0]) == ["student", "position", "phi_deg", "B.s", "B.v", "B.a", "coupler.omega", "coupler.alpha"]
    # the key's numbers survive the CSV to the last digit
    direct = answer_key("crank-slider", variants)
    assert [float(r["B.a"]) for r in key] == [r["B.a"] for r in direct]
    for v in variants:
        form = list(csv.DictReader((tmp_path / f"{v.student}-answers.csv").open()))
        assert [(r["student"], float(r["phi_deg"])) for r in form] == [(v.student, p) for p in v.positions_deg]
        assert all(r["B.v"] == "" for r in form)
        assert (tmp_path / f"{v.student}.png").read_bytes().startswith(b"\x89PNG")
    # variants.json holds what is needed to rebuild every mechanism and its key
    record = json.loads((tmp_path / "variants.json").read_text())
    assert record["seed"] == 8 and record["mechanism"] == "crank-slider"
    rebuilt = [Variant(r["student"], CrankSlider(**r["parameters"]), r["omega"], tuple(r["positions_deg"]))
               for r in record["variants"]]
    assert answer_key("crank-slider", rebuilt) == direct


@pytest.mark.parametrize("name", sorted(TASKS))
def test_sheets_are_complete_and_self_contained(name):
    variant = make_variant(name, seed=4, index=1)
    page = sheet_html(name, variant)
    # no external resource: no links, scripts or images from elsewhere; the drawing is embedded
    assert not re.search(r"""(src|href)=["'](?!data:)""", page)
    assert "<script" not in page and "<link" not in page
    image = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', page)
    assert image and base64.b64decode(image.group(1)).startswith(b"\x89PNG")
    text = sheet_markdown(name, variant, "s02.png")
    for sheet in (page, text):
        assert variant.student in sheet
        assert f"{variant.omega:g}" in sheet
        for p in variant.positions_deg:
            assert f"{p:g}°" in sheet
        for q in TASKS[name].quantities:
            assert q.column in sheet
        for value in variant.mechanism.parameters().values():
            for number in (value if isinstance(value, tuple) else (value,)):
                assert f"{number:.3f}" in sheet or isinstance(number, int)
    # every Markdown table row has as many cells as its header (a stray | would add one)
    for block in re.findall(r"((?:^\|.*\|$\n?)+)", text, flags=re.M):
        rows = [r for r in block.strip().splitlines()]
        counts = {len(re.split(r"(?<!\\)\|", r)) for r in rows}
        assert len(counts) == 1, block


def test_sheets_are_deterministic():
    a = make_variant("slotted-lever", seed=9, index=0)
    b = make_variant("slotted-lever", seed=9, index=0)
    assert sheet_html("slotted-lever", a) == sheet_html("slotted-lever", b)


def test_sheet_symbols_are_set_as_the_book_sets_them():
    # issue 19: the sheets printed L1, ψ_t, (x_C, y_C) as plain text; expected strings written by hand
    from mechanisms.course.assign import symbol_html, symbol_markdown
    assert symbol_html("ψ_tt") == "<i>ψ</i><sub><i>tt</i></sub>"
    assert symbol_html("(x_C, y_C)") == "(<i>x</i><sub><i>C</i></sub>, <i>y</i><sub><i>C</i></sub>)"
    assert symbol_html("φ_t = ω_1") == "<i>φ</i><sub><i>t</i></sub> = <i>ω</i><sub>1</sub>"
    assert symbol_html("a^k") == "<i>a</i><sup><i>k</i></sup>"
    assert symbol_markdown("L_1") == "$L_{1}$" and symbol_markdown("a^k") == "$a^{k}$"
    assert symbol_markdown("") == ""
    # every symbol of every task is in the book's form: no digit glued to a letter (L1), no word index
    for task in TASKS.values():
        for symbol in [q.symbol for q in task.quantities]:
            assert not re.search(r"[A-Za-zα-ω]\d", symbol) and "tek" not in symbol, symbol
