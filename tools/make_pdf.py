"""The printable book: one tagged PDF of a built site, printed by Chromium through Playwright: a title page with
the table of contents, then every page of the book in the order of ``_toc.yml``; every page numbered.

    .venv/bin/python tools/make_pdf.py                       # both editions (``make pdf``)
    .venv/bin/python tools/make_pdf.py --edition student     # one of them

The sites must be built first (``make book`` → ``_build/html``, ``make book-student`` →
``_build/student/_build/html``); the PDFs are ``_build/pdf/mechanisms-book.pdf`` and
``_build/pdf/mechanisms-book-student.pdf``.

Each page is opened from a local server (nothing outside it is loaded, as in the site test), its images loaded,
its math typeset by MathJax (the PDF holds no TeX) and the worked solutions of the full edition opened. Its
article is then moved into ONE printable document, the first page's, with the site's style sheets and MathJax's:
the ids of each page get the page's prefix (``book-03-crank-slider--the-mechanism``) and the links between the
book's pages become links inside the PDF (printing each page alone and joining the PDFs, as this tool did
before, loses the structure trees: pypdf does not merge them). Chromium prints that document with the site's print style
(``@media print``: the player's still image in place of an animation) on A4, as a tagged PDF (``page.pdf(tagged=
True)``): a structure tree with headings H1–H3, the document's language, and a Figure element for every image
whose /Alt is the image's alt text. An SVG still of the player is a Figure too, and its ``<desc>`` (what it
shows, not only its title) is made its accessible name for print; a ``<figure>`` is a group around it, not a
Figure without /Alt. CSS numbers the pages (``@page`` margin boxes; the title and contents pages carry none) and
drops the shadows (each would be printed as an image of the page's size). A first, untagged print finds the page
on which each chapter starts (its named destination), the contents are filled in and the book printed again,
tagged. pypdf (the book and test extras, not a
run-time dependency of the package) then adds the bookmarks, one per page of the book and one per section (the
headings' text from the page, their place from Chromium's destinations), keeping the structure tree. The browser
is found as the site test finds it (``tests/find_browser.py``: ``MECHANISMS_BROWSER``, the usual names and paths,
Playwright's own).
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
from typing import Any, Iterator

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
MARGIN = "16mm 15mm 18mm 15mm"
"""The page's margins (top, right, bottom, left) on A4; the page number sits in the bottom one."""

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

# A prepared page's article, ready to be moved into the book's document: ids prefixed (and every reference to them:
# links, labels, ARIA, SVG url(#…)), links to the book's pages made links inside it, every other address absolute;
# a player's still SVG named by its <desc>; a <figure> a group (its image is the Figure). Returns the article's
# HTML, its first heading, and the page's style sheets (addresses) and styles (MathJax's CHTML rules: only the
# characters the page uses).
EXTRACT = """([prefix, pages]) => {
  const article = document.querySelector("article.bd-article");
  if (!article) { return null; }
  const absolute = text => text.replace(/url\\((['"]?)([^'")]+)\\1\\)/g,
      (whole, quote, address) => address.startsWith("#") || address.startsWith("data:") ? whole
          : "url(" + quote + new URL(address, document.baseURI).href + quote + ")");
  const ids = new Map();
  for (const node of article.querySelectorAll("[id]")) {
    const id = prefix + "--" + node.id;
    ids.set(node.id, id);
    node.id = id;
  }
  const inBook = address => {
    const url = new URL(address, document.baseURI);
    if (url.origin !== location.origin || !(url.pathname in pages)) { return null; }
    const fragment = decodeURIComponent(url.hash.slice(1));
    return "#" + (fragment ? pages[url.pathname] + "--" + fragment : pages[url.pathname]);
  };
  const references = ["for", "aria-labelledby", "aria-describedby", "aria-controls", "aria-owns", "headers"];
  for (const node of article.querySelectorAll("*")) {
    for (const { name, value } of [...node.attributes]) {
      let changed = value;
      if (node instanceof HTMLAnchorElement && name === "href") {
        changed = inBook(value) || new URL(value, document.baseURI).href;
      } else if (name === "src" || (name === "href" && node instanceof HTMLLinkElement)) {
        changed = new URL(value, document.baseURI).href;
      } else if (name === "srcset") {
        changed = value.split(",").map(part => part.trim().replace(/^\\S+/,
            address => new URL(address, document.baseURI).href)).join(", ");
      } else if (references.includes(name)) {
        changed = value.split(/\\s+/).map(id => ids.get(id) || id).join(" ");
      } else if ((name === "href" || name === "xlink:href") && value.startsWith("#")) {
        changed = "#" + (ids.get(value.slice(1)) || value.slice(1));
      }
      if (changed.includes("url(")) {
        changed = absolute(changed.replace(/url\\(#([^)]+)\\)/g, (whole, id) => "url(#" + (ids.get(id) || id) + ")"));
      }
      if (changed !== value) { node.setAttribute(name, changed); }
    }
  }
  for (const figure of article.querySelectorAll("figure")) {
    figure.setAttribute("role", "group");   // not a Figure of its own around the image's (which has the alt)
  }
  for (const svg of article.querySelectorAll("svg[role='img']")) {
    const desc = svg.querySelector(":scope > desc");
    if (desc && desc.textContent.trim() && !svg.hasAttribute("aria-label")) {
      svg.setAttribute("aria-label", desc.textContent.trim().replace(/\\s+/g, " "));
    }
  }
  const heading = article.querySelector("h1");
  const title = heading ? heading.cloneNode(true) : null;
  if (title) { title.querySelectorAll(".headerlink").forEach(link => link.remove()); }
  return {
    html: article.innerHTML,
    title: title ? title.textContent.replace(/\\s+/g, " ").trim() : "",
    sheets: [...document.querySelectorAll("link[rel='stylesheet']")].map(link => link.href),
    styles: [...document.head.querySelectorAll("style")].map(style => absolute(style.textContent)),
  };
}"""

