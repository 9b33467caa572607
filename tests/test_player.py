"""The site's player (_static/mechanisms-player.js, issue 17) in a real headless browser.

Two parts:

(a) a page made here from scenes of the package (a crank-slider, a four-bar family over its crank length
    with members that assemble over part of the turn, a crank-slider explorer over rod length and offset),
    with the project's own player and style sheet copied next to it and served locally: the player loads
    without console errors; the crank-angle slider moves the drawing to the package's positions; a
    parameter slider changes the mechanism, its notes and its readout; **the readout at a chosen frame
    equals the package's ``solve`` at that crank angle and those parameter values, to the printed digits**;
    play and pause work; a member that assembles over part of the turn plays only inside its range and
    says so; a member that assembles nowhere draws nothing, says so, and every control works again when the
    reader moves back; at a phone's width the page does not scroll sideways and the controls are visible.
(b) the built site, both editions (``make book``, ``make book-student``; the test fails naming the command
    when one is missing): on every page with a ``div.mech-player`` every player is ready, with no console
    error and no request leaving the machine, and moving the first player's crank-angle slider changes its
    SVG. Screenshots of each player go to ``_build/screenshots/players/`` for a person to look at.
(c) every explorer of the built site (issue 28): each parameter slider at its minimum and its maximum, by the
    keyboard (Home, End) and by setting its value with events; the drawing there is the member's own (the
    positions of the page's scene data for that member and frame) or, for a member that assembles at no frame,
    hidden with a message; moved back, the crank slider, the readout, play and the toggles work.

Every non-local request is blocked (``test_site.open_page``). Run alone with ``pytest -m browser tests/test_player.py``.
"""

from __future__ import annotations

import functools
import http.server
import json
import math
import pathlib
import re
import shutil
import threading
import warnings
from itertools import product

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.present import Parameter, Readout, explorer, scene, velocity
from test_site import EDITIONS, ROOT, QuietHandler, browser, open_page, require_built, server, servers, site_pages  # noqa: F401

pytestmark = [pytest.mark.browser, pytest.mark.needs_site("full", "student")]

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
# around 180° (1.5), two arcs (2.2, 3.0), one arc across 0° (4.5), none (6.0: |AC| >= 6 - 2 = 4 m > 1.4 + 2.5 m)
CRANKS = [0.5, 1.5, 2.2, 3.0, 4.5, 6.0]
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


# --- a member that assembles nowhere, and the crank angle kept across members (issue 28) ---------------------------

# what the drawing of a player is now: each joint's and dot's circle (shown or not, where), each bar's points,
# whether the member is the empty one, the message over the figure (None where not shown), the readout, the notes,
# the controls' state. "Shown" is what a reader sees: not display:none on the way up, and visibility visible.
DRAWN = """r => {
    const p = r.mechPlayer;
    const seen = e => { if (!e || getComputedStyle(e).visibility !== 'visible') return false;
        for (let n = e; n; n = n.parentElement) if (getComputedStyle(n).display === 'none') return false;
        return true; };
    const message = r.querySelector('.mech-message');
    return {member: p.member, frame: p.frame, angle: parseInt(r.querySelector('input.mech-angle').value, 10),
        joints: [...r.querySelectorAll('.mech-hinge, .mech-dot')].map(c => [c.dataset.joint, seen(c),
            parseFloat(c.getAttribute('cx')), parseFloat(c.getAttribute('cy'))]),
        bars: [...r.querySelectorAll('.mech-bar')].map(b => [b.dataset.points, seen(b), b.getAttribute('points')]),
        message: seen(message) ? message.textContent : null,
        notes: r.querySelector('.mech-notes').textContent,
        values: Object.fromEntries([...r.querySelectorAll('.mech-readout span.mech-value')].map(
            s => [s.dataset.label, s.textContent])),
        play: {disabled: r.querySelector('button.mech-play').disabled, text: r.querySelector('button.mech-play').textContent},
        parameters: [...r.querySelectorAll('input.mech-parameter')].map(i => parseInt(i.value, 10))};
}"""


