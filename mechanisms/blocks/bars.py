"""Joints held by bars, found together by Newton's method: the groups with no closed form.

A class III Assur group (three joints, four links, six pairs) cannot be solved joint after joint:
its joints must be found together. Each bar says that two joints keep their distance,

    Φ = (|r_a − r_b|² − L²) / (2L) = 0      (≈ |r_a − r_b| − L, in m),

and the k joints of the group have 2k coordinates q for 2k bars. Newton's method solves
``Φ_q Δq = −Φ`` with the Jacobian Φ_q (row of a bar: ``(r_a − r_b)/L`` in the columns of a, its
negative in those of b). The assembly mode is the one of the user's guess: the solution is
continued from the guess's crank angle in steps of at most 2°, and every requested position
starts from the nearest step, so a position is never taken from another mode. A crank angle is a
crank position: 370° is solved as 10°, each position at its angle nearest the guess's (within half a
turn of it, or a turn further round where the continuation reaches only that side), so the work never
grows with the size of the angles asked for.

Velocities and accelerations are linear: differentiating Φ along the motion,

    (r_a − r_b)·(v_a − v_b) = 0,    (r_a − r_b)·(a_a − a_b) + |v_a − v_b|² = 0,

the same matrix Φ_q with the known joints' terms on the right.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

import numpy as np

from ..core.angles import wrap_angle
from ..core.errors import AssemblyError
from ..core.motion import PointMotion

__all__ = ["BarGroup", "solve_bars", "CONTINUATION_STEP"]

CONTINUATION_STEP = math.radians(2.0)
"""The largest crank-angle step (rad) of the continuation from the guess."""

_ITERATIONS = 40
_SINGULAR = 1e-9
"""|det| of the Jacobian scaled to unit rows below which the group is at a singular position."""


@dataclass(frozen=True)
class BarGroup:
    """The joints of a group of bars over the crank positions.

    Attributes
    ----------
    points : dict of str to PointMotion
        Each joint of the group (m, m/s, m/s²).
    singular : ndarray of bool
        True where the Jacobian is singular (the group is at a limit of assembly or can move
        without the crank): velocities and accelerations are ``nan`` there.
    """

    points: dict[str, PointMotion]
    singular: np.ndarray


def _unknown_index(joints: Sequence[str]) -> dict[str, int]:
    return {name: i for i, name in enumerate(joints)}


def _residual_and_jacobian(x: np.ndarray, known: Mapping[str, np.ndarray], index: Mapping[str, int],
                           bars: Sequence[tuple[str, str, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Φ (n, m) and Φ_q (n, m, 2k) at the unknowns q (n, k) complex."""
    n, k = x.shape
    residual = np.empty((n, len(bars)))
    jacobian = np.zeros((n, len(bars), 2 * k))
    for row, (a, b, length) in enumerate(bars):
        ra = x[:, index[a]] if a in index else known[a]
        rb = x[:, index[b]] if b in index else known[b]
        d = ra - rb
        residual[:, row] = ((np.abs(d) - length) * (np.abs(d) + length)) / (2.0 * length)
        gradient = d / length
        if a in index:
            jacobian[:, row, 2 * index[a]] = gradient.real
            jacobian[:, row, 2 * index[a] + 1] = gradient.imag
        if b in index:
            jacobian[:, row, 2 * index[b]] -= gradient.real
            jacobian[:, row, 2 * index[b] + 1] -= gradient.imag
    return residual, jacobian


