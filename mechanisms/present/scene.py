"""Layer 6: scenes — what a figure of the site needs to move, as data, and its still image in SVG.

A **scene** is a mechanism's drawing (its :meth:`~mechanisms.linkages.base.Mechanism.scheme`, in the
book's colours) with the joints' positions at evenly spaced crank angles, optionally paths, velocity
and acceleration vectors, extra points and lines, and values to read out (φ, ψ, s …). An
**explorer** is the same over a family of mechanisms, one per value of one or two parameters (a rod
length, a pivot distance, a point's position on the coupler), all precomputed here: the site's player
(``_static/mechanisms-player.js``) only looks values up, so every number the page shows is the
package's. Where a member of the family does not assemble over the whole turn, its frames outside
:meth:`~mechanisms.linkages.base.Mechanism.assembly_intervals` are empty and the player keeps to the
range where it does; a member that assembles at no frame (the end of a parameter's range) has every
frame empty, and the player draws nothing for it but says so.

:meth:`Scene.html` gives the HTML of one figure: an SVG still image of one frame (what a printed page
or a reader without JavaScript sees), the scene's data as JSON, and an ``<div class="mech-player">``
that the player turns into a moving figure with a crank-angle slider, a slider per parameter, play
and pause, toggles and a live readout. In a notebook a :class:`Scene` displays itself.

Positions are stored as whole numbers of a step of 1/4000 of the figure's extent (a point that does
not move, once; a moving point as its steps from frame to frame), vectors of 1/4000 of the longest arrow, read-out values rounded to the digits the
player prints: a scene of 72 frames weighs a few kilobytes a member.
"""

from __future__ import annotations

import html as html_text
import json
import math
import re
import warnings
from dataclasses import dataclass, field
from itertools import product
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from ..core.errors import AssemblyError, SingularPositionWarning, InvalidParameterError
from ..core.motion import PointMotion
from ..linkages.base import Bar, Block, Ground, Guide, Mechanism, Solution
from .colours import (ACCELERATION_COLOUR, BLOCK_FILL, PATH_COLOUR, ROLE_COLOURS, VELOCITY_COLOUR,
                      link_colours)
from .describe import angle_text, extent_text, plain_text, point_text, position_sentence, sentence, series, value_text

__all__ = [
    "Scene",
    "Parameter",
    "Readout",
    "Arrow",
    "Line",
    "On",
    "scene",
    "explorer",
    "velocity",
    "acceleration",
    "STEPS",
]

STEPS = 4000
"""Positions are stored in steps of 1/STEPS of the figure's extent, vectors of 1/STEPS of the longest."""
_ARROW_SHARE = 0.25
"""The longest arrow of a kind is drawn this share of the mechanism's size long (the larger side of the box
round its joints over all frames and members; the figure's extent also takes in the arrows and extra points)."""


@dataclass(frozen=True)
class Parameter:
    """A parameter of an explorer: one slider of the player.

    Parameters
    ----------
    name : str
        The keyword of the family's ``build`` function (``"rod"``).
    label : str
        Its symbol as the book writes it (``"L₂"`` or ``"L_2"``); the player sets its letters in
        italics, as the text's math, and ``_x`` as a subscript x.
    unit : str
        Its unit as printed (``"m"``, ``"°"``, ``""``).
    values : sequence of float
        The values the slider steps through (in the unit printed; ``build`` gets them as they are).
    digits : int
        Decimals printed.
    """

    name: str
    label: str
    unit: str
    values: Sequence[float]
    digits: int = 3


@dataclass(frozen=True)
class Readout:
    """A value the player prints at every frame: ``label = value unit`` (the label's letters in italics).

    ``value(solution, mechanism)`` returns one number per position of the solution (already in the
    unit printed, e.g. degrees); ``order`` is the order of the solve it needs (1 for velocities).
    """

    label: str
    unit: str
    value: Callable[[Solution, Mechanism], Any]
    digits: int = 3
    order: int = 0


@dataclass(frozen=True)
class Arrow:
    """A vector drawn at a point: ``value(solution, mechanism)`` gives it (complex, one per position).

    Arrows of one ``kind`` share a scale (the longest of the family is a quarter of the mechanism's size) and
    one toggle of the player; ``kind`` is ``"velocity"``, ``"acceleration"`` or another word.
    """

    at: str
    label: str
    value: Callable[[Solution, Mechanism], Any]
    colour: str = VELOCITY_COLOUR
    kind: str = "velocity"
    order: int = 1


@dataclass(frozen=True)
class Line:
    """A thin line through named points (joints or extra points), e.g. a normal to a velocity."""

    points: tuple[str, ...]
    colour: str = "#7f7f7f"
    dashed: bool = True


@dataclass(frozen=True)
class On:
    """A point fixed to a link: ``along`` (m) from the link's first joint and ``left`` of it.

    Either may be the name of an explorer's parameter instead of a number: the point then moves
    along the link as the reader moves that parameter's slider (u on the coupler).
    """

    link: str
    along: float | str
    left: float | str = 0.0


def velocity(point: str, label: str | None = None) -> Arrow:
    """The velocity vector of a joint or extra point, in :data:`VELOCITY_COLOUR`."""
    return Arrow(point, label or f"v_{point}", lambda s, m: s.point(point).velocity, VELOCITY_COLOUR, "velocity", 1)


