"""Linkage files: a linkage described in TOML, read into a :class:`~mechanisms.linkages.composed.Linkage`.

Lengths in m, angles in degrees. The keys (a contract: they keep their meaning)::

    name = "Watt six-bar with an output slider"

    [frame]                     # fixed joints, m
    O = [0.0, 0.0]
    C = [0.40, 0.05]

    [crank]                     # the driver: pivot -> pin (optional: link = "crank")
    pivot = "O"
    pin = "A"
    length = 0.10

    [[dyad]]                    # RRR: a joint at given distances from two known joints
    type = "RRR"
    joint = "B"
    from = ["A", "C"]
    lengths = [0.35, 0.30]
    branch = 1                  # +1: left of the directed line from[0] -> from[1]; -1: right
    links = ["coupler", "rocker"]   # optional; default "AB", "CB"

    [[point]]                   # a point fixed to the link through two known joints
    name = "E"
    link = ["C", "B"]           # or a link's name
    along = 0.45                # m along C -> B
    left = 0.05                 # m to the left of C -> B
    # or, instead of along/left: distances = [|CE|, |BE|] and branch = +1 (left of C -> B) or -1

    [[dyad]]                    # RRP: a joint on a straight guide, at a distance from a known joint
    type = "RRP"
    joint = "H"
    from = "E"
    length = 0.40
    guide = { through = [0.0, 0.60], angle_deg = 0.0 }    # a fixed guide
    # a guide on a moving link: { through = "C", toward = "B", angle_deg = 0.0 }, the line through
    # joint C at angle_deg from the direction C -> B (both joints of that link)
    branch = 1                  # +1: the solution farther along the guide's direction
    links = ["rod", "H"]        # optional; default "EH" and the block "H"

    [[dyad]]                    # RPR: a lever through a known pivot, slotted through a block at a known joint
    type = "RPR"
    block = "A"
    pivot = "C"
    joint = "D"                 # optional: the lever's point at `length` from the pivot, on the block's side
    length = 0.60
    links = ["A", "lever"]      # optional; default the block "A" and the lever "CD" (or "CA")

    [[dyad]]                    # PRP: two blocks hinged at `joint`, each sliding on its own guide
    type = "PRP"
    joint = "K"
    guides = [{ through = "B", toward = "C" }, { through = [0.0, 0.2], angle_deg = 90.0 }]
    links = ["K1", "K2"]        # optional; these are the defaults

    [[dyad]]                    # RPP: a block hinged at a known joint slides in a yoke's slot; the yoke on a guide
    type = "RPP"
    joint = "Y"                 # the yoke's point on the guide, where the slot crosses it
    block = "A"
    guide = { through = [0.0, 0.0], angle_deg = 0.0 }
    slot_angle_deg = 90.0       # the slot's angle to the guide
    links = ["A", "Y"]          # optional; the block and the yoke

    [[triad]]                   # a class III group: no closed form, solved by Newton's method
    joints = ["D", "E", "F"]
    bars = [["A", "D", 0.3], ["C", "E", 0.3], ["G", "F", 0.3], ["D", "E", 0.2], ["E", "F", 0.2], ["D", "F", 0.2]]
    guess = { D = [0.1, 0.3], E = [0.3, 0.3], F = [0.2, 0.45] }   # near the assembly mode wanted
    guess_angle_deg = 0.0       # the crank angle of the guess
    links = ["DEF", "AD", "CE", "GF"]   # optional

    gravity = 9.81              # m/s^2, along -y (a top-level key, before the first table); absent: none

    [[mass]]                    # mass properties of a body (energy, forces)
    body = "coupler"            # a link's name, or a block's: its link's name ("ram") or its joint ("H")
    mass = 2.0                  # kg, >= 0
    along = 0.15                # m, the centre of mass in the body's frame (default 0)
    left = 0.0                  # m (default 0)
    inertia = 0.02              # kg m^2, >= 0, about the centre of mass (default 0)

    [[load]]                    # a constant force on a body (N, fixed axes x, y) at a point of it
    body = "ram"
    force = [-800.0, 0.0]
    along = 0.0                 # m, the point in the body's frame, as for [[mass]] (default 0, 0)
    left = 0.0

    [[load]]                    # or a constant torque on a body (N m, counter-clockwise positive)
    body = "output rocker"
    torque = -15.0

A body's frame: a link's first joint at the origin, its x axis along the link (``links`` of its
group: an RRR's first link from ``from[0]``, its second from ``from[1]``; an RRP's rod from
``from``; an RPR's lever from ``pivot``; the crank from ``pivot``); a block's origin is its joint,
its x axis its sliding direction if it turns, the fixed axes x, y if it only translates. A
``[[load]]`` takes exactly one of ``force`` and ``torque``. Masses, loads and gravity give the
forces of ``python -m mechanisms table FILE --forces`` (:mod:`mechanisms.analysis.kinetostatics`);
a file with none of them has all its forces zero.

Groups may come in any order that respects what they need. Every error names the file, the
group (``[[dyad]] #2``) or key, and the cause. Angles in degrees are reduced exactly to (−180°, 180°]
(:func:`~mechanisms.core.angles.reduce_degrees`) before they become radians, so 1e20° is as good an
angle as 280°.
"""

