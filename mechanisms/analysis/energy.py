"""Layer 4: energy and power of a mechanism (chapter 7).

After the kinematic analysis the lecture turns to the centres of mass of the links, their
kinetic and potential energy, Newton's inertia forces and the rate of change (power) of both
energies. This module does that for any mechanism of the package, from its solution:

* the mass properties of a body: :class:`LinkMass` (mass, centre of mass fixed to the body,
  moment of inertia about it), given per body name — a link (``"crank"``, ``"coupler"`` …) or
  a joint that carries a sliding block (``"B"``), which translates with that joint;
* the motion of each centre of mass, the kinetic energy T and potential energy V (gravity and
  optional springs to the frame) with their exact time derivatives (power);
* the inertia forces and moments of d'Alembert, ``F_in = −m a_S`` and ``M_in = −J_S ε``;
* applied loads (:class:`Force`, :class:`Torque`) and their power;
* the reduced (equivalent) moment of inertia J_red(φ) with its exact derivative dJ_red/dφ, the
  reduced torque of the loads, and the driving torque from the power balance.

Every derivative is exact: it comes from the velocities and accelerations of the solution, never
from differences. Units: kg, m, s; energies in J, powers in W, torques in N·m.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike

from ..linkages.base import Mechanism, Solution
from ..core.errors import InvalidParameterError, MechanismError, UnknownNameError
from ..core.validate import require_finite, require_non_negative, require_rates
from ..core.motion import AngleMotion, Motion, PointMotion, polar, translated_point

__all__ = [
    "STANDARD_GRAVITY",
    "LinkMass",
    "linkage_masses",
    "linkage_loads",
    "Force",
    "Torque",
    "Spring",
    "InertiaLoad",
    "body_point",
    "body_angle",
    "centre_of_mass",
    "kinetic_energies",
    "kinetic_energy",
    "potential_energy",
    "inertia_forces",
    "load_values",
    "applied_power",
    "reduced_inertia",
    "reduced_torque",
    "potential_torque",
    "driving_torque",
    "energy_balance",
]

STANDARD_GRAVITY = 9.80665
"""Standard acceleration of gravity g (m/s²); gravity acts along −y."""

Value = Union[float, complex, np.ndarray, Callable[[Solution], np.ndarray]]


@dataclass(frozen=True)
class LinkMass:
    """Mass properties of one body of a mechanism.

    Parameters
    ----------
    mass : float
        m (kg), ≥ 0.
    along, left : float
        The centre of mass S in the body's frame (m): ``along`` the link from its first joint,
        ``left`` of it (as in :meth:`~mechanisms.base.Solution.point_on`). For a sliding block
        (a body named by its joint) the offset from the joint; usually 0.
    inertia : float
        J_S (kg·m²), ≥ 0: moment of inertia about the axis through S normal to the plane.
        A translating block does not turn, so its J_S plays no part.

    Notes
    -----
    The moment of inertia about the first joint follows from Steiner's (parallel-axis) theorem,
    ``J_P = J_S + m (along² + left²)`` (chapter 7; J_O for the crank).
    """

    mass: float
    along: float = 0.0
    left: float = 0.0
    inertia: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "mass", require_non_negative("mass", self.mass, "kg"))
        object.__setattr__(self, "inertia", require_non_negative("inertia", self.inertia, "kg·m²"))
        object.__setattr__(self, "along", require_finite("along", self.along))
        object.__setattr__(self, "left", require_finite("left", self.left))

    def inertia_about_joint(self) -> float:
        """J about the body's first joint (kg·m²), by the parallel-axis theorem."""
        return self.inertia + self.mass * (self.along**2 + self.left**2)