def acceleration(point: str, label: str | None = None) -> Arrow:
    """The acceleration vector of a joint or extra point, in :data:`ACCELERATION_COLOUR`."""
    return Arrow(point, label or f"a_{point}", lambda s, m: s.point(point).acceleration, ACCELERATION_COLOUR,
                 "acceleration", 2)


PointFunction = Callable[[Solution, Mechanism], PointMotion] | On


@dataclass
class Scene:
    """A scene or explorer: its data (JSON-ready) and its HTML. Make one with :func:`scene` or :func:`explorer`."""

    data: dict[str, Any]
    still: tuple[int, int] = (0, 0)
    caption: str = ""
    _json: str = field(default="", repr=False)
    description: str = ""
    """The figure's text alternative: what the still image shows, and what the player lets the reader move
    (the ``<desc>`` of the still SVG)."""

    def json(self) -> str:
        """The scene's data as compact JSON (what the page embeds)."""
        if not self._json:
            self._json = json.dumps(self.data, separators=(",", ":"), ensure_ascii=False, allow_nan=False)
        return self._json

    @property
    def nbytes(self) -> int:
        """Bytes of the HTML the page embeds (data and still image)."""
        return len(self.html().encode())

    def html(self) -> str:
        """The figure: a still SVG of one frame, the data, and the player's mount point."""
        member, frame = self.still
        caption = f'<p class="mech-caption">{html_text.escape(self.caption)}</p>' if self.caption else ""
        return (f'<div class="mech-player" data-still="{member},{frame}">'
                f'{_svg(self.data, member, frame, self.description)}'
                f'<script type="application/json" class="mech-scene">{_script_safe(self.json())}</script>'
                f'{caption}</div>')

    def _repr_html_(self) -> str:
        return self.html()

    def __repr__(self) -> str:
        members = len(self.data["members"])
        return (f"<scene {self.data['title']!r}: {len(self.data['phi'])} frames"
                + (f", {members} members" if members > 1 else "") + ">")

    # --- reading a scene back (for tests and for the text of a page) --------------------------------

    def member_index(self, **values: float) -> int:
        """The member whose parameters equal ``values`` (by name)."""
        names = [p["name"] for p in self.data["parameters"]]
        if set(values) - set(names):
            raise InvalidParameterError("values", values, f"values of the parameters {names} of this explorer")
        for index, key in enumerate(self.data["keys"]):
            if all(math.isclose(key[names.index(n)], v, rel_tol=1e-12, abs_tol=1e-15) for n, v in values.items()):
                return index
        raise InvalidParameterError("values", values, f"values of the parameters {names} of this explorer")

    def position(self, joint: str, member: int = 0) -> np.ndarray:
        """A joint's stored positions (complex, m) over the frames of a member; nan where it does not assemble."""
        xy = self.data["members"][member]["xy"][joint]
        x0, y0, step = self.data["origin"][0], self.data["origin"][1], self.data["step"]
        values = np.array([(np.nan, np.nan) if v is None else v for v in _decoded(xy, len(self.data["phi"]))],
                          dtype=float)
        return (x0 + step * values[:, 0]) + 1j * (y0 + step * values[:, 1])


def _script_safe(text: str) -> str:
    """JSON inside ``<script>``: no ``</`` may appear in it."""
    return text.replace("</", "<\\/")


def scene(mechanism: Mechanism, **options: Any) -> Scene:
    """A moving figure of one mechanism over a turn of its crank: :func:`explorer` with no parameter.

    Parameters
    ----------
    mechanism : Mechanism
        What to draw.
    **options
        As for :func:`explorer` (``frames``, ``paths``, ``arrows``, ``points``, ``lines``, ``readout``,
        ``notes``, ``title`` …).
    """
    return explorer(lambda: mechanism, (), **options)


