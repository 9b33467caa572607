"""Fuzzing the course tools' readers: any answer file, class list or worksheet text is either read or refused with
the package's own error (a :class:`~mechanisms.core.errors.MechanismError` naming the file); no foreign exception
(KeyError, IndexError, ValueError, UnicodeError …) escapes, and what is read can be written (report, marks,
grades) without one either.

Hypothesis is derandomized (tests/conftest.py): the same examples on every run. The texts are built from the
pieces that make CSV files hard: separators, quotes, line ends, byte-order marks, decimal commas, minus signs,
formula starts, and the key's own column names and ids, so that many examples get past the header.
"""

from __future__ import annotations

import codecs
import pathlib
import tempfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechanisms.core.errors import MechanismError
from mechanisms.course.grading import check_files
from mechanisms.course.moodle import fill_worksheet, grades_csv
from mechanisms.course.roster import read_roster
from mechanisms.present.escape import csv_cell, csv_cell_value

FUZZ = settings(derandomize=True, deadline=None, max_examples=300,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])

KEY = ("student,name,email,identifier,position,phi_deg,B.s,B.v\n"
       "s01,Ann,ann@x.org,P1,1,15.0,0.25,-1.5\n"
       "s01,Ann,ann@x.org,P1,2,30.0,1.5,2.0\n"
       "s02,Bob,bob@x.org,P2,1,45.0,0.3,0.0\n")
"""A key written by hand, with a class list (so that worksheets can be filled)."""

PIECES = [",", ";", "\t", '"', "'", "\n", "\r\n", "\r", " ", "\u00a0", "\u2212", "-", "=", "+", "@", "\0",
          "0", "1", "5", ".", ",5", "1,500", "15,0", "1e3", "nan", "inf", "１", "é", "\ufeff",
          "student", "Student", "position", "phi_deg", "B.s", "b.S", "B.v", "name", "email", "identifier",
          "s01", "S02", "s3", "Name", "Full name", "Email address", "Identifier", "Grade", "Feedback comments",
          "Maximum grade", "P1", "P2", "ann@x.org", "Participant 7"]

csv_texts = st.lists(st.sampled_from(PIECES), max_size=40).map("".join)
"""Text made of CSV's hard pieces."""

encodings = st.sampled_from([b"", codecs.BOM_UTF8, "utf-16-le", "utf-16-be", "latin-1"])


def _bytes(text: str, how: bytes | str) -> bytes:
    if isinstance(how, bytes):
        return how + text.encode("utf-8")
    if how == "latin-1":
        return text.encode("latin-1", errors="replace")
    bom = codecs.BOM_UTF16_LE if how == "utf-16-le" else codecs.BOM_UTF16_BE
    return bom + text.encode(how, errors="surrogatepass")


def _folder() -> pathlib.Path:
    folder = pathlib.Path(tempfile.mkdtemp(prefix="fuzz-course-"))
    (folder / "key.csv").write_text(KEY, encoding="utf-8")
    return folder


FOLDER = _folder()


def _read_or_refused(name: str, data: bytes, read):
    """``read(path)`` of a file holding ``data``, or None if the package refused it with its own error naming the
    file; any other exception fails the test."""
    path = FOLDER / name
    path.write_bytes(data)
    try:
        return read(path)
    except MechanismError as error:
        assert str(path) in str(error)
        return None


@FUZZ
@given(st.one_of(csv_texts.map(lambda t: "student,position,phi_deg,B.s,B.v\n" + t), csv_texts), encodings)
def test_answer_files_are_read_or_refused(text, how):
    report = _read_or_refused("answers.csv", _bytes(text, how), lambda p: check_files(FOLDER / "key.csv", [p]))
    if report is not None:
        report.text()
        report.csv()
        grades_csv(report)
        for mark in report.marks:          # nothing NaN silently: an answer read is a finite number
            assert mark.answer is None or abs(mark.answer) < float("inf")


@FUZZ
@given(st.one_of(csv_texts.map(lambda t: "Name,Email,Identifier\n" + t), csv_texts), encodings)
def test_class_lists_are_read_or_refused(text, how):
    people = _read_or_refused("class.csv", _bytes(text, how), read_roster)
    assert people is None or (people and all(p.label for p in people))


@FUZZ
@given(st.one_of(csv_texts.map(lambda t: "Identifier,Grade,Feedback comments\n" + t), csv_texts))
def test_worksheets_are_filled_or_refused(text):
    path = FOLDER / "worksheet.csv"
    path.write_text(text, encoding="utf-8", newline="")
    report = check_files(FOLDER / "key.csv", [FOLDER / "key.csv"])
    try:
        fill_worksheet(report, path, FOLDER / "filled.csv")
    except MechanismError as error:
        assert str(path) in str(error) or "filled.csv" in str(error)


@settings(derandomize=True, deadline=None, max_examples=500)
@given(st.text())
def test_the_neutraliser_round_trips_and_leaves_no_formula(text):
    cell = csv_cell(text)
    assert csv_cell_value(cell) == text
    assert cell[:1] not in ("=", "+", "-", "@", "\t", "\r")