def _newton(x: np.ndarray, known: Mapping[str, np.ndarray], index: Mapping[str, int],
            bars: Sequence[tuple[str, str, float]], scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Newton's iterations on every position at once; returns (x, converged mask)."""
    x = x.copy()
    converged = np.zeros(x.shape[0], dtype=bool)
    for _ in range(_ITERATIONS):
        residual, jacobian = _residual_and_jacobian(x, known, index, bars)
        with np.errstate(all="ignore"):
            try:
                step = np.linalg.solve(jacobian, -residual[..., None])[..., 0]
            except np.linalg.LinAlgError:
                step = np.stack([np.linalg.lstsq(j, -r, rcond=None)[0] for j, r in zip(jacobian, residual)])
        step = np.where(np.isfinite(step), step, 0.0)
        x += step[:, 0::2] + 1j * step[:, 1::2]
        size = np.max(np.abs(step), axis=1)
        converged = (size <= 1e-15 * scale) | ((size <= 1e-9 * scale) & (np.max(np.abs(residual), axis=1)
                                                                           <= 1e-14 * scale))
        if converged.all():
            break
    residual, _ = _residual_and_jacobian(x, known, index, bars)
    converged = np.max(np.abs(residual), axis=1) <= 1e-12 * scale
    return x, converged


def _continuation_grid(start: float, low: float, high: float) -> np.ndarray:
    """Crank angles from ``start`` down to ``low`` and up to ``high`` in steps ≤ CONTINUATION_STEP, ``start`` first."""
    up = math.ceil(max(high - start, 0.0) / CONTINUATION_STEP)
    down = math.ceil(max(start - low, 0.0) / CONTINUATION_STEP)
    upward = start + (high - start) * np.arange(1, up + 1) / max(up, 1)
    downward = start - (start - low) * np.arange(1, down + 1) / max(down, 1)
    return np.concatenate(([start], upward, downward))


def _continuation(known_at: Callable[[np.ndarray], Mapping[str, np.ndarray]], index: Mapping[str, int],
                  bars: Sequence[tuple[str, str, float]], scale: float, joints: Sequence[str],
                  guess: Sequence[complex], guess_angle: float, low: float,
                  high: float) -> tuple[np.ndarray, np.ndarray]:
    """The group continued from the guess down to ``low`` and up to ``high`` (rad) in steps ≤ CONTINUATION_STEP,
    each way until Newton's method fails: the crank angles reached and the joints there (complex, m)."""
    grid = _continuation_grid(guess_angle, low, high)
    grid_known = known_at(grid)
    solved = np.empty((grid.size, len(joints)), dtype=complex)
    ok = np.zeros(grid.size, dtype=bool)
    up = int(np.sum(grid > guess_angle)) if grid.size > 1 else 0
    start = np.asarray(guess, dtype=complex)
    for path in (range(0, up + 1), [0, *range(up + 1, grid.size)]):
        current = start
        for i in path:
            here = {name: np.atleast_1d(values[i:i + 1]) for name, values in grid_known.items()}
            x, converged = _newton(current[None, :], here, index, bars, scale)
            if not converged[0]:
                break
            solved[i], ok[i] = x[0], True
            current = x[0]
        if not ok[0]:
            break
    if not ok[0]:
        raise AssemblyError(f"the group of joints {', '.join(joints)} does not assemble near the guess",
                            angles=[guess_angle])
    return grid[ok], solved[ok]


def solve_bars(known_at: Callable[[np.ndarray], Mapping[str, np.ndarray]], known: Mapping[str, PointMotion],
               joints: Sequence[str], bars: Sequence[tuple[str, str, float]], guess: Sequence[complex],
               guess_angle: float, phi: np.ndarray, order: int) -> BarGroup:
    """Find joints held by bars, continued from a guess; exact rates from the linear equations.

    Parameters
    ----------
    known_at : callable
        ``known_at(angles)`` → positions (m, complex arrays) of the known joints the bars name, at
        any crank angles: the continuation visits angles between the guess and the positions.
    known : mapping of str to PointMotion
        The known joints at the crank positions ``phi`` (m, m/s, m/s²), up to ``order``.
    joints : sequence of str
        The k joints to find.
    bars : sequence of (str, str, float)
        2k bars: two joints and their distance (m).
    guess : sequence of complex
        The joints' positions near the assembly mode wanted, at ``guess_angle`` (m).
    guess_angle : float
        Crank angle of the guess (rad).
    phi : ndarray
        The crank angles of the positions (rad).
    order : int
        0, 1 or 2.

    Returns
    -------
    BarGroup

    Raises
    ------
    AssemblyError
        Where Newton's method finds no position of the group (it does not assemble there, or the
        continuation from the guess cannot reach that crank angle).
    """
    index = _unknown_index(joints)
    phi = np.asarray(phi, dtype=float)
    scale = max(length for _, _, length in bars)
    flat = phi.reshape(-1)
    n = flat.size
    if n == 0:
        empty = np.zeros(phi.shape, dtype=complex)
        return BarGroup({j: PointMotion(empty, *([empty] * order)) for j in joints}, np.zeros(phi.shape, bool))
    # 1. each crank position at its angle nearest the guess's, in (guess − π, guess + π]: 370° is the crank
    #    position of 10°, and the continuation never walks a turn to reach it
    reduced = guess_angle + wrap_angle(flat - guess_angle)
    low, high = float(reduced.min()), float(reduced.max())
    reached, solved = _continuation(known_at, index, bars, scale, joints, guess, guess_angle, low, high)
    # a position beyond the continuation's reach on one side may be reached on the other, a turn away
    # (a group that assembles over [−17°, 213°] from a guess at 0° has 200° there, not at −160°)
    beyond = (reduced < reached.min() - CONTINUATION_STEP) | (reduced > reached.max() + CONTINUATION_STEP)
    if beyond.any():
        other = np.where(reduced > guess_angle, reduced - 2.0 * math.pi, reduced + 2.0 * math.pi)
        wider_low, wider_high = min(low, float(other[beyond].min())), max(high, float(other[beyond].max()))
        if (wider_low < low and reached.min() <= low + 1e-12) or (wider_high > high and reached.max() >= high - 1e-12):
            reached, solved = _continuation(known_at, index, bars, scale, joints, guess, guess_angle,
                                            wider_low, wider_high)
            inside = (other >= reached.min() - CONTINUATION_STEP) & (other <= reached.max() + CONTINUATION_STEP)
            reduced = np.where(beyond & inside, other, reduced)
    # 2. each position from the nearest continued step
    nearest = np.abs(reduced[:, None] - reached[None, :]).argmin(axis=1)
    too_far = np.abs(reduced - reached[nearest]) > CONTINUATION_STEP
    where_known = {name: np.asarray(m.value).reshape(-1) for name, m in known.items()}
    x, converged = _newton(solved[nearest], where_known, index, bars, scale)
    failed = too_far | ~converged
    if failed.any():
        raise AssemblyError(f"the group of joints {', '.join(joints)} does not assemble (Newton's method found no "
                            "position continued from the guess)", angles=flat[failed])
    # 3. rates: J v = −(known terms), J a = −(known terms) − |v_a − v_b|²/L
    _, jacobian = _residual_and_jacobian(x, where_known, index, bars)
    rows = jacobian / np.linalg.norm(jacobian, axis=2, keepdims=True)
    with np.errstate(all="ignore"):
        singular = np.abs(np.linalg.det(rows)) < _SINGULAR
    points = {}
    values = [x[:, i].reshape(phi.shape) for i in range(len(joints))]
    if order == 0:
        return BarGroup({j: PointMotion(v) for j, v in zip(joints, values)}, singular.reshape(phi.shape))
    safe = np.where(singular[:, None, None], np.eye(jacobian.shape[1]), jacobian)

    def rates(derivative: Callable[[str], np.ndarray], extra: np.ndarray | None) -> np.ndarray:
        rhs = np.zeros((n, len(bars)))
        for row, (a, b, length) in enumerate(bars):
            ra = x[:, index[a]] if a in index else where_known[a]
            rb = x[:, index[b]] if b in index else where_known[b]
            d = (ra - rb) / length
            moving = (0 if a in index else derivative(a)) - (0 if b in index else derivative(b))
            rhs[:, row] = -(np.conj(d) * moving).real
        if extra is not None:
            rhs -= extra
        with np.errstate(all="ignore"):
            solution = np.linalg.solve(safe, rhs[..., None])[..., 0]
        result = solution[:, 0::2] + 1j * solution[:, 1::2]
        result[singular] = np.nan
        return result

    velocity = rates(lambda name: np.asarray(known[name].d1).reshape(-1), None)
    if order == 1:
        for i, j in enumerate(joints):
            points[j] = PointMotion(values[i], velocity[:, i].reshape(phi.shape))
        return BarGroup(points, singular.reshape(phi.shape))
    square = np.zeros((n, len(bars)))
    for row, (a, b, length) in enumerate(bars):
        va = velocity[:, index[a]] if a in index else np.asarray(known[a].d1).reshape(-1)
        vb = velocity[:, index[b]] if b in index else np.asarray(known[b].d1).reshape(-1)
        square[:, row] = np.abs(va - vb) ** 2 / length
    acceleration = rates(lambda name: np.asarray(known[name].d2).reshape(-1), square)
    for i, j in enumerate(joints):
        points[j] = PointMotion(values[i], velocity[:, i].reshape(phi.shape), acceleration[:, i].reshape(phi.shape))
    return BarGroup(points, singular.reshape(phi.shape))
