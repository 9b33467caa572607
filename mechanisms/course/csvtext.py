"""CSV files of the course tools, read so that they can be written back unchanged but for the cells filled in.

A class list, an answer file, a key or a learning platform's grading worksheet comes from a spreadsheet or a
web site, in one of the dialects spreadsheets write: UTF-8 with or without a byte-order mark, or UTF-16 with
one (Excel's *Unicode text*); cells separated by commas, semicolons or tabs, quoted or not, with spaces around
them or not; lines ending in ``\\n`` or ``\\r\\n``, blank lines between them; names in any script.
:func:`read_csv_text` reads such a file into records whose cells keep their place in the text, so that
:func:`replace_cells` can change a few cells and leave every other byte of the file as it was. It is the one
reader of the course tools' files (key, answers, class list, worksheet).

The separator is the one of ``,`` ``;`` and tab found in the first line outside quotes. (The standard
library's :class:`csv.Sniffer` guesses from a sample of the whole file; the first line of these files names
the columns, which holds no decimal comma, so it says more, and the reader must keep each cell's place in the
text, which :mod:`csv` does not give.) Where the first line holds two of them, the one that splits no line into
more cells than the first is taken, the one giving more columns if both do; where that does not decide, the
file is refused as ambiguous, naming its first line.
"""

from __future__ import annotations

import codecs
import pathlib
from dataclasses import dataclass
from typing import Iterable, Sequence

from ..core.errors import MechanismError
from ..present.escape import csv_cell

__all__ = ["CourseFileError", "Cell", "Record", "CsvText", "read_csv_text", "replace_cells", "encode_cell",
           "header_key", "write_file", "csv_lines"]

DELIMITERS = (",", ";", "\t")
"""The cell separators recognised (see the module's notes)."""

_DELIMITER_NAMES = {",": "','", ";": "';'", "\t": "tabs"}

_ENCODINGS = ((codecs.BOM_UTF8, "utf-8"), (codecs.BOM_UTF16_LE, "utf-16-le"), (codecs.BOM_UTF16_BE, "utf-16-be"))
"""Byte-order marks and the encodings they announce; a file without one is read as UTF-8."""


class CourseFileError(MechanismError):
    """A class list, worksheet or grades file that cannot be used; the message names the file, the line and
    the cause."""


@dataclass(frozen=True)
class Cell:
    """A cell's value and where its text is in the file (``text[start:end]``, quotes included)."""

    value: str
    start: int
    end: int
    quoted: bool


@dataclass(frozen=True)
class Record:
    """A record (a row) of the file: the line it starts on (1-based) and its cells."""

    line: int
    cells: tuple[Cell, ...]

    @property
    def blank(self) -> bool:
        return not any(cell.value.strip() for cell in self.cells)

    def value(self, index: int) -> str:
        """The value of cell ``index`` ("" if the record is shorter)."""
        return self.cells[index].value if index < len(self.cells) else ""


@dataclass(frozen=True)
class CsvText:
    """A CSV file as read: its text, byte-order mark and encoding, separator and records (blank records
    included)."""

    path: pathlib.Path
    text: str
    bom: bytes
    delimiter: str
    records: tuple[Record, ...]
    encoding: str = "utf-8"

    @property
    def rows(self) -> list[Record]:
        """The records that are not blank: the header first."""
        return [r for r in self.records if not r.blank]


def header_key(text: str) -> str:
    """A column name reduced for matching: lower case, letters and digits only (``"E-mail address"`` →
    ``"emailaddress"``)."""
    return "".join(c for c in text.casefold() if c.isalnum())


def _first_line_counts(text: str) -> dict[str, int]:
    """How often each separator occurs in the first line, outside quotes."""
    counts = dict.fromkeys(DELIMITERS, 0)
    quoted = False
    for char in text:
        if char == '"':
            quoted = not quoted
        elif not quoted and char in "\r\n":
            break
        elif not quoted and char in counts:
            counts[char] += 1
    return counts