from __future__ import annotations

import math
import os
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np

from ..core.angles import reduce_degrees
from ..core.errors import InvalidParameterError, MechanismError, StructureError
from .composed import Linkage, _GroupError
from .groups import PRP, RPP, RPR, RRP, RRR, Crank, Group, Line, LinkPoint, Triad

__all__ = ["load_linkage", "linkage_from_dict", "example_files", "example_file", "FORMAT_SUMMARY"]

FORMAT_SUMMARY = """\
A linkage file (TOML; lengths in m, angles in degrees):
  name = "…"; [frame] JOINT = [x, y]; [crank] pivot, pin, length;
  [[dyad]] type = "RRR": joint, from = [P, Q], lengths = [|PJ|, |QJ|], branch = ±1 (left/right of P -> Q)
  [[dyad]] type = "RRP": joint, from, length, guide = {through = [x, y] or JOINT, toward = JOINT, angle_deg}, branch
  [[dyad]] type = "RPR": block, pivot, joint and length (optional)
  [[dyad]] type = "PRP": joint, guides = [guide, guide]
  [[dyad]] type = "RPP": joint, block, guide, slot_angle_deg
  [[point]] name, link = [P, Q] or LINK, along and left (m) or distances = [|PE|, |QE|] and branch
  [[triad]] joints, bars = [[P, Q, length], …], guess = {JOINT = [x, y]}, guess_angle_deg
  [[mass]] body, mass (kg), along, left (m), inertia (kg m^2)
  [[load]] body, force = [Fx, Fy] (N) with along, left (m), or torque (N m); gravity = g (m/s^2, along -y)
Every group may name its links: links = [...]. The full format: the book's multi-loop chapter."""

_TOP = {"name", "frame", "crank", "dyad", "point", "triad", "mass", "load", "gravity", "description"}
_FILE_KEYS = {"first_length": "lengths", "second_length": "lengths", "first": "from", "second": "from",
              "first guide": "guides", "second guide": "guides", "slot_angle": "slot_angle_deg", "bar": "bars"}
"""The key of the file for a field of a group that :class:`~mechanisms.linkages.composed.Linkage` names."""
_DYAD_KEYS = {
    "RRR": ({"type", "joint", "from", "lengths"}, {"branch", "links"}),
    "RRP": ({"type", "joint", "from", "length", "guide"}, {"branch", "links"}),
    "RPR": ({"type", "block", "pivot"}, {"joint", "length", "links"}),
    "PRP": ({"type", "joint", "guides"}, {"links"}),
    "RPP": ({"type", "joint", "block", "guide", "slot_angle_deg"}, {"links"}),
}