# whether each element a toggle governs (paths for "mech-path", arrows and their labels of a kind for "kind-…")
# is shown
GOVERNED = """(r, name) => {
    const seen = e => { for (let n = e; n; n = n.parentElement) if (getComputedStyle(n).display === 'none') return false;
        return getComputedStyle(e).visibility === 'visible'; };
    const mine = name === 'mech-path' ? e => e.classList.contains('mech-path')
        : e => e.getAttribute('data-kind') === name.slice('kind-'.length);
    return [...r.querySelectorAll('svg .mech-path, svg [data-kind]')].filter(mine).map(seen);
}"""


def drawn(root) -> dict:
    return root.evaluate(DRAWN)


def set_input(root, selector: str, value: int) -> None:
    """Set a slider's value and send the events a person's drag sends (input, then change on release)."""
    root.locator(selector).evaluate("(e, v) => { e.value = String(v); e.dispatchEvent(new Event('input', "
                                    "{bubbles: true})); e.dispatchEvent(new Event('change', {bubbles: true})); }",
                                    value)


def phi_printed(degrees: float) -> str:
    """The crank angle as the readout prints it: in [0°, 360°), whole degrees without decimals."""
    value = degrees % 360.0
    return printed(value, 0 if value == int(value) else 1)


def test_a_member_that_assembles_nowhere_draws_nothing_and_the_controls_come_back(page, scenes):
    s, root = scenes["family"], page.locator(player("family"))
    none, full = s.member_index(crank=6.0), s.member_index(crank=0.5)
    assert "1" not in s.data["members"][none]["valid"]           # |AC| >= 4 m > L2 + L3 = 3.9 m at every angle
    set_slider(page, player("family") + " input.mech-angle", 3)  # 15°
    parameter = root.locator("input.mech-parameter")
    parameter.focus()
    page.keyboard.press("End")                                   # the last crank length, 6.0 m
    shown = drawn(root)
    assert shown["member"] == none
    visible = [j[0] for j in shown["joints"] if j[1]] + [b[0] for b in shown["bars"] if b[1]]
    assert visible == [], f"a member that assembles nowhere still draws {visible} (a stale drawing)"
    assert shown["message"] and "does not assemble at any crank angle" in shown["message"], shown["message"]
    assert "does not assemble at any crank angle" in shown["notes"] and "crank L1 = 6 m" in shown["notes"]
    assert shown["values"] == {"φ": "15", "ψ": "—", "ω_3": "—"}     # the angle asked for; no value to print
    assert shown["play"]["disabled"], "play is offered where nothing can move"
    angle = root.locator("input.mech-angle")
    angle.focus()
    page.keyboard.press("ArrowRight")                            # the crank slider still turns φ: 20°
    shown = drawn(root)
    assert (shown["frame"], shown["angle"], shown["values"]["φ"]) == (4, 4, "20")
    parameter.focus()
    page.keyboard.press("Home")                                  # back to 0.5 m: a full turn, drawn at 20°
    shown = drawn(root)
    assert (shown["member"], shown["frame"], shown["message"]) == (full, 4, None)
    sol = solved(four_bar(0.5), math.radians(20.0))              # the package's positions, solved here
    tolerance = s.data["step"] * math.sqrt(2) / 2 * (1 + 1e-6)
    joints = {j[0]: complex(j[2], j[3]) for j in shown["joints"] if j[1]}
    assert sorted(joints) == ["A", "B", "C", "O"]
    for joint, where in joints.items():
        assert abs(where - sol.point(joint).value[0]) <= tolerance, joint
    assert shown["values"] == {"φ": "20", "ψ": printed(math.degrees(sol.angle("coupler").value[0]), 2),
                               "ω_3": printed(sol.angle("rocker").omega[0], 3)}
    assert not shown["play"]["disabled"]
    angle.focus()
    page.keyboard.press("ArrowRight")
    assert drawn(root)["values"]["φ"] == "25"
    page.click(player("family") + " button.mech-play")
    page.wait_for_function(f"document.querySelector('{player('family')}').mechPlayer.frame !== 5", timeout=10_000)
    page.click(player("family") + " button.mech-play")
    assert "play" in drawn(root)["play"]["text"]