@dataclass(frozen=True)
class Force:
    """An applied force on a body, at a point fixed to it.

    Parameters
    ----------
    body : str
        A link name (``"coupler"``) or a joint with a sliding block (``"B"``).
    force : complex, array or callable
        ``Fx + i Fy`` (N): a constant, an array over the crank positions, or a function of the
        solution returning that array (e.g. a force that acts during one stroke only).
    along, left : float
        The point of application in the body's frame (m), as for :class:`LinkMass`.
    """

    body: str
    force: Value
    along: float = 0.0
    left: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "body", _body_name(self.body))
        if not callable(self.force):
            _load_array(self.force, complex, f"the force on {self.body!r}")
        object.__setattr__(self, "along", require_finite("along", self.along))
        object.__setattr__(self, "left", require_finite("left", self.left))


@dataclass(frozen=True)
class Torque:
    """An applied torque (N·m, counter-clockwise positive) on a link.

    ``torque`` is a constant, an array over the crank positions or a function of the solution.
    A torque on a translating block does no work (the guide takes it up).
    """

    body: str
    torque: Value

    def __post_init__(self):
        object.__setattr__(self, "body", _body_name(self.body))
        if not callable(self.torque):
            _load_array(self.torque, float, f"the torque on {self.body!r}")


@dataclass(frozen=True)
class Spring:
    """A linear spring from a point of a body to a fixed point of the frame.

    Parameters
    ----------
    body : str
        The body (link or block) it is attached to.
    anchor : complex
        The fixed end ``x + iy`` (m).
    stiffness : float
        k_s (N/m), ≥ 0.
    free_length : float
        ℓ_s0 (m), ≥ 0: the length at which it carries no force.
    along, left : float
        The attachment point in the body's frame (m).

    Notes
    -----
    ``V = k_s (ℓ_s − ℓ_s0)²/2`` with ℓ_s the current length; the force on the body is
    ``−k_s (ℓ_s − ℓ_s0) û``, û the unit vector from the anchor to the attachment point.
    """

    body: str
    anchor: complex
    stiffness: float
    free_length: float = 0.0
    along: float = 0.0
    left: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "body", _body_name(self.body))
        object.__setattr__(self, "stiffness", require_non_negative("stiffness", self.stiffness, "N/m"))
        object.__setattr__(self, "free_length", require_non_negative("free_length", self.free_length, "m"))
        anchor = self.anchor
        # a number x + iy (a string such as "1+2j" would be parsed by complex(): refused)
        try:
            if isinstance(anchor, (bool, np.bool_)) or not isinstance(anchor, (numbers.Number, np.number)):
                raise TypeError
            point = complex(anchor)
        except (TypeError, OverflowError):
            point = complex(np.nan)
        if not np.isfinite(point):
            raise InvalidParameterError("anchor", anchor, "a finite point x + iy (m), a complex number")
        object.__setattr__(self, "anchor", point)
        object.__setattr__(self, "along", require_finite("along", self.along))
        object.__setattr__(self, "left", require_finite("left", self.left))

    def length(self, solution: Solution) -> Motion:
        """The current length ℓ (m) with its time derivatives."""
        end = body_point(solution, self.body, self.along, self.left)
        length, _ = polar(end - self.anchor)
        return length

    def force(self, solution: Solution) -> np.ndarray:
        """The spring's force on the body ``Fx + i Fy`` (N) at each position."""
        end = body_point(solution, self.body, self.along, self.left).value
        arm = end - self.anchor
        length = np.abs(arm)
        with np.errstate(invalid="ignore", divide="ignore"):
            unit = np.where(length > 0.0, arm / length, 0.0)
        return -self.stiffness * (length - self.free_length) * unit


@dataclass(frozen=True)
class InertiaLoad:
    """Newton's inertia force and moment of a body (d'Alembert), at its centre of mass.

    Attributes
    ----------
    point : ndarray of complex
        The centre of mass S (m).
    force : ndarray of complex
        ``F_in = −m a_S`` (N).
    moment : ndarray
        ``M_in = −J_S ε`` (N·m), zero for a translating block.
    """

    point: np.ndarray
    force: np.ndarray
    moment: np.ndarray


# --- checks of the inputs (shared with dynamics and kinetostatics) ----------------------------------

def _body_name(body: object) -> str:
    if not isinstance(body, str) or not body:
        raise InvalidParameterError("body", body, "the name of a link or of a joint with a sliding block (a string)")
    return body


