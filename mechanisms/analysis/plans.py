"""Layer 4: velocity and acceleration plans and instant centres (chapter 10).

A *plan* is the vector polygon a course in the theory of mechanisms draws to scale for one crank
position. It is built here as a student builds it, from the drawing of the mechanism (the joint
positions) and the crank's motion only:

* the crank pin's velocity ``v_A = iω₁(A − O)`` and acceleration ``a_A = (iε₁ − ω₁²)(A − O)``;
* for every further joint a vector equation in which two directions are known and two lengths are
  not, e.g. ``v_B = v_A + v_BA`` with ``v_BA ⊥ AB`` and ``v_B`` along the guide, solved as the
  intersection of two lines (:func:`meet`);
* the angular velocity of a link read off its relative velocity, ``ω₂ = v_BA / l_AB``, and used for
  the normal accelerations ``a^n_BA = −ω₂² (B − A)`` and the Coriolis term ``2ω₃ × v_rel``;
* any other point of a link by its *image*: the figure of the link's points on the plan is similar
  to the link itself (:func:`image`).

Nothing is copied from the analytic solution except the positions, so the values read off a plan
can be compared with the closed form: they agree to round-off, and any difference is a defect.

The construction goes group by group through the mechanism's structure (``groups()``): the crank,
then RRR, RRP, RPR, PRP and RPP groups and points fixed to links, for the book's named mechanisms
and for any :class:`~mechanisms.linkages.composed.Linkage` of class II groups alike. A dyad whose
two outer joints both move (a six-bar's) is drawn from both known vertices, ``v_C = v_B + v_CB =
v_D + v_CD``; a slider on a guide carried by a moving link adds the guide link's point under it
(its image) and, on the acceleration plan, the Coriolis component ``2ω × v_rel``. A class III group
is refused with :class:`PlanError` naming it.

Instant centres (:func:`instant_centres`) of any such mechanism, all n(n − 1)/2 of them: the
primary ones from the pairs, the others by Kennedy's theorem, and those its lines leave open from the
velocities; :func:`velocities_from_centre` gives the velocities of a link's points from its instant
centre. :func:`plan_report` lists every vector of both plans for the command line.

Points are complex numbers ``x + iy`` (m), velocities m/s, accelerations m/s². The plan's
vertices are stored in those units; the drawing divides them by the scale (μ_v or μ_a, units per mm).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Mapping, NamedTuple, Sequence, cast

import numpy as np

from ..core.motion import PointMotion
from ..core.validate import require_finite
from ..linkages.base import Mechanism, Solution
from ..core.errors import InvalidParameterError, MechanismError, StructureError
from ..linkages.composed import describe_group
from ..linkages.groups import PRP, RPP, RPR, RRP, RRR, Crank, Group, Line, LinkPoint, Triad, link_numbers

__all__ = [
    "PlanVector",
    "Reading",
    "Plan",
    "VelocityPlan",
    "AccelerationPlan",
    "PlanError",
    "meet",
    "image",
    "nice_scale",
    "velocity_plan",
    "acceleration_plan",
    "PlanStep",
    "plan_steps",
    "InstantCentres",
    "instant_centres",
    "instant_centre_path",
    "kennedy_deviation",
    "velocities_from_centre",
    "PlanRow",
    "PlanReport",
    "plan_report",
]

NICE_STEPS = (1.0, 2.0, 2.5, 4.0, 5.0)
"""The mantissas of the scales a course allows: 1, 2, 2.5, 4, 5 × 10ᵏ."""

class PlanError(MechanismError):
    """A plan cannot be built at this position: two of its lines are parallel (a singular position)."""


# --- geometry of the construction -------------------------------------------------------------------

def _cross(u: complex, v: complex) -> float:
    """The z-component of u × v for plane vectors as complex numbers: Im(conj(u)·v)."""
    return u.real * v.imag - u.imag * v.real


def meet(first_point: complex, first_direction: complex, second_point: complex,
         second_direction: complex) -> tuple[complex, float, float]:
    """Where two lines of a plan meet: ``P = p₁ + t₁d₁ = p₂ + t₂d₂``.

    Parameters
    ----------
    first_point, first_direction : complex
        A point of the first line and its direction (any length, not zero).
    second_point, second_direction : complex
        The same for the second line.

    Returns
    -------
    (point, t1, t2) : (complex, float, float)
        The intersection and the two line parameters, from Cramer's rule:
        ``t₁ = (p₂ − p₁) × d₂ / (d₁ × d₂)``, ``t₂ = (p₂ − p₁) × d₁ / (d₁ × d₂)``.

    Raises
    ------
    PlanError
        If the lines are parallel (|sin of the angle between them| < 1e-12).

    Notes
    -----
    This is the one step of every plan a student does with a ruler and a set square: two
    directions are known, two lengths are not.
    """
    d1, d2 = complex(first_direction), complex(second_direction)
    if d1 == 0 or d2 == 0:
        raise InvalidParameterError("direction", 0, "a non-zero direction of a plan line")
    denominator = _cross(d1, d2)
    if abs(denominator) < 1e-12 * abs(d1) * abs(d2):
        raise PlanError("the two lines of the plan are parallel, so they do not meet: the mechanism is "
                        "at a singular position (or a change point) here, choose another crank position")
    gap = complex(second_point) - complex(first_point)
    t1 = _cross(gap, d2) / denominator
    t2 = _cross(gap, d1) / denominator
    return complex(first_point) + t1 * d1, t1, t2


def image(first_image: complex, second_image: complex, first: complex, second: complex,
          point: complex) -> complex:
    """The image of a link's point on a plan: the similar figure (velocity or acceleration image).

    Parameters
    ----------
    first_image, second_image : complex
        The plan vertices of two points of the link (m/s or m/s², from the pole).
    first, second : complex
        The positions of those two points (m).
    point : complex
        The position of the point whose image is wanted (m).

    Returns
    -------
    complex
        ``x = a + (b − a)(X − A)/(B − A)``: the plan vertex of the point.

    Notes
    -----
    For a rigid link ``v_X − v_A = iω(X − A)`` and ``a_X − a_A = (iε − ω²)(X − A)``: the vectors
    between images are those between points, all multiplied by the same complex number. A product
    with one complex number turns and scales, so the figure of the images is similar to the link,
    turned by 90° in the sense of ω (velocities) or by 180° − arctan(ε/ω²) (accelerations). The
    ratio ``(b − a)/(B − A)`` is that complex number.
    """
    return first_image + (second_image - first_image) * (point - first) / (second - first)


def nice_scale(largest: float, length_mm: float = 100.0) -> float:
    """The smallest scale (μ_v or μ_a) m·10ᵏ (m in 1, 2, 2.5, 4, 5) that draws ``largest`` no longer than ``length_mm``.

    Parameters
    ----------
    largest : float
        The longest vector of the plan, or the farthest vertex from the pole (m/s or m/s²), > 0.
    length_mm : float
        The longest line the drawing may have (mm).

    Returns
    -------
    float
        The scale in units per mm, e.g. μ_a = 0.2 (m/s²)/mm.
    """
    if not largest > 0.0 or not math.isfinite(largest):
        raise InvalidParameterError("largest", largest, "a finite magnitude > 0 of the longest vector")
    wanted = largest / length_mm
    power = math.floor(math.log10(wanted))
    for exponent in (power, power + 1):
        for step in NICE_STEPS:
            mu = step * 10.0 ** exponent
            if mu >= wanted * (1.0 - 1e-12):
                return mu
    return 10.0 ** (power + 1)  # pragma: no cover  (the loop always returns)


# --- the plan --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class PlanVector:
    """One vector of a plan, from vertex ``tail`` to vertex ``head``.

    Attributes
    ----------
    name : str
        Its symbol in the book's lettering: ``v_A``, ``v_BA``, ``a^n_BA``, ``a^k_A2A3`` …
    tail, head : str
        Labels of the plan vertices it joins (``p``, ``a``, ``b`` …; ``π``, ``a′``, ``n2`` …).
    kind : str
        ``absolute`` (from the pole), ``relative`` (rotation about another joint), ``normal``,
        ``tangential``, ``sliding`` (along a slot) or ``coriolis``.
    link : str
        The link whose motion the vector describes (``crank``, ``coupler`` …), for its colour.
    value : complex
        The vector as the construction found it (m/s or m/s²).
    line : complex
        The unit direction of the line the construction drew for the vector before it knew its
        length (perpendicular to a link, along a guide or a slot); 0 for a vector known whole
        (the crank pin's, a normal or a Coriolis component, a point found by its image).
    """

    name: str
    tail: str
    head: str
    kind: str
    link: str
    value: complex
    line: complex = 0j

    @property
    def latex(self) -> str:
        """The name in LaTeX (and matplotlib mathtext): ``a^n_BA`` → ``a^{n}_{BA}``."""
        letter, _, subscript = self.name.partition("_")
        if "^" in letter:
            letter, superscript = letter.split("^")
            return f"{letter}^{{{superscript}}}_{{{subscript}}}"
        return f"{letter}_{{{subscript}}}"

    @property
    def magnitude(self) -> float:
        """Its magnitude ``|value|`` (m/s or m/s²)."""
        return abs(self.value)

    @property
    def direction_deg(self) -> float:
        """Its direction in degrees, counter-clockwise from +x, in [0, 360)."""
        return math.degrees(math.atan2(self.value.imag, self.value.real)) % 360.0


class Reading(NamedTuple):
    """A vector read off a plan: what a ruler and a protractor give (:meth:`Plan.read`)."""

    magnitude: float
    """Its drawn length times the scale μ_v or μ_a (m/s or m/s²)."""
    direction_deg: float
    """Its direction in degrees, counter-clockwise from +x, in [0, 360)."""


@dataclass(frozen=True)
class Plan:
    """A velocity or acceleration plan of a mechanism at one crank position.

    Attributes
    ----------
    quantity : str
        ``"velocity"`` or ``"acceleration"``.
    phi : float
        The crank angle φ (rad).
    pole : str
        The label of the pole: ``p`` (velocities) or ``π`` (accelerations).
    vertices : dict
        Label → vertex, the vector from the pole (m/s or m/s²).
    points : dict
        Name of a mechanism point → the label of its vertex (``{"B": "b"}``).
    vectors : tuple of PlanVector
        Every vector drawn, in the order of construction.
    equations : tuple
        The vector equations of the construction, each ``(left, right)`` two tuples of vector
        names whose sums are equal (``(("v_B",), ("v_A", "v_BA"))``).
    rates : dict
        Link → angular velocity (velocity plan) or angular acceleration (acceleration plan) read
        off the plan, 1/s or 1/s², counter-clockwise positive.
    scale : float
        μ_v or μ_a: units (m/s or m/s²) per mm of the drawing.
    positions : dict
        The mechanism's points used (m), for the similarity of images.
    images : dict
        Link → the names of its points whose vertices form the link's image.
    """

    quantity: str
    phi: float
    pole: str
    vertices: dict[str, complex]
    points: dict[str, str]
    vectors: tuple[PlanVector, ...]
    equations: tuple[tuple[tuple[str, ...], tuple[str, ...]], ...]
    rates: dict[str, float]
    scale: float
    positions: dict[str, complex] = field(default_factory=dict)
    images: dict[str, tuple[str, ...]] = field(default_factory=dict)

    @property
    def unit(self) -> str:
        """The unit of the plan's vectors: ``m/s`` or ``m/s²``."""
        return "m/s" if self.quantity == "velocity" else "m/s²"

    @property
    def symbol(self) -> str:
        """The symbol of the scale: μ_v or μ_a."""
        return "μ_v" if self.quantity == "velocity" else "μ_a"

    def vector(self, name: str) -> PlanVector:
        """The vector of this name (``v_BA``, ``a^t_BA`` …)."""
        for vector in self.vectors:
            if vector.name == name:
                return vector
        raise KeyError(f"no vector named {name!r} on the {self.quantity} plan; known: "
                       + ", ".join(v.name for v in self.vectors))

    def of(self, point: str) -> complex:
        """The velocity or acceleration of a mechanism point: its vertex, seen from the pole."""
        try:
            return self.vertices[self.points[point]]
        except KeyError:
            raise KeyError(f"no point named {point!r} on the {self.quantity} plan; known: "
                           + ", ".join(self.points)) from None

    def value(self, name: str) -> complex:
        """A vector of the plan by its name (``v_BA``), or a mechanism point's absolute vector (``S2``)."""
        return self.of(name) if name in self.points else self.vector(name).value

    def length_mm(self, name: str) -> float:
        """The drawn length (mm) of a vector, or of a point's absolute vector: magnitude / scale."""
        return abs(self.value(name)) / self.scale

    def component(self, name: str, along: complex) -> float:
        """The signed component of a vector (or a point's absolute vector) along a direction.

        Parameters
        ----------
        name : str
            A vector's name (``v_A2A3``, ``a^k_A2A3``) or a mechanism point's name.
        along : complex
            The direction, any length but not zero (e.g. ``A − C``, along the slot from C to A,
            or ``1j * (A − C)``, across it).

        Returns
        -------
        float
            ``Re(value · conj(along)) / |along|`` (m/s or m/s²): positive if the vector points
            the way of ``along``.
        """
        direction = complex(along)
        if direction == 0:
            raise InvalidParameterError("along", along, "a non-zero direction")
        return (self.value(name) * direction.conjugate()).real / abs(direction)

    def drawn(self, label: str) -> complex:
        """A vertex in drawing coordinates (mm from the pole, x to the right, y up)."""
        return self.vertices[label] / self.scale

    def read(self, name: str, resolution_mm: float = 0.0,
             resolution_deg: float = 0.0) -> Reading:
        """Read a vector off the drawing: its length × scale and its direction.

        Parameters
        ----------
        name : str
            A vector's name, or a mechanism point's name for its absolute vector.
        resolution_mm : float
            Round the measured length to this many mm (0: exact), as a ruler does.
        resolution_deg : float
            Round the measured direction to this many degrees (0: exact), as a protractor does.

        Returns
        -------
        Reading
            ``magnitude`` in m/s or m/s², and ``direction_deg`` counter-clockwise from +x in
            [0, 360); a named pair, so ``magnitude, direction = plan.read("B")`` works too.
        """
        value = self.value(name)
        length = abs(value) / self.scale
        direction = math.degrees(math.atan2(value.imag, value.real)) % 360.0
        if resolution_mm:
            length = round(length / resolution_mm) * resolution_mm
        if resolution_deg:
            direction = (round(direction / resolution_deg) * resolution_deg) % 360.0
        return Reading(length * self.scale, direction)

    def closure(self) -> float:
        """The largest |left − right| of the plan's vector equations (m/s or m/s²): round-off."""
        values = {v.name: v.value for v in self.vectors}
        worst = 0.0
        for left, right in self.equations:
            gap = sum(values[n] for n in left) - sum(values[n] for n in right)
            worst = max(worst, abs(gap))
        return worst

    def similarity(self, link: str) -> float:
        """How far the image of a link is from similar to the link (0 for an exact image).

        For a rigid link every image vector is the link vector it images times one complex number κ,
        ``x − a = κ(X − A)``, with κ = (b − a)/(B − A) from the link's two joints. The result is the
        largest ``|x − a − κ(X − A)|`` over the link's points, relative to ``|κ|`` times the link's size.
        """
        names = self.images[link]
        first, second = names[0], names[1]
        at = {n: self.vertices[self.points[n]] for n in names}
        rho = (at[second] - at[first]) / (self.positions[second] - self.positions[first])
        size = max(abs(self.positions[n] - self.positions[first]) for n in names)
        if rho == 0:
            return max(abs(at[n] - at[first]) for n in names)
        return max(abs(at[n] - at[first] - rho * (self.positions[n] - self.positions[first])) for n in names) / (
            abs(rho) * size)


class VelocityPlan(Plan):
    """A velocity plan (pole ``p``, scale μ_v in (m/s)/mm)."""


class AccelerationPlan(Plan):
    """An acceleration plan (pole ``π``, scale μ_a in (m/s²)/mm)."""


# --- the structure at one position ---------------------------------------------------------------------

FRAME = "frame"
"""The name of the fixed link (link 0)."""


def _unit(angle: float) -> complex:
    """The unit vector at ``angle`` (rad) from +x."""
    return complex(math.cos(angle), math.sin(angle))


def _angle_of(vector: complex) -> float:
    return math.atan2(vector.imag, vector.real)


@dataclass(frozen=True)
class _Pair:
    """A kinematic pair at one position: a hinge (``R``) at ``joint``, or a sliding pair (``P``) along ``along``."""

    kind: str
    first: str
    second: str
    joint: str
    along: complex = 0j


class _Structure:
    """A mechanism's structure at one position, read off its groups and its joints' positions only.

    The fixed joints (needed by a group, found by none), the link that first carries each joint, the
    angle of each link's frame (its first joint → its second, as :mod:`mechanisms.linkages.groups`
    defines them; a block's is its guide's), the joints of each link, the blocks (links with one
    joint: sliders and yokes) and the kinematic pairs, each sliding pair with its direction here.
    """

    def __init__(self, groups: Sequence[Group], where: Mapping[str, complex]):
        found = {j for group in groups for j in group.finds}
        fixed = [j for group in groups for j in group.needs if j not in found]
        self.where = where
        self.fixed = set(fixed)
        self.owner: dict[str, str] = {j: FRAME for j in fixed}
        self.heading: dict[str, float] = {FRAME: 0.0}
        self.members: dict[str, list[str]] = {FRAME: list(dict.fromkeys(fixed))}
        self.blocks: set[str] = set()
        self.point_link: dict[str, str] = {}
        self.pairs: list[_Pair] = []
        for group in groups:
            self._add(group)

    def direction(self, line: Line) -> complex:
        """The unit direction of a guide at this position: its angle plus that of the link carrying it."""
        return _unit(self.heading[line.link] + line.angle)

    def _link(self, name: str, joints: Sequence[str], heading: float, block: bool = False) -> None:
        self.heading.setdefault(name, heading)
        self.members.setdefault(name, []).extend(joints)
        for joint in joints:
            self.owner.setdefault(joint, name)
        if block:
            self.blocks.add(name)

    def _add(self, group: Group) -> None:
        where, owner, pairs = self.where, self.owner, self.pairs
        if isinstance(group, Crank):
            pairs.append(_Pair("R", owner[group.pivot], group.link, group.pivot))
            self._link(group.link, (group.pivot, group.pin), _angle_of(where[group.pin] - where[group.pivot]))
        elif isinstance(group, RRR):
            pairs += [_Pair("R", owner[group.first], group.first_link, group.first),
                      _Pair("R", group.first_link, group.second_link, group.joint),
                      _Pair("R", owner[group.second], group.second_link, group.second)]
            self._link(group.first_link, (group.first, group.joint), _angle_of(where[group.joint] - where[group.first]))
            self._link(group.second_link, (group.second, group.joint),
                       _angle_of(where[group.joint] - where[group.second]))
        elif isinstance(group, RRP):
            along = self.direction(group.guide)
            pairs += [_Pair("R", owner[group.known], group.link, group.known),
                      _Pair("R", group.link, group.slider, group.joint),
                      _Pair("P", group.slider, group.guide_link, group.joint, along)]
            self._link(group.link, (group.known, group.joint), _angle_of(where[group.joint] - where[group.known]))
            self._link(group.slider, (group.joint,), _angle_of(along), block=True)
        elif isinstance(group, RPR):
            heading = _angle_of(where[group.block] - where[group.pivot])
            pairs += [_Pair("R", owner[group.block], group.slider, group.block),
                      _Pair("P", group.slider, group.lever, group.block, _unit(heading)),
                      _Pair("R", owner[group.pivot], group.lever, group.pivot)]
            self._link(group.slider, (group.block,), heading, block=True)
            self._link(group.lever, (group.pivot,) + group.finds, heading)
        elif isinstance(group, PRP):
            first, second = self.direction(group.first_guide), self.direction(group.second_guide)
            pairs += [_Pair("P", group.first_guide.link, group.first_slider, group.joint, first),
                      _Pair("R", group.first_slider, group.second_slider, group.joint),
                      _Pair("P", group.second_slider, group.second_guide.link, group.joint, second)]
            self._link(group.first_slider, (group.joint,), _angle_of(first), block=True)
            self._link(group.second_slider, (group.joint,), _angle_of(second), block=True)
        elif isinstance(group, RPP):
            guide = self.direction(group.guide)
            slot = guide * _unit(group.slot_angle)
            pairs += [_Pair("R", owner[group.block], group.slider, group.block),
                      _Pair("P", group.slider, group.yoke, group.block, slot),
                      _Pair("P", group.yoke, group.guide.link, group.joint, guide)]
            self._link(group.slider, (group.block,), _angle_of(slot), block=True)
            self._link(group.yoke, (group.joint,), _angle_of(guide), block=True)
        elif isinstance(group, Triad):
            carriers: dict[str, list[str]] = {}
            for name, body in zip(group.links, group.bodies()):
                for joint in body:
                    if joint in group.joints:
                        carriers.setdefault(joint, []).append(name)
                    else:
                        pairs.append(_Pair("R", owner[joint], name, joint))
                self._link(name, body, _angle_of(where[body[1]] - where[body[0]]))
            pairs += [_Pair("R", carried[0], other, joint) for joint, carried in carriers.items()
                      for other in carried[1:]]
        elif isinstance(group, LinkPoint):
            link = group.link
            if not link and group.axis is not None:
                link = next((name for name, joints in self.members.items() if set(group.axis) <= set(joints)), "")
            if link not in self.members:
                raise StructureError(f"point {group.name}: no link carries it (link {group.link!r}, joints "
                                     f"{group.axis!r}); links: {', '.join(self.members)}")
            self.point_link[group.name] = link
            self.owner.setdefault(group.name, link)
            self.members[link].append(group.name)


# --- the constructions, group by group -----------------------------------------------------------------

class _Builder:
    """Collects the vertices, vectors and equations of a plan as the construction goes.

    ``links`` holds each link with two points on the plan (its image is drawn from them), ``single``
    each block with its one point; ``rates`` the links' ω (or ε) as the construction reads them.
    """

    def __init__(self, quantity: str, where: dict[str, complex], structure: _Structure, numbers: dict[str, int],
                 velocity: Plan | None):
        self.quantity = quantity
        self.pole = "p" if quantity == "velocity" else "π"
        self.prime = "" if quantity == "velocity" else "′"
        self.letter = "v" if quantity == "velocity" else "a"
        self.vertices = {self.pole: 0j}
        self.points: dict[str, str] = {}
        self.vectors: list[PlanVector] = []
        self.equations: list[tuple[tuple[str, ...], tuple[str, ...]]] = []
        self.rates: dict[str, float] = {}
        self.images: dict[str, tuple[str, ...]] = {}
        self.where, self.structure, self.numbers, self.velocity = where, structure, numbers, velocity
        self.links: dict[str, tuple[str, str]] = {}
        self.single: dict[str, str] = {}
        self.coriolis_count = 0

    def vertex(self, label: str, value: complex, point: str | None = None) -> complex:
        self.vertices[label] = complex(value)
        if point is not None:
            self.points[point] = label
        return complex(value)

    def vector(self, name: str, tail: str, head: str, kind: str, link: str, value: complex,
               line: complex = 0j) -> None:
        """Record a vector; ``line`` is the direction of the line it was found on (0 if known whole)."""
        unit = complex(line) / abs(line) if line != 0 else 0j
        self.vectors.append(PlanVector(name, tail, head, kind, link, complex(value), unit))

    def absolute(self, point: str, label: str, link: str, value: complex | None = None,
                 line: complex = 0j) -> None:
        """The vector from the pole to a point's vertex (its velocity or acceleration)."""
        value = self.vertices[label] if value is None else value
        self.vector(f"{self.letter}_{point}", self.pole, label, "absolute", link, value, line)

    def known(self, joint: str) -> str:
        """The label of a known joint's vertex; a fixed joint is the pole."""
        if joint in self.structure.fixed:
            self.vertex(self.pole, 0j, joint)
            return self.pole
        return self.points[joint]

    def terms(self, joint: str, label: str) -> tuple[str, ...]:
        """A known joint's absolute vector in an equation: none for a fixed joint (it is zero)."""
        return () if label == self.pole else (f"{self.letter}_{joint}",)

    def rate_of(self, link: str) -> float:
        return 0.0 if link == FRAME else self.rates[link]

    def field(self, link: str, point: complex) -> complex:
        """The velocity (acceleration) of the point of ``link`` at ``point``: its image from two points of the
        link, or ``v_P + iω(X − P)`` (``a_P + (iε − ω²)(X − P)``) from its one point P (a block)."""
        if link == FRAME:
            return 0j
        where = self.where
        if link in self.links:
            first, second = self.links[link]
            return image(self.vertices[self.points[first]], self.vertices[self.points[second]], where[first],
                         where[second], point)
        pole = self.single[link]
        arm = point - where[pole]
        if self.velocity is None:
            return self.vertices[self.points[pole]] + 1j * self.rates[link] * arm
        omega = self.velocity.rates[link]
        return self.vertices[self.points[pole]] + (1j * self.rates[link] - omega**2) * arm

    def guide_point(self, link: str, joint: str) -> tuple[str, str | None]:
        """The point of ``link`` under ``joint`` (a guide's point under its slider): its vertex label and its
        name, the joint's name and the link's number (``U3``); the pole and ``None`` on the frame."""
        if link == FRAME:
            return self.pole, None
        name = f"{joint}{self.numbers[link]}"
        if name not in self.points:
            self.where[name] = self.where[joint]
            label = name.lower() + self.prime
            self.vertex(label, self.field(link, self.where[joint]), name)
            self.absolute(name, label, link)
        return self.points[name], name

    def coriolis(self, link: str, tail: str, relative: str, slider: str) -> tuple[str, complex]:
        """The Coriolis component ``2ω × v_rel`` of a motion relative to the turning ``link``, drawn from ``tail``:
        its end's label and value (``tail`` itself on a velocity plan or when the link is the frame)."""
        if self.velocity is None or link == FRAME:
            return tail, self.vertices[tail]
        value = 2.0 * 1j * self.velocity.rates[link] * self.velocity.vector(f"v_{relative}").value
        self.coriolis_count += 1
        label = "k" if self.coriolis_count == 1 else f"k{self.coriolis_count}"
        end = self.vertex(label, self.vertices[tail] + value)
        self.vector(f"a^k_{relative}", tail, label, "coriolis", slider, value)
        return label, end

    def finish(self, cls, phi: float, scale: float | None, positions: dict[str, complex]) -> Plan:
        if scale is None:
            largest = max([abs(v) for v in self.vertices.values()] + [abs(v.value) for v in self.vectors])
            scale = nice_scale(largest) if largest > 0 else 1.0
        elif not (scale > 0 and math.isfinite(scale)):
            raise InvalidParameterError("scale", scale, "a finite scale > 0 (units per mm)")
        return cls(self.quantity, float(phi), self.pole, dict(self.vertices), dict(self.points),
                   tuple(self.vectors), tuple(self.equations), dict(self.rates), float(scale),
                   dict(positions), dict(self.images))


def _positions(mechanism: Mechanism, solution: Solution, index: int,
               extra: Mapping[str, tuple[str, float, float]] | None) -> dict[str, complex]:
    """The joint positions of the drawing, and those of the named extra points of links."""
    where = {name: complex(solution.point(name).value[index]) for name in solution.point_names}
    for name, (link, along, left) in (extra or {}).items():
        where[name] = complex(solution.point_on(link, along, left).value[index])
    return where


def _check_extra(extra, allowed: Sequence[str]) -> None:
    if extra is not None and not isinstance(extra, Mapping):
        raise InvalidParameterError("points", extra, "a mapping NAME -> (LINK, u, w)")
    for name, spec in (extra or {}).items():
        if isinstance(spec, (str, bytes)) or not isinstance(spec, Sequence) or len(spec) != 3 or spec[0] not in allowed:
            raise InvalidParameterError("points", {name: spec}, "a mapping NAME -> (LINK, u, w) with LINK one of "
                                        + ", ".join(allowed))


def _crank(b: _Builder, where, crank: Crank, omega1: float, alpha1: float) -> None:
    """The crank pin A: ``v_A = iω₁(A − O)``; ``a_A = a^n_A + a^t_A`` with ``a^n_A = −ω₁²(A − O)``."""
    pin, link = crank.pin, crank.link
    arm = where[pin] - where[crank.pivot]
    b.vertex(b.pole, 0j, crank.pivot)
    label = pin.lower()
    if b.quantity == "velocity":
        b.vertex(label, 1j * omega1 * arm, pin)
        b.absolute(pin, label, link)
        b.rates[link] = omega1
        return
    normal, tangential = -omega1**2 * arm, 1j * alpha1 * arm
    if alpha1 != 0.0:
        b.vertex("n1", normal)
        b.vector(f"a^n_{pin}", b.pole, "n1", "normal", link, normal)
        b.vector(f"a^t_{pin}", "n1", label + "′", "tangential", link, tangential)
    b.vertex(label + "′", normal + tangential, pin)
    b.absolute(pin, label + "′", link)
    if alpha1 != 0.0:
        b.equations.append(((f"a_{pin}",), (f"a^n_{pin}", f"a^t_{pin}")))
    b.rates[link] = alpha1


def _rate(relative: complex, arm: complex) -> float:
    """The angular velocity (or acceleration) of a link from a vector ``iω·arm`` on a plan: Im(v/arm)."""
    return (relative / arm).imag


def _hinge_on_guide(b: _Builder, where, group: RRP, guide: complex) -> None:
    """A link known→joint whose end slides on a guide: ``v_J = v_K + v_JK``, ``v_J = v_Jg + v_JJg`` along the guide.

    On a fixed guide ``v_Jg = 0`` and v_J itself lies along it; on a moving guide Jg is the guide link's
    point under J (its image) and the acceleration adds the Coriolis term ``2ω_g × v_JJg``.
    """
    first, joint, link, slider = group.known, group.joint, group.link, group.slider
    first_label, label = b.known(first), joint.lower() + b.prime
    arm = where[joint] - where[first]
    f = b.vertices[first_label]
    relative = f"{joint}{first}"
    on_label, on_name = b.guide_point(group.guide_link, joint)
    sliding = None if on_name is None else f"{joint}{on_name}"
    letter = b.letter
    if b.quantity == "velocity":
        point, t1, t2 = meet(f, 1j * arm, b.vertices[on_label], guide)
        b.vertex(label, point, joint)
        b.vector(f"v_{relative}", first_label, label, "relative", link, t1 * 1j * arm, 1j * arm)
        if sliding is None:
            b.absolute(joint, label, slider, t2 * guide, guide)
        else:
            b.vector(f"v_{sliding}", on_label, label, "sliding", slider, t2 * guide, guide)
            b.absolute(joint, label, slider)
        start: tuple[str, ...] = (f"v_{relative}",)
        tail = on_label
    else:
        assert b.velocity is not None   # an acceleration plan is built on its velocity plan
        omega = b.velocity.rates[link]
        normal = -omega**2 * arm
        number = b.numbers[link]
        n = b.vertex(f"n{number}", f + normal)
        tail, k = b.coriolis(group.guide_link, on_label, sliding or "", slider)
        point, t1, t2 = meet(n, 1j * arm, k, guide)
        b.vertex(label, point, joint)
        b.vector(f"a^n_{relative}", first_label, f"n{number}", "normal", link, normal)
        b.vector(f"a^t_{relative}", f"n{number}", label, "tangential", link, t1 * 1j * arm, 1j * arm)
        if sliding is None:
            b.absolute(joint, label, slider, t2 * guide, guide)
        else:
            b.vector(f"a^r_{sliding}", tail, label, "sliding", slider, t2 * guide, guide)
            b.absolute(joint, label, slider)
        start = (f"a^n_{relative}", f"a^t_{relative}")
    b.equations.append(((f"{letter}_{joint}",), b.terms(first, first_label) + start))
    if sliding is not None:
        coriolis = (f"a^k_{sliding}",) if tail != on_label else ()
        kind = "v" if letter == "v" else "a^r"
        b.equations.append(((f"{letter}_{joint}",), (f"{letter}_{on_name}",) + coriolis + (f"{kind}_{sliding}",)))
    b.rates[link] = _rate(t1 * 1j * arm, arm)
    b.rates.setdefault(slider, b.rate_of(group.guide_link))
    b.links[link] = (first, joint)
    b.single.setdefault(slider, joint)


def _two_hinges(b: _Builder, where, group: RRR) -> None:
    """A joint of two links, ``v_J = v_F + v_JF = v_S + v_JS`` (``v_S = 0`` for a fixed pivot S).

    The four-bar's coupler F → J and rocker about the fixed pivot S; for a dyad whose two outer joints both
    move (a six-bar's), both ``v_F`` and ``v_S`` are known vectors of the plan drawn before.
    """
    first, pivot, joint, coupler, rocker = group.first, group.second, group.joint, group.first_link, group.second_link
    first_label, pivot_label = b.known(first), b.known(pivot)
    label = joint.lower() + b.prime
    arm1, arm2 = where[joint] - where[first], where[joint] - where[pivot]
    f, q = b.vertices[first_label], b.vertices[pivot_label]
    rel1, rel2 = f"{joint}{first}", f"{joint}{pivot}"
    left, right = b.terms(first, first_label), b.terms(pivot, pivot_label)
    if b.quantity == "velocity":
        point, t1, t2 = meet(f, 1j * arm1, q, 1j * arm2)
        b.vertex(label, point, joint)
        b.vector(f"v_{rel1}", first_label, label, "relative", coupler, t1 * 1j * arm1, 1j * arm1)
        b.vector(f"v_{rel2}", pivot_label, label, "relative", rocker, t2 * 1j * arm2, 1j * arm2)
        b.absolute(joint, label, rocker)
        b.equations.append((left + (f"v_{rel1}",), right + (f"v_{rel2}",)))
        b.equations.append(((f"v_{joint}",), right + (f"v_{rel2}",)))
    else:
        assert b.velocity is not None
        w1, w2 = b.velocity.rates[coupler], b.velocity.rates[rocker]
        normal1, normal2 = -w1**2 * arm1, -w2**2 * arm2
        n1_label, n2_label = f"n{b.numbers[coupler]}", f"n{b.numbers[rocker]}"
        n1 = b.vertex(n1_label, f + normal1)
        n2 = b.vertex(n2_label, q + normal2)
        point, t1, t2 = meet(n1, 1j * arm1, n2, 1j * arm2)
        b.vertex(label, point, joint)
        b.vector(f"a^n_{rel1}", first_label, n1_label, "normal", coupler, normal1)   # both normals first,
        b.vector(f"a^n_{rel2}", pivot_label, n2_label, "normal", rocker, normal2)    # as drawn by hand
        b.vector(f"a^t_{rel1}", n1_label, label, "tangential", coupler, t1 * 1j * arm1, 1j * arm1)
        b.vector(f"a^t_{rel2}", n2_label, label, "tangential", rocker, t2 * 1j * arm2, 1j * arm2)
        b.absolute(joint, label, rocker)
        transport = right + (f"a^n_{rel2}", f"a^t_{rel2}")
        b.equations.append((left + (f"a^n_{rel1}", f"a^t_{rel1}"), transport))
        b.equations.append(((f"a_{joint}",), transport))
    b.rates[coupler] = _rate(t1 * 1j * arm1, arm1)
    b.rates[rocker] = _rate(t2 * 1j * arm2, arm2)
    b.links[coupler] = (first, joint)
    b.links[rocker] = (pivot, joint)


def _block_on_lever(b: _Builder, where, group: RPR) -> None:
    """The block A2 on the crank pin slides in the slot of the lever; A3 is the lever's point under it.

    Velocities: ``v_A = v_A3 + v_A2A3`` (the block relative to the lever, along the slot) and
    ``v_A3 = v_C + v_A3C`` with ``v_A3C ⊥ CA``. Accelerations: ``a_A = a_A3 + a^r_A2A3 + a^k_A2A3`` with
    the Coriolis term ``a^k_A2A3 = 2ω₃ × v_A2A3`` (chapter 5's, of the block relative to the lever) and
    ``a_A3 = a_C + a^n_A3C + a^t_A3C``, ``a^n_A3C = −ω₃²(A − C)``; a fixed pivot C is the pole
    (``v_C = 0``). The digits are the links' numbers (block 2, lever 3 in the slotted lever).

    On the acceleration plan the Coriolis component ends at the block's vertex a′, so its tail k is
    known first, ``k = a′ − a^k_A2A3``; the line along the slot through k and the line ⊥ CA through n3
    meet at a3′.
    """
    on_lever = f"{group.block}{b.numbers[group.lever]}"     # the lever's point under the block (A3 under A2)
    block2 = f"{group.block}{b.numbers[group.slider]}"      # the block at A: A2
    sliding = f"{block2}{on_lever}"                          # A2 relative to A3: A2A3
    where[on_lever] = where[group.block]
    low = on_lever.lower()
    pivot_label = b.known(group.pivot)
    fixed = pivot_label == b.pole
    q = b.vertices[pivot_label]
    arm = where[group.block] - where[group.pivot]
    along = arm / abs(arm)
    relative = f"{on_lever}{group.pivot}"
    block_label = b.points[group.block]
    if b.quantity == "velocity":
        a = b.vertices[block_label]
        point, t1, t2 = meet(q, 1j * arm, a, along)
        b.vertex(low, point, on_lever)
        if fixed:
            b.absolute(on_lever, low, group.lever, t1 * 1j * arm, 1j * arm)
        else:
            b.vector(f"v_{relative}", pivot_label, low, "relative", group.lever, t1 * 1j * arm, 1j * arm)
            b.absolute(on_lever, low, group.lever)
        b.vector(f"v_{sliding}", low, block_label, "sliding", group.slider, -t2 * along, along)
        b.equations.append(((f"v_{group.block}",), (f"v_{on_lever}", f"v_{sliding}")))
        if not fixed:
            b.equations.append(((f"v_{on_lever}",), (f"v_{group.pivot}", f"v_{relative}")))
        b.rates[group.lever] = _rate(t1 * 1j * arm, arm)
    else:
        assert b.velocity is not None
        omega3 = b.velocity.rates[group.lever]
        coriolis = 2.0 * 1j * omega3 * b.velocity.vector(f"v_{sliding}").value
        b.coriolis_count += 1
        tail = "k" if b.coriolis_count == 1 else f"k{b.coriolis_count}"
        b.vertex(tail, b.vertices[block_label] - coriolis)
        b.vector(f"a^k_{sliding}", tail, block_label, "coriolis", group.slider, coriolis)
        k = b.vertices[tail]
        normal = -omega3**2 * arm
        n_label = f"n{b.numbers[group.lever]}"
        n3 = b.vertex(n_label, q + normal)
        b.vector(f"a^n_{relative}", pivot_label, n_label, "normal", group.lever, normal)
        point, t1, t2 = meet(k, along, n3, 1j * arm)
        b.vertex(low + "′", point, on_lever)
        b.vector(f"a^t_{relative}", n_label, low + "′", "tangential", group.lever, t2 * 1j * arm, 1j * arm)
        b.vector(f"a^r_{sliding}", low + "′", tail, "sliding", group.slider, -t1 * along, along)
        b.absolute(on_lever, low + "′", group.lever)
        transport = b.terms(group.pivot, pivot_label) + (f"a^n_{relative}", f"a^t_{relative}")
        b.equations.append(((f"a_{group.block}",), transport + (f"a^r_{sliding}", f"a^k_{sliding}")))
        b.equations.append(((f"a_{on_lever}",), transport))
        b.rates[group.lever] = _rate(t2 * 1j * arm, arm)
    b.rates.setdefault(group.slider, b.rates[group.lever])
    b.links[group.lever] = (group.pivot, on_lever)
    b.single.setdefault(group.slider, group.block)
    if group.joint is not None:
        _link_point(b, where, group.joint, group.lever)


def _sliding_cross(b: _Builder, where, group: PRP) -> None:
    """Two blocks hinged at J, each on its own guide: ``v_J = v_J1 + v_JJ1 = v_J2 + v_JJ2``, each relative velocity
    along its guide (J1, J2: the guide links' points under J); accelerations add ``2ω × v_rel`` for each."""
    joint, label, letter = group.joint, group.joint.lower() + b.prime, b.letter
    sides = []
    for line, slider in ((group.first_guide, group.first_slider), (group.second_guide, group.second_slider)):
        on_label, on_name = b.guide_point(line.link, joint)
        relative = "" if on_name is None else f"{joint}{on_name}"
        tail, start = b.coriolis(line.link, on_label, relative, slider)
        sides.append((line, slider, on_label, on_name, relative, tail, start, b.structure.direction(line)))
    (_, _, _, _, _, _, start1, d1), (_, _, _, _, _, _, start2, d2) = sides
    point, t1, t2 = meet(start1, d1, start2, d2)
    b.vertex(label, point, joint)
    for (line, slider, on_label, on_name, relative, tail, _, d), t in zip(sides, (t1, t2)):
        if on_name is None:       # on a fixed guide the joint's own vector lies along it
            continue
        kind = "v" if letter == "v" else "a^r"
        b.vector(f"{kind}_{relative}", tail, label, "sliding", slider, t * d, d)
        coriolis = (f"a^k_{relative}",) if tail != on_label else ()
        b.equations.append(((f"{letter}_{joint}",), (f"{letter}_{on_name}",) + coriolis + (f"{kind}_{relative}",)))
    b.absolute(joint, label, group.first_slider)
    for line, slider in ((group.first_guide, group.first_slider), (group.second_guide, group.second_slider)):
        b.rates.setdefault(slider, b.rate_of(line.link))
        b.single.setdefault(slider, joint)


def _yoke(b: _Builder, where, group: RPP) -> None:
    """A block at the known joint B in the slot of a yoke that slides on a guide (the Scotch yoke).

    With B3 the yoke's point under B and Bg the guide link's: ``v_B3 = v_Bg + v_B3Bg`` (the yoke slides along
    the guide) and ``v_B = v_B3 + v_BB3`` (the block slides along the slot); accelerations add
    ``2ω_g × v_B3Bg`` and ``2ω_g × v_BB3`` (the yoke turns with its guide). The yoke's joint Y then follows
    from the yoke's motion.
    """
    block, letter, kind = group.block, b.letter, "v" if b.quantity == "velocity" else "a^r"
    on_yoke = f"{block}{b.numbers[group.yoke]}"
    where[on_yoke] = where[block]
    low = on_yoke.lower() + b.prime
    guide, slot = b.structure.direction(group.guide), b.structure.direction(group.guide) * _unit(group.slot_angle)
    on_label, on_name = b.guide_point(group.guide.link, block)
    first = "" if on_name is None else f"{on_yoke}{on_name}"
    tail, start = b.coriolis(group.guide.link, on_label, first, group.yoke)
    block_label = b.points[block]
    second = f"{block}{on_yoke}"
    turning = b.quantity == "acceleration" and b.rate_of(group.guide.link) != 0.0
    back = 2.0 * 1j * b.velocity.rates[group.guide.link] * b.velocity.vector(f"v_{second}").value \
        if turning and b.velocity is not None else 0j
    point, t1, t2 = meet(start, guide, b.vertices[block_label] - back, slot)
    b.vertex(low, point, on_yoke)
    if on_name is None:
        b.absolute(on_yoke, low, group.yoke)
    else:
        b.vector(f"{kind}_{first}", tail, low, "sliding", group.yoke, t1 * guide, guide)
        b.absolute(on_yoke, low, group.yoke)
        coriolis = (f"a^k_{first}",) if tail != on_label else ()
        b.equations.append(((f"{letter}_{on_yoke}",), (f"{letter}_{on_name}",) + coriolis + (f"{kind}_{first}",)))
    middle = low
    if turning:
        b.coriolis_count += 1
        middle = "k" if b.coriolis_count == 1 else f"k{b.coriolis_count}"
        b.vertex(middle, point + back)
        b.vector(f"a^k_{second}", low, middle, "coriolis", group.slider, back)
    b.vector(f"{kind}_{second}", middle, block_label, "sliding", group.slider, -t2 * slot, slot)
    b.equations.append(((f"{letter}_{block}",), (f"{letter}_{on_yoke}",) + ((f"a^k_{second}",) if turning else ())
                        + (f"{kind}_{second}",)))
    b.rates.setdefault(group.yoke, b.rate_of(group.guide.link))
    b.rates.setdefault(group.slider, b.rate_of(group.guide.link))
    b.single.setdefault(group.yoke, on_yoke)
    b.single.setdefault(group.slider, block)
    label = group.joint.lower() + b.prime
    b.vertex(label, b.field(group.yoke, where[group.joint]), group.joint)
    b.absolute(group.joint, label, group.yoke)


def _link_point(b: _Builder, where, name: str, link: str) -> None:
    """A point fixed to a link already on the plan, by its image (on a block: ``v_P + iω(X − P)``)."""
    label = name.lower() + b.prime
    if link == FRAME:
        b.vertex(b.pole, 0j, name)
        return
    b.vertex(label, b.field(link, where[name]), name)
    b.absolute(name, label, link)


def _add_images(b: _Builder, extra: Mapping[str, tuple[str, float, float]] | None) -> None:
    """Images of the named extra points, and the list of vertices of each link's image."""
    for name, (link, _, _) in (extra or {}).items():
        _link_point(b, b.where, name, link)
    for link, (first, second) in b.links.items():
        names = [first, second] + [n for n, (lk, _, _) in (extra or {}).items() if lk == link]
        b.images[link] = tuple(names)


def _require_index(solution: Solution, index: int) -> None:
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)):
        raise InvalidParameterError("index", index, "an integer position of the solution")
    if not -len(solution) <= index < len(solution):
        raise InvalidParameterError("index", index, f"a position of the solution, 0 … {len(solution) - 1}")


