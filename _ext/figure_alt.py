"""Sphinx extension of this book: every figure has a text alternative, the one the package wrote (issue 32).

In a notebook, ``mechanisms.plot`` stores each figure's description beside its PNG, in the output's
metadata: ``{"image/png": {"alt": "A graph of s in m against crank angle φ …"}}``
(``mechanisms.plot.describe.describe_figure``, registered by ``mechanisms.plot.workarounds``). MyST-NB
reads only ``width`` and ``height`` from an output's metadata, so this extension sets each notebook
image's ``alt`` from it: MyST-NB names an output's image file by the SHA-256 of its bytes, which
finds the output again.

Then every image of every page must have a text alternative: an image with none, or whose ``alt`` is
its own file name, is a warning naming the page and the image, and the book builds with warnings as
errors. A figure made by a notebook gets one by executing the notebook with ``mechanisms.plot``
imported; an image of a Markdown page gets one from its ``alt`` (``![what it shows](file.png)``, or the
``:alt:`` of ``{figure}``).
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import json
import pathlib
import re

from docutils import nodes
from sphinx.util import logging

logger = logging.getLogger(__name__)

_IMAGES = ("image/png", "image/jpeg", "image/gif", "image/svg+xml")
_FILE_NAME = re.compile(r"^\S+\.(png|jpe?g|gif|svg|webp|pdf)$", re.IGNORECASE)


def _bytes(mime: str, content: str | list[str]) -> bytes:
    """An output's data as MyST-NB writes it to a file (base64 decoded; SVG text as UTF-8 bytes)."""
    text = "".join(content) if isinstance(content, list) else str(content)
    if mime == "image/svg+xml":
        import os

        return os.linesep.join(text.splitlines()).encode("utf-8")
    try:
        return base64.b64decode(text)
    except (binascii.Error, ValueError):
        return b""


def notebook_alternatives(notebook: dict) -> dict[str, str]:
    """``{SHA-256 of an image output's bytes: its alt}`` for the image outputs of a notebook that carry one."""
    found: dict[str, str] = {}
    for cell in notebook.get("cells", []):
        for output in cell.get("outputs", None) or []:
            data, metadata = output.get("data", {}), output.get("metadata", {})
            for mime in _IMAGES:
                if mime not in data:
                    continue
                alt = (metadata.get(mime) or {}).get("alt") if isinstance(metadata.get(mime), dict) else None
                if isinstance(alt, str) and alt.strip():
                    found[hashlib.sha256(_bytes(mime, data[mime])).hexdigest()] = " ".join(alt.split())
    return found


def missing_alternative(image: nodes.image) -> bool:
    """Whether an image has no text alternative: no ``alt``, a blank one, or a file name."""
    alt = str(image.get("alt", "")).strip()
    uri = str(image.get("uri", ""))
    return not alt or alt == uri or pathlib.PurePosixPath(alt).name == pathlib.PurePosixPath(uri).name \
        or bool(_FILE_NAME.match(alt))


def set_alternatives(app, doctree: nodes.document) -> None:
    """Give each notebook image the alt stored with its output; warn for every image of the page without one."""
    docname = app.env.docname
    source = pathlib.Path(app.env.doc2path(docname))
    alternatives: dict[str, str] = {}
    if source.suffix == ".ipynb" and source.is_file():
        alternatives = notebook_alternatives(json.loads(source.read_text(encoding="utf-8")))
    for image in doctree.findall(nodes.image):
        stem = pathlib.PurePosixPath(str(image.get("uri", ""))).stem
        if stem in alternatives and missing_alternative(image):
            image["alt"] = alternatives[stem]
        if missing_alternative(image):
            logger.warning("image %s has no text alternative: a notebook's figure gets one when the notebook is "
                           "executed with mechanisms.plot imported (its output's metadata image/png alt); "
                           "an image of a page, from its alt", image.get("uri", "?"),
                           location=(docname, image.line), type="figure_alt", subtype="missing")


def setup(app):
    app.connect("doctree-read", set_alternatives)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
