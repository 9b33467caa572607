"""Sphinx extension of this book: pages that pass axe-core's WCAG 2.1 A and AA rules (issue 32).

The theme (sphinx-book-theme 1.3 on pydata-sphinx-theme 0.17) and two extensions write a few elements that
assistive technology cannot name or that use a deprecated role. They are fixed here, where the page is made,
and never by turning an axe rule off (``tests/test_accessibility.py`` runs axe on every page):

* **the theme's search field and colour-mode button** — overridden by the templates in ``_templates/`` (the
  button's accessible name contains its visible text: WCAG 2.5.3, axe ``label-content-name-mismatch``);
  this extension puts that folder first on Sphinx's template path, so it works for both editions
  whatever folder their configuration is in;
* **the sidebar's expand/collapse buttons** — pydata-sphinx-theme makes each a ``<summary>`` holding only a
  chevron icon (axe ``summary-name``): each gets an ``aria-label`` naming the pages it shows or hides;
* **the hidden code cells' toggles** — MyST-NB writes ``<summary aria-label="Toggle hidden content">`` around
  the visible words "Show code cell source": the label is dropped, so the name is the words shown;
* **the module index** (``py-modindex.html``) — Sphinx's table gets a header row (``_templates/domainindex.html``);
* **the bibliography** — docutils marks each entry ``role="doc-biblioentry"``, deprecated in ARIA 1.2 (axe
  ``aria-deprecated-role``), inside a ``role="list"``: each entry becomes a ``listitem``.

Colours with too little contrast are corrected in ``_static/book.css``; the explorers' controls in
``_static/mechanisms-player.js`` and ``.css``.
"""

from __future__ import annotations

import functools
import html
import pathlib
import re
from typing import Any, Callable

TEMPLATES = pathlib.Path(__file__).resolve().parent.parent / "_templates"

# MyST-NB 1.x (sphinx_.py, visit_HideCellInput): the summary of a cell whose input is hidden
_HIDDEN_CELL_SUMMARY = '<summary aria-label="Toggle hidden content">'
_BIBLIOENTRY = re.compile(r'(<div class="citation"[^>]*?) role="doc-biblioentry"')
# pydata-sphinx-theme 0.17 (toctree.py, add_collapse_checkboxes): a page's link, then its collapsible list
_TOC_SUMMARY = re.compile(
    r'(<a class="[^"]*reference internal[^"]*"[^>]*>)((?:(?!</a>).)*)(</a>\s*<details[^>]*>\s*)<summary>', re.S)
_TAGS = re.compile(r"<[^>]+>")


def _templates_first(app: Any, config: Any) -> None:
    """Put ``_templates/`` before the theme's component folder on the template path."""
    path = str(TEMPLATES)
    if path not in config.templates_path:
        config.templates_path.insert(0, path)


def label_toctree_summaries(toc_html: str) -> str:
    """Give each expand/collapse ``<summary>`` of the theme's navigation an ``aria-label`` with its page."""
    def labelled(match: re.Match) -> str:
        title = html.unescape(_TAGS.sub("", match.group(2))).strip()
        label = html.escape(f"Show or hide the pages under {title}", quote=True)
        return f'{match.group(1)}{match.group(2)}{match.group(3)}<summary aria-label="{label}">'
    return _TOC_SUMMARY.sub(labelled, toc_html)


def accessible_body(body: str) -> str:
    """The page's body with the extensions' unnamed toggles and deprecated roles fixed."""
    body = body.replace(_HIDDEN_CELL_SUMMARY, "<summary>")
    return _BIBLIOENTRY.sub(r'\1 role="listitem"', body)


def _wrap_toctree(generate: Callable[..., str]) -> Callable[..., str]:
    @functools.wraps(generate)
    def wrapped(*args: Any, **kwargs: Any) -> str:
        return label_toctree_summaries(str(generate(*args, **kwargs)))
    return wrapped


def _page_context(app: Any, pagename: str, templatename: str, context: dict, doctree: Any) -> None:
    if "body" in context:
        context["body"] = accessible_body(context["body"])
    generate = context.get("generate_toctree_html")
    if generate is not None:
        context["generate_toctree_html"] = _wrap_toctree(generate)


def setup(app: Any) -> dict:
    app.connect("config-inited", _templates_first)
    # after pydata-sphinx-theme has put generate_toctree_html in the context (default priority 500)
    app.connect("html-page-context", _page_context, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