# The book's document: the first page with everything but its article removed (the article keeps its place in
# the theme's layout, so the site's print style applies as on the site), the title, contents and every page's
# article in it, one after another, each from a new sheet; the style sheets and styles of every page added.
ASSEMBLE = """([front, chapters, sheets, styles, title]) => {
  const article = document.querySelector("article.bd-article");
  for (let node = article; node !== document.body; node = node.parentElement) {
    for (const other of [...node.parentElement.children]) { if (other !== node) { other.remove(); } }
  }
  const present = new Set([...document.querySelectorAll("link[rel='stylesheet']")].map(link => link.href));
  for (const sheet of sheets) {
    if (!present.has(sheet)) {
      const link = document.head.appendChild(document.createElement("link"));
      link.rel = "stylesheet";
      link.href = sheet;
      present.add(sheet);
    }
  }
  for (const text of styles) { document.head.appendChild(document.createElement("style")).textContent = text; }
  article.innerHTML = front + chapters.map(([id, body]) =>
      `<div class="pdf-chapter" id="${id}">${body}</div>`).join("");
  document.title = title;
  return Promise.all([...document.querySelectorAll("link[rel='stylesheet']")].map(link => link.sheet ? null :
      new Promise(done => { link.addEventListener("load", done); link.addEventListener("error", done); })));
}"""

# The book's document, once assembled: every image loaded, the fonts too.
LOADED = """async () => {
  for (const img of document.images) { img.loading = "eager"; }
  await Promise.all([...document.images].map(img => img.complete ? null :
      new Promise(done => { img.addEventListener("load", done); img.addEventListener("error", done); })));
  await document.fonts.ready;
}"""

# What the print needs besides the site's print style: A4, the margins, a number at the foot of every page but
# the title and contents pages, each page of the book from a new sheet.
PRINT_STYLE = f"""
@page {{ size: A4; margin: {MARGIN};
        @bottom-center {{ content: counter(page); font-family: 'DejaVu Sans', Arial, sans-serif; font-size: 9pt;
                          color: #555; vertical-align: bottom; padding-bottom: 8mm; }} }}
@page front {{ @bottom-center {{ content: none; }} }}
.pdf-front {{ page: front; }}
@media print {{
  /* the theme hides a page's first h1 in print (it prints its own title block, which is not moved); the full
     width of the sheet for the text */
  .bd-main .bd-content .bd-article h1:first-of-type {{ display: block; }}
  .bd-main .bd-content {{ margin: 0; }}
  .bd-main .bd-content .bd-article-container .bd-article {{ padding: 0; }}
}}
/* no shadows (the theme's admonitions have one, !important): Chromium prints each as a soft-masked image the
   size of the page, ~50 kB a page */
.pdf-chapter div.admonition, .pdf-chapter * {{ box-shadow: none !important; }}
.pdf-chapter {{ break-before: page; }}
.bd-main .bd-content .pdf-front h1 {{ font-size: 26pt; margin: 30mm 0 4mm; }}
.pdf-front .pdf-subtitle {{ font-size: 13pt; color: #444; margin-bottom: 18mm; }}
.pdf-front h2 {{ font-size: 15pt; }}
.pdf-front ul {{ list-style: none; padding: 0; margin: 0; font-size: 11pt; }}
.pdf-front p.pdf-part {{ font-weight: bold; margin: 5mm 0 1mm; }}
.pdf-front li a {{ display: flex; justify-content: space-between; padding: 1.2mm 0; border-bottom: 1px dotted #bbb;
                  color: inherit; text-decoration: none; }}
"""

