"""Layer 6: the package's workarounds of matplotlib's behaviour, each documented, in one place.

Nothing else in the package touches matplotlib's internals. Each workaround says what it works
around, why the book needs it, and what it relies on, so that a new matplotlib can be checked
against this page alone.
"""

from __future__ import annotations

import re

from matplotlib.figure import Figure

__all__ = ["offline_jshtml", "skip_idle_redraw"]

# matplotlib's player loads Font Awesome from a CDN for its button icons; the book must work
# offline, so the link is dropped and each icon becomes a plain character.
_ICONS = {"fa fa-minus": "−", "fa fa-fast-backward": "⇤", "fa fa-step-backward": "‹",
          "fa fa-play fa-flip-horizontal": "◀", "fa fa-pause": "||", "fa fa-play": "▶",
          "fa fa-step-forward": "›", "fa fa-fast-forward": "⇥", "fa fa-plus": "+"}


def offline_jshtml(html: str) -> str:
    """The animation HTML with no request outside the page (no icon font from a CDN).

    Relies on the markup of ``matplotlib.animation.HTMLWriter``: a ``<link>`` to Font Awesome and
    ``<i class="fa …">`` buttons. If matplotlib changes it, the site test (no request leaves the
    machine) fails.
    """
    html = re.sub(r'<link rel="stylesheet"\s+href="https://[^"]*font-awesome[^"]*">', "", html)
    for icon, text in _ICONS.items():
        html = html.replace(f'<i class="{icon}"></i>', text)
    return html




def skip_idle_redraw(fig: Figure) -> None:
    """Skip the redraw that ``FuncAnimation`` asks for after each frame of an animation saved to HTML.

    ``FuncAnimation`` calls ``fig.canvas.draw_idle()`` after each frame and the writer then draws
    the canvas again to save it; with no window looking at the canvas, the first drawing is
    wasted time (a third of an animation's cost). The canvas's ``draw_idle`` of this one figure is
    replaced by a no-op; the frames are identical (tested).
    """
    fig.canvas.draw_idle = lambda *args, **kwargs: None  # type: ignore[method-assign]
