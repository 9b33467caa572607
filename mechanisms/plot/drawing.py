"""Layer 6: figures of the book — one style, drawings of mechanisms, diagrams (moving figures: :mod:`mechanisms.present.scene`).

Every figure of the book is made here, so a notebook cell that makes a figure is two or three
lines. Colours are fixed per link role (:data:`ROLE_COLOURS`); velocity vectors are always
:data:`VELOCITY_COLOUR`, accelerations :data:`ACCELERATION_COLOUR`.
"""

from __future__ import annotations

import re

from typing import TYPE_CHECKING, Any, Callable, Iterable, Mapping, Sequence

import matplotlib

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon, Rectangle

from ..linkages.base import Bar, Block, Ground, Guide, Mechanism, Solution
from ..linkages.groups import PRP, RPP, RRP, Line
from ..core.errors import InvalidParameterError
from ..core.motion import PointMotion
from ..present.colours import (ACCELERATION_COLOUR, BLOCK_FILL, PATH_COLOURS, ROLE_COLOURS, VELOCITY_COLOUR,
                               link_colours)
from ..present.describe import (angle_text, extent_text, mechanism_name, plain_text, point_text, position_sentence,
                                series, value_text)
from .describe import add_description, covering
from .workarounds import light_figures_in_notebooks

# axis labels typeset as the book's math (mathtext), never plain letters
AXIS_X, AXIS_Y = "$x$, m", "$y$, m"
_TEX = {"φ": r"\varphi", "ψ": r"\psi", "θ": r"\theta"}


def point_label(name: str) -> str:
    """A joint's name as the book sets a point, in italic math: ``A`` → ``$A$``, ``O2`` → ``$O_2$``.

    Parameters
    ----------
    name : str
        The package's name of the joint: letters, then optional digits (a subscript).

    Returns
    -------
    str
        Matplotlib mathtext; a name of another form is returned as it is.
    """
    match = re.fullmatch(r"([A-Za-z]+?)(\d*)", name)
    if match is None:
        return name
    letters, digits = match.groups()
    return f"${letters}_{{{digits}}}$" if digits else f"${letters}$"

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "ROLE_COLOURS",
    "PATH_COLOURS",
    "VELOCITY_COLOUR",
    "ACCELERATION_COLOUR",
    "use_book_style",
    "draw",
    "point_label",
    "moving_guides",
    "trajectories",
    "vectors_along",
    "vector_key",
    "diagram",
    "link_snapshots",
    "annotate_angle",
    "annotate_length",
    "annotate_dimension",
    "draw_positions",
]

BOOK_STYLE: dict[str, Any] = {
    "figure.figsize": (6.4, 4.0),
    "figure.dpi": 100,
    "savefig.dpi": 100,
    "font.size": 10,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
    "svg.hashsalt": "mechanisms",
}


def use_book_style() -> None:
    """Set the book's matplotlib style (called on import of :mod:`mechanisms.plot`)."""
    matplotlib.rcParams.update(BOOK_STYLE)  # type: ignore[arg-type]   # its keys are rcParams' names
    light_figures_in_notebooks()


use_book_style()


def _new_axes(ax: Axes | None, equal: bool = True) -> Axes:
    if ax is None:
        _, ax = plt.subplots()
    if equal:
        ax.set_aspect("equal")
    return ax


def _pivot_symbol(ax: Axes, point: complex, size: float) -> None:
    """A frame pivot: a small triangle on a hatched base."""
    x, y = point.real, point.imag
    triangle = Polygon([(x, y), (x - size, y - 1.6 * size), (x + size, y - 1.6 * size)], closed=True,
                       facecolor="white", edgecolor=ROLE_COLOURS["frame"], lw=1.2, zorder=2)
    ax.add_patch(triangle)
    ax.add_patch(Rectangle((x - 1.6 * size, y - 2.2 * size), 3.2 * size, 0.6 * size, facecolor="none",
                           edgecolor=ROLE_COLOURS["frame"], hatch="////", lw=0.0, zorder=1))


