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
import numbers
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike

from ..linkages.base import Mechanism
from ..core.errors import InvalidParameterError, MechanismError, describe_angles
from ..core.validate import (ALPHA_MAX, OMEGA_MAX, require_angles, require_finite_array, require_positive,
                             require_non_negative, require_rates)
from .energy import (STANDARD_GRAVITY, Force, LinkMass, Spring, Torque, _mechanism, applied_power,
                     kinetic_energies, potential_energy)

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

MAX_SAMPLES = 10_000_000
"""The most states (time steps + 1, times the runs side by side) :func:`simulate` keeps: 160 MB of φ and φ_t."""


def _count(name: str, value: object, high: int) -> int:
    """A whole number from 1 to ``high``: an integer (Python's or numpy's, not a bool) or a float without a
    fractional part; else :class:`InvalidParameterError` naming it."""
    requirement = f"a whole number from 1 to {high}"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer, float, np.floating)):
        raise InvalidParameterError(name, value, requirement)
    if isinstance(value, (float, np.floating)) and not (math.isfinite(value) and float(value).is_integer()):
        raise InvalidParameterError(name, value, requirement)
    number = int(value)
    if not 1 <= number <= high:
        raise InvalidParameterError(name, value, requirement)
    return number


def _flywheel(flywheel: ArrayLike, shape: tuple[int, ...] | None = None) -> np.ndarray:
    """J_fl (kg·m²): finite numbers ≥ 0, one or (with ``shape``) one per crank angle."""
    array = (require_finite_array("flywheel", flywheel, "kg·m²") if shape is None
             else require_rates("flywheel", flywheel, shape, np.inf, "kg·m²"))
    if np.any(array < 0.0):
        raise InvalidParameterError("flywheel", array[array < 0.0][:3].tolist() if array.ndim else array.item(),
                                    "a moment of inertia ≥ 0 kg·m² (one, or one per crank angle)")
    return array


def _finite_model(model: "ReducedModel", singular: np.ndarray, phi: np.ndarray) -> None:
    """Nothing unbounded outside the singular positions (which the solution has flagged and warned of)."""
    bad = ~(np.isfinite(model.inertia) & np.isfinite(model.slope) & np.isfinite(model.resistance)) & ~singular
    if np.any(bad):
        raise MechanismError(f"J_red, dJ_red/dφ or M_c is beyond the range of floating-point numbers at crank "
                             f"angle(s) {describe_angles(phi[bad])}: masses, loads, springs or a flywheel too large")


