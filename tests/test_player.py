"""The site's player (_static/mechanisms-player.js, issue 17) in a real headless browser.

Two parts:

(a) a page made here from scenes of the package (a crank-slider, a four-bar family over its crank length
    with members that assemble over part of the turn, a crank-slider explorer over rod length and offset),
    with the project's own player and style sheet copied next to it and served locally: the player loads
    without console errors; the crank-angle slider moves the drawing to the package's positions; a
    parameter slider changes the mechanism, its notes and its readout; **the readout at a chosen frame
    equals the package's ``solve`` at that crank angle and those parameter values, to the printed digits**;
    play and pause work; a member that assembles over part of the turn plays only inside its range and
    says so; at a phone's width the page does not scroll sideways and the controls are visible.
(b) the built site, both editions (``make book``, ``make book-student``; the test fails naming the command
    when one is missing): on every page with a ``div.mech-player`` every player is ready, with no console
    error and no request leaving the machine, and moving the first player's crank-angle slider changes its
    SVG. Screenshots of each player go to ``_build/screenshots/players/`` for a person to look at.

Every non-local request is blocked (``test_site.open_page``). Run alone with ``pytest -m browser tests/test_player.py``.
"""

from __future__ import annotations

import functools
import http.server
import math
import pathlib
import shutil
import threading
import warnings

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.present import Parameter, Readout, explorer, scene, velocity
from test_site import EDITIONS, ROOT, QuietHandler, browser, open_page, require_built, servers, site_pages  # noqa: F401

pytestmark = pytest.mark.browser

STATIC = ROOT / "_static"
SHOTS = ROOT / "_build" / "screenshots" / "players"
PHONE = {"width": 375, "height": 740}
MINUS = "\u2212"


# --- the synthetic page ------------------------------------------------------------------------------------

def crank_slider_readout():
    return [Readout("s", "m", lambda sol, m: sol.point("B").value.real, digits=4),
            Readout("v_B", "m/s", lambda sol, m: sol.point("B").velocity.real, digits=3, order=1)]


R = 0.1                                   # crank of the crank-slider explorer (m)
RODS = [0.25, 0.3, 0.35]                  # its rod lengths
OFFSETS = [0.0, 0.02, -0.03, 0.05]        # its offsets
# a four-bar with coupler 1.4 m, rocker 2.5 m, C = (2, 0) m over its crank length: a full turn (0.5), one arc
# around 180° (1.5), two arcs (2.2, 3.0), one arc across 0° (4.5)
CRANKS = [0.5, 1.5, 2.2, 3.0, 4.5]
FOUR_BAR = dict(coupler=1.4, rocker=2.5, frame=(2.0, 0.0))


def four_bar(crank):
    return mech.FourBar(crank, FOUR_BAR["coupler"], FOUR_BAR["rocker"], frame=FOUR_BAR["frame"])


def make_scenes():
    single = scene(mech.CrankSlider(crank=0.1, rod=0.35, offset=0.02), paths=["B"], arrows=[velocity("B")],
                   readout=crank_slider_readout(), title="crank-slider", caption="A crank-slider.")
    family = explorer(four_bar, [Parameter("crank", "L_1", "m", CRANKS, 2)], paths=["B"], title="four-bar family",
                      readout=[Readout("ψ", "°", lambda sol, m: np.degrees(sol.angle("coupler").value), 2),
                               Readout("ω_3", "rad/s", lambda sol, m: sol.angle("rocker").omega, 3, order=1)],
                      notes=lambda m: [f"crank $L_1$ = {m.crank:g} m"], caption="Drag the crank length.")
    pair = explorer(lambda rod, offset: mech.CrankSlider(crank=R, rod=rod, offset=offset),
                    [Parameter("rod", "L_2", "m", RODS), Parameter("offset", "e", "m", OFFSETS)],
                    readout=crank_slider_readout(), title="rod and offset", still={"rod": 0.3, "offset": 0.02})
    return {"single": single, "family": family, "pair": pair}


def page_html(scenes) -> str:
    figures = "\n".join(f'<section id="{name}"><h2>{name}</h2>{s.html()}</section>' for name, s in scenes.items())
    return ('<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            '<title>players</title><link rel="stylesheet" href="mechanisms-player.css">'
            '<style>body { font-family: sans-serif; margin: 0 auto; max-width: 50rem; padding: 0 0.5rem; }</style>'
            f'</head><body><h1>Players</h1>\n{figures}\n<script src="mechanisms-player.js"></script></body></html>')