def test_the_angle_asked_for_is_kept_through_a_member_that_assembles_over_part_of_the_turn(page, scenes):
    s, root = scenes["family"], page.locator(player("family"))
    set_input(root, "input.mech-angle", 1)                      # 5° on the full-turn member (0.5 m)
    set_input(root, "input.mech-parameter", CRANKS.index(1.5))
    # the 1.5 m crank assembles for φ in (0.5735, 5.7097) rad = (32.9°, 327.1°): the frame nearest 5° inside is 35°
    (lower, upper), = four_bar(1.5).assembly_intervals()
    assert math.degrees(lower) < 35.0 < math.degrees(lower) + 5.0 and math.degrees(upper) < 330.0
    shown = drawn(root)
    assert (shown["member"], shown["frame"], shown["angle"], shown["values"]["φ"]) == \
        (s.member_index(crank=1.5), 7, 7, "35"), "the crank slider, the drawing and φ must agree"
    sol = solved(four_bar(1.5), math.radians(35.0), order=0)
    tolerance = s.data["step"] * math.sqrt(2) / 2 * (1 + 1e-6)
    for joint, seen, x, y in shown["joints"]:
        assert seen and abs(complex(x, y) - sol.point(joint).value[0]) <= tolerance, joint
    set_input(root, "input.mech-parameter", CRANKS.index(0.5))  # back: at the angle the reader had set
    shown = drawn(root)
    assert (shown["frame"], shown["angle"], shown["values"]["φ"]) == (1, 1, "5")


# --- (c) every explorer of the built site at both ends of every parameter -----------------------------------------

SCENE_DATA = re.compile(r'<div class="mech-player" data-still="(\d+),(\d+)">.*?'
                        r'<script type="application/json" class="mech-scene">(.*?)</script>', re.S)


def site_explorers() -> list:
    """(page, index of the player on the page) for every player of the full edition with a parameter slider."""
    site = EDITIONS["full"][0]
    found = []
    for page_path in player_pages(site):
        for index, match in enumerate(SCENE_DATA.finditer((site / page_path).read_text(encoding="utf8"))):
            data = json.loads(match.group(3))                   # "<\/" in the page is JSON's escaped "/"
            if data["parameters"]:
                found.append(pytest.param(page_path, index, id=f"{page_path}:{index}:{data['title']}"))
    return found


def page_scene(page_path: str, index: int) -> tuple[dict, int, int]:
    """The scene data of a player of the built site as the page holds it, and its still (member, frame)."""
    match = list(SCENE_DATA.finditer((EDITIONS["full"][0] / page_path).read_text(encoding="utf8")))[index]
    return json.loads(match.group(3)), int(match.group(1)), int(match.group(2))


def test_the_site_has_explorers():
    require_built("full")
    pages = {p.values[0] for p in site_explorers()}
    assert "book/04-four-bar.html" in pages, f"no explorer found on chapter 4 (explorers on: {sorted(pages)})"


def stored(data: dict, member: int, name: str, frame: int) -> tuple[float, float] | None:
    """A joint's position in the scene data (m), or None where the member has it not."""
    xy = data["members"][member]["xy"].get(name)
    if xy is None:
        return None
    if len(xy) == 2:                            # a point that does not move: stored once
        x, y = xy
    else:                                       # the first position, then differences frame to frame
        x, y = (sum(v for v in xy[axis:2 * frame + 2:2] if v is not None) for axis in (0, 1))
        if xy[2 * frame] is None:
            return None
    if x is None:
        return None
    return data["origin"][0] + data["step"] * x, data["origin"][1] + data["step"] * y


def nearest_frames(valid: str, wanted: int) -> set[int]:
    """The frames where the member assembles nearest (round the turn) to the frame asked for."""
    n = len(valid)
    frames = [k for k in range(n) if valid[k] == "1"]
    distance = {k: min((k - wanted) % n, (wanted - k) % n) for k in frames}
    return {k for k in frames if distance[k] == min(distance.values())}


def member_at(data: dict, positions: list[int]) -> int:
    """The member of the sliders' positions: the one whose key is those values (looked up in the keys)."""
    key = [p["values"][i] for p, i in zip(data["parameters"], positions)]
    return data["keys"].index(key)


