"""Layer 6: drawings of velocity and acceleration plans and of instant centres (chapter 10).

A plan is drawn as a course draws it: to scale, in millimetres of the drawing, from the pole ``p``
or ``π``, with the vertices lettered (``a``, ``b`` …; ``a′``, ``n2``, ``k`` …) and the scale μ
stated. Absolute vectors (from the pole) have the book's velocity or acceleration colour; relative
vectors and components have the colour of the link whose motion they describe
(:data:`mechanisms.plot.ROLE_COLOURS`): normal components dashed, Coriolis components dash-dotted.
"""

from __future__ import annotations

import dataclasses
import re
import textwrap
from typing import TYPE_CHECKING, Any, Mapping

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon
from matplotlib.text import Annotation

from ..analysis.plans import AccelerationPlan, InstantCentres, Plan, PlanStep, VelocityPlan, plan_steps
from ..core.errors import InvalidParameterError
from ..linkages.base import Block, Ground, Mechanism, Solution
from ..present.tables import MarkdownTable, markdown_table
from .describe import add_description
from .drawing import ACCELERATION_COLOUR, ROLE_COLOURS, VELOCITY_COLOUR, draw, point_label

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["LINK_ROLES", "draw_plan", "draw_plans", "draw_plan_step", "draw_plan_steps", "step_caption",
           "draw_instant_centres", "draw_centre_velocities", "vertex_label", "segment_label", "vector_label",
           "vector_table"]

LINK_ROLES = {"crank": "crank", "coupler": "coupler", "rocker": "rocker", "lever": "lever", "slider": "slider",
              "rod": "coupler"}
"""The drawing role (and so the colour) of each link of the plans."""

_STYLE = {  # kind → (line style, line width)
    "absolute": ("-", 2.2),
    "relative": ("-", 1.6),
    "tangential": ("-", 1.6),
    "sliding": ("-", 1.6),
    "normal": ("--", 1.4),
    "coriolis": ("-.", 1.6),
}


# Labels sit on a light box, so a line or an arrowhead under a label does not make it illegible.
_LABEL_BOX_PAD = 0.12
_LABEL_BOX = {"boxstyle": f"round,pad={_LABEL_BOX_PAD}", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}

_LETTER = re.compile(r"^(\D+?)(\d*)(′*)$")


def vertex_label(label: str) -> str:
    r"""A plan's vertex letter in matplotlib mathtext (and LaTeX): ``a3′`` → ``$a_3'$``, ``π`` → ``$\pi$``.

    Parameters
    ----------
    label : str
        A vertex as the plans name it (``p``, ``a``, ``s2``, ``π``, ``a′``, ``n2``, ``k`` …).

    Returns
    -------
    str
        The letter in math mode, digits as a subscript and ``′`` as a prime, as the book writes them
        ($s_2$, $a'$, $n_2$; chapter 10).
    """
    match = _LETTER.match(label)
    if match is None:
        return label
    letter, digits, primes = match.groups()
    letter = r"\pi" if letter == "π" else letter
    return f"${letter}{f'_{{{digits}}}' if digits else ''}{chr(39) * len(primes)}$"


def segment_label(tail: str, head: str) -> str:
    r"""A segment of a plan between two vertices in mathtext: ``("n2", "b′")`` → ``$n_{2}b'$``.

    Parameters
    ----------
    tail, head : str
        The vertices as the plans name them (see :func:`vertex_label`).

    Returns
    -------
    str
        The segment in math mode, as the book writes it ($pa$, $n_2b'$, $\pi a'$; chapter 10).
    """
    tail_math, head_math = vertex_label(tail).strip("$"), vertex_label(head).strip("$")
    return f"${tail_math}{' ' if tail_math.startswith(chr(92)) else ''}{head_math}$"


def vector_label(latex: str) -> str:
    r"""A plan's vector name in mathtext, the joints' digits as subscripts: ``a^{k}_{A2A3}`` → ``$a^{k}_{A_2A_3}$``.

    Parameters
    ----------
    latex : str
        The vector's name in LaTeX without dollars, as ``PlanVector.latex`` gives it.

    Returns
    -------
    str
        The name in math mode, as the book writes it ($v_{BA}$, $a^n_{BA}$, $a^k_{A_2A_3}$; chapter 10).
    """
    return "$" + re.sub(r"([A-Z])(\d+)", r"\1_{\2}", latex) + "$"


def vector_table(*plans: Plan, length_format: str = ".2f", magnitude_format: str = ".2f",
                 direction_format: str = ".1f") -> MarkdownTable:
    """Every vector of one or more plans as a Markdown table: name, segment, magnitude, length, direction.

    Parameters
    ----------
    *plans : Plan
        The plans, in order (e.g. the velocity plan, then the acceleration plan).
    length_format, magnitude_format, direction_format : str
        Format specs of the drawn length (mm), the magnitude (m/s or m/s²) and the direction (°).

    Returns
    -------
    MarkdownTable
        One row a vector, in the order of construction: its name ($v_{BA}$), its segment on the plan
        ($ab$), its magnitude, its drawn length (mm, magnitude / μ) and its direction (°,
        counter-clockwise from +x, in [0, 360)); the book's letters (chapter 10).
    """
    units = list(dict.fromkeys(plan.unit for plan in plans))       # in the order of the plans
    rows = [(vector_label(x.latex), segment_label(x.tail, x.head), x.magnitude, x.magnitude / plan.scale,
             x.direction_deg)
            for plan in plans for x in plan.vectors]
    headers = ["vector", "on the plan", f"magnitude, {' or '.join(units)}", "length, mm", "direction, °"]
    return markdown_table(headers, rows, ["", "", magnitude_format, length_format, direction_format], align="llrrr")


