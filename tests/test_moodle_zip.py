"""Moodle's "Download all submissions" archive as ``check`` takes it (mechanisms.course.moodle.answer_files): read in
memory, each answer file matched to the account that handed it in, a mismatch reported; unsafe archives refused.

The members are named as mod/assign/classes/downloader.php names them: ``FULL NAME_NUMBER_assignsubmission_file``
then ``/FILE`` (Moodle ≥ 4.1), ``_/FILE`` (3.1–4.0) or ``_FILE`` (no folders), NUMBER the participant's number of
the worksheet's identifier (``Participant 2318104``). Expected grades by hand: 10 × right / 15.
"""

from __future__ import annotations

import csv
import io
import pathlib
import zipfile

import pytest

from mechanisms.cli import main
from mechanisms.course.moodle import MEMBER_LIMIT, SubmissionsError, read_submissions
from test_moodle_languages import WORKSHEETS

@pytest.fixture(scope="module")
def course(tmp_path_factory) -> pathlib.Path:
    folder = tmp_path_factory.mktemp("zip")
    (folder / "worksheet.csv").write_text(WORKSHEETS["en"], encoding="utf8")
    assert main(["assign", "crank-slider", "--roster", str(folder / "worksheet.csv"), "--seed", "5", "--positions",
                 "3", "--out", str(folder / "course")]) == 0
    return folder


def answers(folder: pathlib.Path, student: str, named: str | None = None) -> bytes:
    """The key's rows of ``student`` as an answer file (all right), its student column set to ``named``."""
    rows = [r for r in csv.DictReader((folder / "course" / "key.csv").open(encoding="utf8")) if r["student"] == student]
    columns = ["student", "position", "phi_deg", "B.s", "B.v", "B.a", "coupler.omega", "coupler.alpha"]
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([row["student"] if named is None else named] + [row[c] for c in columns[1:]])
    return text.getvalue().encode("utf-8")


def phi(folder: pathlib.Path, student: str) -> list[str]:
    """The crank angles of a student's positions in the key, as the feedback prints them."""
    return [f"{float(r['phi_deg']):g}" for r in csv.DictReader((folder / "course" / "key.csv").open(encoding="utf8"))
            if r["student"] == student]


def archive(path: pathlib.Path, members: dict[str, bytes]) -> pathlib.Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as handle:
        for name, data in members.items():
            handle.writestr(name, data)
    return path


def check(course: pathlib.Path, zip_path: pathlib.Path, *more: str) -> tuple[int, dict[str, dict[str, str]]]:
    out = zip_path.with_suffix(".graded.csv")
    status = main(["check", str(course / "course" / "key.csv"), str(zip_path), "--moodle",
                   str(course / "worksheet.csv"), "--moodle-out", str(out), *more])
    rows = {r["Identifier"]: r for r in csv.DictReader(out.open(encoding="utf8"))} if out.exists() else {}
    return status, rows


def test_each_file_is_the_answers_of_the_account_that_handed_it_in(course, tmp_path, capsys):
    zip_path = archive(tmp_path / "submissions.zip", {
        # Moodle 4.x folders: s01's own answers
        "Olena Kovalenko_2318104_assignsubmission_file/answers.csv": answers(course, "s01"),
        # Taras hands in Olena's file: the rows say s01, the account is s02's
        "Taras Shevchuk_2318105_assignsubmission_file/answers.csv": answers(course, "s01"),
        "Taras Shevchuk_2318105_assignsubmission_onlinetext/onlinetext.html": b"<p>see file</p>",
        # Moodle 3.x folders, the student column left empty: Iryna's by her account
        "Iryna Bondar_2318106_assignsubmission_file_/mine.csv": answers(course, "s03", named=""),
    })
    status, rows = check(course, zip_path)
    printed = capsys.readouterr().out
    assert status == 1                                    # graded, with problems (the mismatch)
    assert rows["Participant 2318104"]["Grade"] == "10.00"          # 15 of 15
    assert rows["Participant 2318105"]["Grade"] == "0.00"           # nothing of his own graded
    assert rows["Participant 2318106"]["Grade"] == "10.00"          # 15 of 15, by the account
    assert rows["Participant 2318105"]["Feedback comments"] == (
        "0 of 15 answers right (0 %). Missing: position 1 (φ = {}°): all; position 2 (φ = {}°): all; position 3 "
        "(φ = {}°): all. Your file answers.csv has rows for student 's01', not s02: not graded.").format(*phi(course, "s02"))
    assert "  note       Your file answers.csv has rows for student 's01', not s02: not graded." in printed
    assert ("submissions.zip: Taras Shevchuk_2318105_assignsubmission_file/answers.csv, line 2: the row is for "
            "student 's01' but the file was handed in by Taras Shevchuk, participant 2318105 (s02 (Taras Shevchuk)); "
            "row not graded") in printed
    assert "s01 (Olena Kovalenko): 15 of 15 right (100 %)" in printed      # not counted twice, not s02's
    assert "left out 1 file(s) that are not CSV: Taras Shevchuk_2318105_assignsubmission_onlinetext/" in printed


