"""CSV files of the course tools, read so that they can be written back unchanged but for the cells filled in.

A class list or a learning platform's grading worksheet comes from a spreadsheet or a web site: UTF-8 with or
without a byte-order mark, cells separated by commas, semicolons or tabs, quoted or not, lines ending in
``\\n`` or ``\\r\\n``, names in any script. :func:`read_csv_text` reads such a file into records whose cells
keep their place in the text, so that :func:`replace_cells` can change a few cells and leave every other
byte of the file as it was.
"""

from __future__ import annotations

import codecs
import pathlib
from dataclasses import dataclass

from ..core.errors import MechanismError

__all__ = ["CourseFileError", "Cell", "Record", "CsvText", "read_csv_text", "replace_cells", "encode_cell",
           "header_key"]

DELIMITERS = (",", ";", "\t")
"""The cell separators recognised, by their count in the first line (outside quotes); a tie goes to the first."""


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
    """A CSV file as read: its text, byte-order mark, separator and records (blank records included)."""

    path: pathlib.Path
    text: str
    bom: bool
    delimiter: str
    records: tuple[Record, ...]

    @property
    def rows(self) -> list[Record]:
        """The records that are not blank: the header first."""
        return [r for r in self.records if not r.blank]


def header_key(text: str) -> str:
    """A column name reduced for matching: lower case, letters and digits only (``"E-mail address"`` →
    ``"emailaddress"``)."""
    return "".join(c for c in text.casefold() if c.isalnum())


def _delimiter(text: str) -> str:
    counts = dict.fromkeys(DELIMITERS, 0)
    quoted = False
    for char in text:
        if char == '"':
            quoted = not quoted
        elif not quoted and char in "\r\n":
            break
        elif not quoted and char in counts:
            counts[char] += 1
    best = max(DELIMITERS, key=lambda d: counts[d])
    return best if counts[best] else ","


def _parse(text: str, delimiter: str, where: str, error: type[CourseFileError]) -> tuple[Record, ...]:
    records: list[Record] = []
    i, n, line = 0, len(text), 1
    while i < n:
        first_line, cells = line, []
        while True:
            start = i
            if i < n and text[i] == '"':
                i += 1
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


def read_csv_text(path: str | pathlib.Path, what: str, error: type[CourseFileError] = CourseFileError) -> CsvText:
    """Read a CSV file (UTF-8, with or without a byte-order mark; ``,`` ``;`` or tab between cells).

    Parameters
    ----------
    path : str or path
    what : str
        What the file is, for messages (``"class list"``).
    error : type
        The error to raise (a :class:`CourseFileError`).

    Raises
    ------
    CourseFileError
        If the file is missing, not UTF-8, empty, or has a quoted cell that is not closed.
    """
    path = pathlib.Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise error(f"{what} {path}: no such file") from None
    except OSError as failure:
        raise error(f"{what} {path}: cannot be read ({failure.strerror})") from None
    bom = data.startswith(codecs.BOM_UTF8)
    try:
        text = data[len(codecs.BOM_UTF8) if bom else 0:].decode("utf-8")
    except UnicodeDecodeError as failure:
        raise error(f"{what} {path}: not UTF-8 text (byte {failure.start + (3 if bom else 0)}); save it as CSV in "
                    "UTF-8") from None
    if not text.strip():
        raise error(f"{what} {path}: empty (the first line must name the columns)")
    delimiter = _delimiter(text.lstrip("\r\n"))
    return CsvText(path, text, bom, delimiter, _parse(text, delimiter, f"{what} {path}", error))


def encode_cell(value: str, delimiter: str, quoted: bool = False) -> str:
    """A cell's text: quoted (``"`` doubled) if it was quoted before or must be (a separator, a quote, a line
    break, or spaces at its ends)."""
    needs = quoted or any(c in value for c in (delimiter, '"', "\n", "\r")) or value != value.strip()
    return '"' + value.replace('"', '""') + '"' if needs else value


def replace_cells(csv_text: CsvText, values: dict[tuple[int, int], str]) -> bytes:
    """The file's bytes with some cells replaced, every other byte as it was.

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
    return (codecs.BOM_UTF8 if csv_text.bom else b"") + "".join(pieces).encode("utf-8")
