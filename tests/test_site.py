"""The built site in a real headless browser (a Chromium-family browser driven by Playwright).

The browser is found by ``tests/find_browser.py`` (``MECHANISMS_BROWSER``, then the usual names and
paths on Linux and macOS, then Playwright's own Chromium); without one the test fails, saying what
it looked for.

Both editions of the site are tested: the full one in `_build/html` (built by `make book`) and
the student edition without the exercises' solutions in `_build/student/_build/html` (built by
`make book-student`); `make test` builds both first. Every page is opened over a local
http.server with every non-local request blocked, as a student without a network would see it.
Each page must have its math typeset by the site's own MathJax, every image loaded, the
controls of every animation, no failed local request and no console error. The exercise pages
of the full edition must have their solutions, those of the student edition none.
Screenshots go to `_build/screenshots/` (`_build/screenshots/student/`) for a person to look at.

Run alone with `pytest -m browser`.
"""

from __future__ import annotations

import functools
import http.server
import pathlib
import re
import threading

import pytest

from find_browser import BrowserNotFound, find_browser

ROOT = pathlib.Path(__file__).resolve().parent.parent
SITE = ROOT / "_build" / "html"
SHOTS = ROOT / "_build" / "screenshots"
# edition -> (site folder, the command that builds it, folder of its screenshots)
EDITIONS = {
    "full": (SITE, "make book", SHOTS),
    "student": (ROOT / "_build" / "student" / "_build" / "html", "make book-student", SHOTS / "student"),
}
SKIPPED_DIRS = {"_static", "_sources", "_images", "mathjax", "_sphinx_design_static"}
GENERATED = {"genindex.html", "search.html", "index.html"}  # Sphinx's own pages and the redirect
# Console messages that are not errors of the book (none are needed today; keep each with a reason).
CONSOLE_ALLOW: tuple[str, ...] = ()

pytestmark = [pytest.mark.browser, pytest.mark.needs_site("full", "student")]


def site_pages(site: pathlib.Path = SITE) -> list[str]:
    if not site.is_dir():
        return []
    pages = []
    for path in sorted(site.rglob("*.html")):
        rel = path.relative_to(site)
        if rel.parts[0] in SKIPPED_DIRS or str(rel) in GENERATED:
            continue
        pages.append(rel.as_posix())
    return pages


def edition_pages() -> list:
    """(edition, page) for every page of both editions; an edition not built has no pages here, and
    ``test_the_site_has_the_book`` fails for it."""
    return [pytest.param(edition, page, id=f"{edition}:{page}")
            for edition, (site, _, _) in EDITIONS.items() for page in site_pages(site)]


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def require_built(edition: str) -> pathlib.Path:
    site, command, _ = EDITIONS[edition]
    assert site.is_dir(), f"the {edition} edition of the site is not built ({site} is missing): run `{command}` first"
    return site


@pytest.fixture(scope="module")
def servers():
    """A local server per edition, started when a test first asks for it: ``servers(edition)`` → URL."""
    running: dict[str, tuple[http.server.ThreadingHTTPServer, str]] = {}

    def serve(edition: str) -> str:
        if edition not in running:
            handler = functools.partial(QuietHandler, directory=str(require_built(edition)))
            httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
            threading.Thread(target=httpd.serve_forever, daemon=True).start()
            running[edition] = (httpd, f"http://127.0.0.1:{httpd.server_address[1]}")
        return running[edition][1]

    yield serve
    for httpd, _ in running.values():
        httpd.shutdown()


@pytest.fixture(scope="module")
def server(servers):
    """The full edition's server."""
    return servers("full")


@pytest.fixture(scope="module")
def browser():
    try:
        from playwright import sync_api as playwright
    except ImportError:
        pytest.fail("Playwright is missing: the site test drives a real browser through it; install the test "
                    "extra (`.venv/bin/pip install -e '.[test]'`, which `make test` does)", pytrace=False)
    try:
        chromium = find_browser()
    except BrowserNotFound as missing:
        pytest.fail(str(missing), pytrace=False)
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(chromium), args=[
            "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync"])
        yield b
        b.close()


