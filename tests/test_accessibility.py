"""A site every student can use (issue 32): WCAG 2.1 A and AA on every page, explorers by keyboard and
screen reader, reduced motion, phones.

(a) **axe-core** on every page of both editions (``make book``, ``make book-student``), in Chromium, with the
    WCAG 2.0 and 2.1 A and AA rules (tags ``wcag2a``, ``wcag2aa``, ``wcag21a``, ``wcag21aa``): no violation.
    axe runs once per page: the full edition's pages in the light mode at a desktop's width, the student
    edition's in the dark mode at a phone's width, and the full edition's exercise pages (the solutions, which
    the student edition has not) in the dark mode on a phone too. axe-core comes from its npm package without
    npm: the pinned tarball is downloaded from the npm registry once, checked against the registry's published
    sha512 ``integrity`` (pinned below), kept in ``_build/axe-core/``, and its ``axe.min.js`` put into each page.
    No rule is turned off: what the theme does wrong is fixed in ``_ext/accessible_site.py``, ``_templates/``
    and ``_static/``. On the same pages: headings nest in order, every table has header cells, every typeset
    equation keeps MathJax's assistive MathML.
(b) **the explorers** (``_static/mechanisms-player.js``): one per chapter is driven by the keyboard alone
    (``page.keyboard``: Tab from the page's last stop before the player to its play button and crank-angle
    slider, arrow keys, Home/End, Space to play and pause); the sliders are named with their unit; the live
    region (``aria-live="polite"``) then says the values of the frame the scene's data gives for that crank
    angle, and says nothing new while the player plays; the focus is drawn. With ``prefers-reduced-motion:
    reduce`` nothing moves by itself and the still and sliders remain.
(c) **phones** (390 × 844 px): on every page with an explorer, its controls are touch targets of at least
    44 × 44 px and its text and the drawing's labels at least 12 px; the mechanism's links keep ≥ 3:1 against
    the player's background in the light and the dark mode. (That no page scrolls sideways at this width is
    ``tests/test_site.py::test_page_renders``.) Screenshots of the first explorer of each page on a phone go to
    ``_build/screenshots/accessibility/``.

Speed: the pages go through two tabs in separate renderer processes of one browser, reused from page to page;
axe (the slow part, 2–10 s of CPU on a long chapter) runs in one while the next page loads in the other, so
both cores work. Run alone with ``pytest -m browser tests/test_accessibility.py``; it needs the network once,
for axe-core.
"""

from __future__ import annotations

import base64
import hashlib
import io
import json
import pathlib
import re
import tarfile
import urllib.request

import pytest

from test_colours import contrast
from test_site import EDITIONS, ROOT, browser, require_built, servers, site_pages  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.needs_site("full", "student")]

AXE_VERSION = "4.14.1"
# the registry's dist.integrity of axe-core 4.14.1 (https://registry.npmjs.org/axe-core/4.14.1)
AXE_INTEGRITY = "sha512-FHfa+lmNjQZfJz1q8wKqIDwC6DExcHt/pkjNQb09a3NPjCKg2rhu5qb2S4r76ASyFNNtuFooJpZe37OgudVGtQ=="
AXE_URL = f"https://registry.npmjs.org/axe-core/-/axe-core-{AXE_VERSION}.tgz"
AXE_CACHE = ROOT / "_build" / "axe-core" / f"axe-core-{AXE_VERSION}.tgz"
WCAG_TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
SHOTS = ROOT / "_build" / "screenshots" / "accessibility"
PHONE = {"width": 390, "height": 844}
DESKTOP = {"width": 1280, "height": 900}
TOUCH = 44          # px: the smallest touch target (WCAG 2.5.5's size, the platforms' guidelines)
LEGIBLE = 12        # px: the smallest text of an explorer on the screen
TIMEOUT = 180_000   # ms: the most one step of a page (loading it, axe on it) may take on a busy machine


def integrity(data: bytes) -> str:
    """The npm registry's Subresource-Integrity string of a tarball."""
    return "sha512-" + base64.b64encode(hashlib.sha512(data).digest()).decode("ascii")