def _width(record: Record) -> int:
    """The number of cells of a record without the empty ones at its end (a spreadsheet's trailing separator)."""
    width = len(record.cells)
    while width and not record.cells[width - 1].value.strip():
        width -= 1
    return width


def _delimiter(text: str, where: str, error: type[CourseFileError]) -> str:
    body = text.lstrip("\r\n")
    counts = _first_line_counts(body)
    found = [d for d in DELIMITERS if counts[d]]
    if len(found) <= 1:
        return found[0] if found else ","
    fits = []                      # the separators that split every line into as many cells as the first
    for delimiter in found:
        try:
            header, *rows = [r for r in _parse(text, delimiter, where, error) if not r.blank] or [Record(1, ())]
        except CourseFileError:
            continue
        if all(_width(r) <= len(header.cells) for r in rows):
            fits.append(delimiter)
    best = sorted(fits, key=lambda d: -counts[d])
    if best and (len(best) == 1 or counts[best[0]] > counts[best[1]]):
        return best[0]
    line = text[:len(text) - len(body)].count("\n") + 1
    names = " and ".join(_DELIMITER_NAMES[d] for d in found)
    raise error(f"{where}, line {line}: the column names are separated by {names}, and the lines do not tell which "
                "one separates the cells; use one separator, and quote a cell that holds it")


def _parse(text: str, delimiter: str, where: str, error: type[CourseFileError]) -> tuple[Record, ...]:
    records: list[Record] = []
    i, n, line = 0, len(text), 1
    while i < n:
        first_line, cells = line, []
        while True:
            start = i
            j = i
            while j < n and text[j] == " ":    # spaces before a quoted cell belong to it
                j += 1
            if j < n and text[j] == '"':
                i = j + 1
                parts = []
                while True:
                    if i >= n:
                        raise error(f"{where}, line {first_line}: a quoted cell is not closed")
                    char = text[i]
                    if char == '"':
                        if text.startswith('""', i):
                            parts.append('"')
                            i += 2
                            continue
                        i += 1
                        break
                    if char == "\n" or (char == "\r" and not text.startswith("\r\n", i)):
                        line += 1
                    parts.append(char)
                    i += 1
                while i < n and text[i] == " ":
                    i += 1
                if i < n and text[i] not in (delimiter, "\r", "\n"):
                    raise error(f"{where}, line {line}: text after the closing quote of a cell")
                cells.append(Cell("".join(parts), start, i, True))
            else:
                while i < n and text[i] not in (delimiter, "\r", "\n"):
                    i += 1
                cells.append(Cell(text[start:i], start, i, False))
            if i < n and text[i] == delimiter:
                i += 1
                continue
            break
        i += 2 if text.startswith("\r\n", i) else 1
        line += 1
        records.append(Record(first_line, tuple(cells)))
    return tuple(records)


def read_csv_text(path: str | pathlib.Path, what: str, error: type[CourseFileError] = CourseFileError,
                  data: bytes | None = None) -> CsvText:
    """Read a CSV file in any of the dialects of the module's notes.

    Parameters
    ----------
    path : str or path
        The file, or the name messages give a file read from memory (a member of a zip archive).
    what : str
        What the file is, for messages (``"class list"``).
    error : type
        The error to raise (a :class:`CourseFileError`).
    data : bytes, optional
        The file's bytes, when they are already in memory (nothing is then read from ``path``).

    Raises
    ------
    CourseFileError
        If the file is missing or cannot be read, is not UTF-8 (or UTF-16 with a byte-order mark), holds a NUL
        character, is empty, has a quoted cell that is not closed, or separators that do not tell which one
        separates the cells.
    """
    path = pathlib.Path(path)
    where = f"{what} {path}"
    try:
        if data is None:
            data = path.read_bytes()
    except FileNotFoundError:
        raise error(f"{where}: no such file") from None
    except OSError as failure:
        raise error(f"{where}: cannot be read ({failure.strerror or failure})") from None
    bom, encoding = next(((mark, name) for mark, name in _ENCODINGS if data.startswith(mark)), (b"", "utf-8"))
    try:
        text = data[len(bom):].decode(encoding)
    except UnicodeDecodeError as failure:
        raise error(f"{where}: not {encoding.upper()[:6]} text (byte {failure.start + len(bom)}); save it as CSV "
                    "in UTF-8") from None
    if "\0" in text:
        raise error(f"{where}: holds a NUL character at line {text[:text.index(chr(0))].count(chr(10)) + 1} (not "
                    "a text file, or UTF-16 without a byte-order mark); save it as CSV in UTF-8")
    delimiter = _delimiter(text, where, error)
    records = _parse(text, delimiter, where, error)
    if all(r.blank for r in records):
        raise error(f"{where}: empty (the first line must name the columns)")
    return CsvText(path, text, bom, delimiter, records, encoding)


