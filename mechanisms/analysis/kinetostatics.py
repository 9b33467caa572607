"""Layer 4: joint forces by Newton–Euler (kinetostatics), chapter 7.

For every moving link of a crank-slider or a four-bar the equations of Newton and Euler,

    Σ F = m a_S,        Σ M_S = J_S ε      (moments about the centre of mass S),

hold with the joint forces as unknowns. Together with the driving torque on the crank they are
as many unknowns as there are equations: 8 for the crank-slider (three for the crank, three for
the coupler, two for the translating slider), 9 for the four-bar. The equations are linear in
the unknowns; they are assembled as one small matrix per crank position and solved for all the
positions at once with :func:`numpy.linalg.solve`.

Joint forces are complex numbers ``Fx + i Fy`` (N). The force at a joint is that of the body
nearer the frame (in the order frame → crank → coupler → slider or rocker) on the next one:

* crank-slider: ``O`` frame on crank, ``A`` crank on coupler, ``B`` coupler on slider,
  ``guide`` guide on slider (normal to the guide, through B);
* four-bar: ``O`` frame on crank, ``A`` crank on coupler, ``B`` coupler on rocker, ``C`` frame
  on rocker.

The driving torque is the torque of the frame (the motor) on the crank. Its value from the
joint forces is independent of the power balance of :mod:`mechanisms.analysis.energy`, and the
two must agree: chapter 7 checks it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from ..linkages.base import Mechanism, Solution
from ..core.errors import InvalidParameterError, MechanismError, UnknownNameError, describe_angles
from ..core.validate import require_finite
from ..linkages.groups import RRP, four_link
from .energy import (STANDARD_GRAVITY, Force, LinkMass, Spring, Torque, _loads, _masses, _mechanism, _solution,
                     _springs, body_angle, body_point, centre_of_mass, load_values)

__all__ = ["JointForces", "joint_forces"]


@dataclass(frozen=True)
class JointForces:
    """Result of :func:`joint_forces`.

    Attributes
    ----------
    forces : dict of ndarray
        Joint name → force ``Fx + i Fy`` (N) of the body nearer the frame on the next one,
        at each crank position; ``guide`` for the normal force of a slider's guide.
    driving_torque : ndarray
        The torque of the frame on the crank (N·m), counter-clockwise positive.
    """

    forces: dict[str, np.ndarray]
    driving_torque: np.ndarray

    def force(self, joint: str) -> np.ndarray:
        """The force at a joint (complex, N)."""
        try:
            return self.forces[joint]
        except (KeyError, TypeError):     # TypeError: a name that cannot be a key (a list)
            raise UnknownNameError("joint", joint, self.forces) from None


class _System:
    """The Newton–Euler equations of a few bodies, as a matrix per crank position.

    Rows: for each body ``x``, ``y`` (force) and, if it turns, ``m`` (moment about its centre of
    mass). Columns: the unknowns. The equations read ``A u = b`` with
    ``b = m a_S − Σ known forces`` and ``J_S ε − Σ known moments``.
    """

    def __init__(self, solution: Solution, bodies: dict[str, bool], unknowns: int,
                 masses: Mapping[str, LinkMass]):
        self.solution = solution
        self.rows: dict[str, int] = {}
        for body, turns in bodies.items():
            for part in ("x", "y", "m") if turns else ("x", "y"):
                self.rows[f"{body}.{part}"] = len(self.rows)
        n = np.size(solution.phi)
        self.matrix = np.zeros((n, len(self.rows), unknowns))
        self.rhs = np.zeros((n, len(self.rows)))
        self.centres = {}
        for body in bodies:
            props = masses.get(body, LinkMass(0.0))
            centre = centre_of_mass(solution, body, props)
            self.centres[body] = centre.value
            self.rhs[:, self.rows[f"{body}.x"]] += props.mass * centre.acceleration.real
            self.rhs[:, self.rows[f"{body}.y"]] += props.mass * centre.acceleration.imag
            if bodies[body]:
                turning = body_angle(solution, body)
                assert turning is not None   # a body that turns has an angle
                self.rhs[:, self.rows[f"{body}.m"]] += props.inertia * turning.alpha

    def _moment_row(self, body: str):
        return self.rows.get(f"{body}.m")

    def unknown_force(self, body: str, column: int, point: np.ndarray, sign: float) -> None:
        """An unknown force (columns ``column``, ``column + 1`` = Fx, Fy) at ``point``, times ``sign``."""
        self.matrix[:, self.rows[f"{body}.x"], column] += sign
        self.matrix[:, self.rows[f"{body}.y"], column + 1] += sign
        row = self._moment_row(body)
        if row is not None:
            arm = point - self.centres[body]
            self.matrix[:, row, column] += -sign * arm.imag   # moment of Fx: −Δy Fx
            self.matrix[:, row, column + 1] += sign * arm.real  # moment of Fy: Δx Fy

    def unknown_normal(self, body: str, column: int, direction: complex) -> None:
        """An unknown force of known direction through the body's centre (a guide's normal force)."""
        self.matrix[:, self.rows[f"{body}.x"], column] += direction.real
        self.matrix[:, self.rows[f"{body}.y"], column] += direction.imag

    def unknown_torque(self, body: str, column: int) -> None:
        self.matrix[:, self._moment_row(body), column] += 1.0

    def known_force(self, body: str, force: np.ndarray, point: np.ndarray) -> None:
        self.rhs[:, self.rows[f"{body}.x"]] -= force.real
        self.rhs[:, self.rows[f"{body}.y"]] -= force.imag
        row = self._moment_row(body)
        if row is not None:
            arm = point - self.centres[body]
            self.rhs[:, row] -= arm.real * force.imag - arm.imag * force.real

    def known_torque(self, body: str, torque: np.ndarray) -> None:
        row = self._moment_row(body)
        if row is not None:  # a translating block: its guide takes the torque up
            self.rhs[:, row] -= torque

    def applied(self, masses: Mapping[str, LinkMass], loads: Sequence[Force | Torque], gravity: float,
                springs: Sequence[Spring]) -> None:
        """Gravity (−y), springs and the applied loads, as known forces and torques."""
        shape = np.shape(self.solution.phi)
        for body, props in masses.items():
            weight = np.full(shape, -1j * props.mass * gravity)
            self.known_force(body, weight, self.centres[body])
        for spring in springs:
            self._check(spring.body, "a spring")
            point = body_point(self.solution, spring.body, spring.along, spring.left).value
            self.known_force(spring.body, spring.force(self.solution), point)
        for load in loads:
            self._check(load.body, "a load")
            if isinstance(load, Force):
                point = body_point(self.solution, load.body, load.along, load.left).value
                self.known_force(load.body, load_values(load, self.solution), point)
            else:
                self.known_torque(load.body, load_values(load, self.solution))

    def _check(self, body: str, what: str) -> None:
        if f"{body}.x" not in self.rows:
            bodies = sorted({row.split(".")[0] for row in self.rows})
            raise InvalidParameterError("body", body, f"one of {', '.join(bodies)} for {what}")

    def solve(self) -> np.ndarray:
        """The unknowns at each position (n, k); NaN where the solution is singular."""
        matrix = self.matrix.copy()
        singular = np.asarray(self.solution.singular, dtype=bool).reshape(-1)
        matrix[singular] = np.eye(matrix.shape[1])  # placeholders, replaced by NaN below
        try:
            unknowns = np.linalg.solve(matrix, self.rhs[..., None])[..., 0]
        except np.linalg.LinAlgError:   # a position the kinematics did not flag as singular
            rank = np.linalg.matrix_rank(matrix)
            phi = np.asarray(self.solution.phi, dtype=float).reshape(-1)
            raise MechanismError("the Newton–Euler equations have no unique solution (the joint forces are "
                                 f"undetermined) at crank angle(s) {describe_angles(phi[rank < matrix.shape[1]])}") \
                from None
        unknowns[singular] = np.nan
        return unknowns


def _check_masses(masses: Mapping[str, LinkMass], bodies: dict[str, bool], mechanism) -> None:
    for body in masses:
        if body not in bodies:
            raise InvalidParameterError(
                "masses", body, f"one of the bodies {', '.join(bodies)} of {type(mechanism).__name__}")


def joint_forces(mechanism: Mechanism, solution: Solution, masses: Mapping[str, LinkMass],
                 loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                 springs: Sequence[Spring] = ()) -> JointForces:
    """Joint forces and the driving torque of a crank-slider or a four-bar by Newton–Euler.

    Parameters
    ----------
    mechanism : Mechanism
        A crank-slider or a four-bar: a crank and one RRR or RRP group (``groups()``), which decide
        the equations.
    solution : Solution
        Its kinematics of order 2 for the crank motion (φ, φ_t, φ_tt).
    masses : mapping
        ``{body: LinkMass}``; bodies ``crank``, ``coupler`` and ``B`` (slider) or ``rocker``.
        A body that is not given is massless.
    loads : sequence of Force or Torque
        Applied loads on those bodies.
    gravity : float
        g (m/s²), along −y.
    springs : sequence of Spring
        Springs from the bodies to the frame.

    Returns
    -------
    JointForces

    Notes
    -----
    Unknowns, crank-slider: R_O, R_A, R_B (two components each), the guide's normal force N_B and
    the driving torque M_d; equations: crank (3), coupler (3), slider (2). The slider translates,
    so its moment equation only fixes the guide's moment, which does no work and is not sought.
    Four-bar: R_O, R_A, R_B, R_C and M_d against three equations for each of its three links.
    Joint forces enter the body nearer the frame with the opposite sign (Newton's third law).
    At a singular position (``solution.singular``) the results are NaN.
    """
    mechanism, solution = _mechanism(mechanism), _solution(solution)
    masses, loads, springs = _masses(masses), _loads(loads), _springs(springs)
    gravity = require_finite("gravity", gravity)
    if solution.order < 2:
        raise MechanismError(f"joint forces need accelerations: solve with order=2 (got order={solution.order})")
    phi = solution.phi
    groups = mechanism.groups()
    structure = four_link(groups)
    if structure is None:
        raise InvalidParameterError("mechanism", type(mechanism).__name__,
                                    "a CrankSlider or a FourBar, a crank and one RRR or RRP group "
                                    "(kinetostatics is written for these two)")
    crank, dyad = structure
    O, A, B = (solution.point(n).value for n in (crank.pivot, crank.pin, dyad.joint))
    if isinstance(dyad, RRP):
        # the slider is a body of its own, named by its joint; it translates along the guide
        coupler, slider = dyad.link, dyad.joint
        bodies = {crank.link: True, coupler: True, slider: False}
        _check_masses(masses, bodies, mechanism)
        system = _System(solution, bodies, 8, masses)
        system.unknown_force(crank.link, 0, O, +1.0)        # R_O: frame on crank
        system.unknown_force(crank.link, 2, A, -1.0)        # R_A: crank on coupler
        system.unknown_force(coupler, 2, A, +1.0)
        system.unknown_force(coupler, 4, B, -1.0)           # R_B: coupler on slider
        system.unknown_force(slider, 4, B, +1.0)
        normal = 1j * dyad.guide_direction
        system.unknown_normal(slider, 6, normal)            # N: guide on slider, across the guide
        system.unknown_torque(crank.link, 7)                # M_d: frame on crank
        system.applied(masses, loads, gravity, springs)
        u = system.solve()
        forces = {crank.pivot: u[:, 0] + 1j * u[:, 1], crank.pin: u[:, 2] + 1j * u[:, 3],
                  dyad.joint: u[:, 4] + 1j * u[:, 5], "guide": normal * u[:, 6]}
        torque = u[:, 7]
    else:
        C = solution.point(dyad.second).value
        coupler, rocker = dyad.first_link, dyad.second_link
        bodies = {crank.link: True, coupler: True, rocker: True}
        _check_masses(masses, bodies, mechanism)
        system = _System(solution, bodies, 9, masses)
        system.unknown_force(crank.link, 0, O, +1.0)        # R_O: frame on crank
        system.unknown_force(crank.link, 2, A, -1.0)        # R_A: crank on coupler
        system.unknown_force(coupler, 2, A, +1.0)
        system.unknown_force(coupler, 4, B, -1.0)           # R_B: coupler on rocker
        system.unknown_force(rocker, 4, B, +1.0)
        system.unknown_force(rocker, 6, C, +1.0)            # R_C: frame on rocker
        system.unknown_torque(crank.link, 8)                # M_d: frame on crank
        system.applied(masses, loads, gravity, springs)
        u = system.solve()
        forces = {crank.pivot: u[:, 0] + 1j * u[:, 1], crank.pin: u[:, 2] + 1j * u[:, 3],
                  dyad.joint: u[:, 4] + 1j * u[:, 5], dyad.second: u[:, 6] + 1j * u[:, 7]}
        torque = u[:, 8]
    shape = np.shape(phi)
    return JointForces({k: v.reshape(shape) for k, v in forces.items()}, torque.reshape(shape))