@pytest.fixture(scope="module")
def scenes():
    return make_scenes()


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory, scenes):
    """A local server of a page with the three scenes and the project's player: its URL."""
    folder = tmp_path_factory.mktemp("players")
    for name in ("mechanisms-player.js", "mechanisms-player.css"):
        shutil.copy(STATIC / name, folder / name)
    (folder / "index.html").write_text(page_html(scenes), encoding="utf8")
    handler = functools.partial(QuietHandler, directory=str(folder))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()


@pytest.fixture
def page(browser, synthetic):
    context, page, problems = open_page(browser, synthetic, "index.html")
    page.wait_for_function("[...document.querySelectorAll('div.mech-player')].every(p => p.mechPlayer)", timeout=10_000)
    yield page
    assert problems == [], "\n".join(problems)
    context.close()


def player(name: str) -> str:
    return f"#{name} div.mech-player"


def set_slider(page, selector: str, value: int) -> None:
    page.eval_on_selector(selector, "(e, v) => { e.value = String(v); e.dispatchEvent(new Event('input')); }", value)


def state(page, name: str) -> dict:
    return page.eval_on_selector(player(name), """root => ({
        frame: root.mechPlayer.frame, member: root.mechPlayer.member,
        hinges: Object.fromEntries([...root.querySelectorAll('.mech-hinge')].map(
            c => [c.dataset.joint, [parseFloat(c.getAttribute('cx')), parseFloat(c.getAttribute('cy'))]])),
        bars: [...root.querySelectorAll('.mech-bar')].map(b => b.getAttribute('points')),
        values: Object.fromEntries([...root.querySelectorAll('.mech-readout span.mech-value')].map(
            s => [s.dataset.label, s.textContent])),
        notes: root.querySelector('.mech-notes').textContent,
        svg: root.querySelector('svg.mech-still').outerHTML,
    })""")


def printed(value: float, digits: int) -> str:
    """A number as the player prints it: fixed digits, a real minus sign, no negative zero."""
    text = f"{value:.{digits}f}"
    if float(text) == 0.0:
        text = text.lstrip("-")
    return text.replace("-", MINUS)


def solved(mechanism, phi, order=1):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mech.SingularPositionWarning)
        return mechanism.solve(np.atleast_1d(phi), order=order)


# --- (a) the player on the synthetic page ---------------------------------------------------------------------

def test_players_load_with_their_controls(page):
    counts = page.evaluate("""() => [...document.querySelectorAll('div.mech-player')].map(p => ({
        ready: p.classList.contains('mech-ready'), play: p.querySelectorAll('button.mech-play').length,
        angle: p.querySelectorAll('input.mech-angle').length,
        parameters: [...p.querySelectorAll('input.mech-parameter')].map(i => i.dataset.name),
        toggles: [...p.querySelectorAll('input[data-toggle]')].map(i => i.dataset.toggle),
        readout: p.querySelectorAll('.mech-readout span.mech-value').length}))""")
    assert [c["ready"] for c in counts] == [True, True, True]
    assert all(c["play"] == 1 and c["angle"] == 1 for c in counts)
    assert [c["parameters"] for c in counts] == [[], ["crank"], ["rod", "offset"]]
    assert counts[0]["toggles"] == ["mech-path", "kind-velocity"]
    assert [c["readout"] for c in counts] == [3, 3, 3]     # the crank angle and two values


def test_the_angle_slider_moves_the_drawing_to_the_package_positions(page, scenes):
    s = scenes["single"]
    before = state(page, "single")
    target = (before["frame"] + 20) % len(s.data["phi"])
    set_slider(page, player("single") + " input.mech-angle", target)
    after = state(page, "single")
    assert after["frame"] == target
    assert after["hinges"]["A"] != before["hinges"]["A"], "the crank pin did not move"
    assert after["bars"] != before["bars"]
    # the drawn positions are the package's at that crank angle (to the stored step)
    phi = math.radians(s.data["phi"][target])
    sol = solved(mech.CrankSlider(crank=0.1, rod=0.35, offset=0.02), phi, order=0)
    tolerance = s.data["step"] * math.sqrt(2) / 2 * (1 + 1e-6)
    for joint in ("O", "A", "B"):
        x, y = after["hinges"][joint]
        assert abs(complex(x, y) - sol.point(joint).value[0]) <= tolerance, joint
    assert after["values"]["φ"] == printed(s.data["phi"][target], 0)


