"""Layer 7: variants of any linkage file — the assignment of ``python -m mechanisms assign FILE.toml``.

A linkage file (:mod:`mechanisms.linkages.linkage_file`) becomes an assignment: each student gets the
file's linkage with its dimensions drawn at random within ranges, its own crank speed and its own crank
positions, written as a linkage file of its own (``sNN.toml``, every number written with ``repr`` so that
anyone can recompute the key from it).

The ranges
----------
By default every *dimension* varies within ±15 % of the file's value (:data:`DEFAULT_SPREAD`); a value 0
stays 0 (a joint on an axis stays on it). The dimensions are: the frame joints' coordinates (``frame.C``),
the crank's length (``crank.length``), each dyad's lengths (``dyad.B.lengths``, ``dyad.H.length``), the
point of a fixed guide (``dyad.H.guide.through``), the place of a point on its link (``point.E.along``,
``point.E.left``, ``point.D.distances``). Angles (``dyad.H.guide.angle_deg``, ``dyad.Y.slot_angle_deg``),
masses (``mass.coupler.mass`` …), loads and class III groups stay as the file gives them unless the file's
``[variants]`` table sets a range for them. A dyad is named by its ``joint`` (an RPR without one by its
``block``); a dyad whose name another dyad has too gets ``#N``, its number among the dyads
(``dyad#3.length``). A mass is named by its ``body``, a load by ``load#N``.

A file may set its own ranges in a ``[variants]`` table (read here: the linkage loader does not see it)::

    [variants]
    spread = 0.10                      # the default spread of every dimension not listed (0: all fixed)
    omega = [20.0, 60.0]               # the crank speed φ_t, 1/s (a number: the same for everyone)
    transmission_min_deg = 40.0        # the least transmission angle at an asked position
    fixed = ["frame.C", "point.E.left"]   # keep these as the file gives them
    "crank.length" = [0.08, 0.12]      # a range [low, high] in the key's unit (m, or ° for *_deg)
    "dyad.B.lengths" = [[0.30, 0.40], 0.30]   # a list key: one entry per element, a range or a number
    "frame.C" = [[0.35, 0.45], [0.0, 0.1]]    # a frame joint: a range (or a number) per coordinate
    "mass.coupler.mass" = [1.5, 2.5]

A number instead of a range sets that value for every student. Values are rounded to three significant
figures of the range's larger end (whole millimetres for a range of decimetres), the crank speed to two.

When a variant is kept
----------------------
A candidate is drawn until it is valid (:func:`FileAssignment.check`): it assembles over the whole turn
(every degree) with the file's branches, no position of the turn is singular, and no RRR or RRP group
passes through a change point (its transmission angle stays above :data:`CHANGE_POINT_DEG` everywhere, so
the branch it has at one asked position is the one it has at the next). The asked positions are then
drawn among the multiples of 15° where every RRR and RRP group has a transmission angle μ ≥ 40° and no
link turns faster than :data:`RATE_RATIO_MAX` times the crank.

The transmission angle μ (the book's symbol): for an RRR group, the angle between its two bars at the
joint it finds, taken acute (μ and 180° − μ are the same quality of transmission); for an RRP group, the
acute angle between the rod and the normal to the guide (90° when the rod pushes along the guide, 0° when
it is perpendicular to it, a singular position) — for the crank-slider this is chapter 3's μ = 90° − |ψ|.
Other groups (RPR, PRP, RPP, triads) have none; their singular positions are refused by the first rule.
"""

from __future__ import annotations

import json
import math
import pathlib
import re
import tomllib
import weakref
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from ..analysis.assignments import Quantity, Task
from ..core.errors import AssemblyError, InvalidParameterError, MechanismError, StructureError
from ..linkages.base import Mechanism, Solution
from ..linkages.composed import Linkage
from ..linkages.groups import PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Triad
from ..linkages.linkage_file import example_file, example_files, linkage_from_dict

__all__ = ["DEFAULT_SPREAD", "DEFAULT_OMEGA", "TRANSMISSION_MIN_DEG", "CHANGE_POINT_DEG", "RATE_RATIO_MAX",
           "FileAssignment", "read_assignment_file", "transmission_angles", "toml_text", "linkage_document",
           "default_columns", "quantity_of"]

