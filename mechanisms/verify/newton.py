"""Layer 5: the generic solver — Newton's method on the constraint equations Φ(q, φ) = 0.

The lecture's recommended sequence of a kinematic analysis ends every few steps with checks:
the trajectories look right, the constraint equations hold, the distances between the joints of
one link are preserved, and velocities and accelerations agree with numerical differentiation of
the positions. This module provides those checks and an independent reference solution:

* :func:`solve_constraints` — Newton's method on the constraint equations Φ(q, φ) = 0 of any
  mechanism given as a function, velocities from ``Φ_q q_t = −Φ_φ φ_t`` and accelerations from
  the twice-differentiated constraints; the derivatives of Φ are exact (:class:`~mechanisms.jet.Jet`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..linkages.base import Mechanism
from ..core.errors import AssemblyError
from ..core.validate import require_order
from .jet import Jet

__all__ = [
    "GenericSolution",
    "jacobian",
    "linear_solve",
    "newton_steps",
    "rates",
    "solve_constraints",
    "newton_history",
    "solve_generic",
]

Constraints = Callable[[Sequence, object], Sequence]


@dataclass(frozen=True)
class GenericSolution:
    """Result of :func:`solve_constraints`: arrays of shape (k, n) for k unknowns at n positions."""

    q: np.ndarray
    q_t: np.ndarray | None
    q_tt: np.ndarray | None
    iterations: int
    residual: float


def _evaluate(constraints: Constraints, q, phi) -> list:
    return list(constraints(q, phi))


def _jacobian(constraints: Constraints, q: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Residuals Φ (n, k) and Jacobian Φ_q (n, k, k), exact, at every position."""
    k = q.shape[0]
    columns = []
    residual = None
    for j in range(k):
        seeded = [Jet(q[i], 1.0 if i == j else 0.0) for i in range(k)]
        out = _evaluate(constraints, seeded, phi)
        residual = [np.broadcast_to(r.f if isinstance(r, Jet) else r, phi.shape) for r in out]
        columns.append([np.broadcast_to(r.d1 if isinstance(r, Jet) else 0.0, phi.shape) for r in out])
    assert residual is not None   # k ≥ 1 unknowns: the loop ran
    jac = np.stack([np.stack(col, axis=-1) for col in columns], axis=-1)  # (n, k_eq, k_unknown)
    return np.stack(residual, axis=-1), jac