def explorer(build: Callable[..., Mechanism], parameters: Sequence[Parameter] = (), *, frames: int = 72,
             start: float = 0.0, angles: Any = None, paths: Sequence[str] = (), arrows: Sequence[Arrow] = (),
             points: Mapping[str, PointFunction] | None = None, lines: Sequence[Line] = (),
             readout: Sequence[Readout] = (), notes: Callable[[Mechanism], Iterable[str]] | None = None,
             title: str = "", angle_symbol: str = "φ", omega: float = 1.0,
             labels: bool | Mapping[str, str] = True,
             still: Mapping[str, float] | None = None, still_angle: float | None = None,
             caption: str = "", colours: Mapping[str, str] | None = None) -> Scene:
    """A family of moving figures, one per value (or pair of values) of the parameters, precomputed.

    Parameters
    ----------
    build : callable
        ``build(**{p.name: value})`` makes the mechanism of one member.
    parameters : sequence of Parameter
        Zero, one or two parameters; the members are every combination of their values.
    frames : int
        Crank positions per turn, evenly spaced from ``start`` (rad); 72 is a frame every 5°.
    angles : array_like, optional
        The frames' crank angles (rad) instead, e.g. at equal steps of time of a simulated run.
    paths : sequence of str
        Joints or extra points whose whole paths are drawn (grey; the player can hide them).
    arrows : sequence of Arrow
        Vectors drawn at points (:func:`velocity`, :func:`acceleration` or your own).
    points : mapping, optional
        Extra points, drawn as dots: ``{name: On(link, along, left)}`` (a coupler point, whose
        ``along`` and ``left`` may be parameters) or ``{name: f(solution, mechanism) -> PointMotion}``
        (a centre of curvature, an instant centre).
    lines : sequence of Line
        Thin lines through joints or extra points.
    readout : sequence of Readout
        Values printed at every frame, after the crank angle.
    notes : callable, optional
        ``notes(mechanism)`` gives lines of text for a member (its Grashof class, its stroke …); a
        symbol between dollars is set as the text's math (``"stroke $H$ = 0.16 m"``: H in italics).
    title : str
        The figure's name (shown by the player, and in ``repr``).
    angle_symbol : str
        The crank angle's symbol in the readout.
    omega : float
        Crank speed φ_t (1/s) of the velocities and accelerations (1 unless the page says otherwise).
    labels : bool or mapping
        Write the joints' names; a mapping ``{package name: label}`` writes some under the page's own
        letters (``{"B": "B_1"}``), the others under the package's (digits as a subscript: ``O2`` is O₂).
    still : mapping, optional
        The parameter values of the still image, a member that assembles at a frame (default: the first
        member that does).
    still_angle : float, optional
        The crank angle (rad) of the still image (default: the first frame where it assembles).
    caption : str
        A sentence under the figure: what to try and what to notice.
    colours : mapping, optional
        ``{link name: "#rrggbb"}``: links drawn in a colour of their own instead of their role's, as
        :func:`mechanisms.plot.draw` takes it (the second of two rockers).

    Returns
    -------
    Scene
    """
    if not 1 <= int(frames) <= 3600:
        raise InvalidParameterError("frames", frames, "a whole number of frames from 1 to 3600")
    if len(parameters) > 2:
        raise InvalidParameterError("parameters", [p.name for p in parameters], "at most two parameters")
    phi = start + np.arange(int(frames)) * (2.0 * math.pi / int(frames))
    if angles is not None:
        phi = np.asarray(angles, dtype=float).ravel()
        if phi.size == 0 or phi.size > 3600 or not np.all(np.isfinite(phi)):
            raise InvalidParameterError("angles", f"{phi.size} values", "1 to 3600 finite crank angles (rad)")
    keys = list(product(*(list(p.values) for p in parameters)))
    order = max([0] + [r.order for r in readout] + [a.order for a in arrows])
    members = []
    for key in keys:
        values = {p.name: k for p, k in zip(parameters, key)}
        members.append(_member(build(**values), phi, order, omega, _resolved(points or {}, values), arrows,
                               readout))
    mechanisms = [m["mechanism"] for m in members]
    data = _layout(mechanisms[0], members, phi, paths, arrows, lines, readout, labels,
                   link_colours(mechanisms[0], colours))
    data.update(title=title, angle=angle_symbol, omega=omega, keys=[list(k) for k in keys],
                parameters=[{"name": p.name, "label": p.label, "unit": p.unit, "digits": p.digits,
                             "values": list(p.values)} for p in parameters])
    for info, member in zip(data["members"], members):
        info["notes"] = list(notes(member["mechanism"])) if notes else []
    assembling = [i for i, m in enumerate(members) if m["valid"].any()]
    chosen = Scene(data).member_index(**still) if still else assembling[0]
    if chosen not in assembling:                # its still image would be an empty picture
        raise InvalidParameterError("still", dict(still or {}), "the parameter values of a member that assembles "
                                    "at a frame of the figure (this one assembles at none)")
    valid = members[chosen]["valid"]
    frames_valid = np.flatnonzero(valid)
    if still_angle is not None and frames_valid.size:
        frame = int(frames_valid[np.argmin(np.abs(np.angle(np.exp(1j * (phi[frames_valid] - still_angle)))))])
    else:
        frame = int(frames_valid[0]) if frames_valid.size else 0
    still_scene = Scene(data, (chosen, frame), caption)
    still_scene.description = _description(still_scene, members[chosen], labels)
    return still_scene


# --- the text alternative ---------------------------------------------------------------------------------

def _symbol(label: str) -> str:
    """A label of the player (``L_2``, ``ψ``, ``v_B``) as read: ``L₂``."""
    return plain_text(f"${label}$") if "$" not in label else plain_text(label)