def axe_tarball() -> bytes:
    """The pinned axe-core tarball: from the cache if it is there and intact, else from the npm registry."""
    if AXE_CACHE.is_file():
        data = AXE_CACHE.read_bytes()
        if integrity(data) == AXE_INTEGRITY:
            return data
    try:
        with urllib.request.urlopen(AXE_URL, timeout=60) as response:
            data = response.read()
    except OSError as error:
        pytest.fail(f"axe-core {AXE_VERSION} is not in {AXE_CACHE.relative_to(ROOT)} and could not be downloaded "
                    f"from {AXE_URL}: {error}", pytrace=False)
    if integrity(data) != AXE_INTEGRITY:
        pytest.fail(f"{AXE_URL} does not match the registry's published integrity {AXE_INTEGRITY} "
                    f"(got {integrity(data)}): refusing to run it", pytrace=False)
    AXE_CACHE.parent.mkdir(parents=True, exist_ok=True)
    AXE_CACHE.write_bytes(data)
    return data


@pytest.fixture(scope="module")
def axe_source() -> str:
    with tarfile.open(fileobj=io.BytesIO(axe_tarball()), mode="r:gz") as archive:
        member = archive.extractfile("package/axe.min.js")
        assert member is not None, "the axe-core tarball has no package/axe.min.js"
        return member.read().decode("utf8")


def test_the_integrity_check_refuses_other_bytes():
    # expected: one changed byte changes the sha512, so a tampered or truncated download is refused
    data = axe_tarball()
    assert integrity(data) == AXE_INTEGRITY
    assert integrity(data[:-1] + bytes([data[-1] ^ 1])) != AXE_INTEGRITY


# axe's WCAG 2.1 A/AA rules over the whole page, started without waiting for its end (the sweep below runs it in
# one page while it loads the next in another)
AXE_START = """tags => { window.__axeViolations = axe.run(document,
        {runOnly: {type: 'tag', values: tags}, resultTypes: ['violations']})
    .then(r => r.violations.map(v => ({id: v.id, impact: v.impact, help: v.help,
        nodes: v.nodes.map(n => n.target.join(' ') + ': ' + n.failureSummary.replace(/\\s+/g, ' ').slice(0, 240))})));
}"""


def set_mode(page, mode: str) -> None:
    """The theme's light or dark mode, as its colour-mode button sets it (pydata-sphinx-theme: data-mode and
    data-theme on <html>)."""
    page.evaluate("m => { document.documentElement.dataset.mode = m; document.documentElement.dataset.theme = m; }",
                  mode)
    page.evaluate("new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")


# the page's own structure: headings in order, tables with headers, equations with their assistive MathML
STRUCTURE = """() => {
    const main = document.querySelector('main article') || document.querySelector('main');
    const levels = [...main.querySelectorAll('h1, h2, h3, h4, h5, h6')].filter(h => h.offsetParent !== null)
        .map(h => [parseInt(h.tagName[1], 10), h.textContent.trim().slice(0, 50)]);
    const jumps = [];
    levels.forEach(([level, text], i) => {
        const before = i ? levels[i - 1][0] : 0;
        if (level > before + 1) jumps.push(`h${level} "${text}" after h${before}`);
    });
    const tables = [...main.querySelectorAll('table')].filter(t => !t.querySelector('th'))
        .map(t => t.textContent.trim().replace(/\\s+/g, ' ').slice(0, 60));
    const math = [...document.querySelectorAll('mjx-container')]
        .filter(m => !m.querySelector('mjx-assistive-mml > math')).map(m => m.textContent.slice(0, 40));
    return {first: levels.length ? levels[0][0] : null, jumps, tables, math};
}"""


def loaded(page) -> None:
    """The page as a reader meets it: loaded, its images complete, its math typeset, its players built. (``test_site.
    settle`` also waits up to 15 s for the network to be idle, which on a loaded machine often never comes; nothing
    read here needs it.)"""
    page.wait_for_function("[...document.images].every(i => i.complete)", timeout=TIMEOUT)
    if page.evaluate("Boolean(window.MathJax && MathJax.startup && MathJax.startup.promise)"):
        page.evaluate("MathJax.startup.promise")
    ready(page)


