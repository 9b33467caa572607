"""Layer 6: grading course assignments — the answer key against the students' answer files.

``python -m mechanisms check KEY.csv ANSWERS.csv [MORE.csv …]`` reads the key written by
``python -m mechanisms assign`` (:mod:`mechanisms.assign`) and one or more answer files with
the same columns (``student``, ``position``, optionally ``phi_deg``, then the quantities), and
reports per student and per quantity what is right, what is wrong and by how much, and which
answers are missing or unreadable.

Tolerances
----------
An answer is right when ``|answer − key| ≤ max(r·|key|, floor)``: ``r`` is 1 % unless the teacher
sets another, and the floor depends on the kind of quantity (:data:`TOLERANCES`), so that a value
close to zero (a slider near a limit position) is not asked for to 1 % of almost nothing. Angles
(``*.angle_deg``) are compared modulo 360° against an absolute tolerance only.

Problems with a file are of two sorts. A file that cannot be graded at all (missing, not CSV,
without the ``student`` or ``position`` column, with a column that the key does not have, or a
key with a bad number) raises :class:`GradingError` with a message that says what to fix. A
problem in a row or a cell (an unknown student id or position, a repeated row, a ``φ`` that is
not the key's, a cell that is not a number) is reported and the rest is graded; so is an answer
file that cannot be read when other answer files can.
"""

from __future__ import annotations

import math
import pathlib
import re
from dataclasses import dataclass, field
from typing import Iterable, Sequence

from ..core.errors import InvalidParameterError
from ..present.escape import csv_cell_value
from .csvtext import CourseFileError, csv_lines, header_key, read_csv_text
from .roster import IDENTITY_COLUMNS, Person

__all__ = [
    "Tolerance",
    "TOLERANCES",
    "DEFAULT_RELATIVE",
    "GradingError",
    "Key",
    "Answers",
    "AnswerFile",
    "Mark",
    "Report",
    "kind_of",
    "Rule",
    "default_rule",
    "parse_tolerance",
    "tolerance_rules",
    "tolerances_path",
    "tolerance",
    "difference",
    "parse_number",
    "read_key",
    "read_answers",
    "grade",
    "check_files",
]

DEFAULT_RELATIVE = 0.01
"""Relative tolerance r of every quantity but angles: 1 % of the key's value."""


@dataclass(frozen=True)
class Tolerance:
    """The tolerance of one kind of quantity.

    Attributes
    ----------
    kind : str
        ``angle``, ``length``, ``velocity`` …
    floor : float
        Absolute tolerance (in ``unit``) below which the relative one never goes.
    unit : str
    relative : bool
        False for angles, which are compared against the floor only.
    """

    kind: str
    floor: float
    unit: str
    relative: bool = True


TOLERANCES: dict[str, Tolerance] = {
    "angle": Tolerance("angle", 0.1, "°", relative=False),
    "length": Tolerance("length", 1e-4, "m"),
    "velocity": Tolerance("velocity", 5e-3, "m/s"),
    "acceleration": Tolerance("acceleration", 0.05, "m/s²"),
    "angular velocity": Tolerance("angular velocity", 0.01, "1/s"),
    "angular acceleration": Tolerance("angular acceleration", 0.5, "1/s²"),
    "force": Tolerance("force", 0.1, "N"),
    "torque": Tolerance("torque", 0.01, "N·m"),
}
"""Tolerances by kind of quantity (see the module's notes)."""

_SUFFIX_KINDS = {
    "angle_deg": "angle", "omega": "angular velocity", "alpha": "angular acceleration",
    "s": "length", "x": "length", "y": "length",
    "v": "velocity", "vx": "velocity", "vy": "velocity",
    "a": "acceleration", "ax": "acceleration", "ay": "acceleration", "coriolis": "acceleration",
    "F": "force",
}
_WHOLE_KINDS = {"driving_torque": "torque"}
"""Quantity columns without a ``NAME.`` part."""
ID_COLUMNS = ("student", "position")
PHI = "phi_deg"
PHI_TOLERANCE = 1e-6
"""How far (degrees) an answer file's φ may be from the key's and still name the same position."""


class GradingError(CourseFileError):
    """A key or an answer file that cannot be graded; the message says what to fix."""