DEFAULT_SPREAD = 0.15
"""The default relative spread of a dimension: ±15 % of the file's value."""
DEFAULT_OMEGA = (10.0, 60.0)
"""The default range of the crank speed φ_t (1/s)."""
TRANSMISSION_MIN_DEG = 40.0
"""The least transmission angle μ (°) of an RRR or RRP group at an asked position."""
CHANGE_POINT_DEG = 3.0
"""Over the whole turn μ stays above this (°): the groups pass through no change point."""
RATE_RATIO_MAX = 20.0
"""At an asked position no link turns faster than this many times the crank (|θ_t| ≤ 20 |φ_t|) nor accelerates
more than this many times φ_t² (|θ_tt| ≤ 20 φ_t²): a position away from singular ones."""
GRID_DEG = 1.0
"""The step (°) of the crank angles at which a candidate is checked over the whole turn."""
STEP_DEG = 15
"""Asked crank positions are multiples of this (°), as for the named mechanisms."""

_DATA: "weakref.WeakKeyDictionary[Mechanism, dict]" = weakref.WeakKeyDictionary()
"""The linkage file's contents of each variant drawn here (to write ``sNN.toml``)."""


@dataclass(frozen=True)
class _Leaf:
    """One numeric value of the file that a variant may change: its key path (``dyad.B.lengths``), where it is
    in the parsed TOML (a path of keys and indices), its file value and whether it varies by default."""

    name: str
    where: tuple[Any, ...]
    value: Any
    dimension: bool


def _label_dyads(dyads: Sequence[Mapping[str, Any]]) -> list[str]:
    labels = [str(t.get("joint") or t.get("block") or "") for t in dyads]
    return [f"dyad.{label}" if label and labels.count(label) == 1 else f"dyad#{n}"
            for n, label in enumerate(labels, 1)]


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _is_pair(value: Any) -> bool:
    return isinstance(value, list) and len(value) == 2 and all(_is_number(v) for v in value)


def _leaves(data: Mapping[str, Any]) -> list[_Leaf]:
    """Every value of the file that a variant may change, in the file's order."""
    leaves: list[_Leaf] = []
    frame = data.get("frame")
    if isinstance(frame, dict):
        leaves += [_Leaf(f"frame.{joint}", ("frame", joint), value, True)
                   for joint, value in frame.items() if _is_pair(value)]
    crank = data.get("crank")
    if isinstance(crank, dict) and _is_number(crank.get("length")):
        leaves.append(_Leaf("crank.length", ("crank", "length"), crank["length"], True))
    dyads = data.get("dyad", [])
    if isinstance(dyads, list) and all(isinstance(t, dict) for t in dyads):
        for index, (label, table) in enumerate(zip(_label_dyads(dyads), dyads)):
            for key in ("lengths", "length"):
                value = table.get(key)
                if _is_number(value) or (isinstance(value, list) and value and all(_is_number(v) for v in value)):
                    leaves.append(_Leaf(f"{label}.{key}", ("dyad", index, key), value, True))
            if _is_number(table.get("slot_angle_deg")):
                leaves.append(_Leaf(f"{label}.slot_angle_deg", ("dyad", index, "slot_angle_deg"),
                                    table["slot_angle_deg"], False))
            guides = [("guide", table.get("guide"))] + [(f"guides.{k}", g) for k, g in enumerate(
                table.get("guides") if isinstance(table.get("guides"), list) else [])]
            for name, guide in guides:
                if not isinstance(guide, dict):
                    continue
                where = ("dyad", index, *(("guides", int(name[7:])) if name.startswith("guides.") else ("guide",)))
                if _is_pair(guide.get("through")):
                    leaves.append(_Leaf(f"{label}.{name}.through", (*where, "through"), guide["through"], True))
                if _is_number(guide.get("angle_deg")):
                    leaves.append(_Leaf(f"{label}.{name}.angle_deg", (*where, "angle_deg"), guide["angle_deg"],
                                        False))
    points = data.get("point", [])
    if isinstance(points, list) and all(isinstance(t, dict) for t in points):
        for index, table in enumerate(points):
            label = f"point.{table.get('name')}"
            for key in ("along", "left"):
                if _is_number(table.get(key)):
                    leaves.append(_Leaf(f"{label}.{key}", ("point", index, key), table[key], True))
            if _is_pair(table.get("distances")):
                leaves.append(_Leaf(f"{label}.distances", ("point", index, "distances"), table["distances"], True))
    masses = data.get("mass", [])
    if isinstance(masses, list) and all(isinstance(t, dict) for t in masses):
        for index, table in enumerate(masses):
            for key in ("mass", "along", "left", "inertia"):
                if _is_number(table.get(key)):
                    leaves.append(_Leaf(f"mass.{table.get('body')}.{key}", ("mass", index, key), table[key], False))
    return leaves