def _groups(mechanism: Mechanism) -> tuple[Group, ...]:
    """The mechanism's structure, crank first, with a class III group refused by name."""
    groups = mechanism.groups()
    if not groups or not isinstance(groups[0], Crank):
        raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                    "a mechanism that describes its structure, crank first (Mechanism.groups()): a "
                                    "named mechanism of the book or a Linkage")
    return groups


def _construct(mechanism: Mechanism, where: dict[str, complex], quantity: str, velocity: Plan | None,
               points: Mapping[str, tuple[str, float, float]] | None, omega1: float, alpha1: float) -> _Builder:
    """A plan constructed group by group from the joints' positions and the crank's ω₁ (ε₁)."""
    groups = _groups(mechanism)
    numbers = link_numbers(groups)
    structure = _Structure(groups, where)
    b = _Builder(quantity, where, structure, numbers, velocity)
    for group in groups:
        if isinstance(group, Crank):
            _crank(b, where, group, omega1, alpha1)
            b.links[group.link] = (group.pivot, group.pin)
        elif isinstance(group, RRR):
            _two_hinges(b, where, group)
        elif isinstance(group, RRP):
            _hinge_on_guide(b, where, group, group.guide_direction if group.guide_link == FRAME
                            else structure.direction(group.guide))
        elif isinstance(group, RPR):
            _block_on_lever(b, where, group)
        elif isinstance(group, PRP):
            _sliding_cross(b, where, group)
        elif isinstance(group, RPP):
            _yoke(b, where, group)
        elif isinstance(group, LinkPoint):
            _link_point(b, where, group.name, structure.point_link[group.name])
        else:
            raise PlanError(f"{describe_group(group)} is a class III group (three joints found together): a plan of it "
                            "needs the special points of Assur's construction, which this package does not draw; "
                            "the plans are drawn for linkages of class II groups")
    _add_images(b, points)
    for group in groups:   # a link's image holds the joints fixed to it (the lever's end B)
        if isinstance(group, LinkPoint):
            name, link = group.name, structure.point_link.get(group.name)
        elif isinstance(group, RPR) and group.joint is not None:
            name, link = group.joint, group.lever
        else:
            continue
        if link in b.images:
            image_points = b.images[link]
            b.images[link] = image_points[:2] + (name,) + image_points[2:]
    return b