def kind_of(column: str) -> str:
    """The kind of a quantity from its column name ``NAME.KEY`` (as in the ``table`` CSV).

    Raises
    ------
    GradingError
        If the name has no known ``KEY``.
    """
    if column in _WHOLE_KINDS:
        return _WHOLE_KINDS[column]
    _, dot, key = column.rpartition(".")
    if not dot or key not in _SUFFIX_KINDS:
        raise GradingError(f"{column!r} is not a quantity column: expected NAME.KEY with KEY one of "
                           + ", ".join(_SUFFIX_KINDS) + " (or " + ", ".join(_WHOLE_KINDS) + ")")
    return _SUFFIX_KINDS[key]


def tolerance(column: str, key_value: float, relative: float = DEFAULT_RELATIVE) -> float:
    """The largest accepted |answer − key| for a key value of a column (in the column's unit)."""
    return default_rule(column, relative).of(key_value)


@dataclass(frozen=True)
class Rule:
    """The tolerance of one quantity: ``max(relative·|key|, floor)``, the floor in the quantity's unit."""

    relative: float
    floor: float

    def of(self, key_value: float) -> float:
        """The largest accepted |answer − key| for a key value."""
        return max(self.relative * abs(key_value), self.floor)

    def text(self, unit: str) -> str:
        """``1 %, at least 0.005 m/s`` or ``0.1 °``."""
        if not self.relative:
            return f"{self.floor:g} {unit}"
        return f"{100 * self.relative:g} %, at least {self.floor:g} {unit}"


def default_rule(column: str, relative: float = DEFAULT_RELATIVE) -> Rule:
    """A column's tolerance by its kind (:data:`TOLERANCES`), with the relative part ``relative`` (not for angles)."""
    rule = TOLERANCES[kind_of(column)]
    return Rule(relative if rule.relative else 0.0, rule.floor)


_TOLERANCE_UNITS = {
    "deg": ("angle", 1.0), "°": ("angle", 1.0), "m": ("length", 1.0), "mm": ("length", 1e-3),
    "m/s": ("velocity", 1.0), "mm/s": ("velocity", 1e-3), "m/s2": ("acceleration", 1.0),
    "m/s²": ("acceleration", 1.0), "1/s": ("angular velocity", 1.0), "1/s2": ("angular acceleration", 1.0),
    "1/s²": ("angular acceleration", 1.0), "N": ("force", 1.0), "N·m": ("torque", 1.0), "Nm": ("torque", 1.0),
}
"""Units a ``--tolerance`` floor may be written in, with their kind and factor to the column's unit."""
_TOLERANCE_PART = re.compile(r"\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(%|[^\s0-9.][^\s]*)?\s*")


def parse_tolerance(text: str, columns: Sequence[str]) -> tuple[list[str], float | None, float | None]:
    """One ``--tolerance`` option: ``TARGET=VALUE[,VALUE]`` → (the columns it sets, relative, floor).

    TARGET is a quantity column (``B.vx``) or a kind (``angle``, ``length``, ``velocity``, ``acceleration``,
    ``angular-velocity``, ``angular-acceleration``, ``force``, ``torque``: every column of that kind). A VALUE
    ending in ``%`` is the relative part (``2%``); any other is the absolute floor, in the column's unit or in a
    unit written after it (``0.5deg``, ``0.5mm``, ``5mm/s``). ``B.vx=2%,0.01`` sets both; what is not given keeps
    its default.

    Raises
    ------
    InvalidParameterError
        Naming ``--tolerance``, the text and what is wrong.
    """
    def bad(why: str) -> InvalidParameterError:
        return InvalidParameterError("--tolerance", text, f"TARGET=VALUE with TARGET a column ({', '.join(columns)}) "
                                     f"or a kind ({', '.join(k.replace(' ', '-') for k in TOLERANCES)}) and VALUE "
                                     f"a percentage (2%) and/or an absolute tolerance (0.5deg, 0.01): {why}")

    target, equals, value = (part.strip() for part in text.partition("="))
    if not equals or not target or not value:
        raise bad("no '='")
    kind_name = target.replace("-", " ").replace("_", " ").lower()
    if target in columns:
        chosen, kind = [target], kind_of(target)
    elif kind_name in TOLERANCES:
        chosen, kind = [c for c in columns if kind_of(c) == kind_name], kind_name
        if not chosen:
            raise bad(f"no column of the kind {kind_name!r} is asked")
    else:
        raise bad(f"{target!r} is neither")
    relative = floor = None
    parts = value.split(",")
    if len(parts) > 2:
        raise bad("at most a percentage and a floor")
    for part in parts:
        match = _TOLERANCE_PART.fullmatch(part)
        if not match:
            raise bad(f"{part.strip()!r} is not a number with an optional unit")
        number, unit = float(match[1]), match[2]
        if not math.isfinite(number):
            raise bad(f"{part.strip()!r} is not finite")
        if unit == "%":
            if relative is not None or kind == "angle" or not number < 100:
                raise bad("one percentage below 100 (angles take an absolute tolerance only)")
            relative = number / 100.0
            continue
        if floor is not None:
            raise bad("one absolute tolerance")
        if unit is not None:
            if unit not in _TOLERANCE_UNITS or _TOLERANCE_UNITS[unit][0] != kind:
                units = [u for u, (k, _) in _TOLERANCE_UNITS.items() if k == kind]
                raise bad(f"the unit {unit!r} is not one of a {kind} ({', '.join(units)})")
            number *= _TOLERANCE_UNITS[unit][1]
        floor = number
    return chosen, relative, floor


