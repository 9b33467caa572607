"""Grades for a learning platform: Moodle's assignment grading worksheet and its archive of submissions, and a
plain CSV for any other.

Moodle's assignment activity, with the feedback types *Offline grading worksheet* and *Feedback comments*
on, exports a *grading worksheet* (View all submissions → Grading action → Download grading worksheet) and
imports it back (Upload grading worksheet). ``mod/assign/gradingtable.php`` writes its columns with the
language strings of the teacher's interface, so their names depend on the language: ``Identifier``,
``Идентификатор``, ``Ідентифікатор`` (:data:`COLUMN_NAMES`; :data:`WORKSHEET_COLUMNS` are the English ones), and
Moodle's importer (``assignfeedback_offline``) finds them again by those names in the language of the teacher
who uploads the file. So the worksheet is read in any language and its header is never touched; its columns
are recognised by what they hold (:func:`read_worksheet`):

- the identifier: every cell a word and a number, the same word in every row (``Participant 2318104``,
  ``Участник2318104``, ``Учасник2318104``: ``hiddenuser`` and the participant's number);
- the e-mail: every cell an e-mail address;
- the maximum grade: every cell a positive number; the grade is the column just before it (Moodle writes
  them side by side), empty or numbers;
- the feedback comments: Moodle writes the feedback plugins' columns last, so the last column after the grade
  with an empty cell (a ``Last modified (grade)`` column is never empty: it holds ``-`` or a date).

A column whose name is one of :data:`COLUMN_NAMES` (English, Russian and Ukrainian, from Moodle's language
packs) is taken where the content leaves a choice, and where the worksheet has no rows.

:func:`fill_worksheet` writes each graded student's grade (``Maximum grade`` × right answers / answers
asked, two decimals) and a feedback comment into that student's row, found by identifier (the participant's
number, whatever the language) or else by e-mail (from the key made with ``assign --roster``), and leaves every
other cell, row and byte of the file as it was: its encoding, byte-order mark, separator, quoting and line
endings. :func:`grades_csv` writes the same grades as a plain CSV for any other platform (:data:`GRADES_COLUMNS`).

*Download all submissions* gives a zip archive, one folder per student and submission plugin, named by
``mod/assign/classes/downloader.php`` as ``FULL NAME_NUMBER_assignsubmission_file/answers.csv`` (Moodle 3.1 to
4.0: ``…_assignsubmission_file_/answers.csv``; with *Download submissions in folders* off, one file
``FULL NAME_NUMBER_assignsubmission_file_answers.csv``), where NUMBER is the participant's number of the
worksheet's identifier. :func:`answer_files` reads such an archive in memory, never writing it to disk, and
with the worksheet knows which account handed in each answer file: its rows are that student's answers, and a
row that names another student is reported, not graded (:class:`mechanisms.course.grading.AnswerFile`). An
archive member with an absolute name or ``..`` stops the reading; one larger than :data:`MEMBER_LIMIT`, an
encrypted one, and one that is not a CSV file are left out with a note; so is anything past
:data:`TOTAL_LIMIT` bytes or :data:`MEMBERS_LIMIT` members (a *zip bomb* is not unpacked).

The other way, the sheets reach the students as *feedback files*: with the feedback type *Feedback files* on,
*Grading action → Upload multiple feedback files in a zip* takes an archive of folders named
``NAME_NUMBER_assignfeedback_file`` (``mod/assign/feedback/file/importziplib.php`` splits a folder's name at
``_`` and takes the second part as the participant's number and the third and fourth as the plugin) and gives
every file of a folder to that participant. :func:`feedback_zip` writes such an archive; its folders are named
by the student ids (``s01_2318104_assignfeedback_file``), never by names.

Spreadsheets open these files, so every text cell written (the student id, identifier, name, e-mail and
feedback comment) goes through :func:`mechanisms.present.escape.csv_cell`: one that could start a formula
(``=``, ``+``, ``-``, ``@``, a tab or a carriage return first) gets a leading ``'``. The grade is a number and is
written as one. (The feedback comments this module writes start with a digit, so they never need it.)
"""

from __future__ import annotations

import io
import math
import pathlib
import re
import zipfile
import zlib
from dataclasses import dataclass

from ..present.escape import csv_cell
from .csvtext import CourseFileError, CsvText, csv_lines, header_key, read_csv_text, replace_cells, write_file
from .grading import AnswerFile, Key, Report
from .roster import Person, email_column, participant_column, participant_number