def _description(figure: Scene, computed: dict[str, Any], labels: bool | Mapping[str, str]) -> str:
    """What a scene's still image shows and what its player moves.

    The mechanism with its parameters, the crank angle of the still, the joints where they are, the paths
    drawn with their extent, each arrow's size and direction (from the member as computed, ``computed``:
    numbers to three significant figures, not the stored steps of 1/4000) and the readout's values at that
    frame as the player prints them, then the parameters an explorer lets the reader change.
    """
    data = figure.data
    member, frame = figure.still
    mechanism = computed["mechanism"]
    letters = labels if isinstance(labels, Mapping) else None
    joints = [name for name in data["members"][member]["xy"] if name not in data["dots"]]
    where = {name: complex(computed["where"][name][frame]) for name in joints}
    phi = math.radians(data["phi"][frame])
    symbol = data["angle"]
    parts = [sentence(data["title"]) if data["title"] else "",
             position_sentence(mechanism, where, phi, letters, _symbol(symbol))]
    shown = []
    for name in data["dots"]:
        point = complex(computed["where"][name][frame])
        if math.isfinite(point.real):
            shown.append(f"{_symbol(data.get('names', {}).get(name, name))} at {point_text(point)}")
    if shown:
        parts.append(sentence("Points marked: " + ", ".join(shown)))
    paths = []
    for name in data["paths"]:
        track = computed["where"][name]
        track = track[np.isfinite(track)]
        if track.size:
            paths.append(f"{_symbol(data.get('names', {}).get(name, name))} ({extent_text(track)})")
    if paths:
        parts.append(sentence(f"Path{'s' if len(paths) > 1 else ''} of " + series(paths)))
    arrows = []
    for index, arrow in enumerate(data["arrows"]):
        vector = complex(computed["vectors"][index][frame])
        if not (math.isfinite(vector.real) and math.isfinite(vector.imag)):
            continue
        unit = {"velocity": "m/s", "acceleration": "m/s²"}.get(arrow["kind"], "")
        direction = f", pointing at {angle_text(math.atan2(vector.imag, vector.real), '')} from the x axis" \
            if abs(vector) else ""
        arrows.append(f"{_symbol(arrow['label'])} = {value_text(abs(vector), unit)}{direction}")
    if arrows:
        parts.append(sentence("Arrows: " + "; ".join(arrows)))
    values = []
    for index, item in enumerate(data["readout"]):
        value = data["members"][member]["values"][index][frame]
        if value is not None:
            values.append(f"{_symbol(item['label'])} = {value_text(value, item['unit'])}")
    if values:
        parts.append(sentence("At this position " + series(values)))
    notes = [plain_text(note) for note in data["members"][member].get("notes", [])]
    if notes:
        parts.append(sentence("; ".join(notes)))
    frames = len(data["phi"])
    moving = f"The player turns the crank through {frames} positions, with a crank-angle slider"
    sliders = [f"{_symbol(p['label'])} from {value_text(min(p['values']), p['unit'])} to "
               f"{value_text(max(p['values']), p['unit'])} in {len(p['values'])} steps"
               for p in data["parameters"]]
    if sliders:
        key = data["keys"][member]
        now = [f"{_symbol(p['label'])} = {value_text(k, p['unit'])}" for p, k in zip(data["parameters"], key)]
        moving += f" and a slider for {series(sliders)}; the image shows {series(now)}"
    valid = data["members"][member]["valid"]
    if "0" in valid:
        moving += f"; this mechanism assembles at {valid.count('1')} of the {frames} positions"
    parts.append(sentence(moving))
    return " ".join(part for part in parts if part)


# --- computing the members --------------------------------------------------------------------------

def _inside(phi: np.ndarray, intervals: Sequence[tuple[float, float]]) -> np.ndarray:
    """Where φ lies strictly inside one of the intervals (taken modulo 2π)."""
    inside = np.zeros(phi.shape, dtype=bool)
    for lower, upper in intervals:
        if upper - lower >= 2.0 * math.pi * (1.0 - 1e-12):
            return np.ones(phi.shape, dtype=bool)
        shifted = lower + np.mod(phi - lower, 2.0 * math.pi)
        inside |= (shifted > lower) & (shifted < upper)
    return inside


def _resolved(points: Mapping[str, PointFunction], values: Mapping[str, float]) -> dict[str, Callable]:
    """The extra points of one member: an :class:`On` with parameter names gets the member's values."""
    out: dict[str, Callable] = {}
    for name, spec in points.items():
        if isinstance(spec, On):
            along = values[spec.along] if isinstance(spec.along, str) else spec.along
            left = values[spec.left] if isinstance(spec.left, str) else spec.left
            out[name] = _point_on(spec.link, float(along), float(left))
        else:
            out[name] = spec
    return out


def _point_on(link: str, along: float, left: float) -> Callable[[Solution, Mechanism], PointMotion]:
    def point(solution: Solution, mechanism: Mechanism) -> PointMotion:
        return solution.point_on(link, along, left)
    return point


def _member(mechanism: Mechanism, phi: np.ndarray, order: int, omega: float, points: Mapping[str, Callable],
            arrows: Sequence[Arrow], readout: Sequence[Readout]) -> dict[str, Any]:
    try:
        intervals = mechanism.assembly_intervals()
        valid = _inside(phi, intervals)
    except NotImplementedError:                 # a mechanism that does not say: try each frame
        valid = np.array([_assembles(mechanism, p) for p in phi], dtype=bool)
        intervals = [(float(p), float(p)) for p in phi[valid]] if not valid.all() else [(-math.pi, math.pi)]
    where: dict[str, np.ndarray] = {}
    angles: dict[str, np.ndarray] = {}
    values: list[np.ndarray] = []
    vectors: list[np.ndarray] = []
    if valid.any():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SingularPositionWarning)
            solution = mechanism.solve(phi[valid], omega=omega, order=order)
        shape = solution.phi.shape
        found = {name: solution.point(name) for name in solution.point_names}
        extra = {name: f(solution, mechanism) for name, f in points.items()}
        found.update(extra)
        solution = solution.with_points(extra)      # readouts and arrows may use the extra points
        for name, motion in found.items():
            where[name] = _spread(np.broadcast_to(motion.value, shape), valid, complex)
        for name in solution.angle_names:
            angles[name] = _spread(np.broadcast_to(solution.angle(name).value, shape), valid, float)
        # rates are unbounded at a singular position: printed and drawn as missing there, not as numbers
        rated = valid.copy()
        rated[np.flatnonzero(valid)[solution.singular]] = False
        for item in readout:
            value = np.broadcast_to(np.asarray(item.value(solution, mechanism), dtype=float), shape)
            values.append(_spread(value, valid, float))
            if item.order:
                values[-1][~rated] = np.nan
        for arrow in arrows:
            vector = _spread(np.broadcast_to(np.asarray(arrow.value(solution, mechanism), dtype=complex), shape),
                             valid, complex)
            vector[~rated] = np.nan
            vectors.append(vector)
    return {"mechanism": mechanism, "valid": valid, "intervals": intervals, "where": where, "angles": angles,
            "values": values, "vectors": vectors}


