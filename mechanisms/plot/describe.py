"""Layer 6: the text alternative of a figure — what it shows, in words, for a reader who cannot see it.

Every figure of the book gets a description, written once, here, not by hand on each page:

* a figure function of the package (:func:`~mechanisms.plot.drawing.draw`,
  :func:`~mechanisms.plot.drawing.vectors_along` …) adds a sentence to the axes it draws on with
  :func:`add_description`: the mechanism, the crank angle, the joints and where they are, what is
  marked. The artists it drew are then *covered*: the generic description below does not describe
  them again;
* :func:`describe_figure` builds the rest from the figure's artists: per panel its title, what kind of
  figure it is (a drawing to scale or a graph, with its axes and units), each line not covered (a curve
  with its range and extremes, and where they are; a path with its extent), points, arrows, shaded
  areas, the words written on it and the entries of its key.

In a notebook, :func:`mechanisms.plot.workarounds.light_figures_in_notebooks` stores the description
beside each figure's PNG (the output's metadata ``{"image/png": {"alt": …}}``), and the book's Sphinx
extension ``_ext/figure_alt.py`` makes it the image's ``alt`` text. Numbers are rounded to three
significant figures (after rounding to nine, so that a last-bit difference of a processor cannot move
them), so that the same figure has the same text on every machine.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any, Iterable

import numpy as np

from ..core.errors import InvalidParameterError
from ..present.describe import extent_text, plain_text, point_text, sentence as _sentence, series as _series, value_text

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["add_description", "describe_figure", "describe_axes", "plain_text", "value_text", "point_text",
           "covering"]

_SENTENCES = "_mechanisms_description"
"""The attribute of an Axes holding the sentences the package's figure functions wrote about it."""
_COVERED = "_mechanisms_covered"
"""The attribute of an Axes holding the ids of the artists those sentences describe."""
_MOST_CURVES = 10
"""Lines described one by one in a panel; the others are counted."""
_MOST_WORDS = 16
"""Words written on a panel that are listed; the others are counted."""


# --- what the package's figure functions say --------------------------------------------------------------

def add_description(ax: Axes, sentence: str, artists: Iterable[Any] = ()) -> None:
    """Say what a figure function drew on ``ax``: a sentence of the figure's text alternative.

    Parameters
    ----------
    ax : matplotlib Axes
        Where it drew.
    sentence : str
        What it drew, in words (mathtext between dollars is read as :func:`plain_text`).
    artists : iterable of Artist
        The artists the sentence describes: the generic description leaves them out.

    Raises
    ------
    InvalidParameterError
        ``sentence`` is not a non-empty string.
    """
    if not isinstance(sentence, str) or not sentence.strip():
        raise InvalidParameterError("sentence", sentence, "a sentence saying what the figure function drew")
    sentences: list[str] = ax.__dict__.setdefault(_SENTENCES, [])
    sentences.append(sentence)
    covered: set[int] = ax.__dict__.setdefault(_COVERED, set())
    covered.update(id(artist) for artist in artists)


class covering:
    """``with covering(ax) as drawn: …``: the artists added to ``ax`` inside the block, in ``drawn.artists``.

    A figure function draws inside the block, then passes ``drawn.artists`` to :func:`add_description`.
    Sentences added inside by the functions it calls are dropped (``replace=True``, the default): the
    caller describes the whole.
    """

    def __init__(self, ax: Axes, replace: bool = True):
        self.ax = ax
        self.replace = replace
        self.artists: list[Any] = []

    def __enter__(self) -> covering:
        self._before = {id(a) for a in self.ax.get_children()}
        self._sentences = len(self.ax.__dict__.get(_SENTENCES, []))
        return self

    def __exit__(self, *exc: object) -> None:
        self.artists = [a for a in self.ax.get_children() if id(a) not in self._before]
        if self.replace and _SENTENCES in self.ax.__dict__:
            del self.ax.__dict__[_SENTENCES][self._sentences:]


def _sentences(ax: Axes) -> list[str]:
    return list(ax.__dict__.get(_SENTENCES, []))


def _covered(ax: Axes) -> set[int]:
    return set(ax.__dict__.get(_COVERED, set()))