def tolerance_rules(columns: Sequence[str], options: Sequence[str] = (), relative: float | None = None) -> dict[str, Rule]:
    """Every column's :class:`Rule`: the kind's default (relative part ``relative``, default 1 %), then the
    ``--tolerance`` options (:func:`parse_tolerance`) in order, a kind's before a column's."""
    relative = DEFAULT_RELATIVE if relative is None else relative
    rules = {column: default_rule(column, relative) for column in columns}
    parsed = [parse_tolerance(option, columns) for option in options]
    for only_columns in (False, True):
        for option, (chosen, rel, floor) in zip(options, parsed):
            if (option.partition("=")[0].strip() in columns) != only_columns:
                continue
            for column in chosen:
                old = rules[column]
                rules[column] = Rule(old.relative if rel is None else rel, old.floor if floor is None else floor)
    return rules


def tolerances_path(key_path: str | pathlib.Path) -> pathlib.Path:
    """The file of the key's tolerances, beside it: ``key.csv`` → ``key-tolerances.csv``."""
    key_path = pathlib.Path(key_path)
    return key_path.with_name(f"{key_path.stem}-tolerances{key_path.suffix or '.csv'}")


def _wrap_degrees(angle: float) -> float:
    """An angle difference (degrees) wrapped to [−180°, 180°)."""
    return (angle + 180.0) % 360.0 - 180.0


def difference(column: str, answer: float, key_value: float) -> float:
    """answer − key; for angles the difference wrapped to [−180°, 180°)."""
    diff = answer - key_value
    return _wrap_degrees(diff) if kind_of(column) == "angle" else diff


_DECIMAL_COMMA = re.compile(r"[+-]?\d*,\d+(?:[eE][+-]?\d+)?")
"""A number written with a decimal comma: ``15,0``, ``-0,25``, ``,5``, ``1,5e3``."""
_GROUPED = re.compile(r"[+-]?[1-9]\d{0,2},\d{3}")
"""A number that a decimal comma and a thousands separator read differently: ``1,500`` is 1.5 or 1500."""
_DECIMAL_POINT = re.compile(r"[+-]?\d*\.\d+(?:[eE][+-]?\d+)?")


def parse_number(text: str, decimal_comma: bool = False) -> float:
    """A cell's number; ``ValueError`` with a reason a student understands if it is not one.

    Parameters
    ----------
    text : str
        The cell: a decimal point (``-0.25``, ``1e3``) or a decimal comma (``-0,25``, ``15,0``), the minus
        sign ``-`` or ``−`` (U+2212, as a spreadsheet or a word processor may write it), spaces around.
    decimal_comma : bool
        True if the file writes decimal commas (it separates its cells with ``;``, or its numbers have decimal
        commas and no decimal point): then ``1,500`` is 1.5. Otherwise ``1,500`` is refused as ambiguous (1.5
        with a decimal comma, 1500 with a thousands separator); ``15,0`` and ``0,25`` are read either way.
    """
    cleaned = text.strip().replace("\u2212", "-")
    shown = repr(text.strip())
    if "," in cleaned:
        if not _DECIMAL_COMMA.fullmatch(cleaned):
            raise ValueError(f"{shown} is not a number (use a decimal point)")
        if _GROUPED.fullmatch(cleaned) and not decimal_comma:
            whole, part = cleaned.split(",")
            raise ValueError(f"{shown} is ambiguous: {whole}.{part} with a decimal comma, {whole}{part} with a "
                             "thousands separator (write it with a decimal point)")
        cleaned = cleaned.replace(",", ".")
    try:
        value = float(cleaned) if cleaned.isascii() else math.nan
    except ValueError:
        raise ValueError(f"{shown} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{shown} is not {'a finite number' if cleaned.isascii() else 'a number'}")
    return value