class _NotYet(Exception):
    """A guide or point on a moving link whose frame is not known yet: try again after more groups."""


class _Where:
    """Where in the file a value comes from, for messages: ``FILE: [[dyad]] #2 (joint 'B')``."""

    def __init__(self, source: str, place: str):
        self.source, self.place = source, place

    def error(self, message: str, key: str | None = None) -> StructureError:
        where = f"{self.source}: {self.place}" + (f": key {key!r}" if key else "")
        return StructureError(f"{where}: {message}")

    def keys(self, table: Mapping[str, Any], required: set[str], optional: set[str]) -> None:
        missing = sorted(required - set(table))
        unknown = sorted(set(table) - required - optional, key=str)
        if missing:
            raise self.error(f"missing key{'s' if len(missing) > 1 else ''} {', '.join(map(repr, missing))}"
                             + (f" (and unknown {', '.join(map(repr, unknown))}: misspelt?)" if unknown else ""))
        if unknown:
            raise self.error(f"unknown key{'s' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))}; "
                             f"this table takes {', '.join(sorted(required | optional))}")

    def name(self, table: Mapping[str, Any], key: str) -> str:
        value = table[key]
        if not isinstance(value, str) or not value.strip():
            raise self.error(f"must be a joint's name (a string): got {value!r}", key)
        return value

    def names(self, table: Mapping[str, Any], key: str, count: int) -> tuple[str, ...]:
        value = table[key]
        if (not isinstance(value, list) or len(value) != count
                or not all(isinstance(v, str) and v.strip() for v in value)):
            raise self.error(f"must be a list of {count} names: got {value!r}", key)
        if len(set(value)) != count:
            raise self.error(f"names the same joint twice: {value!r}", key)
        return tuple(value)

    def angle(self, value: Any, key: str) -> float:
        """An angle in degrees → radians, reduced in degrees first (exactly, whatever its size)."""
        try:
            if not isinstance(value, int) or isinstance(value, bool):       # an int is reduced as an integer
                value = self.number(value, key, "a finite angle in degrees")
            return math.radians(float(reduce_degrees(value, key)))
        except InvalidParameterError as error:
            raise self.error(f"must be a finite angle in degrees: got {error.value!r}", key) from None

    def number(self, value: Any, key: str, what: str = "a finite number") -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(f"must be {what}: got {value!r}", key)
        try:
            value = float(value)
        except OverflowError:                  # an int beyond the largest double
            raise self.error(f"must be {what}: got {value!r}", key) from None
        if not math.isfinite(value):
            raise self.error(f"must be {what}: got {value!r}", key)
        return value

    def length(self, value: Any, key: str) -> float:
        value = self.number(value, key, "a length > 0 m")
        if value <= 0.0:
            raise self.error(f"must be a length > 0 m: got {value!r}", key)
        return value

    def point(self, value: Any, key: str) -> complex:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(f"must be a point [x, y] in m: got {value!r}", key)
        return complex(self.number(value[0], key, "a point [x, y] of finite numbers, m"),
                       self.number(value[1], key, "a point [x, y] of finite numbers, m"))

    def branch(self, table: Mapping[str, Any], key: str = "branch") -> int:
        value = table.get(key, 1)
        # an int or a float, never a bool or an array (whose comparison has no single truth value)
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
                or value not in (1, -1):
            raise self.error(f"must be +1 or -1: got {value!r}", key)
        return int(value)

    def links(self, table: Mapping[str, Any], defaults: tuple[str, ...]) -> tuple[str, ...]:
        if "links" not in table:
            return defaults
        return self.names(table, "links", len(defaults))


