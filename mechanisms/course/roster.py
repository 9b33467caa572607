"""The class list of a course: who the students are (name, e-mail, identifier), read from a CSV file.

``python -m mechanisms assign MECHANISM --roster CLASS.csv`` gives the students of the list their variants in
the list's order (``s01`` is the first row): the sheets carry each student's name, the key their name,
e-mail and identifier, so that ``check`` can write the grades into a learning platform's worksheet.

The columns are recognised by name, whatever their case, spaces and hyphens (:data:`COLUMNS`, in English,
Russian and Ukrainian, as Moodle names them in those languages); other columns are ignored. A file that names
no e-mail or identifier column is also searched by content: a column of e-mail addresses is the e-mail, a
column of Moodle participant identifiers (``Participant 2318104``, ``Участник2318104``: a word and a number,
the same word in every row, :func:`participant_number`) the identifier. Moodle's own files can serve as the
list, in any interface language: its assignment's grading worksheet (``Identifier``, ``Full name``, ``Email
address``), its participants' or gradebook's export (``First name``, ``Last name`` or ``Surname``, ``ID
number``, ``Email address``). The file may be in any of the dialects
spreadsheets write (:mod:`mechanisms.course.csvtext`). A cell that a spreadsheet-safe file holds with a leading
``'`` (:func:`mechanisms.present.escape.csv_cell`: ``'=x``) is read without it, so the grades CSV that
``check --grades`` writes is a class list too.
"""

from __future__ import annotations

import pathlib
import re
import unicodedata
from dataclasses import dataclass
from typing import Callable, Sequence

from ..present.escape import csv_cell_value
from .csvtext import CourseFileError, header_key, read_csv_text

__all__ = ["Person", "RosterError", "COLUMNS", "IDENTITY_COLUMNS", "read_roster", "participant_number",
           "looks_like_email", "participant_column", "email_column", "same_identifier"]

IDENTITY_COLUMNS = ("name", "email", "identifier")
"""The columns of a key made from a class list (``assign --roster``) that say who each student is."""

COLUMNS: dict[str, tuple[str, ...]] = {
    "name": ("Name", "Full name", "Student name",
             "Полное имя", "ФИО", "Имя студента",                  # Russian (Moodle's fullname)
             "Повна назва", "Повне ім'я", "ПІБ", "Ім'я студента"),  # Ukrainian (Moodle's fullname)
    "first name": ("First name", "Given name", "Имя", "Ім'я"),
    "last name": ("Last name", "Surname", "Family name", "Фамилия", "Прізвище"),
    "email": ("Email", "E-mail", "Email address", "E-mail address", "Mail",
              "Адрес электронной почты", "Электронная почта", "Електронна пошта", "Адреса електронної пошти"),
    "identifier": ("Identifier", "ID", "ID number", "Student ID", "Student number", "Username", "User ID",
                   "Идентификатор", "Індивідуальний номер", "Ідентифікатор", "Индивидуальный номер"),
}
"""The column names a class list may use for each field (matched ignoring case, spaces, hyphens, underscores and
apostrophes: ``full_name`` and ``FULL NAME`` are ``Full name``). The Russian and Ukrainian names are Moodle's
(its language packs' strings ``fullname``, ``email``, ``idnumber``, ``firstname``, ``lastname`` and
``assign``'s ``recordid``). Where a file has two columns for one field, the one named first here is taken (a
Moodle worksheet's ``Identifier`` before an ``ID number``). A name is either one column or a first and a last
name, joined with a space."""

_PARTICIPANT = re.compile(r"\s*([^\W\d_][^\d]{2,}?)\s*(\d{1,18})\s*")
_EMAIL = re.compile(r"\s*[^@\s,;\"<>()]+@[^@\s,;\"'<>()]+\.[^@\s,;\"'<>().]+\s*")


def participant_number(text: str) -> str | None:
    """The number of a Moodle participant identifier, else None.

    Moodle's grading worksheet writes ``get_string('hiddenuser', 'assign')`` and the participant's number:
    ``Participant 2318104`` in English, ``Участник2318104`` in Russian, ``Учасник2318104`` in Ukrainian (those
    language packs have the word without the space). So an identifier is a word of three or more characters
    (letters first, no digits) and a number at the end: a student id such as ``s01`` is not one.
    """
    match = _PARTICIPANT.fullmatch(text)
    return (match[2].lstrip("0") or "0") if match else None


def same_identifier(a: str, b: str) -> bool:
    """Whether two identifiers name the same person: equal ignoring case and spaces, or two participant
    identifiers with the same number (``Participant 7`` is ``Учасник7``: one worksheet in two languages)."""
    if " ".join(a.split()).casefold() == " ".join(b.split()).casefold():
        return bool(a.strip())
    number = participant_number(a)
    return number is not None and number == participant_number(b)


def looks_like_email(text: str) -> bool:
    """Whether a cell holds one e-mail address (``name@host.domain``)."""
    return bool(_EMAIL.fullmatch(text))