def ready(page) -> None:
    page.wait_for_function("[...document.querySelectorAll('div.mech-player')].every(p => p.mechPlayer)",
                           timeout=TIMEOUT)


# --- the sweep: every page of both editions, axe once per page --------------------------------------------------

# What each page is checked in. Every page of the full edition in the light mode at a desktop's width, every page
# of the student edition in the dark mode at a phone's width (its pages are the full edition's without the
# solutions, so between them every page's text is checked in both modes and at both widths), and the full
# edition's exercise pages, the only ones whose text the student edition lacks (the solutions), also dark on a
# phone.
def sweep_jobs() -> list[tuple[str, str, str]]:
    jobs = [(edition, page, mode) for edition, mode in (("full", "light"), ("student", "dark"))
            for page in site_pages(EDITIONS[edition][0])]
    return jobs + [("full", page, "dark") for page in site_pages(EDITIONS["full"][0]) if page.startswith("exercises/")]


def job_id(job: tuple[str, str, str]) -> str:
    edition, page, mode = job
    return f"{edition}:{page}:{mode}"


SLOTS = 2           # pages checked at once: axe runs in one while the next page loads in the other (2 cores)


class Slot:
    """A browser context with one tab, reused for page after page (the axe script is put into every page it
    opens before the page's own scripts run)."""

    def __init__(self, browser, axe: str, server_of):
        self.context = browser.new_context(viewport=DESKTOP)
        self.context.add_init_script(script=axe)
        self.context.set_default_timeout(TIMEOUT)        # a long chapter on a busy machine loads slowly
        self.context.set_default_navigation_timeout(TIMEOUT)
        self.page = self.context.new_page()
        self.server_of = server_of
        self.errors: list[str] = []
        self.page.on("pageerror", lambda e: self.errors.append(f"page error: {e}"))
        self.job: tuple[str, str, str] | None = None
        self.found: dict = {}

    def start(self, job: tuple[str, str, str]) -> None:
        """Open the page of ``job`` at its width, make it ready in its mode, read what needs no axe, start axe."""
        edition, page_path, mode = self.job = job
        self.errors.clear()
        page = self.page
        page.set_viewport_size(DESKTOP if mode == "light" else PHONE)
        page.goto(f"{self.server_of(edition)}/{page_path}", wait_until="load")
        loaded(page)
        set_mode(page, mode)
        self.found = {"structure": page.evaluate(STRUCTURE), "lines": page.evaluate(LINES)}
        if mode == "dark":
            self.found["sizes"] = page.evaluate(SIZES)
            if page.locator("div.mech-player").count():
                SHOTS.mkdir(parents=True, exist_ok=True)
                first = page.locator("div.mech-player").first
                first.scroll_into_view_if_needed()
                first.screenshot(path=str(SHOTS / f"{edition}_{page_path.replace('/', '_')}.phone.{mode}.png"))
        page.evaluate(AXE_START, WCAG_TAGS)

    def finish(self) -> tuple[tuple[str, str, str], dict]:
        """Wait for axe on the page started last; its job and what was found."""
        found = dict(self.found, violations=self.page.evaluate("window.__axeViolations"), errors=list(self.errors))
        job, self.job = self.job, None
        assert job is not None
        return job, found


@pytest.fixture(scope="module")
def sweep(browser, servers, axe_source):
    """``{job: what was found}`` for every job of :func:`sweep_jobs`: axe's violations, the page's structure, the
    contrast of the mechanisms' lines and, on a phone, the sizes of the explorers' controls and text. The pages
    go through :data:`SLOTS` tabs in separate processes, so that axe (the slow part) runs in one while the next
    page loads in another; a page that fails is reported by its own test."""
    results: dict[tuple[str, str, str], dict] = {}
    jobs = sweep_jobs()
    slots = [Slot(browser, axe_source, servers) for _ in range(SLOTS)]

    def start(slot: Slot) -> None:
        while jobs:
            job = jobs.pop(0)
            try:
                slot.start(job)
                return
            except Exception as error:          # reported by the page's own test, the others go on
                results[job] = {"failed": f"{type(error).__name__}: {error}"}
                slot.job = None

    try:
        for slot in slots:
            start(slot)
        while any(slot.job for slot in slots):
            for slot in slots:
                if slot.job is None:
                    continue
                try:
                    job, found = slot.finish()
                    results[job] = found
                except Exception as error:
                    results[slot.job] = {"failed": f"{type(error).__name__}: {error}"}
                    slot.job = None
                start(slot)
        yield results
    finally:
        for slot in slots:
            slot.context.close()


