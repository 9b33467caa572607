"""Sphinx extension of this book: a self-contained static site and readable docstrings.

**Offline.** 
Jupyter Book 1 always loads sphinx-thebe, which adds scripts that fetch thebe from a CDN for live
code cells. The book has none (its notebooks are executed and tested ahead of time), and those
scripts are added twice, which is a JavaScript error in every page. This extension removes
sphinx-thebe's script hook before the build reads any document.

**Docstrings.** The package's docstrings write magnitudes as in the book, ``|v|``, ``|J − p|``;
reStructuredText would read ``|…|`` as a substitution, so the API reference escapes the bars.
"""

import re

_MAGNITUDE = re.compile(r"(?<![\\|])\|([^|\n`]+)\|(?!\|)")


def _drop_thebe(app, config):
    listeners = app.events.listeners.get("env-before-read-docs", [])
    for listener in list(listeners):
        if getattr(listener.handler, "__name__", "") == "init_thebe_core":
            app.disconnect(listener.id)


def _escape_line(line: str) -> str:
    """Escape ``|…|`` outside inline literals (odd pieces between double backticks are literals)."""
    pieces = line.split("``")
    return "``".join(p if k % 2 else _MAGNITUDE.sub(r"\\|\1\\|", p) for k, p in enumerate(pieces))


def _escape_magnitudes(app, what, name, obj, options, lines):
    lines[:] = [_escape_line(line) for line in lines]


def setup(app):
    app.connect("config-inited", _drop_thebe, priority=900)
    app.connect("autodoc-process-docstring", _escape_magnitudes)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