def _load_array(value: object, dtype: type, what: str) -> np.ndarray:
    """A load's value (a number or an array over the crank positions) as an array of ``dtype`` (complex for a
    force ``Fx + i Fy``, float for a torque), finite; or :class:`InvalidParameterError` naming the load."""
    kinds = "iufc" if dtype is complex else "iuf"
    requirement = "finite numbers Fx + i Fy (N)" if dtype is complex else "finite numbers (N·m)"
    if value is None or isinstance(value, (str, bytes, bool, np.bool_)):
        raise InvalidParameterError(what, value, requirement)
    try:
        array = np.asarray(value)
        if array.dtype.kind not in kinds:
            raise TypeError
        array = array.astype(dtype)
    except (TypeError, ValueError, OverflowError):
        raise InvalidParameterError(what, value, requirement) from None
    if not np.all(np.isfinite(array)):
        raise InvalidParameterError(what, value, requirement)
    return array


def _masses(masses: object) -> Mapping[str, LinkMass]:
    """``masses`` checked: a mapping ``{body name: LinkMass}``."""
    if not isinstance(masses, Mapping):
        raise InvalidParameterError("masses", masses, "a mapping {body name: LinkMass(...)}")
    for body, props in masses.items():
        if not isinstance(body, str) or not isinstance(props, LinkMass):
            raise InvalidParameterError(f"masses[{body!r}]", props, "a LinkMass(...) for a body named by a string")
    return masses


def _items(name: str, values: object, kinds: tuple[type, ...], each: str) -> tuple:
    if not isinstance(values, (list, tuple)):
        raise InvalidParameterError(name, values, f"a list (or tuple), each item {each}")
    for index, value in enumerate(values):
        if not isinstance(value, kinds):
            raise InvalidParameterError(f"{name}[{index}]", value, each)
    return tuple(values)


def _loads(loads: object) -> tuple[Force | Torque, ...]:
    """``loads`` checked: a list or tuple of :class:`Force` and :class:`Torque`."""
    return _items("loads", loads, (Force, Torque), "a Force(...) or a Torque(...)")


def _springs(springs: object) -> tuple[Spring, ...]:
    """``springs`` checked: a list or tuple of :class:`Spring`."""
    return _items("springs", springs, (Spring,), "a Spring(...)")


def _solution(solution: object) -> Solution:
    if not isinstance(solution, Solution):
        raise InvalidParameterError("solution", solution, "a Solution, as mechanism.solve(...) returns")
    return solution


def _mechanism(mechanism: object) -> Mechanism:
    if not isinstance(mechanism, Mechanism):
        raise InvalidParameterError("mechanism", mechanism, "a mechanism of the package (a Mechanism)")
    return mechanism


# --- bodies ---------------------------------------------------------------------------------

def _is_link(solution: Solution, body: str) -> bool:
    body = _body_name(body)
    if body in solution.angle_names:
        return True
    if body in solution.point_names:
        return False
    # a body is a link or a joint with a sliding block
    raise UnknownNameError("body (a link or a joint with a sliding block)", body,
                           [*solution.angle_names, *solution.point_names])


def body_point(solution: Solution, body: str, along: float = 0.0, left: float = 0.0) -> PointMotion:
    """A point fixed to a body: a link (``point_on``) or a translating block at a joint.

    Parameters
    ----------
    solution : Solution
        The kinematics.
    body : str
        A link name or a joint name (a block that translates with the joint).
    along, left : float
        The point in the body's frame (m); for a block, the offset ``along + i left`` from the joint.
    """
    solution = _solution(solution)
    if _is_link(solution, body):
        return solution.point_on(body, along, left)
    return translated_point(solution.point(body), complex(require_finite("along", along), require_finite("left", left)))


def body_angle(solution: Solution, body: str) -> AngleMotion | None:
    """The angle of a link, or ``None`` for a translating block (it does not turn)."""
    return solution.angle(body) if _is_link(_solution(solution), body) else None