def _build(mechanism: Mechanism, solution: Solution, index: int, quantity: str, velocity: Plan | None,
           points: Mapping[str, tuple[str, float, float]] | None, scale: float | None) -> Plan:
    _require_index(solution, index)
    needed = 1 if quantity == "velocity" else 2
    if solution.order < needed:
        raise InvalidParameterError("solution", f"order={solution.order}", f"a solution of order ≥ {needed} "
                                    "(the crank's angular velocity and acceleration are read from it)")
    groups = _groups(mechanism)
    crank = solution.angle(cast(Crank, groups[0]).link)
    omega1, alpha1 = float(crank.omega[index]), float(crank.alpha[index]) if needed == 2 else 0.0
    phi = float(crank.value[index])
    cls = VelocityPlan if quantity == "velocity" else AccelerationPlan
    structure = _Structure(groups, _positions(mechanism, solution, index, None))
    _check_extra(points, tuple(link for link in link_numbers(groups) if link != FRAME
                               and link not in structure.blocks))
    where = _positions(mechanism, solution, index, points)
    b = _construct(mechanism, where, quantity, velocity, points, omega1, alpha1)
    return b.finish(cls, phi, scale, where)


def velocity_plan(mechanism: Mechanism, solution: Solution, index: int = 0,
                  points: Mapping[str, tuple[str, float, float]] | None = None,
                  scale: float | None = None) -> VelocityPlan:
    """The velocity plan of a mechanism at one crank position, constructed as on paper.

    Parameters
    ----------
    mechanism : Mechanism
        One that describes its structure (``groups()``): a crank, then class II groups (RRR, RRP,
        RPR, PRP, RPP, on fixed or moving guides) and points fixed to links: the crank-slider, the
        four-bar, the slotted lever, the shaper (chapters 3, 4, 5) or a linkage file's
        :class:`~mechanisms.linkages.composed.Linkage` (chapter 6).
    solution : Solution
        Its solution, order ≥ 1; only the joint positions and the crank's ω₁ are used.
    index : int
        Which crank position of the solution.
    points : dict, optional
        Further points of links by name: ``{"S2": ("coupler", u, w)}``, u along the link from its
        first joint and w to its left (m), found on the plan by their images.
    scale : float, optional
        μ_v in (m/s)/mm; by default the smallest course scale (1, 2, 2.5, 4, 5 × 10ᵏ) that keeps
        every vertex of the plan within 100 mm of the pole.

    Returns
    -------
    VelocityPlan
        Pole ``p``; vertices ``a``, ``b`` … (lower-case joint names; ``a3`` for the lever's point
        under the block of a slotted lever: a link's point under a joint is named by the joint and
        the link's number); ``rates`` holds the links' angular velocities read off the plan (a
        block's is its guide's, zero on a fixed guide).

    Raises
    ------
    PlanError
        At a singular position (two lines of the plan parallel), or for a class III group.
    InvalidParameterError
        A mechanism that does not describe its structure, an index out of range, a solution of
        order 0, an extra point on an unknown link or on a block, a scale that is not finite and > 0.

    Notes
    -----
    Crank-slider: ``v_B = v_A + v_BA``, ``v_BA ⊥ AB``, ``v_B ∥ guide``. Four-bar:
    ``v_B = v_A + v_BA = v_C + v_BC`` with ``v_BA ⊥ AB``, ``v_BC ⊥ CB``. Slotted lever:
    ``v_A = v_A3 + v_A2A3`` with ``v_A3 ⊥ CA`` and ``v_A2A3 ∥ CA`` (the block A2 relative to the lever's
    point A3 under it); shaper: then
    ``v_D = v_B + v_DB``. ω of a link = (relative velocity)/(length), its sense from the direction.
    A six-bar's dyad E–F–D: ``v_F = v_E + v_FE = v_D + v_FD``, both v_E and v_D known. A slider J on
    a guide of the moving link g: ``v_J = v_K + v_JK = v_Jg + v_JJg`` with Jg the image of J on g
    and ``v_JJg`` along the guide. A PRP's joint: ``v_J = v_J1 + v_JJ1 = v_J2 + v_JJ2``; an RPP's
    (the yoke's point B3 under the block B): ``v_B3 = v_Bg + v_B3Bg``, ``v_B = v_B3 + v_BB3``.
    """
    return cast(VelocityPlan, _build(mechanism, solution, index, "velocity", None, points, scale))