def check_drawing(root, data: dict, positions: list[int], wanted: int, where: str) -> dict:
    """The player shows the member of the sliders' positions, at the frame asked for or the nearest where it
    assembles, with the scene data's positions; or, for a member that assembles at no frame, nothing drawn, a
    message, the angle asked for and no value. Returns what it shows."""
    shown = drawn(root)
    member = member_at(data, positions)
    valid = data["members"][member]["valid"]
    assert shown["parameters"] == positions, f"{where}: the sliders are at {shown['parameters']}"
    assert shown["member"] == member, f"{where}: member {shown['member']} shown for the sliders' member {member}"
    if "1" in valid:
        assert shown["frame"] in nearest_frames(valid, wanted), \
            f"{where}: frame {shown['frame']} shown, asked {wanted}, the member assembles at {valid}"
        frame = shown["frame"]
        assert shown["angle"] == frame and shown["message"] is None and not shown["play"]["disabled"], where
        extent = data["step"] * 4000
        for name, seen, x, y in shown["joints"]:
            expected = stored(data, member, name, frame)
            assert seen == (expected is not None), f"{where}: {name} {'drawn' if seen else 'hidden'} at frame {frame}"
            if expected is not None:
                assert math.isclose(x, expected[0], abs_tol=1e-9 * extent) and \
                    math.isclose(y, expected[1], abs_tol=1e-9 * extent), \
                    f"{where}: {name} drawn at ({x}, {y}), the member's own is {expected} (frame {frame})"
        for names, seen, points in shown["bars"]:
            expected = [p for p in (stored(data, member, n, frame) for n in names.split(",")) if p is not None]
            got = [tuple(float(v) for v in pair.split(",")) for pair in points.split()]
            assert seen and len(got) == len(expected), f"{where}: bar {names} is {points!r}"
            assert all(math.isclose(a, b, abs_tol=1e-9 * extent) for p, q in zip(got, expected) for a, b in zip(p, q)), \
                f"{where}: bar {names} drawn through {points}, the member's own is {expected}"
        values = [v for k, v in shown["values"].items() if k != data["angle"]]
        assert len(values) == len(data["readout"]), f"{where}: readout {shown['values']}"
        if "0" in valid:
            assert "assembles" in shown["notes"], f"{where}: no note says where the member assembles: {shown['notes']}"
    else:
        frame = wanted
        visible = [j[0] for j in shown["joints"] if j[1]] + [b[0] for b in shown["bars"] if b[1]]
        assert visible == [], f"{where}: the member assembles at no frame, yet {visible} are drawn (stale)"
        assert shown["message"], f"{where}: the member assembles at no frame and no message says so"
        assert "assemble" in shown["message"] and "assemble" in shown["notes"], (shown["message"], shown["notes"])
        assert shown["angle"] == wanted and shown["play"]["disabled"], where
        assert [v for k, v in shown["values"].items() if k != data["angle"]] == ["—"] * len(data["readout"]), \
            f"{where}: values printed for a member that assembles nowhere: {shown['values']}"
    assert shown["values"][data["angle"]] == phi_printed(data["phi"][frame]), \
        f"{where}: {data['angle']} reads {shown['values'][data['angle']]}, frame {frame} is {data['phi'][frame]}°"
    return shown


def check_crank_slider(page, root, data: dict, positions: list[int], shown: dict, where: str) -> int:
    """Turn the crank one step with the keyboard: the readout's angle changes with it (the frame it lands on
    follows the rule of check_drawing). Returns the frame now asked for."""
    n = len(data["phi"])
    asked = shown["frame"] + 1 if shown["frame"] < n - 1 else shown["frame"] - 1
    root.locator("input.mech-angle").focus()
    page.keyboard.press("ArrowRight" if asked > shown["frame"] else "ArrowLeft")
    after = check_drawing(root, data, positions, asked, where + ", the crank turned a step")
    member = data["members"][member_at(data, positions)]
    if member["valid"][asked] == "1" or "1" not in member["valid"]:
        assert after["values"][data["angle"]] != shown["values"][data["angle"]], \
            f"{where}: the crank slider moved and the readout did not"
    return after["frame"]