@pytest.mark.parametrize("job", sweep_jobs(), ids=job_id)
def test_every_page_passes_axe_and_has_structure(sweep, job):
    edition, page_path, mode = job
    found = sweep[job]
    assert "failed" not in found, f"{job_id(job)}: the page could not be checked: {found.get('failed')}"
    report = [f"{v['id']} ({v['impact']}, {len(v['nodes'])}×): {v['help']}\n    " + "\n    ".join(v["nodes"][:5])
              for v in found["violations"]]
    width = (DESKTOP if mode == "light" else PHONE)["width"]
    assert report == [], (f"{edition}:{page_path} ({mode}, {width} px): axe-core {AXE_VERSION} finds WCAG 2.1 "
                          "A/AA violations:\n" + "\n".join(report))
    structure = found["structure"]
    assert structure["first"] == 1, f"{page_path}: the page does not start with its h1: {structure}"
    assert structure["jumps"] == [], f"{page_path}: headings skip a level: {structure['jumps']}"
    assert structure["tables"] == [], f"{page_path}: tables without header cells: {structure['tables']}"
    assert structure["math"] == [], f"{page_path}: equations without assistive MathML: {structure['math'][:5]}"
    assert found["errors"] == [], "\n".join(found["errors"])


# --- the explorers ---------------------------------------------------------------------------------------------

def chapter_explorer_pages() -> list[str]:
    """The chapters (book/NN-…) of the full edition with a player: one explorer of each is driven."""
    site = EDITIONS["full"][0]
    return [p for p in site_pages(site) if re.match(r"book/\d\d-", p)
            and 'class="mech-player' in (site / p).read_text(encoding="utf8")]


def test_the_chapters_have_explorers():
    require_built("full")
    assert len(chapter_explorer_pages()) >= 6, chapter_explorer_pages()


def scene_of(page, index: int) -> dict:
    """The scene data of the page's player ``index``, as the package wrote it into the page."""
    return json.loads(page.locator("div.mech-player").nth(index).locator("script.mech-scene").text_content())


def degrees_printed(value: float) -> str:
    value %= 360.0
    return f"{value:.0f}" if value == int(value) else f"{value:.1f}"


# the last element before the player that Tab stops at (a link, a button, an equation MathJax made focusable …)
FOCUS_BEFORE = """s => {
    const player = document.querySelector(s);
    const stops = [...document.querySelectorAll('a[href], button, input, select, textarea, summary, [tabindex]')]
        .filter(e => e.tabIndex >= 0 && !e.disabled && e.checkVisibility({visibilityProperty: true})
                && (player.compareDocumentPosition(e) & Node.DOCUMENT_POSITION_PRECEDING));
    const last = stops[stops.length - 1];
    last.focus();
    return document.activeElement === last;
}"""


def tab_to(page, selector: str, limit: int = 3) -> None:
    """Press Tab until the element ``selector`` (the first that matches) has the focus: from the page's last stop
    before the player (Tab from the top of a chapter would pass hundreds of links and equations first)."""
    for _ in range(limit):
        page.keyboard.press("Tab")
        if page.evaluate("s => document.activeElement === document.querySelector(s)", selector):
            return
    pytest.fail(f"{limit} presses of Tab from the stop before the player never reached {selector}")


def live_text(page, root: str) -> str:
    return page.eval_on_selector(root + ' [aria-live="polite"]', "e => e.textContent")


def wait_live_change(page, root: str, before: str) -> str:
    page.wait_for_function("([s, t]) => document.querySelector(s + ' [aria-live=\"polite\"]').textContent !== t",
                           arg=[root, before], timeout=30_000)
    return live_text(page, root)


