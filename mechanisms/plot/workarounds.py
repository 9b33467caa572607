"""Layer 6: the package's workarounds of matplotlib's behaviour, each documented, in one place.

Nothing else in the package touches matplotlib's internals. Each workaround says what it works
around, why the book needs it, and what it relies on, so that a new matplotlib can be checked
against this page alone.
"""

from __future__ import annotations

import io
from typing import Any

from matplotlib.colors import to_rgb
from matplotlib.figure import Figure

from ..present.colours import ACCELERATION_COLOUR, BLOCK_FILL, PATH_COLOURS, ROLE_COLOURS, VELOCITY_COLOUR

__all__ = ["PALETTE_COLOURS", "palette_png", "described_png", "light_figures_in_notebooks"]

PALETTE_COLOURS = 64
"""Colours of a figure stored by a notebook: the book's figures use a few dozen, plus antialiasing."""

_BOOK_COLOURS = tuple(dict.fromkeys(("#000000", "#ffffff", *ROLE_COLOURS.values(), *PATH_COLOURS,
                                     VELOCITY_COLOUR, ACCELERATION_COLOUR, BLOCK_FILL)))
"""The book's own colours: always in a figure's palette, so that quantizing never merges two of them."""


def palette_png(fig: Figure, colours: int = PALETTE_COLOURS) -> bytes:
    """The figure as a PNG with a palette of ``colours`` colours instead of 24-bit colour.

    A line figure of the book has a few flat colours and their antialiased edges; stored as a
    palette image (no dithering) it is three to four times lighter than matplotlib's RGBA PNG and
    looks the same at the same resolution; the book's own colours are always in the palette, so no
    two of them are merged. Drawn as the inline backend draws it (tight bounding
    box, the figure's dpi, white background), then quantized by Pillow, which matplotlib itself
    depends on. Deterministic: the same figure gives the same bytes.
    """
    from PIL import Image

    buffer = io.BytesIO()
    fig.canvas.print_figure(buffer, format="png", bbox_inches="tight", dpi=fig.dpi, facecolor="white",
                            metadata={"Software": None})
    image = Image.open(io.BytesIO(buffer.getvalue())).convert("RGB")
    # median cut alone may merge two flat colours of the book that lie close in colour space (the
    # crank's blue into a teal path) when one covers many more pixels: the book's colours are put
    # into the palette first, and median cut chooses only the rest
    fixed = [round(255 * c) for colour in _BOOK_COLOURS for c in to_rgb(colour)]
    adaptive = image.quantize(colors=colours - len(_BOOK_COLOURS), method=Image.Quantize.MEDIANCUT,
                              dither=Image.Dither.NONE)
    chosen = fixed + (adaptive.getpalette() or [])[:3 * (colours - len(_BOOK_COLOURS))]
    palette = Image.new("P", (1, 1))
    palette.putpalette(chosen + chosen[-3:] * (256 - len(chosen) // 3))
    quantized = image.quantize(palette=palette, dither=Image.Dither.NONE)
    out = io.BytesIO()
    quantized.save(out, format="PNG", optimize=True)
    return out.getvalue()


def light_figures_in_notebooks() -> None:
    """In a notebook (IPython), store every figure shown as a :func:`palette_png`, with its description.

    Works around the size of matplotlib-inline's PNGs: the book's notebooks keep their outputs in
    the repository and the site serves them, and full-colour PNGs made them several megabytes.
    Relies on IPython's display formatters: the PNG formatter of ``matplotlib.figure.Figure`` is
    replaced, after pyplot's inline backend (matplotlib-inline) has registered its own, which it does
    when its module is imported: this function imports it first. The formatter returns the PNG with its
    metadata, the figure's text alternative (:func:`described_png`). Outside IPython it does nothing.
    """
    try:
        from IPython import get_ipython
    except ImportError:
        return
    shell: Any = get_ipython()
    if shell is None or not hasattr(shell, "display_formatter"):
        return
    import matplotlib

    if "matplotlib_inline" in str(matplotlib.rcParams["backend"]):
        # the inline backend registers its own formatters when its module is first imported (at the first
        # figure): import it now, so that the formatter below is registered after it and is the one used
        import matplotlib_inline.backend_inline  # noqa: F401
    shell.display_formatter.formatters["image/png"].for_type(Figure, described_png)


def described_png(fig: Figure) -> tuple[bytes, dict[str, str]]:
    """A figure's :func:`palette_png` with its text alternative: IPython's ``(data, metadata)`` of a PNG.

    IPython's display formatters may return the data with its metadata; the notebook then stores
    ``{"image/png": {"alt": description}}`` beside the PNG (:func:`~mechanisms.plot.describe.describe_figure`),
    which the book's Sphinx extension ``_ext/figure_alt.py`` makes the image's ``alt``. The PNG's bytes
    are those of :func:`palette_png`.
    """
    from .describe import describe_figure

    return palette_png(fig), {"alt": describe_figure(fig)}
