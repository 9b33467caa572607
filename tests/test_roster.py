"""Class lists (mechanisms.course.roster): the columns a list may use, spreadsheets' CSV dialects, bad lists."""

from __future__ import annotations

import pathlib

import pytest

from mechanisms.course.roster import Person, RosterError, read_roster

DATA = pathlib.Path(__file__).parent / "data" / "moodle"


def write(tmp_path: pathlib.Path, data: bytes | str, name: str = "class.csv") -> pathlib.Path:
    path = tmp_path / name
    path.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
    return path


def test_a_spreadsheet_list_with_bom_semicolons_crlf_and_quotes():
    # tests/data/moodle/class-list.csv, written by hand: BOM, ';', CRLF, a quoted cell holding a ';'
    assert read_roster(DATA / "class-list.csv") == [
        Person("Olena Kovalenko", "olena.kovalenko@example.edu"),
        Person("José Núñez", "Jose.Nunez@Example.edu"),
        Person("Seán O'Brien", "SEAN.OBRIEN@example.edu"),
    ]


def test_moodles_worksheet_is_a_class_list():
    # the worksheet's Identifier, Full name and Email address (tests/data/moodle/worksheet.csv)
    people = read_roster(DATA / "worksheet.csv")
    assert people[0] == Person("Olena Kovalenko", "olena.kovalenko@example.edu", "Participant 2318104")
    assert [p.name for p in people] == ["Olena Kovalenko", "José Núñez", "Seán O'Brien", "Ärne Teacher-Assistant"]


@pytest.mark.parametrize("text, expected", [
    ("Full_Name,E-MAIL\nAnn Example,ann@example.edu\n", [Person("Ann Example", "ann@example.edu")]),
    ("name\tstudent id\nБорис Іванов\t42\n", [Person("Борис Іванов", "", "42")]),          # tabs, Cyrillic
    ("Identifier,ID number,Name\nParticipant 7,A-1,  Ann   Example \n", [Person("Ann Example", "", "Participant 7")]),
    ('email\n"x@example.edu"\n\n\ny@example.edu', [Person("", "x@example.edu"), Person("", "y@example.edu")]),
    ("Surname,First name,Username\nNúñez,José,jnunez\r\n", [Person("José Núñez", "", "jnunez")]),
])
def test_accepted_columns_and_dialects(tmp_path, text, expected):
    assert read_roster(write(tmp_path, text)) == expected


@pytest.mark.parametrize("text, message", [
    ("student,group\ns01,A\n", "no column names a student (found 'student', 'group'); the accepted column names"),
    ("name,email\nAnn,a@x.org\nBob,A@X.ORG\n", "lines 2 and 3: the same email 'A@X.ORG' twice"),
    ("name,id\nAnn,7\n\nBob,7\n", "lines 2 and 4: the same identifier '7' twice"),
    ("name,email,group\nAnn,a@x.org,A\n,,\n , ,B\n", ", line 4: no name, e-mail or identifier"),
    ("name,email\nSmith, Ann,a@x.org\n", "line 2: more cells than the 2 columns"),
    ("name,email\n", "no students"),
    ("First name,email\nAnn,a@x.org\n", "a first name needs a last name column too"),
    ('name\n"Ann\n', 'line 2: a quoted cell is not closed'),
    ("", "empty"),
])
def test_bad_lists_name_the_file_line_and_cause(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(RosterError) as error:
        read_roster(path)
    assert str(path) in str(error.value) and message in str(error.value)


def test_a_list_that_is_not_utf8(tmp_path):
    path = write(tmp_path, "name\nJosé\n".encode("cp1252"))
    with pytest.raises(RosterError, match="not UTF-8 text .*save it as CSV in UTF-8"):
        read_roster(path)


def test_a_missing_list(tmp_path):
    with pytest.raises(RosterError, match="no such file"):
        read_roster(tmp_path / "nowhere.csv")