@pytest.fixture(scope="module")
def explorer_tab(browser, servers):
    """One tab of the full edition reused by the explorers' tests (a new page is opened in it for each)."""
    context = browser.new_context(viewport=DESKTOP)
    context.set_default_timeout(TIMEOUT)
    context.set_default_navigation_timeout(TIMEOUT)
    page = context.new_page()
    problems: list[str] = []
    page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    server = servers("full")

    def open_chapter(page_path: str):
        problems.clear()
        page.goto(f"{server}/{page_path}", wait_until="load")
        ready(page)
        return page, problems

    yield open_chapter
    context.close()


@pytest.mark.parametrize("page_path", chapter_explorer_pages())
def test_an_explorer_by_keyboard_alone(explorer_tab, page_path):
    page, problems = explorer_tab(page_path)
    # the explorer driven is the page's first player with a parameter, else its first player
    kinds = page.evaluate("[...document.querySelectorAll('div.mech-player')].map("
                          "p => p.querySelectorAll('input.mech-parameter').length)")
    index = next((i for i, n in enumerate(kinds) if n), 0)
    page.evaluate("i => document.querySelectorAll('div.mech-player')[i].setAttribute('data-driven', '')", index)
    css = "div.mech-player[data-driven]"
    data = scene_of(page, index)
    names = page.eval_on_selector_all(css + " input[type=range]", "rs => rs.map(r => r.getAttribute('aria-label'))")
    assert "degrees" in names[0], f"the crank slider's name has no unit: {names[0]!r}"
    for spec, name in zip(data["parameters"], names[1:]):
        assert spec["unit"] in name, f"the slider of {spec['name']} is named {name!r}, without its unit"

    assert page.evaluate(FOCUS_BEFORE, css), "nothing before the player takes the focus"
    tab_to(page, css + " button.mech-play")                    # the first stop of the player is its play button
    page.keyboard.press("Tab")                                 # then the crank's slider
    assert page.evaluate("s => document.activeElement === document.querySelector(s + ' input.mech-angle')", css)
    outline = page.evaluate("() => { const s = getComputedStyle(document.activeElement); "
                            "return [s.outlineStyle, parseFloat(s.outlineWidth)]; }")
    assert outline[0] != "none" and outline[1] >= 2, f"the focused slider has no visible focus: {outline}"
    before = live_text(page, css)
    frame = page.evaluate("s => document.querySelector(s).mechPlayer.frame", css)
    member = page.evaluate("s => document.querySelector(s).mechPlayer.member", css)
    valid = data["members"][member]["valid"]
    page.keyboard.press("ArrowRight")
    said = wait_live_change(page, css, before)
    # expected: the scene's own crank angle of the frame after (or the nearest where the member assembles)
    n = len(data["phi"])
    target = next(k % n for k in range(frame + 1, frame + 1 + n) if valid[k % n] == "1")
    assert f"= {degrees_printed(data['phi'][target])}°" in said, \
        f"after ArrowRight the live region says {said!r}, not φ = {degrees_printed(data['phi'][target])}°"
    readout = page.eval_on_selector_all(css + " .mech-readout .mech-item", "items => items.map(i => i.textContent)")
    assert all(item in said for item in readout), f"the live region {said!r} is not the readout {readout}"
    valuetext = page.evaluate("() => document.activeElement.getAttribute('aria-valuetext')")
    assert valuetext == f"{degrees_printed(data['phi'][target])} degrees", valuetext

    page.keyboard.press("End")                                 # the last frame of the turn (or nearest)
    said = wait_live_change(page, css, said)
    assert "φ" in said or data["angle"] in said

    if data["parameters"]:
        page.keyboard.press("Tab")                             # the first parameter's slider
        spec = data["parameters"][0]
        assert page.evaluate("() => document.activeElement.dataset.name") == spec["name"]
        start = int(page.evaluate("() => document.activeElement.value"))
        last = len(spec["values"]) - 1
        key, end = ("End", last) if start != last else ("Home", 0)
        page.keyboard.press(key)
        said = wait_live_change(page, css, said)
        # expected: the scene's value at that end of the range, printed with the scene's digits and unit
        value = f"{spec['values'][end]:.{spec['digits']}f}".replace("-", "\u2212")
        shown = page.evaluate("() => document.activeElement.getAttribute('aria-valuetext')")
        assert shown == f"{value} {spec['unit']}".strip(), (shown, value)
        assert f"= {value}" in page.inner_text(css + f' output[data-name="{spec["name"]}"]')
        page.keyboard.press("Home")                            # back where it was, by arrow keys
        for _ in range(start):
            page.keyboard.press("ArrowRight")
        assert int(page.evaluate("() => document.activeElement.value")) == start
        page.keyboard.press("Shift+Tab")                       # back to the crank slider
        said = live_text(page, css)

    # Space on the crank slider plays, Space again pauses; nothing new is said while it plays
    page.keyboard.press("Space")
    page.wait_for_function("s => document.querySelector(s).mechPlayer.timer !== null", arg=css, timeout=30_000)
    playing = live_text(page, css)
    page.wait_for_function("([s, f]) => document.querySelector(s).mechPlayer.frame !== f", arg=[css, frame],
                           timeout=30_000)
    page.wait_for_timeout(600)                                 # longer than the player waits before it speaks
    assert live_text(page, css) == playing, "the live region changed while the explorer played"
    page.keyboard.press("Space")
    assert page.evaluate("s => document.querySelector(s).mechPlayer.timer", css) is None, "Space did not pause"
    said = wait_live_change(page, css, playing)
    stopped = page.evaluate("s => document.querySelector(s).mechPlayer.frame", css)
    assert f"= {degrees_printed(data['phi'][stopped])}°" in said, (said, stopped)
    # the play button is reached by the keyboard and Space works it
    page.keyboard.press("Shift+Tab")
    assert page.evaluate("() => document.activeElement.classList.contains('mech-play')")
    page.keyboard.press("Space")
    assert "pause" in page.inner_text(css + " button.mech-play")
    page.keyboard.press("Space")
    assert "play" in page.inner_text(css + " button.mech-play")
    assert problems == [], "\n".join(problems)