__all__ = ["WORKSHEET_COLUMNS", "COLUMN_NAMES", "GRADES_COLUMNS", "WorksheetError", "SubmissionsError",
           "StudentGrade", "student_grades", "feedback_text", "Worksheet", "read_worksheet", "fill_worksheet",
           "WorksheetResult", "grades_csv", "Submission", "read_submissions", "answer_files", "MEMBER_LIMIT",
           "TOTAL_LIMIT", "MEMBERS_LIMIT", "feedback_zip", "FEEDBACK_FOLDER"]

WORKSHEET_COLUMNS = ("Identifier", "Full name", "Email address", "Status", "Grade", "Maximum grade",
                     "Grade can be changed", "Last modified (submission)", "Online text", "Last modified (grade)",
                     "Feedback comments")
"""The columns of Moodle's grading worksheet in English for an assignment with online text submissions, a point
grade and feedback comments (older versions write ``Maximum Grade``). Columns are found by what they hold
(see the module's notes); only the grade, the feedback comments and the identifier or the e-mail are needed."""

COLUMN_NAMES: dict[str, tuple[str, ...]] = {
    "identifier": ("Identifier", "Идентификатор", "Ідентифікатор"),
    "email": ("Email address", "Адрес электронной почты", "Електронна пошта"),
    "grade": ("Grade", "Оценка", "Оцінка"),
    "maximum": ("Maximum grade", "Максимальная оценка", "Максимальна оцінка"),
    "scale": ("Scale", "Шкала"),
    "feedback": ("Feedback comments", "Отзыв в виде комментария", "Відгук - коментарем"),
}
"""The worksheet's column names in English, Russian and Ukrainian: Moodle's strings ``assign/recordid``,
``email``, ``grade`` (``gradenoun``), ``assign/maxgrade``, ``assign/scale`` and ``assignfeedback_comments/pluginname``
of its language packs."""

_ROLE_NAMES = {"identifier": "Identifier", "email": "Email address", "grade": "Grade", "maximum": "Maximum grade",
               "feedback": "Feedback comments"}
_NAMED = {header_key(name): role for role, names in COLUMN_NAMES.items() for name in names}

GRADES_COLUMNS = ("student", "identifier", "name", "email", "grade", "feedback")
"""The plain grades CSV: the key's student id, who the student is (from the class list), the grade in
percent (0–100, two decimals) and the feedback comment (text cells spreadsheet-safe, see the module's notes)."""

MEMBER_LIMIT = 1_000_000
"""The largest archive member read (bytes): an answer file is a few kilobytes."""
TOTAL_LIMIT = 50_000_000
"""The most bytes read from one archive."""
MEMBERS_LIMIT = 10_000
"""The most members an archive may have."""


class WorksheetError(CourseFileError):
    """A grading worksheet that cannot be filled; the message names the file, the line and the cause."""


class SubmissionsError(CourseFileError):
    """An archive of submissions that cannot be read; the message names the archive, the member and the cause."""


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
    """A short feedback comment for a student: the score, then what was wrong, missing or unreadable, then the
    notes about their files (a row for another student)."""
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
    return " ".join(parts + report.notes.get(student, []))


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


def _number(text: str) -> float | None:
    """A cell's number (``10.00``, ``10,00``), or None."""
    try:
        value = float(text.strip().replace(",", "."))
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _identity(field: str, text: str) -> str:
    """How a row's identifier or e-mail is compared: a participant by number (whatever the language), the rest
    ignoring case."""
    number = participant_number(text) if field == "identifier" else None
    return f"#{number}" if number is not None else " ".join(text.split()).casefold()