_DECIDED = 6
"""Decimals (of a mm of the drawing, and of a score) to which every number that places something on a
plan is rounded: positions and scores that differ only in their last bits from processor to processor
(numpy's sines, cosines and hypot differ there) give the same drawing, and equal scores stay equal."""


def _decided(z: complex) -> complex:
    """A position (mm of the drawing) rounded to :data:`_DECIDED` decimals."""
    return complex(round(z.real, _DECIDED), round(z.imag, _DECIDED))


def _drawn(plan: Plan) -> dict[str, complex]:
    """The plan's vertices in drawing coordinates (mm), rounded to :data:`_DECIDED` decimals."""
    return {label: _decided(complex(plan.drawn(label))) for label in plan.vertices}


def _arrow(ax: Axes, tail: complex, head: complex, colour: str, style: str, width: float, zorder: int = 3) -> None:
    ax.annotate("", xy=(head.real, head.imag), xytext=(tail.real, tail.imag),
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": width, "linestyle": style,
                            "shrinkA": 0, "shrinkB": 0, "mutation_scale": 12}, zorder=zorder)


def _box_distance(centre: complex, half: tuple[float, float], points: Any) -> float:
    """The distance from a text's box (centre, half width and height, mm) to the nearest of ``points``."""
    z = np.atleast_1d(np.asarray(points, dtype=complex))
    dx = np.maximum(np.abs(z.real - centre.real) - half[0], 0.0)
    dy = np.maximum(np.abs(z.imag - centre.imag) - half[1], 0.0)
    return float(np.min(np.hypot(dx, dy)))


def _boxes_distance(first: tuple[float, float, float, float], second: tuple[float, float, float, float]) -> float:
    """The gap between two boxes (left, right, bottom, top): 0 if they touch or overlap."""
    dx = max(first[0] - second[1], second[0] - first[1], 0.0)
    dy = max(first[2] - second[3], second[2] - first[3], 0.0)
    return float(np.hypot(dx, dy))


def _along(tail: complex, head: complex, a: complex, b: complex, within: float = 2.0) -> bool:
    """Whether the segment a–b runs along the line tail–head: its ends within ``within`` (mm) of it.

    Two such lines (a component on an absolute vector, or beside it) are drawn so close that the
    place of a name cannot tell them apart; the colour does.
    """
    u = (head - tail) / abs(head - tail)
    return all(abs(((z - tail) * u.conjugate()).imag) <= within for z in (a, b))


def _to_segment(point: complex, a: complex, b: complex) -> float:
    """The distance from a point to the segment a–b."""
    d = b - a
    t = 0.0 if abs(d) == 0 else min(max(((point - a) * d.conjugate()).real / abs(d) ** 2, 0.0), 1.0)
    return abs(point - (a + t * d))


def _reach(hw: float, hh: float, u: complex, clear: float) -> float:
    """How far in the direction ``u`` to put a box's centre so that the box is ``clear`` from the point."""
    low, high = 0.0, hw + hh + clear
    for _ in range(40):                    # the gap grows with the distance: bisect
        middle = 0.5 * (low + high)
        gap = np.hypot(max(middle * abs(u.real) - hw, 0.0), max(middle * abs(u.imag) - hh, 0.0))
        low, high = (middle, high) if gap < clear else (low, middle)
    return high


# An arrowhead of _arrow ("-|>", mutation scale 12): 0.4 × 12 pt long, 0.2 × 12 pt either side of the line.
_HEAD_LENGTH, _HEAD_HALF_WIDTH = 4.8, 2.4
# The gap (in points, as a fraction of the font size) every letter keeps from every other letter, every
# vertex and every arrowhead, and the gap beyond which a position counts as free as any.
_GAP, _FREE = 0.25, 0.8