def test_reduced_motion_stops_the_motion(browser, servers):
    page_path = chapter_explorer_pages()[0]
    for motion in ("no-preference", "reduce"):
        context = browser.new_context(viewport=DESKTOP, reduced_motion=motion)
        context.set_default_navigation_timeout(TIMEOUT)
        try:
            page = context.new_page()
            page.goto(f"{servers('full')}/{page_path}", wait_until="load")
            ready(page)
            css = "div.mech-player"
            page.locator(css + " input.mech-angle").first.focus()
            frame = page.evaluate("s => document.querySelector(s).mechPlayer.frame", css)
            page.keyboard.press("Space")
            if motion == "no-preference":                 # the same keys animate without the preference
                page.wait_for_function("([s, f]) => document.querySelector(s).mechPlayer.frame !== f",
                                       arg=[css, frame], timeout=30_000)
                continue
            page.wait_for_timeout(500)                    # six frames' time, were it playing
            assert page.evaluate("s => document.querySelector(s).mechPlayer.timer", css) is None, "it plays"
            assert page.evaluate("s => document.querySelector(s).mechPlayer.frame", css) == frame, \
                "the explorer moved by itself with prefers-reduced-motion: reduce"
            assert not page.locator(css + " button.mech-play").first.is_visible(), "a play button is offered"
            assert page.locator(css + " svg.mech-still").first.is_visible(), "the still image is gone"
            page.keyboard.press("ArrowRight")                 # the sliders remain
            assert page.evaluate("s => document.querySelector(s).mechPlayer.frame", css) != frame
            assert "reduced motion" in page.inner_text(css + " .mech-notes >> nth=0")
        finally:
            context.close()


# --- phones and contrast (read by the sweep above) -------------------------------------------------------------