def acceleration_plan(mechanism: Mechanism, solution: Solution, index: int = 0,
                      points: Mapping[str, tuple[str, float, float]] | None = None,
                      scale: float | None = None, velocity: VelocityPlan | None = None) -> AccelerationPlan:
    """The acceleration plan of a mechanism at one crank position, constructed as on paper.

    Parameters
    ----------
    mechanism, solution, index, points
        As for :func:`velocity_plan`; the solution must have order 2 (the crank's ε₁ is read).
    scale : float, optional
        μ_a in (m/s²)/mm; by default as for :func:`velocity_plan`.
    velocity : VelocityPlan, optional
        The velocity plan whose angular velocities and relative velocities the normal and
        Coriolis terms use; built here if omitted.

    Returns
    -------
    AccelerationPlan
        Pole ``π``; vertices ``a′``, ``b′`` …, the ends ``n2``, ``n3``, ``n4`` of the normal
        components of links 2, 3, 4 (``n1`` of the crank's if ε₁ ≠ 0) and ``k`` of the Coriolis
        component (``k2``, ``k3`` … of further ones); ``rates`` holds the angular accelerations
        read off the plan.

    Notes
    -----
    Crank-slider: ``a_B = a_A + a^n_BA + a^t_BA`` with ``a^n_BA = ω₂² l_AB`` directed from B to A,
    ``a^t_BA ⊥ AB`` and ``a_B ∥ guide``. Four-bar: also ``a_B = a^n_BC + a^t_BC``. Slotted lever:
    ``a_A = a_A3 + a^r_A2A3 + a^k_A2A3`` with ``a_A3 = a^n_A3C + a^t_A3C``, ``a^k_A2A3 = 2ω₃ v_A2A3``
    turned by 90° in the sense of ω₃ (chapter 5's sense), ``a^r ∥ CA``. ε of a link = a^t/(length), its sense from the direction.
    A slider on a moving guide g: ``a_J = a_Jg + a^k_JJg + a^r_JJg`` with ``a^k_JJg = 2ω_g × v_JJg``.
    """
    _require_index(solution, index)
    if velocity is None:
        velocity = velocity_plan(mechanism, solution, index, points)
    elif not math.isclose(velocity.phi, float(solution.phi[index]), abs_tol=1e-12):
        raise InvalidParameterError("velocity", f"a plan at φ = {math.degrees(velocity.phi):g}°",
                                    f"the velocity plan of the same position, φ = "
                                    f"{math.degrees(float(solution.phi[index])):g}°")
    return cast(AccelerationPlan, _build(mechanism, solution, index, "acceleration", velocity, points, scale))