def _guide(where: _Where, value: Any, key: str,
           local: Callable[[str, str], tuple[str, complex, float | None]]) -> Line:
    """A guide table → Line: a fixed one through a point, or one through a joint of a moving link."""
    if not isinstance(value, dict):
        raise where.error(f"must be a table {{through = [x, y], angle_deg = …}}: got {value!r}", key)
    extra = set(value) - {"through", "toward", "angle_deg"}
    if extra or "through" not in value:
        raise where.error("a guide takes through = [x, y] or a joint, toward = a joint (for a moving link) and "
                          f"angle_deg: got {value!r}", key)
    angle = where.angle(value.get("angle_deg", 0.0), key + ".angle_deg")
    through = value["through"]
    if isinstance(through, list):
        if "toward" in value:
            raise where.error("a fixed guide (through = [x, y]) takes no 'toward'", key)
        return Line("frame", where.point(through, key + ".through"), angle)
    if not isinstance(through, str):
        raise where.error(f"through must be a point [x, y] or a joint's name: got {through!r}", key)
    toward = value.get("toward")
    if toward is None:
        raise where.error("a guide through a joint needs 'toward', a second joint of the same link "
                          "(the guide's direction is angle_deg from through -> toward)", key)
    if not isinstance(toward, str) or not toward.strip():
        raise where.error(f"toward must be a joint's name: got {toward!r}", key)
    if toward == through:
        raise where.error(f"through and toward are the same joint {through!r}: the guide has no direction (give "
                          "toward, a second joint of the link)", key + ".toward")
    link, point, base = local(through, toward)
    if base is None:
        raise where.error(f"joints {through!r} and {toward!r} are one point of link {link!r}: the guide has no "
                          "direction", key + ".toward")
    return Line(link, point, base + angle)