def encode_cell(value: str, delimiter: str, quoted: bool = False) -> str:
    """A cell's text: quoted (``"`` doubled) if it was quoted before or must be (a separator, a quote, a line
    break, or spaces at its ends)."""
    needs = quoted or any(c in value for c in (delimiter, '"', "\n", "\r")) or value != value.strip()
    return '"' + value.replace('"', '""') + '"' if needs else value


def csv_lines(rows: Iterable[Sequence[object]]) -> str:
    """CSV text (``,`` between cells, ``\\n`` after each row) of rows of text and numbers, safe for a spreadsheet.

    A ``str`` is text, perhaps from a person: written through :func:`mechanisms.present.escape.csv_cell` (a
    leading ``'`` if it could start a formula) and quoted where it must be (:func:`encode_cell`: a separator, a
    quote, a line break or a carriage return in it, spaces at its ends). A ``float`` is written to full precision
    (``repr``), an ``int`` as it is, ``None`` as an empty cell: numbers stay numbers (``-0.25``, no ``'``).
    """
    def cell(value: object) -> str:
        if value is None:
            return ""
        if isinstance(value, str):
            return encode_cell(csv_cell(value), ",")
        return repr(float(value)) if isinstance(value, float) else str(value)

    return "".join(",".join(cell(value) for value in row) + "\n" for row in rows)


def replace_cells(csv_text: CsvText, values: dict[tuple[int, int], str]) -> bytes:
    """The file's bytes with some cells replaced, every other byte as it was (its encoding and byte-order mark
    kept).

    Parameters
    ----------
    csv_text : CsvText
    values : dict
        ``{(record index in csv_text.records, cell index): new value}``; the cells must exist.
    """
    pieces, last = [], 0
    for (record, index), value in sorted(values.items(), key=lambda item: csv_text.records[item[0][0]]
                                          .cells[item[0][1]].start):
        cell = csv_text.records[record].cells[index]
        pieces += [csv_text.text[last:cell.start], encode_cell(value, csv_text.delimiter, cell.quoted)]
        last = cell.end
    pieces.append(csv_text.text[last:])
    return csv_text.bom + "".join(pieces).encode(csv_text.encoding)


def write_file(path: str | pathlib.Path, data: str | bytes, what: str,
               error: type[CourseFileError] = CourseFileError) -> pathlib.Path:
    """Write a file of the course tools (text as UTF-8), or raise ``error`` naming it and the cause.

    Parameters
    ----------
    path : str or path
    data : str or bytes
    what : str
        What the file is, for messages (``"grades file"``).
    error : type
        The error to raise (a :class:`CourseFileError`).
    """
    path = pathlib.Path(path)
    try:
        if isinstance(data, str):
            with path.open("w", encoding="utf-8", newline="") as handle:
                handle.write(data)
        else:
            path.write_bytes(data)
    except OSError as failure:
        raise error(f"{what} {path}: cannot be written ({failure.strerror or failure})") from None
    return path