# --- the order of construction ---------------------------------------------------------------------

class PlanStep(NamedTuple):
    """One step of a plan's construction (:func:`plan_steps`): the vertex it finds and how."""

    vertex: str
    """The label of the vertex found at this step (``a``, ``n2``, ``b′`` …)."""
    vectors: tuple[str, ...]
    """The names of the vectors drawn at this step, in the order of construction."""
    lines: tuple[tuple[str, complex, str], ...]
    """The two (or more) lines whose intersection is the vertex, each as (the known vertex it passes
    through, its unit direction, the name of the vector that lies on it); empty when the vertex is
    drawn from a vector known whole (the crank pin's, a normal or Coriolis component, an image)."""


def _line_direction(vector: PlanVector) -> complex:
    if vector.line != 0:
        return vector.line
    return vector.value / abs(vector.value) if vector.value != 0 else 0j


def plan_steps(plan: Plan) -> tuple[PlanStep, ...]:
    """The order in which a plan is constructed by hand, one vertex per step.

    The vectors are taken in the order of construction. Each step finds one new vertex: from the one
    vector that joins it to a vertex already drawn when that vector is known whole (its length and
    direction: the crank pin's velocity, a normal or Coriolis component, a point by its image), or as
    the intersection of the lines of two vectors whose directions only are known (perpendicular to a
    link, along a guide or a slot), each drawn through the vertex already known at its other end. The
    vectors of a step are all those that join its vertex to vertices already drawn.

    Parameters
    ----------
    plan : VelocityPlan or AccelerationPlan

    Returns
    -------
    tuple of PlanStep
        One step per vertex other than the pole, in the order of construction.

    Notes
    -----
    Where an intersection has more than two lines (the four-bar's ``v_BC`` and ``v_B`` both run from
    ``p`` in one direction) the relative vectors are used and lines through one vertex in one
    direction are counted once. A vector that joins two vertices both drawn before it is drawn with
    the step of its later vertex.
    """
    known = {plan.pole}
    drawn: set[int] = set()
    steps: list[PlanStep] = []
    for index, vector in enumerate(plan.vectors):
        if index in drawn:
            continue
        new = [end for end in (vector.tail, vector.head) if end not in known]
        if not new:
            drawn.add(index)
            if steps:                            # both ends drawn already: it joins the last step
                last = steps[-1]
                steps[-1] = last._replace(vectors=last.vectors + (vector.name,))
            continue
        vertex = new[0]
        if len(new) == 2:                        # neither end drawn (not built so): the head is found
            known.add(vector.tail)
            vertex = vector.head
        group = [k for k, v in enumerate(plan.vectors) if k not in drawn
                 and vertex in (v.tail, v.head) and ({v.tail, v.head} - {vertex}) <= known]
        whole = len(group) == 1 or any(plan.vectors[k].line == 0 and plan.vectors[k].kind != "absolute"
                                       for k in group)
        lines: list[tuple[str, complex, str]] = []
        if not whole:
            chosen = [k for k in group if plan.vectors[k].kind != "absolute"]
            if len(chosen) < 2:
                chosen = group
            for k in chosen:
                v = plan.vectors[k]
                through = v.head if v.tail == vertex else v.tail
                direction = _line_direction(v)
                if direction == 0 or any(t == through and abs(_cross(d, direction)) < 1e-12 for t, d, _ in lines):
                    continue
                lines.append((through, direction, v.name))
        known.add(vertex)
        drawn.update(group)
        steps.append(PlanStep(vertex, tuple(plan.vectors[k].name for k in group), tuple(lines)))
    return tuple(steps)


