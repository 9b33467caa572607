"""The printable book (``make pdf``, tools/make_pdf.py): both editions' PDFs hold every page of the table of
contents, no TeX left unrendered, page numbers, a table of contents and a bookmark per page; the student edition
no solution. Both are tagged PDFs (issue 32): a structure tree with headings, the site's language, and a Figure
element for every figure of the site whose /Alt is the figure's text alternative, read from the site's HTML.

The sites must be built (``make test`` builds both, then ``make pdf``); without them this test fails and says
so. It reads the PDFs that ``make pdf`` wrote when they are newer than their site, and makes them otherwise.
The chapters' titles expected come from the sources (the first heading of each page's ``.md``), not from the
PDF tool.
"""

from __future__ import annotations

import functools
import html.parser
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


@functools.cache
def printed(edition: str) -> pypdf.PdfReader:
    """The PDF of an edition, made first if it is missing or older than its site."""
    site, pdf, _ = make_pdf.EDITIONS[edition]
    if not (site / "index.html").exists():
        pytest.fail(f"the {edition} edition's site {site.relative_to(ROOT)} is not built: run `make book` and "
                    "`make book-student` (`make test` builds both, then the PDFs)", pytrace=False)
    if not pdf.exists() or pdf.stat().st_mtime < (site / "index.html").stat().st_mtime:
        make_pdf.make_pdf(edition)
    return pypdf.PdfReader(pdf)


@pytest.fixture(scope="module", params=list(make_pdf.EDITIONS))
def book(request) -> tuple[str, list[str], int]:
    """(edition, the text of each page of its PDF, the number of front pages: title and contents)."""
    reader = printed(request.param)
    front = reader.get_destination_page_number(reader.outline[0])     # the first page of the book's text
    return request.param, [page.extract_text() for page in reader.pages], front


@pytest.fixture(scope="module", params=list(make_pdf.EDITIONS))
def tagged(request) -> tuple[str, pypdf.PdfReader, list[pypdf.generic.DictionaryObject]]:
    """(edition, its PDF, the structure elements of its structure tree in document order: none in an untagged
    PDF)."""
    reader = printed(request.param)
    root = reader.trailer["/Root"]
    elements: list[pypdf.generic.DictionaryObject] = []

    def walk(node) -> None:
        node = node.get_object()
        if not isinstance(node, pypdf.generic.DictionaryObject):
            return                               # a marked-content id: the page's content, not an element
        if "/S" in node:
            elements.append(node)
        kids = node.get("/K")
        for kid in kids if isinstance(kids, pypdf.generic.ArrayObject) else [] if kids is None else [kids]:
            walk(kid)

    if "/StructTreeRoot" in root:
        walk(root["/StructTreeRoot"])
    return request.param, reader, elements


class Alternatives(html.parser.HTMLParser):
    """The text alternatives of the figures in a page's article, in order: an image's alt, a player's still SVG
    (``role="img"``) its ``<desc>``."""

    def __init__(self) -> None:
        super().__init__()
        self.depth = 0            # > 0 inside the article
        self.found: list[str] = []
        self.desc: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        attributes = dict(attrs)
        if tag == "article" and "bd-article" in (attributes.get("class") or "").split():
            self.depth = 1
        elif self.depth and tag not in VOID:
            self.depth += 1
        if self.depth and tag == "img" and (attributes.get("alt") or "").strip():
            self.found.append(str(attributes["alt"]))
        if self.depth and tag == "desc":
            self.desc = []

    def handle_endtag(self, tag: str) -> None:
        if self.depth and tag not in VOID:
            self.depth -= 1
        if tag == "desc" and self.desc is not None:
            self.found.append("".join(self.desc))
            self.desc = None

    def handle_data(self, data: str) -> None:
        if self.desc is not None:
            self.desc.append(data)


VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


def site_alternatives(edition: str) -> list[str]:
    """Every figure's text alternative on the site of an edition, in the order of the book."""
    site = make_pdf.EDITIONS[edition][0]
    found = []
    for chapter in make_pdf.toc_pages():
        parser = Alternatives()
        parser.feed((site / chapter.html).read_text(encoding="utf8"))
        found += parser.found
    return [" ".join(html.unescape(text).split()) for text in found]


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
        words = normalized(pages[index]).split()     # the number is read first or last, as the PDF draws it
        assert str(index + 1) in (words[0], words[-1]), f"page {index + 1} carries no number"


def test_the_student_edition_has_no_solution_and_the_full_one_has_them(book):
    edition, pages, _ = book
    solutions = sum(page.count(SOLUTION_MARK) for page in pages)
    if edition == "student":
        assert solutions == 0, "the student edition's PDF holds worked solutions"
    else:
        assert solutions >= 40, f"the full edition's PDF holds only {solutions} solutions (≥ 4 per chapter)"


def test_the_pdf_is_tagged_in_the_sites_language(tagged):
    edition, reader, elements = tagged
    root = reader.trailer["/Root"]
    assert "/StructTreeRoot" in root, f"{edition}: the PDF is not tagged (no /StructTreeRoot)"
    assert "/MarkInfo" in root and root["/MarkInfo"]["/Marked"].value is True, f"{edition}: the PDF is not marked"
    site = make_pdf.EDITIONS[edition][0]
    language = re.search(r'<html[^>]*\blang="([^"]+)"', (site / f"{make_pdf.toc_pages()[0].html}").read_text(
        encoding="utf8")).group(1)
    assert root["/Lang"] == language, f"{edition}: the PDF's language is {root.get('/Lang')!r}, the site's {language!r}"
    kinds = [str(element["/S"]) for element in elements]
    assert kinds.count("/H1") >= len(make_pdf.toc_pages()), f"{edition}: fewer H1 than pages of the book"
    assert "/H2" in kinds and "/P" in kinds and "/Table" in kinds and "/Link" in kinds


def test_every_figure_keeps_its_text_alternative(tagged):
    edition, _, elements = tagged
    printed_alternatives = [" ".join(str(e.get("/Alt", "")).split()) for e in elements if e["/S"] == "/Figure"]
    expected = site_alternatives(edition)
    assert len(expected) >= 50, f"{edition}: only {len(expected)} figures with a text alternative on the site"
    assert all(printed_alternatives), f"{edition}: a Figure of the PDF has no /Alt"
    assert printed_alternatives == expected, \
        f"{edition}: the PDF's figures ({len(printed_alternatives)}) are not the site's ({len(expected)}) in order"


def test_a_bookmark_for_every_page_of_the_book(book):
    edition, _, front = book
    reader = printed(edition)
    top = [item for item in reader.outline if not isinstance(item, list)]
    titles = source_titles()
    assert len(top) == len(titles), f"{edition}: {len(top)} top-level bookmarks for {len(titles)} pages"
    for item, title in zip(top, titles):
        assert normalized(title) in normalized(item.title), f"{edition}: the bookmark {item.title!r} is not {title!r}"
    assert reader.get_destination_page_number(top[0]) == front
    pages = [reader.get_destination_page_number(item) for item in top]
    assert pages == sorted(pages), f"{edition}: the bookmarks are out of order"
