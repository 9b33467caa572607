"""Layer 5: the checks of the analysis sequence — constraint residual, preserved distances,
derivatives against numerical differentiation, coordinates against the generic solver."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..core.angles import wrap_angle
from ..core.motion import AngleMotion
from ..linkages.base import Mechanism, Solution
from .differences import central_difference
from .newton import solve_generic

__all__ = ["constraint_residual", "distance_deviation", "derivative_errors", "generic_errors"]


def constraint_residual(mechanism: Mechanism, solution: Solution) -> float:
    """Largest |Φ(q, φ)| of the mechanism's constraint equations at a solution (m or rad)."""
    q = [c.value for c in mechanism.coordinates(solution)]
    return float(max(np.max(np.abs(r)) for r in mechanism.constraints(q, solution.phi)))


def distance_deviation(mechanism: Mechanism, solution: Solution) -> float:
    """Largest change of a distance between two joints of one rigid link (m)."""
    mechanism.require_one_linkage("the distance check")
    return float(max(np.max(np.abs(np.abs(solution.point(a).value - solution.point(b).value) - length))
                     for (a, b), length in mechanism.preserved_distances().items()))


def derivative_errors(mechanism: Mechanism, phi: ArrayLike, omega: float, step: float = 1e-5,
                      step2: float = 1e-4) -> dict[str, tuple[float, float]]:
    """Largest difference between exact derivatives and numerical differentiation.

    For every link angle and joint of the mechanism at constant crank speed ω, returns
    ``{name: (velocity error, acceleration error)}`` in 1/s, 1/s² or m/s, m/s².
    """
    phi = np.asarray(phi, dtype=float)
    exact = mechanism.solve(phi, omega, 0.0, order=2)
    positions = {}

    def at(name, kind):
        def g(angles):
            key = (name, kind, angles.tobytes())
            if key not in positions:
                sol = mechanism.solve(angles, omega, order=0)
                positions[key] = sol.angle(name).value if kind == "angle" else sol.point(name).value
            return positions[key]
        return g

    result = {}
    for kind, names in (("angle", exact.angle_names), ("point", exact.point_names)):
        for name in names:
            motion = exact.angle(name) if kind == "angle" else exact.point(name)
            v = central_difference(at(name, kind), phi, omega, step, 1, angle=kind == "angle")
            a = central_difference(at(name, kind), phi, omega, step2, 2, angle=kind == "angle")
            result[name] = (float(np.max(np.abs(v - motion.velocity))),
                            float(np.max(np.abs(a - motion.acceleration))))
    return result


def generic_errors(mechanism: Mechanism, phi: ArrayLike, omega: float = 1.0, alpha: float = 0.0,
                   tol: float = 1e-14) -> tuple[float, float, float]:
    """Largest difference of the closed form's coordinates from the generic solver's.

    Returns the errors of positions, velocities and accelerations (angles wrapped).
    """
    mechanism.require_one_linkage("the comparison with the generic solver")
    closed = mechanism.solve(phi, omega, alpha, order=2)
    generic = solve_generic(mechanism, phi, omega, alpha, order=2, tol=tol)
    coords = mechanism.coordinates(closed)
    q = np.array([c.value for c in coords])
    q_t = np.array([c.velocity for c in coords])
    q_tt = np.array([c.acceleration for c in coords])
    angles = np.array([isinstance(c, AngleMotion) for c in coords])[:, None]
    position_errors = np.where(angles, wrap_angle(q - generic.q), q - generic.q)   # lengths are not wrapped
    return (float(np.max(np.abs(position_errors))),
            float(np.max(np.abs(q_t - generic.q_t))),
            float(np.max(np.abs(q_tt - generic.q_tt))))