def _column_holding(rows: Sequence[Sequence[str]], width: int, test: Callable[[str], bool]) -> list[int]:
    """The columns whose cells all pass ``test`` (blank cells aside), with at least one that is not blank."""
    found = []
    for index in range(width):
        cells = [row[index].strip() for row in rows if index < len(row) and row[index].strip()]
        if cells and all(test(cell) for cell in cells):
            found.append(index)
    return found


def participant_column(rows: Sequence[Sequence[str]], width: int) -> list[int]:
    """The columns that hold Moodle participant identifiers: every cell one, with the same word
    (:func:`participant_number`)."""
    found = []
    for index in _column_holding(rows, width, lambda cell: participant_number(cell) is not None):
        words = {_PARTICIPANT.fullmatch(row[index])[1].casefold()            # type: ignore[index]
                 for row in rows if index < len(row) and row[index].strip()}
        if len(words) == 1:
            found.append(index)
    return found


def email_column(rows: Sequence[Sequence[str]], width: int) -> list[int]:
    """The columns that hold e-mail addresses (:func:`looks_like_email`)."""
    return _column_holding(rows, width, looks_like_email)


_FIELD_OF = {header_key(name): field for field, names in COLUMNS.items() for name in names}
_PRIORITY = {header_key(name): rank for names in COLUMNS.values() for rank, name in enumerate(names)}


class RosterError(CourseFileError):
    """A class list that cannot be used; the message names the file, the line and the cause."""


@dataclass(frozen=True)
class Person:
    """A student of the class list. Any of the three may be empty, not all of them.

    Attributes
    ----------
    name : str
    email : str
    identifier : str
        The platform's or the school's identifier (Moodle's worksheet: ``Participant 123456``).
    """

    name: str = ""
    email: str = ""
    identifier: str = ""

    @property
    def label(self) -> str:
        """How a person reads in a report: the name, else the e-mail, else the identifier."""
        return self.name or self.email or self.identifier


def _columns(header: list[str], where: str, rows: Sequence[Sequence[str]] = ()) -> dict[str, int]:
    found: dict[str, int] = {}
    for index, name in enumerate(header):
        field = _FIELD_OF.get(header_key(name))
        if field is None:
            continue
        if field not in found or _PRIORITY[header_key(name)] < _PRIORITY[header_key(header[found[field]])]:
            found[field] = index
    for field, finder in (("identifier", participant_column), ("email", email_column)):
        candidates = finder(list(rows), len(header)) if field not in found else []
        if len(candidates) == 1 and candidates[0] not in found.values():
            found[field] = candidates[0]
    if "name" in found and ({"first name", "last name"} & set(found)):
        raise RosterError(f"{where}: a name column and first/last name columns; keep one or the other")
    if ("first name" in found) != ("last name" in found):
        raise RosterError(f"{where}: a first name needs a last name column too (or use one name column)")
    if not found:
        accepted = "; ".join(f"{field}: {', '.join(names)}" for field, names in COLUMNS.items())
        raise RosterError(f"{where}: no column names a student (found {', '.join(map(repr, header))}); the "
                          f"accepted column names are {accepted}")
    return found


def read_roster(path: str | pathlib.Path) -> list[Person]:
    """Read a class list: one student a row, in the list's order (blank rows skipped).

    Raises
    ------
    RosterError
        If the file cannot be read, has no column that names a student, has a row with none of name, e-mail
        and identifier, with a control character in one of them, with more cells than columns, or two rows with
        the same identifier or e-mail.
    """
    table = read_csv_text(path, "class list", RosterError)
    where = f"class list {table.path}"
    header, *rows = table.rows
    columns = _columns([cell.value.strip() for cell in header.cells], where,
                       [[csv_cell_value(cell.value.strip()) for cell in row.cells] for row in rows])
    people: list[Person] = []
    seen: dict[tuple[str, str], int] = {}
    for row in rows:
        if len(row.cells) > len(header.cells) and any(c.value.strip() for c in row.cells[len(header.cells):]):
            raise RosterError(f"{where}, line {row.line}: more cells than the {len(header.cells)} columns (a "
                              f"separator inside a name? quote the cell)")
        value = {field: " ".join(csv_cell_value(row.value(index).strip()).split()) for field, index in columns.items()}
        name = value.get("name") or " ".join(filter(None, (value.get("first name"), value.get("last name"))))
        person = Person(name, value.get("email", ""), value.get("identifier", ""))
        control = next((c for c in "".join(vars(person).values()) if unicodedata.category(c) == "Cc"), None)
        if control is not None:
            raise RosterError(f"{where}, line {row.line}: a control character (U+{ord(control):04X}) in a name, "
                              "e-mail or identifier")
        if not person.label:
            raise RosterError(f"{where}, line {row.line}: no name, e-mail or identifier")
        for field in ("identifier", "email"):
            text = getattr(person, field).casefold()
            if text and (field, text) in seen:
                raise RosterError(f"{where}, lines {seen[field, text]} and {row.line}: the same {field} "
                                  f"{getattr(person, field)!r} twice")
            seen[field, text] = row.line
        people.append(person)
    if not people:
        raise RosterError(f"{where}: no students (only the line of column names)")
    return people