def test_the_parameter_slider_changes_the_mechanism(page, scenes):
    before = state(page, "family")
    assert before["member"] == 0
    set_slider(page, player("family") + ' input.mech-parameter[data-name="crank"]', CRANKS.index(1.5))
    after = state(page, "family")
    assert after["member"] == scenes["family"].member_index(crank=1.5)
    assert after["bars"] != before["bars"], "the bars did not change with the crank length"
    assert after["notes"] != before["notes"] and "crank L1 = 1.5 m" in after["notes"], after["notes"]
    assert after["values"] != before["values"]
    shown = page.eval_on_selector(player("family") + " output.mech-parameter-value", "o => o.textContent")
    assert shown.strip() == "= 1.50 m"


@pytest.mark.parametrize(("rod", "offset", "frame"), [(0.25, -0.03, 5), (0.35, 0.05, 40), (0.3, 0.0, 63)])
def test_readout_equals_solve_to_the_printed_digits(page, scenes, rod, offset, frame):
    s = scenes["pair"]
    root = player("pair")
    set_slider(page, f'{root} input.mech-parameter[data-name="rod"]', RODS.index(rod))
    set_slider(page, f'{root} input.mech-parameter[data-name="offset"]', OFFSETS.index(offset))
    set_slider(page, f"{root} input.mech-angle", frame)
    shown = state(page, "pair")
    assert shown["member"] == RODS.index(rod) * len(OFFSETS) + OFFSETS.index(offset)
    assert shown["frame"] == frame
    degrees = 360.0 * frame / len(s.data["phi"])
    sol = solved(mech.CrankSlider(crank=R, rod=rod, offset=offset), math.radians(degrees))
    expected = {"φ": printed(degrees, 0 if degrees == int(degrees) else 1),
                "s": printed(sol.point("B").value.real[0], 4),
                "v_B": printed(sol.point("B").velocity.real[0], 3)}
    assert shown["values"] == expected, f"rod {rod} m, offset {offset} m, frame {frame}"


def test_readout_of_the_family_equals_solve(page):
    root = player("family")
    set_slider(page, f'{root} input.mech-parameter[data-name="crank"]', CRANKS.index(3.0))
    set_slider(page, f"{root} input.mech-angle", 8)             # 40°: inside the arc [10.7°, 100.6°]
    shown = state(page, "family")
    assert shown["frame"] == 8
    sol = solved(four_bar(3.0), math.radians(40.0))
    assert shown["values"] == {"φ": "40", "ψ": printed(math.degrees(sol.angle("coupler").value[0]), 2),
                               "ω_3": printed(sol.angle("rocker").omega[0], 3)}


def test_play_and_pause(page):
    root = player("single")
    start = state(page, "single")["frame"]
    page.click(f"{root} button.mech-play")
    page.wait_for_timeout(500)
    page.wait_for_function(f"document.querySelector('{root}').mechPlayer.frame !== {start}", timeout=10_000)
    assert "pause" in page.inner_text(f"{root} button.mech-play")
    page.click(f"{root} button.mech-play")
    assert "play" in page.inner_text(f"{root} button.mech-play")
    stopped = state(page, "single")["frame"]
    page.wait_for_timeout(500)
    assert state(page, "single")["frame"] == stopped, "the figure moved on after pause"


def record_frames(page, name: str) -> None:
    """From now on the player notes every frame it shows, and whether its drawing was whole there (every
    hinge shown, every bar through all its joints)."""
    page.eval_on_selector(player(name), """root => { const p = root.mechPlayer; p.shown = []; p.broken = [];
        const show = p.show;
        p.show = function (f) {
            show.call(this, f);
            this.shown.push(this.frame);
            const hidden = [...root.querySelectorAll('.mech-hinge')].some(c => c.style.display === 'none');
            const short = [...root.querySelectorAll('.mech-bar')].some(b =>
                b.getAttribute('points').trim().split(/\\s+/).length < b.dataset.points.split(',').length);
            if (hidden || short) this.broken.push(this.frame);
        }; }""")