@dataclass(frozen=True)
class Worksheet:
    """A grading worksheet as read: its text and the column of each role (``identifier``, ``email``, ``grade``,
    ``maximum``, ``feedback``; the first two may be missing, not both)."""

    table: CsvText
    columns: dict[str, int]
    header_index: int

    @property
    def where(self) -> str:
        return f"worksheet {self.table.path}"

    def records(self) -> list[int]:
        """The indexes (in ``table.records``) of the participants' rows."""
        return [i for i, r in enumerate(self.table.records) if i > self.header_index and not r.blank]

    def value(self, index: int, role: str) -> str:
        return self.table.records[index].value(self.columns[role]).strip() if role in self.columns else ""

    def rows_of(self, key: Key) -> dict[str, int]:
        """The row of each student of the key (by identifier, else e-mail).

        Raises
        ------
        WorksheetError
            If two rows have the same identifier or e-mail, a student's identifier and e-mail are on two rows,
            two students share a row, or a student has none.
        """
        rows: dict[tuple[str, str], int] = {}
        for index in self.records():
            record = self.table.records[index]
            for field in ("identifier", "email"):
                value = self.value(index, field)
                if value and (field, _identity(field, value)) in rows:
                    raise WorksheetError(f"{self.where}, lines {self.table.records[rows[field, _identity(field, value)]].line}"
                                         f" and {record.line}: the same {field} {value!r} twice")
                if value:
                    rows[field, _identity(field, value)] = index
        found: dict[str, int] = {}
        missing: list[str] = []
        for student in key.students:
            person = key.people.get(student) or Person()
            given = {field: rows.get((field, _identity(field, getattr(person, field))))
                     for field in ("identifier", "email") if getattr(person, field).strip()}
            matched = {index for index in given.values() if index is not None}
            if len(matched) > 1:
                lines = " and ".join(str(self.table.records[i].line) for i in sorted(matched))
                raise WorksheetError(f"{self.where}, lines {lines}: {key.label(student)} has the identifier "
                                     f"{person.identifier!r} on one line and the e-mail {person.email!r} on another")
            if not matched:
                missing.append(f"{key.label(student)}" + "".join(f", {f} {getattr(person, f)!r}" for f in given))
                continue
            index = matched.pop()
            if index in found.values():
                other = next(s for s, i in found.items() if i == index)
                raise WorksheetError(f"{self.where}, line {self.table.records[index].line}: the row of both "
                                     f"{key.label(other)} and {key.label(student)}")
            found[student] = index
        if missing:
            raise WorksheetError(f"{self.where}: no row for {len(missing)} student(s) of the key {key.path.name}: "
                                 + "; ".join(missing) + " (is it the worksheet of this class and assignment?)")
        return found

    def participant_rows(self) -> dict[str, int]:
        """The row of each participant's number (``Participant 2318104`` → ``"2318104"``)."""
        found = {}
        for index in self.records():
            number = participant_number(self.value(index, "identifier"))
            if number is not None:
                found[number] = index
        return found


def _choose(role: str, candidates: list[int], named: list[int], header: list[str], where: str) -> int | None:
    """A role's column: the one the content allows that is also named so, else the only one the content allows,
    else the named one (no rows to tell)."""
    both = [i for i in candidates if i in named]
    if both or len(candidates) == 1:
        return (both or candidates)[0]
    if len(candidates) > 1:
        raise WorksheetError(f"{where}: the columns {', '.join(repr(header[i]) for i in candidates)} could each be "
                             f"the {_ROLE_NAMES[role]!r} column; keep the worksheet as Moodle wrote it")
    return named[0] if named else None


