"""Grades for a learning platform (mechanisms.course.moodle): Moodle's grading worksheet filled in a round trip
(assign --roster → answers → check --moodle), every other byte of it unchanged; the plain grades CSV; bad input.

The worksheet in tests/data/moodle/ has the columns Moodle's assignment writes (mod/assign/gradingtable.php:
Identifier, Full name, Email address, Status, Grade, Maximum grade, Grade can be changed, Last modified
(submission), Online text, Last modified (grade), Feedback comments), quoted as PHP's fputcsv quotes them. The
filled worksheet expected, worksheet-graded.csv, is written by hand: grades = 10 × right / 15 (5 quantities
at 3 positions), the feedback as the module documents it; the crank angles come from the key.
"""

from __future__ import annotations

import codecs
import csv
import pathlib
import shutil

import pytest

from mechanisms.cli import main
from mechanisms.course.grading import check_files
from mechanisms.course.moodle import WorksheetError, fill_worksheet, grades_csv

DATA = pathlib.Path(__file__).parent / "data" / "moodle"


def make_course(folder: pathlib.Path, roster: pathlib.Path) -> pathlib.Path:
    """An assignment for the class list ``roster`` in ``folder/course``, and ``folder/answers.csv``: s01 all right,
    s02 one wrong (B.v at position 1 × 1.5), the others none."""
    assert main(["assign", "crank-slider", "--roster", str(roster), "--seed", "11", "--positions",
                 "3", "--out", str(folder / "course")]) == 0
    rows = list(csv.DictReader((folder / "course" / "key.csv").open(encoding="utf8")))
    answers = [dict(r) for r in rows if r["student"] in ("s01", "s02")]
    for row in answers:
        if row["student"] == "s02" and row["position"] == "1":
            row["B.v"] = repr(1.5 * float(row["B.v"]))
    with (folder / "answers.csv").open("w", encoding="utf8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(answers)
    return folder


@pytest.fixture(scope="module")
def course(tmp_path_factory) -> pathlib.Path:
    """The class list's three students, their assignment, and answers: s01 all right, s02 one wrong, s03 none."""
    return make_course(tmp_path_factory.mktemp("moodle"), DATA / "class-list.csv")


def phi(folder: pathlib.Path) -> dict[str, str]:
    """The crank angles of the key, as the feedback prints them ({s02_phi1} …)."""
    rows = csv.DictReader((folder / "course" / "key.csv").open(encoding="utf8"))
    return {f"{r['student']}_phi{r['position']}": f"{float(r['phi_deg']):g}" for r in rows}


def expected(folder: pathlib.Path) -> str:
    return (DATA / "worksheet-graded.csv").read_bytes().decode("utf-8").format(**phi(folder))


def test_the_key_and_sheets_carry_the_class_list(course):
    rows = list(csv.DictReader((course / "course" / "key.csv").open(encoding="utf8")))
    assert list(rows[0])[:6] == ["student", "name", "email", "identifier", "position", "phi_deg"]
    assert [(r["student"], r["name"], r["email"]) for r in rows[::3]] == [
        ("s01", "Olena Kovalenko", "olena.kovalenko@example.edu"), ("s02", "José Núñez", "Jose.Nunez@Example.edu"),
        ("s03", "Seán O'Brien", "SEAN.OBRIEN@example.edu")]
    assert "Name: José Núñez" in (course / "course" / "s02.md").read_text(encoding="utf8")
    assert "Name: Seán O&#x27;Brien" in (course / "course" / "s03.html").read_text(encoding="utf8")


def test_round_trip_fills_grades_and_feedback_and_nothing_else(course, capsys):
    out = course / "graded.csv"
    status = main(["check", str(course / "course" / "key.csv"), str(course / "answers.csv"),
                   "--moodle", str(DATA / "worksheet.csv"), "--moodle-out", str(out)])
    assert status == 0
    printed = capsys.readouterr().out
    assert "s02 (José Núñez): 14 of 15 right (93 %)" in printed
    assert f"Moodle worksheet: 3 grades and feedback comments written to {out} (1 other row(s) left" in printed
    assert out.read_bytes().decode("utf-8") == expected(course)      # byte for byte, but the filled cells


def test_default_output_beside_the_worksheet(course, tmp_path):
    worksheet = shutil.copy(DATA / "worksheet.csv", tmp_path / "Kinematics-grades.csv")
    assert main(["check", str(course / "course" / "key.csv"), str(course / "answers.csv"), "--moodle",
                 str(worksheet)]) == 0
    assert (tmp_path / "Kinematics-grades-graded.csv").read_text(encoding="utf8") == expected(course)
    assert pathlib.Path(worksheet).read_bytes() == (DATA / "worksheet.csv").read_bytes()    # the original kept


def test_bom_semicolons_and_crlf_are_kept(course, tmp_path):
    # a worksheet re-saved by a spreadsheet: BOM, ';' between cells, CRLF; the same cells filled, the rest kept
    def dialect(text: str) -> bytes:
        rows = list(csv.reader(text.splitlines()))
        # quoted where a spreadsheet quotes (a space or ';'); the filled feedback (last) only where it must be
        lines = [";".join(f'"{c}"' if (";" in c or (" " in c and i < len(row) - 1)) else c
                          for i, c in enumerate(row)) for row in rows]
        return codecs.BOM_UTF8 + ("\r\n".join(lines) + "\r\n").encode("utf-8")

    original = (DATA / "worksheet.csv").read_text(encoding="utf8").replace('""s01-answers.csv""', "s01-answers")
    (tmp_path / "sheet.csv").write_bytes(dialect(original))
    report = check_files(course / "course" / "key.csv", [course / "answers.csv"])
    result = fill_worksheet(report, tmp_path / "sheet.csv", tmp_path / "out.csv")
    assert result.filled == {"s01": 2, "s02": 3, "s03": 4} and result.untouched == [5]
    filled = expected(course).replace('""s01-answers.csv""', "s01-answers")
    # the feedback of s03 holds ';': quoted in a ';' file
    assert (tmp_path / "out.csv").read_bytes() == dialect(filled)


def test_matched_by_identifier_when_the_worksheet_is_the_class_list(tmp_path, capsys):
    assert main(["assign", "four-bar", "--roster", str(DATA / "worksheet.csv"), "--seed", "5", "--out",
                 str(tmp_path / "c")]) == 0
    worksheet = tmp_path / "ws.csv"
    # the e-mails changed since: the identifier still finds each row
    worksheet.write_text((DATA / "worksheet.csv").read_text(encoding="utf8").replace("@example.edu", "@new.edu"),
                         encoding="utf8")
    assert main(["check", str(tmp_path / "c" / "key.csv"), str(tmp_path / "c" / "key.csv"), "--moodle",
                 str(worksheet), "--grades", str(tmp_path / "grades.csv")]) == 0
    rows = list(csv.DictReader((tmp_path / "ws-graded.csv").open(encoding="utf8")))
    assert [r["Grade"] for r in rows] == ["10.00"] * 4            # the key as answers: 18 of 18 right each
    grades = list(csv.DictReader((tmp_path / "grades.csv").open(encoding="utf8")))
    assert list(grades[0]) == ["student", "identifier", "name", "email", "grade", "feedback"]
    assert grades[3] == {"student": "s04", "identifier": "Participant 2318107", "name": "Ärne Teacher-Assistant",
                         "email": "arne.ta@example.edu", "grade": "100.00", "feedback": "18 of 18 answers right (100 %)."}


def test_plain_grades_csv_without_a_class_list(tmp_path):
    main(["assign", "crank-slider", "--students", "2", "--seed", "3", "--out", str(tmp_path)])
    report = check_files(tmp_path / "key.csv", [tmp_path / "key.csv"])
    assert grades_csv(report).splitlines()[1:] == ["s01,,,,100.00,15 of 15 answers right (100 %).",
                                                   "s02,,,,100.00,15 of 15 answers right (100 %)."]


def worksheet_error(course, tmp_path, text: str) -> str:
    (tmp_path / "ws.csv").write_text(text, encoding="utf8")
    status = main(["check", str(course / "course" / "key.csv"), str(course / "answers.csv"), "--moodle",
                   str(tmp_path / "ws.csv")])
    assert status == 2 and not (tmp_path / "ws-graded.csv").exists()
    return str(tmp_path / "ws.csv")


HEADER = ('Identifier,"Full name","Email address",Status,Grade,"Maximum grade","Grade can be changed",'
          '"Last modified (grade)","Feedback comments"\n')
ROWS = ['"Participant 1","Olena Kovalenko",olena.kovalenko@example.edu,x,,10.00,Yes,-,\n',
        '"Participant 2","José Núñez",jose.nunez@example.edu,x,,10.00,Yes,-,\n',
        '"Participant 3","Seán O\'Brien",sean.obrien@example.edu,x,,10.00,Yes,-,\n']


@pytest.mark.parametrize("text, message", [
    (HEADER.replace(',"Feedback comments"', "") + "".join(r[:-2] + "\n" for r in ROWS),
     "line 1: no column 'Feedback comments' (turn on the feedback type 'Feedback comments'"),
    # no maximum grade beside it, and a name in no language known: nothing says which column is the grade
    (HEADER.replace('Grade,"Maximum grade"', "Mark") + "".join(r.replace(",,10.00,", ",,") for r in ROWS),
     "line 1: no column 'Grade'"),
    # neither participant identifiers nor e-mail addresses in any column
    (HEADER.replace('Identifier,"Full name","Email address"', '"Full name"')
     + "".join(",".join(c for c in r.split(",") if "@" not in c and "Participant" not in c) for r in ROWS),
     "no column 'Identifier or Email address'"),
    (HEADER + "".join(ROWS[:2]), "no row for 1 student(s) of the key key.csv: s03 (Seán O'Brien), email "
                                 "'SEAN.OBRIEN@example.edu'"),
    (HEADER + "".join(ROWS) + ROWS[1].replace("Participant 2", "Participant 9"),
     "lines 3 and 5: the same email 'jose.nunez@example.edu' twice"),
    (HEADER + ROWS[0] + ROWS[1].replace("10.00", "ten") + ROWS[2], "line 3: Maximum grade 'ten' is not a number"),
    (HEADER + ROWS[0] + ROWS[1].split(",Yes")[0] + "\n" + ROWS[2], "line 3: fewer cells than columns"),
    (HEADER + ROWS[0] + '"Participant 2,José\n', "line 3: a quoted cell is not closed"),
])
def test_bad_worksheets_name_the_file_line_and_cause(course, tmp_path, capsys, text, message):
    path = worksheet_error(course, tmp_path, text)
    err = capsys.readouterr().err
    assert err.startswith(f"error: worksheet {path}") and message in err and "Traceback" not in err


def test_a_key_without_a_class_list_cannot_fill_a_worksheet(tmp_path, capsys):
    main(["assign", "crank-slider", "--students", "2", "--seed", "3", "--out", str(tmp_path)])
    status = main(["check", str(tmp_path / "key.csv"), str(tmp_path / "key.csv"), "--moodle",
                   str(DATA / "worksheet.csv"), "--moodle-out", str(tmp_path / "out.csv")])
    assert status == 2 and "make the assignment with --roster" in capsys.readouterr().err


def test_assign_with_a_bad_class_list_or_count(tmp_path, capsys):
    (tmp_path / "bad.csv").write_text("group\nA\n", encoding="utf8")
    assert main(["assign", "four-bar", "--roster", str(tmp_path / "bad.csv"), "--out", str(tmp_path)]) == 2
    assert "error: class list" in capsys.readouterr().err
    assert main(["assign", "four-bar", "--roster", str(DATA / "class-list.csv"), "--students", "5", "--out",
                 str(tmp_path)]) == 2
    assert "the number of students of the class list" in capsys.readouterr().err
    assert main(["assign", "four-bar", "--out", str(tmp_path)]) == 2
    assert "or a class list given with --roster" in capsys.readouterr().err