@pytest.mark.parametrize("crank", [1.5, 2.2, 4.5])
def test_a_partial_member_plays_only_where_it_assembles(page, scenes, crank):
    s = scenes["family"]
    index = s.member_index(crank=crank)
    valid = s.data["members"][index]["valid"]
    assert "0" in valid
    root = player("family")
    set_slider(page, f'{root} input.mech-parameter[data-name="crank"]', CRANKS.index(crank))
    shown_first = state(page, "family")
    assert "assembles only for" in shown_first["notes"], shown_first["notes"]
    # the arc (taken round the turn) of frames where it assembles that holds the frame shown now
    n, start = len(valid), shown_first["frame"]
    assert valid[start] == "1"
    arc = {start}
    for direction in (1, -1):
        k = start
        while valid[(k + direction) % n] == "1" and (k + direction) % n not in arc:
            k = (k + direction) % n
            arc.add(k)
    record_frames(page, "family")
    page.click(f"{root} button.mech-play")
    # rocking back and forth through the arc takes 2·len(arc) steps; a few more
    page.wait_for_function(f"document.querySelector('{root}').mechPlayer.shown.length >= {2 * len(arc) + 4}",
                           timeout=30_000)
    page.click(f"{root} button.mech-play")
    shown = page.eval_on_selector(root, "r => r.mechPlayer.shown")
    broken = page.eval_on_selector(root, "r => r.mechPlayer.broken")
    assert broken == [], f"crank {crank} m: a broken drawing (a joint or a bar missing) at frames {sorted(set(broken))}"
    outside = sorted({k for k in shown if valid[k] != "1"})
    assert outside == [], f"crank {crank} m: frames {outside} shown where it does not assemble (valid {valid})"
    # it rocks through the whole arc it started in
    missed = sorted(arc - set(shown))
    assert missed == [], (f"crank {crank} m: playing never reached frames {missed} of the arc where it assembles "
                          f"(valid {valid}, shown {sorted(set(shown))})")


def test_phone_width_has_no_sideways_scroll_and_the_controls_show(page):
    page.set_viewport_size(PHONE)
    page.evaluate("new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")
    assert page.evaluate("window.innerWidth") == PHONE["width"]
    assert page.evaluate("document.documentElement.scrollWidth <= document.documentElement.clientWidth"), \
        f"the page scrolls sideways at {PHONE['width']} px: scrollWidth " \
        f"{page.evaluate('document.documentElement.scrollWidth')}"
    for name in ("single", "family", "pair"):
        for selector in ("button.mech-play", "input.mech-angle", "input.mech-parameter", ".mech-readout"):
            for control in page.locator(f"{player(name)} {selector}").all():
                control.scroll_into_view_if_needed()
                assert control.is_visible(), f"{name}: {selector} is not visible at {PHONE['width']} px"
                box = control.bounding_box()
                assert box and box["x"] >= 0 and box["x"] + box["width"] <= PHONE["width"] + 0.5, \
                    f"{name}: {selector} sticks out of the screen: {box}"
                assert box["width"] >= 20, f"{name}: {selector} is squeezed to {box['width']} px"
        overlaps = page.eval_on_selector(player(name), OVERLAPS)
        assert overlaps == [], f"{name}: controls drawn over each other at {PHONE['width']} px: {overlaps}"
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.evaluate("window.scrollTo(0, 0)")
    page.screenshot(path=str(SHOTS / "synthetic.phone.png"), full_page=True)


# pairs of controls (the children of .mech-controls and what they hold) whose boxes overlap by more than a pixel
OVERLAPS = """root => {
    const items = [...root.querySelectorAll('.mech-controls > *, .mech-controls > * > *')];
    const box = e => e.getBoundingClientRect(), found = [];
    const name = e => e.className || e.tagName.toLowerCase() + (e.dataset.toggle ? '[' + e.dataset.toggle + ']' : '');
    for (let i = 0; i < items.length; i++) for (let j = i + 1; j < items.length; j++) {
        const a = items[i], b = items[j];
        if (a.contains(b) || b.contains(a)) continue;
        const p = box(a), q = box(b);
        const w = Math.min(p.right, q.right) - Math.max(p.left, q.left);
        const h = Math.min(p.bottom, q.bottom) - Math.max(p.top, q.top);
        if (w > 1 && h > 1) found.push(name(a) + ' / ' + name(b) + ' (' + w.toFixed(0) + ' × ' + h.toFixed(0) + ' px)');
    }
    return found; }"""


# --- (b) the built site ------------------------------------------------------------------------------------------

# the chapters issue 17 asks an explorer of (chapter 7 of the issue is 08-frenet since the multi-loop chapter)
EXPLORER_CHAPTERS = ("book/01-links.html", "book/03-crank-slider.html", "book/04-four-bar.html",
                     "book/05-slotted-links.html", "book/06-multi-loop.html", "book/08-frenet.html")