# --- the generic description ---------------------------------------------------------------------------------

def _label_parts(label: str) -> tuple[str, str]:
    """An axis label ``"crank angle φ, °"`` as its name and unit (``"crank angle φ"``, ``"°"``)."""
    text = plain_text(label)
    match = re.fullmatch(r"(.*\S),\s*([^,]{1,16})", text)
    if match and not re.fullmatch(r"[-−+]?[\d.]+\)?", match.group(2).strip()):     # not "(4, 0)"
        return match.group(1), match.group(2)
    return text, ""


def _axis_label(ax: Axes, which: str) -> str:
    """The axes' label of ``which`` ("x" or "y"), or that of an axes sharing it (a label left on one panel)."""
    axis = ax.xaxis if which == "x" else ax.yaxis
    label = axis.get_label_text()
    if label:
        return label
    group = ax.get_shared_x_axes() if which == "x" else ax.get_shared_y_axes()
    for other in group.get_siblings(ax):
        text = (other.xaxis if which == "x" else other.yaxis).get_label_text()
        if text:
            return text
    return ""


def _is_drawing(ax: Axes) -> bool:
    aspect = ax.get_aspect()
    return aspect == "equal" or (isinstance(aspect, (int, float)) and aspect == 1.0)


def _ordered(values: np.ndarray) -> np.ndarray:
    """Values rounded to 6 significant figures of their range: ties of round-off stay ties, and the first wins.

    A range below 10⁻⁶ of the values' size is round-off of a constant: the values are then all equal.
    """
    finite = values[np.isfinite(values)]
    span = float(np.ptp(finite)) if finite.size else 0.0
    size = float(np.max(np.abs(finite), initial=0.0))
    scale = max(span, 1e-6 * size) or 1.0
    return np.round(values / scale, 6)


def _symbol_of(name: str) -> str:
    """The symbol that ends an axis name, to say where a value is: ``crank angle φ`` → ``φ``, ``λ = L₁/L₂`` → ``λ``.

    The name itself when it ends with no symbol (``time per position``).
    """
    if " = " in name:
        return name.split(" = ")[0].strip()
    words = name.split()
    symbol = r"[A-Za-zα-ωΑ-Ω][₀-₉ₐ-ₜᵢ-ᵥ]*(?:_\S+)?"
    if len(words) > 1 and re.fullmatch(symbol, words[-1]) and not re.fullmatch(r"[-+*/=×·]", words[-2]):
        return words[-1]
    return name


def _unit_words(unit: str) -> str:
    return "degrees" if unit == "°" else unit


def _at(name: str, value: float, unit: str, tiny: float = 0.0) -> str:
    where = value_text(value, unit, tiny=tiny)
    return f"at {_symbol_of(name)} = {where}" if name else f"at {where}"


def _curve(label: str, x: np.ndarray, y: np.ndarray, xname: str, xunit: str, yunit: str, log: bool,
           xlog: bool = False) -> str:
    """A curve of a graph: its extremes and where they are, or that it rises or falls, or is constant."""
    keep = np.isfinite(x) & np.isfinite(y)
    gaps = int(np.count_nonzero(~keep))
    x, y = x[keep], y[keep]
    if x.size == 0:
        return f"{label}: no finite values"
    tiny = 0.0 if log else 1e-9 * float(np.max(np.abs(y)))
    xtiny = 0.0 if xlog else 1e-9 * float(np.max(np.abs(x)))

    def v(value: float) -> str:
        return value_text(value, yunit, tiny=tiny)

    def at(value: float) -> str:
        return _at(xname, value, xunit, xtiny)

    if x.size == 1:
        return f"{label}: one point, {v(y[0])} {at(x[0])}"
    order = _ordered(y)
    low, high = int(np.argmin(order)), int(np.argmax(order))
    ends = f"from {value_text(x[0], xunit, tiny=xtiny)} to {value_text(x[-1], xunit, tiny=xtiny)}"
    if order[low] == order[high]:
        text = f"{label}: constant at {v(y[0])}, {xname + ' ' if xname else ''}{ends}"
    else:
        steps = np.diff(order)
        if np.all(steps >= 0) or np.all(steps <= 0):
            trend = "rises" if order[-1] > order[0] else "falls"
            text = f"{label}: {trend} from {v(y[0])} {at(x[0])} to {v(y[-1])} {at(x[-1])}"
        else:
            text = (f"{label}, {xname + ' ' if xname else ''}{ends}: lowest {v(y[low])} {at(x[low])}, "
                    f"highest {v(y[high])} {at(x[high])}")
            if order[0] != order[low] and order[0] != order[high]:
                text += f", starting at {v(y[0])}"
            if order[-1] != order[low] and order[-1] != order[high]:
                text += f", ending at {v(y[-1])}"
    if gaps:
        text += f" ({gaps} values missing)"
    return text


