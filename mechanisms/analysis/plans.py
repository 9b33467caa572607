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

Instant centres (:func:`instant_centres`) are found by Kennedy's theorem for the four-bar and the
crank-slider; :func:`velocities_from_centre` gives the velocities of a link's points from its
instant centre.

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
from ..linkages.base import Mechanism, Solution
from ..core.errors import InvalidParameterError, MechanismError
from ..linkages.groups import RPR, RRP, RRR, Crank, LinkPoint, four_link, link_numbers

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
    "InstantCentres",
    "instant_centres",
    "instant_centre_path",
    "kennedy_deviation",
    "velocities_from_centre",
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
        Its symbol in the book's lettering: ``v_A``, ``v_BA``, ``a^n_BA``, ``a^k_A3A2`` …
    tail, head : str
        Labels of the plan vertices it joins (``p``, ``a``, ``b`` …; ``π``, ``a′``, ``n2`` …).
    kind : str
        ``absolute`` (from the pole), ``relative`` (rotation about another joint), ``normal``,
        ``tangential``, ``sliding`` (along a slot) or ``coriolis``.
    link : str
        The link whose motion the vector describes (``crank``, ``coupler`` …), for its colour.
    value : complex
        The vector as the construction found it (m/s or m/s²).
    """

    name: str
    tail: str
    head: str
    kind: str
    link: str
    value: complex

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
            A vector's name (``v_A3A2``, ``a^k_A3A2``) or a mechanism point's name.
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


# --- the constructions, one per mechanism --------------------------------------------------------------

class _Builder:
    """Collects the vertices, vectors and equations of a plan as the construction goes."""

    def __init__(self, quantity: str):
        self.quantity = quantity
        self.pole = "p" if quantity == "velocity" else "π"
        self.vertices = {self.pole: 0j}
        self.points: dict[str, str] = {}
        self.vectors: list[PlanVector] = []
        self.equations: list[tuple[tuple[str, ...], tuple[str, ...]]] = []
        self.rates: dict[str, float] = {}
        self.images: dict[str, tuple[str, ...]] = {}

    def vertex(self, label: str, value: complex, point: str | None = None) -> complex:
        self.vertices[label] = complex(value)
        if point is not None:
            self.points[point] = label
        return complex(value)

    def vector(self, name: str, tail: str, head: str, kind: str, link: str, value: complex) -> None:
        self.vectors.append(PlanVector(name, tail, head, kind, link, complex(value)))

    def absolute(self, point: str, label: str, link: str, value: complex | None = None) -> None:
        """The vector from the pole to a point's vertex (its velocity or acceleration)."""
        letter = "v" if self.quantity == "velocity" else "a"
        value = self.vertices[label] if value is None else value
        self.vector(f"{letter}_{point}", self.pole, label, "absolute", link, value)

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
    for name, spec in (extra or {}).items():
        if len(spec) != 3 or spec[0] not in allowed:
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


def _hinge_on_guide(b: _Builder, where, first: str, first_label: str, joint: str, label: str, link: str,
                    slider: str, guide: complex, velocity: Plan | None, number: int) -> None:
    """A link first→joint whose end slides on a fixed guide: ``v_J = v_F + v_JF``, v_J along the guide."""
    arm = where[joint] - where[first]
    f = b.vertices[first_label]
    relative = f"{joint}{first}"
    if b.quantity == "velocity":
        point, t1, t2 = meet(f, 1j * arm, 0j, guide)
        b.vertex(label, point, joint)
        b.vector(f"v_{relative}", first_label, label, "relative", link, t1 * 1j * arm)
        b.absolute(joint, label, slider, t2 * guide)
        b.equations.append(((f"v_{joint}",), (f"v_{first}", f"v_{relative}")))
        b.rates[link] = _rate(t1 * 1j * arm, arm)
        return
    assert velocity is not None   # an acceleration plan is built on its velocity plan
    omega = velocity.rates[link]
    normal = -omega**2 * arm
    n = b.vertex(f"n{number}", f + normal)
    point, t1, t2 = meet(n, 1j * arm, 0j, guide)
    b.vertex(label, point, joint)
    b.vector(f"a^n_{relative}", first_label, f"n{number}", "normal", link, normal)
    b.vector(f"a^t_{relative}", f"n{number}", label, "tangential", link, t1 * 1j * arm)
    b.absolute(joint, label, slider, t2 * guide)
    b.equations.append(((f"a_{joint}",), (f"a_{first}", f"a^n_{relative}", f"a^t_{relative}")))
    b.rates[link] = _rate(t1 * 1j * arm, arm)