def jacobian(constraints: Constraints, q: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The residuals Φ (n, k) and the exact Jacobian Φ_q (n, k, k) at every position, in the float type of q.

    Parameters
    ----------
    constraints : callable
        ``Φ(q, φ)``, written with numpy operations (differentiated by jets).
    q : ndarray, shape (k, n)
        The unknown coordinates at n positions (float64, or numpy.longdouble for extended precision).
    phi : ndarray, shape (n,)
        Crank angles φ (rad).
    """
    return _jacobian(constraints, q, phi)


def linear_solve(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve ``matrix · x = rhs`` at every position: matrix (n, k, k), rhs (n, k) → x (n, k).

    In double precision by LAPACK (``numpy.linalg.solve``); in any other float type (extended
    precision: ``numpy.longdouble``, which LAPACK does not take) by Gaussian elimination with partial
    pivoting, vectorized over the positions. A singular matrix gives non-finite values.
    """
    if matrix.dtype == np.float64 and rhs.dtype == np.float64:
        with np.errstate(all="ignore"):
            try:
                return np.linalg.solve(matrix, rhs[..., None])[..., 0]
            except np.linalg.LinAlgError:
                return np.full_like(rhs, np.nan)
    a, b = matrix.copy(), rhs.copy()
    rows = np.arange(a.shape[0])
    size = a.shape[-1]
    with np.errstate(all="ignore"):
        for col in range(size):
            pivot = col + np.argmax(np.abs(a[:, col:, col]), axis=1)
            a[rows, col], a[rows, pivot] = a[rows, pivot].copy(), a[rows, col].copy()
            b[rows, col], b[rows, pivot] = b[rows, pivot].copy(), b[rows, col].copy()
            for r in range(col + 1, size):
                factor = a[:, r, col] / a[:, col, col]
                a[:, r, col:] -= factor[:, None] * a[:, col, col:]
                b[:, r] -= factor * b[:, col]
        x = np.empty_like(b)
        for r in reversed(range(size)):
            x[:, r] = (b[:, r] - (a[:, r, r + 1:] * x[:, r + 1:]).sum(axis=1)) / a[:, r, r]
    return x


def newton_steps(constraints: Constraints, q: np.ndarray, phi: np.ndarray, steps: int) -> np.ndarray:
    """A fixed number of Newton steps ``q ← q − Φ_q⁻¹ Φ`` from q (k, n), in the float type of q.

    For a reference in extended precision (the benchmark's): from a double-precision solution two
    steps reach the round-off of ``numpy.longdouble``, Newton's method converging quadratically.
    """
    for _ in range(steps):
        residual, jac = _jacobian(constraints, q, phi)
        q = q - linear_solve(jac, residual).T
    return q


def rates(constraints: Constraints, q: np.ndarray, phi: np.ndarray, omega: ArrayLike, alpha: ArrayLike, order: int,
          jac: np.ndarray | None = None) -> tuple[np.ndarray | None, np.ndarray | None]:
    """Velocities and accelerations ``(q_t, q_tt)`` (k, n) of the coordinates q, in the float type of q.

    ``Φ_q q_t = −Φ_φ φ_t``; ``Φ_q q_tt = −(d²Φ/dt²)|_{q_tt = 0}``, the constraints differentiated twice
    along the motion with exact derivatives (jets); ``None`` above ``order``.
    """
    if order < 1:
        return None, None
    if jac is None:
        _, jac = _jacobian(constraints, q, phi)
    omega = np.broadcast_to(np.asarray(omega, dtype=q.dtype), phi.shape)
    alpha = np.broadcast_to(np.asarray(alpha, dtype=q.dtype), phi.shape)
    rate = _evaluate(constraints, [Jet(qi) for qi in q], Jet(phi, omega))
    rhs = -np.stack([np.broadcast_to(r.d1 if isinstance(r, Jet) else 0.0, phi.shape) for r in rate], -1)
    q_t = linear_solve(jac, rhs.astype(q.dtype)).T
    if order < 2:
        return q_t, None
    path = _evaluate(constraints, [Jet(qi, vi) for qi, vi in zip(q, q_t)], Jet(phi, omega, alpha))
    rhs = -np.stack([np.broadcast_to(r.d2 if isinstance(r, Jet) else 0.0, phi.shape) for r in path], -1)
    return q_t, linear_solve(jac, rhs.astype(q.dtype)).T


def _newton(constraints, q, phi, tol, max_iter):
    """Vectorized Newton iterations from the guess q (k, n); returns q and the iterations used.

    A position has converged when its step is below ``tol·(1 + |q|)``, or when its step has stopped
    shrinking once it is below ``√tol·(1 + |q|)``: near a singular position (1e-9 rad from a limit of
    assembly) round-off keeps the steps at about ε/√δ, above ``tol``, and the iterate is then as good as
    double precision makes it.
    """
    done = np.zeros(phi.shape, dtype=bool)
    previous = np.full(phi.shape, np.inf)
    size = np.zeros(phi.shape)
    for iteration in range(1, max_iter + 1):
        residual, jac = _jacobian(constraints, q, phi)
        step = linear_solve(jac, residual)
        step[done] = 0.0
        q = q - step.T
        size = np.max(np.abs(step), axis=-1)
        bad = ~np.isfinite(size)
        if bad.any():
            raise AssemblyError("Newton's method met a singular constraint Jacobian (no assembly or a "
                                "singular position)", phi[bad])
        bound = 1.0 + np.max(np.abs(q), axis=0)
        stalled = (size >= 0.9 * previous) & (size <= np.sqrt(tol) * bound)
        done |= (size <= tol * bound) | stalled
        previous = np.where(done, previous, size)
        if done.all():
            return q, iteration
    raise AssemblyError(f"Newton's method did not converge in {max_iter} iterations "
                        "(no assembly, or the guess is far off)", phi[~done])


_LARGEST_CHANGE = 0.5
"""The largest change of a coordinate (rad or m) in one continuation step: far below the 2π by which an
angle could jump without Newton's method noticing."""

_SMALLEST_STEP = 2.0**-40
"""The shortest continuation step, as a fraction of ``max_step``, before the continuation gives up."""


def _tangent(constraints, q: np.ndarray, angle: float) -> np.ndarray:
    """dq/dφ at one position (k,), from ``Φ_q q' = −Φ_φ``; zeros where the Jacobian is singular."""
    slope, _ = rates(constraints, q[:, None], np.array([angle]), 1.0, 0.0, 1)
    assert slope is not None
    return slope[:, 0] if np.all(np.isfinite(slope)) else np.zeros_like(q)


def _continue(constraints, guess, phi, tol, max_iter, max_step):
    """Continuation from the first crank angle on, with a predictor and step control.

    Each step predicts the solution along the branch's tangent (at the start, from the differentiated
    constraints; then the secant of the last step), corrects it by Newton's method, and accepts it
    only if the correction is small against the step (at most a tenth of ``h·(1 + |q'|)``) and no
    coordinate changed by more than 0.5 (rad or m); otherwise it halves the step. Near a change point, where another branch crosses this one at an angle, the
    other branch is about ``h`` away and the predictor's error is of order ``h²``, so a short enough step
    stays on the branch it started on; near a limit of assembly, where the branch turns steeply, the
    steps shorten likewise. Steps grow back (doubling) up to ``max_step``.
    """
    q = np.empty((guess.size, phi.size))
    angle = float(phi[0])
    current, iterations = _newton(constraints, guess[:, None], phi[:1], tol, max_iter)
    current = current[:, 0]
    slope = _tangent(constraints, current, angle)
    q[:, 0] = current
    step = max_step
    for i in range(1, phi.size):
        target = float(phi[i])
        while angle != target:
            h = float(np.clip(target - angle, -step, step))
            here = target if abs(target - angle) <= step else angle + h
            h = here - angle
            predicted = current + slope * h
            try:
                solved, used = _newton(constraints, predicted[:, None], np.array([here]), tol, max_iter)
                corrected = solved[:, 0]
                accepted = bool(np.max(np.abs(corrected - predicted)) <= 0.1 * abs(h) * (1.0 + np.max(np.abs(slope)))
                                and np.max(np.abs(corrected - current)) <= _LARGEST_CHANGE)
            except AssemblyError:
                accepted, used, corrected = False, 0, predicted
            if not accepted and step > _SMALLEST_STEP * max_step:
                step *= 0.5
                continue
            if not accepted and np.any(corrected is predicted):
                raise AssemblyError("the continuation cannot follow the branch (no assembly, or a singular "
                                    "position where the branch ends)", np.array([here]))
            slope = (corrected - current) / h
            angle, current = here, corrected
            iterations = max(iterations, used)
            step = min(max_step, 2.0 * step)
        q[:, i] = current
    return q, iterations


def solve_constraints(constraints: Constraints, guess: ArrayLike, phi: ArrayLike, omega: ArrayLike = 1.0,
                      alpha: ArrayLike = 0.0, order: int = 2,
                      tol: float = 1e-13, max_iter: int = 50, max_step: float = np.radians(2.0)) -> GenericSolution:
    """Solve the constraint equations Φ(q, φ) = 0 by Newton's method, with exact derivatives.

    Parameters
    ----------
    constraints : callable
        ``constraints(q, phi) -> sequence of k residuals``; ``q`` is a sequence of k arrays
        (the unknowns), ``phi`` the crank angles. Numpy operations only (see
        :class:`~mechanisms.jet.Jet`).
    guess : array_like, shape (k,) or (k, n)
        Starting values. Shape (k,): the solution is continued position by position from the
        first crank angle, in sub-steps of at most ``max_step``, so the branch of the guess is
        kept (order ``phi`` along the motion). Shape (k, n): one guess per position, all
        solved at once.
    phi : array_like, shape (n,)
        Crank angles φ (rad).
    omega, alpha : float or array_like
        Crank angular velocity φ_t (1/s) and acceleration φ_tt (1/s²).
    order : int
        0, 1 or 2.
    tol : float
        Newton stops when every step is below ``tol·(1 + |q|)``.
    max_iter : int
        Iterations allowed per solve before :class:`AssemblyError`.
    max_step : float
        Largest crank-angle step (rad) of the continuation.

    Returns
    -------
    GenericSolution

    Notes
    -----
    Positions: ``q ← q − Φ_q⁻¹ Φ``. Velocities: ``Φ_q q_t = −Φ_φ φ_t``. Accelerations: the
    constraints differentiated twice along the motion, ``Φ_q q_tt = −(d²Φ/dt²)|_{q_tt = 0}``
    (chapter 2). All derivatives of Φ come from :class:`~mechanisms.jet.Jet`, exactly.
    """
    order = require_order(order)
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    guess = np.asarray(guess, dtype=float)
    if guess.ndim == 2:
        q, iterations = _newton(constraints, guess.copy(), phi, tol, max_iter)
    else:
        q, iterations = _continue(constraints, guess, phi, tol, max_iter, max_step)
    residual, jac = _jacobian(constraints, q, phi)
    q_t, q_tt = rates(constraints, q, phi, omega, alpha, order, jac)
    return GenericSolution(q, q_t, q_tt, iterations, float(np.max(np.abs(residual))))


def newton_history(constraints: Constraints, guess: ArrayLike, phi: ArrayLike,
                   steps: int = 6) -> list[tuple[np.ndarray, float]]:
    """Newton's iterations one by one, for teaching: ``[(q, largest |Φ|), …]`` from the guess on.

    Parameters
    ----------
    constraints : callable
        As for :func:`solve_constraints`.
    guess : array_like, shape (k,)
        The starting values of the unknowns.
    phi : float
        One crank angle (rad).
    steps : int
        How many iterations to make (no stopping test: watch the residual fall).
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    q = np.asarray(guess, dtype=float).reshape(-1, 1)
    history = []
    for _ in range(steps + 1):
        residual, jac = _jacobian(constraints, q, phi)
        history.append((q[:, 0].copy(), float(np.max(np.abs(residual)))))
        q = q - np.linalg.solve(jac, residual[..., None])[..., 0].T
    return history


def solve_generic(mechanism: Mechanism, phi: ArrayLike, omega: ArrayLike = 1.0, alpha: ArrayLike = 0.0,
                  order: int = 2, guess: ArrayLike | None = None,
                  tol: float = 1e-13) -> GenericSolution:
    """Solve a mechanism's own constraint equations with :func:`solve_constraints`.

    The guess defaults to the closed-form solution at the first crank angle, continued from
    there (so the same branch is followed), or pass ``guess`` of shape (k,) or (k, n).
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    if guess is None:
        start = mechanism.solve(phi[:1], omega, alpha, order=0)
        guess = np.array([c.value[0] for c in mechanism.coordinates(start)], dtype=float)
    return solve_constraints(mechanism.constraints, guess, phi, omega, alpha, order, tol=tol)