# --- instant centres ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class InstantCentres:
    """The instant centres P_ij of a mechanism at one crank position.

    Attributes
    ----------
    links : dict
        Link name → its number, in the order the groups add the links: frame 0, crank 1, then (a
        four-bar, a crank-slider) coupler 2, rocker or slider 3.
    finite : dict
        ``(i, j)`` (i < j) → the centre ``x + iy`` (m).
    infinite : dict
        ``(i, j)`` → the direction (a unit complex number) in which a centre at infinity lies: the
        relative motion of the two links is a translation perpendicular to it.
    positions : dict
        The joints of the drawing (m).
    lines : dict
        ``(i, k)`` → the two lines of Kennedy's theorem that located P_ik, each as the pair of centres
        it passes through (``((0, 1), (1, 2))`` for the line P01P12); only the centres found so.
    joints : dict
        ``(i, j)`` → the joint of the pair that gives a primary centre (a hinge, or a slider's joint
        for a centre at infinity).

    A centre neither in ``lines`` nor in ``joints`` was found from the velocities.
    """

    links: dict[str, int]
    finite: dict[tuple[int, int], complex]
    infinite: dict[tuple[int, int], complex]
    positions: dict[str, complex]
    lines: dict[tuple[int, int], tuple[tuple[tuple[int, int], tuple[int, int]], ...]] = field(default_factory=dict)
    joints: dict[tuple[int, int], str] = field(default_factory=dict)

    def __getitem__(self, pair: tuple[int, int]) -> complex:
        """The centre P_ij as a point; for a centre at infinity, infinite components along its direction."""
        i, j = sorted(pair)
        if (i, j) in self.finite:
            return self.finite[(i, j)]
        if (i, j) not in self.infinite:
            raise KeyError(f"no instant centre P{i}{j}; the links are numbered "
                           + ", ".join(f"{name} {n}" for name, n in self.links.items()))
        d = self.infinite[(i, j)]
        far = lambda part: math.copysign(math.inf, part) if abs(part) > 1e-12 else 0.0  # noqa: E731
        return complex(far(d.real), far(d.imag))

    def is_finite(self, i: int, j: int) -> bool:
        """True if P_ij is a point of the plane, False if it lies at infinity."""
        return tuple(sorted((i, j))) in self.finite

    @property
    def pairs(self) -> list[tuple[int, int]]:
        """All pairs (i, j), i < j: n(n − 1)/2 of them for n links."""
        return sorted(set(self.finite) | set(self.infinite))

    @staticmethod
    def name(i: int, j: int) -> str:
        """``P13`` for the pair (1, 3)."""
        i, j = sorted((i, j))
        return f"P{i}{j}"