def _writes_decimal_commas(texts: Iterable[str], delimiter: str) -> bool:
    """Whether a file writes decimal commas: it separates its cells with ``;`` (a spreadsheet in a language that
    writes decimal commas), or some of its cells have one and none a decimal point."""
    if delimiter == ";":
        return True
    comma = point = False
    for text in texts:
        cleaned = text.strip().replace("\u2212", "-")
        comma = comma or bool(_DECIMAL_COMMA.fullmatch(cleaned) and not _GROUPED.fullmatch(cleaned))
        point = point or bool(_DECIMAL_POINT.fullmatch(cleaned))
    return comma and not point


# --- reading ---------------------------------------------------------------------------------------------

_FIXED = {header_key(name): name for name in (*ID_COLUMNS, PHI, *IDENTITY_COLUMNS)}
"""The columns of the key and of answer files that are not quantities, by their names reduced for matching:
``Student``, ``STUDENT`` and `` student `` are ``student``, ``Phi deg`` is ``phi_deg``."""


def _read_table(path: pathlib.Path, what: str, data: bytes | None = None
                ) -> tuple[list[str], list[tuple[int, dict[str, str], bool]], bool]:
    """Header, (line number, row, too many cells) triples and whether the file writes decimal commas.

    The file is read by :func:`mechanisms.course.csvtext.read_csv_text` (any dialect a spreadsheet writes). The
    names of the columns that are not quantities are matched whatever their case and spaces; a column without a
    name (a spreadsheet's separator at the end of every line) is left out if it is empty.
    """
    table = read_csv_text(path, what, GradingError, data)
    where = f"{what} {table.path}"
    first, *records = table.rows
    written = [cell.value.strip() for cell in first.cells]
    for index, name in enumerate(written):
        filled = next((r for r in records if r.value(index).strip()), None) if not name else None
        if filled is not None:
            raise GradingError(f"{where}, line {filled.line}: {filled.value(index).strip()!r} in column {index + 1}, "
                               f"which has no name on line {first.line}")
    named = [(index, _FIXED.get(header_key(name), name)) for index, name in enumerate(written) if name]
    header = [name for _, name in named]
    if len(set(header)) != len(header):
        repeated = sorted({h for h in header if header.count(h) > 1})
        raise GradingError(f"{where}: the column(s) {', '.join(repeated)} appear more than once")
    rows = [(r.line, {name: r.value(index) for index, name in named},
             any(c.value.strip() for c in r.cells[len(first.cells):])) for r in records]
    comma = _writes_decimal_commas((c.value for r in records for c in r.cells), table.delimiter)
    return header, rows, comma


def _overflow(line: int, cells: int, columns: int) -> str:
    return (f"line {line}: more cells than the {columns} columns (a decimal comma in a comma-separated file? "
            "use a decimal point, or quote the cell)")


@dataclass
class Key:
    """The answer key: per (student, position) the crank angle and the value of each quantity."""

    path: pathlib.Path
    quantities: list[str]
    phi: dict[tuple[str, int], float]
    values: dict[tuple[str, int], dict[str, float]]
    people: dict[str, Person] = field(default_factory=dict)
    """Who each student is, if the key was made from a class list (else empty)."""
    tolerances: dict[tuple[str, int], dict[str, float]] = field(default_factory=dict)
    """The accepted |answer − key| of every value, from the key's tolerance file (``key-tolerances.csv``, written
    by ``assign``) if there is one (else empty)."""

    @property
    def students(self) -> list[str]:
        """Student ids in the key's order."""
        return list(dict.fromkeys(student for student, _ in self.values))

    def positions(self, student: str) -> list[int]:
        return [p for s, p in self.values if s == student]

    def label(self, student: str) -> str:
        """``s01`` or, from a class list, ``s01 (Ann Example)``."""
        person = self.people.get(student)
        return f"{student} ({person.label})" if person and person.label else student


def _position(text: str) -> int:
    value = text.strip()
    if not (value.isascii() and value.isdigit() and len(value) <= 9) or int(value) < 1:
        raise ValueError(f"position {text.strip()!r} is not a whole number ≥ 1")
    return int(value)