@dataclass(frozen=True)
class _Range:
    """How one number of the file varies: uniformly in [low, high], rounded to ``digits`` decimals."""

    low: float
    high: float
    digits: int

    def draw(self, rng: np.random.Generator) -> float:
        if self.low == self.high:
            return self.low
        return round(float(rng.uniform(self.low, self.high)), self.digits)


def _digits(scale: float, figures: int) -> int:
    """Decimals that keep ``figures`` significant figures of ``scale``."""
    return figures - 1 - math.floor(math.log10(scale)) if scale > 0 else 0


def _range(low: float, high: float, figures: int = 3) -> _Range:
    scale = max(abs(low), abs(high))
    return _Range(low, high, _digits(scale, figures))


def _fixed(value: float) -> _Range:
    return _Range(float(value), float(value), 0)


@dataclass
class FileAssignment:
    """An assignment made of a linkage file: its contents, how each number varies, what is asked.

    Built by :func:`read_assignment_file`. ``task(columns)`` gives the :class:`~mechanisms.analysis.assignments.Task`
    that :func:`mechanisms.course.assign.make_variants` draws from.
    """

    source: str
    name: str
    data: dict
    ranges: dict[tuple[Any, ...], _Range]
    omega: _Range
    transmission_min_deg: float = TRANSMISSION_MIN_DEG
    description: list[str] = field(default_factory=list)
    linkage: Linkage | None = None

    # --- drawing and checking a candidate ----------------------------------------------------------

    def sample(self, rng: np.random.Generator) -> tuple[Mechanism, float]:
        """A candidate: the file with every varying number drawn, its linkage and a crank speed."""
        data = json.loads(json.dumps(self.data))      # a deep copy of plain TOML data
        for where, rule in self.ranges.items():
            *path, last = where
            target: Any = data
            for key in path:
                target = target[key]
            target[last] = rule.draw(rng)
        omega = self.omega.draw(rng)
        try:
            linkage = linkage_from_dict(data, self.source)
        except StructureError as error:
            raise MechanismError(f"candidate refused: {error}") from None
        _DATA[linkage] = data
        return linkage, omega

    def check(self, mechanism: Mechanism) -> list[str]:
        """Why a candidate is not a valid variant over the whole turn (empty: valid)."""
        phi = np.radians(np.arange(0.0, 360.0, GRID_DEG))
        try:
            solution = mechanism.solve(phi, 1.0, 0.0, order=1)
        except AssemblyError as error:
            return [f"it does not assemble over the whole turn: {error}"]
        except MechanismError as error:
            return [str(error)]
        if np.any(solution.singular):
            return ["it has singular positions"]
        for group, mu in transmission_angles(mechanism, solution).items():
            if not np.all(np.isfinite(mu)) or np.min(mu) < CHANGE_POINT_DEG:
                return [f"group {group} passes through a change point (μ < {CHANGE_POINT_DEG:g}°)"]
        return []

    def eligible(self, mechanism: Mechanism) -> np.ndarray:
        """Which multiples of 15° may be asked: every μ ≥ the least transmission angle, the rates moderate."""
        phi = np.radians(np.arange(0, 360, STEP_DEG, dtype=float))
        solution = mechanism.solve(phi, 1.0, 0.0, order=2)
        good = np.ones(phi.shape, dtype=bool)
        for mu in transmission_angles(mechanism, solution).values():
            good &= mu >= self.transmission_min_deg
        for name in solution.angle_names:
            angle = solution.angle(name)
            good &= np.abs(np.asarray(angle.omega)) <= RATE_RATIO_MAX
            good &= np.abs(np.asarray(angle.alpha)) <= RATE_RATIO_MAX
        return good

    def data_rows(self, mechanism: Mechanism) -> list[tuple[str, str, str, str]]:
        """The sheet's data table: every value of the variant's file that a student needs."""
        data = _DATA.get(mechanism, self.data)
        rows: list[tuple[str, str, str, str]] = []
        for joint, value in data.get("frame", {}).items():
            rows.append(("", f"fixed joint {joint} (x, y)", f"({value[0]:g}, {value[1]:g})", "m"))
        crank = data["crank"]
        rows.append(("L_1", f"crank length |{crank['pivot']}{crank['pin']}|", f"{crank['length']:g}", "m"))
        for label, table in zip(_label_dyads(data.get("dyad", [])), data.get("dyad", [])):
            rows.append(("", f"{label[5:] if label.startswith('dyad.') else label}: {_describe_dyad(table)}", "", ""))
        for table in data.get("point", []):
            rows.append(("", f"point {table.get('name')}: {_describe_point(table)}", "", ""))
        for table in data.get("triad", []):
            rows.append(("", f"triad {', '.join(table.get('joints', []))}: bars "
                         + "; ".join(f"|{p}{q}| = {length:g} m" for p, q, length in table.get("bars", [])), "", ""))
        for table in data.get("mass", []):
            rows.append(("", f"body {table.get('body')}: mass {table.get('mass', 0):g} kg, centre of mass "
                         f"({table.get('along', 0):g}, {table.get('left', 0):g}) m, J_S = {table.get('inertia', 0):g} "
                         "kg m²", "", ""))
        if data.get("gravity"):
            rows.append(("g", "gravity, along −y", f"{data['gravity']:g}", "m/s²"))
        return rows

    def task(self, columns: Sequence[str] | None = None) -> Task:
        """The assignment task asking ``columns`` (default: :func:`default_columns`)."""
        base = self.base_linkage()
        asked = list(columns) if columns else default_columns(base)
        quantities = tuple(quantity_of(base, column) for column in asked)
        return Task(self.name, base.name, self.sample, self.check, self.data_rows, quantities,
                    f"it assembles over the whole turn with the file's branches and no singular position, and at "
                    f"every asked crank angle the transmission angle of every RRR and RRP group is at least "
                    f"{self.transmission_min_deg:g}°", eligible=self.eligible, document=linkage_document)

    def base_linkage(self) -> Linkage:
        if self.linkage is None:
            self.linkage = linkage_from_dict(self.data, self.source)
        return self.linkage