# every control of every explorer: its touch target (the label around a checkbox) and the sizes of its text
SIZES = """() => [...document.querySelectorAll('div.mech-player')].flatMap((p, n) => {
    const box = e => e.getBoundingClientRect();
    const targets = [...p.querySelectorAll('button:not([hidden]), input')].map(c => {
        const t = c.type === 'checkbox' ? c.closest('label') : c, b = box(t);
        return {n, what: c.className || c.type, width: b.width, height: b.height};
    });
    const texts = [...p.querySelectorAll('.mech-controls *, .mech-readout *, .mech-notes *')]
        .filter(e => [...e.childNodes].some(t => t.nodeType === 3 && t.textContent.trim()))
        .map(e => ({n, what: e.tagName.toLowerCase() + ' ' + e.textContent.trim().slice(0, 20),
                    size: parseFloat(getComputedStyle(e).fontSize)}));
    const labels = [...p.querySelectorAll('svg text')].filter(t => getComputedStyle(t).display !== 'none')
        .map(t => ({n, what: 'drawing label ' + t.textContent,
                    size: parseFloat(getComputedStyle(t).fontSize) * t.getScreenCTM().a}));
    return [{targets, texts: texts.concat(labels)}];
})"""


@pytest.mark.parametrize("page_path", chapter_explorer_pages())
def test_explorers_on_a_phone(sweep, page_path):
    # read at 390 px in the student edition (the same players as the full edition's), in the dark mode
    found = sweep[("student", page_path, "dark")]
    assert "failed" not in found, found.get("failed")
    small, tiny = [], []
    for player in found["sizes"]:
        small += [f"player {t['n']}: {t['what']} {t['width']:.0f} × {t['height']:.0f} px"
                  for t in player["targets"] if t["width"] < TOUCH - 0.5 or t["height"] < TOUCH - 0.5]
        tiny += [f"player {t['n']}: {t['what']!r} {t['size']:.1f} px" for t in player["texts"]
                 if t["size"] < LEGIBLE - 0.05]
    assert found["sizes"], f"{page_path}: no player found on the phone"
    assert small == [], f"{page_path}: touch targets smaller than {TOUCH} px at {PHONE['width']} px:\n" \
        + "\n".join(small[:20])
    assert tiny == [], f"{page_path}: text smaller than {LEGIBLE} px at {PHONE['width']} px:\n" + "\n".join(tiny[:20])


RGB = re.compile(r"rgba?\((\d+), (\d+), (\d+)(?:, ([\d.]+))?\)")

# the stroke of every link drawn and the background the player puts it on (its own, or the first opaque one)
LINES = """() => [...document.querySelectorAll('div.mech-player')].flatMap((p, n) => {
    let bg = null;
    for (let e = p; e && !bg; e = e.parentElement) {
        const c = getComputedStyle(e).backgroundColor;
        if (c && c !== 'transparent' && !/, 0\\)$/.test(c)) bg = c;
    }
    return [...p.querySelectorAll('svg .mech-bar')].map(b => ({n, link: b.dataset.points,
        stroke: getComputedStyle(b).stroke, background: bg || 'rgb(255, 255, 255)'}));
})"""


def hex_colour(text: str) -> str:
    """``rgb(31, 119, 180)`` (a computed style) as ``#1f77b4``."""
    match = RGB.match(text)
    assert match, f"not a colour: {text}"
    return "#" + "".join(f"{int(match.group(k)):02x}" for k in (1, 2, 3))


@pytest.mark.parametrize("page_path", chapter_explorer_pages())
def test_the_mechanisms_lines_keep_their_contrast(sweep, page_path):
    # the full edition's page in the light mode, the student edition's in the dark mode
    faint = []
    for job in (("full", page_path, "light"), ("student", page_path, "dark")):
        found = sweep[job]
        assert "failed" not in found, found.get("failed")
        assert found["lines"], f"{job_id(job)}: no link drawn"
        for line in found["lines"]:
            ratio = contrast(hex_colour(line["stroke"]), hex_colour(line["background"]))
            if ratio < 3.0:
                faint.append(f"{job[2]}: player {line['n']} link {line['link']}: {line['stroke']} on "
                             f"{line['background']} is {ratio:.2f}:1")
    assert faint == [], f"{page_path}: links drawn with less than 3:1 contrast:\n" + "\n".join(faint)