def _assembles(mechanism: Mechanism, phi: float) -> bool:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        try:
            mechanism.solve(np.array([phi]), order=0)
        except AssemblyError:
            return False
    return True


def _spread(values: np.ndarray, valid: np.ndarray, dtype: type) -> np.ndarray:
    out: np.ndarray = np.full(valid.shape, np.nan, dtype=dtype)
    out[valid] = values
    return out


# --- the data ---------------------------------------------------------------------------------------------

def _layout(first: Mechanism, members: list[dict], phi: np.ndarray, paths: Sequence[str], arrows: Sequence[Arrow],
            lines: Sequence[Line], readout: Sequence[Readout], labels: bool | Mapping[str, str],
            colours: Mapping[str, str]) -> dict[str, Any]:
    joints = _joints(first)
    body = np.concatenate([np.concatenate([w[np.isfinite(w)] for name, w in m["where"].items()
                                           if name in joints] or [np.zeros(0)])
                           for m in members] + [np.zeros(0, dtype=complex)])
    for m in members:
        body = np.concatenate([body, [g.through for g in m["mechanism"].scheme() if isinstance(g, Guide)]])
    if body.size == 0:
        raise InvalidParameterError("parameters", "—", "at least one member that assembles somewhere")
    size = float(max(np.ptp(body.real), np.ptp(body.imag))) or 1.0
    centre = complex(float(body.real.min() + body.real.max()) / 2, float(body.imag.min() + body.imag.max()) / 2)
    # extra points are in the figure while they are near the mechanism (within its size of its middle);
    # farther (an instant centre near infinity) they are not drawn
    near = size
    for m in members:
        for name, w in m["where"].items():
            if name not in joints:
                w[(np.abs(w.real - centre.real) > near) | (np.abs(w.imag - centre.imag) > near)] = np.nan
    everything = np.concatenate([body] + [w[np.isfinite(w)] for m in members for name, w in m["where"].items()
                                          if name not in joints])
    scales = {}
    for kind in dict.fromkeys(a.kind for a in arrows):
        longest = max((float(np.nanmax(np.abs(m["vectors"][i]), initial=0.0)) for m in members
                       for i, a in enumerate(arrows) if a.kind == kind), default=0.0)
        scales[kind] = _significant(_ARROW_SHARE * size / longest) if longest > 0 and math.isfinite(longest) else 0.0
    for m in members:                           # the arrows' tips are in the figure too
        for i, a in enumerate(arrows):
            tips = m["where"][a.at] + scales[a.kind] * m["vectors"][i]
            everything = np.concatenate([everything, tips[np.isfinite(tips)]])
    # the extent (and so the step, the joints' size and the view's margin) and the arrows' scales are
    # stored: rounded to 6 digits, they do not depend on the last bits of the processor's sines and
    # absolute values of complex numbers, which the positions and vectors they are computed from do
    extent = _significant(float(max(np.ptp(everything.real), np.ptp(everything.imag))) or 1.0)
    step = extent / STEPS
    x0, y0 = float(everything.real.min()), float(everything.imag.min())
    origin = (_fixed(x0, step), _fixed(y0, step))
    data: dict[str, Any] = {
        "version": 1,
        "phi": [round(math.degrees(p), 6) for p in phi],
        "origin": list(origin),
        "step": step,
        "size": 0.025 * extent,
        "view": _view(everything, extent),
        "labels": labels if isinstance(labels, bool) else True,
        "parts": _parts(first, colours),
        "paths": list(paths),
        "lines": [{"points": list(line.points), "colour": line.colour, "dashed": line.dashed} for line in lines],
        "arrows": [{"at": a.at, "label": a.label, "colour": a.colour, "kind": a.kind} for a in arrows],
        "scales": scales,
        "readout": [{"label": r.label, "unit": r.unit, "digits": r.digits} for r in readout],
        "members": [],
    }
    if isinstance(labels, Mapping) and labels:
        data["names"] = {str(k): str(v) for k, v in labels.items()}   # the page's letters for some joints
    extra = list(dict.fromkeys(name for m in members for name in m["where"] if name not in joints))
    data["dots"] = extra
    for m in members:
        data["members"].append({
            "valid": "".join("1" if v else "0" for v in m["valid"]),
            "intervals": [[round(math.degrees(a), 3), round(math.degrees(b), 3)] for a, b in m["intervals"]],
            "xy": {name: _encoded(_quantized(w, origin, step)) for name, w in m["where"].items()},
            "angles": {name: [None if not math.isfinite(v) else round(v, 5) for v in values]
                       for name, values in m["angles"].items() if name in _block_angles(first)},
            "guides": [[_round(g.through.real, step), _round(g.through.imag, step), round(g.angle, 6)]
                       for g in m["mechanism"].scheme() if isinstance(g, Guide)],
            "values": [[None if not math.isfinite(v) else round(float(v), r.digits) for v in values]
                       for r, values in zip(readout, m["values"])],
            "vectors": [_vector(v, scales[a.kind] / step) for a, v in zip(arrows, m["vectors"])],
        })
    return data


