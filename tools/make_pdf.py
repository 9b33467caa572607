"""The printable book: one PDF of a built site, its pages printed by Chromium through Playwright, in the order of
``_toc.yml``, after a title page with the table of contents; every page numbered.

    .venv/bin/python tools/make_pdf.py                       # both editions (``make pdf``)
    .venv/bin/python tools/make_pdf.py --edition student     # one of them

The sites must be built first (``make book`` → ``_build/html``, ``make book-student`` →
``_build/student/_build/html``); the PDFs are ``_build/pdf/mechanisms-book.pdf`` and
``_build/pdf/mechanisms-book-student.pdf``.

Each page is opened from a local server (nothing outside it is loaded, as in the site test), its images loaded,
its math typeset by MathJax (the PDF holds no TeX), the worked solutions of the full edition opened, and then
printed with the site's print style (``@media print``: the player's still image in place of an animation) on
A4. The pages are joined with pypdf (the book and test extras, not a run-time dependency of the package), with
a bookmark for every page, and numbered at the foot of each page by an overlay that Chromium prints too. The
browser is found as the site test finds it (``tests/find_browser.py``: ``MECHANISMS_BROWSER``, the usual
names and paths, Playwright's own).
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import html
import http.server
import io
import pathlib
import sys
import threading
import time
from dataclasses import dataclass
from typing import Iterator

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from find_browser import BrowserNotFound, find_browser  # noqa: E402

EDITIONS = {
    "full": (ROOT / "_build" / "html", ROOT / "_build" / "pdf" / "mechanisms-book.pdf", ""),
    "student": (ROOT / "_build" / "student" / "_build" / "html", ROOT / "_build" / "pdf" / "mechanisms-book-student.pdf",
                "Student edition (without the solutions)"),
}
"""Per edition: the built site, the PDF written, the subtitle of its title page."""

TITLE = "Kinematics of Planar Linkage Mechanisms"
PAGE = {"format": "A4", "margin": {"top": "16mm", "bottom": "18mm", "left": "15mm", "right": "15mm"}}

# Every image loaded (a lazy image off screen would print empty), MathJax done, worked solutions opened.
PREPARE = """async (openSolutions) => {
  for (const img of document.images) { img.loading = "eager"; }
  await Promise.all([...document.images].map(img => img.complete ? null :
      new Promise(done => { img.addEventListener("load", done); img.addEventListener("error", done); })));
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) { await MathJax.startup.promise; }
  if (window.MathJax && MathJax.typesetPromise) { await MathJax.typesetPromise(); }
  if (openSolutions) {
    document.querySelectorAll("details").forEach(d => { d.open = true; });
    document.querySelectorAll(".toggle-hidden").forEach(e => e.classList.remove("toggle-hidden"));
    document.querySelectorAll(".dropdown").forEach(e => e.classList.remove("toggle-hidden"));
  }
  await document.fonts.ready;
  return document.querySelectorAll("mjx-container").length;
}"""

TEX_LEFT = "() => document.body.innerText.includes('$$') || /\\\\(frac|begin)\\b/.test(document.body.innerText)"


@dataclass(frozen=True)
class Chapter:
    """A page of the book in the order of ``_toc.yml``: its source file, the part it is in, its HTML page."""

    file: str
    part: str

    @property
    def html(self) -> str:
        return f"{self.file}.html"


def toc_pages(toc: pathlib.Path = ROOT / "_toc.yml") -> list[Chapter]:
    """Every page of the book in the order of the table of contents (the root first)."""
    data = yaml.safe_load(toc.read_text(encoding="utf8"))
    pages = [Chapter(data["root"], "")]
    for part in data.get("parts", []):
        pages += [Chapter(entry["file"], part.get("caption", "")) for entry in part.get("chapters", [])]
    return pages


@contextlib.contextmanager
def serve(site: pathlib.Path) -> Iterator[str]:
    """A local HTTP server of the site (quiet), its address while the block runs."""

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args: object) -> None:
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    try:
        yield f"http://127.0.0.1:{httpd.server_address[1]}"
    finally:
        httpd.shutdown()


def _html_page(body: str, style: str = "") -> str:
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><style>body {{ font-family: 'DejaVu Sans', "
            f"Arial, sans-serif; margin: 0; }} {style}</style></head><body>{body}</body></html>")


def contents_html(title: str, subtitle: str, entries: list[tuple[str, str, int]]) -> str:
    """The title page and table of contents: (part, title, first page) per page of the book."""
    rows, part = [], None
    for caption, name, first in entries:
        if caption != part and caption:
            rows.append(f"<tr class='part'><td colspan='2'>{html.escape(caption)}</td></tr>")
        part = caption
        rows.append(f"<tr><td>{html.escape(name)}</td><td class='page'>{first}</td></tr>")
    style = ("h1 { font-size: 26pt; margin: 30mm 0 4mm; } .sub { font-size: 13pt; color: #444; margin-bottom: 18mm; } "
             "h2 { font-size: 15pt; } table { width: 100%; border-collapse: collapse; font-size: 11pt; } "
             "td { padding: 1.2mm 0; border-bottom: 1px dotted #bbb; } td.page { text-align: right; width: 15mm; } "
             "tr.part td { font-weight: bold; border: none; padding-top: 5mm; }")
    return _html_page(f"<h1>{html.escape(title)}</h1><div class='sub'>{html.escape(subtitle) or '&nbsp;'}</div>"
                      f"<h2>Contents</h2><table>{''.join(rows)}</table>", style)


def numbers_html(count: int) -> str:
    """``count`` empty A4 pages, each with its number at the foot: the overlay that numbers the book."""
    pages = "".join(f"<div class='p'><span>{n}</span></div>" for n in range(1, count + 1))
    style = ("@page { size: A4; margin: 0; } .p { position: relative; width: 210mm; height: 297mm; "
             "page-break-after: always; overflow: hidden; } .p span { position: absolute; bottom: 8mm; left: 0; "
             "right: 0; text-align: center; font-size: 9pt; color: #555; }")
    return _html_page(pages, style)


def print_html(context, text: str) -> bytes:
    page = context.new_page()
    page.set_content(text, wait_until="load")
    data = page.pdf(format="A4", margin={"top": "0", "bottom": "0", "left": "0", "right": "0"}
                    if "@page" in text else {"top": "15mm", "bottom": "18mm", "left": "20mm", "right": "20mm"},
                    prefer_css_page_size=True, print_background=True)
    page.close()
    return data


def print_site_page(context, url: str, open_solutions: bool) -> tuple[bytes, str]:
    """One page of the site as PDF bytes, and its title (the first heading)."""
    page = context.new_page()
    page.goto(url, wait_until="load")
    page.evaluate(PREPARE, open_solutions)
    if page.evaluate(TEX_LEFT):
        raise RuntimeError(f"{url}: TeX left on the page after MathJax ran")
    title = page.evaluate("() => (document.querySelector('main h1, article h1, h1') || document).textContent")
    data = page.pdf(print_background=True, **PAGE)   # print media: the site's @media print rules apply
    page.close()
    return data, " ".join(str(title).replace("#", "").split())


def make_pdf(edition: str, browser_path: pathlib.Path | None = None) -> pathlib.Path:
    """Print the built site of an edition into one PDF; returns its path."""
    from playwright.sync_api import sync_playwright
    from pypdf import PdfReader, PdfWriter

    site, out, subtitle = EDITIONS[edition]
    if not (site / "index.html").exists():
        raise SystemExit(f"{site} is not built: run `make book` (full) or `make book-student` (student) first")
    chapters = toc_pages()
    browser_path = browser_path or find_browser()
    with serve(site) as server, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(browser_path), args=[
            "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"])
        context = browser.new_context(viewport={"width": 1100, "height": 1400})
        context.route("**/*", lambda r: r.continue_() if r.request.url.startswith((server, "data:", "about:"))
                      else r.abort())
        printed = [print_site_page(context, f"{server}/{c.html}", edition == "full") for c in chapters]
        readers = [PdfReader(io.BytesIO(data)) for data, _ in printed]
        entries = [(c.part, title, 0) for c, (_, title) in zip(chapters, printed)]
        front = len(PdfReader(io.BytesIO(print_html(context, contents_html(TITLE, subtitle, entries)))).pages)
        starts, page_number = [], front + 1
        for reader in readers:
            starts.append(page_number)
            page_number += len(reader.pages)
        entries = [(part, title, start) for (part, title, _), start in zip(entries, starts)]
        contents = PdfReader(io.BytesIO(print_html(context, contents_html(TITLE, subtitle, entries))))
        numbers = PdfReader(io.BytesIO(print_html(context, numbers_html(page_number - 1))))
        browser.close()
    writer = PdfWriter()
    for source in [contents, *readers]:
        for page in source.pages:
            writer.add_page(page)
    for index, page in enumerate(writer.pages):
        if index >= len(contents.pages):   # the title and contents pages carry no number
            page.merge_page(numbers.pages[index])
    for page in writer.pages:
        page.compress_content_streams()   # the numbered pages' merged content is written uncompressed otherwise
    writer.compress_identical_objects(remove_duplicates=True, remove_unreferenced=True)   # fonts shared by pages
    for (_, title, _), start in zip(entries, starts):
        writer.add_outline_item(title=title, page_number=start - 1)
    writer.add_metadata({"/Title": TITLE + (f" — {subtitle}" if subtitle else "")})
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("wb") as handle:
        writer.write(handle)
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--edition", choices=[*EDITIONS, "both"], default="both")
    args = parser.parse_args(argv)
    try:
        browser = find_browser()
    except BrowserNotFound as missing:
        print(f"error: {missing}", file=sys.stderr)
        return 2
    for edition in (EDITIONS if args.edition == "both" else [args.edition]):
        start = time.perf_counter()
        path = make_pdf(edition, browser)
        print(f"{edition}: {path.relative_to(ROOT)} ({path.stat().st_size / 1e6:.1f} MB, "
              f"{time.perf_counter() - start:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