def _find_columns(table: CsvText, where: str) -> tuple[dict[str, int], int]:
    """The column of each role (see the module's notes), and the index of the header record."""
    header_record = table.rows[0]
    header = [cell.value.strip() for cell in header_record.cells]
    width = len(header)
    data = [[cell.value for cell in r.cells] for r in table.rows[1:]]
    seen: dict[str, int] = {}
    for index, name in enumerate(header):
        key = header_key(name)
        if key and key in seen:
            raise WorksheetError(f"{where}, line {header_record.line}: the column {name!r} appears twice")
        if key:
            seen[key] = index
    named: dict[str, list[int]] = {role: [] for role in COLUMN_NAMES}
    for index, name in enumerate(header):
        if header_key(name) in _NAMED:
            named[_NAMED[header_key(name)]].append(index)

    def cells(index: int) -> list[str]:
        return [row[index].strip() if index < len(row) else "" for row in data]

    columns: dict[str, int] = {}
    for role, finder in (("identifier", participant_column), ("email", email_column)):
        chosen = _choose(role, finder(data, width), named[role], header, where)
        if chosen is not None:
            columns[role] = chosen
    taken = set(columns.values())
    maxima = [i for i in range(1, width) if data and i not in taken and i - 1 not in taken
              and all((_number(c) or 0) > 0 for c in cells(i))
              and all(not c or _number(c) is not None for c in cells(i - 1))]
    if len(maxima) > 1:           # an ID number beside a number column: the maximum grade is the same for all
        maxima = [i for i in maxima if len(set(cells(i))) == 1] or maxima
    maximum = _choose("maximum", maxima, named["maximum"], header, where)
    if maximum is not None:
        columns["maximum"] = maximum
        columns["grade"] = maximum - 1 if maximum in maxima else (named["grade"] or [maximum - 1])[0]
    elif named["grade"]:
        columns["grade"] = named["grade"][0]
    after = columns.get("grade", width)
    last = max((i for i, name in enumerate(header) if name), default=-1)
    if named["feedback"]:
        columns["feedback"] = named["feedback"][0]
    elif last > after and last not in columns.values() and any(not c for c in cells(last)):
        columns["feedback"] = last
    missing = [_ROLE_NAMES[role] for role in ("grade", "feedback") if role not in columns]
    if "identifier" not in columns and "email" not in columns:
        missing.append("Identifier or Email address")
    if missing:
        hint = (" (turn on the feedback type 'Feedback comments' in the assignment's settings and download the "
                "worksheet again)" if _ROLE_NAMES["feedback"] in missing else "")
        raise WorksheetError(f"{where}, line {header_record.line}: no column {', '.join(map(repr, missing))}{hint}; "
                             f"found {', '.join(repr(c.value) for c in header_record.cells)}")
    if named["scale"] and "maximum" not in columns:
        raise WorksheetError(f"{where}: the assignment is graded on a scale; grades can be written for a point "
                             "grade only (Grade type: Point in the assignment's settings)")
    return columns, table.records.index(header_record)


def read_worksheet(path: str | pathlib.Path) -> Worksheet:
    """Read Moodle's grading worksheet, in any interface language, and find its columns (see the module's notes).

    Raises
    ------
    WorksheetError
        If the file cannot be read, or lacks the grade, the feedback comments, or both the identifier and the
        e-mail.
    """
    table = read_csv_text(path, "worksheet", WorksheetError)
    columns, header_index = _find_columns(table, f"worksheet {table.path}")
    return Worksheet(table, columns, header_index)


def _maximum(text: str, where: str) -> float:
    value = _number(text)     # Moodle writes 100.00, a spreadsheet may write 100,00
    if value is None:
        raise WorksheetError(f"{where}: Maximum grade {text.strip()!r} is not a number")
    if not value > 0:
        raise WorksheetError(f"{where}: Maximum grade {text.strip()!r} is not a positive number")
    return value


def fill_worksheet(report: Report, worksheet: str | pathlib.Path | Worksheet,
                   out: str | pathlib.Path) -> WorksheetResult:
    """Write the grades and feedback comments of a report into a copy of Moodle's grading worksheet.

    Parameters
    ----------
    report : Report
        The grades (:func:`mechanisms.course.grading.check_files`) of a key made with a class list.
    worksheet : str, path or Worksheet
        The worksheet as Moodle exported it, in any language (UTF-8; any separator, quoting and line endings),
        or as :func:`read_worksheet` read it.
    out : str or path
        Where to write the filled worksheet (may be the worksheet itself).

    Returns
    -------
    WorksheetResult

    Raises
    ------
    WorksheetError
        If the worksheet lacks the columns, a student's row is missing or found twice, two rows have the same
        identifier or e-mail, or the key has no class list; nothing is written then.
    """
    sheet = worksheet if isinstance(worksheet, Worksheet) else read_worksheet(worksheet)
    if not report.key.people:
        raise WorksheetError(f"key {report.key.path}: no names, e-mails or identifiers to find the students in the "
                             "worksheet by; make the assignment with --roster (the worksheet itself can be the "
                             "class list)")
    rows = sheet.rows_of(report.key)
    header = sheet.table.rows[0]
    values: dict[tuple[int, int], str] = {}
    for grade in student_grades(report):
        index = rows[grade.student]
        record = sheet.table.records[index]
        for role in ("grade", "feedback"):
            if sheet.columns[role] >= len(record.cells):
                raise WorksheetError(f"{sheet.where}, line {record.line}: fewer cells than columns (no "
                                     f"{header.cells[sheet.columns[role]].value.strip()!r} cell)")
        maximum = (_maximum(record.value(sheet.columns["maximum"]), f"{sheet.where}, line {record.line}")
                   if "maximum" in sheet.columns else 100.0)
        values[index, sheet.columns["grade"]] = f"{maximum * grade.fraction:.2f}"
        values[index, sheet.columns["feedback"]] = csv_cell(grade.feedback)
    out = write_file(out, replace_cells(sheet.table, values), "filled worksheet", WorksheetError)
    untouched = [sheet.table.records[i].line for i in sheet.records() if i not in rows.values()]
    return WorksheetResult(out, {s: sheet.table.records[i].line for s, i in rows.items()}, untouched)