def read_key(path: str | pathlib.Path) -> Key:
    """Read and check an answer key (``student,position,phi_deg,QUANTITY…``; from a class list also ``name``,
    ``email`` and ``identifier``, anywhere)."""
    path = pathlib.Path(path)
    header, rows, comma = _read_table(path, "key")
    identity = [h for h in header if h in IDENTITY_COLUMNS]
    columns = [h for h in header if h not in IDENTITY_COLUMNS]
    if columns[:3] != [*ID_COLUMNS, PHI] or len(columns) < 4:
        raise GradingError(f"key {path}: the columns must be student,position,phi_deg and then the quantities "
                           f"(and name, email, identifier if made from a class list); got {','.join(header)}")
    quantities = columns[3:]
    people: dict[str, Person] = {}
    for column in quantities:
        kind_of(column)   # raises GradingError for a column that is not a quantity
    phi: dict[tuple[str, int], float] = {}
    values: dict[tuple[str, int], dict[str, float]] = {}
    for line, row, overflow in rows:
        where = f"key {path}, line {line}"
        if overflow:
            raise GradingError(f"key {path}, " + _overflow(line, len(row), len(header)))
        student = row["student"].strip()
        if not student:
            raise GradingError(f"{where}: no student id")
        numbers = {}
        for column in (*ID_COLUMNS[1:], PHI, *quantities):
            try:
                if not row[column].strip():
                    raise ValueError("empty (a key has every value)")
                numbers[column] = _position(row[column]) if column == "position" else parse_number(row[column], comma)
            except ValueError as error:
                raise GradingError(f"{where}, column {column}: {error}") from None
        position, angle = int(numbers.pop("position")), numbers.pop(PHI)
        if (student, position) in values:
            raise GradingError(f"{where}: student {student} position {position} appears twice")
        phi[student, position] = angle
        values[student, position] = numbers
        if identity:
            person = Person(**{c: " ".join(csv_cell_value(row[c].strip()).split()) for c in identity})
            if people.setdefault(student, person) != person:
                raise GradingError(f"{where}: student {student} is {person.label!r} here but "
                                   f"{people[student].label!r} on an earlier line")
    if not values:
        raise GradingError(f"key {path}: no rows")
    key = Key(path, quantities, phi, values, people)
    if tolerances_path(path).exists():
        key.tolerances = _read_tolerances(tolerances_path(path), key)
    return key


def _read_tolerances(path: pathlib.Path, key: Key) -> dict[tuple[str, int], dict[str, float]]:
    """The key's tolerance file: the key's layout, each value the accepted |answer − key| (≥ 0)."""
    header, rows, comma = _read_table(path, "tolerance file")
    columns = [h for h in header if h not in IDENTITY_COLUMNS]
    if columns != [*ID_COLUMNS, PHI, *key.quantities]:
        raise GradingError(f"tolerance file {path}: the columns must be the key's, "
                           f"{','.join([*ID_COLUMNS, PHI, *key.quantities])}; got {','.join(header)}")
    found: dict[tuple[str, int], dict[str, float]] = {}
    for line, row, overflow in rows:
        where = f"tolerance file {path}, line {line}"
        try:
            if overflow:
                raise ValueError("more cells than columns")
            place = (row["student"].strip(), _position(row["position"]))
            if place not in key.values:
                raise ValueError(f"student {place[0]} position {place[1]} is not in the key")
            found[place] = {q: parse_number(row[q], comma) for q in key.quantities}
            if any(v < 0 for v in found[place].values()):
                raise ValueError("a tolerance is negative")
        except ValueError as error:
            raise GradingError(f"{where}: {error}") from None
    missing = [p for p in key.values if p not in found]
    if missing:
        raise GradingError(f"tolerance file {path}: no row for student {missing[0][0]} position {missing[0][1]}")
    return found


@dataclass
class Answers:
    """The cells of one or more answer files by (student, position), the problems found, and notes for a
    student's feedback (an answer file handed in by one student's account that names another)."""

    cells: dict[tuple[str, int], dict[str, str]] = field(default_factory=dict)
    decimal_comma: dict[tuple[str, int], bool] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)
    notes: dict[str, list[str]] = field(default_factory=dict)


@dataclass(frozen=True)
class AnswerFile:
    """An answer file in memory (a member of a learning platform's archive of submissions) and who handed it in.

    Attributes
    ----------
    name : str
        How messages name it (``answers.zip: Olena Kovalenko_2318104_assignsubmission_file/answers.csv``).
    data : bytes
        Its bytes.
    owner : str or None
        The key's student id of the account that handed it in, if known: its rows are that student's answers
        (a row with an empty ``student`` cell, or a file without that column, is theirs), and a row that names
        another student is reported, not graded.
    account : str
        How the account reads in messages (``Olena Kovalenko, Participant 2318104``).
    """

    name: str
    data: bytes
    owner: str | None = None
    account: str = ""