def centre_of_mass(solution: Solution, body: str, properties: LinkMass) -> PointMotion:
    """The motion of a body's centre of mass S (m, m/s, m/s²)."""
    if not isinstance(properties, LinkMass):
        raise InvalidParameterError("properties", properties, "a LinkMass(...)")
    return body_point(solution, body, properties.along, properties.left)


def _require(solution: Solution, order: int, what: str) -> None:
    if _solution(solution).order < order:
        need = ("velocities", "accelerations")[order - 1]
        raise MechanismError(f"{what} needs {need}: solve with order={order} (got order={solution.order})")


# --- kinetic energy ---------------------------------------------------------------------------

def kinetic_energies(solution: Solution, masses: Mapping[str, LinkMass]) -> dict[str, Motion]:
    """The kinetic energy of each body, with its time derivative where known.

    Parameters
    ----------
    solution : Solution
        Kinematics of order ≥ 1 (order 2 for the derivative).
    masses : mapping
        ``{body: LinkMass}``.

    Returns
    -------
    dict of Motion
        ``T_i = m v_S²/2 + J_S ω²/2`` (J) and ``dT_i/dt = m v_S·a_S + J_S ω ε`` (W).

    Notes
    -----
    König's theorem: the energy of the motion of the centre of mass plus that of the rotation
    about it (chapter 7). With points as complex numbers ``v·a = Re(conj(v) a)``.
    """
    _require(solution, 1, "the kinetic energy")
    masses = _masses(masses)
    result = {}
    for body, props in masses.items():
        centre = centre_of_mass(solution, body, props)
        angle = body_angle(solution, body)
        v = centre.velocity
        energy = 0.5 * props.mass * np.abs(v) ** 2
        power = props.mass * np.real(np.conj(v) * centre.acceleration) if solution.order >= 2 else None
        if angle is not None and props.inertia:
            energy = energy + 0.5 * props.inertia * angle.omega**2
            if power is not None:
                power = power + props.inertia * angle.omega * angle.alpha
        result[body] = Motion(energy, power)
    return result


def kinetic_energy(solution: Solution, masses: Mapping[str, LinkMass]) -> Motion:
    """The kinetic energy T of the mechanism (J) and, at order 2, its power dT/dt (W).

    The sum over the bodies of :func:`kinetic_energies`.
    """
    parts = list(kinetic_energies(solution, masses).values())
    shape = np.shape(solution.phi)
    energy = sum((p.value for p in parts), np.zeros(shape))
    if solution.order < 2:
        return Motion(energy)
    return Motion(energy, sum((p.velocity for p in parts), np.zeros(shape)))


# --- potential energy ---------------------------------------------------------------------------

def potential_energy(solution: Solution, masses: Mapping[str, LinkMass], gravity: float = STANDARD_GRAVITY,
                     springs: Sequence[Spring] = ()) -> Motion:
    """The potential energy V (J) of gravity and springs and, at order ≥ 1, its power dV/dt (W).

    Parameters
    ----------
    solution : Solution
        Kinematics (order 0 for V only).
    masses : mapping
        ``{body: LinkMass}``.
    gravity : float
        g (m/s²), acting along −y; 0 for a mechanism that works in a horizontal plane.
    springs : sequence of Spring
        Springs to the frame.

    Returns
    -------
    Motion
        ``V = Σ m g y_S + Σ k_s (ℓ_s − ℓ_s0)²/2`` (zero level y = 0) and
        ``dV/dt = Σ m g (y_S)_t + Σ k_s (ℓ_s − ℓ_s0) ℓ_s,t``.
    """
    solution, masses, springs = _solution(solution), _masses(masses), _springs(springs)
    gravity = require_finite("gravity", gravity)
    shape = np.shape(solution.phi)
    energy = np.zeros(shape)
    power = np.zeros(shape) if solution.order >= 1 else None
    for body, props in masses.items():
        centre = centre_of_mass(solution, body, props)
        energy = energy + props.mass * gravity * centre.y
        if power is not None:
            power = power + props.mass * gravity * centre.velocity.imag
    for spring in springs:
        length = spring.length(solution)
        stretch = length.value - spring.free_length
        energy = energy + 0.5 * spring.stiffness * stretch**2
        if power is not None:
            power = power + spring.stiffness * stretch * length.velocity
    return Motion(energy, power)