def _guide_symbol(ax: Axes, through: complex, angle: float, half_length: float, size: float) -> None:
    direction = np.exp(1j * angle)
    normal = 1j * direction
    a, b = through - half_length * direction, through + half_length * direction
    ax.plot([a.real, b.real], [a.imag, b.imag], color=ROLE_COLOURS["frame"], lw=1.2, zorder=1)
    corners = [a, b, b - 0.7 * size * normal, a - 0.7 * size * normal]
    ax.add_patch(Polygon([(c.real, c.imag) for c in corners], closed=True, facecolor="none",
                         edgecolor=ROLE_COLOURS["frame"], hatch="////", lw=0.0, zorder=0))


def _block_corners(centre: complex, angle: float, size: float) -> list[tuple[float, float]]:
    direction = np.exp(1j * angle)
    normal = 1j * direction
    corners = [centre + s * 1.4 * size * direction + t * 0.8 * size * normal for s, t in
               ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    return [(c.real, c.imag) for c in corners]


def _block_symbol(ax: Axes, centre: complex, angle: float, size: float) -> None:
    ax.add_patch(Polygon(_block_corners(centre, angle, size), closed=True, facecolor=BLOCK_FILL,
                         edgecolor=ROLE_COLOURS["slider"], lw=1.5, zorder=3))


def _line_at(mechanism: Mechanism, solution: Solution, line: Line, index: int) -> tuple[complex, float] | None:
    """Where a line carried by a moving link is at one position: a point of it (m) and its direction (rad).

    ``None`` for a line of the frame (drawn as a fixed :class:`Guide`) or of a link that the
    mechanism does not place by its first joint.
    """
    if line.link == "frame" or line.link not in mechanism.links:
        return None
    local = complex(line.point)
    point = complex(solution.point_on(line.link, local.real, local.imag).value[index])
    return point, float(solution.angle(line.link).value[index]) + line.angle


def moving_guides(mechanism: Mechanism, solution: Solution, index: int = 0) -> list[tuple[str, complex, float,
                                                                                           list[str]]]:
    """The guides and slots carried by moving links, at one crank position.

    A guide on the frame is part of the mechanism's scheme (a hatched :class:`Guide`); a guide
    carried by a moving link turns and travels with it: the slot across a crank of a PRP group,
    the slot of a lever of an RRP group, the yoke's slot of an RPP group (the Scotch yoke).

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism that describes its structure (:meth:`~mechanisms.linkages.base.Mechanism.groups`).
    solution : Solution
        Its positions.
    index : int
        Which crank position.

    Returns
    -------
    list of (str, complex, float, list of str)
        For each moving guide: the link that carries it, a point of it (m), its direction (rad)
        and the joints of the blocks that slide on it.
    """
    guides: list[tuple[str, complex, float, list[str]]] = []
    for group in mechanism.groups():
        carried: list[tuple[Line, str]] = []
        if isinstance(group, RRP):
            carried = [(group.guide, group.joint)]
        elif isinstance(group, PRP):
            carried = [(group.first_guide, group.joint), (group.second_guide, group.joint)]
        elif isinstance(group, RPP):
            carried = [(group.guide, group.joint)]
            where = _line_at(mechanism, solution, group.guide, index)
            guide_angle = group.guide.angle if where is None else where[1]
            guides.append((group.yoke, complex(solution.point(group.joint).value[index]),
                           guide_angle + group.slot_angle, [group.block]))
        for line, joint in carried:
            placed = _line_at(mechanism, solution, line, index)
            if placed is not None:
                guides.append((line.link, placed[0], placed[1], [joint]))
    return guides


def _moving_guide_symbol(ax: Axes, through: complex, angle: float, blocks: list[complex], colour: str,
                         margin: float) -> None:
    """A guide carried by a link: a line in the link's colour from ``through`` past its blocks, ``margin`` beyond."""
    direction = np.exp(1j * angle)
    along = [0.0] + [((b - through) * np.conj(direction)).real for b in blocks]
    a, b = through + (min(along) - margin) * direction, through + (max(along) + margin) * direction
    ax.plot([a.real, b.real], [a.imag, b.imag], color=colour, lw=1.6, solid_capstyle="butt", zorder=1.5,
            label="_nolegend_")


def _free_side(spokes: list[complex], distance: float = 10.0) -> tuple[float, float]:
    """An offset (points) for a joint's name: of eight directions, the one farthest from every spoke
    (the directions of the joint's bars and of its pivot symbol); up-right first among equals."""
    candidates = [np.exp(1j * np.pi * k / 4) for k in (1, 3, 7, 5, 0, 2, 4, 6)]
    if spokes:
        best = max(candidates, key=lambda c: min(abs(np.angle(c / s)) for s in spokes))
    else:
        best = candidates[0]
    return (distance * best.real, distance * best.imag)


def _extent(solution: Solution) -> float:
    points = np.concatenate([np.ravel(solution.point(n).value) for n in solution.point_names])
    span = np.ptp(points.real) + np.ptp(points.imag) if points.size else 1.0
    return float(span) or 1.0


def draw(mechanism: Mechanism, solution: Solution, index: int = 0, ax: Axes | None = None,
         labels: bool | Mapping[str, str] = True,
         size: float | None = None, guide_half_length: float | None = None,
         label_offset: tuple[float, float] | Mapping[str, tuple[float, float]] | None = None,
         colours: Mapping[str, str] | None = None) -> Axes:
    """Draw a mechanism at one crank position: bars, hinges, hatched frame, blocks, guides.

    A guide fixed to the frame is drawn hatched; a guide or slot carried by a moving link
    (:func:`moving_guides`) is drawn as a line in that link's colour, through the blocks that
    slide on it.

    Parameters
    ----------
    mechanism : Mechanism
        What to draw (its :meth:`~mechanisms.base.Mechanism.scheme`).
    solution : Solution
        A solution with at least positions (``order=0`` is enough).
    index : int
        Which crank position of the solution to draw.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    labels : bool or dict
        Write the joint names next to the joints; a dict ``{package name: page letter}`` writes the
        page's own letters for the joints it lists (``{"B": "B1"}``: B in its first position), the
        package's names for the others.
    size : float, optional
        Size of hinges and symbols (m); by default 3 % of the mechanism's extent.
    label_offset : (float, float) or dict
        Where the joint names sit relative to their joints, in points: one ``(dx, dy)`` for all, or a
        dict ``{joint: (dx, dy)}`` (by package name) for the names it lists. By default a name sits on
        the side of its joint that is farthest from the joint's bars and pivot symbol.
    colours : dict, optional
        ``{link name: "#rrggbb"}``: links drawn in a colour of their own instead of their role's
        (:func:`~mechanisms.present.colours.link_colours`), e.g. the second of two rockers.

    Returns
    -------
    matplotlib Axes
    """
    ax = _new_axes(ax)
    with covering(ax) as drawn:
        _draw(ax, mechanism, solution, index, labels, size, guide_half_length, label_offset, colours)
    where = {name: complex(solution.point(name).value[index]) for name in solution.point_names}
    moving = [f"a slot of the {link} through {series([plain_text(point_label(b)) for b in blocks])}"
              for link, _, _, blocks in moving_guides(mechanism, solution, index)]
    text = position_sentence(mechanism, where, float(np.ravel(solution.phi)[index]),
                             labels if isinstance(labels, Mapping) else None)
    add_description(ax, text + (" Drawn also: " + series(moving) + "." if moving else ""), drawn.artists)
    return ax


def _draw(ax: Axes, mechanism: Mechanism, solution: Solution, index: int, labels: bool | Mapping[str, str],
          size: float | None, guide_half_length: float | None,
          label_offset: tuple[float, float] | Mapping[str, tuple[float, float]] | None,
          colours: Mapping[str, str] | None) -> None:
    """The artists of :func:`draw`."""
    colour_of = link_colours(mechanism, colours)
    size = size or 0.03 * _extent(solution)
    where = {name: complex(solution.point(name).value[index]) for name in solution.point_names}
    guide_half_length = guide_half_length or 0.6 * _extent(solution)
    artists: list[Any] = []
    spokes: dict[str, list[complex]] = {name: [] for name in where}   # directions taken at each joint
    for item in mechanism.scheme():
        if isinstance(item, Guide):
            _guide_symbol(ax, item.through, item.angle, guide_half_length, size)
        elif isinstance(item, Ground):
            _pivot_symbol(ax, where[item.joint], size)
            spokes[item.joint].append(-1j)                    # the pivot symbol hangs below
        elif isinstance(item, Bar):
            pts = [where[j] for j in item.joints]
            for first, second in zip(item.joints, item.joints[1:]):
                if where[second] != where[first]:
                    direction = (where[second] - where[first]) / abs(where[second] - where[first])
                    spokes[first].append(direction)
                    spokes[second].append(-direction)
            artists += ax.plot([p.real for p in pts], [p.imag for p in pts], color=colour_of[item.link],
                               lw=3.0, solid_capstyle="round", zorder=2, label="_nolegend_", gid=item.link)
        elif isinstance(item, Block):
            angle = item.angle if isinstance(item.angle, (int, float)) else float(
                solution.angle(item.angle).value[index])
            _block_symbol(ax, where[item.joint], angle, size)
    for link, through, angle, blocks in moving_guides(mechanism, solution, index):
        _moving_guide_symbol(ax, through, angle, [where[b] for b in blocks],
                             colour_of.get(link, ROLE_COLOURS["slider"]), 2.5 * size)
    hinges = np.array(list(where.values()))
    ax.plot(hinges.real, hinges.imag, "o", ms=6, mfc="white", mec="black", mew=1.2, zorder=4)
    if labels:
        offsets = dict(label_offset) if isinstance(label_offset, Mapping) else {}
        letters = labels if isinstance(labels, Mapping) else {}
        common: tuple[float, float] | None = (
            None if label_offset is None or isinstance(label_offset, Mapping) else label_offset)
        for name, p in where.items():
            fixed = offsets.get(name, common)
            offset = fixed if fixed is not None else _free_side(spokes[name])
            centred = "left" if fixed is not None else "center"
            ax.annotate(point_label(letters.get(name, name)), (p.real, p.imag), xytext=offset,
                        textcoords="offset points", fontsize=10, zorder=5, ha=centred,
                        va="baseline" if fixed is not None else "center")
    ax.set_xlabel(AXIS_X)
    ax.set_ylabel(AXIS_Y)


def annotate_angle(ax: Axes, vertex: complex, start: float, stop: float, label: str, radius: float,
                   colour: str = "0.25") -> None:
    """Mark an angle on a drawing: an arc from ``start`` to ``stop`` (rad) about ``vertex``, labelled.

    A dotted reference line is drawn along the ``start`` direction (usually the +x axis).
    """
    with covering(ax) as drawn:
        _angle_arc(ax, vertex, start, stop, label, radius, colour)
    add_description(ax, f"the angle {plain_text(label)} is marked at {point_text(vertex)}, from "
                        f"{value_text(np.degrees(start), '°')} to {value_text(np.degrees(stop), '°')}",
                    drawn.artists)


def _angle_arc(ax: Axes, vertex: complex, start: float, stop: float, label: str, radius: float,
               colour: str) -> None:
    """The artists of :func:`annotate_angle`."""
    sweep = np.linspace(start, stop, 40)
    arc = vertex + radius * np.exp(1j * sweep)
    ax.plot(arc.real, arc.imag, color=colour, lw=0.9)
    ref = vertex + 1.5 * radius * np.exp(1j * start)
    ax.plot([vertex.real, ref.real], [vertex.imag, ref.imag], color=colour, lw=0.7, ls=":")
    tip = arc[-1] - arc[-2]
    ax.annotate("", xy=(arc[-1].real, arc[-1].imag), xytext=(arc[-1].real - tip.real, arc[-1].imag - tip.imag),
                arrowprops={"arrowstyle": "->", "color": colour, "lw": 0.9})
    middle = vertex + 1.25 * radius * np.exp(1j * 0.5 * (start + stop))
    ax.text(middle.real, middle.imag, label, ha="center", va="center", fontsize=11, color=colour)


def annotate_length(ax: Axes, first: complex, second: complex, label: str, offset: float) -> None:
    """Write a length's symbol beside the segment first–second, ``offset`` m to its left."""
    middle = 0.5 * (first + second) + offset * 1j * np.exp(1j * np.angle(second - first))
    text = ax.text(middle.real, middle.imag, label, ha="center", va="center", fontsize=11)
    add_description(ax, f"the length {plain_text(label)} is written beside the segment from "
                        f"{point_text(first, '')} to {point_text(second)}", [text])


def annotate_dimension(ax: Axes, start: complex, end: complex, label: str, both: bool = True,
                       offset: float = 0.0) -> None:
    """A dimension arrow from ``start`` to ``end`` (m) with its symbol beside the middle.

    ``both`` draws a double-headed arrow (a length such as an offset e); otherwise a single
    arrow from start to end (a coordinate such as the slider's s). The label sits ``offset`` m
    to the left of the arrow (default: 4 % of its length).
    """
    arrow = ax.annotate("", xy=(end.real, end.imag), xytext=(start.real, start.imag),
                        arrowprops={"arrowstyle": "<->" if both else "->", "color": "0.2", "lw": 0.9})
    direction = np.exp(1j * np.angle(end - start))
    where = 0.5 * (start + end) + (offset or 0.06 * abs(end - start) + 0.004) * 1j * direction
    text = ax.text(where.real, where.imag, label, ha="center", va="center", fontsize=11)
    kind = "a dimension arrow" if both else "an arrow"
    add_description(ax, f"{kind} marks {plain_text(label)} from {point_text(start, '')} to "
                        f"{point_text(end)}, {value_text(abs(end - start), 'm')} long", [arrow, text])


def draw_positions(mechanism: Mechanism, solution: Solution, indices: Iterable[int] | None = None,
                   ax: Axes | None = None, paths: dict[str, PointMotion] | None = None, **draw_options: Any) -> Axes:
    """A family of positions: the mechanism drawn at several crank angles, over point paths.

    Parameters
    ----------
    mechanism, solution
        What to draw; ``solution`` needs positions only.
    indices : iterable of int, optional
        Positions to draw (default: all of the solution's).
    paths : dict, optional
        ``{label: PointMotion}`` trajectories drawn underneath, in :data:`PATH_COLOURS`,
        with a legend.
    draw_options
        Passed to :func:`draw` (``labels``, ``size``, ``guide_half_length``); labels are off
        by default.
    """
    ax = _new_axes(ax)
    if paths:
        trajectories(solution, paths, ax=ax)
        ax.legend(loc="upper right", ncol=2)
    draw_options.setdefault("labels", False)
    chosen = list(range(len(solution)) if indices is None else indices)
    with covering(ax) as drawn:
        for i in chosen:
            draw(mechanism, solution, i, ax=ax, **draw_options)
    angles = [angle_text(float(np.ravel(solution.phi)[i]), "") for i in chosen]
    add_description(ax, f"the {mechanism_name(mechanism)} drawn at {len(chosen)} crank positions, one over "
                        f"another: φ = {series(angles)}", drawn.artists)
    return ax


def _full_turn(phi: np.ndarray) -> bool:
    """True when evenly spaced crank angles cover a whole turn (the last step would close it)."""
    if np.size(phi) < 3:
        return False
    step = np.diff(phi)
    return bool(np.allclose(step, step[0]) and abs(abs(phi[-1] - phi[0] + step[0]) - 2 * np.pi) < 1e-9)


def trajectories(solution: Solution | None, points: dict[str, PointMotion] | Sequence[str], ax: Axes | None = None,
                 colours: Iterable[str] | None = None) -> Axes:
    """Draw the paths of points: named joints of the solution or given point motions.

    Parameters
    ----------
    solution : Solution or None
        The solution (positions over the crank angles); may be None when ``points`` is a dict.
        When its crank angles cover a whole turn evenly, each path is drawn closed.
    points : sequence of str or dict
        Joint names, or ``{label: PointMotion}`` (e.g. from ``solution.point_on``).
    """
    ax = _new_axes(ax)
    if not isinstance(points, dict):
        if solution is None:
            raise InvalidParameterError("solution", None, "a Solution when the points are given by name")
        points = {name: solution.point(name) for name in points}
    colours = iter(colours if colours is not None else PATH_COLOURS * 4)
    closed = solution is not None and _full_turn(solution.phi)
    for label, motion in points.items():
        x, y = (np.append(motion.x, motion.x[0]), np.append(motion.y, motion.y[0])) if closed else (motion.x, motion.y)
        ax.plot(x, y, lw=1.2, label=label, color=next(colours))
    names = series([plain_text(label) for label in points])
    add_description(ax, f"path{'s' if len(points) > 1 else ''} of {names}"
                        + (" over a whole turn of the crank" if closed else ""))
    ax.set_xlabel(AXIS_X)
    ax.set_ylabel(AXIS_Y)
    return ax


def vectors_along(motion: PointMotion, every: int = 1, ax: Axes | None = None, scale_velocity: float | None = None,
                  scale_acceleration: float | None = None, velocity: bool = True, acceleration: bool = True) -> Axes:
    """Velocity and acceleration vectors drawn at points of a trajectory.

    The vectors are scaled so that the longest is 15 % of the path's extent unless scales
    (m per m/s, m per m/s²) are given; the book states the scale in the caption.
    """
    ax = _new_axes(ax)
    sel = slice(None, None, every)
    p = motion.value[sel]
    extent = (np.ptp(motion.x) + np.ptp(motion.y)) or 1.0
    for show, vec, colour, scale in ((velocity, motion.velocity, VELOCITY_COLOUR, scale_velocity),
                                     (acceleration, motion.acceleration, ACCELERATION_COLOUR, scale_acceleration)):
        if not show or vec is None:
            continue
        v = vec[sel]
        scale = scale or 0.15 * extent / (np.max(np.abs(v)) or 1.0)
        arrows = ax.quiver(p.real, p.imag, (v * scale).real, (v * scale).imag, angles="xy", scale_units="xy",
                           scale=1.0, color=colour, width=0.004, zorder=3)
        kind, unit = ("velocity", "m/s") if colour == VELOCITY_COLOUR else ("acceleration", "m/s²")
        size = np.abs(v)
        relative = np.round(size / (np.max(size) or 1.0), 6)
        largest, smallest = int(np.argmax(relative)), int(np.argmin(relative))
        tiny = 1e-9 * float(np.max(np.abs(p)))
        sizes = (f"all {value_text(size[0], unit)} long" if relative[largest] == relative[smallest] else
                 f"the longest {value_text(size[largest], unit)} at {point_text(p[largest], 'm', tiny)}, the "
                 f"shortest {value_text(size[smallest], unit)} at {point_text(p[smallest], 'm', tiny)}")
        add_description(ax, f"{kind} vectors at {v.size} points of a path, {sizes}", [arrows])
    return ax


def _scale_text(scale: float) -> str:
    """A drawing scale as the book prints it: ``0.04``, ``$6\\cdot10^{-6}$``."""
    text = f"{scale:.3g}"
    if "e" not in text:
        return text
    mantissa, exponent = text.split("e")
    power = f"10^{{{int(exponent)}}}"
    return f"${power}$" if mantissa == "1" else f"${mantissa}\\cdot{power}$"


def vector_key(ax: Axes, scale_velocity: float | None = None, scale_acceleration: float | None = None,
               of: str = "", **legend: Any) -> Any:
    """The legend of a figure's vectors: the colour of each kind and the scale it is drawn to.

    Parameters
    ----------
    ax : Axes
        Axes whose vectors were drawn by :func:`vectors_along` with these scales.
    scale_velocity, scale_acceleration : float, optional
        The scales given to :func:`vectors_along`: m of drawing per m/s, per m/s²; a kind whose
        scale is not given gets no entry.
    of : str
        The points the vectors belong to, named in the entries (``"$P_1$, $P_2$"``), or nothing.
    **legend
        Passed to :meth:`Axes.legend` (``loc``, ``bbox_to_anchor`` …); the axes' other labelled
        artists (the paths of :func:`trajectories`) stay in the legend.

    Returns
    -------
    Legend
        The axes' legend.
    """
    whose = f" of {of}" if of else ""
    for kind, scale, colour, unit in (("velocity", scale_velocity, VELOCITY_COLOUR, "m/s"),
                                      ("acceleration", scale_acceleration, ACCELERATION_COLOUR, "m/s²")):
        if scale is None:
            continue
        if not isinstance(scale, (int, float, np.number)) or not (np.isfinite(scale) and scale > 0):
            raise InvalidParameterError(f"scale_{kind}", scale, f"a positive number of m per {unit}")
        ax.plot([], [], color=colour, label=f"{kind}{whose}: {_scale_text(scale)} m per {unit}")
    return ax.legend(**legend)


def diagram(phi: np.ndarray, curves: dict[str, np.ndarray], ylabel: str, ax: Axes | None = None, step_deg: int = 30,
            colours: Iterable[str] | None = None, angle_symbol: str = "φ") -> Axes:
    """Quantities against the crank angle (degrees, ticks every ``step_deg``).

    Parameters
    ----------
    phi : ndarray
        Crank angles (rad).
    curves : dict
        ``{label: values}``; the label goes into the legend when there is more than one.
    ylabel : str
        Axis label with its unit.
    colours : iterable of str, optional
        One colour per curve; by default :data:`PATH_COLOURS`, the colours of
        :func:`trajectories`, so a point keeps its colour from path to diagram.
    angle_symbol : str
        The crank angle's symbol on the axis, typeset as math: a Greek letter (φ, ψ, θ) or TeX
        (chapter 8 writes ψ, after its source).
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 3.2))
    deg = np.degrees(phi)
    colours = iter(colours if colours is not None else PATH_COLOURS * 4)
    for label, values in curves.items():
        ax.plot(deg, values, label=label, color=next(colours))
    lo, hi = np.floor(deg.min() / step_deg) * step_deg, np.ceil(deg.max() / step_deg) * step_deg
    ax.set_xticks(np.arange(lo, hi + 0.5 * step_deg, step_deg))
    ax.set_xlim(deg.min(), deg.max())
    ax.set_xlabel(f"crank angle ${_TEX.get(angle_symbol, angle_symbol)}$, °")
    ax.set_ylabel(ylabel)
    if len(curves) > 1:
        ax.legend()
    return ax


def link_snapshots(first: PointMotion, second: PointMotion, role: str, ax: Axes | None = None, every: int = 1,
                   paths: bool = True) -> Axes:
    """A link drawn as a bar between two of its points at several instants, faded in time order.

    Parameters
    ----------
    first, second : PointMotion
        Two points of the link (positions over time, m).
    role : str
        The link's role, for its colour (``crank``, ``rocker``, ``coupler``, ``slider`` …).
    every : int
        Draw every ``every``-th instant.
    paths : bool
        Also draw the trajectories of both points.
    """
    ax = _new_axes(ax)
    with covering(ax) as drawn:
        count = _snapshots(ax, first, second, role, every, paths)
    ends = "" if not paths else (f", with the dashed paths of its two ends "
                                 f"({extent_text(np.concatenate([first.value, second.value]))})")
    what = "block" if role == "slider" else "bar"
    add_description(ax, f"the {role} drawn as a {what} at {count} instants, fainter for the earlier ones"
                        + ends, drawn.artists)
    return ax


def _snapshots(ax: Axes, first: PointMotion, second: PointMotion, role: str, every: int, paths: bool) -> int:
    """The artists of :func:`link_snapshots`; returns how many instants it drew."""
    colour = ROLE_COLOURS.get(role, "k")
    index = np.arange(0, first.value.size, every)
    if role == "slider":  # a block that translates: draw the block, its guide and the travel
        span = (np.ptp(first.x) + np.ptp(first.y)) or 0.01
        angle = float(np.angle(second.value[0] - first.value[0]))
        _guide_symbol(ax, complex(np.mean(first.value)) - 0.06 * span * 1j * np.exp(1j * angle), angle,
                      0.7 * span, 0.05 * span)
        for rank, i in enumerate(index):
            block = Polygon(_block_corners(first.value[i], angle, 0.05 * span), closed=True, facecolor="none",
                            edgecolor=colour, lw=1.5, alpha=min(1.0, 0.35 + 0.65 * rank / max(len(index) - 1, 1)))
            ax.add_patch(block)
        centre = complex(np.mean(first.value))
        ax.set_ylim(centre.imag - 0.35 * span, centre.imag + 0.35 * span)
    else:
        for rank, i in enumerate(index):
            p, q = first.value[i], second.value[i]
            ax.plot([p.real, q.real], [p.imag, q.imag], color=colour, lw=2.5,
                    alpha=min(1.0, 0.35 + 0.65 * rank / max(len(index) - 1, 1)), solid_capstyle="round")
    if paths:
        for motion in (first, second):
            ax.plot(motion.x, motion.y, color="0.6", lw=0.8, ls="--")
    ax.set_xlabel(AXIS_X)
    ax.set_ylabel(AXIS_Y)
    return len(index)