def _acceleration(model: "ReducedModel", torque: np.ndarray, omega: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """φ_tt = (M_d − M_c − ½ J_red' φ_t²)/J_red, refused where J_red = 0 (the motion is then not determined)."""
    still = np.broadcast_to(model.inertia <= 0.0, np.broadcast_shapes(np.shape(model.inertia), np.shape(phi)))
    if np.any(still):
        raise InvalidParameterError(
            "masses", f"J_red = 0 at crank angle(s) {describe_angles(np.broadcast_to(phi, still.shape)[still])}",
            "masses (or a flywheel) that give the crank a reduced moment of inertia J_red > 0 at every angle")
    return (torque - model.resistance - 0.5 * model.slope * omega**2) / model.inertia


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
    solution = _mechanism(mechanism).solve(phi, omega=1.0, alpha=0.0, order=2)
    shape = np.shape(solution.phi)
    wheel = _flywheel(flywheel, shape)
    parts = kinetic_energies(solution, masses).values()
    inertia = 2.0 * sum((p.value for p in parts), np.zeros(shape))
    slope = 2.0 * sum((p.velocity for p in parts), np.zeros(shape))
    resistance = potential_energy(solution, masses, gravity, springs).velocity - applied_power(solution, loads)
    with np.errstate(over="ignore", invalid="ignore"):
        model = ReducedModel(inertia + wheel, slope, resistance)
    _finite_model(model, np.asarray(solution.singular, dtype=bool), solution.phi)
    return model


def required_torque(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike, omega: ArrayLike,
                    alpha: ArrayLike = 0.0, loads: Sequence[Force | Torque] = (), gravity: float = STANDARD_GRAVITY,
                    springs: Sequence[Spring] = (), flywheel: ArrayLike = 0.0) -> np.ndarray:
    """The driving torque for a given crank motion, from Lagrange's equation (N·m).

    ``M_d = J_red φ_tt + ½ J_red' φ_t² + M_c``. Unlike the power balance it holds at φ_t = 0 too.
    """
    model = reduced_model(mechanism, masses, phi, loads, gravity, springs, flywheel)
    shape = np.shape(model.inertia)
    omega = require_rates("omega", omega, shape, OMEGA_MAX, "1/s")
    alpha = require_rates("alpha", alpha, shape, ALPHA_MAX, "1/s²")
    return model.inertia * alpha + 0.5 * model.slope * omega**2 + model.resistance


def _drive_torque(drive: Drive, t, phi, omega) -> np.ndarray:
    """M_d (N·m): ``drive`` itself or what it returns for (t, φ, φ_t); finite numbers, one or one per crank angle."""
    shape = np.broadcast_shapes(np.shape(phi), np.shape(omega))
    if callable(drive):
        return require_rates("drive", drive(t, phi, omega), shape, np.inf, "N·m, as the drive's function returns it")
    return require_rates("drive", drive, shape, np.inf, "N·m")


def angular_acceleration(mechanism: Mechanism, masses: Mapping[str, LinkMass], phi: ArrayLike, omega: ArrayLike,
                         drive: Drive, t: ArrayLike = 0.0, loads: Sequence[Force | Torque] = (),
                         gravity: float = STANDARD_GRAVITY, springs: Sequence[Spring] = (),
                         flywheel: ArrayLike = 0.0) -> np.ndarray:
    """The crank's angular acceleration from the equation of motion (1/s²).

    ``φ_tt = (M_d − M_c − ½ J_red' φ_t²)/J_red``; ``drive`` is a torque (N·m) or a function
    ``M_d(t, φ, φ_t)`` (a motor's characteristic).
    """
    model = reduced_model(mechanism, masses, phi, loads, gravity, springs, flywheel)
    phi = np.asarray(phi, dtype=float)
    omega = require_rates("omega", omega, phi.shape, OMEGA_MAX, "1/s")
    t = require_finite_array("t", t, "s")
    return _acceleration(model, _drive_torque(drive, t, phi, omega), omega, phi)


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
    duration = require_positive("duration", duration, "s")
    steps = _count("steps", steps, MAX_SAMPLES - 1)
    start = require_angles("phi0", phi0), require_finite_array("omega0", omega0, "1/s"), _flywheel(flywheel)
    if np.any(np.abs(start[1]) > OMEGA_MAX):
        raise InvalidParameterError("omega0", omega0, f"of magnitude at most {OMEGA_MAX:g} 1/s")
    try:
        phi, omega, wheel = np.broadcast_arrays(*start)
    except ValueError:
        raise InvalidParameterError("phi0, omega0 and flywheel", f"arrays of shapes {[a.shape for a in start]}",
                                    "numbers, or arrays of one shape (one run each)") from None
    shape = phi.shape
    if (steps + 1) * max(phi.size, 1) > MAX_SAMPLES:
        raise InvalidParameterError("steps", steps, f"at most {MAX_SAMPLES} states in all: (steps + 1) × "
                                    f"{phi.size} runs ≤ {MAX_SAMPLES}")
    phi, omega, wheel = (np.array(a, dtype=float).reshape(-1) for a in (phi, omega, wheel))
    h = duration / steps
    if not (h > 0.0 and math.isfinite(h)):
        raise InvalidParameterError("duration", duration, "a time step duration/steps that is a positive number")

    def rate(t, p, w):
        _bounded(t, p, w)
        model = reduced_model(mechanism, masses, p, loads, gravity, springs, wheel)
        return w, _acceleration(model, _drive_torque(drive, t, p, w), w, p)

    times = h * np.arange(steps + 1)
    phis = np.empty((steps + 1, phi.size))
    omegas = np.empty((steps + 1, phi.size))
    phis[0], omegas[0] = phi, omega
    for k in range(steps):
        with np.errstate(over="ignore", invalid="ignore"):   # an unbounded motion is found and named below
            phi, omega = _step(rate, times[k], h, phi, omega)
        _bounded(times[k + 1], phi, omega)
        phis[k + 1], omegas[k + 1] = phi, omega
    return Run(times, phis.reshape((steps + 1,) + shape), omegas.reshape((steps + 1,) + shape))


def _bounded(t: float, phi: np.ndarray, omega: np.ndarray) -> None:
    """Refuse a state that has left the numbers: the motion has become unbounded."""
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(omega))):
        raise MechanismError(f"the motion becomes unbounded near t = {t:.6g} s: a driving torque or load too "
                             "large for the masses, or a step Δt too long")


