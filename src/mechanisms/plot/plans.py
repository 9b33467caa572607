"""Layer 6: drawings of velocity and acceleration plans and of instant centres (chapter 10).

A plan is drawn as a course draws it: to scale, in millimetres of the drawing, from the pole ``p``
or ``π``, with the vertices lettered (``a``, ``b`` …; ``a′``, ``n2``, ``k`` …) and the scale μ
stated. Absolute vectors (from the pole) have the book's velocity or acceleration colour; relative
vectors and components have the colour of the link whose motion they describe
(:data:`mechanisms.plot.ROLE_COLOURS`): normal components dashed, Coriolis components dash-dotted.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon

from ..analysis.plans import AccelerationPlan, InstantCentres, Plan, VelocityPlan
from ..linkages.base import Mechanism, Solution
from .drawing import ACCELERATION_COLOUR, ROLE_COLOURS, VELOCITY_COLOUR, draw

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["LINK_ROLES", "draw_plan", "draw_plans", "draw_instant_centres", "draw_centre_velocities"]

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
_LABEL_BOX = {"boxstyle": "round,pad=0.12", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}


def _arrow(ax: Axes, tail: complex, head: complex, colour: str, style: str, width: float, zorder: int = 3) -> None:
    ax.annotate("", xy=(head.real, head.imag), xytext=(tail.real, tail.imag),
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": width, "linestyle": style,
                            "shrinkA": 0, "shrinkB": 0, "mutation_scale": 12}, zorder=zorder)


def draw_plan(plan: Plan, ax: Axes | None = None, names: bool = True, images: bool = True, title: str | None = None,
              label_offset: float = 3.5) -> Axes:
    """Draw a velocity or acceleration plan to scale, in mm of the drawing.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan
        From :func:`mechanisms.analysis.plans.velocity_plan` or ``acceleration_plan``.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    names : bool
        Write the names of the relative vectors and components beside them (``v_BA``, ``a^n_BA`` …),
        except on vectors too short to carry one.
    images : bool
        Shade the image of every link that has three or more points on the plan.
    title : str, optional
        The title; by default "velocity plan" or "acceleration plan" with the crank angle.
    label_offset : float
        Distance of the vertex letters from their vertices (mm of the drawing).

    Returns
    -------
    matplotlib Axes
        Axes in mm, equal aspect, with the scale stated in the lower right corner.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(5.0, 5.0))
    colour = VELOCITY_COLOUR if plan.quantity == "velocity" else ACCELERATION_COLOUR
    drawn = {label: plan.drawn(label) for label in plan.vertices}
    if images:
        for link, members in plan.images.items():
            corners = [drawn[plan.points[n]] for n in members]
            if len(corners) >= 3:
                ax.add_patch(Polygon([(c.real, c.imag) for c in corners], closed=True, zorder=1, alpha=0.15,
                                     facecolor=ROLE_COLOURS[LINK_ROLES.get(link, "coupler")], edgecolor="none"))
    for vector in plan.vectors:
        tail, head = drawn[vector.tail], drawn[vector.head]
        if abs(head - tail) < 1e-9:
            continue
        style, width = _STYLE[vector.kind]
        shade = colour if vector.kind == "absolute" else ROLE_COLOURS[LINK_ROLES.get(vector.link, "coupler")]
        _arrow(ax, tail, head, shade, style, width, 4 if vector.kind == "absolute" else 3)
        if names and vector.kind != "absolute" and abs(head - tail) >= 3.0 * label_offset:
            middle = 0.5 * (tail + head)
            side = 1j * (head - tail) / abs(head - tail) * 0.9 * label_offset
            ax.text((middle + side).real, (middle + side).imag, f"${vector.latex}$", fontsize=9, color=shade,
                    ha="center", va="center", zorder=5, bbox=_LABEL_BOX)
    # the vertices and their letters, away from the pole (the pole's away from the plan's centre);
    # vertices closer than the letters' size share one label, "a, b"
    groups: list[list[str]] = []
    for label, point in drawn.items():
        for group in groups:
            if abs(drawn[group[0]] - point) < 0.8 * label_offset:
                group.append(label)
                break
        else:
            groups.append([label])
    centre = complex(np.mean(list(drawn.values())))
    for group in groups:
        point = complex(np.mean([drawn[label] for label in group]))
        away = point - centre if plan.pole in group else point
        away = away / abs(away) if abs(away) > 1e-9 else 1j
        for label in group:
            ax.plot(drawn[label].real, drawn[label].imag, "o", ms=3.5, color="black", zorder=6)
        text = point + (label_offset + 1.2 * (len(group) - 1)) * away
        ax.text(text.real, text.imag, ", ".join(group), fontsize=11, ha="center", va="center", zorder=6,
                style="normal" if plan.pole in group else "italic", bbox=_LABEL_BOX)
    values = np.array(list(drawn.values()))
    span = max(np.ptp(values.real), np.ptp(values.imag), 10.0)
    margin = 0.12 * span + label_offset
    ax.set_xlim(values.real.min() - margin, values.real.max() + margin)
    ax.set_ylim(values.imag.min() - margin, values.imag.max() + margin)
    ax.set_aspect("equal")
    ax.set_xlabel("mm of the drawing")
    ax.set_ylabel("mm of the drawing")
    symbol = r"$\mu_v$" if plan.quantity == "velocity" else r"$\mu_a$"
    ax.text(0.98, 0.02, f"{symbol} = {plan.scale:g} ({plan.unit})/mm", transform=ax.transAxes, ha="right",
            va="bottom", fontsize=9, bbox={"facecolor": "white", "edgecolor": "0.7", "boxstyle": "round"})
    what = "velocity plan" if plan.quantity == "velocity" else "acceleration plan"
    ax.set_title(title if title is not None else f"{what}, φ = {np.degrees(plan.phi) % 360:.4g}°")
    return ax