def _path(label: str, x: np.ndarray, y: np.ndarray, unit: str) -> str:
    """A line of a drawing to scale: a segment's ends, or a path's extent and whether it closes."""
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    if x.size == 0:
        return ""
    tiny = 1e-9 * float(max(np.max(np.abs(x)), np.max(np.abs(y))))
    if x.size == 1:
        return f"{label}: a point at {point_text(complex(x[0], y[0]), unit, tiny)}"
    if x.size == 2:
        return (f"{label}: a straight line from {point_text(complex(x[0], y[0]), '', tiny)} to "
                f"{point_text(complex(x[1], y[1]), unit, tiny)}")
    span = float(max(np.ptp(x), np.ptp(y)))
    closed = abs(complex(x[0] - x[-1], y[0] - y[-1])) <= 1e-6 * span
    return f"{label}: {'closed' if closed else 'open'}, {extent_text(x + 1j * y, unit)}"


_STYLES = {"--": "dashed", ":": "dotted", "-.": "dash-dotted"}


def _line_name(line: Any, default: str) -> str:
    """``curve s``, ``path A``; a labelled straight line by its label alone; ``a dashed line`` unlabelled."""
    label = str(line.get_label())
    if label and not label.startswith("_"):
        return plain_text(label) if default == "line" else f"{default} {plain_text(label)}"
    style = _STYLES.get(str(line.get_linestyle()), "")
    return f"{'a ' + style if style else 'an unlabelled'} {default}"


def _lines(ax: Axes, covered: set[int], drawing: bool, xname: str, xunit: str, yunit: str) -> list[str]:
    import matplotlib.transforms as mtransforms

    out: list[str] = []
    described = 0
    points: list[complex] = []
    for line in ax.get_lines():
        if id(line) in covered or not line.get_visible():
            continue
        x = np.asarray(line.get_xdata(), dtype=float).ravel()
        y = np.asarray(line.get_ydata(), dtype=float).ravel()
        if x.size == 0 or x.size != y.size:
            continue
        transform = line.get_transform()
        if transform != ax.transData and isinstance(transform, mtransforms.BlendedGenericTransform):
            # axhline / axvline: one coordinate is in axes units
            if transform.contains_branch_seperately(ax.transData)[1] and np.ptp(y) == 0:
                text = f"{_line_name(line, 'line')}: horizontal at {value_text(y[0], yunit)}"
            elif np.ptp(x) == 0:
                text = f"{_line_name(line, 'line')}: vertical {_at(xname, x[0], xunit)}"
            else:
                continue
        elif drawing and x.size == 1 and str(line.get_label()).startswith("_"):
            points.append(complex(x[0], y[0]))
            continue
        elif drawing:
            text = _path(_line_name(line, "line" if x.size == 2 else "path"), x, y, xunit)
        elif x.size <= 3 and str(line.get_linestyle()) in ("None", "", " "):
            marks = [f"{value_text(b, yunit)} {_at(xname, a, xunit)}" for a, b in zip(x, y)]
            text = f"{_line_name(line, 'marker')}: {_series(marks)}"
        else:
            text = _curve(_line_name(line, "curve"), x, y, xname, xunit, yunit, ax.get_yscale() == "log",
                          ax.get_xscale() == "log")
        if not text:
            continue
        described += 1
        if described <= _MOST_CURVES:
            out.append(text)
    if described > _MOST_CURVES:
        more = described - _MOST_CURVES
        out.append(f"{more} more line{'s' if more > 1 else ''}")
    if points:
        tiny = 1e-9 * max(abs(p) for p in points)
        unique = list(dict.fromkeys(point_text(p, "", tiny) for p in points))
        listed = ", ".join(unique[:_MOST_WORDS]) + (f" and {len(unique) - _MOST_WORDS} more" if len(unique) >
                                                   _MOST_WORDS else "")
        out.append(f"{len(unique)} marked point{'s' if len(unique) > 1 else ''} at {listed}"
                   + (f" {xunit}" if xunit else ""))
    return out


