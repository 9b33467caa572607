"""Tests of mechanisms.course.grading: the key graded as answers is 100 % right, perturbed answers are caught by
the stated tolerances, and malformed files give clear messages."""

from __future__ import annotations

import csv
import pathlib

import pytest

from mechanisms.course.assign import answer_key, make_variants, write_assignment
from mechanisms.course.grading import (GradingError, check_files, difference, kind_of, parse_number, read_key,
                                tolerance)


@pytest.fixture(scope="module")
def assignment(tmp_path_factory) -> pathlib.Path:
    out = tmp_path_factory.mktemp("assignment")
    write_assignment("four-bar", make_variants("four-bar", 4, seed=31), out, seed=31)
    return out


def key_rows(folder: pathlib.Path) -> list[dict]:
    return list(csv.DictReader((folder / "key.csv").open(encoding="utf8")))


def write(path: pathlib.Path, rows: list[dict], columns: list[str] | None = None, delimiter: str = ",") -> pathlib.Path:
    columns = columns or list(rows[0])
    with path.open("w", newline="", encoding="utf8") as handle:
        writer = csv.DictWriter(handle, fieldnames=columns, delimiter=delimiter, extrasaction="ignore",
                                lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
    return path


def marks_by(report) -> dict:
    return {(m.student, m.position, m.quantity): m for m in report.marks}


# --- tolerances, stated in the module: max(1 % of |key|, floor of the kind); angles: 0.1°, modulo 360° ---

def test_kinds_from_column_names():
    assert kind_of("coupler.angle_deg") == "angle"
    assert kind_of("rocker.omega") == "angular velocity"
    assert kind_of("coupler.alpha") == "angular acceleration"
    assert kind_of("B.s") == "length" and kind_of("S2.y") == "length"
    assert kind_of("B.v") == "velocity" and kind_of("A.vx") == "velocity"
    assert kind_of("B.a") == "acceleration" and kind_of("A.coriolis") == "acceleration"
    for bad in ("psi", "coupler.speed", "B."):
        with pytest.raises(GradingError, match="not a quantity column"):
            kind_of(bad)


def test_tolerance_values():
    # by hand from the stated rule
    assert tolerance("B.a", -3713.0) == pytest.approx(37.13)           # 1 % of 3713 m/s²
    assert tolerance("B.a", 1.0) == pytest.approx(0.05)                # the floor, 0.05 m/s²
    assert tolerance("B.v", 0.0) == pytest.approx(0.005)               # a slider at rest: the floor, 5 mm/s
    assert tolerance("coupler.omega", -50.1) == pytest.approx(0.501)
    assert tolerance("B.s", 0.38) == pytest.approx(0.0038)
    assert tolerance("B.s", 0.38, relative=0.001) == pytest.approx(0.00038)
    assert tolerance("coupler.angle_deg", 300.0) == 0.1                 # angles: absolute only
    assert difference("coupler.angle_deg", 359.95, 0.02) == pytest.approx(-0.07)
    assert difference("coupler.angle_deg", -10.0, 350.0) == pytest.approx(0.0)
    assert difference("B.v", 1.5, 2.0) == -0.5


def test_numbers():
    assert parse_number(" 12.5 ") == 12.5 and parse_number("-1e3") == -1000.0
    # a decimal comma that no thousands separator could be is read in any file: 12,5 is 12.5
    assert parse_number("12,5") == 12.5 and parse_number("-0,25") == -0.25 and parse_number(",5") == 0.5
    assert parse_number("1,5e3") == 1500.0 and parse_number("0,500") == 0.5
    assert parse_number("\u22120.25") == -0.25 and parse_number(" \u22121,5 ") == -1.5   # U+2212, the minus sign
    # 1,500: 1.5 with a decimal comma, 1500 with a thousands separator; only a decimal-comma file says which
    with pytest.raises(ValueError, match=r"'1,500' is ambiguous: 1.500 with a decimal comma, 1500 with a "
                                         r"thousands separator \(write it with a decimal point\)"):
        parse_number("1,500")
    assert parse_number("1,500", decimal_comma=True) == 1.5 and parse_number("-12,345", decimal_comma=True) == -12.345
    for text in ("abc", "nan", "inf", "12.5 m/s", "1,234.5", "1,2,3", "5,", "\u0661\u0662", "--1", "1.2.3"):
        with pytest.raises(ValueError, match="not a"):
            parse_number(text)


# --- grading --------------------------------------------------------------------------------------------

def test_the_key_as_answers_is_all_right(assignment):
    report = check_files(assignment / "key.csv", [assignment / "key.csv"])
    assert report.score() == (4 * 3 * 6, 4 * 3 * 6)        # 4 students × 3 positions × 6 quantities
    assert report.problems == []
    text = report.text()
    assert "Class: 72 of 72 answers right (100 %)." in text
    for student in ("s01", "s02", "s03", "s04"):
        assert f"{student}: 18 of 18 right (100 %)" in text


def test_the_key_agrees_with_the_generated_variants(assignment):
    # what the grader reads is what answer_key computed (no loss in the CSV)
    key = read_key(assignment / "key.csv")
    direct = answer_key("four-bar", make_variants("four-bar", 4, seed=31))
    for row in direct:
        assert key.values[row["student"], row["position"]] == {c: row[c] for c in key.quantities}
        assert key.phi[row["student"], row["position"]] == row["phi_deg"]


def test_perturbed_answers_are_caught(assignment, tmp_path):
    rows = key_rows(assignment)
    original = {(r["student"], int(r["position"])): dict(r) for r in rows}
    rows[0]["coupler.omega"] = repr(float(rows[0]["coupler.omega"]) * 1.02)    # 2 % off: wrong
    rows[1]["coupler.alpha"] = repr(float(rows[1]["coupler.alpha"]) * 1.005)   # 0.5 % off: right
    rows[2]["rocker.angle_deg"] = repr(float(rows[2]["rocker.angle_deg"]) + 0.3)  # 0.3° off: wrong
    rows[3]["rocker.angle_deg"] = repr(float(rows[3]["rocker.angle_deg"]) - 360.05)  # a turn less, 0.05°: right
    rows[4]["rocker.omega"] = repr(-float(rows[4]["rocker.omega"]))              # the sign: wrong
    report = check_files(assignment / "key.csv", [write(tmp_path / "answers.csv", rows)])
    marks = marks_by(report)
    s, p = rows[0]["student"], int(rows[0]["position"])
    wrong = marks[s, p, "coupler.omega"]
    assert wrong.status == "wrong"
    assert wrong.difference == pytest.approx(0.02 * float(original[s, p]["coupler.omega"]), rel=1e-9)
    assert marks[rows[1]["student"], int(rows[1]["position"]), "coupler.alpha"].status == "right"
    angle = marks[rows[2]["student"], int(rows[2]["position"]), "rocker.angle_deg"]
    assert angle.status == "wrong" and angle.difference == pytest.approx(0.3, abs=1e-9)
    assert marks[rows[3]["student"], int(rows[3]["position"]), "rocker.angle_deg"].status == "right"
    flipped = marks[rows[4]["student"], int(rows[4]["position"]), "rocker.omega"]
    assert flipped.status == "wrong" and flipped.note == "right but for the sign"
    assert report.score() == (72 - 3, 72)
    text = report.text()
    assert f"wrong      position {p} (φ = {float(original[s, p]['phi_deg']):g}°) coupler.omega" in text
    assert "+2 %" in text or "-2 %" in text
    assert "coupler.omega      11 of 12 (1 wrong)" in text


def test_missing_and_unreadable_answers(assignment, tmp_path):
    rows = [r for r in key_rows(assignment) if r["student"] != "s04"]       # s04 handed in nothing
    rows[0]["coupler.alpha"] = ""                                            # an empty cell
    rows[1]["rocker.alpha"] = "about 300"                                   # text
    answers = write(tmp_path / "answers.csv", rows, columns=[c for c in rows[0] if c != "rocker.omega"])
    report = check_files(assignment / "key.csv", [answers])
    marks = marks_by(report)
    assert marks[rows[0]["student"], int(rows[0]["position"]), "coupler.alpha"].status == "missing"
    unreadable = marks[rows[1]["student"], int(rows[1]["position"]), "rocker.alpha"]
    assert unreadable.status == "unreadable" and "'about 300' is not a number" in unreadable.note
    # the column rocker.omega was left out: every rocker.omega is missing
    assert all(m.status == "missing" for m in report.marks if m.quantity == "rocker.omega")
    assert all(m.status == "missing" for m in report.of("s04"))
    text = report.text()
    assert "s04: no answers (0 of 18 right)" in text
    assert "unreadable position" in text and "missing    position" in text
    # right: 3 students × 3 positions × 5 quantities − 2 (the empty cell and the text)
    assert report.score() == (3 * 3 * 5 - 2, 72)


def test_student_ids_ignore_case_and_spaces(assignment, tmp_path):
    rows = key_rows(assignment)
    for r in rows:
        r["student"] = f" {r['student'].upper()} "
    report = check_files(assignment / "key.csv", [write(tmp_path / "answers.csv", rows)])
    assert report.score() == (72, 72) and report.problems == []


def test_answers_in_several_files_and_any_column_order(assignment, tmp_path):
    rows = key_rows(assignment)
    files = []
    for student in ("s01", "s02", "s03", "s04"):
        mine = [r for r in rows if r["student"] == student]
        columns = ["position", "student"] + sorted(c for c in mine[0] if c not in ("student", "position", "phi_deg"))
        files.append(write(tmp_path / f"{student}.csv", mine, columns=columns))
    report = check_files(assignment / "key.csv", files)
    assert report.score() == (72, 72) and report.problems == []


def test_a_semicolon_file_with_decimal_commas_is_read(assignment, tmp_path):
    # what a spreadsheet saves in many European locales
    rows = key_rows(assignment)
    for r in rows:
        for c in r:
            if c not in ("student", "position"):
                r[c] = r[c].replace(".", ",")
    report = check_files(assignment / "key.csv", [write(tmp_path / "answers.csv", rows, delimiter=";")])
    assert report.score() == (72, 72)


def test_row_problems_are_reported_and_the_rest_graded(assignment, tmp_path):
    rows = key_rows(assignment)
    good = [dict(r) for r in rows]
    stranger = dict(rows[0], student="s99")
    bad_position = dict(rows[0], position="7")
    not_whole = dict(rows[0], position="one")
    wrong_phi = dict(rows[1], phi_deg=repr(float(rows[1]["phi_deg"]) + 15))
    repeated = dict(rows[2])
    answers = write(tmp_path / "answers.csv", good + [stranger, bad_position, not_whole, wrong_phi, repeated])
    report = check_files(assignment / "key.csv", [answers])
    assert report.score() == (72, 72)      # every good row graded
    problems = "\n".join(report.problems)
    assert len(report.problems) == 5
    assert "line 14: unknown student id 's99' (the key has s01 … s04); row ignored" in problems
    assert f"line 15: student {rows[0]['student']} has no position 7" in problems
    assert "line 16: position 'one' is not a whole number" in problems
    assert f"line 17: φ = {float(rows[1]['phi_deg']) + 15:g}° but position" in problems
    assert "line 18: a second row for" in problems
    assert "Problems in the answer files:" in report.text()


def test_a_decimal_comma_in_a_comma_file_is_a_row_problem(assignment, tmp_path):
    path = tmp_path / "answers.csv"
    lines = (assignment / "key.csv").read_text().splitlines()
    first = lines[1].split(",")
    first[3] = first[3].replace(".", ",")        # 283.15 → 283,15: one cell more than the columns
    path.write_text("\n".join([lines[0], ",".join(first)] + lines[2:]) + "\n")
    report = check_files(assignment / "key.csv", [path])
    assert any("line 2: more cells than the 9 columns (a decimal comma" in p for p in report.problems)
    assert report.score() == (72 - 6, 72)


# --- files that cannot be graded ------------------------------------------------------------------------

def test_wrong_columns(assignment, tmp_path):
    rows = key_rows(assignment)
    renamed = [{("psi" if k == "coupler.angle_deg" else k): v for k, v in r.items()} for r in rows]
    with pytest.raises(GradingError, match=r"column\(s\) not in the key: 'psi'\. The columns must be "
                                           r"student,position,phi_deg,coupler\.angle_deg"):
        check_files(assignment / "key.csv", [write(tmp_path / "a.csv", renamed)])
    no_student = [{k: v for k, v in r.items() if k != "student"} for r in rows]
    with pytest.raises(GradingError, match="no column 'student'"):
        check_files(assignment / "key.csv", [write(tmp_path / "b.csv", no_student)])
    (tmp_path / "c.csv").write_text("")
    with pytest.raises(GradingError, match="empty"):
        check_files(assignment / "key.csv", [tmp_path / "c.csv"])
    (tmp_path / "d.csv").write_bytes(b"student\x81\xffbinary")      # not UTF-8, no byte-order mark
    with pytest.raises(GradingError, match="UTF-8"):
        check_files(assignment / "key.csv", [tmp_path / "d.csv"])
    with pytest.raises(GradingError, match="no such file"):
        check_files(assignment / "key.csv", [tmp_path / "missing.csv"])
    (tmp_path / "e.csv").write_text("student,student,position\n")
    with pytest.raises(GradingError, match="student appear more than once"):
        check_files(assignment / "key.csv", [tmp_path / "e.csv"])


def test_a_bad_key(assignment, tmp_path):
    rows = key_rows(assignment)
    broken = [dict(r) for r in rows]
    broken[2]["rocker.alpha"] = "n/a"
    with pytest.raises(GradingError, match=r"key .*line 4, column rocker\.alpha: 'n/a' is not a number"):
        read_key(write(tmp_path / "k1.csv", broken))
    twice = rows + [rows[0]]
    with pytest.raises(GradingError, match="appears twice"):
        read_key(write(tmp_path / "k2.csv", twice))
    answers_as_key = [{k: v for k, v in r.items() if k != "phi_deg"} for r in rows]
    with pytest.raises(GradingError, match="the columns must be student,position,phi_deg"):
        read_key(write(tmp_path / "k3.csv", answers_as_key))
    (tmp_path / "k4.csv").write_text("student,position,phi_deg,coupler.speed\ns01,1,30,2\n")
    with pytest.raises(GradingError, match="'coupler.speed' is not a quantity column"):
        read_key(tmp_path / "k4.csv")


def test_marks_csv(assignment):
    report = check_files(assignment / "key.csv", [assignment / "key.csv"])
    marks = list(csv.DictReader(report.csv().splitlines()))
    assert len(marks) == 72
    assert {m["status"] for m in marks} == {"right"}
    assert all(float(m["difference"]) == 0.0 for m in marks)


def test_one_bad_file_among_several_is_reported_and_the_others_graded(assignment, tmp_path):
    rows = key_rows(assignment)
    good = write(tmp_path / "good.csv", [r for r in rows if r["student"] != "s02"])
    (tmp_path / "bad.csv").write_text("student,position,phi,psi\ns02,1,30,2\n")
    report = check_files(assignment / "key.csv", [good, tmp_path / "bad.csv"])
    assert report.score() == (72 - 18, 72)
    assert report.problems == [f"not graded: answer file {tmp_path / 'bad.csv'}: column(s) not in the key: 'phi', "
                               "'psi'. The columns must be student,position,phi_deg,coupler.angle_deg,"
                               "rocker.angle_deg,coupler.omega,rocker.omega,coupler.alpha,rocker.alpha "
                               "(phi_deg may be left out)"]
    assert all(m.status == "missing" for m in report.of("s02"))
    # when no answer file can be read, there is nothing to grade: an error
    with pytest.raises(GradingError, match="no answer file could be read"):
        check_files(assignment / "key.csv", [tmp_path / "bad.csv", tmp_path / "bad.csv"])


def test_a_position_without_a_row_is_reported_once(assignment, tmp_path):
    rows = key_rows(assignment)
    report = check_files(assignment / "key.csv", [write(tmp_path / "answers.csv", rows[1:])])
    first = rows[0]
    text = report.text()
    assert f"  missing    position 1 (φ = {float(first['phi_deg']):g}°): all 6 answers" in text
    assert f"position 1 (φ = {float(first['phi_deg']):g}°) coupler" not in text   # no line per quantity
    assert report.score(first["student"]) == (12, 18)
