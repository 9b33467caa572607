"""The printable book (``make pdf``, tools/make_pdf.py): both editions' PDFs hold every page of the table of
contents, no TeX left unrendered, page numbers and a table of contents; the student edition no solution.

The sites must be built (``make test`` builds both, then ``make pdf``); without them this test fails and says
so. It reads the PDFs that ``make pdf`` wrote when they are newer than their site, and makes them otherwise.
The chapters' titles expected come from the sources (the first heading of each page's ``.md``), not from the
PDF tool.
"""

from __future__ import annotations

import pathlib
import re
import sys
import unicodedata

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import make_pdf  # noqa: E402

import pypdf  # noqa: E402  (the test extra)

pytestmark = pytest.mark.needs_site("full", "student")   # the PDFs are printed from both sites

SOLUTION_MARK = "Solution to"
"""How the site marks a worked solution: sphinx-exercise titles each one "Solution to Exercise N.M"."""


def source_titles() -> list[str]:
    """The first heading of every page's source, in the order of _toc.yml."""
    titles = []
    for chapter in make_pdf.toc_pages():
        text = (ROOT / f"{chapter.file}.md").read_text(encoding="utf8")
        titles.append(re.search(r"^# (.+)$", text, flags=re.M).group(1).strip())
    return titles


def normalized(text: str) -> str:
    """Text as read from a PDF, comparable: ligatures undone (ﬁ → fi), words hyphenated at a line's end joined
    ("crank-\\nslider" → "crank-slider"), runs of white space one space."""
    return " ".join(unicodedata.normalize("NFKC", text).replace("-\n", "-").split())


@pytest.fixture(scope="module", params=list(make_pdf.EDITIONS))
def book(request) -> tuple[str, list[str], int]:
    """(edition, the text of each page of its PDF, the number of front pages: title and contents)."""
    edition = request.param
    site, pdf, _ = make_pdf.EDITIONS[edition]
    if not (site / "index.html").exists():
        pytest.fail(f"the {edition} edition's site {site.relative_to(ROOT)} is not built: run `make book` and "
                    "`make book-student` (`make test` builds both, then the PDFs)", pytrace=False)
    if not pdf.exists() or pdf.stat().st_mtime < (site / "index.html").stat().st_mtime:
        make_pdf.make_pdf(edition)
    reader = pypdf.PdfReader(pdf)
    front = reader.get_destination_page_number(reader.outline[0])     # the first page of the book's text
    return edition, [page.extract_text() for page in reader.pages], front


def test_every_page_of_the_contents_is_there_in_order(book):
    edition, pages, front = book
    text = normalized(" ".join(pages[front:]))
    contents = normalized(" ".join(pages[:front]))
    assert contents.startswith(make_pdf.TITLE) and "Contents" in contents
    position = 0
    for title in source_titles():
        assert normalized(title) in contents, f"{edition}: {title!r} is not in the table of contents"
        found = text.find(normalized(title), position)
        assert found >= 0, f"{edition}: the page {title!r} is missing or out of the order of _toc.yml"
        position = found


def test_the_math_is_typeset(book):
    edition, pages, _ = book
    for number, page in enumerate(pages, start=1):
        assert "$$" not in page and "\\frac" not in page and "\\begin{" not in page, \
            f"{edition}, page {number}: TeX left unrendered"


def test_pages_are_numbered(book):
    _, pages, front = book
    assert 1 <= front <= 3
    for index in (front, len(pages) // 2, len(pages) - 1):
        assert normalized(pages[index]).endswith(str(index + 1)), f"page {index + 1} carries no number"


def test_the_student_edition_has_no_solution_and_the_full_one_has_them(book):
    edition, pages, _ = book
    solutions = sum(page.count(SOLUTION_MARK) for page in pages)
    if edition == "student":
        assert solutions == 0, "the student edition's PDF holds worked solutions"
    else:
        assert solutions >= 40, f"the full edition's PDF holds only {solutions} solutions (≥ 4 per chapter)"