def _collections(ax: Axes, covered: set[int]) -> list[str]:
    from matplotlib.collections import LineCollection, PathCollection, PolyCollection
    from matplotlib.quiver import Quiver

    out = []
    for item in ax.collections:
        if id(item) in covered or not item.get_visible():
            continue
        if isinstance(item, Quiver):
            out.append(f"{item.N} arrows")
        elif isinstance(item, PathCollection):
            out.append(f"{np.shape(item.get_offsets())[0]} marked points")
        elif isinstance(item, LineCollection):
            out.append(f"{len(item.get_segments())} line segments")
        elif isinstance(item, PolyCollection):
            out.append("a shaded area")
    return out


def _patches(ax: Axes, covered: set[int]) -> list[str]:
    from matplotlib.patches import FancyArrowPatch

    shapes = arrows = 0
    for patch in ax.patches:
        if id(patch) in covered or not patch.get_visible():
            continue
        if isinstance(patch, FancyArrowPatch):
            arrows += 1
        else:
            shapes += 1
    out = []
    if arrows:
        out.append(f"{arrows} arrow{'s' if arrows > 1 else ''}")
    if shapes:
        out.append(f"{shapes} shaded shape{'s' if shapes > 1 else ''}")
    return out


def _words(ax: Axes, covered: set[int]) -> tuple[list[str], int]:
    """The words written on the axes (annotations and texts not covered), and how many arrows they draw."""
    words, arrows = [], 0
    for text in ax.texts:
        if id(text) in covered or not text.get_visible():
            continue
        if getattr(text, "arrow_patch", None) is not None:
            arrows += 1
        written = plain_text(text.get_text())
        if written and written not in words:
            words.append(written)
    return words, arrows


def _key(ax: Axes, covered: set[int]) -> list[str]:
    """Entries of the key that describe no line of the panel's data (the scale of the vectors …)."""
    if ax.get_legend() is None:
        return []
    entries = []
    for handle, label in zip(*ax.get_legend_handles_labels()):
        data = getattr(handle, "get_xdata", None)
        if id(handle) not in covered and data is not None and np.size(data()) == 0:
            entries.append(plain_text(label))
    return [entry for entry in entries if entry]


def describe_axes(ax: Axes) -> str:
    """The description of one panel: what it is, what the package drew on it, its lines, points and words.

    Parameters
    ----------
    ax : matplotlib Axes

    Returns
    -------
    str
        Sentences; empty for a panel with nothing on it.
    """
    return " ".join(_panel_parts(ax))