# --- the archive of submissions ------------------------------------------------------------------------------

_FOLDER = re.compile(r"(?P<name>.*?)_(?P<number>\d{1,18})_(?P<plugin>assignsubmission_[a-z0-9]+)(?:_(?P<rest>.*))?",
                     re.DOTALL)
"""A member's name as ``mod/assign`` writes it: ``NAME_NUMBER_assignsubmission_TYPE`` then ``/FILE`` (folders),
``_/FILE`` (folders, Moodle 3.1–4.0) or ``_FILE`` (no folders)."""


@dataclass(frozen=True)
class Submission:
    """An archive member: who handed it in (the participant's number and name, from its folder's name; None and
    "" if its name is not Moodle's), its name in the archive and its bytes."""

    participant: str | None
    name: str
    member: str
    data: bytes


def _unsafe(name: str) -> bool:
    parts = name.replace("\\", "/").split("/")
    return name.startswith(("/", "\\")) or bool(re.match(r"[A-Za-z]:", name)) or ".." in parts


def read_submissions(path: str | pathlib.Path) -> tuple[list[Submission], list[str], list[str]]:
    """Read the CSV files of Moodle's *Download all submissions* archive, in memory.

    Returns
    -------
    submissions : list of Submission
    skipped : list of str
        Members left out that may hold answers (too large, encrypted, damaged), for the report's problems.
    notes : list of str
        Members left out that are not answer files (not CSV), for the report.

    Raises
    ------
    SubmissionsError
        If the archive cannot be read, has more than :data:`MEMBERS_LIMIT` members or a member with an absolute
        name or ``..`` (nothing is read then).
    """
    path = pathlib.Path(path)
    where = f"archive {path}"
    submissions: list[Submission] = []
    skipped: list[str] = []
    notes: list[str] = []
    try:
        with zipfile.ZipFile(path) as archive:
            members = archive.infolist()
            if len(members) > MEMBERS_LIMIT:
                raise SubmissionsError(f"{where}: {len(members)} members, more than the {MEMBERS_LIMIT} an archive "
                                       "of submissions may have")
            unsafe = next((m.filename for m in members if _unsafe(m.filename)), None)
            if unsafe is not None:
                raise SubmissionsError(f"{where}: the member {unsafe!r} has an absolute name or '..'; Moodle writes no "
                                       "such name, so the archive is not read")
            total = 0
            for member in members:
                name = member.filename
                if member.is_dir():
                    continue
                if not name.lower().endswith(".csv") or "__MACOSX/" in name or name.rpartition("/")[2].startswith("._"):
                    notes.append(f"{name} (not a CSV file)")
                    continue
                if member.flag_bits & 0x1:
                    skipped.append(f"{where}: {name}: encrypted; not read")
                    continue
                if member.file_size > MEMBER_LIMIT or total + member.file_size > TOTAL_LIMIT:
                    skipped.append(f"{where}: {name}: {member.file_size} bytes, more than an answer file; not read")
                    continue
                try:
                    with archive.open(member) as handle:
                        data = handle.read(MEMBER_LIMIT + 1)
                except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError) as failure:
                    skipped.append(f"{where}: {name}: cannot be read ({failure}); not read")
                    continue
                total += len(data)
                if len(data) > MEMBER_LIMIT or total > TOTAL_LIMIT:
                    skipped.append(f"{where}: {name}: larger than it says (more than {MEMBER_LIMIT} bytes); not read")
                    continue
                top = name.partition("/")[0] if "/" in name else name
                folder = _FOLDER.fullmatch(top)
                number = (folder["number"].lstrip("0") or "0") if folder else None
                submissions.append(Submission(number, folder["name"].strip() if folder else "", name, data))
    except (zipfile.BadZipFile, zipfile.LargeZipFile, OSError, EOFError) as failure:
        if isinstance(failure, FileNotFoundError):
            raise SubmissionsError(f"{where}: no such file") from None
        raise SubmissionsError(f"{where}: not a zip archive that can be read ({failure})") from None
    return submissions, skipped, notes