def draw_plans(mechanism: Mechanism, solution: Solution, velocity: VelocityPlan,
               acceleration: AccelerationPlan | None = None, index: int = 0,
               figsize: tuple[float, float] | None = None) -> tuple[Figure, list[Axes]]:
    """The mechanism at a position beside its velocity plan (and its acceleration plan).

    Returns
    -------
    (figure, axes)
        The mechanism (m) on top; below it the velocity plan and the acceleration plan (mm of the
        drawing).
    """
    count = 1 if acceleration is None else 2
    fig = plt.figure(figsize=figsize or (4.6 * count + 1.0, 7.6))
    grid = fig.add_gridspec(2, count, height_ratios=(1.0, 1.7))
    axes = [fig.add_subplot(grid[0, :])] + [fig.add_subplot(grid[1, k]) for k in range(count)]
    draw(mechanism, solution, index=index, ax=axes[0])
    for name, position in velocity.positions.items():
        if name not in solution.point_names and name != "A3":
            axes[0].plot(position.real, position.imag, "o", ms=4, color=ROLE_COLOURS["point"], zorder=5)
            axes[0].annotate(name, (position.real, position.imag), xytext=(5, -12), textcoords="offset points")
    axes[0].set_title(f"the mechanism at φ = {np.degrees(velocity.phi) % 360:.4g}°")
    draw_plan(velocity, ax=axes[1], title="velocity plan")
    if acceleration is not None:
        draw_plan(acceleration, ax=axes[2], title="acceleration plan")
    fig.tight_layout()
    return fig, axes


def _extend(ax: Axes, first: complex, second: complex, beyond: float = 0.15) -> None:
    """A thin dotted line through two points, a little beyond both."""
    d = second - first
    a, b = first - beyond * d, second + beyond * d
    ax.plot([a.real, b.real], [a.imag, b.imag], ls=":", lw=1.0, color="0.45", zorder=1)


def draw_instant_centres(mechanism: Mechanism, solution: Solution, centres: InstantCentres, index: int = 0,
                         ax: Axes | None = None, lines: bool = True, arrow_length: float | None = None) -> Axes:
    """The mechanism with all its instant centres P_ij, and Kennedy's lines that locate P02 and P13.

    Parameters
    ----------
    mechanism, solution, index
        The mechanism at one crank position.
    centres : InstantCentres
        From :func:`mechanisms.analysis.plans.instant_centres` at that position.
    lines : bool
        Draw the lines of Kennedy's theorem through the centres that locate P02 and P13.
    arrow_length : float, optional
        Length (m) of the arrows that point to centres at infinity.

    Returns
    -------
    matplotlib Axes
    """
    ax = draw(mechanism, solution, index=index, ax=ax, labels=True)
    finite = centres.finite
    every = np.array(list(finite.values()) + list(centres.positions.values()))
    span = max(np.ptp(every.real), np.ptp(every.imag))
    arrow_length = arrow_length or 0.12 * span
    if lines:
        for target, ways in (((0, 2), (((0, 1), (1, 2)), ((0, 3), (2, 3)))),
                             ((1, 3), (((0, 1), (0, 3)), ((1, 2), (2, 3))))):
            if target not in finite:
                continue
            for pair in (p for way in ways for p in way):
                if pair in finite:
                    _extend(ax, finite[pair], finite[target])
                else:  # a centre at infinity: the line through the target in its direction
                    d = centres.infinite[pair] * 0.6 * span
                    _extend(ax, finite[target] - d, finite[target] + d, 0.0)
    for (i, j), point in finite.items():
        joint = any(abs(point - p) < 1e-12 * span for p in centres.positions.values())
        if not joint:
            ax.plot(point.real, point.imag, marker="*", ms=12, color=ROLE_COLOURS["point"], mec="black", zorder=6)
        ax.annotate(f"$P_{{{i}{j}}}$", (point.real, point.imag), xytext=(6, -14) if joint else (-10, 9),
                    textcoords="offset points", fontsize=10, color="0.2", zorder=6,
                    ha="left" if joint else "right")
    for (i, j), direction in centres.infinite.items():
        # from the joint of the slider, an arrow towards the centre at infinity
        start = centres.positions.get("B", 0j)
        end = start + arrow_length * direction
        ax.annotate("", xy=(end.real, end.imag), xytext=(start.real, start.imag),
                    arrowprops={"arrowstyle": "->", "color": "0.3", "lw": 1.0, "linestyle": "--"})
        ax.annotate(f"$P_{{{i}{j}}}$ at ∞", (end.real, end.imag), xytext=(4, 2), textcoords="offset points",
                    fontsize=10, color="0.2")
    margin = 0.1 * span
    ax.set_xlim(every.real.min() - margin, every.real.max() + margin)
    ax.set_ylim(every.imag.min() - margin, every.imag.max() + margin)
    return ax


def draw_centre_velocities(ax: Axes, centre: complex, positions: Mapping[str, complex],
                           velocities: Mapping[str, complex], scale: float) -> Axes:
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
        m of the drawing per m/s; state it in the caption.

    Returns
    -------
    matplotlib Axes
    """
    for name, point in positions.items():
        ax.plot([centre.real, point.real], [centre.imag, point.imag], color="0.55", lw=0.9, ls="--", zorder=1)
        tip = point + scale * velocities[name]
        _arrow(ax, point, tip, VELOCITY_COLOUR, "-", 2.0, zorder=5)
    return ax
