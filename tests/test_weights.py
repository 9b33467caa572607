"""Weight budgets of issue 17: what a reader downloads, and what the repository stores.

* Every page of the built site, both editions (``make book``, ``make book-student``; pytest stops at
  collection naming the command when one is missing, tests/conftest.py), weighs at most 1 MB with its own figures: the HTML file itself (with
  every ``data:`` URI and scene inline in it) plus every file under ``_images/`` it refers to. MathJax
  (``mathjax/``) and the theme's shared files (``_static/`` …) are loaded once for the whole site and are
  not counted.
* All notebooks under ``book/`` and ``exercises/`` together weigh at most 4 MB (the outputs are stored in
  the repository and every re-execution that changes them adds to its history). Twelve chapters keep to the
  budget of ten because a scene stores a point that does not move once and a moving point as its steps from
  frame to frame.

The messages list every page's and every notebook's weight, heaviest first, so that a person sees
which figures cost what.
"""

from __future__ import annotations

import html
import pathlib
import re
import urllib.parse

import pytest

from conftest import BUILT_SITES, ROOT

PAGE_BUDGET = 1_000_000          # bytes of a page with its own images and scenes
NOTEBOOK_BUDGET = 4_000_000      # bytes of all notebooks of book/ and exercises/ together
SHARED = {"_static", "mathjax", "_sphinx_design_static", "_sources", "_images"}   # not pages
REFERENCE = re.compile(r"""(?:src|href|poster|data)\s*=\s*["']([^"']+)["']|url\(\s*["']?([^"')]+)["']?\s*\)""")
SRCSET = re.compile(r"""srcset\s*=\s*["']([^"']+)["']""")


def pages(site: pathlib.Path) -> list[pathlib.Path]:
    return sorted(p for p in site.rglob("*.html") if p.relative_to(site).parts[0] not in SHARED)


def own_images(page: pathlib.Path, site: pathlib.Path) -> set[pathlib.Path]:
    """The files under the site's ``_images/`` that the page refers to (each once)."""
    text = page.read_text(encoding="utf8")
    targets = [a or b for a, b in REFERENCE.findall(text)]
    for srcset in SRCSET.findall(text):
        targets += [part.strip().split()[0] for part in srcset.split(",") if part.strip()]
    found = set()
    images = (site / "_images").resolve()
    for target in targets:
        target = html.unescape(target)
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I) or target.startswith(("//", "#")):
            continue                      # data: URIs are inline (counted in the page), other schemes are not ours
        path = urllib.parse.unquote(target.split("#")[0].split("?")[0])
        resolved = (page.parent / path).resolve()
        if images in resolved.parents and resolved.is_file():
            found.add(resolved)
    return found


def weigh(site: pathlib.Path) -> list[tuple[int, int, int, str]]:
    """(total, HTML with its inline data, images, page) for every page, heaviest first."""
    rows = []
    for page in pages(site):
        own = page.stat().st_size
        images = sum(p.stat().st_size for p in own_images(page, site))
        rows.append((own + images, own, images, page.relative_to(site).as_posix()))
    return sorted(rows, reverse=True)


def table(rows, budget: int) -> str:
    lines = [f"{'total':>10} {'page+inline':>12} {'_images':>10}  page"]
    for total, own, images, name in rows:
        flag = "  <-- over" if total > budget else ""
        lines.append(f"{total / 1e6:>8.3f} MB {own / 1e6:>9.3f} MB {images / 1e6:>7.3f} MB  {name}{flag}")
    return "\n".join(lines)


def test_own_images_finds_the_files_a_page_refers_to(tmp_path):
    # a small site: a page two folders down refers to two images (one twice, one by srcset), a shared file
    # and a data: URI; only the two files under _images/ are its own
    (tmp_path / "_images").mkdir()
    (tmp_path / "_static").mkdir()
    (tmp_path / "book").mkdir()
    for name, size in (("a.png", 1000), ("b c.svg", 300), ("unused.png", 5000)):
        (tmp_path / "_images" / name).write_bytes(b"x" * size)
    (tmp_path / "_static" / "theme.css").write_bytes(b"x" * 7000)
    page = tmp_path / "book" / "p.html"
    page.write_text('<img src="../_images/a.png"><a href="../_images/a.png">big</a>'
                    '<img srcset="../_images/b%20c.svg 2x, ../_images/a.png 1x">'
                    '<link href="../_static/theme.css"><img src="data:image/png;base64,AAAA">', encoding="utf8")
    assert own_images(page, tmp_path) == {(tmp_path / "_images" / "a.png").resolve(),
                                          (tmp_path / "_images" / "b c.svg").resolve()}
    [(total, own, images, name)] = weigh(tmp_path)
    assert (images, name) == (1300, "book/p.html") and total == own + 1300 == page.stat().st_size + 1300


@pytest.mark.parametrize("edition", [pytest.param(e, marks=pytest.mark.needs_site(e)) for e in BUILT_SITES])
def test_every_page_is_within_its_budget(edition, built_site):
    site = built_site(edition)
    rows = weigh(site)
    assert rows, f"the {edition} edition has no pages"
    over = [name for total, _, _, name in rows if total > PAGE_BUDGET]
    assert over == [], (f"{len(over)} page(s) of the {edition} edition weigh more than {PAGE_BUDGET / 1e6:g} MB "
                        f"with their own images and scenes (MathJax and _static/ not counted):\n"
                        + table(rows, PAGE_BUDGET))


def notebooks() -> list[pathlib.Path]:
    return sorted(p for folder in ("book", "exercises") for p in (ROOT / folder).rglob("*.ipynb")
                  if ".ipynb_checkpoints" not in p.parts)


def test_the_notebooks_are_within_their_budget():
    found = notebooks()
    assert found, "no notebooks under book/ and exercises/"
    sizes = sorted(((p.stat().st_size, p.relative_to(ROOT).as_posix()) for p in found), reverse=True)
    total = sum(size for size, _ in sizes)
    listing = "\n".join(f"{size / 1e6:>8.3f} MB  {name}" for size, name in sizes)
    assert total <= NOTEBOOK_BUDGET, (f"the notebooks of book/ and exercises/ weigh {total / 1e6:.3f} MB together, "
                                      f"more than {NOTEBOOK_BUDGET / 1e6:g} MB:\n{listing}")