def _describe_dyad(table: Mapping[str, Any]) -> str:
    kind = table.get("type")
    if kind == "RRR":
        (p, q), (lp, lq) = table["from"], table["lengths"]
        side = "left" if table.get("branch", 1) == 1 else "right"
        return (f"RRR, joint {table['joint']} at |{p}{table['joint']}| = {lp:g} m, |{q}{table['joint']}| = {lq:g} m, "
                f"to the {side} of {p} → {q}")
    if kind == "RRP":
        side = "farther" if table.get("branch", 1) == 1 else "nearer"
        return (f"RRP, slider {table['joint']} at |{table['from']}{table['joint']}| = {table['length']:g} m from "
                f"{table['from']} on the guide {_describe_guide(table['guide'])}, the {side} solution along it")
    if kind == "RPR":
        end = f", lever end {table['joint']} at {table['length']:g} m from {table['pivot']}" if "joint" in table else ""
        return f"RPR, block {table['block']} slides on the lever through the pivot {table['pivot']}{end}"
    if kind == "PRP":
        return (f"PRP, joint {table['joint']} on the guides " + " and ".join(_describe_guide(g) for g in table["guides"]))
    return (f"RPP, block {table.get('block')} in a slot at {table.get('slot_angle_deg'):g}° to the guide "
            f"{_describe_guide(table.get('guide', {}))} of the yoke {table.get('joint')}")


def _describe_guide(guide: Mapping[str, Any]) -> str:
    through = guide.get("through")
    angle = guide.get("angle_deg", 0.0)
    if isinstance(through, list):
        return f"through ({through[0]:g}, {through[1]:g}) m at {angle:g}° from +x"
    return f"through {through} at {angle:g}° from {through} → {guide.get('toward')}"


def _describe_point(table: Mapping[str, Any]) -> str:
    link = table.get("link")
    on = f"{link[0]} → {link[1]}" if isinstance(link, list) else str(link)
    if "distances" in table and isinstance(link, list):
        d = table["distances"]
        side = "left" if table.get("branch", 1) == 1 else "right"
        return f"|{link[0]}{table['name']}| = {d[0]:g} m, |{link[1]}{table['name']}| = {d[1]:g} m, to the {side} of {on}"
    return f"{table.get('along', 0.0):g} m along {on}, {table.get('left', 0.0):g} m to its left"