# The page's headings that become bookmarks: (level, text, the id of the section they head).
HEADINGS = """() => [...document.querySelectorAll(".pdf-chapter h1, .pdf-chapter h2, .pdf-chapter h3")].map(h => {
  const copy = h.cloneNode(true);
  copy.querySelectorAll(".headerlink").forEach(link => link.remove());
  const section = h.id ? h : h.closest("[id]");
  return [Number(h.tagName[1]), copy.textContent.replace(/\\s+/g, " ").trim(), section ? section.id : ""];
})"""


@dataclass(frozen=True)
class Chapter:
    """A page of the book in the order of ``_toc.yml``: its source file, the part it is in, its HTML page."""

    file: str
    part: str

    @property
    def html(self) -> str:
        return f"{self.file}.html"

    @property
    def anchor(self) -> str:
        """The id of the page in the book's document (the prefix of its own ids): ``book-03-crank-slider``."""
        return self.file.replace("/", "-")


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


def contents_html(title: str, subtitle: str, entries: list[tuple[str, str, str, int]]) -> str:
    """The title page and table of contents: (part, title, anchor, first page) per page of the book; each entry
    a link to its page."""
    items, part = [], None
    for caption, name, anchor, first in entries:
        if caption != part:
            if part is not None:
                items.append("</ul>")
            if caption:
                items.append(f"<p class='pdf-part'>{html.escape(caption)}</p>")
            items.append("<ul>")
        part = caption
        items.append(f"<li><a href='#{anchor}'><span>{html.escape(name)}</span><span>{first}</span></a></li>")
    items.append("</ul>")
    return (f"<div class='pdf-front'><h1>{html.escape(title)}</h1><p class='pdf-subtitle'>"
            f"{html.escape(subtitle) or '&nbsp;'}</p><h2>Contents</h2>{''.join(items)}</div>")


def chapter_pages(pdf: bytes, chapters: list[Chapter]) -> list[int]:
    """The page (from 1) on which each chapter starts in a printed book: its named destination."""
    from pypdf import PdfReader

    reader = PdfReader(io.BytesIO(pdf))
    destinations = _destinations(reader)
    missing = [c.anchor for c in chapters if c.anchor not in destinations]
    if missing:
        raise RuntimeError(f"the printed book has no destination for the pages {missing}")
    return [_page_index(reader, destinations[c.anchor], c.anchor) + 1 for c in chapters]


def _destinations(reader: Any) -> dict[str, Any]:
    """The named destinations of a PDF by the id they were made from (Chromium writes ``/id``)."""
    return {str(name).removeprefix("/"): target for name, target in reader.named_destinations.items()}


def _page_index(reader: Any, destination: Any, name: str) -> int:
    """The index (from 0) of the page a destination of the PDF points to."""
    index = reader.get_destination_page_number(destination)
    if index is None:
        raise RuntimeError(f"the destination #{name} of the printed book points to no page")
    return int(index)


def print_book(page: Any, tagged: bool = True) -> bytes:
    """The book's document as a PDF (tagged unless told), its size and margins from the print style."""
    return page.pdf(tagged=tagged, outline=False, prefer_css_page_size=True, print_background=True,
                    margin={"top": "0", "bottom": "0", "left": "0", "right": "0"})