class _Placer:
    """Places the letters of a plan clear of each other, of the vertices and of the arrowheads.

    Sizes are in mm of the drawing: each text is measured as drawn, its white box included. Every
    candidate position is scored: a letter nearer than a quarter of its font size (its gap) to
    another letter, a vertex or an arrowhead is penalised as much as one covering them; among the
    others, the farther a letter is from the nearest of them (up to 1.2 times its font size), the
    better, and the less line it covers; the edge of the axes bounds it. The candidate with the
    lowest score wins.
    """

    def __init__(self, ax: Axes, dots: list[complex], segments: list[tuple[complex, complex]],
                 widths: list[float] | None = None):
        self.ax, self.dots, self.segments = ax, dots, segments
        ax.apply_aspect()
        width = ax.get_window_extent().width
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        self.mm_per_pixel = (x1 - x0) / width if width > 0 else 1.0
        self.mm_per_point = self.mm_per_pixel * ax.figure.dpi / 72
        self.limits = (x0, x1, y0, y1)
        self.boxes: list[tuple[float, float, float, float]] = []
        self.radius = 3.5 / 2 * self.mm_per_point              # a vertex dot's radius (ms = 3.5 pt)
        self.dot = 1.2 * self.radius                            # vertices closer than this are one
        self.heads = self._arrowheads(widths or [2.0] * len(segments))

    def _arrowheads(self, widths: list[float]) -> np.ndarray:
        """Points on the outline of every vector's arrowhead (a triangle at its head, line width added)."""
        samples = [np.zeros(0, dtype=complex)]
        s = np.linspace(0.0, 1.0, 9)
        for (tail, head), width in zip(self.segments, widths):
            along = (head - tail) / abs(head - tail)
            pad = 0.5 * width * self.mm_per_point
            back = head - (_HEAD_LENGTH * self.mm_per_point + pad) * along
            side = (_HEAD_HALF_WIDTH * self.mm_per_point + pad) * 1j * along
            corners = [head + pad * along, back + side, back - side]
            for k in range(3):
                samples.append(corners[k] + s * (corners[(k + 1) % 3] - corners[k]))
        return np.concatenate(samples)

    def half_size(self, text: Any) -> tuple[float, float]:
        """Half the width and height (mm) of a text's white box."""
        box = text.get_window_extent()
        pad = _LABEL_BOX_PAD * text.get_fontsize() * self.ax.figure.dpi / 72
        return ((box.width / 2 + pad) * self.mm_per_pixel, (box.height / 2 + pad) * self.mm_per_pixel)

    def clearance(self, centre: complex, half: tuple[float, float],
                  owner: complex | None = None) -> tuple[float, float]:
        """The gaps (mm) from a text's box to the nearest thing it must not touch.

        Returns the gap to the nearest letter, vertex or arrowhead, and the same without the letter's own
        vertex (``owner``), which a letter stays beside.
        """
        hw, hh = half
        box = (centre.real - hw, centre.real + hw, centre.imag - hh, centre.imag + hh)
        gaps = [_boxes_distance(box, other) for other in self.boxes]
        if len(self.heads):
            gaps.append(_box_distance(centre, half, self.heads))
        own = np.inf
        for dot in self.dots:
            gap = _box_distance(centre, half, dot) - self.radius
            if owner is not None and abs(dot - owner) <= self.dot:
                own = min(own, gap)
            else:
                gaps.append(gap)
        others = min(gaps, default=np.inf)
        return min(others, own), others

    def cost(self, centre: complex, half: tuple[float, float], size: float, skip: int | None = None,
             owner: complex | None = None) -> float:
        hw, hh = half
        left, right, bottom, top = centre.real - hw, centre.real + hw, centre.imag - hh, centre.imag + hh
        area = 4 * hw * hh
        total = 0.0
        for l2, r2, b2, t2 in self.boxes:          # letters already placed: never on each other
            overlap = max(0.0, min(right, r2) - max(left, l2)) * max(0.0, min(top, t2) - max(bottom, b2))
            total += 200.0 * overlap / area
        for dot in self.dots:                      # vertices stay visible
            if _box_distance(centre, half, dot) < self.radius:
                total += 60.0
        nearest, others = self.clearance(centre, half, owner)
        gap, free = _GAP * size * self.mm_per_point, _FREE * size * self.mm_per_point
        if nearest < 0.999 * gap:                  # touching a letter, a vertex or an arrowhead
            total += 40.0 + 20.0 * (gap - max(nearest, 0.0)) / gap
        total += 1.0 * max(free - others, 0.0) / free      # the farther from the others the better
        for k, (a, b) in enumerate(self.segments):  # lines under a letter: the length covered
            if k == skip:
                continue
            t = np.linspace(0.0, 1.0, 41)
            z = a + t * (b - a)
            inside = (z.real > left) & (z.real < right) & (z.imag > bottom) & (z.imag < top)
            total += 3.0 * inside.mean() * abs(b - a) / hh
        total += self.misleading(centre, half, skip, owner)
        x0, x1, y0, y1 = self.limits               # inside the axes
        outside = max(0.0, x0 - left) + max(0.0, right - x1) + max(0.0, y0 - bottom) + max(0.0, top - y1)
        return total + 50.0 * outside / hh

    def misleading(self, centre: complex, half: tuple[float, float], skip: int | None,
                   owner: complex | None) -> float:
        """A penalty for a letter nearer to another vertex, or a vector's name nearer to another vector.

        A reader takes a letter for the name of the vertex nearest to its middle, and a vector's name
        for that of the line nearest to its middle; ``owner`` is the letter's own vertex, ``skip`` the
        index of the named vector. A letter's own vertex must be the nearest by 1 mm of the drawing; a
        vector's own line must be the nearest by half a millimetre of all vectors that do not run along
        it (within 2 mm of its line: a component on an absolute vector cannot be told from it by its
        place), and the name must not lie across any of those.
        """
        if owner is not None:
            others = [abs(centre - dot) for dot in self.dots if abs(dot - owner) > self.dot]
            return 25.0 if others and min(others) < abs(centre - owner) + 1.0 else 0.0
        if skip is None:
            return 0.0
        tail, head = self.segments[skip]
        rivals = [(a, b) for k, (a, b) in enumerate(self.segments) if k != skip and not _along(tail, head, a, b)]
        if not rivals:
            return 0.0
        own = _to_segment(centre, tail, head)
        penalty = 25.0 if min(_to_segment(centre, a, b) for a, b in rivals) < own + 0.5 else 0.0
        t = np.linspace(0.0, 1.0, 41)
        for a, b in rivals:
            if _box_distance(centre, half, a + t * (b - a)) == 0.0:      # a name across another vector
                penalty += 10.0
        return penalty

    def choices(self, text: Any, candidates: list[tuple[complex, float]], skip: int | None = None,
                owner: complex | None = None) -> int:
        """How many of the candidates are nearly as good as the best, before any letter is placed."""
        half, size = self.half_size(text), text.get_fontsize()
        scores = np.array([self.score(c, p, half, size, skip, owner) for c, p in candidates])
        return int(np.sum(scores <= scores.min() + 1.5))

    def score(self, centre: complex, preference: float, half: tuple[float, float], size: float,
              skip: int | None, owner: complex | None) -> float:
        """A candidate's cost plus its preference, rounded to :data:`_DECIDED` decimals: candidates that
        tie in exact arithmetic (symmetric places) tie here too, and the first of them wins everywhere."""
        return round(self.cost(centre, half, size, skip, owner) + preference, _DECIDED)

    def place(self, text: Any, candidates: list[tuple[complex, float]], skip: int | None = None,
              optional: bool = False, owner: complex | None = None) -> None:
        """Move ``text`` to the best of the candidate centres (each with its own penalty).

        An ``optional`` text (a vector's name) that would touch a letter, a vertex or an arrowhead
        wherever it went is removed instead.
        """
        half, size = self.half_size(text), text.get_fontsize()
        best, score = min(((c, self.score(c, p, half, size, skip, owner)) for c, p in candidates),
                          key=lambda cs: cs[1])
        if optional and score >= 40.0:
            text.remove()
            return
        text.set_position((best.real, best.imag))
        self.boxes.append((best.real - half[0], best.real + half[0], best.imag - half[1], best.imag + half[1]))

    def around(self, text: Any, point: complex, away: complex) -> list[tuple[complex, float]]:
        """Candidate centres for a vertex's letter: all round the vertex, clear of its dot; ``away`` preferred."""
        hw, hh = self.half_size(text)
        clear = self.radius + _GAP * text.get_fontsize() * self.mm_per_point
        out = []
        for angle in np.radians(np.arange(0.0, 360.0, 15.0)):
            u = complex(np.cos(angle), np.sin(angle))
            reach = _reach(hw, hh, u, clear)
            for extra in (0.0, 0.6, 1.2):
                preference = 0.6 * (1.0 - (u * away.conjugate()).real) + 1.5 * extra
                out.append((_decided(point + (reach + extra * hh) * u), preference))
        return out

    def beside(self, text: Any, tail: complex, head: complex) -> list[tuple[complex, float]]:
        """Candidate centres for a vector's name: beside it, near its middle, the left side preferred."""
        hw, hh = self.half_size(text)
        along = (head - tail) / abs(head - tail)
        normal = 1j * along
        clear = hw * abs(normal.real) + hh * abs(normal.imag) + 0.3 * hh
        out = []
        for fraction in np.arange(0.1, 0.91, 0.05):
            for side in (1.0, -1.0):
                for extra in (-0.2, 0.0, 0.2, 0.4, 0.8, 1.2, 1.6):
                    preference = 2.0 * abs(fraction - 0.5) + (0.0 if side > 0 else 0.3) + 1.5 * max(extra, 0.0)
                    out.append((_decided(tail + fraction * (head - tail) + side * (clear + extra * hh) * normal),
                                preference))
        return out