def _step(rate, t: float, h: float, phi: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One step Δt = h of the classical Runge–Kutta method on the state (φ, φ_t)."""
    k1p, k1w = rate(t, phi, omega)
    k2p, k2w = rate(t + 0.5 * h, phi + 0.5 * h * k1p, omega + 0.5 * h * k1w)
    k3p, k3w = rate(t + 0.5 * h, phi + 0.5 * h * k2p, omega + 0.5 * h * k2w)
    k4p, k4w = rate(t + h, phi + h * k3p, omega + h * k3w)
    return (phi + h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p),
            omega + h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w))


@dataclass(frozen=True)
class SpeedFluctuation:
    """Extreme and mean crank speeds (1/s) over whole revolutions, and δ = (ω_max − ω_min)/ω_m.

    In the run's sense of rotation: for a clockwise run (φ decreasing, φ_t < 0) ω_max is the fastest speed,
    the most negative φ_t, ω_min the slowest, and ω_m is negative too, so δ ≥ 0 either way."""

    minimum: np.ndarray
    maximum: np.ndarray
    mean: np.ndarray
    coefficient: np.ndarray


def speed_fluctuation(run: Run, revolutions: int = 1) -> SpeedFluctuation:
    """The coefficient of speed fluctuation over the last revolutions of a run.

    Parameters
    ----------
    run : Run
        A simulation that has reached steady motion, the crank turning either way.
    revolutions : int
        How many of the last whole crank revolutions to look at, ≥ 1.

    Returns
    -------
    SpeedFluctuation
        ``ω_m = (ω_max + ω_min)/2`` and ``δ = (ω_max − ω_min)/ω_m`` (the textbook definition), per run,
        in the run's sense of rotation (a clockwise run gives the same δ as its mirror image).

    Raises
    ------
    InvalidParameterError
        Naming ``revolutions`` if the crank has not turned that many times in the run, and ``run`` if it is
        not a :class:`Run` of finite numbers or its crank turns back within those revolutions (no steady motion).

    Notes
    -----
    The extremes are taken over the time steps, so they are accurate to O(Δt²) relative to the
    curvature of ω(t) at its extremes: with 100 steps per revolution, to about 1e-4 of the swing.
    """
    if not isinstance(run, Run):
        raise InvalidParameterError("run", run, "a Run, as simulate(...) returns")
    revolutions = _count("revolutions", revolutions, 2**53)
    t = require_finite_array("run.t", run.t, "s")
    phi = require_finite_array("run.phi", run.phi, "rad")
    omega = require_finite_array("run.omega", run.omega, "1/s")
    if t.ndim != 1 or t.size < 2 or phi.shape != omega.shape or phi.shape[:1] != t.shape:
        raise InvalidParameterError("run", f"t of shape {t.shape}, phi {phi.shape}, omega {omega.shape}",
                                    "t of shape (n,) with n ≥ 2, phi and omega of one shape (n,) or (n, k)")
    phi, omega = phi.reshape(len(t), -1), omega.reshape(len(t), -1)
    sense = np.where(phi[-1] >= phi[0], 1.0, -1.0)          # +1 counter-clockwise, −1 clockwise, per run
    turn = 2.0 * math.pi * revolutions
    if np.any(sense * (phi[-1] - phi[0]) < turn):
        raise InvalidParameterError("revolutions", revolutions, "no more than the crank has turned in the run")
    # the last revolutions: the angles within `turn` of the last one, in the run's sense
    window = sense * (phi[-1] - phi) <= turn
    speed = sense * omega                                   # the speed in the run's sense of rotation
    high = np.where(window, speed, -np.inf).max(axis=0)
    low = np.where(window, speed, np.inf).min(axis=0)
    if np.any(low < 0.0):
        raise InvalidParameterError("run", "a crank that turns back within the last revolutions",
                                    "a run in steady motion, its crank turning one way (then δ is defined)")
    mean = 0.5 * (high + low)
    shape = run.phi.shape[1:]
    return SpeedFluctuation(*(a.reshape(shape) for a in (sense * low, sense * high, sense * mean, (high - low) / mean)))


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
    with np.errstate(over="ignore", invalid="ignore"):
        work = np.concatenate([[0.0], np.cumsum(0.5 * (torque[1:] + torque[:-1]) * np.diff(phi))])
        work = work - (phi - phi[0]) * work[-1] / (phi[-1] - phi[0])
        swing = float(work.max() - work.min())
    if not math.isfinite(swing):
        raise InvalidParameterError("torque", "values whose work overflows",
                                    "torques and angles whose work over the period is a finite number of J")
    return swing


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
    with np.errstate(over="ignore", divide="ignore"):
        inertia = float(np.float64(swing) / (np.float64(coefficient) * np.float64(mean_speed)**2))
    if not math.isfinite(inertia):
        raise InvalidParameterError("mean_speed", mean_speed, f"a speed for which ΔE/(δ ω_m²) is a finite number "
                                    f"(ΔE = {swing:g} J, δ = {coefficient:g})")
    return inertia