# --- inertia forces -----------------------------------------------------------------------------

def inertia_forces(solution: Solution, masses: Mapping[str, LinkMass]) -> dict[str, InertiaLoad]:
    """Newton's inertia force ``F_in = −m a_S`` and moment ``M_in = −J_S ε`` of each body (d'Alembert).

    Requires a solution of order 2. Added to the applied and joint forces of a body, they
    make a system in equilibrium (kinetostatics, :mod:`mechanisms.analysis.kinetostatics`).
    """
    _require(solution, 2, "the inertia forces")
    masses = _masses(masses)
    result = {}
    for body, props in masses.items():
        centre = centre_of_mass(solution, body, props)
        angle = body_angle(solution, body)
        moment = (-props.inertia * angle.alpha if angle is not None
                  else np.zeros(np.shape(solution.phi)))
        result[body] = InertiaLoad(centre.value, -props.mass * centre.acceleration, moment)
    return result


# --- loads and their power ----------------------------------------------------------------------

def load_values(load: Force | Torque, solution: Solution) -> np.ndarray:
    """The force (complex, N) or torque (N·m) of a load at each crank position.

    A constant, an array over the crank positions, or what the load's function returns for the solution: finite
    numbers, one or one per position; anything else is an :class:`InvalidParameterError` naming the load."""
    if not isinstance(load, (Force, Torque)):
        raise InvalidParameterError("load", load, "a Force(...) or a Torque(...)")
    solution = _solution(solution)
    value = load.force if isinstance(load, Force) else load.torque
    what = f"the {'force' if isinstance(load, Force) else 'torque'} on {load.body!r}"
    if callable(value):
        value = value(solution)
        what += " (as its function returns it)"
    array = _load_array(value, complex if isinstance(load, Force) else float, what)
    shape = np.shape(solution.phi)
    try:
        return np.broadcast_to(array, shape)
    except ValueError:
        raise InvalidParameterError(what, f"an array of shape {array.shape}",
                                    f"one value or one per crank position (shape {shape})") from None


def applied_power(solution: Solution, loads: Sequence[Force | Torque]) -> np.ndarray:
    """The power of applied loads (W): ``Σ F·v_P + Σ M ω``.

    Positive when a load drives the mechanism, negative when the mechanism works against it
    (a resistance). Gravity and springs are not loads here: they are in the potential energy.
    """
    _require(solution, 1, "the power of the loads")
    power = np.zeros(np.shape(solution.phi))
    for load in _loads(loads):
        if isinstance(load, Force):
            point = body_point(solution, load.body, load.along, load.left)
            power = power + np.real(np.conj(point.velocity) * load_values(load, solution))
        elif isinstance(load, Torque):
            angle = body_angle(solution, load.body)
            if angle is not None:
                power = power + load_values(load, solution) * angle.omega
    return power


def _file_masses(linkage: Any) -> dict[str, LinkMass]:
    """A linkage's ``[[mass]]`` tables as :class:`LinkMass`, by the body names the file gives."""
    return dict(_masses({body: LinkMass(**properties) for body, properties in getattr(linkage, "masses", {}).items()}))


def _block_joints(groups: Sequence[Any]) -> dict[str, str]:
    """Every block (a sliding pair's block or yoke) of a mechanism's groups, by its link name → its joint."""
    from ..linkages.groups import PRP, RPP, RPR, RRP
    blocks: dict[str, str] = {}
    for group in groups:
        if isinstance(group, RRP):
            blocks[group.slider] = group.joint
        elif isinstance(group, RPR):
            blocks[group.slider] = group.block
        elif isinstance(group, PRP):
            blocks[group.first_slider] = blocks[group.second_slider] = group.joint
        elif isinstance(group, RPP):
            blocks[group.slider], blocks[group.yoke] = group.block, group.joint
    return blocks