def _significant(value: float) -> float:
    """``value`` rounded to 6 significant digits: a number stored in a scene that round-off must not move."""
    return float(f"{value:.6g}")


def _fixed(value: float, step: float) -> float:
    return round(math.floor(value / step) * step, 12)


def _round(value: float, step: float) -> float:
    digits = max(0, 1 - int(math.floor(math.log10(step))))
    return round(value, digits)


def _view(points: np.ndarray, extent: float) -> list[float]:
    margin = 0.1 * extent
    return [round(float(points.real.min()) - margin, 6), round(float(points.imag.min()) - 1.3 * margin, 6),
            round(float(np.ptp(points.real)) + 2 * margin, 6), round(float(np.ptp(points.imag)) + 2.3 * margin, 6)]


def _quantized(values: np.ndarray, origin: tuple[float, float], step: float) -> list[int | None]:
    out: list[int | None] = []
    for z in values:
        if np.isfinite(z):
            out += [int(round((z.real - origin[0]) / step)), int(round((z.imag - origin[1]) / step))]
        else:
            out += [None, None]
    return out


def _digits_below(name: str) -> str:
    """A joint's name as the drawings set it: trailing digits as a subscript (``P1`` → ``P_1``)."""
    return re.sub(r"^([A-Za-z]+)(\d+)$", r"\1_\2", name)