def _limits(plan: Plan, label_offset: float = 3.5) -> tuple[tuple[float, float], tuple[float, float]]:
    """The x and y limits (mm) of a plan's axes: its vertices with a margin for the letters."""
    values = np.array(list(_drawn(plan).values()))
    span = max(np.ptp(values.real), np.ptp(values.imag), 10.0)
    margin = 0.12 * span + label_offset
    return ((values.real.min() - margin, values.real.max() + margin),
            (values.imag.min() - margin, values.imag.max() + margin))


def draw_plan(plan: Plan, ax: Axes | None = None, names: bool = True, images: bool = True, title: str | None = None,
              label_offset: float = 3.5) -> Axes:
    r"""Draw a velocity or acceleration plan to scale, in mm of the drawing.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan
        From :func:`mechanisms.analysis.plans.velocity_plan` or ``acceleration_plan``.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    names : bool
        Write the names of the relative vectors and components beside them ($v_{BA}$, $a^n_{BA}$ …),
        except on vectors too short to carry one.
    images : bool
        Shade the image of every link that has three or more points on the plan.
    title : str, optional
        The title; by default "velocity plan" or "acceleration plan" with the crank angle.
    label_offset : float
        Spacing of the letters (mm of the drawing): vertices closer than 0.8 of it share one letter
        ("$b'$, $n_4$"), and vectors shorter than twice it carry no name.

    Returns
    -------
    matplotlib Axes
        Axes in mm, equal aspect, with the scale stated in the lower right corner.

    Notes
    -----
    The letters are the book's (chapter 10) in mathtext: $p$, $a$, $s_2$ on a velocity plan, $\pi$,
    $a'$, $n_2$, $k$ on an acceleration plan. Each letter (and each vector's name) is tried at
    positions round its vertex (beside its vector) and put where it keeps a gap of a quarter of its
    font size from every other letter, every vertex and every arrowhead, farther if it can (up to
    0.8 of its font size), covers as little of the vectors as possible and is taken for no other
    vertex or vector (a name's middle is nearer its own vector than any other it does not run along,
    and lies across none), preferably away from the plan's middle (the pole's) or on the left of its
    vector. The names choose first, since they are bound to their vectors, those with the fewest good
    positions (beside a short vector in a crowd) before the others; then the letters, in the same
    order. A name that cannot keep its gap anywhere is left out.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 5.0))
    colour = VELOCITY_COLOUR if plan.quantity == "velocity" else ACCELERATION_COLOUR
    drawn = _drawn(plan)
    if images:
        for link, members in plan.images.items():
            corners = [drawn[plan.points[n]] for n in members]
            if len(corners) >= 3:
                ax.add_patch(Polygon([(c.real, c.imag) for c in corners], closed=True, zorder=1, alpha=0.15,
                                     facecolor=ROLE_COLOURS[LINK_ROLES.get(link, "coupler")], edgecolor="none"))
    segments: list[tuple[complex, complex]] = []
    widths: list[float] = []
    named = []
    for vector in plan.vectors:
        tail, head = drawn[vector.tail], drawn[vector.head]
        if abs(head - tail) < 1e-9:
            continue
        style, width = _STYLE[vector.kind]
        shade = colour if vector.kind == "absolute" else ROLE_COLOURS[LINK_ROLES.get(vector.link, "coupler")]
        # a component is drawn over the (wider) absolute vector it may lie along, so both show
        _arrow(ax, tail, head, shade, style, width, 3 if vector.kind == "absolute" else 4)
        segments.append((tail, head))
        widths.append(width)
        if names and vector.kind != "absolute" and abs(head - tail) >= 2.0 * label_offset:
            named.append((len(segments) - 1, vector, shade))
    values = np.array(list(drawn.values()))
    (x0, x1), (y0, y1) = _limits(plan, label_offset)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    # the vertices; vertices closer than the letters' size share one label, "a, b"
    groups: list[list[str]] = []
    for label, point in drawn.items():
        ax.plot(point.real, point.imag, "o", ms=3.5, color="black", zorder=6)
        for group in groups:
            if abs(drawn[group[0]] - point) < 0.8 * label_offset:
                group.append(label)
                break
        else:
            groups.append([label])
    symbol = r"$\mu_v$" if plan.quantity == "velocity" else r"$\mu_a$"
    scale = ax.text(0.98, 0.02, f"{symbol} = {plan.scale:g} ({plan.unit})/mm", transform=ax.transAxes,
                    ha="right", va="bottom", fontsize=9,
                    bbox={"facecolor": "white", "edgecolor": "0.7", "boxstyle": "round"})
    placer = _Placer(ax, [complex(v) for v in values], segments, widths)
    corner = scale.get_window_extent().transformed(ax.transData.inverted())   # no letter on the scale
    placer.boxes.append((corner.x0 - 1.0, corner.x1 + 1.0, corner.y0 - 1.0, corner.y1 + 1.0))
    centre = complex(np.mean(values))
    where = {tuple(group): _decided(complex(np.mean([drawn[label] for label in group]))) for group in groups}

    def crowding(group: list[str]) -> float:     # the most crowded letters choose first
        others = [abs(where[tuple(group)] - z) for g, z in where.items() if g != tuple(group)]
        return round(min(others, default=np.inf), _DECIDED)

    jobs: list[tuple[Any, list[tuple[complex, float]], int | None, complex | None]] = []
    # each: the text, its candidates, the index of its vector (a name), its vertex (a letter)
    for group in sorted(groups, key=crowding):
        point = where[tuple(group)]
        away = point - centre if plan.pole in group else point
        away = away / abs(away) if abs(away) > 1e-9 else 1j
        text = ax.text(point.real, point.imag, ", ".join(vertex_label(label) for label in group), fontsize=11,
                       ha="center", va="center", zorder=7, bbox=_LABEL_BOX)
        jobs.append((text, placer.around(text, point, away), None, point))
    for index, vector, shade in named:
        tail, head = drawn[vector.tail], drawn[vector.head]
        name = vector_label(vector.latex)
        size = 12 if re.search(r"[A-Z]_\{\d", name) else 10     # a subscript's subscript needs the larger size
        text = ax.text(0.0, 0.0, name, fontsize=size, color=shade, ha="center", va="center", zorder=5,
                       bbox=_LABEL_BOX)
        jobs.append((text, placer.beside(text, tail, head), index, None))
    # the names first (a letter can go all round its vertex, a name only beside its vector), each kind
    # in the order of its fewest good places (a name beside a short vector in a crowd first)
    for text, candidates, skip, owner in sorted(jobs, key=lambda job: (job[2] is None, placer.choices(*job))):
        placer.place(text, candidates, skip=skip, optional=skip is not None, owner=owner)
    ax.set_xlabel("mm of the drawing")
    ax.set_ylabel("mm of the drawing")
    what = "velocity plan" if plan.quantity == "velocity" else "acceleration plan"
    ax.set_title(title if title is not None else rf"{what}, $\varphi$ = {np.degrees(plan.phi) % 360:.4g}°")
    return ax


def draw_plans(mechanism: Mechanism, solution: Solution, velocity: VelocityPlan,
               acceleration: AccelerationPlan | None = None, index: int = 0,
               figsize: tuple[float, float] | None = None,
               label_offset: Mapping[str, tuple[float, float]] | None = None) -> tuple[Figure, list[Axes]]:
    """The mechanism at a position beside its velocity plan (and its acceleration plan).

    Parameters
    ----------
    label_offset : dict, optional
        ``{joint: (dx, dy)}`` in points, for joint letters of the drawing that should sit elsewhere
        than :func:`~mechanisms.plot.draw` puts them (off a block or a guide's hatching).

    Returns
    -------
    (figure, axes)
        The mechanism (m) on top; below it the velocity plan and the acceleration plan (mm of the
        drawing).
    """
    count = 1 if acceleration is None else 2
    fig = plt.figure(figsize=figsize or (4.6 * count + 1.0, 7.6))
    # a wide plan beside a tall one gets the more width: each plan's share grows with the square root
    # of its axes' width-to-height ratio, so neither is drawn much smaller than the other
    shapes = [_limits(plan) for plan in (velocity, acceleration) if plan is not None]
    ratios = [np.sqrt((x1 - x0) / (y1 - y0)) for (x0, x1), (y0, y1) in shapes]
    grid = fig.add_gridspec(2, count, height_ratios=(1.0, 1.7), width_ratios=ratios)
    axes = [fig.add_subplot(grid[0, :])] + [fig.add_subplot(grid[1, k]) for k in range(count)]
    draw(mechanism, solution, index=index, ax=axes[0], label_offset=label_offset)
    joints = {velocity.positions[name] for name in solution.point_names if name in velocity.positions}
    for name, position in velocity.positions.items():
        # the named extra points of links; not a link's point under a block (A3 under A2), which is a joint
        if name not in solution.point_names and position not in joints:
            axes[0].plot(position.real, position.imag, "o", ms=4, color=ROLE_COLOURS["point"], zorder=5)
            axes[0].annotate(point_label(name), (position.real, position.imag),
                             xytext=(5, -12), textcoords="offset points")
    axes[0].set_title(rf"the mechanism at $\varphi$ = {np.degrees(velocity.phi) % 360:.4g}°")
    draw_plan(velocity, ax=axes[1], title="velocity plan")
    if acceleration is not None:
        draw_plan(acceleration, ax=axes[2], title="acceleration plan")
    fig.tight_layout()
    _keep_letters_inside(axes[0])       # a joint's letter neither on the frame nor in the title
    fig.tight_layout()
    _keep_letters_inside(axes[0])
    return fig, axes


def step_caption(plan: Plan, step: PlanStep) -> str:
    r"""What a step of a plan's construction does, in words, with the book's letters in mathtext.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan
    step : PlanStep
        One of :func:`mechanisms.analysis.plans.plan_steps` of the plan.

    Returns
    -------
    str
        For a vector known whole, "from $p$ draw $v_A$, to $a$" (or "draw $a^k_{A_2A_3}$ to end at
        $a'$: it starts at $k$"); for a point of a link found by proportion, "$s_2$ by the image of its
        link; draw $v_{S_2}$"; for an intersection, "the lines of $v_{BA}$ through $a$ and of $v_B$
        through $p$ meet at $b$".
    """
    vectors = {v.name: v for v in plan.vectors}
    found = vertex_label(step.vertex)
    if step.lines:
        parts = [f"of {vector_label(vectors[name].latex)} through {vertex_label(through)}"
                 for through, _, name in step.lines]
        return "the lines " + " and ".join(parts) + f" meet at {found}"
    first = vectors[step.vectors[0]]
    start = first.tail if first.head == step.vertex else first.head
    if first.head != step.vertex:
        return f"draw {vector_label(first.latex)} to end at {vertex_label(start)}: it starts at {found}"
    if all(vectors[name].kind == "absolute" for name in step.vectors) and first is not plan.vectors[0]:
        return f"{found} by the image of its link; draw {vector_label(first.latex)}"
    return f"from {vertex_label(start)} draw {vector_label(first.latex)}, to {found}"


def _partial(plan: Plan, steps: tuple[PlanStep, ...], upto: int) -> Plan:
    """The plan as drawn after its first ``upto`` steps: their vertices and vectors only."""
    labels = {plan.pole} | {s.vertex for s in steps[:upto]}
    names = {name for s in steps[:upto] for name in s.vectors}
    points = {point: label for point, label in plan.points.items() if label in labels}
    images = {link: members for link, members in plan.images.items()
              if all(plan.points[m] in labels for m in members)}
    return dataclasses.replace(plan, vertices={k: v for k, v in plan.vertices.items() if k in labels},
                               points=points, vectors=tuple(v for v in plan.vectors if v.name in names),
                               equations=(), images=images)


def draw_plan_step(plan: Plan, step: int, ax: Axes | None = None, caption: bool = True,
                   label_offset: float = 3.5) -> Axes:
    r"""Draw a plan as it stands after ``step`` steps of its construction, with that step's lines.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan
        From :func:`mechanisms.analysis.plans.velocity_plan` or ``acceleration_plan``.
    step : int
        How many steps of :func:`mechanisms.analysis.plans.plan_steps` are done, 1 … their number.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    caption : bool
        Title the panel "step k: …" with :func:`step_caption`; otherwise "step k".
    label_offset : float
        As for :func:`draw_plan`.

    Returns
    -------
    matplotlib Axes
        In mm of the drawing, with the limits of the finished plan, so that the panels of a sequence
        share one frame: the vectors of the steps done, drawn as :func:`draw_plan` draws them; the
        vertex of this step ringed; and, when it is an intersection, the lines intersected, dotted,
        across the whole panel.

    Raises
    ------
    InvalidParameterError
        ``step`` is not an integer from 1 to the number of steps.
    """
    steps = plan_steps(plan)
    if isinstance(step, bool) or not isinstance(step, (int, np.integer)) or not 1 <= step <= len(steps):
        raise InvalidParameterError("step", step, f"a step of the construction, 1 … {len(steps)}")
    current = steps[step - 1]
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 5.0))
    text = step_caption(plan, current)
    title = f"step {step}: {text}" if caption else f"step {step}"
    draw_plan(_partial(plan, steps, step), ax=ax, title="\n".join(textwrap.wrap(title, 40)),
              label_offset=label_offset)
    (x0, x1), (y0, y1) = _limits(plan, label_offset)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    reach = 2.0 * max(x1 - x0, y1 - y0)
    for through, direction, _ in current.lines:
        z = plan.drawn(through)
        a, b = z - reach * direction, z + reach * direction
        ax.plot([a.real, b.real], [a.imag, b.imag], ls=":", lw=1.3, color="0.3", zorder=2)
    found = plan.drawn(current.vertex)
    ax.plot(found.real, found.imag, "o", ms=11, mfc="none", mec="black", mew=1.2, zorder=6)
    ax.title.set_fontsize(11)
    add_description(ax, f"Step {step} of the construction of the {plan.quantity} plan: {text}.")
    return ax


def draw_plan_steps(plan: Plan, columns: int = 2, panel: float = 3.5) -> tuple[Figure, list[Axes]]:
    """Every step of a plan's construction, one panel per step (:func:`draw_plan_step`), in a grid.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan
    columns : int
        Panels per row (1 … 3). Two panels of 3.5 in make a figure of 7 in, which a page of the book
        shows at about its natural size, so that the letters stay as large as the text.
    panel : float
        Width of a panel, inches; the height follows the plan's shape.

    Returns
    -------
    (figure, axes)
        The axes of the steps, in order; unused cells of the grid are removed.
    """
    if isinstance(columns, bool) or not isinstance(columns, (int, np.integer)) or not 1 <= columns <= 3:
        raise InvalidParameterError("columns", columns, "1, 2 or 3 panels per row")
    if not (isinstance(panel, (int, float)) and np.isfinite(panel) and panel > 0):
        raise InvalidParameterError("panel", panel, "a panel width > 0, inches")
    count = len(plan_steps(plan))
    rows = -(-count // columns)
    (x0, x1), (y0, y1) = _limits(plan)
    height = panel * min(max((y1 - y0) / (x1 - x0), 0.5), 1.6) + 0.9
    fig, grid = plt.subplots(rows, columns, figsize=(panel * columns, height * rows), squeeze=False)
    axes = list(grid.ravel())
    for k, ax in enumerate(axes[:count], start=1):
        draw_plan_step(plan, k, ax=ax)
    for ax in axes[count:]:
        fig.delaxes(ax)
    fig.tight_layout()
    return fig, axes[:count]


def _keep_letters_inside(ax: Axes, pad: float = 3.0) -> None:
    """Widen the limits of a drawing until every text on it lies ``pad`` points inside its frame."""
    renderer = ax.figure.canvas.get_renderer()   # type: ignore[attr-defined]
    pad_pixels = pad * ax.figure.dpi / 72
    for _ in range(4):
        ax.apply_aspect()
        frame = ax.get_window_extent(renderer)
        boxes = [t.get_window_extent(renderer) for t in ax.texts if t.get_visible() and t.get_text()]
        if not boxes:
            return
        left = max(frame.x0 + pad_pixels - min(b.x0 for b in boxes), 0.0)
        right = max(max(b.x1 for b in boxes) - frame.x1 + pad_pixels, 0.0)
        bottom = max(frame.y0 + pad_pixels - min(b.y0 for b in boxes), 0.0)
        top = max(max(b.y1 for b in boxes) - frame.y1 + pad_pixels, 0.0)
        if left + right + bottom + top < 0.5:
            return
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        per_x, per_y = (x1 - x0) / frame.width, (y1 - y0) / frame.height
        ax.set_xlim(x0 - 1.2 * left * per_x, x1 + 1.2 * right * per_x)
        ax.set_ylim(y0 - 1.2 * bottom * per_y, y1 + 1.2 * top * per_y)


def _extend(ax: Axes, first: complex, second: complex, beyond: float = 0.15, label: str = "_nolegend_") -> None:
    """A thin dotted line through two points, a little beyond both."""
    d = second - first
    a, b = first - beyond * d, second + beyond * d
    ax.plot([a.real, b.real], [a.imag, b.imag], ls=":", lw=1.0, color="0.45", zorder=1, label=label)


def _free_directions(occupied: list[complex], preferred: complex = 1j) -> list[complex]:
    """The 24 unit directions, those farthest in angle from every occupied direction first.

    ``occupied`` are the directions of the lines through a point; ties go to the direction nearest
    ``preferred``.
    """
    units = [d / abs(d) for d in occupied if abs(d) > 0]
    scored = []
    for angle in np.radians(np.arange(0.0, 360.0, 15.0)):
        u = complex(np.cos(angle), np.sin(angle))
        gap = min((abs(np.angle(u * d.conjugate())) for d in units), default=np.pi)
        scored.append((round(-(gap + 0.05 * (u * preferred.conjugate()).real), _DECIDED), angle, u))
    return [u for _, _, u in sorted(scored)]


class _Letters:
    """Writes letters beside points: in a free direction, over as little line as can be, on no earlier letter.

    The lines are those on the axes when it is made (bars, Kennedy's lines, rays) and the arrows of
    annotations, sampled in display coordinates.
    """

    def __init__(self, ax: Axes):
        self.ax = ax
        ax.apply_aspect()
        self.renderer = ax.figure.canvas.get_renderer()   # type: ignore[attr-defined]
        self.boxes: list[Any] = []
        samples = []
        t = np.linspace(0.0, 1.0, 60)[:, None]
        for line in ax.lines:
            xy = np.column_stack([np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)])
            for a, b in zip(xy[:-1], xy[1:]):
                samples.append(a + t * (b - a))
        for text in ax.texts:
            if isinstance(text, Annotation) and text.arrow_patch is not None:
                head = np.array(text.xy, float)
                tail = np.array(text.xyann, float) if text.anncoords == "data" else head
                samples.append(tail + t * (head - tail))
        points = np.concatenate(samples) if samples else np.zeros((0, 2))
        self.samples = ax.transData.transform(points) if len(points) else points

    def covered(self, box: Any) -> int:
        """How many sampled points of lines lie under a box (display coordinates)."""
        if not len(self.samples):
            return 0
        x, y = self.samples[:, 0], self.samples[:, 1]
        return int(np.sum((x > box.x0) & (x < box.x1) & (y > box.y0) & (y < box.y1)))

    def write(self, point: complex, text: str, directions: list[complex], distance: float, **style: Any) -> None:
        """Of the first directions, keep the one over the least line whose letter overlaps no letter written."""
        best: tuple[float, complex] | None = None
        for rank, direction in enumerate(directions[:12]):
            label = self._label(point, text, direction, distance, **style)
            box = label.get_window_extent(self.renderer).expanded(1.05, 1.1)
            label.remove()
            if any(box.overlaps(other) for other in self.boxes):
                continue
            score = self.covered(box.padded(4.0)) + 0.5 * rank
            if best is None or score < best[0]:
                best = (score, direction)
        direction = directions[0] if best is None else best[1]
        label = self._label(point, text, direction, distance, **style)
        self.boxes.append(label.get_window_extent(self.renderer).expanded(1.05, 1.1))

    def _label(self, point: complex, text: str, direction: complex, distance: float, **style: Any) -> Any:
        ha = "left" if direction.real > 0.35 else "right" if direction.real < -0.35 else "center"
        va = "bottom" if direction.imag > 0.35 else "top" if direction.imag < -0.35 else "center"
        return self.ax.annotate(text, (point.real, point.imag), textcoords="offset points",
                                xytext=(distance * direction.real, distance * direction.imag),
                                ha=ha, va=va, bbox=_LABEL_BOX, **style)


def _key(ax: Axes) -> None:
    """The key of the line styles, below the axes, where it covers nothing."""
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=9, frameon=False)


def draw_instant_centres(mechanism: Mechanism, solution: Solution, centres: InstantCentres, index: int = 0,
                         ax: Axes | None = None, lines: bool = True, arrow_length: float | None = None,
                         legend: bool = True) -> Axes:
    """The mechanism with all its instant centres P_ij, and Kennedy's lines that locate the others (P02 and P13 of a four-bar).

    Parameters
    ----------
    mechanism, solution, index
        The mechanism at one crank position.
    centres : InstantCentres
        From :func:`mechanisms.analysis.plans.instant_centres` at that position.
    lines : bool
        Draw (dotted) the lines of Kennedy's theorem through the centres that locate the centres found by
        it (``centres.lines``: P02 and P13 of a four-bar).
    arrow_length : float, optional
        Length (m) of the arrows that point to centres at infinity.
    legend : bool
        Give the dotted lines a key.

    Returns
    -------
    matplotlib Axes

    Notes
    -----
    A joint is lettered with its centre ("$A = P_{12}$"); the centres that are not joints (found by
    Kennedy's theorem or from the velocities) are stars. Each letter is set in the direction, from
    its point, farthest from the lines that pass through the point (bars, Kennedy's lines, the frame's
    support below a pivot).
    """
    ax = draw(mechanism, solution, index=index, ax=ax, labels=False)
    finite = centres.finite
    every = np.array(list(finite.values()) + list(centres.positions.values()))
    span = max(np.ptp(every.real), np.ptp(every.imag))
    arrow_length = arrow_length or 0.12 * span
    if lines:
        first = True
        for target, ways in centres.lines.items():
            if target not in finite:
                continue
            for pair in (p for way in ways for p in way):
                label = "lines of Kennedy's theorem" if first else "_nolegend_"
                first = False
                if pair in finite:
                    _extend(ax, finite[pair], finite[target], label=label)
                else:  # a centre at infinity: the line through the target in its direction
                    d = centres.infinite[pair] * 0.6 * span
                    _extend(ax, finite[target] - d, finite[target] + d, 0.0, label=label)
    scheme = mechanism.scheme()
    fixed = {item.joint for item in scheme if isinstance(item, Ground)}
    sliding = {item.joint: item.angle for item in scheme if isinstance(item, Block)
               and isinstance(item.angle, (int, float))}      # a block on a fixed guide
    names = {pair: name for name, where in centres.positions.items() for pair, point in finite.items()
             if abs(point - where) < 1e-12 * span}
    margin = 0.12 * span
    ax.set_xlim(every.real.min() - margin, every.real.max() + margin)
    ax.set_ylim(every.imag.min() - margin, every.imag.max() + margin)
    letters = _Letters(ax)
    for (i, j), point in sorted(finite.items(), key=lambda item: item[0] in names):   # stars first
        occupied = [q - point for q in finite.values() if abs(q - point) > 1e-12 * span]
        occupied += [-d for d in occupied]
        occupied += [d for d in centres.infinite.values()] + [-d for d in centres.infinite.values()]
        name = names.get((i, j))
        if name in fixed:
            occupied += [-1j, -0.6 - 1j, 0.6 - 1j]      # the pivot's support, below it
        if name in sliding:                             # the guide, its hatching below, the block
            along = complex(np.cos(sliding[name]), np.sin(sliding[name]))
            occupied += [along, -along, -1j * along, 0.5 * along - 1j * along, -0.5 * along - 1j * along]
        if name is None:
            ax.plot(point.real, point.imag, marker="*", ms=12, color=ROLE_COLOURS["point"], mec="black", zorder=6)
        text = f"$P_{{{i}{j}}}$" if name is None else f"${name} = P_{{{i}{j}}}$"
        distance = 14.0 if name in sliding else 8.0 if name is None else 6.0
        letters.write(point, text, _free_directions(occupied), distance, fontsize=10,
                      color="black" if name else "0.2", zorder=7)
    for (i, j), direction in centres.infinite.items():
        # from the joint of the sliding pair (else the joint B), an arrow towards the centre at infinity
        joint = centres.joints.get((i, j), "B")
        start = centres.positions.get(joint, centres.positions.get("B", 0j))
        end = start + arrow_length * direction
        ax.annotate("", xy=(end.real, end.imag), xytext=(start.real, start.imag),
                    arrowprops={"arrowstyle": "->", "color": "0.3", "lw": 1.0, "linestyle": "--"})
        letters.write(end, f"$P_{{{i}{j}}}$ at ∞", [direction, direction * 1j, -direction * 1j], 4.0,
                      fontsize=10, color="0.2", zorder=7)
    if legend and lines:
        _key(ax)
    return ax


def draw_centre_velocities(ax: Axes, centre: complex, positions: Mapping[str, complex],
                           velocities: Mapping[str, complex], scale: float, centre_label: str = "the centre",
                           legend: bool = True) -> Axes:
    """Velocities of a link's points drawn at the points, with the rays from the link's instant centre.

    Parameters
    ----------
    ax : matplotlib Axes
        A drawing of the mechanism (m).
    centre : complex
        The instant centre (m).
    positions, velocities : dict
        Name → position (m) and velocity (m/s) of each point.
    scale : float
        m of the drawing per m/s; the key states it.
    centre_label : str
        The centre's name in the key (``"$P_{02}$"``).
    legend : bool
        Give the rays and the arrows a key (with the lines already labelled on the axes).

    Returns
    -------
    matplotlib Axes
    """
    for k, (name, point) in enumerate(positions.items()):
        ax.plot([centre.real, point.real], [centre.imag, point.imag], color="0.55", lw=0.9, ls="--", zorder=1,
                label=f"rays from {centre_label}" if k == 0 else "_nolegend_")
        tip = point + scale * velocities[name]
        _arrow(ax, point, tip, VELOCITY_COLOUR, "-", 2.0, zorder=5)
    if legend:
        ax.plot([], [], color=VELOCITY_COLOUR, lw=2.0, marker=">", markevery=[-1],
                label=f"velocities, 1 m/s drawn as {scale:g} m")
        _key(ax)
    return ax