def _body_key(linkage: Any, body: str) -> str:
    """The name under which this module finds a linkage's body: a link that turns by its name, a block that only
    translates by its joint (the joint of a block that turns: that block's link)."""
    turning = getattr(linkage, "links", {})
    blocks = _block_joints(linkage.groups()) if isinstance(linkage, Mechanism) else {}
    if body in turning:
        return body
    if body in blocks:
        return blocks[body]
    carried = [link for link, joint in blocks.items() if joint == body and link in turning]
    return carried[0] if len(carried) == 1 else body


def linkage_masses(linkage: Any) -> dict[str, LinkMass]:
    """The mass properties a linkage file gives (``[[mass]]``), by body, for the functions of this module.

    A link that turns keeps its name; a block that only translates is named by its joint (its ``along`` and
    ``left`` are then the offset from the joint in fixed axes). Two blocks that translate with one joint (a
    PRP's) are one body here: their masses add, at their common centre of mass.

    Parameters
    ----------
    linkage : Linkage
        A composed linkage (:class:`~mechanisms.linkages.composed.Linkage`) with ``masses``.
    """
    merged: dict[str, LinkMass] = {}
    for body, props in _file_masses(linkage).items():
        key = _body_key(linkage, body)
        if key in merged:
            other = merged[key]
            total = other.mass + props.mass
            share = 0.5 if total == 0.0 else props.mass / total
            props = LinkMass(total, other.along + share * (props.along - other.along),
                             other.left + share * (props.left - other.left), other.inertia + props.inertia)
        merged[key] = props
    return merged


def _file_loads(linkage: Any, key: Callable[[str], str] = str) -> list[Force | Torque]:
    """A linkage's ``[[load]]`` tables as :class:`Force` and :class:`Torque`, each on the body ``key(name)``."""
    loads: list[Force | Torque] = []
    for load in getattr(linkage, "loads", ()):
        if "torque" in load:
            loads.append(Torque(key(load["body"]), float(load["torque"])))
        else:
            fx, fy = load["force"]
            loads.append(Force(key(load["body"]), complex(fx, fy), load.get("along", 0.0), load.get("left", 0.0)))
    return loads


def linkage_loads(linkage: Any) -> list[Force | Torque]:
    """The loads a linkage file gives (``[[load]]``), a :class:`Force` or a :class:`Torque` each, on bodies named
    as :func:`linkage_masses` names them, for :func:`applied_power` and the reduced torque."""
    return _file_loads(linkage, lambda body: _body_key(linkage, body))


def _crank_speed(solution: Solution) -> np.ndarray:
    return solution.angle("crank").omega


# --- reduction to the crank ---------------------------------------------------------------------