def linkage_from_dict(data: Mapping[str, Any], source: str = "<linkage>") -> Linkage:
    """A :class:`Linkage` from the parsed contents of a linkage file (see the module's docstring).

    Raises
    ------
    StructureError
        Naming ``source``, the group or key, and what is wrong.
    """
    top = _Where(source, "the file")
    if not isinstance(data, Mapping):
        raise top.error(f"must be a table of keys (name, frame, crank, …): got {data!r}")
    unknown = sorted(set(data) - _TOP, key=str)
    if unknown:
        raise top.error(f"unknown key{'s' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))}; "
                        f"a linkage file has {', '.join(sorted(_TOP))}")
    for key in ("frame", "crank"):
        if key not in data:
            raise top.error(f"missing [{key}]")
        if not isinstance(data[key], dict):
            raise top.error(f"[{key}] must be one table" + (" (a linkage has one driving crank)"
                                                             if key == "crank" else ""), key)
    name = data.get("name", Path(source).stem)
    for key, text in (("name", name), ("description", data.get("description", ""))):
        if not isinstance(text, str):
            raise top.error(f"must be a string: got {text!r}", key)
    frame_where = _Where(source, "[frame]")
    frame = {joint: frame_where.point(value, joint) for joint, value in data["frame"].items()}
    where = _Where(source, "[crank]")
    crank_table = data["crank"]
    where.keys(crank_table, {"pivot", "pin", "length"}, {"link"})
    groups: list[Group] = [Crank(where.name(crank_table, "pivot"), where.name(crank_table, "pin"),
                                 crank_table.get("link", "crank") if "link" not in crank_table
                                 else where.name(crank_table, "link"),
                                 where.length(crank_table["length"], "length"))]
    places: dict[int, _Where] = {id(groups[0]): where}
    # moving guides and points on joint pairs need the links' frames: resolved by a first Linkage
    pending: list[tuple[str, Mapping[str, Any], _Where]] = []
    for kind in ("dyad", "point", "triad"):
        tables = data.get(kind, [])
        if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
            raise top.error(f"must be an array of tables [[{kind}]]", kind)
        for number, table in enumerate(tables, 1):
            pending.append((kind, table, _Where(source, _place(kind, number, table))))
    masses = _masses(data.get("mass", []), source)
    loads = _loads(data.get("load", []), source)
    gravity = top.number(data["gravity"], "gravity", "an acceleration g in m/s² (along −y), a finite number") \
        if "gravity" in data else 0.0

    def local_of(groups_so_far: list[Group]) -> Callable[[str, str], tuple[str, complex, float | None]]:
        def local(through: str, toward: str) -> tuple[str, complex, float | None]:
            try:
                partial = Linkage(frame, groups_so_far, name=name)
            except MechanismError:
                raise _NotYet from None
            for link, joints in partial.link_joints().items():
                if through in joints and toward in joints:
                    frame_of = partial._links[link].local
                    direction = frame_of[toward] - frame_of[through]
                    return link, frame_of[through], (math.atan2(direction.imag, direction.real)
                                                     if direction else None)
            raise _NotYet
        return local

    # groups that need a moving link's frame wait until the groups before them make it
    waiting = pending
    while waiting:
        progress = False
        still: list[tuple[str, Mapping[str, Any], _Where]] = []
        for kind, table, place in waiting:
            try:
                group = _group(kind, table, place, local_of(groups))
            except _NotYet:
                still.append((kind, table, place))
                continue
            places[id(group)] = place
            groups.append(group)
            progress = True
        if not progress:
            try:      # an error elsewhere (a joint no group finds, a cycle) is the one to report
                Linkage(frame, groups, name=name)
            except MechanismError as error:
                raise _located(error, source, places) from None
            kind, table, place = still[0]
            guide = table.get("guide") or table.get("guides")
            raise place.error(f"its guide ({guide!r}) or link is on joints that are not both on one link, or that "
                              "no group finds")
        waiting = still
    try:
        linkage = Linkage(frame, groups, name=name, masses=masses, source=source, loads=loads, gravity=gravity)
    except MechanismError as error:
        raise _located(error, source, places) from None
    bodies = _bodies(linkage)
    given: dict[str, int] = {}
    for number, body in enumerate(masses, 1):
        where = _Where(source, f"[[mass]] #{number}")
        found = _body(where, body, bodies)
        if found in given:
            raise where.error(f"body {body!r} is the body of [[mass]] #{given[found]} (its mass is given twice)",
                              "body")
        given[found] = number
    for number, load in enumerate(loads, 1):
        _body(_Where(source, f"[[load]] #{number}"), load["body"], bodies)
    return linkage


def _bodies(linkage: Linkage) -> dict[str, list[str]]:
    """Every name of a moving body → the bodies it names: each link by its name, each block by its joint too."""
    names: dict[str, list[str]] = {name: [name] for name in linkage.link_joints() if name != "frame"}
    by_joint: dict[str, list[str]] = {}
    for name, item in linkage._links.items():
        if item.role == "slider" and item.pole is not None:
            by_joint.setdefault(item.pole, []).append(name)
    for joint, blocks in by_joint.items():
        names.setdefault(joint, blocks)
    return names


def _body(where: _Where, body: str, bodies: Mapping[str, list[str]]) -> str:
    """The body a [[mass]] or [[load]] names, or the file's error naming the known bodies."""
    found = bodies.get(body, [])
    if len(found) == 1:
        return found[0]
    links = [name for name, named in bodies.items() if named == [name]]
    blocks = [name for name, named in bodies.items() if named != [name]]
    if found:
        raise where.error(f"joint {body!r} carries the blocks {', '.join(map(repr, found))}: name one of them",
                          "body")
    raise where.error(f"no body {body!r}: a body is a link ({', '.join(links)})"
                      + (f" or a block's joint ({', '.join(blocks)})" if blocks else ""), "body")


def _located(error: MechanismError, source: str, places: Mapping[int, _Where]) -> StructureError:
    """A linkage's error about one group, told at the group's place in the file and, if known, its key."""
    place = places.get(id(error.group)) if isinstance(error, _GroupError) else None
    if place is None or not isinstance(error, _GroupError):
        return StructureError(f"{source}: {error}")
    return place.error(error.cause, _file_key(error.key))


