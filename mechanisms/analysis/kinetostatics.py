"""Layer 4: joint forces by Assur groups (kinetostatics), chapter 7.

The classical method of the force analysis of a linkage of class II groups. To every moving body
the inertia force ``−m a_S`` (at its centre of mass S) and the inertia moment ``−J_S ε`` of
d'Alembert are added, with its weight ``−m g ĵ``, the applied loads and the springs; then every body
is in equilibrium. Each class II (two-link) Assur group is statically determinate — six equations
(three per link), six unknowns (two per hinge; for a sliding pair the normal force and its line of
action, written as its moment about the pair's joint) — so the groups are solved one at a time,
from the **last** group back to the crank: the reactions a group's links receive from the groups
solved after it are known by then (Newton's third law). Last of all the crank gives the reaction of
its pivot and the driving torque M_d. Every step is a closed form, vectorized over the crank
positions (a loop over the groups, none over the positions):

* RRR (joint J from P and Q): ``(P−J)×R_P = −M₁``, ``(Q−J)×R_Q = −M₂``, ``R_P + R_Q = −(F₁ + F₂)``
  (moments about J of the known loads of each link), then ``R_J = R_P + F₁``;
* RRP: the normal force of the guide from the rod's moment about J and the group's force balance;
* RPR: the normal force from the lever's moment about its pivot;
* PRP, RPP: the two normal forces from a force balance along two directions.

The structure is read from :meth:`~mechanisms.linkages.base.Mechanism.groups`, so a named
mechanism (crank-slider, four-bar, slotted lever) and any :class:`~mechanisms.linkages.composed.Linkage`
(a linkage file) go through this same code. A class III group (a triad) is refused, naming it.

Conventions (the result, :class:`JointForces`):

* The bodies are numbered as the groups add them (:func:`~mechanisms.linkages.groups.link_numbers`):
  the frame 0, the crank 1, then each group's links in order. The force at a pair is the force
  exerted **by the body of the lower number on the other one** (nearer the frame in the solving
  order): ``O`` frame on crank, ``A`` crank on coupler, ``B`` coupler on rocker or slider.
* A hinge that joins exactly two bodies is named by its joint (``"B"``). Where one joint joins three
  or more bodies, the pin is taken to belong to the body that first carried the joint, and each
  hinge to it is named ``"JOINT:GIVER/TAKER"`` (``"B:coupler/link BD"``).
* A sliding pair is named by its block's link name (the block that the pair lets slide: the RRP's
  slider, the RPR's block, each block of a PRP, the RPP's block in the yoke's slot and the yoke on
  its guide). Its reaction (:class:`SlidingForce`) is a force ``N n`` normal to the sliding
  direction t (n = i t, its left normal; N signed, N) whose line of action is given by its moment
  ``M`` about the pair's joint (N·m): the line crosses the sliding line at ``joint + (M/N) t``.
  No friction: no force along t.
* Forces are complex numbers ``Fx + i Fy`` (N); torques counter-clockwise positive (N·m). The
  driving torque is the torque of the frame (the motor) on the crank; the crank moves as the
  solution says (φ_t, and φ_tt if given).

Its value is independent of the power balance of :mod:`mechanisms.analysis.energy`, and the two
must agree: chapter 7 checks it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy as np

from ..core.errors import InvalidParameterError, MechanismError, StructureError, UnknownNameError, describe_angles
from ..core.motion import AngleMotion, PointMotion, point_on_link, translated_point
from ..core.validate import require_finite
from ..linkages.base import Mechanism, Solution
from ..linkages.groups import PRP, RPP, RPR, RRP, RRR, Crank, Group, Line, LinkPoint, Triad
from .energy import (STANDARD_GRAVITY, Force, LinkMass, Spring, Torque, _loads, _masses, _mechanism,
                     _solution, _springs, _file_loads, _file_masses, load_values)

if TYPE_CHECKING:
    from .plans import VelocityPlan

__all__ = ["JointForces", "SlidingForce", "joint_forces", "linkage_forces", "force_rows", "force_columns",
           "force_blocks", "FORCE_UNITS", "ZhukovskyLever", "zhukovsky_torque"]

FORCE_UNITS = {"M_d": "N·m", "Fx": "N", "Fy": "N", "N": "N", "M": "N·m"}
"""The unit of each column of :func:`force_rows`, :func:`force_columns` and :func:`force_blocks`."""

FRAME = "frame"


@dataclass(frozen=True)
class SlidingForce:
    """The reaction of a sliding pair (no friction): a force normal to the sliding direction.

    Attributes
    ----------
    joint : str
        The pair's joint (the block's joint), about which ``moment`` is taken.
    giver, taker : str
        The body that exerts the force (the lower number) and the one it acts on.
    normal : ndarray of complex
        The unit normal n = i t of the sliding direction t at each position.
    magnitude : ndarray
        N (N), signed: the force is ``N n``.
    moment : ndarray
        M (N·m): the moment of the pair's reaction about the joint; its line of action crosses the
        sliding line at ``joint + (M/N) t`` (at the joint when M = 0).
    """

    joint: str
    giver: str
    taker: str
    normal: np.ndarray
    magnitude: np.ndarray
    moment: np.ndarray

    @property
    def force(self) -> np.ndarray:
        """The force ``N n = Fx + i Fy`` (N) of the giver on the taker."""
        return self.magnitude * self.normal


@dataclass(frozen=True)
class JointForces:
    """Result of :func:`joint_forces`.

    Attributes
    ----------
    forces : dict of ndarray
        Hinge → force ``Fx + i Fy`` (N) of the body of the lower number on the other one, at each
        crank position (names: the module's docstring).
    driving_torque : ndarray
        The torque of the frame on the crank (N·m), counter-clockwise positive.
    sliding : dict of SlidingForce
        Sliding pair (by its block's name) → its normal force and line of action.
    bodies : dict of (str, str)
        Hinge → (giver, taker), the two bodies it joins.
    """

    forces: dict[str, np.ndarray]
    driving_torque: np.ndarray
    sliding: dict[str, SlidingForce] = field(default_factory=dict)
    bodies: dict[str, tuple[str, str]] = field(default_factory=dict)

    def force(self, joint: str) -> np.ndarray:
        """The force at a hinge (complex, N); ``"guide"``: the normal force of the only sliding pair of a
        mechanism that has one (the crank-slider's guide, as chapter 7 names it)."""
        if isinstance(joint, str) and joint not in self.forces and joint == "guide" and len(self.sliding) == 1:
            return next(iter(self.sliding.values())).force
        try:
            return self.forces[joint]
        except (KeyError, TypeError):     # TypeError: a name that cannot be a key (a list)
            raise UnknownNameError("joint", joint, self.forces) from None


def _cross(a: Any, b: Any) -> Any:
    """The z component of a × b for vectors as complex numbers (N·m for an arm and a force)."""
    return a.real * b.imag - a.imag * b.real


class _Wrench:
    """The known loads on one body: their resultant force and their moment about a reference point."""

    def __init__(self, reference: np.ndarray):
        self.reference = reference
        self.force = np.zeros(np.shape(reference), dtype=complex)
        self.moment = np.zeros(np.shape(reference))

    def add(self, force: Any, at: Any) -> None:
        self.force = self.force + force
        self.moment = self.moment + _cross(at - self.reference, force)

    def turn(self, moment: Any) -> None:
        self.moment = self.moment + moment

    def about(self, point: Any) -> np.ndarray:
        """The moment (N·m) about ``point``."""
        return self.moment + _cross(self.reference - point, self.force)


@dataclass
class _Body:
    name: str
    pole: str                       # the joint at its frame's origin
    angle: AngleMotion | None       # None: a block that only translates
    direction: Any                  # its x axis exp(iθ) (a translating block: its fixed direction)
    block_joint: str | None = None  # a block: its joint, which may name it too


class _Structure:
    """The bodies of a mechanism, which body carries each joint, and the directions of its lines, read off
    its groups and its solution."""

    def __init__(self, mechanism: Mechanism, solution: Solution):
        self.groups: tuple[Group, ...] = tuple(mechanism.groups())
        if not self.groups or not isinstance(self.groups[0], Crank):
            raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                        "a mechanism that describes its structure (groups(): a crank, then Assur "
                                        "groups of class II), such as a CrankSlider, a FourBar or a linkage file")
        for group in self.groups:
            if isinstance(group, Triad):
                from ..linkages.composed import describe_group
                raise StructureError(f"{_title(mechanism)}: forces by Assur groups are written for class II groups; "
                                     f"{describe_group(group)} is a class III group (a triad), which this method "
                                     "does not solve")
        self.solution = solution
        shape = np.shape(solution.phi)
        self.shape = shape
        self.bodies: dict[str, _Body] = {}
        self.carrier: dict[str, str] = {}
        self.joints: dict[str, list[str]] = {FRAME: []}
        self.renamed: dict[tuple[int, str], str] = {}
        for group in self.groups:
            self._add(group)

    def _carrier(self, joint: str) -> str:
        if joint not in self.carrier:          # a joint no group finds: the frame's
            self.carrier[joint] = FRAME
            self.joints[FRAME].append(joint)
        return self.carrier[joint]

    def _link(self, name: str, pole: str, joints: Sequence[str]) -> None:
        if name in self.bodies or name == FRAME:
            raise StructureError(f"link {name!r} is named twice: every body needs a name of its own for its forces")
        angle = self.solution.angle(name)
        self.bodies[name] = _Body(name, pole, angle, np.exp(1j * angle.value))
        self._own(name, joints)

    def _own(self, name: str, joints: Sequence[str]) -> None:
        self.joints[name] = list(joints)
        for joint in joints:
            self.carrier.setdefault(joint, name)

    def _block(self, group: Group, name: str, joint: str, angle: AngleMotion | None, fixed: float = 0.0) -> None:
        given = name
        if name in self.bodies and joint not in self.bodies:
            name = joint       # a named mechanism's second block called "slider" too: named by its joint
        self.renamed[(id(group), given)] = name
        if name in self.bodies or name == FRAME:
            raise StructureError(f"link {name!r} is named twice: every body needs a name of its own for its forces")
        if name in self.solution.angle_names:
            angle = self.solution.angle(name)
        direction = (np.exp(1j * angle.value) if angle is not None
                     else np.full(self.shape, complex(math.cos(fixed), math.sin(fixed))))
        self.bodies[name] = _Body(name, joint, angle, direction, joint)
        self._own(name, [joint])

    def name(self, group: Group, link: str) -> str:
        """The body's name of a group's link (a block may be named by its joint, see :meth:`_block`)."""
        return self.renamed.get((id(group), link), link)

    def line(self, line: Line) -> tuple[AngleMotion | None, Any]:
        """A guide's angle motion (``None`` if it does not turn) and its unit direction at each position."""
        if line.link == FRAME:
            return None, np.full(self.shape, complex(math.cos(line.angle), math.sin(line.angle)))
        body = self.bodies.get(line.link)
        if body is None:
            raise StructureError(f"a guide is on link {line.link!r}, which no group makes")
        turn = complex(math.cos(line.angle), math.sin(line.angle))
        if body.angle is None:
            return None, body.direction * turn
        shifted = AngleMotion(body.angle.value + line.angle, body.angle.velocity, body.angle.acceleration)
        return shifted, body.direction * turn

    def _add(self, group: Group) -> None:
        if isinstance(group, Crank):
            self._carrier(group.pivot)
            self._link(group.link, group.pivot, [group.pivot, group.pin])
        elif isinstance(group, RRR):
            self._carrier(group.first), self._carrier(group.second)
            self._link(group.first_link, group.first, [group.first, group.joint])
            self._link(group.second_link, group.second, [group.second, group.joint])
        elif isinstance(group, RRP):
            self._carrier(group.known)
            self._link(group.link, group.known, [group.known, group.joint])
            angle, _ = self.line(group.guide)
            self._block(group, group.slider, group.joint, angle, _fixed_angle(group.guide))
        elif isinstance(group, RPR):
            self._carrier(group.block), self._carrier(group.pivot)
            lever = self.solution.angle(group.lever)
            self._block(group, group.slider, group.block, lever)
            self._link(group.lever, group.pivot, [group.pivot] + ([group.joint] if group.joint else []))
        elif isinstance(group, PRP):
            for slider, guide in ((group.first_slider, group.first_guide), (group.second_slider, group.second_guide)):
                angle, _ = self.line(guide)
                self._block(group, slider, group.joint, angle, _fixed_angle(guide))
        elif isinstance(group, RPP):
            self._carrier(group.block)
            angle, _ = self.line(group.guide)
            slot = None if angle is None else AngleMotion(angle.value + group.slot_angle, angle.velocity,
                                                          angle.acceleration)
            self._block(group, group.slider, group.block, slot, _fixed_angle(group.guide) + group.slot_angle)
            self._block(group, group.yoke, group.joint, angle, _fixed_angle(group.guide))
        elif isinstance(group, LinkPoint):
            link = group.link
            if group.axis is not None:
                found = [name for name, joints in self.joints.items() if set(group.axis) <= set(joints)]
                found = [name for name in found if not link or name == link]
                if not found:
                    raise StructureError(f"point {group.name!r}: joints {group.axis} are not on one link")
                link = found[0]
            if link != FRAME and link not in self.bodies:
                raise StructureError(f"point {group.name!r} is on link {link!r}, which no group makes")
            self.joints[link].append(group.name)
            self.carrier.setdefault(group.name, link)

    # --- the bodies by name, their points ------------------------------------------------------------

    def body(self, name: object, what: str, role: str) -> _Body:
        """The body a name means: a link's name, or a block's joint."""
        if isinstance(name, str):
            if name in self.bodies:
                return self.bodies[name]
            blocks = [b for b in self.bodies.values() if b.block_joint == name]
            if len(blocks) == 1:
                return blocks[0]
        known = ", ".join([*self.bodies, *sorted({b.block_joint for b in self.bodies.values()
                                                  if b.block_joint and b.block_joint not in self.bodies})])
        raise InvalidParameterError(what, name, f"one of the bodies {known} ({role}); a block is named by its "
                                                "link or its joint")

    def point(self, body: _Body, along: float, left: float) -> PointMotion:
        """A point of a body at (along, left) in its frame; a translating block: offset in fixed axes."""
        pole = self.solution.point(body.pole)
        if body.angle is None:
            return translated_point(pole, complex(along, left))
        return point_on_link(pole, body.angle, along, left)


def _fixed_angle(line: Line) -> float:
    return line.angle if line.link == FRAME else 0.0


def _title(mechanism: Mechanism) -> str:
    return str(getattr(mechanism, "name", type(mechanism).__name__))


@dataclass
class _Hinge:
    joint: str
    giver: str
    taker: str
    force: Any


@dataclass
class _Slide:
    name: str
    joint: str
    giver: str
    taker: str
    normal: Any
    magnitude: Any
    moment: Any


class _Solver:
    """The groups solved from the last back to the crank, with the known loads of every body."""

    def __init__(self, structure: _Structure):
        self.s = structure
        self.wrench = {name: _Wrench(structure.solution.point(body.pole).value)
                       for name, body in structure.bodies.items()}
        self.steps: list[list[_Hinge | _Slide]] = []

    def at(self, joint: str) -> np.ndarray:
        return self.s.solution.point(joint).value

    def react(self, item: _Hinge | _Slide) -> None:
        """Newton's third law: the giver receives the opposite of what it exerts (the frame is not needed)."""
        if item.giver == FRAME:
            return
        if isinstance(item, _Hinge):
            self.wrench[item.giver].add(-item.force, self.at(item.joint))
        else:
            self.wrench[item.giver].add(-item.magnitude * item.normal, self.at(item.joint))
            self.wrench[item.giver].turn(-item.moment)

    def solve(self) -> np.ndarray:
        for group in reversed(self.s.groups[1:]):
            items = self._group(group)
            for item in items:
                self.react(item)
            self.steps.append(items)
        crank = self.s.groups[0]
        assert isinstance(crank, Crank)
        load = self.wrench[crank.link]
        self.steps.append([_Hinge(crank.pivot, self.s.carrier[crank.pivot], crank.link, -load.force)])
        self.steps.reverse()
        return -load.about(self.at(crank.pivot))

    def _group(self, group: Group) -> list[_Hinge | _Slide]:
        carrier, w, at = self.s.carrier, self.wrench, self.at
        if isinstance(group, RRR):
            P, Q, J = at(group.first), at(group.second), at(group.joint)
            one, two = w[group.first_link], w[group.second_link]
            a, b, F = P - J, Q - J, one.force + two.force
            c1, c2 = -one.about(J), two.about(J) - _cross(b, F)
            R_P = (c1 * b - c2 * a) / _cross(a, b)
            return [_Hinge(group.first, carrier[group.first], group.first_link, R_P),
                    _Hinge(group.joint, group.first_link, group.second_link, R_P + one.force),
                    _Hinge(group.second, carrier[group.second], group.second_link, -F - R_P)]
        if isinstance(group, RRP):
            K, J = at(group.known), at(group.joint)
            slider = self.s.name(group, group.slider)
            rod, block = w[group.link], w[slider]
            _, t = self.s.line(group.guide)
            n, a, F = 1j * t, K - J, rod.force + block.force
            N = (rod.about(J) - _cross(a, F)) / _cross(a, n)
            R_K = -F - N * n
            return [_Hinge(group.known, carrier[group.known], group.link, R_K),
                    _Hinge(group.joint, group.link, slider, R_K + rod.force),
                    _Slide(slider, group.joint, group.guide.link, slider, n, N, -block.about(J))]
        if isinstance(group, RPR):
            A, C = at(group.block), at(group.pivot)
            slider = self.s.name(group, group.slider)
            block, lever = w[slider], w[group.lever]
            n = 1j * self.s.bodies[group.lever].direction
            M = block.about(A)
            N = -(M + lever.about(C)) / _cross(A - C, n)
            return [_Hinge(group.block, carrier[group.block], slider, N * n - block.force),
                    _Slide(slider, group.block, slider, group.lever, n, N, M),
                    _Hinge(group.pivot, carrier[group.pivot], group.lever, -N * n - lever.force)]
        if isinstance(group, PRP):
            K = at(group.joint)
            first, second = self.s.name(group, group.first_slider), self.s.name(group, group.second_slider)
            one, two = w[first], w[second]
            n1, n2 = 1j * self.s.line(group.first_guide)[1], 1j * self.s.line(group.second_guide)[1]
            F, across = one.force + two.force, _cross(n1, n2)
            N1, N2 = -_cross(F, n2) / across, _cross(F, n1) / across
            return [_Slide(first, group.joint, group.first_guide.link, first, n1, N1, -one.about(K)),
                    _Hinge(group.joint, first, second, N1 * n1 + one.force),
                    _Slide(second, group.joint, group.second_guide.link, second, n2, N2, -two.about(K))]
        if isinstance(group, RPP):
            A, J = at(group.block), at(group.joint)
            slider, yoker = self.s.name(group, group.slider), self.s.name(group, group.yoke)
            block, yoke = w[slider], w[yoker]
            t = self.s.line(group.guide)[1]
            n_g, n_s = 1j * t, 1j * t * complex(math.cos(group.slot_angle), math.sin(group.slot_angle))
            across = _cross(n_s, n_g)
            N_s, N_g = -_cross(yoke.force, n_g) / across, _cross(yoke.force, n_s) / across
            M_s = block.about(A)
            M_g = -(M_s + _cross(A - J, N_s * n_s) + yoke.about(J))
            return [_Hinge(group.block, carrier[group.block], slider, N_s * n_s - block.force),
                    _Slide(slider, group.block, slider, yoker, n_s, N_s, M_s),
                    _Slide(yoker, group.joint, group.guide.link, yoker, n_g, N_g, M_g)]
        return []     # a point of a link: no pair of its own


def _applied(structure: _Structure, solver: _Solver, masses: Mapping[str, LinkMass],
             loads: Sequence[Force | Torque], gravity: float, springs: Sequence[Spring]) -> None:
    """Inertia forces and moments (d'Alembert), weights, springs and loads, on every body."""
    solution = structure.solution
    seen: dict[str, str] = {}
    for name, props in masses.items():
        body = structure.body(name, "masses", "a body with a mass")
        if body.name in seen:
            raise InvalidParameterError("masses", name, f"a body given once (it is {body.name!r}, which "
                                                        f"{seen[body.name]!r} names too)")
        seen[body.name] = name
        centre = structure.point(body, props.along, props.left)
        solver.wrench[body.name].add(-props.mass * centre.acceleration - 1j * props.mass * gravity, centre.value)
        if body.angle is not None and props.inertia:
            solver.wrench[body.name].turn(-props.inertia * body.angle.alpha)
    for spring in springs:
        body = structure.body(spring.body, "body", "a spring's body")
        end = structure.point(body, spring.along, spring.left).value
        arm = end - spring.anchor
        length = np.abs(arm)
        with np.errstate(invalid="ignore", divide="ignore"):
            unit = np.where(length > 0.0, arm / np.where(length > 0.0, length, 1.0), 0.0)
        solver.wrench[body.name].add(-spring.stiffness * (length - spring.free_length) * unit, end)
    for load in loads:
        body = structure.body(load.body, "body", "a load's body")
        value = load_values(load, solution)
        if isinstance(load, Force):
            solver.wrench[body.name].add(value, structure.point(body, load.along, load.left).value)
        else:
            solver.wrench[body.name].turn(value)


def joint_forces(mechanism: Mechanism, solution: Solution, masses: Mapping[str, LinkMass],
                 loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                 springs: Sequence[Spring] = ()) -> JointForces:
    """Joint forces and the driving torque of a linkage of class II groups, group by group (kinetostatics).

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism that describes its structure (``groups()``): a crank-slider, a four-bar, a slotted
        lever, any :class:`~mechanisms.linkages.composed.Linkage` of RRR, RRP, RPR, PRP and RPP groups
        with points on links and guides on moving links.
    solution : Solution
        Its kinematics of order 2 for the crank motion (φ, φ_t, φ_tt).
    masses : mapping
        ``{body: LinkMass}``; a body is a link (``crank``, ``coupler``, ``rocker``, a linkage's link) or
        a block, by its link's name (``slider``, ``ram``) or its joint (``B``). A body that is not
        given is massless. A block that only translates takes ``along``/``left`` in fixed axes.
    loads : sequence of Force or Torque
        Applied loads on those bodies.
    gravity : float
        g (m/s²), along −y.
    springs : sequence of Spring
        Springs from the bodies to the frame.

    Returns
    -------
    JointForces
        The hinges' forces, the sliding pairs' normal forces and the driving torque M_d (conventions:
        the module's docstring).

    Raises
    ------
    InvalidParameterError
        A bad argument, or a body that the mechanism does not have (the known bodies named).
    StructureError
        A class III group (named), or a mechanism that does not describe its groups.
    MechanismError
        A solution of order < 2, or forces undetermined at a position the kinematics did not flag.

    Notes
    -----
    Each class II group is statically determinate: 6 equations, 6 unknowns. The groups are solved
    from the last back to the crank; the crank's moment about its pivot O gives ``M_d``. Where the
    solution is singular (``solution.singular``) the results are NaN.
    """
    mechanism, solution = _mechanism(mechanism), _solution(solution)
    masses, loads, springs = _masses(masses), _loads(loads), _springs(springs)
    gravity = require_finite("gravity", gravity)
    if solution.order < 2:
        raise MechanismError(f"joint forces need accelerations: solve with order=2 (got order={solution.order})")
    structure = _Structure(mechanism, solution)
    solver = _Solver(structure)
    _applied(structure, solver, masses, loads, gravity, springs)
    with np.errstate(divide="ignore", invalid="ignore"):
        torque = solver.solve()
    items = [item for step in solver.steps for item in step]
    singular = np.broadcast_to(np.asarray(solution.singular, dtype=bool), np.shape(solution.phi))
    values = [torque] + [i.force if isinstance(i, _Hinge) else i.magnitude for i in items] \
        + [i.moment for i in items if isinstance(i, _Slide)]
    bad = np.zeros(np.shape(solution.phi), dtype=bool)
    for value in values:
        bad = bad | ~np.isfinite(value)
    bad &= ~singular
    if bad.any():
        raise MechanismError("the equations of the groups have no unique solution (the joint forces are "
                             f"undetermined) at crank angle(s) {describe_angles(np.asarray(solution.phi)[bad])}")

    def masked(value: Any) -> np.ndarray:
        return np.where(singular, np.nan, value)

    hinges = [i for i in items if isinstance(i, _Hinge)]
    count: dict[str, int] = {}
    for hinge in hinges:
        count[hinge.joint] = count.get(hinge.joint, 0) + 1
    forces, bodies = {}, {}
    for hinge in hinges:
        key = hinge.joint if count[hinge.joint] == 1 else f"{hinge.joint}:{hinge.giver}/{hinge.taker}"
        forces[key] = masked(hinge.force)
        bodies[key] = (hinge.giver, hinge.taker)
    sliding = {i.name: SlidingForce(i.joint, i.giver, i.taker, np.asarray(i.normal), masked(i.magnitude),
                                    masked(i.moment)) for i in items if isinstance(i, _Slide)}
    return JointForces(forces, masked(torque), sliding, bodies)


# --- a linkage file's forces, for the command line ---------------------------------------------------------

def linkage_forces(linkage: Mechanism, solution: Solution) -> JointForces:
    """:func:`joint_forces` with the masses (``[[mass]]``), loads (``[[load]]``) and gravity (``gravity``, 0 if
    absent) that a linkage file declares. A linkage with none of them has all its forces zero."""
    linkage = _mechanism(linkage)
    return joint_forces(linkage, solution, _file_masses(linkage), _file_loads(linkage),
                        float(getattr(linkage, "gravity", 0.0)))


def _number(value: float) -> float | None:
    """A JSON-safe number: null at a singular position, and no negative zero."""
    value = float(value) + 0.0
    return value if math.isfinite(value) else None


def force_rows(result: JointForces) -> list[dict]:
    """One dict per crank position for the command line's JSON (``"forces"`` of each row)::

        {"driving_torque": M_d, "joints": {NAME: {"Fx": …, "Fy": …}},
         "sliding": {BLOCK: {"N": …, "Fx": …, "Fy": …, "M": …}}}

    in N and N·m (conventions: the module's docstring); a singular position gives ``None`` (null).
    """
    torque = np.reshape(result.driving_torque, -1)
    joints = {name: np.reshape(force, -1) for name, force in result.forces.items()}
    slides = {name: (np.reshape(s.magnitude, -1), np.reshape(s.force, -1), np.reshape(s.moment, -1))
              for name, s in result.sliding.items()}
    rows = []
    for i in range(torque.size):
        rows.append({"driving_torque": _number(torque[i]),
                     "joints": {name: {"Fx": _number(f[i].real), "Fy": _number(f[i].imag)}
                                for name, f in joints.items()},
                     "sliding": {name: {"N": _number(N[i]), "Fx": _number(F[i].real), "Fy": _number(F[i].imag),
                                        "M": _number(M[i])} for name, (N, F, M) in slides.items()}})
    return rows


def force_columns(row: Mapping[str, Any]) -> dict[str, float | None]:
    """A row of :func:`force_rows` as flat columns for CSV and text: ``forces.driving_torque``,
    ``forces.joints.B.Fx``, ``forces.sliding.ram.N`` …"""
    flat: dict[str, float | None] = {"forces.driving_torque": row["driving_torque"]}
    for group in ("joints", "sliding"):
        for name, values in row[group].items():
            for key, value in values.items():
                flat[f"forces.{group}.{name}.{key}"] = value
    return flat


def force_blocks(row: Mapping[str, Any]) -> dict[str, dict[str, float | None]]:
    """A row of :func:`force_rows` as the text table's blocks: ``"driving torque"`` (``M_d``), ``"joint B"``
    (``Fx``, ``Fy``), ``"sliding pair ram"`` (``N``, ``Fx``, ``Fy``, ``M``)."""
    blocks: dict[str, dict[str, float | None]] = {"driving torque": {"M_d": row["driving_torque"]}}
    blocks |= {f"joint {name}": dict(values) for name, values in row["joints"].items()}
    blocks |= {f"sliding pair {name}": dict(values) for name, values in row["sliding"].items()}
    return blocks


# --- Zhukovsky's lever: the balancing torque from the velocity plan turned by 90° ---------------------------

@dataclass(frozen=True)
class ZhukovskyLever:
    """Result of :func:`zhukovsky_torque`: the velocity plan turned by 90° as a lever in equilibrium.

    Attributes
    ----------
    torque : float
        The balancing torque M_d on the crank (N·m, counter-clockwise positive): the driving torque
        that holds the given forces and torques in equilibrium.
    images : dict of complex
        Point → its image on the turned plan, ``i v`` (m/s): the velocity turned by +90°.
    moments : dict of float
        Point → the moment about the pole of the force applied at its image, ``(i v) × F``
        (N·m/s = W); it equals ``−F · v``.
    couples : dict of float
        Link → the moment on the lever of the torque M_j on that link, ``−M_j ω_j`` (W).
    """

    torque: float
    images: dict[str, complex]
    moments: dict[str, float]
    couples: dict[str, float]


def _plan_force(name: object, value: object) -> complex:
    """A force of :func:`zhukovsky_torque` as a complex number (N), or the package's error naming it."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, complex, np.number)):
        raise InvalidParameterError(f"forces[{name!r}]", value, "a force Fx + i Fy in N, a finite complex number")
    force = complex(value)
    if not (math.isfinite(force.real) and math.isfinite(force.imag)):
        raise InvalidParameterError(f"forces[{name!r}]", value, "a force Fx + i Fy in N, a finite complex number")
    return force


def zhukovsky_torque(plan: VelocityPlan, forces: Mapping[str, complex],
                     torques: Mapping[str, float] | None = None, crank: str = "crank") -> ZhukovskyLever:
    """The balancing torque on the crank by Zhukovsky's lever (the velocity plan turned by 90°).

    Every force ``F_k`` acting at a point K is applied, unchanged in direction, at the image of K on
    the velocity plan turned by +90° about its pole p, that is at ``i v_K``; a torque ``M_j`` on link j
    adds the couple ``−M_j ω_j``. The turned plan, taken as a rigid lever pivoted at p, is in
    equilibrium under all of them and the balancing torque M_d on the crank (N. E. Zhukovsky, 1909):

    ``Σ_k (i v_K) × F_k − Σ_j M_j ω_j − M_d ω₁ = 0``.

    Since ``(i v) × F = −F · v``, the lever is the power balance read on the plan: with the inertia
    forces and moments of d'Alembert among the loads, M_d is the driving torque of chapter 7.

    Parameters
    ----------
    plan : VelocityPlan
        A velocity plan of :func:`mechanisms.analysis.plans.velocity_plan`; the points the forces act
        at must be on it (pass the centres of mass as its ``points``).
    forces : mapping
        Point of the plan → the resultant force at it, ``Fx + i Fy`` (N): loads, weights ``−i m g`` and
        inertia forces ``−m a_S`` (add forces that act at one point).
    torques : mapping, optional
        Link → the torque on it (N·m, counter-clockwise positive), inertia moments ``−J_S ε`` among
        them; a block that only translates has ω = 0 and takes none.
    crank : str
        The name of the crank's link on the plan (its ``rates``), ``"crank"`` by default.

    Returns
    -------
    ZhukovskyLever
        ``torque`` (M_d, N·m), the turned images and each force's and torque's moment on the lever.

    Raises
    ------
    InvalidParameterError
        A plan that is not a velocity plan, a force or torque that is not a finite number, a crank at
        rest (ω₁ = 0: the lever does not give the torque).
    UnknownNameError
        A point that is not on the plan or a link it does not know (the known names listed).

    Examples
    --------
    A crank of 1 m at φ = 90° turning at ω₁ = 1 1/s, pushed at its pin by F = −10 N along x:
    ``v_A = −1`` m/s, the lever's moment of F is ``−F · v_A = −10`` W, so M_d = −10 N·m (the
    frame holds the crank against F's 10 N·m).
    """
    if getattr(plan, "quantity", None) != "velocity" or not hasattr(plan, "points"):
        raise InvalidParameterError("plan", type(plan).__name__, "a velocity plan (plans.velocity_plan)")
    if not isinstance(forces, Mapping):
        raise InvalidParameterError("forces", forces, "a mapping {point: force Fx + i Fy in N}")
    if torques is not None and not isinstance(torques, Mapping):
        raise InvalidParameterError("torques", torques, "a mapping {link: torque in N·m}")
    if crank not in plan.rates:
        raise UnknownNameError("link", crank, plan.rates)
    omega1 = float(plan.rates[crank])
    if omega1 == 0.0:
        raise InvalidParameterError("plan", "a crank at rest (ω₁ = 0)", "a velocity plan of a turning crank: "
                                    "the lever balances powers, which vanish with ω₁")
    images: dict[str, complex] = {}
    moments: dict[str, float] = {}
    for point, value in forces.items():
        if point not in plan.points:
            raise UnknownNameError("point on the velocity plan", point, plan.points)
        force = _plan_force(point, value)
        images[point] = 1j * complex(plan.of(point))
        moments[point] = float(_cross(images[point], force))
    couples: dict[str, float] = {}
    for link, value in (torques or {}).items():
        if link not in plan.rates:
            raise UnknownNameError("link on the velocity plan", link, plan.rates)
        couples[link] = -require_finite(f"torques[{link!r}]", value) * float(plan.rates[link])
    torque = (math.fsum(moments.values()) + math.fsum(couples.values())) / omega1
    return ZhukovskyLever(torque, images, moments, couples)
