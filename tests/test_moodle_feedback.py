"""The sheets handed out through Moodle: ``moodle-feedback.zip`` for *Upload multiple feedback files in a zip*.

The expected folder names come from Moodle's importer (``mod/assign/feedback/file/importziplib.php``,
``is_valid_filename_for_import``), re-written below in Python: each path part is split at ``_`` into at most five
pieces (PHP's ``explode('_', $part, 5)``); a part with four or more pieces whose second is a number that is a
participant's, and whose third and fourth name an enabled plugin, gives the file to that participant.
"""

from __future__ import annotations

import io
import pathlib
import zipfile

import pytest

from mechanisms.cli import main
from mechanisms.course.moodle import feedback_zip
from mechanisms.course.roster import Person


def moodle_import(name: str, participants: set[int]) -> tuple[int, str, str] | None:
    """What Moodle's importer makes of an archive member: (participant, plugin, file name), or None."""
    parts = name.split("/")
    while parts:
        part = parts.pop(0)
        pieces = part.split("_", 4)                  # explode('_', $part, 5)
        if len(pieces) < 4 or not pieces[1].isdigit() or int(pieces[1]) not in participants:
            continue
        if (pieces[2], pieces[3]) != ("assignfeedback", "file"):
            continue
        rest = pieces[4] if len(pieces) == 5 else ""
        return int(pieces[1]), f"{pieces[2]}_{pieces[3]}", "/".join([rest, *parts]).lstrip("/")
    return None


WORKSHEET = """Identifier,"Full name","Email address",Status,Grade,"Maximum grade","Grade can be changed","Last modified (submission)","Last modified (grade)","Feedback comments"
"Учасник 1001","Anna_Maria O'Neil",anna@example.edu,"No submission",,10.00,Yes,-,-,
"Учасник 1002","=HYPERLINK(""x"")",b@example.edu,"No submission",,10.00,Yes,-,-,
"""


def test_every_student_gets_their_files_by_participant_number(tmp_path, capsys):
    (tmp_path / "worksheet.csv").write_text(WORKSHEET, encoding="utf8")
    assert main(["assign", "watt-six-bar", "--roster", str(tmp_path / "worksheet.csv"), "--seed", "3",
                 "--out", str(tmp_path / "out")]) == 0
    assert "moodle-feedback.zip" in capsys.readouterr().out
    data = (tmp_path / "out" / "moodle-feedback.zip").read_bytes()
    with zipfile.ZipFile(io.BytesIO(data)) as archive:
        got = {name: archive.read(name) for name in archive.namelist()}
    imported = {name: moodle_import(name, {1001, 1002}) for name in got}
    # a name with "_" or a formula never reaches the archive: the folders are named by the student ids
    assert imported == {f"s0{i}_{1000 + i}_assignfeedback_file/s0{i}{suffix}": (1000 + i, "assignfeedback_file",
                                                                                  f"s0{i}{suffix}")
                        for i in (1, 2) for suffix in (".html", "-answers.csv", ".toml")}
    for name, content in got.items():        # each member is the file written beside it
        assert content == (tmp_path / "out" / name.split("/")[1]).read_bytes()


def test_the_archive_is_the_same_byte_for_byte():
    people = {"s01": Person(name="A", identifier="Participant 7")}
    files = {"s01": [("s01.html", b"<p>sheet</p>"), ("s01-answers.csv", b"student,position\n")]}
    assert feedback_zip(files, people) == feedback_zip(dict(files), dict(people))


@pytest.mark.parametrize("people", [
    {"s01": Person(name="A", email="a@example.edu")},               # a class list without Moodle's identifiers
    {"s01": Person(name="A", identifier="Participant 7")},          # s02 not in the class list
])
def test_no_archive_without_a_participant_for_every_student(people):
    files = {"s01": [("s01.html", b"x")], "s02": [("s02.html", b"y")]}
    assert feedback_zip(files, people) is None


def test_no_archive_for_a_class_list_that_is_not_moodles(tmp_path, capsys):
    (tmp_path / "class.csv").write_text("Name,Email\nAnna,anna@example.edu\n", encoding="utf8")
    assert main(["assign", "crank-slider", "--roster", str(tmp_path / "class.csv"), "--seed", "1",
                 "--out", str(tmp_path / "out")]) == 0
    assert "moodle-feedback.zip" not in capsys.readouterr().out
    assert not (tmp_path / "out" / "moodle-feedback.zip").exists()