def read_answers(path: str | pathlib.Path | AnswerFile, key: Key, into: Answers | None = None) -> Answers:
    """Read an answer file (a path, or an :class:`AnswerFile` in memory) against the key; row problems go to
    ``Answers.problems``.

    Raises
    ------
    GradingError
        If the file cannot be read or its columns are not the key's (``student``, ``position``,
        optionally ``phi_deg`` and, if the key has them, ``name``, ``email``, ``identifier`` (ignored), and
        quantities of the key, in any order; ``student`` may be left out of a file whose owner is known).
    """
    source = path if isinstance(path, AnswerFile) else None
    path = pathlib.Path(path.name if isinstance(path, AnswerFile) else path)
    name = source.name if source else path.name
    owner = source.owner if source else None
    answers = into if into is not None else Answers()
    header, rows, comma = _read_table(path, "answer file", source.data if source else None)
    missing = [c for c in ID_COLUMNS if c not in header and not (c == "student" and owner)]
    identity = IDENTITY_COLUMNS if key.people else ()      # the key's own columns, when it has a class list
    # a quantity's column whatever its case (b.S is B.s), unless the key has two names that differ only in case
    fold = str.casefold if len({q.casefold() for q in key.quantities}) == len(key.quantities) else str
    by_fold = {fold(q): q for q in key.quantities}
    quantity = {h: by_fold[fold(h)] for h in header if h not in (*ID_COLUMNS, PHI, *identity) and fold(h) in by_fold}
    unknown = [c for c in header if c not in (*ID_COLUMNS, PHI, *identity) and c not in quantity]
    if missing or unknown:
        parts = []
        if missing:
            parts.append("no column " + " or ".join(repr(c) for c in missing))
        if unknown:
            parts.append("column(s) not in the key: " + ", ".join(repr(c) for c in unknown))
        raise GradingError(f"answer file {path}: " + "; ".join(parts) + ". The columns must be "
                           f"{','.join([*ID_COLUMNS, PHI, *key.quantities])} (phi_deg may be left out)")
    students = key.students
    by_id = {s.casefold(): s for s in students}       # "S01" is s01
    for line, row, overflow in rows:
        where = f"{name}, line {line}"
        if overflow:
            answers.problems.append(f"{name}, " + _overflow(line, len(row), len(header)) + "; row ignored")
            continue
        written = row.get("student", "").strip()
        student = by_id.get(written.casefold(), written) if written or not owner else owner
        if owner and student != owner:
            handed = f"handed in by {source.account or owner} ({key.label(owner)})" if source else ""
            answers.problems.append(f"{where}: the row is for student {written!r} but the file was {handed}; "
                                    "row not graded")
            note = f"Your file {name.rpartition('/')[2]} has rows for student {written!r}, not {owner}: not graded."
            if note not in answers.notes.setdefault(owner, []):
                answers.notes[owner].append(note)
            continue
        if student not in students:
            known = f"{students[0]} … {students[-1]}" if len(students) > 2 else ", ".join(students)
            answers.problems.append(f"{where}: unknown student id {student!r} (the key has {known}); row ignored")
            continue
        try:
            position = _position(row["position"])
        except ValueError as error:
            answers.problems.append(f"{where}: {error}; row ignored")
            continue
        if (student, position) not in key.values:
            answers.problems.append(f"{where}: student {student} has no position {position} (the key has "
                                    f"{', '.join(map(str, key.positions(student)))}); row ignored")
            continue
        if PHI in row and row[PHI].strip():
            try:
                angle = parse_number(row[PHI], comma)
            except ValueError as error:
                answers.problems.append(f"{where}: φ: {error}; row ignored")
                continue
            expected = key.phi[student, position]
            if abs(_wrap_degrees(angle - expected)) > PHI_TOLERANCE:
                answers.problems.append(f"{where}: φ = {angle:g}° but position {position} of {student} is at "
                                        f"φ = {expected:g}°; row ignored")
                continue
        if (student, position) in answers.cells:
            answers.problems.append(f"{where}: a second row for {student} position {position}; the first one "
                                    "is graded, this one ignored")
            continue
        answers.cells[student, position] = {q: row[h] for h, q in quantity.items()}
        answers.decimal_comma[student, position] = comma
    return answers