def player_pages(site: pathlib.Path) -> list[str]:
    return [p for p in site_pages(site) if 'class="mech-player' in (site / p).read_text(encoding="utf8")]


def edition_player_pages() -> list:
    return [pytest.param(edition, page, id=f"{edition}:{page}")
            for edition, (site, _, _) in EDITIONS.items() for page in player_pages(site)]


@pytest.mark.parametrize("edition", list(EDITIONS))
def test_the_site_has_players(edition):
    site = require_built(edition)
    pages = player_pages(site)
    missing = [p for p in EXPLORER_CHAPTERS if p not in pages]
    assert missing == [], (f"the {edition} edition has no player on {missing} (pages with players: {pages}); "
                           f"rebuild with `{EDITIONS[edition][1]}` after converting them")
    jshtml = [p for p in site_pages(site) if "anim-buttons" in (site / p).read_text(encoding="utf8")]
    assert jshtml == [], f"pages of the {edition} edition still hold a PNG-strip (jshtml) animation: {jshtml}"


@pytest.mark.parametrize(("edition", "page_path"), edition_player_pages())
def test_site_players_work(browser, servers, edition, page_path):
    context, page, problems = open_page(browser, servers(edition), page_path)
    try:
        count = page.locator("div.mech-player").count()
        assert count > 0
        try:
            page.wait_for_function("[...document.querySelectorAll('div.mech-player')]"
                                   ".every(p => p.classList.contains('mech-ready'))", timeout=15_000)
        except Exception:
            pass
        not_ready = page.evaluate("[...document.querySelectorAll('div.mech-player')].map((p, i) => "
                                  "p.classList.contains('mech-ready') ? null : i).filter(i => i !== null)")
        assert not_ready == [], f"players {not_ready} of {count} did not start:\n" + "\n".join(problems)
        first = page.locator("div.mech-player").first
        first.scroll_into_view_if_needed()
        before = first.evaluate("r => r.querySelector('svg.mech-still').outerHTML")
        target = first.evaluate("""r => { const p = r.mechPlayer, n = p.data.phi.length; let best = -1, far = -1;
            for (let k = 0; k < n; k++) { const d = Math.min(Math.abs(k - p.frame), n - Math.abs(k - p.frame));
              if (p.valid(k) && d > far) { far = d; best = k; } } return best; }""")
        first.evaluate("(r, v) => { const i = r.querySelector('input.mech-angle'); i.value = String(v); "
                       "i.dispatchEvent(new Event('input')); }", target)
        after = first.evaluate("r => r.querySelector('svg.mech-still').outerHTML")
        assert after != before, f"moving the first player's angle slider to frame {target} did not change its SVG"
        assert first.evaluate("r => r.mechPlayer.frame") == target
        shots = SHOTS / edition
        shots.mkdir(parents=True, exist_ok=True)
        name = page_path.replace("/", "_").removesuffix(".html")
        for index, figure in enumerate(page.locator("div.mech-player").all()):
            figure.scroll_into_view_if_needed()
            figure.screenshot(path=str(shots / f"{name}.{index}.png"))
        assert problems == [], "\n".join(problems)
    finally:
        context.close()


def test_symbols_in_labels_and_notes_are_set_as_the_texts_math(page, scenes):
    """Letters of a symbol in italics, "_1" a subscript, digits upright; a note's $…$ likewise, no dollar left."""
    root = player("family")
    names = page.eval_on_selector_all(root + " .mech-slider-name .mech-symbol", "ss => ss.map(s => s.innerHTML)")
    assert names == ["<i>φ</i>", "<i>L</i><sub>1</sub>"], names        # the crank angle, the parameter
    style = page.eval_on_selector(root + " .mech-label", "t => getComputedStyle(t).fontStyle")
    assert style == "italic", style                                     # joint letters as in the figures
    note = page.eval_on_selector(root + " .mech-notes", "n => n.innerHTML")
    assert '<span class="mech-symbol"><i>L</i><sub>1</sub></span>' in note and "$" not in note, note
    readout = page.eval_on_selector_all(root + " .mech-readout .mech-symbol", "ss => ss.map(s => s.innerHTML)")
    assert readout[:3] == ["<i>φ</i>", "<i>ψ</i>", "<i>ω</i><sub>3</sub>"], readout