def _two_hinges(b: _Builder, where, first: str, first_label: str, pivot: str, pivot_label: str, joint: str,
                label: str, coupler: str, rocker: str, velocity: Plan | None) -> None:
    """A joint of two links, coupler first→joint and rocker about the fixed pivot: ``v_J = v_F + v_JF = v_JP``."""
    arm1, arm2 = where[joint] - where[first], where[joint] - where[pivot]
    f, q = b.vertices[first_label], b.vertices[pivot_label]
    rel1, rel2 = f"{joint}{first}", f"{joint}{pivot}"
    if b.quantity == "velocity":
        point, t1, t2 = meet(f, 1j * arm1, q, 1j * arm2)
        b.vertex(label, point, joint)
        b.vector(f"v_{rel1}", first_label, label, "relative", coupler, t1 * 1j * arm1)
        b.vector(f"v_{rel2}", pivot_label, label, "relative", rocker, t2 * 1j * arm2)
        b.absolute(joint, label, rocker)
        b.equations.append(((f"v_{first}", f"v_{rel1}"), (f"v_{rel2}",)))   # v_C = 0: a fixed pivot
        b.equations.append(((f"v_{joint}",), (f"v_{rel2}",)))
        b.rates[coupler] = _rate(t1 * 1j * arm1, arm1)
        b.rates[rocker] = _rate(t2 * 1j * arm2, arm2)
        return
    assert velocity is not None
    w1, w2 = velocity.rates[coupler], velocity.rates[rocker]
    normal1, normal2 = -w1**2 * arm1, -w2**2 * arm2
    n1 = b.vertex("n2", f + normal1)
    n2 = b.vertex("n3", q + normal2)
    point, t1, t2 = meet(n1, 1j * arm1, n2, 1j * arm2)
    b.vertex(label, point, joint)
    b.vector(f"a^n_{rel1}", first_label, "n2", "normal", coupler, normal1)
    b.vector(f"a^t_{rel1}", "n2", label, "tangential", coupler, t1 * 1j * arm1)
    b.vector(f"a^n_{rel2}", pivot_label, "n3", "normal", rocker, normal2)
    b.vector(f"a^t_{rel2}", "n3", label, "tangential", rocker, t2 * 1j * arm2)
    b.absolute(joint, label, rocker)
    b.equations.append(((f"a_{first}", f"a^n_{rel1}", f"a^t_{rel1}"), (f"a^n_{rel2}", f"a^t_{rel2}")))
    b.equations.append(((f"a_{joint}",), (f"a^n_{rel2}", f"a^t_{rel2}")))
    b.rates[coupler] = _rate(t1 * 1j * arm1, arm1)
    b.rates[rocker] = _rate(t2 * 1j * arm2, arm2)