# --- grading ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Mark:
    """The grade of one answer.

    ``status`` is ``right``, ``wrong``, ``missing`` (no row or an empty cell) or ``unreadable``
    (``note`` says why; for a wrong answer it may give a hint, "right but for the sign");
    ``difference`` is answer − key (wrapped for angles) and ``tolerance`` the accepted
    |difference|, both in the quantity's unit.
    """

    student: str
    position: int
    phi_deg: float
    quantity: str
    key: float
    answer: float | None
    status: str
    difference: float | None
    tolerance: float
    note: str = ""

    @property
    def right(self) -> bool:
        return self.status == "right"


@dataclass
class Report:
    """All marks and the problems found in the answer files."""

    key: Key
    marks: list[Mark]
    problems: list[str]
    relative: float
    rules: dict[str, Rule] = field(default_factory=dict)
    """The tolerance of each quantity, when not the key's own (``key.tolerances``)."""
    notes: dict[str, list[str]] = field(default_factory=dict)
    """Notes for a student's feedback (:attr:`Answers.notes`)."""

    def of(self, student: str) -> list[Mark]:
        return [m for m in self.marks if m.student == student]

    def score(self, student: str | None = None) -> tuple[int, int]:
        """(right, asked) for a student, or for the class."""
        marks = self.marks if student is None else self.of(student)
        return sum(m.right for m in marks), len(marks)

    def text(self) -> str:
        """The report for a person: per student, per quantity, and the file problems."""
        unit = {q: TOLERANCES[kind_of(q)].unit for q in self.key.quantities}
        lines = [f"Key {self.key.path.name}: {len(self.key.students)} students, {len(self.key.values)} positions, "
                 f"{len(self.key.quantities)} quantities ({len(self.marks)} answers).", self._rules_text(), ""]
        for student in self.key.students:
            marks = self.of(student)
            right, asked = self.score(student)
            notes = [f"  note       {note}" for note in self.notes.get(student, [])]
            if all(m.status == "missing" for m in marks):
                lines += [f"{self.key.label(student)}: no answers ({right} of {asked} right)", *notes]
                continue
            lines += [f"{self.key.label(student)}: {right} of {asked} right ({100 * right / asked:.0f} %)", *notes]
            absent = {p for p in dict.fromkeys(m.position for m in marks)
                      if all(m.status == "missing" for m in marks if m.position == p)}
            for m in marks:
                where = f"position {m.position} (φ = {m.phi_deg:g}°) {m.quantity}"
                if m.position in absent:
                    if m.quantity == self.key.quantities[0]:
                        lines.append(f"  missing    position {m.position} (φ = {m.phi_deg:g}°): all "
                                     f"{len(self.key.quantities)} answers")
                elif m.status == "wrong":
                    relative = ""
                    if m.key and m.difference is not None and TOLERANCES[kind_of(m.quantity)].relative:
                        relative = f", {100 * m.difference / abs(m.key):+.3g} %"
                    note = f"; {m.note}" if m.note else ""
                    lines.append(f"  wrong      {where}: answer {m.answer:.6g}, key {m.key:.6g} {unit[m.quantity]}, "
                                 f"off by {m.difference:+.4g}{relative} (tolerance {m.tolerance:.2g}){note}")
                elif m.status == "missing":
                    lines.append(f"  missing    {where}")
                elif m.status == "unreadable":
                    lines.append(f"  unreadable {where}: {m.note}")
        lines += ["", "Per quantity (right of asked):"]
        width = max(len(q) for q in self.key.quantities)
        for q in self.key.quantities:
            marks = [m for m in self.marks if m.quantity == q]
            counts = {s: sum(m.status == s for m in marks) for s in ("right", "wrong", "missing", "unreadable")}
            extra = ", ".join(f"{n} {s}" for s, n in counts.items() if s != "right" and n)
            lines.append(f"  {q.ljust(width)}  {counts['right']} of {len(marks)}" + (f" ({extra})" if extra else ""))
        if self.problems:
            lines += ["", "Problems in the answer files:"] + [f"  {p}" for p in self.problems]
        right, asked = self.score()
        lines += ["", f"Class: {right} of {asked} answers right ({100 * right / asked:.0f} %)."]
        return "\n".join(lines)

    def _rules_text(self) -> str:
        """The line that says when an answer is right."""
        defaults = {q: default_rule(q, self.relative) for q in self.key.quantities}
        if not self.rules:
            return (f"Right when |answer − key| ≤ the key's tolerance ({tolerances_path(self.key.path).name}, stated "
                    "on each sheet); angles modulo 360°.")
        floors = ", ".join(f"{t.kind} {t.floor:g} {t.unit}" for t in TOLERANCES.values())
        text = (f"Right when |answer − key| ≤ max({100 * self.relative:g} % of |key|, floor); floors: {floors}; "
                "angles modulo 360° within their floor.")
        changed = [f"{q} {rule.text(TOLERANCES[kind_of(q)].unit)}" for q, rule in self.rules.items()
                   if rule != defaults[q]]
        return text + (" Set by --tolerance: " + "; ".join(changed) + "." if changed else "")

    def csv(self) -> str:
        """Every mark as CSV: student, position, phi_deg, quantity, key, answer, difference, tolerance, status, note."""
        header = ("student", "position", "phi_deg", "quantity", "key", "answer", "difference", "tolerance", "status",
                  "note")
        return csv_lines([header, *((m.student, m.position, m.phi_deg, m.quantity, m.key, m.answer, m.difference,
                                     m.tolerance, m.status, m.note) for m in self.marks)])