def _encoded(xy: list[int | None]) -> list[int | None]:
    """A point's stored positions in their light form, which :func:`_decoded` reads back.

    A point that does not move (a fixed pivot) is written once, as two numbers. Otherwise the first
    position the point has is written, then each next one as its difference from the one before
    (``None`` where the point has none): a point moves a few steps a frame, and small numbers are
    short. Whole numbers, so the form loses nothing.
    """
    if len(xy) > 2 and xy == xy[:2] * (len(xy) // 2):
        return xy[:2]
    out: list[int | None] = []
    x = y = 0
    for k in range(0, len(xy), 2):
        nx, ny = xy[k], xy[k + 1]
        if nx is None or ny is None:
            out += [None, None]
            continue
        out += [nx - x, ny - y]
        x, y = nx, ny
    return out


def _decoded(xy: list[int | None], frames: int) -> list[tuple[int, int] | None]:
    """The positions (whole steps from the origin) of a point at each frame, from :func:`_encoded`'s form."""
    if len(xy) == 2:
        pair = None if xy[0] is None or xy[1] is None else (xy[0], xy[1])
        return [pair] * frames
    out: list[tuple[int, int] | None] = []
    x = y = 0
    for k in range(frames):
        dx, dy = xy[2 * k], xy[2 * k + 1]
        if dx is None or dy is None:
            out.append(None)
            continue
        x, y = x + dx, y + dy
        out.append((x, y))
    return out


def _vector(values: np.ndarray, scale: float) -> list[int | None]:
    return _quantized(values * scale, (0.0, 0.0), 1.0)


def _joints(mechanism: Mechanism) -> set[str]:
    found: set[str] = set()
    for item in mechanism.scheme():
        if isinstance(item, Bar):
            found.update(item.joints)
        elif isinstance(item, (Ground, Block)):
            found.add(item.joint)
    return found


def _block_angles(mechanism: Mechanism) -> set[str]:
    return {item.angle for item in mechanism.scheme() if isinstance(item, Block) and isinstance(item.angle, str)}


def _parts(mechanism: Mechanism, colours: Mapping[str, str]) -> list[dict[str, Any]]:
    parts: list[dict[str, Any]] = []
    guides = 0
    for item in mechanism.scheme():
        if isinstance(item, Guide):
            parts.append({"guide": guides})
            guides += 1
        elif isinstance(item, Ground):
            parts.append({"ground": item.joint})
        elif isinstance(item, Bar):
            parts.append({"bar": list(item.joints), "colour": colours[item.link],
                          "link": item.link})
        elif isinstance(item, Block):
            parts.append({"block": item.joint, "angle": item.angle if isinstance(item.angle, str)
                          else round(float(item.angle), 6)})
    return parts


# --- the still image: SVG, the same elements the player moves -------------------------------------------

def _svg(data: dict[str, Any], member_index: int, frame: int, description: str = "") -> str:
    """The figure at one frame as SVG; the player updates these elements' coordinates in place.

    Its ``<title>`` (the scene's title) names it and its ``<desc>`` (:attr:`Scene.description`) says what it
    shows, for a reader who cannot see it.
    """
    member = data["members"][member_index]
    x0, y0 = data["origin"]
    step, size = data["step"], data["size"]

    def at(name: str) -> tuple[float, float] | None:
        xy = member["xy"].get(name)
        stored = None if xy is None else _decoded(xy, len(data["phi"]))[frame]
        if stored is None:
            return None
        return x0 + step * stored[0], y0 + step * stored[1]

    def num(v: float) -> str:
        return f"{v:.6g}"

    def points_of(names: Sequence[str]) -> str:
        found = [at(n) for n in names]
        return " ".join(f"{num(p[0])},{num(p[1])}" for p in found if p is not None)

    view = data["view"]
    # the drawing is in metres with y up: flipped inside one group; text is written unflipped
    body: list[str] = []
    for index, name in enumerate(data["paths"]):
        body.append(f'<path class="mech-path" data-point="{name}" fill="none" stroke="{PATH_COLOUR}" '
                    f'stroke-width="1" vector-effect="non-scaling-stroke" d="{_path_d(data, member, name)}"/>')
    for part in data["parts"]:
        if "guide" in part:
            x, y, angle = member["guides"][part["guide"]]
            half = 0.6 * max(view[2], view[3])
            hatch = "".join(f"M{num(t)},0 l{num(-0.5 * size)},{num(-0.7 * size)} "
                            for t in np.linspace(-half, half, 25))
            body.append(f'<g class="mech-guide" data-guide="{part["guide"]}" '
                        f'transform="translate({num(x)} {num(y)}) rotate({num(math.degrees(angle))})">'
                        f'<path d="M{num(-half)},0 L{num(half)},0 {hatch}" stroke="{ROLE_COLOURS["frame"]}" '
                        f'stroke-width="1.2" vector-effect="non-scaling-stroke" fill="none"/></g>')
    for part in data["parts"]:
        if "ground" in part:
            c = at(part["ground"]) or (0.0, 0.0)
            s = size
            hatch = "".join(f"M{num(t)},{num(-1.6 * s)} l{num(-0.5 * s)},{num(-0.6 * s)} "
                            for t in np.linspace(-1.4 * s, 1.6 * s, 6))
            body.append(f'<g class="mech-ground" data-joint="{part["ground"]}" '
                        f'transform="translate({num(c[0])} {num(c[1])})">'
                        f'<path d="M0,0 L{num(-s)},{num(-1.6 * s)} L{num(s)},{num(-1.6 * s)} Z" fill="#ffffff" '
                        f'stroke="{ROLE_COLOURS["frame"]}" stroke-width="1.2" vector-effect="non-scaling-stroke"/>'
                        f'<path d="M{num(-1.6 * s)},{num(-1.6 * s)} L{num(1.6 * s)},{num(-1.6 * s)} {hatch}" '
                        f'stroke="{ROLE_COLOURS["frame"]}" stroke-width="1" vector-effect="non-scaling-stroke" '
                        f'fill="none"/></g>')
    for line in data["lines"]:
        dash = ' stroke-dasharray="4 3"' if line["dashed"] else ""
        body.append(f'<polyline class="mech-line" data-points="{",".join(line["points"])}" fill="none" '
                    f'stroke="{line["colour"]}" stroke-width="1" vector-effect="non-scaling-stroke"{dash} '
                    f'points="{points_of(line["points"])}"/>')
    for part in data["parts"]:
        if "bar" in part:
            body.append(f'<polyline class="mech-bar" data-points="{",".join(part["bar"])}" fill="none" '
                        f'stroke="{part["colour"]}" stroke-width="4" stroke-linecap="round" stroke-linejoin="round" '
                        f'vector-effect="non-scaling-stroke" points="{points_of(part["bar"])}"/>')
    for part in data["parts"]:
        if "block" in part:
            c = at(part["block"]) or (0.0, 0.0)
            angle = part["angle"]
            if isinstance(angle, str):
                values = member["angles"].get(angle, [])
                angle = values[frame] if frame < len(values) and values[frame] is not None else 0.0
            s = size
            body.append(f'<g class="mech-block" data-joint="{part["block"]}" data-angle="{part["angle"]}" '
                        f'transform="translate({num(c[0])} {num(c[1])}) rotate({num(math.degrees(angle))})">'
                        f'<rect x="{num(-1.4 * s)}" y="{num(-0.8 * s)}" width="{num(2.8 * s)}" height="{num(1.6 * s)}" '
                        f'fill="{BLOCK_FILL}" stroke="{ROLE_COLOURS["slider"]}" stroke-width="1.5" '
                        f'vector-effect="non-scaling-stroke"/></g>')
    joints = list(dict.fromkeys(name for m in data["members"] for name in m["xy"] if name not in data["dots"]))
    # every joint, dot and label is written, hidden where it is not at this frame: the player shows it
    for name in joints:
        c, hidden = at(name) or (0.0, 0.0), "" if at(name) else ' style="display:none"'
        body.append(f'<circle class="mech-hinge" data-joint="{name}"{hidden} cx="{num(c[0])}" cy="{num(c[1])}" '
                    f'r="{num(0.55 * size)}" fill="#ffffff" stroke="#000000" stroke-width="1.2" '
                    f'vector-effect="non-scaling-stroke"/>')
    for name in data["dots"]:
        c, hidden = at(name) or (0.0, 0.0), "" if at(name) else ' style="display:none"'
        body.append(f'<circle class="mech-dot" data-joint="{name}"{hidden} cx="{num(c[0])}" cy="{num(c[1])}" '
                    f'r="{num(0.4 * size)}" fill="{ROLE_COLOURS["point"]}"/>')
    for index, arrow in enumerate(data["arrows"]):
        p = at(arrow["at"])
        vector = member["vectors"][index]
        d = ""
        if p is not None and vector[2 * frame] is not None:
            d = _arrow_d(p, (vector[2 * frame] * step, vector[2 * frame + 1] * step), size)
        body.append(f'<path class="mech-arrow" data-arrow="{index}" data-kind="{arrow["kind"]}" d="{d}" '
                    f'fill="none" stroke="{arrow["colour"]}" stroke-width="2" vector-effect="non-scaling-stroke"/>')
    font = 1.25 * size
    text: list[str] = []
    if data["labels"]:
        for name in list(joints) + list(data["dots"]):
            c, hidden = at(name) or (0.0, 0.0), "" if at(name) else ' style="display:none"'
            text.append(f'<text class="mech-label" data-joint="{name}"{hidden} x="{num(c[0] + 0.6 * size)}" '
                        f'y="{num(-c[1] - 0.6 * size)}">{_subscripted(data.get("names", {}).get(name, _digits_below(name)), font)}</text>')
    for index, arrow in enumerate(data["arrows"]):
        p, vector = at(arrow["at"]), data["members"][member_index]["vectors"][index]
        shown = p is not None and vector[2 * frame] is not None
        tip = (0.0, 0.0)
        if p is not None and shown:
            tip = (p[0] + vector[2 * frame] * step, p[1] + vector[2 * frame + 1] * step)
        hidden = "" if shown else ' style="display:none"'
        text.append(f'<text class="mech-arrow-label" data-arrow="{index}" data-kind="{arrow["kind"]}"{hidden} '
                    f'fill="{arrow["colour"]}" x="{num(tip[0] + 0.4 * size)}" y="{num(-tip[1] - 0.4 * size)}">'
                    f'{_subscripted(arrow["label"], font)}</text>')
    label = html_text.escape(data["title"] or "mechanism", quote=False)
    desc = f"<desc>{html_text.escape(description, quote=False)}</desc>" if description else ""
    return (f'<svg class="mech-still" xmlns="http://www.w3.org/2000/svg" role="img" '
            f'viewBox="{num(view[0])} {num(-view[1] - view[3])} {num(view[2])} {num(view[3])}" '
            f'preserveAspectRatio="xMidYMid meet"><title>{label}</title>{desc}'
            f'<g class="mech-world" transform="scale(1,-1)">{"".join(body)}</g>'
            f'<g class="mech-text" font-size="{num(font)}" font-family="sans-serif">{"".join(text)}</g></svg>')


def _subscripted(label: str, font: float) -> str:
    """``v_B`` as SVG text: v with a subscript B (``_`` subscripts the one character after it)."""
    parts = re.split(r"_(.)", label)
    out = []
    for index, part in enumerate(parts):
        if index % 2:
            out.append(f'<tspan dy="{0.3 * font:.4g}" font-size="{0.7 * font:.4g}">{html_text.escape(part)}</tspan>'
                       f'<tspan dy="{-0.3 * font:.4g}"></tspan>')
        elif part:
            out.append(html_text.escape(part))
    return "".join(out)


def _path_d(data: dict[str, Any], member: dict[str, Any], name: str) -> str:
    """A point's whole path (SVG path data), broken where the member does not assemble."""
    xy = member["xy"].get(name, [])
    x0, y0, step = data["origin"][0], data["origin"][1], data["step"]
    out, pen = [], False
    for stored in _decoded(xy, len(data["phi"])) if xy else []:
        if stored is None:
            pen = False
            continue
        out.append(f'{"L" if pen else "M"}{x0 + step * stored[0]:.6g},{y0 + step * stored[1]:.6g}')
        pen = True
    full = all(v == "1" for v in member["valid"])
    return " ".join(out) + (" Z" if full and out else "")


def _arrow_d(p: tuple[float, float], v: tuple[float, float], size: float) -> str:
    """An arrow from p along v with a head of 1.2·size (SVG path data); the player draws it alike."""
    length = math.hypot(*v)
    if length == 0:
        return ""
    ux, uy = v[0] / length, v[1] / length
    tip = (p[0] + v[0], p[1] + v[1])
    head = min(1.2 * size, 0.5 * length)
    left = (tip[0] - head * ux - 0.5 * head * uy, tip[1] - head * uy + 0.5 * head * ux)
    right = (tip[0] - head * ux + 0.5 * head * uy, tip[1] - head * uy - 0.5 * head * ux)
    return (f"M{p[0]:.6g},{p[1]:.6g} L{tip[0]:.6g},{tip[1]:.6g} M{left[0]:.6g},{left[1]:.6g} "
            f"L{tip[0]:.6g},{tip[1]:.6g} L{right[0]:.6g},{right[1]:.6g}")