def _block_on_lever(b: _Builder, where, group: RPR, on_lever: str, velocity: Plan | None) -> None:
    """The lever's point A3 under the block A2 (on the crank pin): ``v_A3 = v_A2 + v_A3A2``, v_A3 ⊥ CA.

    Accelerations: ``a_A3 = a_A2 + a^k_A3A2 + a^r_A3A2 = a^n_A3C + a^t_A3C`` with the Coriolis term
    ``a^k_A3A2 = 2ω₃ × v_A3A2`` (the block turns with the lever) and ``a^n_A3C = −ω₃²(A − C)``.
    """
    low = on_lever.lower()
    block2 = group.block + "2"     # the block (link 2) at A: A2
    arm = where[group.block] - where[group.pivot]
    along = arm / abs(arm)
    b.vertex(b.pole, 0j, group.pivot)
    if b.quantity == "velocity":
        a = b.vertices[b.points[group.block]]
        point, t1, t2 = meet(0j, 1j * arm, a, along)
        b.vertex(low, point, on_lever)
        b.vector(f"v_{on_lever}{block2}", b.points[group.block], low, "sliding", group.slider, t2 * along)
        b.absolute(on_lever, low, group.lever, t1 * 1j * arm)
        b.equations.append(((f"v_{on_lever}",), (f"v_{group.block}", f"v_{on_lever}{block2}")))
        b.rates[group.lever] = _rate(t1 * 1j * arm, arm)
        return
    assert velocity is not None
    omega3 = velocity.rates[group.lever]
    sliding = velocity.vector(f"v_{on_lever}{block2}").value
    coriolis = 2.0 * 1j * omega3 * sliding
    k = b.vertex("k", b.vertices[b.points[group.block]] + coriolis)
    normal = -omega3**2 * arm
    n3 = b.vertex("n3", normal)
    point, t1, t2 = meet(k, along, n3, 1j * arm)
    b.vertex(low + "′", point, on_lever)
    b.vector(f"a^k_{on_lever}{block2}", b.points[group.block], "k", "coriolis", group.slider, coriolis)
    b.vector(f"a^r_{on_lever}{block2}", "k", low + "′", "sliding", group.slider, t1 * along)
    b.vector(f"a^n_{on_lever}{group.pivot}", b.pole, "n3", "normal", group.lever, normal)
    b.vector(f"a^t_{on_lever}{group.pivot}", "n3", low + "′", "tangential", group.lever, t2 * 1j * arm)
    b.absolute(on_lever, low + "′", group.lever)
    transport = (f"a^n_{on_lever}{group.pivot}", f"a^t_{on_lever}{group.pivot}")
    b.equations.append(((f"a_{group.block}", f"a^k_{on_lever}{block2}", f"a^r_{on_lever}{block2}"), transport))
    b.equations.append(((f"a_{on_lever}",), transport))
    b.rates[group.lever] = _rate(t2 * 1j * arm, arm)


def _add_images(b: _Builder, where, link_points: Mapping[str, tuple[str, str]],
                extra: Mapping[str, tuple[str, float, float]] | None, prime: str) -> None:
    """Images of the named extra points, and the list of vertices of each link's image."""
    for name, (link, _, _) in (extra or {}).items():
        first, second = link_points[link]
        la, lb = b.points[first], b.points[second]
        label = name.lower() + prime
        b.vertex(label, image(b.vertices[la], b.vertices[lb], where[first], where[second], where[name]), name)
        b.absolute(name, label, link)
    for link, (first, second) in link_points.items():
        names = [first, second] + [n for n, (lk, _, _) in (extra or {}).items() if lk == link]
        b.images[link] = tuple(names)


def _require_index(solution: Solution, index: int) -> None:
    if not -len(solution) <= index < len(solution):
        raise InvalidParameterError("index", index, f"a position of the solution, 0 … {len(solution) - 1}")