@pytest.mark.parametrize(("page_path", "index"), site_explorers())
def test_site_explorer_at_both_ends_of_every_parameter(browser, server, page_path, index):
    data, still_member, still_frame = page_scene(page_path, index)
    context, page, problems = open_page(browser, server, page_path)
    try:
        page.wait_for_function("[...document.querySelectorAll('div.mech-player')].every(p => p.mechPlayer)",
                               timeout=15_000)
        root = page.locator("div.mech-player").nth(index)
        root.scroll_into_view_if_needed()
        start = [p["values"].index(v) for p, v in zip(data["parameters"], data["keys"][still_member])]
        wanted = still_frame
        check_drawing(root, data, start, wanted, "the still")
        shots = SHOTS / "ends"
        shots.mkdir(parents=True, exist_ok=True)
        name = f"{page_path.replace('/', '_').removesuffix('.html')}.{index}"
        for number, parameter in enumerate(data["parameters"]):
            slider = f'input.mech-parameter[data-name="{parameter["name"]}"]'
            last = len(parameter["values"]) - 1
            for way, end in (("End", last), ("Home", 0), ("events", last), ("events", 0)):
                positions = list(start)
                positions[number] = end
                if way == "events":
                    set_input(root, slider, end)
                else:
                    root.locator(slider).focus()
                    page.keyboard.press(way)
                where = f"{page_path} player {index}: {parameter['name']} = {parameter['values'][end]} ({way})"
                shown = check_drawing(root, data, positions, wanted, where)
                if way != "events":
                    root.screenshot(path=str(shots / f"{name}.{parameter['name']}-{way}.png"))
                    wanted = check_crank_slider(page, root, data, positions, shown, where)
            set_input(root, slider, start[number])
            check_drawing(root, data, start, wanted, f"{page_path} player {index}: {parameter['name']} moved back")
        if len(data["parameters"]) == 2:                         # the corners of a two-parameter family
            for corner in product(*[(0, len(p["values"]) - 1) for p in data["parameters"]]):
                for p, i in zip(data["parameters"], corner):
                    set_input(root, f'input.mech-parameter[data-name="{p["name"]}"]', i)
                check_drawing(root, data, list(corner), wanted, f"{page_path} player {index}: corner {corner}")
            for p, i in zip(data["parameters"], start):
                set_input(root, f'input.mech-parameter[data-name="{p["name"]}"]', i)
        # back at the start: the crank slider, the readout, play and the toggles work
        where = f"{page_path} player {index}, moved back"
        shown = check_drawing(root, data, start, wanted, where)
        valid = data["members"][member_at(data, start)]["valid"]
        n = len(valid)
        target = max((k for k in range(n) if valid[k] == "1"),
                     key=lambda k: min((k - shown["frame"]) % n, (shown["frame"] - k) % n))
        set_input(root, "input.mech-angle", target)
        after = check_drawing(root, data, start, target, where + ", crank slider set")
        if target != shown["frame"]:
            assert after["frame"] == target and after["values"] != shown["values"], \
                f"{where}: the crank slider moved to frame {target} and the readout did not change"
        if valid.count("1") > 1:
            root.locator("button.mech-play").click()
            page.wait_for_function("([r, f]) => r.mechPlayer.frame !== f", arg=[root.element_handle(), target],
                                   timeout=10_000)
            root.locator("button.mech-play").click()
            assert "play" in drawn(root)["play"]["text"], f"{where}: play did not stop"
            check_drawing(root, data, start, drawn(root)["frame"], where + ", played")
        for toggle in root.locator("input[data-toggle]").all():
            name = toggle.get_attribute("data-toggle")
            before = root.evaluate(GOVERNED, name)
            assert any(before), f"{where}: the toggle {name!r} governs nothing drawn"
            toggle.click()
            assert not any(root.evaluate(GOVERNED, name)), f"{where}: the toggle {name!r} turned off hid nothing"
            toggle.click()
            assert root.evaluate(GOVERNED, name) == before, f"{where}: the toggle {name!r} did not show them again"
        assert problems == [], "\n".join(problems)
    finally:
        context.close()