def _file_key(field: str | None) -> str | None:
    """The file's key for a field a group's error names: ``first_length`` → ``lengths``, ``bar AD`` → ``bars``,
    ``distances[0]`` → ``distances``; ``guess.D`` as it is."""
    if field is None:
        return None
    if field in _FILE_KEYS:
        return _FILE_KEYS[field]
    head = field.split("[")[0].split(".")[0].split(" ")[0]
    return _FILE_KEYS.get(head, head if head != field.split("[")[0] or "[" in field else field)


def _place(kind: str, number: int, table: Mapping[str, Any]) -> str:
    label = table.get("joint") or table.get("name") or table.get("joints") or table.get("block")
    return f"[[{kind}]] #{number}" + (f" ({label!r})" if label else "")


def _group(kind: str, table: Mapping[str, Any], where: _Where,
           local: Callable[[str, str], tuple[str, complex, float | None]]) -> Group:
    if kind == "point":
        return _point(table, where)
    if kind == "triad":
        return _triad(table, where)
    kind_name = table.get("type")
    if not isinstance(kind_name, str) or kind_name not in _DYAD_KEYS:
        raise where.error(f"must be one of {', '.join(_DYAD_KEYS)}: got {kind_name!r}", "type")
    where.keys(table, *_DYAD_KEYS[kind_name])
    if kind_name == "RRR":
        joint = where.name(table, "joint")
        first, second = where.names(table, "from", 2)
        lengths = table["lengths"]
        if not isinstance(lengths, list) or len(lengths) != 2:
            raise where.error(f"must be two lengths [|{first}{joint}|, |{second}{joint}|] in m: got {lengths!r}",
                              "lengths")
        links = where.links(table, (first + joint, second + joint))
        return RRR(joint, first, second, links[0], links[1], where.length(lengths[0], "lengths"),
                   where.length(lengths[1], "lengths"), where.branch(table))
    if kind_name == "RRP":
        joint, known = where.name(table, "joint"), where.name(table, "from")
        guide = _guide(where, table["guide"], "guide", local)
        links = where.links(table, (known + joint, joint))
        return RRP(joint, known, links[0], links[1], guide.angle, where.length(table["length"], "length"),
                   where.branch(table), guide.point, guide.link)
    if kind_name == "RPR":
        block, pivot = where.name(table, "block"), where.name(table, "pivot")
        lever_end = where.name(table, "joint") if "joint" in table else None
        if (lever_end is None) != ("length" not in table):
            raise where.error("give both 'joint' and 'length' (the lever's point at length from the pivot) or "
                              "neither")
        length = where.length(table["length"], "length") if lever_end is not None else None
        links = where.links(table, (block, pivot + (lever_end or block)))
        return RPR(block, pivot, links[1], links[0], lever_end, length)
    if kind_name == "PRP":
        joint = where.name(table, "joint")
        guides = table["guides"]
        if not isinstance(guides, list) or len(guides) != 2:
            raise where.error(f"must be two guides [{{…}}, {{…}}]: got {guides!r}", "guides")
        lines = [_guide(where, g, f"guides[{i}]", local) for i, g in enumerate(guides)]
        links = where.links(table, (joint + "1", joint + "2"))
        return PRP(joint, lines[0], lines[1], links[0], links[1])
    joint, block = where.name(table, "joint"), where.name(table, "block")
    guide = _guide(where, table["guide"], "guide", local)
    slot = where.angle(table["slot_angle_deg"], "slot_angle_deg")
    links = where.links(table, (block, joint))
    return RPP(joint, block, guide, slot, links[0], links[1])