# --- the [variants] table --------------------------------------------------------------------------------

_VARIANTS_OPTIONS = {"spread", "omega", "transmission_min_deg", "fixed"}


def _spec_range(spec: Any, value: float, key: str, source: str) -> _Range:
    """One element's rule: a number (fixed there) or a range [low, high]."""
    where = f"{source}: [variants] key {key!r}"
    if _is_number(spec):
        return _fixed(float(spec))
    if _is_pair(spec) and math.isfinite(spec[0]) and math.isfinite(spec[1]):
        low, high = float(spec[0]), float(spec[1])
        if low > high:
            raise StructureError(f"{where}: a range [low, high] with low ≤ high: got {spec!r}")
        return _range(low, high)
    raise StructureError(f"{where}: must be a number or a range [low, high] (file value {value!r}): got {spec!r}")


def _default_range(value: float, spread: float) -> _Range:
    if value == 0 or spread == 0:
        return _fixed(value)
    low, high = sorted((value * (1 - spread), value * (1 + spread)))
    return _range(low, high)


def read_assignment_file(path: str | pathlib.Path) -> FileAssignment:
    """Read a linkage file (or a shipped example's name) with its optional ``[variants]`` table.

    Raises
    ------
    StructureError
        The file cannot be read, is not TOML, describes no valid linkage, or its ``[variants]`` table has an
        unknown key or a bad range (the message names the file and the key).
    """
    name = str(path)
    file = pathlib.Path(name)
    if not file.exists() and file.suffix == "" and file.name in example_files():
        file, name = example_file(file.name), f"{file.name}.toml (shipped with the package)"
    try:
        text = file.read_bytes()
    except FileNotFoundError:
        raise StructureError(f"{name}: no such file (shipped examples: {', '.join(example_files())})") from None
    except OSError as error:
        raise StructureError(f"{name}: cannot be read: {error.strerror or error}") from None
    try:
        data = tomllib.loads(text.decode("utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeError) as error:
        raise StructureError(f"{name}: not a valid TOML file: {error}") from None
    options = data.pop("variants", {})
    if not isinstance(options, dict):
        raise StructureError(f"{name}: [variants] must be a table")
    linkage = linkage_from_dict(data, name)           # the file itself must be a valid linkage
    leaves = {leaf.name: leaf for leaf in _leaves(data)}
    unknown = sorted(set(options) - _VARIANTS_OPTIONS - set(leaves))
    if unknown:
        raise StructureError(f"{name}: [variants]: unknown key(s) {', '.join(map(repr, unknown))}; it takes "
                             f"{', '.join(sorted(_VARIANTS_OPTIONS))} and the keys of the file's numbers: "
                             f"{', '.join(leaves)}")
    spread = options.get("spread", DEFAULT_SPREAD)
    if not _is_number(spread) or not 0.0 <= spread < 1.0:
        raise StructureError(f"{name}: [variants] key 'spread': a fraction from 0 to less than 1: got {spread!r}")
    fixed = options.get("fixed", [])
    if not isinstance(fixed, list) or not all(isinstance(f, str) and f in leaves for f in fixed):
        raise StructureError(f"{name}: [variants] key 'fixed': a list of the keys {', '.join(leaves)}: got {fixed!r}")
    mu = options.get("transmission_min_deg", TRANSMISSION_MIN_DEG)
    if not _is_number(mu) or not 0.0 <= mu <= 90.0:
        raise StructureError(f"{name}: [variants] key 'transmission_min_deg': an angle from 0 to 90°: got {mu!r}")
    omega_spec = options.get("omega", list(DEFAULT_OMEGA))
    omega = (_spec_range(omega_spec, 0.0, "omega", name) if not _is_number(omega_spec)
             else _fixed(float(omega_spec)))
    if omega.low != omega.high:
        omega = _range(omega.low, omega.high, 2)
    if not (math.isfinite(omega.low) and omega.low > 0.0):
        raise StructureError(f"{name}: [variants] key 'omega': a crank speed > 0 1/s or a range of them: got "
                             f"{omega_spec!r}")
    ranges: dict[tuple[Any, ...], _Range] = {}
    for leaf in leaves.values():
        elements = leaf.value if isinstance(leaf.value, list) else [leaf.value]
        places = [(*leaf.where, i) for i in range(len(elements))] if isinstance(leaf.value, list) else [leaf.where]
        if leaf.name in options:
            spec = options[leaf.name]
            if isinstance(leaf.value, list) and not (isinstance(spec, list) and len(spec) == len(elements)):
                raise StructureError(f"{name}: [variants] key {leaf.name!r}: one number or range [low, high] per "
                                     f"element of {leaf.value!r}: got {spec!r}")
            specs = spec if isinstance(leaf.value, list) else [spec]
            rules = [_spec_range(s, v, leaf.name, name) for s, v in zip(specs, elements)]
        elif leaf.name in fixed or not leaf.dimension:
            continue
        else:
            rules = [_default_range(float(v), spread) for v in elements]
        for place, rule in zip(places, rules):
            ranges[place] = rule
    return FileAssignment(name, file.stem, data, ranges, omega, float(mu), linkage=linkage)


# --- the transmission angle -------------------------------------------------------------------------------

def transmission_angles(mechanism: Mechanism, solution: Solution) -> dict[str, np.ndarray]:
    """The transmission angle μ (°, acute) of every RRR and RRP group at the solution's positions.

    RRR (joint J from P and Q): the angle between the bars J→P and J→Q, taken acute. RRP (slider J from K):
    the acute angle between the rod K→J and the normal to the guide. Keyed ``"RRR B"``, ``"RRP H"``.
    """
    out: dict[str, np.ndarray] = {}
    for group in mechanism.groups():
        if isinstance(group, RRR):
            joint = solution.point(group.joint).value
            first = solution.point(group.first).value - joint
            second = solution.point(group.second).value - joint
            mu = np.degrees(np.abs(np.angle(first * np.conj(second))))
            out[f"RRR {group.joint}"] = np.minimum(mu, 180.0 - mu)
        elif isinstance(group, RRP):
            rod = solution.point(group.joint).value - solution.point(group.known).value
            guide = float(group.guide_angle or 0.0)
            turning = group.guide_link not in (None, "frame")
            direction = guide + (np.asarray(solution.angle(group.guide_link).value) if turning else 0.0)
            # |sin| of the angle between the rod and the guide is the cosine of the angle to the guide's normal
            along = np.abs(np.sin(np.angle(rod) - direction))
            out[f"RRP {group.joint}"] = np.degrees(np.arccos(np.clip(along, 0.0, 1.0)))
    return out


# --- the columns a course asks -----------------------------------------------------------------------------

_JOINT_KEYS = {"x": ("x_{J}", "x coordinate of joint {J}", "m"), "y": ("y_{J}", "y coordinate of joint {J}", "m"),
               "vx": ("x_{J}t", "velocity of joint {J}, x component", "m/s"),
               "vy": ("y_{J}t", "velocity of joint {J}, y component", "m/s"),
               "ax": ("x_{J}tt", "acceleration of joint {J}, x component", "m/s²"),
               "ay": ("y_{J}tt", "acceleration of joint {J}, y component", "m/s²"),
               "F": ("F_{J}", "magnitude of the force in the hinge {J}", "N")}
_LINK_KEYS = {"angle_deg": ("θ", "angle of link {L}, counter-clockwise from +x, in [0°, 360°)", "°"),
              "omega": ("θ_t", "angular velocity of link {L} (positive counter-clockwise)", "1/s"),
              "alpha": ("θ_tt", "angular acceleration of link {L} (positive counter-clockwise)", "1/s²")}
_SLIDER_KEYS = {"s": ("s", "position of block {L} along its guide", "m"),
                "v": ("s_t", "sliding velocity of block {L}", "m/s"),
                "a": ("s_tt", "sliding acceleration of block {L}", "m/s²")}


def _output_joint(linkage: Linkage) -> str:
    """The joint the last group finds: the linkage's output."""
    for group in reversed(linkage.groups()):
        if isinstance(group, (RRR, RRP, PRP, RPP)):
            return group.joint
        if isinstance(group, RPR):
            return group.joint or group.block
        if isinstance(group, LinkPoint):
            return group.name
        if isinstance(group, Triad):
            return group.joints[-1]
    first = linkage.groups()[0]
    return first.pin if isinstance(first, Crank) else "A"     # only a crank


def _crank_link(linkage: Linkage) -> str:
    first = linkage.groups()[0]
    return first.link if isinstance(first, Crank) else "crank"


def default_columns(linkage: Linkage) -> list[str]:
    """What a course asks by default: the output joint's position, velocity and acceleration, and every link's
    angular velocity and acceleration but the crank's (given)."""
    joint = _output_joint(linkage)
    crank = _crank_link(linkage)
    phi = np.zeros(1)
    names = linkage.solve(phi, 1.0, order=0).angle_names
    return ([f"{joint}.{k}" for k in ("x", "y", "vx", "vy", "ax", "ay")]
            + [f"{name}.{k}" for name in names if name != crank for k in ("omega", "alpha")])


def has_masses(linkage: Mechanism) -> bool:
    """Whether a linkage file declares masses, loads or gravity (so that forces can be asked)."""
    return bool(getattr(linkage, "masses", None) or getattr(linkage, "loads", None)
                or getattr(linkage, "gravity", 0.0))


def quantity_of(linkage: Linkage, column: str) -> Quantity:
    """The :class:`Quantity` of a column of a linkage: ``JOINT.x|y|vx|vy|ax|ay|F``, ``LINK.angle_deg|omega|alpha``,
    ``BLOCK.s|v|a``, ``driving_torque``.

    Raises
    ------
    UnknownNameError
        A column the linkage does not have (the known ones listed).
    """
    from ..core.errors import UnknownNameError

    solution = linkage.solve(np.zeros(1), 1.0, order=0)
    crank = _crank_link(linkage)
    forces = has_masses(linkage)
    known = ([f"{j}.{k}" for j in solution.point_names for k in _JOINT_KEYS if k != "F" or forces]
             + [f"{n}.{k}" for n in solution.angle_names if n != crank for k in _LINK_KEYS]
             + [f"{n}.{k}" for n in solution.slider_names for k in _SLIDER_KEYS]
             + (["driving_torque"] if forces else []))
    if column not in known:
        raise UnknownNameError("quantity", column, known)
    if column == "driving_torque":
        return Quantity(column, "M_d", "driving torque on the crank (positive counter-clockwise)", "N·m")
    name, _, key = column.rpartition(".")
    if name in solution.point_names and key in _JOINT_KEYS:
        symbol, meaning, unit = _JOINT_KEYS[key]
        return Quantity(column, symbol.format(J=name) if _plain(name) else "", meaning.format(J=name), unit)
    table = _LINK_KEYS if name in solution.angle_names and key in _LINK_KEYS else _SLIDER_KEYS
    symbol, meaning, unit = table[key]
    return Quantity(column, symbol, meaning.format(L=name), unit)


def _plain(name: str) -> bool:
    return re.fullmatch(r"[A-Za-z0-9]+", name) is not None


# --- writing a variant's file ---------------------------------------------------------------------------

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def _key(key: str) -> str:
    return key if _BARE.fullmatch(key) else json.dumps(key, ensure_ascii=False)


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ("nan" if math.isnan(value) else
                                                         ("inf" if value > 0 else "-inf"))
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + " }"
    raise InvalidParameterError("value", value, "a TOML value (string, number, boolean, list or table)")


def toml_text(data: Mapping[str, Any], comments: Sequence[str] = ()) -> str:
    """A linkage file's contents as TOML text (numbers with ``repr``: read back, they are the same doubles)."""
    lines = [f"# {c}" for c in comments]
    scalars = [(k, v) for k, v in data.items() if not isinstance(v, dict)
               and not (isinstance(v, list) and v and all(isinstance(t, dict) for t in v))]
    lines += [f"{_key(k)} = {_value(v)}" for k, v in scalars]
    for key, value in data.items():
        if isinstance(value, dict):
            lines += ["", f"[{_key(key)}]"] + [f"{_key(k)} = {_value(v)}" for k, v in value.items()]
        elif isinstance(value, list) and value and all(isinstance(t, dict) for t in value):
            for table in value:
                lines += ["", f"[[{_key(key)}]]"] + [f"{_key(k)} = {_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


def linkage_document(mechanism: Mechanism, comments: Sequence[str] = ()) -> str | None:
    """The linkage file of a variant drawn by :meth:`FileAssignment.sample` (None for any other mechanism)."""
    data = _DATA.get(mechanism)
    return None if data is None else toml_text(data, comments)
