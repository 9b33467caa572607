"""Any linkage built from a frame, a driving crank and Assur groups, solved group after group.

The lecture's analysis sequence starts with the structure and then solves "link after link":
the crank, then each Assur group from joints already known. :class:`Linkage` does exactly that
with the closed-form blocks of layer 2, vectorized over the crank angles, so a deep-well pump, a
six-bar or Jansen's leg is solved like the book's own classes: ``solve`` with ``order`` 0, 1 or 2,
the checks, the generic solver's cross-check, drawings and energy.

Every link has its own frame (its first joint at the origin, its x axis at the link's angle), and
every joint or point of a link has fixed coordinates in it; a point's motion is then that of the
link, ``r = r_P + (u + iw)·exp(iθ)`` (:func:`~mechanisms.core.motion.point_on_link`). A group
with no closed form (a class III group, :class:`~mechanisms.linkages.groups.Triad`) is solved by
Newton's method continued from the user's guess (:mod:`mechanisms.blocks.bars`).

Linkages are described in Python (this module) or in a TOML file
(:mod:`mechanisms.linkages.linkage_file`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..blocks.bars import solve_bars
from ..blocks.circle_circle import hinge
from ..blocks.circle_line import slider_on_line
from ..blocks.crank import crank_angle, crank_pin
from ..blocks.lever_block import lever_block
from ..blocks.lines import LineIntersection, circle_on_line, line_intersection, parallel_directions
from ..core.errors import AssemblyError, MechanismError, StructureError, describe_range
from ..core.motion import AngleMotion, Motion, PointMotion, fixed_point, point_on_link, polar
from ..core.validate import require_branch, require_finite, require_length
from .base import Bar, Block, Ground, Guide, Mechanism, Solution
from .chunks import solve_in_chunks
from .groups import KINDS, PRP, RPP, RPR, RRP, RRR, Crank, Group, Line, LinkPoint, Triad

__all__ = ["Linkage", "Pair", "FRAME"]

FRAME = "frame"
"""The name of the fixed link."""

_SAMPLES = 3600
"""Crank positions sampled to find where a linkage assembles (0.1° apart)."""


class _GroupError(StructureError):
    """A group that cannot be, whatever the crank angle: the message, the group and its field at fault.

    The linkage file's reader turns the group and the field into the file's place and key
    (``[[dyad]] #2 ('K'): key 'guides'``); for a linkage made in Python the message names the group.
    """

    def __init__(self, message: str, key: str | None = None, group: Any = None, cause: str | None = None):
        super().__init__(message)
        self.key, self.group, self.cause = key, group, message if cause is None else cause


@dataclass(frozen=True)
class Pair:
    """A kinematic pair: ``kind`` "R" (a hinge at ``joint``) or "P" (a sliding pair), between two links."""

    kind: str
    first: str
    second: str
    joint: str


@dataclass
class _Link:
    """A link's frame: its first joint (the pole, at the origin) and the joints and points fixed to it."""

    pole: str | None
    local: dict[str, complex] = field(default_factory=dict)
    turns: bool = True          # False for a block that only translates (its angle is constant)
    role: str = "coupler"


def _apex(base: float, first: float, second: float, side: int) -> complex:
    """The apex of a triangle on a base of length ``base`` along +x: at ``first`` from the origin and
    ``second`` from the base's end, to the left (side +1) or right (−1); m. Computed on the lengths divided
    by a power of two near the largest (exact, and no square overflows or underflows), then scaled back."""
    size = math.ldexp(1.0, math.frexp(max(base, first, second))[1])
    base, first, second = base / size, first / size, second / size
    total, difference = first + second, abs(first - second)
    product = (total - base) * (total + base) * (base - difference) * (base + difference)
    if product < -1e-12 * (total * base) ** 2:
        raise StructureError(f"no triangle has sides {base * size:g}, {first * size:g} and {second * size:g} m")
    along = 0.5 * (base + (first - second) * (first + second) / base)
    return complex(along, side * math.sqrt(max(product, 0.0)) / (2.0 * base)) * size


def _given(length: float | None) -> float:
    """A group's length, checked when the linkage was made (so never ``None`` while solving)."""
    if length is None:
        raise StructureError("a group of a linkage needs its lengths")
    return length


def _kind(group: Group) -> str:
    return KINDS.get(type(group), type(group).__name__)


def describe_group(group: Group) -> str:
    """A group in words, for messages and the structure report: ``RRR B (from A, C)``."""
    if isinstance(group, Crank):
        return f"crank {group.pivot} → {group.pin}"
    if isinstance(group, LinkPoint):
        return f"point {group.name} on {group.link or '-'.join(group.axis or ())}"
    if isinstance(group, Triad):
        return f"group {', '.join(group.joints)} (bars {', '.join(a + b for a, b, _ in group.bars)})"
    needs = ", ".join(group.needs)
    return f"{_kind(group)} {', '.join(group.finds)}" + (f" (from {needs})" if needs else "")


class Linkage(Mechanism):
    """A planar linkage composed of a frame, one driving crank and Assur groups.

    Parameters
    ----------
    frame : mapping of str to complex or (float, float)
        The fixed joints and their positions (m).
    groups : sequence of Group
        The crank (:class:`~mechanisms.linkages.groups.Crank`, with its ``length``), then the groups
        and points, in any order that lets each find what it needs: they are put in an order in
        which every group's joints and links are known before it.
    name : str
        What to call the linkage in messages and tables.
    masses : mapping, optional
        Mass properties by body name: ``{"BC": {"mass": 2.0, "along": 0.15, "inertia": 0.01}}``
        (kg, m, kg·m²), for :func:`mechanisms.analysis.energy.linkage_masses`.
    source : str, optional
        The file the linkage was read from, named in tables and messages.
    loads : sequence of mapping, optional
        Constant loads by body: ``{"body": "slider", "force": (Fx, Fy), "along": 0.0, "left": 0.0}`` (N, m) or
        ``{"body": "rocker", "torque": T}`` (N·m), for :func:`mechanisms.analysis.energy.linkage_loads`.
    gravity : float, optional
        g (m/s²) along −y for the linkage's forces (:func:`mechanisms.analysis.kinetostatics.linkage_forces`);
        0 (no gravity) by default.

    Raises
    ------
    StructureError
        A joint or link no group finds, a cycle, a name used twice, two cranks, a point placed on
        joints of different links, a group of the wrong number of bars (degrees of freedom ≠ 1), a name
        that is not a non-empty string; a group with no position at any crank angle: an RRR between two
        joints that are one point, an RPR whose block is its pivot, a PRP whose two guides on one link are
        parallel, an RPP whose slot is parallel to its guide.
    InvalidParameterError
        A length that is not finite and > 0, a branch that is not ±1, a position that is not finite.

    Notes
    -----
    The link names and the pole of each link come from the groups: the crank's pivot is its pole,
    an RRR's first link has its pole at ``first`` and the second at ``second``, an RRP's rod at
    ``known``, an RPR's lever at ``pivot``; blocks and yokes have their pole at their joint.
    """

    def __init__(self, frame: Mapping[str, Any], groups: Sequence[Group], name: str = "linkage",
                 masses: Mapping[str, Mapping[str, float]] | None = None, source: str | None = None,
                 loads: Sequence[Mapping[str, Any]] = (), gravity: float = 0.0):
        self.name = str(name)
        self.source = source
        self.loads = [dict(load) for load in loads]
        self.gravity = require_finite("gravity", gravity)
        if not isinstance(frame, Mapping):
            raise StructureError(f"{self.name}: the frame must map joint names to points [x, y] in m: got {frame!r}")
        if isinstance(groups, (str, bytes)) or not isinstance(groups, Sequence):
            raise StructureError(f"{self.name}: the groups must be a sequence (the crank and Assur groups): "
                                 f"got {groups!r}")
        self.frame = {str(k): self._position(f"frame.{k}", v) for k, v in dict(frame).items()}
        if not self.frame:
            raise StructureError(f"{self.name}: the frame has no joints: give the crank's pivot at least")
        self.masses = {str(k): dict(v) for k, v in (masses or {}).items()}
        self._links: dict[str, _Link] = {FRAME: _Link(None, dict(self.frame), turns=False, role="frame")}
        self._owner: dict[str, str] = {j: FRAME for j in self.frame}   # the link that first carried a joint
        self._pairs: list[Pair] = []
        self._groups = self._ordered(list(groups))
        for group in self._groups:
            self._add(group)
        self.links = {name: link.pole for name, link in self._links.items() if name != FRAME and link.turns  # type: ignore[misc]
                      and link.pole is not None}
        self._intervals: list[tuple[float, float]] | None = None

    # --- construction --------------------------------------------------------------------------

    @staticmethod
    def _position(name: str, value: Any) -> complex:
        if isinstance(value, (bool, str)):
            raise StructureError(f"{name} must be a point [x, y] in m: got {value!r}")
        try:
            point = complex(value) if not isinstance(value, (list, tuple)) else complex(float(value[0]), float(value[1]))
            if isinstance(value, (list, tuple)) and len(value) != 2:
                raise ValueError
        except (TypeError, ValueError, IndexError):
            raise StructureError(f"{name} must be a point [x, y] in m: got {value!r}") from None
        if not (math.isfinite(point.real) and math.isfinite(point.imag)):
            raise StructureError(f"{name} must be a finite point [x, y] in m: got {value!r}")
        return point

    def _ordered(self, groups: list[Group]) -> tuple[Group, ...]:
        """The groups in an order in which each one's joints and links are known before it."""
        cranks = [g for g in groups if isinstance(g, Crank)]
        if len(cranks) != 1:
            raise StructureError(f"{self.name}: a linkage has one driving crank (one degree of freedom), "
                                 f"not {len(cranks)}")
        found: dict[str, str] = {j: "the frame" for j in self.frame}
        links = {FRAME}
        for group in groups:
            _check_names(group)
        for group in groups:
            for joint in group.finds:
                if joint in found:
                    raise StructureError(f"{self.name}: joint {joint!r} is found twice: by {describe_group(group)} "
                                         f"and by {found[joint]}")
                found[joint] = describe_group(group)
            for link in group.links:
                if link in links:
                    raise StructureError(f"{self.name}: link {link!r} is named twice (by {describe_group(group)})")
                links.add(link)
        known, known_links = set(self.frame), {FRAME}
        ordered: list[Group] = []
        waiting = [cranks[0]] + [g for g in groups if not isinstance(g, Crank)]
        while waiting:
            ready = next((g for g in waiting if set(_needs(g)) <= known and set(_needs_links(g)) <= known_links),
                         None)
            if ready is None:
                lines = []
                for g in waiting:
                    missing = [j for j in _needs(g) if j not in known]
                    unknown = [j for j in missing if j not in found]
                    missing_links = [k for k in _needs_links(g) if k not in known_links]
                    if unknown or [k for k in missing_links if k not in links]:
                        what = ", ".join([f"joint {j!r}" for j in unknown]
                                         + [f"link {k!r}" for k in missing_links if k not in links])
                        lines.append(f"{describe_group(g)} needs {what}, which no group finds")
                    else:
                        lines.append(f"{describe_group(g)} waits for "
                                     + ", ".join([f"{j} ({found[j]})" for j in missing] + missing_links))
                cycle = all("waits for" in line for line in lines)
                raise StructureError(f"{self.name}: " + ("these groups need each other (a cycle): " if cycle else "")
                                     + "; ".join(lines))
            waiting.remove(ready)
            ordered.append(ready)
            known.update(ready.finds)
            known_links.update(ready.links)
        return tuple(ordered)

    def _carrier(self, joint: str) -> str:
        return self._owner[joint]

    def _new_link(self, name: str, pole: str | None, local: dict[str, complex], turns: bool = True,
                  role: str = "coupler") -> None:
        self._links[name] = _Link(pole, local, turns, role)
        for joint in local:
            self._owner.setdefault(joint, name)

    def _line(self, line: Line, what: str) -> Line:
        if line.link not in self._links:
            raise StructureError(f"{self.name}: {what}: no link {line.link!r}")
        point = self._position(f"{what}.point", line.point)
        return Line(line.link, point, require_finite(f"{what}.angle", line.angle))

    def _add(self, group: Group) -> None:
        where = describe_group(group)
        try:
            self._add_checked(group)
        except MechanismError as error:
            if isinstance(error, StructureError) and str(error).startswith(self.name + ":"):
                raise
            key = error.key if isinstance(error, _GroupError) else getattr(error, "name", None)
            raise _GroupError(f"{self.name}: {where}: {error}", key if isinstance(key, str) else None,
                              group, str(error)) from None

    def _coincide(self, first: str, second: str) -> bool:
        """True if the joints ``first`` and ``second`` are one point of one link (the frame's included) at every
        crank angle: a group that needs them as two points is undefined."""
        return first == second or any(first in item.local and second in item.local
                                      and item.local[first] == item.local[second] for item in self._links.values())

    def _add_checked(self, group: Group) -> None:
        if isinstance(group, Crank):
            length = require_length("length", group.length)
            if group.pivot not in self.frame:
                raise StructureError(f"the crank's pivot {group.pivot!r} must be a joint of the frame")
            self._new_link(group.link, group.pivot, {group.pivot: 0j, group.pin: complex(length)}, role="crank")
            self._pairs.append(Pair("R", FRAME, group.link, group.pivot))
        elif isinstance(group, RRR):
            first = require_length("first_length", group.first_length)
            second = require_length("second_length", group.second_length)
            require_branch(group.branch)
            if self._coincide(group.first, group.second):
                raise _GroupError(f"the known joints {group.first!r} and {group.second!r} are one point: the "
                                  f"joint {group.joint!r} could be anywhere on a circle about it", "from")
            pairs = [Pair("R", self._carrier(group.first), group.first_link, group.first),
                     Pair("R", group.first_link, group.second_link, group.joint),
                     Pair("R", self._carrier(group.second), group.second_link, group.second)]
            self._new_link(group.first_link, group.first, {group.first: 0j, group.joint: complex(first)})
            self._new_link(group.second_link, group.second, {group.second: 0j, group.joint: complex(second)},
                           role="rocker")
            self._pairs += pairs
        elif isinstance(group, RRP):
            length = require_length("length", group.length)
            require_branch(group.branch)
            line = self._line(group.guide, "guide")
            pairs = [Pair("R", self._carrier(group.known), group.link, group.known),
                     Pair("R", group.link, group.slider, group.joint), Pair("P", group.slider, line.link, group.joint)]
            self._new_link(group.link, group.known, {group.known: 0j, group.joint: complex(length)})
            self._new_link(group.slider, group.joint, {group.joint: 0j}, turns=line.link != FRAME, role="slider")
            self._pairs += pairs
        elif isinstance(group, RPR):
            if self._coincide(group.block, group.pivot):
                raise _GroupError(f"the block {group.block!r} and the pivot {group.pivot!r} are one point: the "
                                  "lever through them has no direction", "pivot")
            pairs = [Pair("R", self._carrier(group.block), group.slider, group.block),
                     Pair("P", group.slider, group.lever, group.block),
                     Pair("R", self._carrier(group.pivot), group.lever, group.pivot)]
            local = {group.pivot: 0j}
            if group.joint is not None:
                local[group.joint] = complex(require_length("length", group.length))
            self._new_link(group.slider, group.block, {group.block: 0j}, role="slider")
            self._new_link(group.lever, group.pivot, local, role="lever")
            self._pairs += pairs
        elif isinstance(group, PRP):
            one, two = self._line(group.first_guide, "first guide"), self._line(group.second_guide, "second guide")
            if one.link == two.link and parallel_directions(one.angle, two.angle):
                raise _GroupError(f"its two guides (both on {one.link!r}) are parallel: they never cross at one "
                                  f"point, so the joint {group.joint!r} has no position", "guides")
            self._pairs += [Pair("P", one.link, group.first_slider, group.joint),
                            Pair("R", group.first_slider, group.second_slider, group.joint),
                            Pair("P", group.second_slider, two.link, group.joint)]
            self._new_link(group.first_slider, group.joint, {group.joint: 0j}, turns=one.link != FRAME,
                           role="slider")
            self._new_link(group.second_slider, group.joint, {group.joint: 0j}, turns=two.link != FRAME,
                           role="slider")
        elif isinstance(group, RPP):
            guide = self._line(group.guide, "guide")
            if parallel_directions(0.0, require_finite("slot_angle", group.slot_angle)):
                raise _GroupError("the slot is parallel to the guide (slot angle 0° or 180°): the yoke's "
                                  "position along the guide is free", "slot_angle")
            self._pairs += [Pair("R", self._carrier(group.block), group.slider, group.block),
                            Pair("P", group.slider, group.yoke, group.block),
                            Pair("P", group.yoke, guide.link, group.joint)]
            self._new_link(group.slider, group.block, {group.block: 0j}, turns=guide.link != FRAME, role="slider")
            self._new_link(group.yoke, group.joint, {group.joint: 0j}, turns=guide.link != FRAME, role="slider")
        elif isinstance(group, Triad):
            self._add_triad(group)
        elif isinstance(group, LinkPoint):
            self._add_point(group)
        else:
            raise StructureError(f"not a group this package can solve: {group!r}")

    def _add_triad(self, group: Triad) -> None:
        if len(group.guess) != len(group.joints):
            raise StructureError(f"give a guess for each of the {len(group.joints)} joints")
        guess = {j: self._position(f"guess.{j}", g) for j, g in zip(group.joints, group.guess)}
        lengths = {}
        for a, b, length in group.bars:
            lengths[frozenset((a, b))] = require_length(f"bar {a}{b}", length)
        bodies = group.bodies()
        names = group.links
        if len(names) != len(bodies):
            raise StructureError(f"name each of its {len(bodies)} links ({', '.join(''.join(b) for b in bodies)})")
        pairs: list[Pair] = []
        members: dict[str, list[str]] = {}
        for name, body in zip(names, bodies):
            a, b = body[0], body[1]
            local = {a: 0j, b: complex(lengths[frozenset((a, b))])}
            if len(body) == 3:
                c = body[2]
                side = 1 if ((guess[b] - guess[a]).conjugate() * (guess[c] - guess[a])).imag >= 0 else -1
                local[c] = _apex(lengths[frozenset((a, b))], lengths[frozenset((a, c))],
                                 lengths[frozenset((b, c))], side)
            for joint in body:
                if joint in group.joints:
                    members.setdefault(joint, []).append(name)
                else:
                    pairs.append(Pair("R", self._carrier(joint), name, joint))
            self._new_link(name, a, local, role="rocker")
        for joint, carried in members.items():
            pairs += [Pair("R", carried[0], other, joint) for other in carried[1:]]
        freedom = 3 * len(bodies) - 2 * len(pairs)
        if freedom != 0 or len(group.bars) != 2 * len(group.joints):
            raise StructureError(f"the group of joints {', '.join(group.joints)} has {len(bodies)} links and "
                                 f"{len(pairs)} pairs, so it adds {freedom:+d} degrees of freedom "
                                 f"(W = {1 + freedom}); an Assur group adds none: {len(group.joints)} joints "
                                 f"need {2 * len(group.joints)} bars, not {len(group.bars)}")
        self._pairs += pairs

    def _add_point(self, group: LinkPoint) -> None:
        link = group.link
        if group.axis is not None:
            p, q = group.axis
            carriers = [name for name, item in self._links.items() if p in item.local and q in item.local]
            if link and link not in carriers:
                carriers = []
            if not carriers:
                raise StructureError(f"joints {p!r} and {q!r} are not on one link"
                                     + (f" (not both on {link!r})" if link else ""))
            link = carriers[0]
        if link not in self._links:
            raise StructureError(f"no link {link!r}; links: {', '.join(self._links)}")
        item = self._links[link]
        if group.axis is None:
            if group.along is None:
                raise StructureError("give its position on the link: along (and left), m")
            local = complex(require_finite("along", group.along), require_finite("left", group.left))
        else:
            origin, end = item.local[group.axis[0]], item.local[group.axis[1]]
            base = abs(end - origin)
            if base == 0.0:
                raise StructureError(f"joints {group.axis[0]!r} and {group.axis[1]!r} coincide on link {link!r}")
            unit = (end - origin) / base
            if group.distances is not None:
                first = require_length("distances[0]", group.distances[0])
                second = require_length("distances[1]", group.distances[1])
                offset = _apex(base, first, second, require_branch(group.branch))
            else:
                if group.along is None:
                    raise StructureError("give along (and left) or distances, m")
                offset = complex(require_finite("along", group.along), require_finite("left", group.left))
            local = origin + offset * unit
        item.local[group.name] = local
        self._owner.setdefault(group.name, link)

    # --- the structure -------------------------------------------------------------------------

    def groups(self) -> tuple[Group, ...]:
        return self._groups

    def pairs(self) -> list[Pair]:
        """The kinematic pairs, in the order the groups add them."""
        return list(self._pairs)

    def link_joints(self) -> dict[str, list[str]]:
        """Every link (the frame first) with the joints and points fixed to it."""
        return {name: list(item.local) for name, item in self._links.items()}

    def mobility(self) -> int:
        """Degrees of freedom W = 3n − 2p₁ by the structural formula (n moving links, p₁ lower pairs)."""
        return 3 * (len(self._links) - 1) - 2 * len(self._pairs)

    def group_kind(self, group: Group) -> tuple[str, str]:
        """The class and kind of a group: ``("II", "RRR")``, ``("III", "triad")``, ``("I", "crank")``."""
        if isinstance(group, Crank):
            return "I", "crank"
        if isinstance(group, Triad):
            triangle = any(len(body) == 3 for body in group.bodies())
            return ("III" if len(group.joints) == 3 and triangle else f"≥ III ({len(group.joints)} joints)"), "bars"
        if isinstance(group, LinkPoint):
            return "-", "point"
        return "II", _kind(group)

    def describe(self) -> str:
        return self.name + (f" ({self.source})" if self.source else "")

    def __repr__(self) -> str:
        return f"Linkage(name={self.name!r}, frame={self.frame!r}, groups={list(self._groups)!r})"

    def parameters(self) -> dict[str, object]:
        return {"file": self.source} if self.source else {"name": self.name}

    def _rescaled(self, factor: float) -> "Linkage":
        """The same linkage with every length, position and guess multiplied by ``factor`` (a power of four)."""
        return Linkage({name: point * factor for name, point in self.frame.items()},
                       [_scaled_group(group, factor) for group in self._groups], self.name, self.masses, self.source,
                       self.loads, self.gravity)

    # --- solving -------------------------------------------------------------------------------

    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        if any(isinstance(g, Triad) for g in self._groups):
            return self._solve_block(crank, order)     # Newton's continuation over all positions at once
        return solve_in_chunks(self._solve_block, crank, order, self.links)

    def _solve_block(self, crank: AngleMotion, order: int, upto: int | None = None, raw: bool = False) -> Solution:
        phi = crank.value
        state = _State(phi, order)
        for joint, position in self.frame.items():
            state.points[joint] = fixed_point(position, phi, order)
        for index, group in enumerate(self._groups[:upto]):
            try:
                self._step(group, index, crank, state)
            except AssemblyError as error:
                if raw:        # finding where it assembles: the error as the block gave it
                    raise
                raise self._assembly_error(group, error) from None
        angles = {name: state.angles[name] for name in self.links if name in state.angles}
        return Solution(phi, order, angles=angles, points=state.points, links=self.links, sliders=state.sliders,
                        singular=state.singular)

    def _assembly_error(self, group: Group, error: AssemblyError) -> AssemblyError:
        reason = f"{self.name}: {describe_group(group)} cannot be assembled: {error.reason}"
        try:
            intervals = self.assembly_intervals()
        except MechanismError:
            intervals = None
        valid = None
        if intervals == []:
            reason += " (the linkage assembles at no crank angle)"
        elif intervals is not None and len(intervals) == 1:
            valid = intervals[0]
        elif intervals:
            reason += " (it assembles for crank angles in " + " and ".join(
                describe_range(lo, hi) for lo, hi in intervals) + ")"
        return AssemblyError(reason, error.angles, valid)

    def _pose(self, link: str, state: "_State") -> tuple[PointMotion | complex, AngleMotion | None]:
        """The pole and angle of a link (``None`` for the frame)."""
        item = self._links[link]
        if link == FRAME:
            return 0j, None
        pole = state.points[item.pole] if item.pole is not None else 0j
        return pole, state.angles[link]

    def _point(self, link: str, local: complex, state: "_State") -> PointMotion:
        """A point fixed to a link, at ``local`` in the link's frame."""
        if link == FRAME:
            return fixed_point(local, state.phi, state.order)
        item = self._links[link]
        pole = state.points[item.pole] if item.pole is not None else 0j
        return point_on_link(pole, state.angles[link], local.real, local.imag)

    def _line_motion(self, line: Line, state: "_State") -> tuple[PointMotion | complex, AngleMotion | float]:
        """A guide's point and direction: fixed numbers for the frame's, motions for a moving link's."""
        if line.link == FRAME:
            return line.point, line.angle
        angle = state.angles[line.link]
        turned = AngleMotion(angle.value + line.angle, angle.velocity, angle.acceleration)
        return self._point(line.link, line.point, state), turned

    def _fixed_angle(self, value: float, state: "_State") -> AngleMotion:
        shape = np.shape(state.phi)
        zero = np.zeros(shape)
        return AngleMotion(np.full(shape, value), zero if state.order else None, zero if state.order > 1 else None)

    def _step(self, group: Group, index: int, crank: AngleMotion, state: "_State") -> None:
        phi, points, angles = state.phi, state.points, state.angles
        if isinstance(group, Crank):
            points[group.pin] = crank_pin(crank, self._links[group.link].local[group.pin].real,
                                          self.frame[group.pivot])
            angles[group.link] = crank
        elif isinstance(group, RRR):
            joint = hinge(points[group.first], points[group.second], _given(group.first_length),
                          _given(group.second_length),
                          group.branch, phi)
            points[group.joint] = joint.point
            angles[group.first_link], angles[group.second_link] = joint.angle_p, joint.angle_q
            state.singular = state.singular | joint.singular
        elif isinstance(group, RRP):
            guide = group.guide
            if guide.link == FRAME:
                block = slider_on_line(points[group.known], _given(group.length), guide.point, guide.angle, group.branch, phi)
                points[group.joint], angles[group.link] = block.point, block.rod_angle
                angles[group.slider] = self._fixed_angle(guide.angle, state)
                state.sliders[group.slider], singular = block.travel, block.singular
            else:
                through, direction = self._line_motion(guide, state)
                assert isinstance(direction, AngleMotion)
                found = circle_on_line(points[group.known], _given(group.length), through, direction, group.branch, phi)
                points[group.joint] = found.point
                angles[group.link] = polar(found.point - points[group.known])[1]
                angles[group.slider] = direction
                state.sliders[group.slider], singular = found.along, found.singular
            state.singular = state.singular | singular
        elif isinstance(group, RPR):
            pivot: PointMotion | complex = (self.frame[group.pivot] if group.pivot in self.frame
                                            else points[group.pivot])
            lever = lever_block(points[group.block], pivot)
            angles[group.lever] = angles[group.slider] = lever.lever_angle
            state.sliders[group.slider] = lever.distance
            if group.joint is not None:
                points[group.joint] = point_on_link(pivot, lever.lever_angle, _given(group.length))
            state.singular = state.singular | lever.singular
        elif isinstance(group, PRP):
            first = self._line_motion(group.first_guide, state)
            second = self._line_motion(group.second_guide, state)
            crossing = _broadcast(line_intersection(*first, *second, angles=phi), np.shape(phi))
            points[group.joint] = crossing.point
            state.sliders[group.first_slider] = crossing.along_first
            state.sliders[group.second_slider] = crossing.along_second
            state.singular = state.singular | crossing.singular
            for name, (_, direction) in ((group.first_slider, first), (group.second_slider, second)):
                angles[name] = (direction if isinstance(direction, AngleMotion)
                                else self._fixed_angle(direction, state))
        elif isinstance(group, RPP):
            through, direction = self._line_motion(group.guide, state)
            if isinstance(direction, AngleMotion):
                slot: AngleMotion | float = AngleMotion(direction.value + group.slot_angle, direction.velocity,
                                                        direction.acceleration)
            else:
                slot = direction + group.slot_angle
            crossing = _broadcast(line_intersection(points[group.block], slot, through, direction, angles=phi),
                                  np.shape(phi))
            points[group.joint] = crossing.point
            state.singular = state.singular | crossing.singular
            state.sliders[group.slider] = crossing.along_first * -1.0     # the block from the yoke's point
            state.sliders[group.yoke] = crossing.along_second
            for name, angle in ((group.slider, slot), (group.yoke, direction)):
                angles[name] = angle if isinstance(angle, AngleMotion) else self._fixed_angle(angle, state)
        elif isinstance(group, Triad):
            needs = group.needs

            def known_at(angles_at: np.ndarray) -> dict[str, np.ndarray]:
                before = self._solve_block(crank_angle(angles_at, 1.0, 0.0, 0), 0, upto=index, raw=True)
                return {j: before.point(j).value for j in needs}

            solved = solve_bars(known_at, {j: points[j] for j in needs}, group.joints,
                                [(a, b, float(length)) for a, b, length in group.bars], group.guess,
                                group.guess_angle, phi, state.order)
            points.update(solved.points)
            for name, body in zip(group.links, group.bodies()):
                angles[name] = polar(points[body[1]] - points[body[0]])[1]
            state.singular = state.singular | solved.singular
        elif isinstance(group, LinkPoint):
            link = self._owner[group.name]
            points[group.name] = self._point(link, self._links[link].local[group.name], state)

    # --- where it assembles --------------------------------------------------------------------

    def _assembles(self, phi: np.ndarray) -> np.ndarray:
        """Mask of the crank angles at which the linkage assembles."""
        ok = np.ones(phi.shape, dtype=bool)
        for _ in range(len(self._groups) + 2):
            if not ok.any():
                break
            try:
                self._solve_block(crank_angle(phi[ok], 1.0, 0.0, 0), 0, raw=True)
                break
            except AssemblyError as error:
                if error.angles is None or error.angles.size == 0:
                    ok[:] = False
                    break
                ok[ok] &= ~np.isin(phi[ok], error.angles)
        return ok

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Crank-angle intervals (rad) in which the linkage assembles, found numerically.

        The crank angles are sampled 0.1° apart and each end of an interval is then found by
        bisection to about 1e-12 rad; a gap narrower than the sampling can be missed. A full turn is
        ``[(−π, π)]``.
        """
        if self._intervals is not None:
            return list(self._intervals)
        self._intervals = self._find_intervals()
        return list(self._intervals)

    def _edge(self, good: float, bad: float) -> float:
        """The end of an interval of assembly between a crank angle where it assembles and one where not."""
        for _ in range(45):
            middle = 0.5 * (good + bad)
            if self._assembles(np.array([middle]))[0]:
                good = middle
            else:
                bad = middle
        return good

    def _find_intervals(self) -> list[tuple[float, float]]:
        triads = [g for g in self._groups if isinstance(g, Triad)]
        if triads:
            # Newton's continuation decides the assembly mode: the interval is the one reached from the guess
            start = triads[0].guess_angle
            phi = start + np.linspace(-2 * math.pi, 2 * math.pi, 2 * _SAMPLES + 1)
            ok = self._assembles(phi)
            middle = _SAMPLES
            if not ok[middle]:
                return []
            low, high = middle, middle
            while low > 0 and ok[low - 1]:
                low -= 1
            while high < phi.size - 1 and ok[high + 1]:
                high += 1
            lo = phi[0] if low == 0 else self._edge(phi[low], phi[low - 1])
            hi = phi[-1] if high == phi.size - 1 else self._edge(phi[high], phi[high + 1])
            return [(-math.pi, math.pi)] if hi - lo >= 2 * math.pi else [(lo, hi)]
        phi = np.linspace(-math.pi, math.pi, _SAMPLES, endpoint=False)
        ok = self._assembles(phi)
        if ok.all():
            return [(-math.pi, math.pi)]
        step = phi[1] - phi[0]
        intervals = []
        n = phi.size
        for i in range(n):
            if ok[i] and not ok[i - 1]:                 # an interval starts at sample i
                j = i
                while ok[(j + 1) % n]:
                    j += 1
                turn = (j // n) * 2 * math.pi           # an interval through ±180° ends past π
                start = self._edge(phi[i], phi[i] - step)
                stop = self._edge(phi[j % n] + turn, phi[j % n] + turn + step)
                intervals.append((start, stop))
        return sorted(intervals)

    # --- drawing and the generic solver's view ---------------------------------------------------

    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        items: list[Bar | Ground | Block | Guide] = []
        used = {p.joint for p in self._pairs if FRAME in (p.first, p.second) and p.kind == "R"}
        items += [Ground(j) for j in self.frame if j in used]
        for group in self._groups:
            for line in _guides(group):
                if line.link == FRAME:
                    items.append(Guide(line.point, line.angle))
        for name, item in self._links.items():
            if name == FRAME:
                continue
            joints = list(item.local)
            if item.role == "slider":
                items.append(Block(joints[0], name if item.turns else self._block_angle(name)))
                continue
            if len(joints) >= 3:
                joints = joints + [joints[0]]
            items.append(Bar(name, tuple(joints), item.role))
        return items

    def _block_angle(self, link: str) -> float:
        for group in self._groups:
            if isinstance(group, RRP) and group.slider == link:
                return group.guide.angle
            if isinstance(group, PRP):
                if group.first_slider == link:
                    return group.first_guide.angle
                if group.second_slider == link:
                    return group.second_guide.angle
            if isinstance(group, RPP):
                if group.yoke == link:
                    return group.guide.angle
                if group.slider == link:
                    return group.guide.angle + group.slot_angle
        return 0.0

    def preserved_distances(self) -> dict[tuple[str, str], float]:
        """The distances that stay constant: on each moving link, from each of its joints and points to the
        link's two defining joints (its pole and the first joint apart from it), which fixes the rigid body;
        2N distances for N points of a link, not the N(N − 1)/2 of every pair."""
        distances = {}
        for name, item in self._links.items():
            if name == FRAME:
                continue
            joints = list(item.local)
            first = joints[0]
            second = next((j for j in joints[1:] if item.local[j] != item.local[first]), None)
            for other in joints[1:]:
                for base in (first, second):
                    if base is not None and base != other and (other, base) not in distances:
                        distances[(base, other)] = abs(item.local[base] - item.local[other])
        return distances

    def coordinates(self, solution: Solution) -> list[Motion]:
        q: list[Motion] = []
        for group in self._groups:
            if isinstance(group, RRR):
                q += [solution.angle(group.first_link), solution.angle(group.second_link)]
            elif isinstance(group, RRP):
                q += [solution.angle(group.link), solution.slider(group.slider)]
            elif isinstance(group, RPR):
                q += [solution.angle(group.lever), solution.slider(group.slider)]
            elif isinstance(group, PRP):
                q += [solution.slider(group.first_slider), solution.slider(group.second_slider)]
            elif isinstance(group, RPP):
                q += [solution.slider(group.slider), solution.slider(group.yoke)]
            elif isinstance(group, Triad):
                for joint in group.joints:
                    p = solution.point(joint)
                    q += [Motion(*(None if d is None else np.real(d) for d in p.derivatives())),
                          Motion(*(None if d is None else np.imag(d) for d in p.derivatives()))]
        return q

    def constraints(self, q: Sequence[Any], phi: Any) -> tuple:
        """Φ(q, φ): each group's loop closure, with points as (x, y) pairs and link directions as unit
        vectors (cos, sin), numpy operations only (for the jets of :mod:`mechanisms.verify`)."""
        points: dict[str, tuple[Any, Any]] = {j: (p.real, p.imag) for j, p in self.frame.items()}
        units: dict[str, tuple[Any, Any]] = {FRAME: (1.0, 0.0)}
        residuals: list[Any] = []
        values = iter(q)

        def place(link: str, local: complex) -> tuple[Any, Any]:
            item = self._links[link]
            px, py = points[item.pole] if item.pole is not None and link != FRAME else (0.0, 0.0)
            c, s = units[link]
            return px + local.real * c - local.imag * s, py + local.real * s + local.imag * c

        def line(guide: Line) -> tuple[tuple[Any, Any], tuple[Any, Any]]:
            c0, s0 = units[guide.link]
            ca, sa = math.cos(guide.angle), math.sin(guide.angle)
            return place(guide.link, guide.point), (c0 * ca - s0 * sa, s0 * ca + c0 * sa)

        def close(a: tuple[Any, Any], b: tuple[Any, Any]) -> None:
            residuals.extend((a[0] - b[0], a[1] - b[1]))

        for group in self._groups:
            if isinstance(group, Crank):
                units[group.link] = (np.cos(phi), np.sin(phi))
                points[group.pin] = place(group.link, self._links[group.link].local[group.pin])
            elif isinstance(group, RRR):
                first, second = next(values), next(values)
                units[group.first_link] = (np.cos(first), np.sin(first))
                units[group.second_link] = (np.cos(second), np.sin(second))
                end = place(group.first_link, complex(_given(group.first_length)))
                close(end, place(group.second_link, complex(_given(group.second_length))))
                points[group.joint] = end
            elif isinstance(group, RRP):
                theta, s = next(values), next(values)
                units[group.link] = (np.cos(theta), np.sin(theta))
                (gx, gy), (ec, es) = line(group.guide)
                units[group.slider] = (ec, es)
                end = (gx + s * ec, gy + s * es)
                close(place(group.link, complex(_given(group.length))), end)
                points[group.joint] = end
            elif isinstance(group, RPR):
                xi, length = next(values), next(values)
                units[group.lever] = units[group.slider] = (np.cos(xi), np.sin(xi))
                px, py = points[group.pivot]
                close((px + length * np.cos(xi), py + length * np.sin(xi)), points[group.block])
                if group.joint is not None:
                    points[group.joint] = place(group.lever, complex(_given(group.length)))
            elif isinstance(group, PRP):
                s1, s2 = next(values), next(values)
                (ax, ay), (ac, as_) = line(group.first_guide)
                (bx, by), (bc, bs) = line(group.second_guide)
                units[group.first_slider], units[group.second_slider] = (ac, as_), (bc, bs)
                end = (ax + s1 * ac, ay + s1 * as_)
                close(end, (bx + s2 * bc, by + s2 * bs))
                points[group.joint] = end
            elif isinstance(group, RPP):
                along_slot, along_guide = next(values), next(values)
                (gx, gy), (ec, es) = line(group.guide)
                ca, sa = math.cos(group.slot_angle), math.sin(group.slot_angle)
                slot = (ec * ca - es * sa, es * ca + ec * sa)
                units[group.yoke], units[group.slider] = (ec, es), slot
                end = (gx + along_guide * ec, gy + along_guide * es)
                close((end[0] + along_slot * slot[0], end[1] + along_slot * slot[1]), points[group.block])
                points[group.joint] = end
            elif isinstance(group, Triad):
                for joint in group.joints:
                    points[joint] = (next(values), next(values))
                for a, b, length in group.bars:
                    dx, dy = points[a][0] - points[b][0], points[a][1] - points[b][1]
                    residuals.append((dx * dx + dy * dy - length * length) / (2.0 * length))
                for name, body in zip(group.links, group.bodies()):
                    dx, dy = points[body[1]][0] - points[body[0]][0], points[body[1]][1] - points[body[0]][1]
                    norm = np.sqrt(dx * dx + dy * dy)
                    units[name] = (dx / norm, dy / norm)
            elif isinstance(group, LinkPoint):
                link = self._owner[group.name]
                points[group.name] = place(link, self._links[link].local[group.name])
        return tuple(residuals)


@dataclass
class _State:
    """What is known while a linkage is solved group after group."""

    phi: np.ndarray
    order: int
    points: dict[str, PointMotion] = field(default_factory=dict)
    angles: dict[str, AngleMotion] = field(default_factory=dict)
    sliders: dict[str, Motion] = field(default_factory=dict)
    singular: Any = False

    def __post_init__(self):
        self.singular = np.zeros(np.shape(self.phi), dtype=bool)


def _times(value: Any, factor: float) -> Any:
    return None if value is None else value * factor


def _scaled_line(line: Line, factor: float) -> Line:
    return replace(line, point=line.point * factor)


_LENGTH_FIELDS: dict[type, tuple[str, ...]] = {Crank: ("length",), RRR: ("first_length", "second_length"),
                                               RRP: ("length", "through"), RPR: ("length",), LinkPoint: ("along", "left")}
"""The fields of each kind of group that are lengths or points (m), scaled with the linkage."""

_LINE_FIELDS: dict[type, tuple[str, ...]] = {PRP: ("first_guide", "second_guide"), RPP: ("guide",)}


def _scaled_group(group: Group, factor: float) -> Group:
    """A group with its lengths, points and guesses multiplied by ``factor`` (angles and names kept)."""
    changes: dict[str, Any] = {name: _times(getattr(group, name), factor) for name in _LENGTH_FIELDS.get(type(group), ())}
    changes |= {name: _scaled_line(getattr(group, name), factor) for name in _LINE_FIELDS.get(type(group), ())}
    if isinstance(group, Triad):
        changes = {"bars": tuple((a, b, length * factor) for a, b, length in group.bars),
                   "guess": tuple(complex(g) * factor for g in group.guess)}
    if isinstance(group, LinkPoint) and group.distances is not None:
        changes["distances"] = (group.distances[0] * factor, group.distances[1] * factor)
    return replace(group, **changes)


def _guides(group: Group) -> tuple[Line, ...]:
    if isinstance(group, RRP):
        return (group.guide,)
    if isinstance(group, PRP):
        return (group.first_guide, group.second_guide)
    if isinstance(group, RPP):
        return (group.guide,)
    return ()


def _needs(group: Group) -> tuple[str, ...]:
    return group.needs


def _needs_links(group: Group) -> tuple[str, ...]:
    links = tuple(line.link for line in _guides(group) if line.link != FRAME)
    if isinstance(group, LinkPoint) and group.axis is None:
        links += (group.link,)
    return links


def _broadcast(crossing: LineIntersection, shape: tuple[int, ...]) -> LineIntersection:
    """An intersection of two lines at every crank position: two fixed lines cross at one fixed point, which
    :func:`~mechanisms.blocks.lines.line_intersection` gives as a 0-d value."""
    def spread(motion: Any) -> Any:
        return type(motion)(*(None if x is None else np.broadcast_to(x, shape) for x in motion.derivatives()))
    return LineIntersection(spread(crossing.point), spread(crossing.along_first), spread(crossing.along_second),
                            np.broadcast_to(crossing.singular, shape))


def _check_names(group: Group) -> None:
    """Every joint and link a group names is a name: a non-empty string."""
    named = [*group.finds, *group.needs, *group.links, *(line.link for line in _guides(group))]
    if isinstance(group, LinkPoint) and group.axis is None:
        named.append(group.link)
    for name in named:
        if not isinstance(name, str) or not name.strip():
            raise StructureError(f"{type(group).__name__}: a joint or link is named {name!r}: names are "
                                 "non-empty strings")