def reduced_inertia(mechanism: Mechanism, masses: Mapping[str, LinkMass],
                    phi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The reduced (equivalent) moment of inertia J_red(φ) at the crank and its derivative dJ_red/dφ.

    Parameters
    ----------
    mechanism : Mechanism
        Any one-degree-of-freedom mechanism of the package.
    masses : mapping
        ``{body: LinkMass}``.
    phi : array_like
        Crank angles φ (rad).

    Returns
    -------
    J : ndarray
        ``J_red = Σ m |dr_S/dφ|² + Σ J_S (dθ/dφ)²`` (kg·m²), so that ``T = J_red φ_t²/2``.
    dJ : ndarray
        ``dJ_red/dφ = Σ 2 m (dr_S/dφ)·(d²r_S/dφ²) + Σ 2 J_S (dθ/dφ)(d²θ/dφ²)`` (kg·m²/rad).

    Notes
    -----
    The velocity ratios dr/dφ are the velocities of the solution at φ_t = 1, and the second
    derivatives d²r/dφ² its accelerations at φ_t = 1, φ_tt = 0, because ``r_tt = r'' φ_t² + r' φ_tt``.
    Both are exact: no differences are taken (chapter 7).
    """
    solution = _mechanism(mechanism).solve(phi, omega=1.0, alpha=0.0, order=2)
    parts = kinetic_energies(solution, masses).values()
    shape = np.shape(solution.phi)
    # at φ_t = 1: T = J_red/2 and dT/dt = dT/dφ = (dJ_red/dφ)/2
    energy = sum((p.value for p in parts), np.zeros(shape))
    slope = sum((p.velocity for p in parts), np.zeros(shape))
    return 2.0 * energy, 2.0 * slope


def reduced_torque(mechanism: Mechanism, loads: Sequence[Force | Torque], phi: ArrayLike) -> np.ndarray:
    """The reduced torque of the applied loads at the crank, M_red(φ) = (the loads' power)/φ_t (N·m).

    Their power at φ_t = 1 (the loads' part of the generalized force Q_φ = M_d − M_c, chapter 7). The loads are evaluated on the
    solution at φ_t = 1, φ_tt = 0, so a load may depend on the position and on the direction of
    motion for a crank turning counter-clockwise.
    """
    solution = _mechanism(mechanism).solve(phi, omega=1.0, alpha=0.0, order=1)
    return applied_power(solution, loads)


def potential_torque(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike,
                     gravity: float = STANDARD_GRAVITY, springs: Sequence[Spring] = ()) -> np.ndarray:
    """dV/dφ (N·m): the torque at the crank that holds gravity and the springs in balance.

    The power dV/dt at φ_t = 1, exact.
    """
    solution = _mechanism(mechanism).solve(phi, omega=1.0, alpha=0.0, order=1)
    return potential_energy(solution, masses, gravity, springs).velocity


def driving_torque(solution: Solution, masses: Mapping[str, LinkMass], loads: Sequence[Force | Torque] = (),
                   gravity: float = STANDARD_GRAVITY, springs: Sequence[Spring] = ()) -> np.ndarray:
    """The driving torque on the crank from the power balance (N·m).

    Parameters
    ----------
    solution : Solution
        Kinematics of order 2 for the given crank motion φ, φ_t ≠ 0, φ_tt.
    masses, loads, gravity, springs
        As for :func:`kinetic_energy`, :func:`applied_power` and :func:`potential_energy`.

    Returns
    -------
    ndarray
        ``M_d = (dT/dt + dV/dt − P_loads)/φ_t``.

    Notes
    -----
    With ideal (frictionless) joints the joint forces do no work, so the power of the driving
    torque and of the loads goes into the change of the two energies:
    ``M_d φ_t + P_loads = dT/dt + dV/dt`` (chapter 7). Where φ_t = 0 use the Lagrange form of
    :func:`mechanisms.analysis.dynamics.required_torque`.
    """
    _require(solution, 2, "the driving torque")
    speed = _crank_speed(solution)
    if np.any(speed == 0.0):
        raise InvalidParameterError("omega", 0.0, "non-zero for the power balance (divide by φ_t); "
                                    "use dynamics.required_torque where the crank is at rest")
    change = kinetic_energy(solution, masses).velocity + potential_energy(solution, masses, gravity, springs).velocity
    return (change - applied_power(solution, loads)) / speed


def energy_balance(solution: Solution, masses: Mapping[str, LinkMass], drive: ArrayLike,
                   loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                   springs: Sequence[Spring] = ()) -> np.ndarray:
    """The residual of the power balance (W): ``M_d φ_t + P_loads − dT/dt − dV/dt``.

    Parameters
    ----------
    drive : float or array_like
        The driving torque M_d on the crank (N·m) found in some other way (Newton–Euler).

    Returns
    -------
    ndarray
        Zero up to round-off when ``drive`` is right.
    """
    _require(solution, 2, "the energy balance")
    drive = require_rates("drive", drive, np.shape(solution.phi), np.inf, "N·m")
    change = kinetic_energy(solution, masses).velocity + potential_energy(solution, masses, gravity, springs).velocity
    return drive * _crank_speed(solution) + applied_power(solution, loads) - change