def _point(table: Mapping[str, Any], where: _Where) -> LinkPoint:
    where.keys(table, {"name", "link"}, {"along", "left", "distances", "branch"})
    name = where.name(table, "name")
    link = table["link"]
    placed = ("distances" in table, "along" in table or "left" in table)
    if placed[0] == placed[1]:
        raise where.error("give its place as along (and left), m, or as distances = [|PE|, |QE|] with a branch")
    if "distances" in table:
        if not isinstance(link, list):
            raise where.error("distances need the link as two joints, link = [P, Q]", "link")
        distances = table["distances"]
        if not isinstance(distances, list) or len(distances) != 2:
            raise where.error(f"must be two lengths [|P{name}|, |Q{name}|] in m: got {distances!r}", "distances")
        p, q = where.names(table, "link", 2)
        return LinkPoint(name, "", axis=(p, q), branch=where.branch(table),
                         distances=(where.length(distances[0], "distances"), where.length(distances[1], "distances")))
    along = where.number(table.get("along", 0.0), "along", "a distance in m")
    left = where.number(table.get("left", 0.0), "left", "a distance in m")
    if "branch" in table:
        raise where.error("branch goes with distances, not with along/left", "branch")
    if isinstance(link, list):
        p, q = where.names(table, "link", 2)
        return LinkPoint(name, "", along, left, axis=(p, q))
    if not isinstance(link, str) or not link:
        raise where.error(f"must be a link's name or two joints [P, Q]: got {link!r}", "link")
    return LinkPoint(name, link, along, left)


def _triad(table: Mapping[str, Any], where: _Where) -> Triad:
    where.keys(table, {"joints", "bars", "guess"}, {"guess_angle_deg", "links"})
    joints = table["joints"]
    if not isinstance(joints, list) or len(joints) < 2 or not all(isinstance(j, str) and j for j in joints):
        raise where.error(f"must be a list of the group's joints: got {joints!r}", "joints")
    bars = table["bars"]
    if not isinstance(bars, list) or not bars:
        raise where.error(f"must be a list of bars [P, Q, length]: got {bars!r}", "bars")
    parsed = []
    for bar in bars:
        if not (isinstance(bar, list) and len(bar) == 3 and isinstance(bar[0], str) and isinstance(bar[1], str)):
            raise where.error(f"each bar is [P, Q, length in m]: got {bar!r}", "bars")
        parsed.append((bar[0], bar[1], where.length(bar[2], "bars")))
    guess = table["guess"]
    if not isinstance(guess, dict) or set(guess) != set(joints):
        raise where.error(f"must give a position [x, y] for each joint {', '.join(joints)}: got {guess!r}", "guess")
    links = table.get("links", [])
    if (not isinstance(links, list) or not all(isinstance(v, str) and v.strip() for v in links)
            or len(set(links)) != len(links)):
        raise where.error(f"must be a list of the group's link names, each once: got {links!r}", "links")
    return Triad(tuple(joints), tuple(parsed), tuple(where.point(guess[j], f"guess.{j}") for j in joints),
                 where.angle(table.get("guess_angle_deg", 0.0), "guess_angle_deg"), tuple(links))


def _masses(tables: Any, source: str) -> dict[str, dict[str, float]]:
    top = _Where(source, "the file")
    if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
        raise top.error("must be an array of tables [[mass]]", "mass")
    masses: dict[str, dict[str, float]] = {}
    for number, table in enumerate(tables, 1):
        where = _Where(source, f"[[mass]] #{number}")
        where.keys(table, {"body", "mass"}, {"along", "left", "inertia"})
        body = where.name(table, "body")
        if body in masses:
            raise where.error(f"body {body!r} has its mass given twice", "body")
        properties = {key: where.number(table[key], key) for key in ("mass", "along", "left", "inertia")
                      if key in table}
        for key in ("mass", "inertia"):
            if properties.get(key, 0.0) < 0.0:
                raise where.error(f"must be ≥ 0: got {properties[key]!r}", key)
        masses[body] = properties
    return masses