def add_bookmarks(pdf: bytes, headings: list[tuple[int, str, str]], title: str) -> bytes:
    """The PDF with a bookmark per heading (level 1–3, nested), at the place of its section's destination; the
    document (its structure tree, language, links) otherwise as Chromium wrote it; ``title`` its title."""
    from pypdf import PdfReader, PdfWriter
    from pypdf.generic import Fit

    reader = PdfReader(io.BytesIO(pdf))
    destinations = _destinations(reader)
    writer = PdfWriter(reader, incremental=True)     # what Chromium wrote, and the bookmarks appended
    parents: dict[int, Any] = {}
    for level, text, anchor in headings:
        if anchor not in destinations:
            raise RuntimeError(f"the printed book has no destination for the heading {text!r} (#{anchor})")
        target = destinations[anchor]
        fit = Fit.xyz(target.left, target.top) if target.typ == "/XYZ" else Fit.fit()
        parents[level] = writer.add_outline_item(title=text, page_number=_page_index(reader, target, anchor),
                                                 parent=parents.get(level - 1), fit=fit)
        for deeper in [key for key in parents if key > level]:
            del parents[deeper]
    writer.page_mode = "/UseOutlines"
    writer.add_metadata({"/Title": title})   # in the appended trailer's information too
    out = io.BytesIO()
    writer.write(out)
    return out.getvalue()


def make_pdf(edition: str, browser_path: pathlib.Path | None = None, site: pathlib.Path | None = None,
             out: pathlib.Path | None = None) -> pathlib.Path:
    """Print the built site of an edition into one tagged PDF; returns its path (by default the edition's site
    and PDF of ``EDITIONS``)."""
    from playwright.sync_api import sync_playwright

    default_site, default_out, subtitle = EDITIONS[edition]
    site, out = site or default_site, out or default_out
    if not (site / "index.html").exists():
        raise SystemExit(f"{site} is not built: run `make book` (full) or `make book-student` (student) first")
    chapters = toc_pages()
    title = TITLE + (f" — {subtitle}" if subtitle else "")
    pages = {f"/{c.html}": c.anchor for c in chapters}
    pages["/index.html"] = pages["/"] = chapters[0].anchor      # the site's root redirects to the book's first page
    browser_path = browser_path or find_browser()
    with serve(site) as server, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(browser_path), args=[
            "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"])
        context = browser.new_context(viewport={"width": 1100, "height": 1400})
        context.route("**/*", lambda r: r.continue_() if r.request.url.startswith((server, "data:", "about:"))
                      else r.abort())
        articles, sheets, styles, entries = [], [], [PRINT_STYLE], []
        reader = context.new_page()
        for chapter in chapters:
            url = f"{server}/{chapter.html}"
            reader.goto(url, wait_until="load")
            reader.evaluate(PREPARE, edition == "full")
            if reader.evaluate(TEX_LEFT):
                raise RuntimeError(f"{url}: TeX left on the page after MathJax ran")
            part = reader.evaluate(EXTRACT, [chapter.anchor, pages])
            if part is None:
                raise RuntimeError(f"{url}: the page has no article (article.bd-article) to print")
            articles.append((chapter.anchor, part["html"]))
            sheets += [s for s in part["sheets"] if s not in sheets]
            styles += [s for s in part["styles"] if s not in styles]
            entries.append((chapter.part, part["title"], chapter.anchor))
        reader.close()
        book = context.new_page()
        book.goto(f"{server}/{chapters[0].html}", wait_until="load")
        book.evaluate(PREPARE, False)
        starts = [0] * len(chapters)
        front = contents_html(TITLE, subtitle, [(*entry, 0) for entry in entries])
        book.evaluate(ASSEMBLE, [front, articles, sheets, styles, title])
        book.evaluate(LOADED)
        for attempt in range(3):   # the contents' page numbers, until a print confirms them (the second one)
            pdf = print_book(book, tagged=attempt > 0)     # the first one only finds the pages: untagged, faster
            printed = chapter_pages(pdf, chapters)
            if printed == starts:
                break
            starts = printed
            book.evaluate("(front) => { document.querySelector('.pdf-front').outerHTML = front; }",
                          contents_html(TITLE, subtitle, [(*entry, start) for entry, start in zip(entries, starts)]))
        else:
            raise RuntimeError(f"the contents' page numbers do not settle: {starts}")
        headings = [tuple(h) for h in book.evaluate(HEADINGS)]
        browser.close()
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_bytes(add_bookmarks(pdf, headings, title))
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