def _line_meet(p1: complex, d1: complex, p2: complex, d2: complex) -> complex | None:
    """The meeting point of two lines, or None if they are parallel."""
    try:
        return meet(p1, d1, p2, d2)[0]
    except PlanError:
        return None


def instant_centre_path(solution: Solution, link: str) -> PointMotion:
    """The instant centre of a link relative to the frame, at every position of a solution.

    With the link's first joint P as its pole, the velocity of a point r of the link is
    v = v_P + iθ_t(r − r_P) (chapter 1), which is zero at r_I = r_P + i·v_P/θ_t.

    Parameters
    ----------
    solution : Solution
        A solution with velocities (``order`` ≥ 1).
    link : str
        The link's name (``"coupler"`` …).

    Returns
    -------
    PointMotion
        Positions only (m); ``nan`` where θ_t = 0, where the link translates for an instant and
        its centre is at infinity.
    """
    if solution.order < 1:
        raise InvalidParameterError("solution", f"order {solution.order}", "a solution with velocities (order ≥ 1)")
    pole = solution.point_on(link, 0.0)
    turning = np.broadcast_to(solution.angle(link).omega, np.shape(solution.phi))
    with np.errstate(divide="ignore", invalid="ignore"):
        centre = np.where(turning != 0.0, pole.value + 1j * pole.velocity / turning, np.nan + 0j)
    return PointMotion(centre)


def _line(finite: Mapping[tuple[int, int], complex], infinite: Mapping[tuple[int, int], complex],
          pair_a: tuple[int, int], pair_b: tuple[int, int]) -> tuple[complex, complex] | None:
    """The line through two centres (one of them may be at infinity): (point, direction); None for two at infinity."""
    if pair_a in infinite:
        pair_a, pair_b = pair_b, pair_a
    if pair_a in infinite:
        return None
    if pair_b in infinite:
        return finite[pair_a], infinite[pair_b]
    direction = finite[pair_b] - finite[pair_a]
    return (finite[pair_a], direction) if direction != 0 else None


def _kennedy(lines: Sequence[tuple[complex, complex]], size: float) -> tuple[str, complex, int, int] | None:
    """Where Kennedy's lines of one centre meet: ``("finite", point, a, b)`` from the two lines a, b that cross
    at the widest angle, ``("infinite", direction, a, b)`` if all are parallel and two are distinct, or None
    if they all coincide (the centre is not fixed by them)."""
    best = max(((abs(_cross(lines[a][1], lines[b][1])) / (abs(lines[a][1]) * abs(lines[b][1])), a, b)
                for a, b in itertools.combinations(range(len(lines)), 2)), key=lambda item: item[0])
    _, a, b = best
    point = _line_meet(lines[a][0], lines[a][1], lines[b][0], lines[b][1])
    if point is not None:
        return "finite", point, a, b
    for a, b in itertools.combinations(range(len(lines)), 2):
        (p1, d1), (p2, _) = lines[a], lines[b]
        if abs(_cross(d1, p2 - p1)) / abs(d1) > 1e-9 * size:     # parallel and apart: they meet at infinity
            return "infinite", d1 / abs(d1), a, b
    return None


def _unit_velocity_fields(mechanism: Mechanism, where: dict[str, complex]) -> dict[str, tuple[complex, float]]:
    """Each link's velocity field at ω₁ = 1 from a velocity plan built on the positions: link → (v at the
    origin, ω), so that ``v(X) = v₀ + iωX``; the frame's is zero."""
    b = _construct(mechanism, dict(where), "velocity", None, None, 1.0, 0.0)
    fields: dict[str, tuple[complex, float]] = {FRAME: (0j, 0.0)}
    for link, rate in b.rates.items():
        point = b.links[link][0] if link in b.links else b.single[link]
        fields[link] = (b.vertices[b.points[point]] - 1j * rate * b.where[point], rate)
    return fields