def _loads(tables: Any, source: str) -> list[dict[str, Any]]:
    """The [[load]] tables: a constant force (N) at a point of a body, or a constant torque (N·m) on it."""
    top = _Where(source, "the file")
    if not isinstance(tables, list) or not all(isinstance(t, dict) for t in tables):
        raise top.error("must be an array of tables [[load]]", "load")
    loads = []
    for number, table in enumerate(tables, 1):
        where = _Where(source, f"[[load]] #{number}")
        where.keys(table, {"body"}, {"force", "torque", "along", "left"})
        body = where.name(table, "body")
        if ("force" in table) == ("torque" in table):
            raise where.error("give exactly one of force = [Fx, Fy] (N) and torque = T (N·m)")
        if "torque" in table:
            if "along" in table or "left" in table:
                raise where.error("a torque acts on the whole body: it takes no point (along, left)",
                                  "along" if "along" in table else "left")
            loads.append({"body": body, "torque": where.number(table["torque"], "torque", "a torque in N·m, a finite "
                                                                                          "number")})
            continue
        force = table["force"]
        what = "a force [Fx, Fy] in N, two finite numbers"
        if not isinstance(force, list) or len(force) != 2:
            raise where.error(f"must be {what}: got {force!r}", "force")
        loads.append({"body": body, "force": (where.number(force[0], "force", what), where.number(force[1], "force", what)),
                      "along": where.number(table.get("along", 0.0), "along", "a distance in m"),
                      "left": where.number(table.get("left", 0.0), "left", "a distance in m")})
    return loads


def load_linkage(path: str | Path) -> Linkage:
    """Read a linkage file (TOML).

    Parameters
    ----------
    path : str or Path
        The file; or the name of a file shipped with the package (``"watt-six-bar"``, see
        :func:`example_files`).

    Raises
    ------
    StructureError
        The file cannot be read, is not TOML, or describes no valid linkage (the message names
        the file, the group or key, and the cause).
    """
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not isinstance(path, (str, os.PathLike)):
        raise StructureError(f"load_linkage: path must be a file's path (a str or a Path) or the name of a shipped "
                             f"example: got {path!r}")
    try:
        path = Path(path)
    except TypeError:                           # an os.PathLike whose __fspath__ gives no str
        raise StructureError(f"load_linkage: path must be a file's path: got {path!r}") from None
    source = str(path)
    if "\0" in source:
        raise StructureError(f"{source!r}: not a file's path: it holds a NUL character")
    try:
        folder, exists = path.is_dir(), path.exists()
    except (OSError, ValueError) as error:       # a name too long for the system, one it cannot encode
        raise StructureError(f"{source[:200]}: cannot be read: {getattr(error, 'strerror', None) or error}") from None
    if folder:
        raise StructureError(f"{source}: is a folder, not a linkage file")
    if not exists and path.suffix == "" and path.name in example_files():
        path, source = example_file(path.name), f"{path.name}.toml (shipped with the package)"
    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except FileNotFoundError:
        raise StructureError(f"{source}: no such file (shipped examples: {', '.join(example_files())})") from None
    except OSError as error:
        raise StructureError(f"{source}: cannot be read: {error.strerror or error}") from None
    except (tomllib.TOMLDecodeError, UnicodeError) as error:
        raise StructureError(f"{source}: not a valid TOML file: {error}") from None
    return linkage_from_dict(data, source)


def example_files() -> list[str]:
    """The names of the linkage files shipped with the package (``mechanisms/linkages/examples``)."""
    folder = resources.files(__package__).joinpath("examples")
    return sorted(entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml"))


def example_file(name: str) -> Path:
    """The path of a shipped linkage file by its name (``"jansen"``)."""
    path = Path(str(resources.files(__package__).joinpath("examples", f"{name}.toml")))
    if not path.exists():
        raise StructureError(f"no shipped linkage file {name!r}; there are {', '.join(example_files())}")
    return path