def open_page(browser, server: str, page_path: str):
    """Open a page with non-local requests blocked; return (page, problems found while loading)."""
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    page = context.new_page()
    problems: list[str] = []

    def route(r):
        if r.request.url.startswith(server) or r.request.url.startswith("data:"):
            r.continue_()
        else:
            problems.append(f"non-local request blocked: {r.request.url}")
            r.abort()

    page.route("**/*", route)
    page.on("console", lambda m: m.type == "error" and not any(a in m.text for a in CONSOLE_ALLOW)
            and problems.append(f"console error: {m.text}"))
    page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    page.on("response", lambda r: r.status >= 400 and problems.append(f"HTTP {r.status}: {r.url}"))
    page.goto(f"{server}/{page_path}", wait_until="load")
    return context, page, problems


def settle(page) -> None:
    """Wait for the page to finish loading what it asks for.

    Playwright's "networkidle" (no request for 0.5 s) is the usual signal, but on a loaded machine one
    stalled connection to the local server can keep it from coming (a CI run timed out on one page
    whose every file was there). So it is waited for a while and then not required: what the tests
    need is checked directly, every image complete and the math typeset, each with its own time limit
    and a message saying what did not arrive.
    """
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    try:
        page.wait_for_load_state("networkidle", timeout=15_000)
    except PlaywrightTimeout:
        pass
    try:
        page.wait_for_function("[...document.images].every(i => i.complete)", timeout=30_000)
    except PlaywrightTimeout:
        pass  # the test's own check names the images that did not load
    if page.evaluate("Boolean(window.MathJax && MathJax.startup && MathJax.startup.promise)"):
        page.evaluate("MathJax.startup.promise")


@pytest.mark.parametrize("edition", list(EDITIONS))
def test_the_site_has_the_book(edition):
    pages = site_pages(require_built(edition))
    for expected in ("book/preface.html", "book/01-links.html", "book/02-constraints.html",
                     "exercises/01-links.html", "book/appendix/errata.html"):
        assert expected in pages, f"{expected} is missing from the {edition} edition"


def exercise_pages(edition: str) -> list[str]:
    return [p for p in site_pages(require_built(edition)) if p.startswith("exercises/")]


def test_the_full_edition_has_the_solutions():
    site = require_built("full")
    for page in exercise_pages("full"):
        html = (site / page).read_text(encoding="utf8")
        # sphinx-exercise writes each solution as <div class="solution dropdown admonition" ...>
        assert html.count('class="exercise admonition') >= 6, f"{page}: fewer than 6 exercises"
        assert html.count('class="solution dropdown admonition') >= html.count('class="exercise admonition'), \
            f"{page}: an exercise without its solution (in a dropdown)"


@pytest.mark.parametrize("edition", list(EDITIONS))
def test_exercises_are_numbered_by_chapter(edition):
    # expected: on the page exercises/NN-…, the exercises NN.1, NN.2 … in order (_ext/exercise_numbers.py)
    site = require_built(edition)
    for page in exercise_pages(edition):
        chapter = int(re.match(r"exercises/(\d+)-", page).group(1))
        html = (site / page).read_text(encoding="utf8")
        titles = re.findall(r'<p class="admonition-title">\s*(?:<span[^>]*>)?\s*Exercise ([0-9.]+)', html)
        assert titles == [f"{chapter}.{k}" for k in range(1, len(titles) + 1)], f"{page}: {titles}"
        assert len(titles) >= 6, f"{page}: the exercise titles were not found"


def test_the_student_edition_has_no_solutions():
    site = require_built("student")
    assert exercise_pages("student") == exercise_pages("full"), "the two editions have different exercise pages"
    for page in exercise_pages("student"):
        html = (site / page).read_text(encoding="utf8")
        assert html.count('class="exercise admonition') >= 6, f"{page}: the exercises are missing"
        assert 'class="solution' not in html and "solution-content" not in html, f"{page}: a solution is shown"
        # the code of a worked solution is gone too: only code cells outside the solutions remain
        full = (require_built("full") / page).read_text(encoding="utf8")
        assert html.count('class="cell docutils container') < full.count('class="cell docutils container'), \
            f"{page}: the solutions' code cells are still on the page"
    # the sources (which hold the solutions) can neither be downloaded nor found in the site
    assert not (site / "_sources").exists(), "the student edition holds the sources (_sources) with the solutions"
    for page in site_pages(site):
        html = (site / page).read_text(encoding="utf8")
        assert "_sources/" not in html and "btn-download-source-button" not in html, \
            f"{page} offers its source for download"