def _build(mechanism: Mechanism, solution: Solution, index: int, quantity: str, velocity: Plan | None,
           points: Mapping[str, tuple[str, float, float]] | None, scale: float | None) -> Plan:
    _require_index(solution, index)
    needed = 1 if quantity == "velocity" else 2
    if solution.order < needed:
        raise InvalidParameterError("solution", f"order={solution.order}", f"a solution of order ≥ {needed} "
                                    "(the crank's angular velocity and acceleration are read from it)")
    crank = solution.angle("crank")
    omega1, alpha1 = float(crank.omega[index]), float(crank.alpha[index]) if needed == 2 else 0.0
    phi = float(crank.value[index])
    b = _Builder(quantity)
    prime = "" if quantity == "velocity" else "′"
    cls = VelocityPlan if quantity == "velocity" else AccelerationPlan

    groups = mechanism.groups()
    if not groups or not isinstance(groups[0], Crank):
        raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                    "a mechanism that describes its structure, crank first (Mechanism.groups()): a "
                                    "CrankSlider, FourBar, SlottedLever or Shaper (the plans of chapter 10)")
    numbers = link_numbers(groups)
    _check_extra(points, tuple(link for group in groups for link in group.links if link != "slider"))
    where = _positions(mechanism, solution, index, points)
    links: dict[str, tuple[str, str]] = {}
    for group in groups:
        if isinstance(group, Crank):
            _crank(b, where, group, omega1, alpha1)
            links[group.link] = (group.pivot, group.pin)
        elif isinstance(group, RRR):
            b.vertex(b.pole, 0j, group.second)
            _two_hinges(b, where, group.first, b.points[group.first], group.second, b.pole, group.joint,
                        group.joint.lower() + prime, group.first_link, group.second_link, velocity)
            links[group.first_link] = (group.first, group.joint)
            links[group.second_link] = (group.second, group.joint)
        elif isinstance(group, RRP):
            _hinge_on_guide(b, where, group.known, b.points[group.known], group.joint, group.joint.lower() + prime,
                            group.link, group.slider, group.guide_direction, velocity, numbers[group.link])
            links[group.link] = (group.known, group.joint)
        elif isinstance(group, RPR):
            on_lever = group.block + "3"     # the lever's point under the block (A3 under A2)
            where[on_lever] = where[group.block]
            _block_on_lever(b, where, group, on_lever, velocity)
            links[group.lever] = (group.pivot, on_lever)
        elif isinstance(group, LinkPoint):
            first, second = links[group.link]
            label = group.name.lower() + prime
            b.vertex(label, image(b.vertices[b.points[first]], b.vertices[b.points[second]], where[first],
                                  where[second], where[group.name]), group.name)
            b.absolute(group.name, label, group.link)
        else:
            raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                        f"groups the plans can draw (crank, RRR, RRP, RPR): not {group!r}")
    _add_images(b, where, links, points, prime)
    for group in groups:   # a link's image holds the joints fixed to it (the lever's end B)
        if isinstance(group, LinkPoint) and group.link in b.images:
            image_points = b.images[group.link]
            b.images[group.link] = image_points[:2] + (group.name,) + image_points[2:]
    return b.finish(cls, phi, scale, where)


def velocity_plan(mechanism: Mechanism, solution: Solution, index: int = 0,
                  points: Mapping[str, tuple[str, float, float]] | None = None,
                  scale: float | None = None) -> VelocityPlan:
    """The velocity plan of a mechanism at one crank position, constructed as on paper.

    Parameters
    ----------
    mechanism : Mechanism
        One that describes its structure (``groups()``): a crank, then RRR, RRP and RPR groups and
        points fixed to links (the crank-slider, the four-bar, the slotted lever, the shaper).
        The mechanism (chapters 3, 4, 5).
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
        under the block of a slotted lever); ``rates`` holds the links' angular velocities read off
        the plan.

    Notes
    -----
    Crank-slider: ``v_B = v_A + v_BA``, ``v_BA ⊥ AB``, ``v_B ∥ guide``. Four-bar:
    ``v_B = v_A + v_BA = v_C + v_BC`` with ``v_BA ⊥ AB``, ``v_BC ⊥ CB``. Slotted lever:
    ``v_A3 = v_A2 + v_A3A2`` with ``v_A3 ⊥ CA`` and ``v_A3A2 ∥ CA``; shaper: then
    ``v_D = v_B + v_DB``. ω of a link = (relative velocity)/(length), its sense from the direction.
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
        component; ``rates`` holds the angular accelerations read off the plan.

    Notes
    -----
    Crank-slider: ``a_B = a_A + a^n_BA + a^t_BA`` with ``a^n_BA = ω₂² l_AB`` directed from B to A,
    ``a^t_BA ⊥ AB`` and ``a_B ∥ guide``. Four-bar: also ``a_B = a^n_BC + a^t_BC``. Slotted lever:
    ``a_A3 = a_A2 + a^k_A3A2 + a^r_A3A2 = a^n_A3C + a^t_A3C``, ``a^k = 2ω₃ v_A3A2`` turned by 90°
    in the sense of ω₃, ``a^r ∥ CA``. ε of a link = a^t/(length), its sense from the direction.
    """
    _require_index(solution, index)
    if velocity is None:
        velocity = velocity_plan(mechanism, solution, index, points)
    elif not math.isclose(velocity.phi, float(solution.phi[index]), abs_tol=1e-12):
        raise InvalidParameterError("velocity", f"a plan at φ = {math.degrees(velocity.phi):g}°",
                                    f"the velocity plan of the same position, φ = "
                                    f"{math.degrees(float(solution.phi[index])):g}°")
    return cast(AccelerationPlan, _build(mechanism, solution, index, "acceleration", velocity, points, scale))