def test_files_without_folders_and_a_participant_not_in_the_worksheet(course, tmp_path, capsys):
    zip_path = archive(tmp_path / "flat.zip", {
        "Olena Kovalenko_2318104_assignsubmission_file_answers.csv": answers(course, "s01"),
        "Guest User_9999999_assignsubmission_file_answers.csv": answers(course, "s02"),
    })
    status, rows = check(course, zip_path)
    printed = capsys.readouterr().out
    assert status == 1 and rows["Participant 2318104"]["Grade"] == "10.00"
    assert rows["Participant 2318105"]["Grade"] == "0.00"                 # the guest's file is not s02's
    assert ("not graded: flat.zip: Guest User_9999999_assignsubmission_file_answers.csv: handed in by Guest User, "
            "participant 9999999, who has no row in the worksheet") in printed


def test_without_the_worksheet_files_are_graded_by_their_student_column(course, tmp_path, capsys):
    zip_path = archive(tmp_path / "s.zip", {"Olena Kovalenko_2318104_assignsubmission_file/a.csv": answers(course, "s01")})
    assert main(["check", str(course / "course" / "key.csv"), str(zip_path)]) == 0
    printed = capsys.readouterr().out
    assert "s01 (Olena Kovalenko): 15 of 15 right (100 %)" in printed
    assert "s.zip: 1 file(s) graded by their student column (the accounts are known with --moodle" in printed


@pytest.mark.parametrize("member", ["../evil.csv", "/tmp/evil.csv", "a/../../evil.csv", "C:/evil.csv", "..\\evil.csv"])
def test_an_archive_with_an_unsafe_name_is_refused(course, tmp_path, capsys, member):
    zip_path = archive(tmp_path / "bad.zip", {"Olena Kovalenko_2318104_assignsubmission_file/a.csv": b"x",
                                             member: answers(course, "s01")})
    status, rows = check(course, zip_path)
    err = capsys.readouterr().err
    assert status == 2 and not rows and f"error: archive {zip_path}: the member {member!r}" in err
    assert not (tmp_path / "evil.csv").exists() and not (tmp_path.parent / "evil.csv").exists()


def test_a_member_too_large_is_left_out(course, tmp_path, capsys):
    # 2 MB of zeros compress to a few kB: declared larger than an answer file, never unpacked
    zip_path = archive(tmp_path / "bomb.zip", {
        "Olena Kovalenko_2318104_assignsubmission_file/a.csv": answers(course, "s01"),
        "Taras Shevchuk_2318105_assignsubmission_file/big.csv": b"0" * (2 * MEMBER_LIMIT)})
    assert zip_path.stat().st_size < 50_000
    status, rows = check(course, zip_path)
    printed = capsys.readouterr().out
    assert status == 1 and rows["Participant 2318104"]["Grade"] == "10.00"
    assert f"big.csv: {2 * MEMBER_LIMIT} bytes, more than an answer file; not read" in printed


def test_a_member_that_lies_about_its_size_is_left_out(tmp_path):
    # the central directory says 10 bytes; the data unpacks to 2 MB
    path = archive(tmp_path / "lie.zip", {"X_1_assignsubmission_file/a.csv": b"0" * (2 * MEMBER_LIMIT)})
    data = bytearray(path.read_bytes())
    central = data.rindex(b"PK\x01\x02")
    data[central + 24:central + 28] = (10).to_bytes(4, "little")         # its uncompressed size
    local = data.index(b"PK\x03\x04")
    data[local + 22:local + 26] = (10).to_bytes(4, "little")
    path.write_bytes(bytes(data))
    found, skipped, _ = read_submissions(path)
    # no more than the 10 bytes it declares are unpacked, and their checksum is not the member's
    assert found == [] and skipped == [f"archive {path}: X_1_assignsubmission_file/a.csv: cannot be read (Bad CRC-32 "
                                       "for file 'X_1_assignsubmission_file/a.csv'); not read"]


def test_not_a_zip(tmp_path):
    (tmp_path / "answers.zip").write_text("student,position\n", encoding="utf8")
    with pytest.raises(SubmissionsError, match=r"answers.zip: not a zip archive"):
        read_submissions(tmp_path / "answers.zip")
    with pytest.raises(SubmissionsError, match="no such file"):
        read_submissions(tmp_path / "missing.zip")