def grade(key: Key, answers: Answers, relative: float | None = None, tolerance: Sequence[str] = ()) -> Report:
    """Grade every answer the key asks for.

    The tolerances are the key's own (``key.tolerances``, from its tolerance file) unless ``relative`` or
    ``tolerance`` (``--tolerance`` options, :func:`parse_tolerance`) is given, or the key has none: then every
    quantity's is :func:`tolerance_rules`.
    """
    if relative is not None and not (math.isfinite(relative) and 0.0 <= relative < 1.0):
        raise GradingError(f"the relative tolerance must be in [0, 1): got {relative!r}")
    own = bool(key.tolerances) and relative is None and not tolerance
    rules = {} if own else tolerance_rules(key.quantities, tolerance, relative)
    marks = []
    for (student, position), expected in key.values.items():
        cells = answers.cells.get((student, position), {})
        comma = answers.decimal_comma.get((student, position), False)
        phi = key.phi[student, position]
        for quantity in key.quantities:
            value = expected[quantity]
            tol = key.tolerances[student, position][quantity] if own else rules[quantity].of(value)
            text = cells.get(quantity, "").strip()
            if not text:
                marks.append(Mark(student, position, phi, quantity, value, None, "missing", None, tol))
                continue
            try:
                answer = parse_number(text, comma)
            except ValueError as error:
                marks.append(Mark(student, position, phi, quantity, value, None, "unreadable", None, tol, str(error)))
                continue
            diff = difference(quantity, answer, value)
            status = "right" if abs(diff) <= tol else "wrong"
            note = ""
            if status == "wrong" and kind_of(quantity) != "angle" and abs(answer + value) <= tol:
                note = "right but for the sign"
            marks.append(Mark(student, position, phi, quantity, value, answer, status, diff, tol, note))
    return Report(key, marks, list(answers.problems), DEFAULT_RELATIVE if relative is None else relative, rules,
                  {s: list(n) for s, n in answers.notes.items()})


def check_files(key_path: str | pathlib.Path | Key,
                answer_paths: Sequence[str | pathlib.Path | AnswerFile] | Iterable,
                relative: float | None = None, tolerance: Sequence[str] = (), problems: Sequence[str] = ()) -> Report:
    """Read the key and the answer files and grade them.

    An answer file that cannot be read is reported among the problems (its answers count as
    missing) and the other files are graded.

    Parameters
    ----------
    key_path : str, path or Key
        The key's file, or the key already read (:func:`read_key`).
    answer_paths : paths or AnswerFile
        The answer files: paths, or files in memory with the account that handed them in.
    relative, tolerance
        As for :func:`grade`.
    problems : sequence of str
        Problems found before (in an archive the files came from), reported first.

    Raises
    ------
    GradingError
        If the key cannot be read, or none of the answer files.
    """
    key = key_path if isinstance(key_path, Key) else read_key(key_path)
    answers = Answers(problems=list(problems))
    failures = []
    paths = list(answer_paths)
    for path in paths:
        try:
            read_answers(path, key, into=answers)
        except GradingError as error:
            failures.append(str(error))
            answers.problems.append(f"not graded: {error}")
    if failures and len(failures) == len(paths):
        raise GradingError(failures[0] if len(failures) == 1 else
                           "no answer file could be read:\n  " + "\n  ".join(failures))
    return grade(key, answers, relative, tolerance)