def _panel_parts(ax: Axes) -> list[str]:
    """:func:`describe_axes`'s sentences, one item per thing described (the first says what the panel is)."""
    covered = _covered(ax)
    drawing = _is_drawing(ax)
    xname, xunit = _label_parts(_axis_label(ax, "x"))
    yname, yunit = _label_parts(_axis_label(ax, "y"))
    title = plain_text(ax.get_title()) or plain_text(ax.get_title("left")) or plain_text(ax.get_title("right"))
    parts: list[str] = []
    lines = _lines(ax, covered, drawing, xname, xunit, yunit)
    others = _collections(ax, covered) + _patches(ax, covered)
    words, annotated_arrows = _words(ax, covered)
    sentences = _sentences(ax)
    if not (sentences or lines or others or words):
        return []
    if drawing:
        kind = "A drawing to scale"
        if xname == yname and xunit == yunit and xname:
            kind += f", both axes in {xunit or xname}"
        elif xname or yname:
            kind += f", {xname} and {yname}" + (f" in {xunit}" if xunit and xunit == yunit else "")
    else:
        kind = "A graph"
        if yname or xname:
            kind += f" of {yname or 'values'}" + (f" in {_unit_words(yunit)}" if yunit else "")
            kind += f" against {xname or 'x'}" + (f" in {_unit_words(xunit)}" if xunit else "")
        scales = [f"{which} axis" for which, axis in (("x", ax.xaxis), ("y", ax.yaxis))
                  if axis.get_scale() == "log"]
        if scales:
            kind += f", logarithmic {_series(scales).replace(' axis and ', ' and ')}"
    parts.append(_sentence(f"{title}: {kind[0].lower() + kind[1:]}" if title else kind))
    parts += [_sentence(plain_text(s)) for s in sentences]
    if lines:
        parts.append(_sentence("; ".join(lines)))
    if annotated_arrows:
        others.append(f"{annotated_arrows} arrow{'s' if annotated_arrows > 1 else ''} with labels")
    if others:
        parts.append(_sentence("Also " + _series(others)))
    if words:
        shown = words[:_MOST_WORDS]
        more = f" and {len(words) - _MOST_WORDS} more" if len(words) > _MOST_WORDS else ""
        parts.append(_sentence("Written on it: " + ", ".join(shown) + more))
    key = _key(ax, covered)
    if key:
        parts.append(_sentence("Key: " + "; ".join(key)))
    return parts


def _position_words(axes: list[Axes]) -> list[str]:
    """Where each panel is: top, bottom, left, right, as its position in the grid of panels says."""
    boxes = [ax.get_position() for ax in axes]
    rows = sorted({round(-b.y1, 2) for b in boxes})
    cols = sorted({round(b.x0, 2) for b in boxes})
    out = []
    for b in boxes:
        row, col = rows.index(round(-b.y1, 2)), cols.index(round(b.x0, 2))
        vertical = "" if len(rows) == 1 else ("top" if row == 0 else "bottom" if row == len(rows) - 1 else "middle")
        horizontal = "" if len(cols) == 1 else ("left" if col == 0 else "right" if col == len(cols) - 1
                                                else "centre")
        out.append(" ".join(w for w in (vertical, horizontal) if w))
    return out


def describe_figure(fig: Figure) -> str:
    """A figure's text alternative: what each panel shows, in a few sentences.

    Built from the sentences of the package's figure functions (:func:`add_description`) and from the
    figure's artists (:func:`describe_axes`); numbers have three significant figures.

    Parameters
    ----------
    fig : matplotlib Figure

    Returns
    -------
    str
        The description; ``""`` for a figure with nothing on it.
    """
    axes = [ax for ax in fig.get_axes() if ax.get_visible()]
    described = [(ax, _panel_parts(ax)) for ax in axes]
    described = [(ax, parts) for ax, parts in described if parts]
    # what every panel shows alike (the same mechanism in the same position) is said once, before them
    common = [part for part in described[0][1][1:] if all(part in parts[1:] for _, parts in described)] \
        if len(described) > 1 else []
    panels = [(ax, " ".join(part for part in parts if part not in common)) for ax, parts in described]
    suptitle = getattr(fig, "_suptitle", None)
    head = plain_text(suptitle.get_text()) if suptitle is not None else ""
    legends = [plain_text(t.get_text()) for legend in fig.legends for t in legend.get_texts()]
    tail = _sentence("Key of the panels: " + "; ".join(legends)) if legends else ""
    if not panels:
        return " ".join(p for p in (_sentence(head), tail) if p)
    if len(panels) == 1:
        return " ".join(p for p in (_sentence(head), panels[0][1], tail) if p)
    where = _position_words([ax for ax, _ in panels])
    ordered = sorted(zip(panels, where), key=lambda item: (-round(item[0][0].get_position().y1, 2),
                                                            round(item[0][0].get_position().x0, 2)))
    text = [_sentence(head) if head else "", f"{len(panels)} panels."]
    if common:
        text.append("In every panel: " + " ".join(common))
    for number, ((ax, description), place) in enumerate(ordered, 1):
        text.append(f"Panel {number}{' (' + place + ')' if place else ''}: {description}")
    text.append(tail)
    return " ".join(t for t in text if t)