def answer_files(paths: list[str | pathlib.Path], key: Key, worksheet: Worksheet | None = None
                 ) -> tuple[list[str | pathlib.Path | AnswerFile], list[str], list[str]]:
    """The answer files to grade: the paths as they are, and the CSV files of each archive of submissions
    (``.zip``), each with the account that handed it in when the worksheet tells it.

    Returns
    -------
    files : list
        Paths and :class:`mechanisms.course.grading.AnswerFile` objects.
    problems : list of str
        Answer files not graded (an account that is not a student of the key, a member not read).
    notes : list of str
        What else the archives held, and how their files were matched.
    """
    files: list[str | pathlib.Path | AnswerFile] = []
    problems: list[str] = []
    notes: list[str] = []
    participants = worksheet.participant_rows() if worksheet is not None else {}
    students = ({index: student for student, index in worksheet.rows_of(key).items()}
                if worksheet is not None and key.people else {})
    for path in paths:
        if pathlib.Path(path).suffix.lower() != ".zip":
            files.append(path)
            continue
        name = pathlib.Path(path).name
        found, skipped, ignored = read_submissions(path)
        problems += skipped
        if ignored:
            notes.append(f"{name}: left out {len(ignored)} file(s) that are not CSV: " + ", ".join(ignored))
        unknown = 0
        for item in found:
            label = f"{name}: {item.member}"
            account = f"{item.name or 'participant'}, participant {item.participant}"
            if item.participant is None or worksheet is None:
                unknown += 1
                files.append(AnswerFile(label, item.data))
                continue
            row = participants.get(item.participant)
            if row is None:
                problems.append(f"not graded: {label}: handed in by {account}, who has no row in the {worksheet.where}")
            elif row not in students:
                problems.append(f"not graded: {label}: handed in by {account}, who is not a student of the key "
                                f"{key.path.name}")
            else:
                files.append(AnswerFile(label, item.data, students[row], account))
        if unknown:
            why = ("not in Moodle's folders of submissions" if worksheet is not None
                   else "the accounts are known with --moodle WORKSHEET.csv only")
            notes.append(f"{name}: {unknown} file(s) graded by their student column ({why})")
    return files, problems, notes


def grades_csv(report: Report) -> str:
    """The grades as a plain CSV (:data:`GRADES_COLUMNS`; grade in percent), one row per student of the key."""
    rows = [(g.student, (g.person or Person()).identifier, (g.person or Person()).name, (g.person or Person()).email,
             f"{100 * g.fraction:.2f}", g.feedback) for g in student_grades(report)]
    return csv_lines([GRADES_COLUMNS, *rows])


FEEDBACK_FOLDER = "{student}_{number}_assignfeedback_file"
"""The folder of a student's files in :func:`feedback_zip`: Moodle's importer reads the participant's number
after the first ``_`` and the plugin (``assignfeedback``, ``file``) after it; the first part (a student id
here) is not used, so no name reaches the archive."""


def feedback_zip(files: dict[str, list[tuple[str, bytes]]], people: dict[str, Person]) -> bytes | None:
    """An archive for Moodle's *Upload multiple feedback files in a zip*: each student's files in the folder
    of their participant number (:data:`FEEDBACK_FOLDER`).

    Parameters
    ----------
    files : dict
        Student id → ``[(file name, content), …]`` (names without folders, such as ``s01.html``).
    people : dict
        Student id → the class list's :class:`~mechanisms.course.roster.Person`.

    Returns
    -------
    bytes or None
        The zip archive, byte for byte the same for the same files (members in the given order, each dated
        1980-01-01); None unless every student's identifier is a Moodle participant identifier (a class list
        that is not Moodle's grading worksheet has no numbers to address the files to).
    """
    numbers = {student: participant_number(people[student].identifier) if student in people else None
               for student in files}
    if not files or any(number is None for number in numbers.values()):
        return None
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for student, members in files.items():
            folder = FEEDBACK_FOLDER.format(student=student, number=numbers[student])
            for name, content in members:
                info = zipfile.ZipInfo(f"{folder}/{name}", date_time=(1980, 1, 1, 0, 0, 0))
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = 0o644 << 16
                archive.writestr(info, content)
    return buffer.getvalue()