def instant_centres(mechanism: Mechanism, solution: Solution, index: int = 0) -> InstantCentres:
    """All n(n − 1)/2 instant centres of a mechanism of n links (the frame counted) at one crank position.

    Parameters
    ----------
    mechanism : Mechanism
        One that describes its structure (``groups()``): a named mechanism or a
        :class:`~mechanisms.linkages.composed.Linkage`.
    solution : Solution
        Positions are enough (order 0).
    index : int
        Which crank position.

    Returns
    -------
    InstantCentres
        The centres P_ij, links numbered as the groups add them (frame 0, crank 1 …).

    Raises
    ------
    InvalidParameterError
        A mechanism that does not describe its structure, or names one link twice, or an index out of range.
    PlanError
        A centre that neither Kennedy's lines nor the velocities fix (a singular position), or that needs
        the velocities of a class III group.

    Notes
    -----
    The *primary* centres come from the pairs: a hinge joining links i and j is P_ij; a sliding pair lies
    at infinity perpendicular to its guide, whether the guide is fixed or moves. Kennedy's theorem (the
    three centres of any three links lie on one line) then gives every P_ik for which two links j have
    P_ij and P_jk known: the lines P_ijP_jk meet at P_ik; it is applied again as long as it finds more
    (for a four-bar: P02 on P01P12 and P03P23, P13 on P01P03 and P12P23). A centre whose lines are
    parallel lies at infinity (P02 of a four-bar whose crank and rocker are parallel). The centres Kennedy's
    lines leave undetermined come from the velocities (a velocity plan at ω₁ = 1 on the positions): with
    ``v_i(X) = v_i0 + iω_i X`` the field of link i, P_ik is where ``v_i(X) = v_k(X)``,
    ``X = (v_k0 − v_i0) / (i(ω_i − ω_k))``, at infinity across ``v_i0 − v_k0`` if ω_i = ω_k.
    :func:`kennedy_deviation` checks the result.
    """
    _require_index(solution, index)
    groups = _groups(mechanism)
    named = [link for group in groups for link in group.links]
    twice = sorted({link for link in named if named.count(link) > 1})
    if twice:
        raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                    "a mechanism whose links have distinct names, so that its centres can be "
                                    f"numbered: link {', '.join(map(repr, twice))} is named by two groups")
    where = {name: complex(solution.point(name).value[index]) for name in solution.point_names}
    structure = _Structure(groups, where)
    links = link_numbers(groups)
    finite: dict[tuple[int, int], complex] = {}
    infinite: dict[tuple[int, int], complex] = {}
    joints: dict[tuple[int, int], str] = {}
    for pair in structure.pairs:
        key = cast(tuple[int, int], tuple(sorted((links[pair.first], links[pair.second]))))
        if key in finite or key in infinite:
            continue
        if pair.kind == "R":
            finite[key] = where[pair.joint]
        else:   # a sliding pair: at infinity, perpendicular to the guide
            infinite[key] = 1j * pair.along
        joints[key] = pair.joint
    numbers = sorted(links.values())
    positions = list(where.values())
    size = max([abs(p - q) for p in positions for q in positions] + [1e-300])
    lines: dict[tuple[int, int], tuple[tuple[tuple[int, int], tuple[int, int]], ...]] = {}
    found = True
    while found:
        found = False
        for i, k in itertools.combinations(numbers, 2):
            if (i, k) in finite or (i, k) in infinite:
                continue
            ways, drawn = [], []
            for j in numbers:
                first = cast(tuple[int, int], tuple(sorted((i, j))))
                second = cast(tuple[int, int], tuple(sorted((j, k))))
                if j in (i, k) or not all(p in finite or p in infinite for p in (first, second)):
                    continue
                line = _line(finite, infinite, first, second)
                if line is not None:
                    ways.append((first, second))
                    drawn.append(line)
            if len(drawn) < 2:
                continue
            result = _kennedy(drawn, size)
            if result is None:
                continue
            kind, value, a, b = result
            (finite if kind == "finite" else infinite)[(i, k)] = value
            lines[(i, k)] = (ways[a], ways[b])
            found = True
    missing = [(i, k) for i, k in itertools.combinations(numbers, 2) if (i, k) not in finite and (i, k) not in infinite]
    if missing:
        try:
            fields = _unit_velocity_fields(mechanism, where)
        except PlanError as error:
            raise PlanError(f"the instant centres {', '.join(InstantCentres.name(*p) for p in missing)} are fixed by "
                            f"no two of Kennedy's lines here, and the velocities cannot be found: {error}") from None
        by_number = {number: link for link, number in links.items()}
        for i, k in missing:
            (vi, wi), (vk, wk) = fields[by_number[i]], fields[by_number[k]]
            if abs(wi - wk) > 1e-12 * max(abs(wi), abs(wk), 1.0):
                finite[(i, k)] = (vk - vi) / (1j * (wi - wk))
            elif vi != vk:
                infinite[(i, k)] = 1j * (vi - vk) / abs(vi - vk)
            else:
                raise PlanError(f"the instant centre {InstantCentres.name(i, k)} is undetermined here: links "
                                f"{by_number[i]!r} and {by_number[k]!r} have no relative motion at this position")
    return InstantCentres(links, finite, infinite, where, lines, joints)


def kennedy_deviation(centres: InstantCentres) -> float:
    """The largest departure from Kennedy's theorem over all triples of links, relative to the mechanism's size.

    For three finite centres: the distance of one of them from the line through the other two, taking
    the line through the two farthest apart. With one centre at infinity: how far the line through the
    other two is from its direction, i.e. the component of their chord across that direction. Both
    are divided by the size of the mechanism (the largest distance between two joints), so the result
    is 0 when every triple is collinear and of the order of round-off for exact centres. Triples with
    two centres at infinity lie on the line at infinity and count as collinear.
    """
    joints = list(centres.positions.values())
    size = max([abs(p - q) for p in joints for q in joints] + [1e-300])
    worst = 0.0
    numbers = sorted(centres.links.values())
    for i, j, k in itertools.combinations(numbers, 3):
        trio = [(i, j), (j, k), (i, k)]
        far = [p for p in trio if not centres.is_finite(*p)]
        near = [centres[p] for p in trio if centres.is_finite(*p)]
        if len(far) >= 2:
            continue
        if far:
            direction = centres.infinite[far[0]]
            offset = abs(_cross(near[1] - near[0], direction)) / abs(direction)
        else:
            # the longest side is the base; the third point's distance from it is the departure
            sides = sorted(((abs(near[b] - near[a]), a, b) for a, b in ((0, 1), (1, 2), (0, 2))), reverse=True)
            length, a, b = sides[0]
            if length == 0.0:
                continue
            c = 3 - a - b
            offset = abs(_cross(near[b] - near[a], near[c] - near[a])) / length
        worst = max(worst, offset / size)
    return worst


def velocities_from_centre(centre: complex, known_point: complex, known_velocity: complex,
                           points: Mapping[str, complex]) -> tuple[float, dict[str, complex]]:
    """A link's angular velocity and its points' velocities from its instant centre.

    Parameters
    ----------
    centre : complex
        The link's instant centre P (m), finite.
    known_point, known_velocity : complex
        One point of the link and its velocity (m, m/s), e.g. the crank pin A with ``iω₁(A − O)``.
    points : dict
        Name → position (m) of the points whose velocities are wanted.

    Returns
    -------
    (omega, velocities)
        ω (1/s) from ``v_A = iω(A − P)``, i.e. ``ω = |v_A| / |PA|`` with its sense, and
        ``{name: iω(X − P)}``: every velocity is perpendicular to the ray from P and
        proportional to the distance from P.
    """
    arm = complex(known_point) - complex(centre)
    if abs(arm) == 0:
        raise InvalidParameterError("known_point", known_point, "a point other than the instant centre")
    omega = (complex(known_velocity) / (1j * arm)).real
    return omega, {name: 1j * omega * (complex(p) - complex(centre)) for name, p in points.items()}


# --- a report of both plans, for the command line --------------------------------------------------------

class PlanRow(NamedTuple):
    """One vector of a plan as a student checks it against a hand drawing (:func:`plan_report`)."""

    quantity: str
    """``velocity`` or ``acceleration``: the plan it is on."""
    name: str
    """Its symbol in the book's lettering: ``v_A``, ``v_BA``, ``a^n_BA``, ``a^k_A2A3`` …"""
    segment: str
    """Its segment on the plan, tail and head vertex: ``pa``, ``ab``, ``πa′``, ``n2b′`` …"""
    length_mm: float
    """Its drawn length at the plan's scale (mm): magnitude / μ_v or μ_a."""
    magnitude: float
    """Its value (m/s or m/s²)."""
    unit: str
    """``m/s`` or ``m/s²``."""
    direction_deg: float
    """Its direction, degrees counter-clockwise from +x, in [0, 360)."""


@dataclass(frozen=True)
class PlanReport:
    """Both plans of a mechanism at one crank position, and every vector of them (:func:`plan_report`).

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism, for drawing the plans beside it.
    solution : Solution
        Its solution at the one crank position (order 2).
    velocity, acceleration : Plan
        The velocity plan (pole ``p``, scale μ_v) and the acceleration plan (pole ``π``, μ_a).
    rows : tuple of PlanRow
        Every vector of the velocity plan, then every vector of the acceleration plan, in the order
        of construction.
    """

    mechanism: Mechanism
    solution: Solution
    velocity: VelocityPlan
    acceleration: AccelerationPlan
    rows: tuple[PlanRow, ...]

    def as_dict(self) -> dict[str, object]:
        """The report as plain data (for JSON): the crank angle, both scales, the links' rates and the rows."""
        return {"phi_deg": math.degrees(self.velocity.phi),
                "scale_v": self.velocity.scale, "scale_a": self.acceleration.scale,
                "omega": dict(self.velocity.rates), "epsilon": dict(self.acceleration.rates),
                "vectors": [row._asdict() for row in self.rows]}


def plan_report(linkage: Mechanism, phi: float, omega: float, alpha: float = 0.0, scale_v: float | None = None,
                scale_a: float | None = None) -> PlanReport:
    """The velocity and acceleration plans of a mechanism at one crank angle, vector by vector.

    Parameters
    ----------
    linkage : Mechanism
        A mechanism of class II groups that describes its structure: a
        :class:`~mechanisms.linkages.composed.Linkage` (a linkage file) or a named mechanism.
    phi : float
        The crank angle φ (rad).
    omega : float
        The crank's angular velocity ω₁ (1/s, counter-clockwise positive).
    alpha : float
        The crank's angular acceleration ε₁ (1/s²).
    scale_v, scale_a : float, optional
        μ_v in (m/s)/mm and μ_a in (m/s²)/mm; by default the smallest course scales (1, 2, 2.5, 4,
        5 × 10ᵏ) that keep each plan within 100 mm of its pole (:func:`nice_scale`).

    Returns
    -------
    PlanReport
        Both plans and, for every vector, its name, its segment on the plan, its length in mm at the
        scale, its value and its direction.

    Raises
    ------
    InvalidParameterError
        A φ, ω₁ or ε₁ that is not a finite number, a scale that is not finite and > 0.
    AssemblyError
        If the mechanism cannot be assembled at φ.
    PlanError
        At a singular position (two lines of a plan parallel), or for a class III group.
    """
    phi = require_finite("phi", phi)
    omega = require_finite("omega", omega)
    alpha = require_finite("alpha", alpha)
    for name, scale in (("scale_v", scale_v), ("scale_a", scale_a)):
        if scale is not None and not require_finite(name, scale) > 0.0:
            raise InvalidParameterError(name, scale, "a finite scale > 0 (units per mm)")
    solution = linkage.solve(np.array([phi]), omega, alpha=alpha, order=2)
    velocity = velocity_plan(linkage, solution, 0, scale=scale_v)
    acceleration = acceleration_plan(linkage, solution, 0, scale=scale_a, velocity=velocity)
    rows = tuple(PlanRow(plan.quantity, vector.name, vector.tail + vector.head, vector.magnitude / plan.scale,
                         vector.magnitude, plan.unit, vector.direction_deg)
                 for plan in (velocity, acceleration) for vector in plan.vectors)
    return PlanReport(linkage, solution, velocity, acceleration, rows)