@pytest.mark.parametrize(("edition", "page_path"), edition_pages())
def test_page_renders(browser, servers, edition, page_path):
    context, page, problems = open_page(browser, servers(edition), page_path)
    try:
        settle(page)
        has_math = page.evaluate("document.querySelectorAll('.math, span.math, div.math').length") > 0
        if has_math:
            loaded = page.evaluate("Boolean(window.MathJax && MathJax.startup && MathJax.startup.promise)")
            assert loaded, "MathJax did not load from the site itself:\n" + "\n".join(problems)
            page.evaluate("MathJax.startup.promise")
            assert page.locator("mjx-container").count() > 0, "math is not typeset (no mjx-container)"
            assert page.locator("mjx-merror").count() == 0, "MathJax reports a formula error"
        settle(page)
        broken = page.evaluate("[...document.images].filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.src)")
        assert broken == [], f"images that did not load: {broken}"
        for animation in page.locator("div.animation").all():
            assert animation.locator(".anim-buttons button").count() >= 5, "animation without its buttons"
            assert animation.locator("input.anim-slider").count() == 1, "animation without its slider"
        shots = EDITIONS[edition][2]
        shots.mkdir(parents=True, exist_ok=True)
        name = page_path.replace("/", "_")
        page.screenshot(path=str(shots / f"{name}.png"), full_page=False)
        assert page.evaluate(NO_OVERFLOW), "the page scrolls sideways on a desktop screen"
        page.set_viewport_size(PHONE)
        page.wait_for_timeout(200)
        page.screenshot(path=str(shots / f"{name}.phone.png"), full_page=False)
        assert page.evaluate(NO_OVERFLOW), f"the page scrolls sideways on a phone ({PHONE['width']} px)"
        assert problems == [], "\n".join(problems)
    finally:
        context.close()


# The text column must not push the page sideways: wide tables, code and equations scroll in their
# own boxes (the theme's overflow rules), the page itself never does.
NO_OVERFLOW = "document.documentElement.scrollWidth <= window.innerWidth + 1"
PHONE = {"width": 390, "height": 844}


# A code block or a display equation wider than its box makes the reader scroll inside it (issue 19,
# item 7): each must fit at a desktop and at a phone width. scrollWidth counts the content that does
# not fit, whether the box scrolls or not.
BOX_WIDTHS = {"desktop": 1280, "phone": 375}
# Code blocks wrap, so they never need more than their box. A display equation fits its box on a desktop;
# on a phone a long one may scroll inside its own box (book.css), but the box itself stays in the page.
WIDER_THAN_BOX = """(phone) => [...document.querySelectorAll('div.highlight pre, mjx-container[display]')]
    .filter(e => e.offsetParent !== null)
    .filter(e => (phone && e.tagName === 'MJX-CONTAINER')
                 ? e.getBoundingClientRect().right > document.documentElement.clientWidth + 1
                 : e.scrollWidth > e.clientWidth + 1)
    .map(e => `${e.tagName.toLowerCase()} ${e.scrollWidth} px in a box of ${e.clientWidth} px: `
              + (e.textContent || '').trim().replace(/\\s+/g, ' ').slice(0, 60))"""


@pytest.mark.parametrize("page_path", site_pages())
def test_code_and_equations_fit_their_boxes(browser, servers, page_path):
    context, page, _ = open_page(browser, servers("full"), page_path)
    try:
        settle(page)
        offenders = []
        for name, width in BOX_WIDTHS.items():
            page.set_viewport_size({"width": width, "height": 900})
            page.wait_for_timeout(200)
            offenders += [f"{name} ({width} px): {o}" for o in page.evaluate(WIDER_THAN_BOX, name == "phone")]
        assert offenders == [], f"{page_path}: wider than their box:\n" + "\n".join(offenders)
    finally:
        context.close()


@pytest.mark.parametrize("edition", list(EDITIONS))
def test_internal_links_resolve(edition):
    """Every link from a page to another file of the site points to a file that exists (no 404)."""
    site = require_built(edition)
    missing = []
    for page in site_pages(site):
        html = (site / page).read_text(encoding="utf8")
        for target in re.findall(r'(?:href|src)="([^"#?]+)[^"]*"', html):
            if re.match(r"^[a-z]+:", target) or target.startswith("//"):
                continue  # an external address or a data: URI: blocked offline, checked in test_page_renders
            resolved = (site / page).parent / target
            if not resolved.exists():
                missing.append(f"{page} → {target}")
    assert missing == [], "links to files that do not exist:\n" + "\n".join(sorted(set(missing))[:30])
