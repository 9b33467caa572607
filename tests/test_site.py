"""The built site in a real headless browser (Debian's Chromium driven by Playwright).

Every page of `_build/html` (built by `make book`, which `make test` runs first) is opened over
a local http.server with every non-local request blocked, as a student without a network would
see it. Each page must have its math typeset by the site's own MathJax, every image loaded,
the controls of every animation, no failed local request and no console error.
Screenshots go to `_build/screenshots/` for a person to look at.

Run alone with `pytest -m browser`.
"""

from __future__ import annotations

import functools
import http.server
import pathlib
import threading

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
SITE = ROOT / "_build" / "html"
SHOTS = ROOT / "_build" / "screenshots"
CHROMIUM = pathlib.Path("/usr/bin/chromium")
SKIPPED_DIRS = {"_static", "_sources", "_images", "mathjax", "_sphinx_design_static"}
GENERATED = {"genindex.html", "search.html", "index.html"}  # Sphinx's own pages and the redirect
# Console messages that are not errors of the book (none are needed today; keep each with a reason).
CONSOLE_ALLOW: tuple[str, ...] = ()

pytestmark = pytest.mark.browser


def site_pages() -> list[str]:
    if not SITE.is_dir():
        return []
    pages = []
    for path in sorted(SITE.rglob("*.html")):
        rel = path.relative_to(SITE)
        if rel.parts[0] in SKIPPED_DIRS or str(rel) in GENERATED:
            continue
        pages.append(rel.as_posix())
    return pages


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


@pytest.fixture(scope="module")
def server():
    assert SITE.is_dir(), "the site is not built: run `make book` first"
    handler = functools.partial(QuietHandler, directory=str(SITE))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()


@pytest.fixture(scope="module")
def browser():
    playwright = pytest.importorskip("playwright.sync_api")
    assert CHROMIUM.exists(), "Chromium is missing: `apt-get install chromium` (Debian package)"
    with playwright.sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(CHROMIUM), args=[
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


def test_the_site_has_the_book(server):
    pages = site_pages()
    for expected in ("book/preface.html", "book/01-links.html", "book/02-constraints.html",
                     "exercises/01-links.html", "book/appendix/errata.html"):
        assert expected in pages


@pytest.mark.parametrize("page_path", site_pages())
def test_page_renders(browser, server, page_path):
    context, page, problems = open_page(browser, server, page_path)
    try:
        page.wait_for_load_state("networkidle")
        has_math = page.evaluate("document.querySelectorAll('.math, span.math, div.math').length") > 0
        if has_math:
            loaded = page.evaluate("Boolean(window.MathJax && MathJax.startup && MathJax.startup.promise)")
            assert loaded, "MathJax did not load from the site itself:\n" + "\n".join(problems)
            page.evaluate("MathJax.startup.promise")
            assert page.locator("mjx-container").count() > 0, "math is not typeset (no mjx-container)"
            assert page.locator("mjx-merror").count() == 0, "MathJax reports a formula error"
        page.wait_for_load_state("networkidle")
        broken = page.evaluate("[...document.images].filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.src)")
        assert broken == [], f"images that did not load: {broken}"
        for animation in page.locator("div.animation").all():
            assert animation.locator(".anim-buttons button").count() >= 5, "animation without its buttons"
            assert animation.locator("input.anim-slider").count() == 1, "animation without its slider"
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / (page_path.replace("/", "_") + ".png")), full_page=False)
        assert problems == [], "\n".join(problems)
    finally:
        context.close()