# --- instant centres ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class InstantCentres:
    """The instant centres P_ij of a mechanism at one crank position.

    Attributes
    ----------
    links : dict
        Link name → its number (frame 0, crank 1, coupler 2, rocker or slider 3).
    finite : dict
        ``(i, j)`` (i < j) → the centre ``x + iy`` (m).
    infinite : dict
        ``(i, j)`` → the direction (a unit complex number) in which a centre at infinity lies: the
        relative motion of the two links is a translation perpendicular to it.
    positions : dict
        The joints of the drawing (m).
    """

    links: dict[str, int]
    finite: dict[tuple[int, int], complex]
    infinite: dict[tuple[int, int], complex]
    positions: dict[str, complex]

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


def instant_centres(mechanism: Mechanism, solution: Solution, index: int = 0) -> InstantCentres:
    """All instant centres of a four-bar or a crank-slider at one crank position (Kennedy's theorem).

    Parameters
    ----------
    mechanism : Mechanism
        A crank and one RRR or RRP group (``groups()``): a four-bar or a crank-slider.
    solution : Solution
        Positions are enough (order 0).
    index : int
        Which crank position.

    Returns
    -------
    InstantCentres
        Six centres for the four links. The hinges give four directly (P01 = O, P12 = A, P23 = B
        and P03 = C of a four-bar; a slider's P03 lies at infinity, perpendicular to its guide).
        Kennedy's theorem (the three centres of any three links lie on one line) gives the other
        two as intersections: P02 on the lines P01P12 and P03P23, P13 on P01P03 and P12P23.

    Notes
    -----
    A centre whose two lines are parallel lies at infinity (e.g. P02 of a four-bar whose crank and
    rocker are parallel: the coupler translates for an instant, ω₂ = 0).
    """
    where = {name: complex(solution.point(name).value[index]) for name in solution.point_names}
    groups = mechanism.groups()
    structure = four_link(groups)
    if structure is None:
        raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                    "a FourBar or a CrankSlider: a four-link mechanism, a crank and one RRR or RRP "
                                    "group")
    crank, dyad = structure
    links = link_numbers(groups)
    finite: dict[tuple[int, int], complex] = {(0, 1): where[crank.pivot], (1, 2): where[crank.pin],
                                              (2, 3): where[dyad.joint]}
    infinite: dict[tuple[int, int], complex] = {}
    if isinstance(dyad, RRR):
        finite[(0, 3)] = where[dyad.second]
    else:  # the slider's centre lies at infinity, perpendicular to its guide
        infinite[(0, 3)] = 1j * dyad.guide_direction

    def line(pair_a, pair_b):
        """The line through two centres (one of them may be at infinity): (point, direction)."""
        if pair_a in infinite:
            pair_a, pair_b = pair_b, pair_a
        if pair_b in infinite:
            return finite[pair_a], infinite[pair_b]
        return finite[pair_a], finite[pair_b] - finite[pair_a]

    for target, (first, second) in {(0, 2): (((0, 1), (1, 2)), ((0, 3), (2, 3))),
                                     (1, 3): (((0, 1), (0, 3)), ((1, 2), (2, 3)))}.items():
        p1, d1 = line(*first)
        p2, d2 = line(*second)
        point = _line_meet(p1, d1, p2, d2)
        if point is None:
            infinite[target] = d1 / abs(d1)
        else:
            finite[target] = point
    return InstantCentres(links, finite, infinite, where)


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
