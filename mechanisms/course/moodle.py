"""Grades for a learning platform: Moodle's assignment grading worksheet, and a plain CSV for any other.

Moodle's assignment activity, with the feedback types *Offline grading worksheet* and *Feedback comments*
on, exports a *grading worksheet* (View all submissions → Grading action → Download grading worksheet) and
imports it back (Upload grading worksheet). Its columns, as Moodle's ``mod/assign/gradingtable.php`` writes
them with its English language strings, are :data:`WORKSHEET_COLUMNS` (``Identifier`` is
``Participant NNN``, an identifier of the student in that assignment; the e-mail column is there when the
site shows e-mail addresses; columns for the submission types enabled come between). When Moodle imports it,
it finds each student by ``Identifier`` and reads ``Grade``, ``Feedback comments`` and ``Last modified
(grade)``.

:func:`fill_worksheet` writes each graded student's grade (``Maximum grade`` × right answers / answers
asked, two decimals) and a feedback comment into that student's row, found by identifier or else by
e-mail (from the key made with ``assign --roster``), and leaves every other cell, row and byte of the file
as it was: its encoding, byte-order mark, separator, quoting and line endings. :func:`grades_csv` writes the
same grades as a plain CSV for any other platform (:data:`GRADES_COLUMNS`).

Spreadsheets open these files, so every text cell written (the student id, identifier, name, e-mail and
feedback comment) goes through :func:`mechanisms.present.escape.csv_cell`: one that could start a formula
(``=``, ``+``, ``-``, ``@``, a tab or a carriage return first) gets a leading ``'``. The grade is a number and is
written as one. (The feedback comments this module writes start with a digit, so they never need it.)
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass

from ..present.escape import csv_cell
from .csvtext import CourseFileError, CsvText, csv_lines, header_key, read_csv_text, replace_cells, write_file
from .grading import Report
from .roster import Person

__all__ = ["WORKSHEET_COLUMNS", "GRADES_COLUMNS", "WorksheetError", "StudentGrade", "student_grades",
           "feedback_text", "fill_worksheet", "WorksheetResult", "grades_csv"]

WORKSHEET_COLUMNS = ("Identifier", "Full name", "Email address", "Status", "Grade", "Maximum grade",
                     "Grade can be changed", "Last modified (submission)", "Online text", "Last modified (grade)",
                     "Feedback comments")
"""The columns of Moodle's grading worksheet for an assignment with online text submissions, a point grade and
feedback comments (English; older versions write ``Maximum Grade``). Columns are found by name, whatever
their case; only ``Grade``, ``Feedback comments`` and ``Identifier`` or ``Email address`` are needed."""

GRADES_COLUMNS = ("student", "identifier", "name", "email", "grade", "feedback")
"""The plain grades CSV: the key's student id, who the student is (from the class list), the grade in
percent (0–100, two decimals) and the feedback comment (text cells spreadsheet-safe, see the module's notes)."""

_GRADE, _MAXIMUM, _FEEDBACK, _IDENTIFIER, _EMAIL, _SCALE = (header_key(n) for n in (
    "Grade", "Maximum grade", "Feedback comments", "Identifier", "Email address", "Scale"))


class WorksheetError(CourseFileError):
    """A grading worksheet that cannot be filled; the message names the file, the line and the cause."""


@dataclass(frozen=True)
class StudentGrade:
    """One student's result: right answers of those asked, and the feedback comment."""

    student: str
    person: Person | None
    right: int
    asked: int
    feedback: str

    @property
    def fraction(self) -> float:
        return self.right / self.asked if self.asked else 0.0


def feedback_text(report: Report, student: str) -> str:
    """A short feedback comment for a student: the score, then what was wrong, missing or unreadable."""
    marks = report.of(student)
    right, asked = report.score(student)
    parts = [f"{right} of {asked} answers right ({100 * right / asked:.0f} %)."]
    for status, word in (("wrong", "Wrong"), ("missing", "Missing"), ("unreadable", "Unreadable")):
        by_position: dict[int, list[str]] = {}
        for m in marks:
            if m.status == status:
                by_position.setdefault(m.position, []).append(m.quantity)
        if by_position:
            listed = "; ".join(
                f"position {p} (φ = {report.key.phi[student, p]:g}°): "
                + ("all" if len(q) == len(report.key.quantities) else ", ".join(q)) for p, q in by_position.items())
            parts.append(f"{word}: {listed}.")
    return " ".join(parts)


def student_grades(report: Report) -> list[StudentGrade]:
    """Every student of the key with their score and feedback comment, in the key's order."""
    return [StudentGrade(s, report.key.people.get(s), *report.score(s), feedback_text(report, s))
            for s in report.key.students]


@dataclass(frozen=True)
class WorksheetResult:
    """What :func:`fill_worksheet` did: the rows filled (by line), the rows of other participants left alone."""

    path: pathlib.Path
    filled: dict[str, int]
    untouched: list[int]


def _columns(table: CsvText, where: str) -> tuple[dict[str, int], int]:
    rows = table.rows
    header = rows[0]
    found: dict[str, int] = {}
    for index, cell in enumerate(header.cells):
        key = header_key(cell.value)
        if not key:        # a column without a name (a spreadsheet's trailing separator) is left as it is
            continue
        if key in found:
            raise WorksheetError(f"{where}, line {header.line}: the column {cell.value.strip()!r} appears twice")
        found[key] = index
    missing = [name for name, key in (("Grade", _GRADE), ("Feedback comments", _FEEDBACK)) if key not in found]
    if _IDENTIFIER not in found and _EMAIL not in found:
        missing.append("Identifier or Email address")
    if missing:
        hint = (" (turn on the feedback type 'Feedback comments' in the assignment's settings and download the "
                "worksheet again)" if "Feedback comments" in missing else "")
        raise WorksheetError(f"{where}, line {header.line}: no column {', '.join(map(repr, missing))}{hint}; "
                             f"found {', '.join(repr(c.value) for c in header.cells)}")
    if _SCALE in found and _MAXIMUM not in found:
        raise WorksheetError(f"{where}: the assignment is graded on a scale; grades can be written for a point "
                             "grade only (Grade type: Point in the assignment's settings)")
    return found, table.records.index(header)


def _maximum(text: str, where: str) -> float:
    try:
        value = float(text.strip().replace(",", "."))   # Moodle writes 100.00, a spreadsheet may write 100,00
    except ValueError:
        raise WorksheetError(f"{where}: Maximum grade {text.strip()!r} is not a number") from None
    if not (math.isfinite(value) and value > 0):
        raise WorksheetError(f"{where}: Maximum grade {text.strip()!r} is not a positive number")
    return value


def fill_worksheet(report: Report, worksheet: str | pathlib.Path, out: str | pathlib.Path) -> WorksheetResult:
    """Write the grades and feedback comments of a report into a copy of Moodle's grading worksheet.

    Parameters
    ----------
    report : Report
        The grades (:func:`mechanisms.course.grading.check_files`) of a key made with a class list.
    worksheet : str or path
        The worksheet as Moodle exported it (UTF-8; any separator, quoting and line endings).
    out : str or path
        Where to write the filled worksheet (may be ``worksheet`` itself).

    Returns
    -------
    WorksheetResult

    Raises
    ------
    WorksheetError
        If the worksheet lacks the columns, a student's row is missing or found twice, two rows have the same
        identifier or e-mail, or the key has no class list; nothing is written then.
    """
    table = read_csv_text(worksheet, "worksheet", WorksheetError)
    where = f"worksheet {table.path}"
    if not report.key.people:
        raise WorksheetError(f"key {report.key.path}: no names, e-mails or identifiers to find the students in the "
                             "worksheet by; make the assignment with --roster (the worksheet itself can be the "
                             "class list)")
    columns, header_index = _columns(table, where)
    rows: dict[tuple[str, str], int] = {}
    for index, record in enumerate(table.records):
        if index <= header_index or record.blank:
            continue
        for field, column in (("identifier", _IDENTIFIER), ("email", _EMAIL)):
            value = record.value(columns[column]).strip().casefold() if column in columns else ""
            if value and (field, value) in rows:
                raise WorksheetError(f"{where}, lines {table.records[rows[field, value]].line} and {record.line}: "
                                     f"the same {field} {record.value(columns[column]).strip()!r} twice")
            if value:
                rows[field, value] = index
    values: dict[tuple[int, int], str] = {}
    filled: dict[str, int] = {}
    missing: list[str] = []
    for grade in student_grades(report):
        person = grade.person or Person()
        found = {field: rows.get((field, getattr(person, field).strip().casefold()))
                 for field in ("identifier", "email") if getattr(person, field).strip()}
        matched = {index for index in found.values() if index is not None}
        if len(matched) > 1:
            lines = " and ".join(str(table.records[i].line) for i in sorted(matched))
            raise WorksheetError(f"{where}, lines {lines}: {report.key.label(grade.student)} has the identifier "
                                 f"{person.identifier!r} on one line and the e-mail {person.email!r} on another")
        if not matched:
            missing.append(f"{report.key.label(grade.student)}"
                           + "".join(f", {field} {getattr(person, field)!r}" for field in found))
            continue
        index = matched.pop()
        record = table.records[index]
        if index in filled.values():
            other = next(s for s, i in filled.items() if i == index)
            raise WorksheetError(f"{where}, line {record.line}: the row of both {report.key.label(other)} and "
                                 f"{report.key.label(grade.student)}")
        for column in (_GRADE, _FEEDBACK):
            if columns[column] >= len(record.cells):
                raise WorksheetError(f"{where}, line {record.line}: fewer cells than columns (no "
                                     f"{table.rows[0].cells[columns[column]].value.strip()!r} cell)")
        maximum = (_maximum(record.value(columns[_MAXIMUM]), f"{where}, line {record.line}")
                   if _MAXIMUM in columns else 100.0)
        values[index, columns[_GRADE]] = f"{maximum * grade.fraction:.2f}"
        values[index, columns[_FEEDBACK]] = csv_cell(grade.feedback)
        filled[grade.student] = index
    if missing:
        raise WorksheetError(f"{where}: no row for {len(missing)} student(s) of the key {report.key.path.name}: "
                             + "; ".join(missing) + " (is it the worksheet of this class and assignment?)")
    out = write_file(out, replace_cells(table, values), "filled worksheet", WorksheetError)
    untouched = [r.line for i, r in enumerate(table.records)
                 if i > header_index and not r.blank and i not in filled.values()]
    return WorksheetResult(out, {s: table.records[i].line for s, i in filled.items()}, untouched)


def grades_csv(report: Report) -> str:
    """The grades as a plain CSV (:data:`GRADES_COLUMNS`; grade in percent), one row per student of the key."""
    rows = [(g.student, (g.person or Person()).identifier, (g.person or Person()).name, (g.person or Person()).email,
             f"{100 * g.fraction:.2f}", g.feedback) for g in student_grades(report)]
    return csv_lines([GRADES_COLUMNS, *rows])
