"""Layer 4: the equation of motion of a one-degree-of-freedom mechanism (chapter 7).

Reduced to its crank, a mechanism with one degree of freedom has the kinetic energy
``T = J_red(φ) φ_t²/2`` (:func:`~mechanisms.analysis.energy.reduced_inertia`). Lagrange's
equation ``d/dt(∂T/∂φ_t) − ∂T/∂φ = Q_φ`` (Q_φ the generalized force) then reads

    J_red(φ) φ_tt + ½ J_red'(φ) φ_t² = M_d − M_c(φ),

with M_d the driving torque and ``M_c = dV/dφ − M_red`` the reduced torque of the resistance
(gravity and springs through V, the applied loads through their reduced torque M_red). This module evaluates that equation exactly, integrates
it in time with the classical Runge–Kutta method, and gives the two classical figures of a
machine in steady motion: the coefficient of speed fluctuation and the flywheel that keeps it
small. numpy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike

from ..linkages.base import Mechanism
from ..core.errors import InvalidParameterError
from ..core.validate import require_finite, require_finite_array, require_positive, require_non_negative
from .energy import (STANDARD_GRAVITY, Force, LinkMass, Spring, Torque, applied_power, kinetic_energies,
                     potential_energy)

__all__ = [
    "ReducedModel",
    "reduced_model",
    "required_torque",
    "angular_acceleration",
    "Run",
    "simulate",
    "SpeedFluctuation",
    "speed_fluctuation",
    "energy_swing",
    "flywheel_inertia",
]

Drive = Union[float, np.ndarray, Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]]


@dataclass(frozen=True)
class ReducedModel:
    """The mechanism reduced to its crank at some crank angles.

    Attributes
    ----------
    inertia : ndarray
        J_red(φ) (kg·m²), the flywheel included.
    slope : ndarray
        dJ_red/dφ (kg·m²/rad).
    resistance : ndarray
        M_c(φ) = dV/dφ − M_red (N·m): the torque the crank must supply, at rest, to hold the
        mechanism against gravity, springs and loads.
    """

    inertia: np.ndarray
    slope: np.ndarray
    resistance: np.ndarray


def reduced_model(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike,
                  loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                  springs: Sequence[Spring] = (), flywheel: ArrayLike = 0.0) -> ReducedModel:
    """J_red, dJ_red/dφ and M_c at crank angles φ, from one solution at φ_t = 1, φ_tt = 0.

    Parameters
    ----------
    mechanism : Mechanism
        Any mechanism of the package.
    masses : mapping
        ``{body: LinkMass}``.
    phi : array_like
        Crank angles (rad).
    loads, gravity, springs
        As in :mod:`mechanisms.analysis.energy`.
    flywheel : float or array_like
        A flywheel's moment of inertia J_fl (kg·m²) on the crank shaft, added to J_red.

    Notes
    -----
    At φ_t = 1 and φ_tt = 0 the velocities are the velocity ratios (derivatives with respect to
    φ) and the accelerations their derivatives, so that T = J_red/2, dT/dt = J_red'/2,
    dV/dt = dV/dφ and the power of the loads is M_red: all exact.
    """
    solution = mechanism.solve(phi, omega=1.0, alpha=0.0, order=2)
    shape = np.shape(solution.phi)
    parts = kinetic_energies(solution, masses).values()
    inertia = 2.0 * sum((p.value for p in parts), np.zeros(shape))
    slope = 2.0 * sum((p.velocity for p in parts), np.zeros(shape))
    resistance = potential_energy(solution, masses, gravity, springs).velocity - applied_power(solution, loads)
    return ReducedModel(inertia + np.asarray(flywheel, dtype=float), slope, resistance)


def required_torque(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike, omega: ArrayLike,
                    alpha: ArrayLike = 0.0, loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                    springs: Sequence[Spring] = (), flywheel: ArrayLike = 0.0) -> np.ndarray:
    """The driving torque for a given crank motion, from Lagrange's equation (N·m).

    ``M_d = J_red φ_tt + ½ J_red' φ_t² + M_c``. Unlike the power balance it holds at φ_t = 0 too.
    """
    model = reduced_model(mechanism, masses, phi, loads, gravity, springs, flywheel)
    omega, alpha = np.asarray(omega, dtype=float), np.asarray(alpha, dtype=float)
    return model.inertia * alpha + 0.5 * model.slope * omega**2 + model.resistance


def _drive_torque(drive: Drive, t, phi, omega) -> np.ndarray:
    if callable(drive):
        return np.asarray(drive(t, phi, omega), dtype=float)
    return np.asarray(drive, dtype=float)


def angular_acceleration(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike, omega: ArrayLike,
                         drive: Drive, t: ArrayLike = 0.0, loads: Sequence[Force | Torque] = (),
                         gravity: float = STANDARD_GRAVITY, springs: Sequence[Spring] = (),
                         flywheel: ArrayLike = 0.0) -> np.ndarray:
    """The crank's angular acceleration from the equation of motion (1/s²).

    ``φ_tt = (M_d − M_c − ½ J_red' φ_t²)/J_red``; ``drive`` is a torque (N·m) or a function
    ``M_d(t, φ, φ_t)`` (a motor's characteristic).
    """
    model = reduced_model(mechanism, masses, phi, loads, gravity, springs, flywheel)
    omega = np.asarray(omega, dtype=float)
    torque = _drive_torque(drive, t, phi, omega)
    return (torque - model.resistance - 0.5 * model.slope * omega**2) / model.inertia


@dataclass(frozen=True)
class Run:
    """A simulated motion of the crank.

    Attributes
    ----------
    t : ndarray, shape (n + 1,)
        Times (s).
    phi, omega : ndarray, shape (n + 1,) or (n + 1, k)
        Crank angle φ (rad, not wrapped) and speed φ_t (1/s); one column per run when several
        runs (e.g. several flywheels) were integrated together.
    """

    t: np.ndarray
    phi: np.ndarray
    omega: np.ndarray


def simulate(mechanism: Mechanism, masses: Mapping[str, LinkMass], drive: Drive, *, duration: float,
             steps: int, phi0: ArrayLike = 0.0, omega0: ArrayLike = 0.0, loads: Sequence[Force | Torque] = (),
             gravity: float = STANDARD_GRAVITY, springs: Sequence[Spring] = (), flywheel: ArrayLike = 0.0) -> Run:
    """Integrate the equation of motion ``J_red φ_tt + ½ J_red' φ_t² = M_d − M_c`` in time.

    Parameters
    ----------
    mechanism, masses, loads, gravity, springs, flywheel
        As for :func:`reduced_model`. ``flywheel``, ``phi0`` and ``omega0`` may be arrays: the
        runs are integrated side by side (one column each).
    drive : float or callable
        The driving torque M_d (N·m) or a function ``M_d(t, φ, φ_t)`` of arrays.
    duration : float
        Time span (s), > 0.
    steps : int
        Number of fixed time steps Δt = duration/steps.
    phi0, omega0 : float or array_like
        Initial crank angle (rad) and speed (1/s).

    Returns
    -------
    Run

    Notes
    -----
    The classical fourth-order Runge–Kutta method with a fixed step Δt on the state (φ, φ_t);
    every stage evaluates J_red, J_red' and M_c exactly (:func:`reduced_model`). For a smooth
    right-hand side the local error is O(Δt⁵) and the global error O(Δt⁴): halving the step
    divides the error by about 16. The tests measure it as the drift of the energy of a free
    run (no drive, no load), which the exact motion conserves: for the crank-slider of
    chapter 7, below 1e-7 of the energy over 3 revolutions at 200 steps per revolution, and
    about 16 times less when Δt halves.
    A load with a jump in its reduced torque lowers the order near the jump; choose Δt small
    against the angle over which the load changes.
    """
    duration = float(duration)
    if not (math.isfinite(duration) and duration > 0.0):
        raise InvalidParameterError("duration", duration, "a finite time > 0 s")
    if int(steps) != steps or steps < 1:
        raise InvalidParameterError("steps", steps, "a whole number ≥ 1")
    steps = int(steps)
    phi, omega, flywheel = np.broadcast_arrays(np.asarray(phi0, dtype=float), np.asarray(omega0, dtype=float),
                                               np.asarray(flywheel, dtype=float))
    shape = phi.shape
    phi, omega, flywheel = (np.array(a, dtype=float).reshape(-1) for a in (phi, omega, flywheel))
    h = duration / steps

    def rate(t, p, w):
        model = reduced_model(mechanism, masses, p, loads, gravity, springs, flywheel)
        torque = _drive_torque(drive, t, p, w)
        return w, (torque - model.resistance - 0.5 * model.slope * w**2) / model.inertia

    times = h * np.arange(steps + 1)
    phis = np.empty((steps + 1, phi.size))
    omegas = np.empty((steps + 1, phi.size))
    phis[0], omegas[0] = phi, omega
    for k in range(steps):
        t = times[k]
        k1p, k1w = rate(t, phi, omega)
        k2p, k2w = rate(t + 0.5 * h, phi + 0.5 * h * k1p, omega + 0.5 * h * k1w)
        k3p, k3w = rate(t + 0.5 * h, phi + 0.5 * h * k2p, omega + 0.5 * h * k2w)
        k4p, k4w = rate(t + h, phi + h * k3p, omega + h * k3w)
        phi = phi + h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p)
        omega = omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w)
        phis[k + 1], omegas[k + 1] = phi, omega
    return Run(times, phis.reshape((steps + 1,) + shape), omegas.reshape((steps + 1,) + shape))


@dataclass(frozen=True)
class SpeedFluctuation:
    """Extreme and mean crank speeds (1/s) over whole revolutions, and δ = (ω_max − ω_min)/ω_m."""

    minimum: np.ndarray
    maximum: np.ndarray
    mean: np.ndarray
    coefficient: np.ndarray


def speed_fluctuation(run: Run, revolutions: int = 1) -> SpeedFluctuation:
    """The coefficient of speed fluctuation over the last revolutions of a run.

    Parameters
    ----------
    run : Run
        A simulation that has reached steady motion.
    revolutions : int
        How many of the last whole crank revolutions to look at.

    Returns
    -------
    SpeedFluctuation
        ``ω_m = (ω_max + ω_min)/2`` and ``δ = (ω_max − ω_min)/ω_m`` (the textbook definition), per run.

    Notes
    -----
    The extremes are taken over the time steps, so they are accurate to O(Δt²) relative to the
    curvature of ω(t) at its extremes: with 100 steps per revolution, to about 1e-4 of the swing.
    """
    phi = run.phi.reshape(len(run.t), -1)
    omega = run.omega.reshape(len(run.t), -1)
    window = phi >= phi[-1] - 2.0 * math.pi * revolutions
    if np.any(phi[0] > phi[-1] - 2.0 * math.pi * revolutions):
        raise InvalidParameterError("revolutions", revolutions, "no more than the crank has turned in the run")
    high = np.where(window, omega, -np.inf).max(axis=0)
    low = np.where(window, omega, np.inf).min(axis=0)
    mean = 0.5 * (high + low)
    shape = run.phi.shape[1:]
    return SpeedFluctuation(*(a.reshape(shape) for a in (low, high, mean, (high - low) / mean)))


def energy_swing(phi: ArrayLike, torque: ArrayLike) -> float:
    """The largest swing of the excess work over one period (J), for the flywheel estimate.

    Parameters
    ----------
    phi : array_like
        Increasing crank angles spanning one period of the machine's cycle, ends included (rad).
    torque : array_like
        The torque that changes the kinetic energy of the constant part of the inertia (N·m):
        M_d − M_c, and, for a mechanism whose J_red varies, minus ½ J_red' ω_m², the inertia
        torque of the variable part at the mean speed ω_m (chapter 7).

    Returns
    -------
    float
        ΔE, the largest swing (maximum minus minimum) of the excess work ``∫ (M_d − M_c) dφ``,
        taken with its mean slope removed (the trapezoid rule), i.e. for a driving torque whose work
        over the period equals that of the resistance.
    """
    phi = require_finite_array("phi", phi, "crank angles in rad")
    torque = require_finite_array("torque", torque, "N·m")
    if phi.ndim != 1 or phi.shape != torque.shape or phi.size < 2:
        raise InvalidParameterError("torque", f"{torque.size} values for {phi.size} crank angles",
                                    "one value per crank angle, at two or more angles")
    if not np.all(np.diff(phi) > 0.0):
        raise InvalidParameterError("phi", "angles that do not increase", "increasing crank angles over one period")
    work = np.concatenate([[0.0], np.cumsum(0.5 * (torque[1:] + torque[:-1]) * np.diff(phi))])
    work = work - (phi - phi[0]) * work[-1] / (phi[-1] - phi[0])
    return float(work.max() - work.min())


def flywheel_inertia(swing: float, mean_speed: float, coefficient: float) -> float:
    """The moment of inertia (kg·m²) that keeps the speed fluctuation to δ: ``J_tot = ΔE/(δ ω_m²)``.

    Notes
    -----
    From ``ΔE = J_tot (ω_max² − ω_min²)/2 = J_tot ω_m² δ`` for a constant J_tot: the classical estimate
    (chapter 7). The result J_tot includes the mean reduced inertia of the mechanism itself, which
    is subtracted to size the flywheel. The variable part of J_red enters through ``swing``: pass the
    swing of the excess work with the torque ½ J_red′ ω_m² included (:func:`energy_swing` of
    ``M_d − M_c − ½ J_red′ ω_m²``), as chapter 7 does; left out, δ comes out markedly larger than
    asked (chapter 7, §7.11).
    """
    swing = require_non_negative("swing", swing, "J")
    mean_speed = require_positive("mean_speed", mean_speed, "1/s")
    coefficient = require_positive("coefficient", coefficient, "(δ = (ω_max − ω_min)/ω_m)")
    return swing / (coefficient * mean_speed**2)
