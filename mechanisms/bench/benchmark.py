"""Layer 6: the benchmark — time per position against error, side by side, in one process.

``python -m mechanisms bench`` runs every method the book compares (chapter 9) on the same
mechanisms and crank angles and reports, for each, the time per position (best of R runs) and
the largest error against a high-accuracy reference:

* ``closed form`` — :meth:`~mechanisms.base.Mechanism.solve` at ``order`` 0, 1 and 2;
* ``newton`` — the generic solver (:func:`~mechanisms.verify.solve_constraints`), all positions
  at once, started from the closed-form solution 1° earlier in the crank angle (as a
  continuation over a 1° grid would start it), at several tolerances;
* ``central difference`` — velocities (order 1) and accelerations (order 2) from positions of
  the closed form by :func:`~mechanisms.verify.central_difference`, at several steps h;
* ``memory floor`` — copying as many bytes as the closed form returns at that order, into
  newly allocated memory, in the same run: no method that returns its results can beat it;
* peers, when installed (``pip install mechanisms[bench]``): pylinkage's ``step()`` and its
  numba-compiled ``step_fast()`` on the four-bar.

The reference is the solution of the mechanism's own constraint equations by Newton's method in
extended precision (``numpy.longdouble``, 64-bit mantissa on x86-64), polished from the closed
form and differentiated exactly with jets (:mod:`mechanisms.verify.jet`): its error is about 1e-19,
a thousand times below the double-precision errors it measures, and it shares no formula with
the closed forms.
"""

from __future__ import annotations

import datetime
import json
import math
import os
import platform
import time
import warnings
from typing import Any, Callable, Iterable, NamedTuple, Sequence, cast

import numpy as np
from numpy.typing import ArrayLike

from ..core.motion import AngleMotion, Motion
from ..linkages.base import Mechanism, Solution, registry
from ..core.errors import SingularPositionWarning
from ..linkages.composed import Linkage
from ..linkages.chunks import BLOCK
from ..linkages.four_bar import FourBar, _pqf, half_angle_formula, stable_formula
from ..linkages.groups import RRR, Crank
from ..linkages.linkage_file import load_linkage
from ..verify import central_difference, solve_constraints
from ..verify.newton import jacobian, newton_steps, rates

__all__ = [
    "benchmark_mechanisms",
    "setting_label",
    "reference",
    "Reference",
    "coordinate_errors",
    "jacobian_condition",
    "reproducible_reference",
    "reproducible_jacobian_condition",
    "logspace",
    "rounded_once",
    "reproducible_coupler_angles",
    "output_bytes",
    "best_time",
    "run",
    "format_text",
    "format_json",
    "pylinkage_available",
    "DEFAULT_SIZES",
    "NEWTON_TOLERANCES",
    "DIFFERENCE_STEPS",
    "CHECK_STEPS",
    "RESULT_KEYS",
]

DEFAULT_SIZES = (1000, 100_000, 1_000_000)
NEWTON_TOLERANCES = (1e-2, 1e-4, 1e-8, 1e-14)
DIFFERENCE_STEPS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
RESULT_KEYS = ("mechanism", "method", "order", "parameter", "n", "seconds", "ns_per_position", "max_error")
REFERENCE_SAMPLE = 100_000
"""The errors are measured on at most this many positions, evenly spread over those computed."""
LOOP_LIMIT = 100_000
"""pylinkage's Python loop ``step()`` is timed on at most this many positions (it takes ~10 µs each)."""
OMEGA = 1.0
"""Crank speed φ_t (1/s) of every run: velocities in 1/s are then derivatives in φ."""


def benchmark_mechanisms() -> dict[str, Mechanism]:
    """The mechanisms of the benchmark, by name.

    The classes that set ``benchmark``, at their examples, by command-line name: the four-bar is
    the peers' one (frame |OC| = 4, crank 1, coupler 3.5, rocker 3: a crank-rocker), the
    crank-slider has crank 1, rod 3.5 and offset 0.5, the slotted lever crank 1 and the lever's
    pivot at (0, 2) (oscillating). Then two composed linkages (chapter 6), solved group after group
    by :class:`~mechanisms.linkages.composed.Linkage`: ``four-bar (composed)``, the same four-bar
    built from its crank and one RRR group (what composition costs against the hand-written
    class), and ``watt-six-bar``, the shipped linkage file of that name (a crank, two RRR groups
    and an RRP group: ten coordinates).
    """
    table: dict[str, Mechanism] = {name: cls.example() for name, cls in registry.items() if cls.benchmark}
    four_bar = FourBar.example()
    table["four-bar (composed)"] = Linkage(
        {"O": 0.0, "C": complex(*four_bar.frame)},
        [Crank("O", "A", length=four_bar.crank),
         RRR("B", "A", "C", "coupler", "rocker", four_bar.coupler, four_bar.rocker, four_bar.branch)],
        name="four-bar (composed)")
    table["watt-six-bar"] = load_linkage("watt-six-bar")
    return table


# --- the reference ------------------------------------------------------------------------------

class Reference(NamedTuple):
    """The reference coordinates of :func:`reference`: each of shape (k, n), row i the i-th coordinate
    of ``mechanism.coordinates`` (constraint order), column j the j-th crank angle; ``numpy.longdouble``."""

    q: np.ndarray
    """Positions q (rad or m)."""
    q_t: np.ndarray
    """Velocities q_t (1/s or m/s)."""
    q_tt: np.ndarray
    """Accelerations q_tt (1/s² or m/s²)."""


def reference(mechanism: Mechanism, phi: ArrayLike, omega: float = OMEGA, alpha: float = 0.0,
              iterations: int = 3) -> Reference:
    """The coordinates q with q_t and q_tt in extended precision, from the constraint equations.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates (``mechanism.coordinates``).
    phi : array_like
        Crank angles φ (rad), taken as exact (double or extended precision).
    omega, alpha : float
        Crank speed φ_t (1/s) and acceleration φ_tt (1/s²).
    iterations : int
        Newton iterations in ``numpy.longdouble`` from the double-precision closed form.

    Returns
    -------
    Reference
        The named triple ``(q, q_t, q_tt)``, each of shape (k, n), dtype longdouble.

    Notes
    -----
    Newton's method converges quadratically: from the closed form's 1e-15 two steps reach the
    extended precision's round-off (about 1e-19 relative); the third is a margin. The closed
    form only selects the branch: the result is the root of Φ(q, φ) = 0 next to it. Velocities
    and accelerations come from ``Φ_q q_t = −Φ_φ φ_t`` and the twice-differentiated constraints
    (chapter 2), with exact derivatives (jets) in extended precision: the generic solver's own Newton
    steps and rates (:mod:`mechanisms.verify.newton`), in ``numpy.longdouble``.
    """
    phi_ld = np.atleast_1d(np.asarray(phi)).astype(np.longdouble)
    phi = phi_ld.astype(float)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        start = mechanism.solve(phi, omega, alpha, order=0)
    q = np.array([np.asarray(c.value, dtype=np.longdouble) for c in mechanism.coordinates(start)])
    q = newton_steps(mechanism.constraints, q, phi_ld, iterations)
    q_t, q_tt = rates(mechanism.constraints, q, phi_ld, np.longdouble(omega), np.longdouble(alpha), 2)
    assert q_t is not None and q_tt is not None   # order 2
    return Reference(q, q_t, q_tt)


def jacobian_condition(mechanism: Mechanism, phi: ArrayLike) -> np.ndarray:
    """The condition number of the constraint Jacobian Φ_q at the closed-form positions.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates.
    phi : array_like
        Crank angles φ (rad).

    Returns
    -------
    ndarray
        ``cond₂(Φ_q)``, the largest over the smallest singular value of Φ_q, at each position: how
        much a relative error of the constraint residual can grow in the coordinates; ``inf`` at a
        singular position (the end of a crank's range, a rod perpendicular to its guide, a change
        point). It depends on the units of the coordinates when they mix angles
        and lengths (chapter 9).
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        solution = mechanism.solve(phi, order=0)
    q = np.array([np.asarray(c.value, dtype=float) for c in mechanism.coordinates(solution)])
    _, matrix = jacobian(mechanism.constraints, q, phi)
    singular_values = np.linalg.svd(matrix, compute_uv=False)
    with np.errstate(divide="ignore"):
        return singular_values[..., 0] / singular_values[..., -1]


def _wrapped(difference: np.ndarray, angle: bool) -> np.ndarray:
    if not angle:
        return difference
    return (difference + np.pi) % (2.0 * np.pi) - np.pi


def coordinate_errors(mechanism: Mechanism, q: np.ndarray | None, q_t: np.ndarray | None, q_tt: np.ndarray | None,
                      ref: Sequence[np.ndarray]) -> tuple[float, float, float]:
    """Largest errors of coordinates, velocities and accelerations against :func:`reference`.

    ``q``, ``q_t``, ``q_tt`` are arrays of shape (k, n), one row per coordinate of
    ``mechanism.coordinates`` (or ``None`` if not computed); angles
    are compared modulo 2π. Returns ``(position, velocity, acceleration)`` errors (rad or m,
    per second, per second squared), ``nan`` for what was not computed.
    """
    angles = _angle_rows(mechanism)
    out: list[float] = []
    for mine, theirs, wrap in ((q, ref[0], True), (q_t, ref[1], False), (q_tt, ref[2], False)):
        if mine is None:
            out.append(math.nan)
            continue
        worst = 0.0
        for row in range(len(theirs)):
            diff = np.asarray(mine[row], dtype=np.longdouble) - theirs[row]
            diff = _wrapped(diff, wrap and angles[row])
            worst = max(worst, float(np.max(np.abs(diff))))
        out.append(worst)
    return out[0], out[1], out[2]


def _angle_rows(mechanism: Mechanism) -> tuple[bool, ...]:
    """Which of the coordinates are angles (the others are lengths), from a solution at one crank angle."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        sample = mechanism.solve(np.array([0.5]), order=0)
    return tuple(isinstance(c, AngleMotion) for c in mechanism.coordinates(sample))


def _coordinates(mechanism: Mechanism, solution: Solution, order: int) -> list[Any]:
    coords = mechanism.coordinates(solution)
    parts: list[Any] = [np.array([c.value for c in coords])]
    for k in (1, 2):
        parts.append(np.array([c.derivatives()[k] for c in coords]) if order >= k else None)
    return parts


# --- timing ---------------------------------------------------------------------------------------

def best_time(task: Callable[[], object], repeat: int) -> float:
    """The shortest of ``repeat`` wall-clock times of ``task()`` (s); runs over 2 s are not repeated."""
    best = math.inf
    for _ in range(max(1, repeat)):
        start = time.perf_counter()
        task()
        elapsed = time.perf_counter() - start
        best = min(best, elapsed)
        if elapsed > 2.0:
            break
    return best


def output_bytes(solution: Solution) -> int:
    """Bytes of the arrays a solution holds (angles, points, sliders), each array counted once.

    Not counted, because they cost no memory traffic: the crank angles passed in, and views of one
    number (a zero stride: a fixed pivot, its zero velocity and acceleration, a constant crank
    speed), which take no memory.
    """
    seen, total = set(), 0
    skip = {np.asarray(solution.phi).__array_interface__["data"][0]}
    groups: list[Motion] = [solution.angle(n) for n in solution.angle_names]
    groups += [solution.point(n) for n in solution.point_names]
    groups += [solution.slider(n) for n in solution.slider_names]
    for motion in groups:
        for array in motion.derivatives():
            if array is None:
                continue
            array = np.asarray(array)
            address = array.__array_interface__["data"][0]
            if address in seen or address in skip or 0 in array.strides:
                continue
            seen.add(address)
            total += array.nbytes
    return total


def _result(mechanism: str, method: str, order: int, parameter: Any, n: int, seconds: float,
            error: float | None) -> dict:
    return {"mechanism": mechanism, "method": method, "order": order, "parameter": parameter, "n": int(n),
            "seconds": seconds, "ns_per_position": seconds / n * 1e9,
            "max_error": None if error is None or not math.isfinite(error) else error}


def _sample(n: int) -> np.ndarray:
    return np.unique(np.linspace(0, n - 1, min(n, REFERENCE_SAMPLE)).astype(int))


def _bench_mechanism(name: str, mechanism: Mechanism, n: int, repeat: int) -> list[dict]:
    phi = np.arange(n) * (2.0 * math.pi / n)
    sample = _sample(n)
    ref = reference(mechanism, phi[sample])
    results = []
    # the closed form, and the memory floor of each order
    for order in (0, 1, 2):
        seconds = best_time(lambda: mechanism.solve(phi, OMEGA, order=order), repeat)
        solution = mechanism.solve(phi, OMEGA, order=order)
        q = _coordinates(mechanism, solution, order)
        q0, q1, q2 = (None if a is None else a[:, sample] for a in q)
        errors = coordinate_errors(mechanism, q0, q1, q2, ref)
        results.append(_result(name, "closed form", order, None, n, seconds, max(errors[:order + 1])))
        buffer = np.ones(output_bytes(solution), dtype=np.uint8)
        seconds = best_time(buffer.copy, repeat)
        results.append(_result(name, "memory floor", order, buffer.nbytes, n, seconds, None))
        del solution, buffer
    # Newton's method on the constraint equations, from the solution 1° earlier
    guess = np.array([c.value for c in mechanism.coordinates(mechanism.solve(phi - math.radians(1.0), order=0))])
    for tol in NEWTON_TOLERANCES:
        def newton():
            return solve_constraints(mechanism.constraints, guess, phi, OMEGA, 0.0, order=2, tol=tol)
        seconds = best_time(newton, repeat)
        g = newton()
        errors = coordinate_errors(mechanism, g.q[:, sample], g.q_t[:, sample], g.q_tt[:, sample], ref)
        results.append(_result(name, "newton", 2, tol, n, seconds, max(errors)))
    # numerical differentiation of the closed-form positions
    angle_rows = _angle_rows(mechanism)
    for order in (1, 2):
        for h in DIFFERENCE_STEPS:
            def difference():
                return _central_differences(mechanism, phi, h, order, angle_rows)
            seconds = best_time(difference, repeat)
            values = difference()[:, sample]
            error = max(float(np.max(np.abs(values[row] - ref[order][row]))) for row in range(len(angle_rows)))
            results.append(_result(name, "central difference", order, h, n, seconds, error))
    return results


def _central_differences(mechanism: Mechanism, phi: np.ndarray, step: float, derivative: int,
                         angle_rows: Sequence[bool],
                         positions: Callable[[np.ndarray], np.ndarray] | None = None) -> np.ndarray:
    """Central differences of every coordinate, shape (k, n): velocities or accelerations.

    Each shifted crank angle is solved once for all k coordinates, as a program would: velocities
    cost two solutions of positions (at φ ± h), accelerations three (also at φ). Each row is
    :func:`~mechanisms.verify.central_difference` of its coordinate (angles wrapped). ``positions``
    gives the coordinates (k, n) at crank angles (rad); by default the closed form's.
    """
    if positions is None:
        def positions(shifted: np.ndarray) -> np.ndarray:
            return np.array([c.value for c in mechanism.coordinates(mechanism.solve(shifted, OMEGA, order=0))])
    solve = positions
    solved: dict[int, np.ndarray] = {}     # −1, 0, +1: the solution at φ − h, φ, φ + h

    def row_function(row: int) -> Callable[[np.ndarray], np.ndarray]:
        def position(shifted: np.ndarray) -> np.ndarray:
            side = round(float(shifted.flat[0] - phi.flat[0]) / step)
            if side not in solved:
                solved[side] = solve(shifted)
            return solved[side][row]
        return position

    return np.array([central_difference(row_function(row), phi, OMEGA, step, derivative, angle=angle)
                     for row, angle in enumerate(angle_rows)])


# --- peers ------------------------------------------------------------------------------------------

def pylinkage_available() -> bool:
    """True if pylinkage (and numba, for ``step_fast``) can be imported."""
    try:
        import numba  # noqa: F401
        import pylinkage  # noqa: F401
    except ImportError:
        return False
    return True


def _pylinkage_four_bar(n: int):
    """pylinkage's four-bar with the benchmark's lengths; the crank turns 2π/n per step."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRRDyad
    from pylinkage.simulation import Linkage

    origin, pivot = Ground(0.0, 0.0, name="O"), Ground(4.0, 0.0, name="C")
    crank = Crank(anchor=origin, radius=1.0, angular_velocity=2.0 * math.pi / n, name="A")
    joint = RRRDyad(crank.output, pivot, distance1=3.5, distance2=3.0, name="B")
    return Linkage([origin, pivot, crank, joint], name="four-bar")


def _peer_error(mechanism: FourBar, points: np.ndarray, n: int) -> float:
    """Largest distance of pylinkage's joints A and B (rows 2 and 3) from the reference (m).

    After k + 1 steps of 2π/n its crank angle is (k + 1)·(2π/n): the reference is evaluated at
    that angle, in extended precision.
    """
    sample = _sample(points.shape[0])
    phi = (sample + 1).astype(np.longdouble) * np.longdouble(2.0 * math.pi / n)
    psi = reference(mechanism, phi)[0][0]
    ax, ay = mechanism.crank * np.cos(phi), mechanism.crank * np.sin(phi)
    bx, by = ax + mechanism.coupler * np.cos(psi), ay + mechanism.coupler * np.sin(psi)
    errors = (np.hypot(points[sample, 2, 0] - ax, points[sample, 2, 1] - ay),
              np.hypot(points[sample, 3, 0] - bx, points[sample, 3, 1] - by))
    return float(max(np.max(e) for e in errors))


def _bench_peers(mechanism: FourBar, n: int, repeat: int) -> list[dict]:
    results = []
    linkage = _pylinkage_four_bar(n)
    start = [c.position for c in linkage.components]
    linkage.step_fast(iterations=2)             # compile (or load numba's cache) before timing

    def fast():
        linkage.set_coords(start)
        return linkage.step_fast(iterations=n)

    seconds = best_time(fast, repeat)
    results.append(_result("four-bar", "pylinkage step_fast", 0, None, n, seconds, _peer_error(mechanism, fast(), n)))
    m = min(n, LOOP_LIMIT)
    loop = _pylinkage_four_bar(n)
    loop_start = [c.position for c in loop.components]

    def slow():
        loop.set_coords(loop_start)
        return np.array([[p if p[0] is not None else (math.nan, math.nan) for p in row]
                         for row in loop.step(iterations=m)], dtype=float)

    seconds = best_time(slow, repeat)
    results.append(_result("four-bar", "pylinkage step", 0, None, m, seconds, _peer_error(mechanism, slow(), n)))
    return results


# --- a family of four-bars ------------------------------------------------------------------------------

FAMILY_MEMBERS = 100_000
"""Members of the benchmark's family of four-bars (the family row)."""

FAMILY_POSITIONS = 360
"""Crank positions of each member in the family row."""

FAMILY_CHUNK = max(1, BLOCK // FAMILY_POSITIONS)
"""Members solved per call of a family of :class:`~mechanisms.linkages.four_bar.FourBar`: as many as make
:data:`~mechanisms.linkages.chunks.BLOCK` positions (91 × 360), so that a call's temporaries stay in the
processor's cache and their memory is reused by the next call. With 2000 members a call's arrays (11 MB each)
were given back to the system and taken again at every call, and the page faults cost two thirds of the time.
"""

PEER_FAMILY_MEMBERS = 500
"""Members of the same family that pylinkage solves, one linkage after another, to time its loop."""


def benchmark_family(members: int = FAMILY_MEMBERS, seed: int = 0) -> tuple[np.ndarray, ...]:
    """The family row's four-bars: the benchmark's crank-rocker (1, 3.5, 3, C = (4, 0) m) with each of L1, L2,
    L3 and x_C scaled by a factor from 0.95 to 1.05 (all crank-rockers that assemble at every angle)."""
    factors = np.random.default_rng(seed).uniform(0.95, 1.05, (4, members))
    return 1.0 * factors[0], 3.5 * factors[1], 3.0 * factors[2], 4.0 * factors[3]


def _pylinkage_member(crank: float, coupler: float, rocker: float, frame_x: float, positions: int):
    """One member of the family as a pylinkage linkage; the crank turns 2π/positions per step."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRRDyad
    from pylinkage.simulation import Linkage

    origin, pivot = Ground(0.0, 0.0, name="O"), Ground(frame_x, 0.0, name="C")
    arm = Crank(anchor=origin, radius=crank, angular_velocity=2.0 * math.pi / positions, name="A")
    joint = RRRDyad(arm.output, pivot, distance1=coupler, distance2=rocker, name="B")
    return Linkage([origin, pivot, arm, joint], name="four-bar")


def bench_family(members: int = FAMILY_MEMBERS, positions: int = FAMILY_POSITIONS, repeat: int = 3,
                 peers: bool = True) -> list[dict]:
    """The family row: ``members`` four-bars × ``positions`` crank angles, positions only, in ns per
    linkage-position; beside it pylinkage's numba solver looping over :data:`PEER_FAMILY_MEMBERS` members of
    the same family (building each linkage, as a loop over geometries does), when installed.

    The error column is the largest distance of B from the extended-precision reference over three members.
    """
    l1, l2, l3, xc = benchmark_family(members)
    phi = 2.0 * math.pi * np.arange(1, positions + 1) / positions      # pylinkage's angles after each step

    def ours():
        for lo in range(0, members, FAMILY_CHUNK):
            hi = lo + FAMILY_CHUNK
            FourBar(l1[lo:hi], l2[lo:hi], l3[lo:hi], (xc[lo:hi], 0.0), keep_side=True).solve(phi, order=0)

    seconds = best_time(ours, repeat)
    sample = FourBar(l1[:3], l2[:3], l3[:3], (xc[:3], 0.0), keep_side=True).solve(phi, order=0).point("B").value
    error = 0.0
    references = []
    for k in range(3):
        m = FourBar(float(l1[k]), float(l2[k]), float(l3[k]), (float(xc[k]), 0.0))
        psi = reference(m, phi)[0][0]
        b = m.crank * np.exp(1j * phi) + m.coupler * np.exp(1j * psi.astype(float))
        references.append(b)
        error = max(error, float(np.max(np.abs(sample[k] - b))))
    label = f"family {members}x{positions}"
    results = [_result(label, "closed form, family", 0, None, members * positions, seconds, error)]
    if peers and pylinkage_available():
        count = min(members, PEER_FAMILY_MEMBERS)
        _pylinkage_member(1.0, 3.5, 3.0, 4.0, positions).step_fast(iterations=2)   # compile numba's code first

        def loop():
            return [_pylinkage_member(float(l1[k]), float(l2[k]), float(l3[k]), float(xc[k]), positions)
                    .step_fast(iterations=positions) for k in range(count)]

        seconds = best_time(loop, repeat)
        solved = loop()
        peer_error = max(float(np.max(np.hypot(solved[k][:, 3, 0] - references[k].real,
                                               solved[k][:, 3, 1] - references[k].imag))) for k in range(3))
        results.append(_result(label, "pylinkage step_fast", 0, None, count * positions, seconds, peer_error))
    return results


# --- the whole run ------------------------------------------------------------------------------------

def machine_description() -> str:
    """The machine and software of a run, in one line."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:
        cpus = os.cpu_count() or 1
    return (f"{platform.machine()} {platform.processor() or ''} {cpus} CPU(s), {platform.system()}, "
            f"Python {platform.python_version()}, numpy {np.__version__}").replace("  ", " ")


def run(sizes: Iterable[int] = DEFAULT_SIZES, repeat: int = 3, mechanisms: Iterable[str] | None = None,
        peers: bool = True) -> dict:
    """Run the benchmark.

    Parameters
    ----------
    sizes : iterable of int
        Numbers of crank positions n.
    repeat : int
        Each time is the best of this many runs (R).
    mechanisms : iterable of str, optional
        Names from :func:`benchmark_mechanisms` (default: all three).
    peers : bool
        Also time pylinkage, if it is installed.

    Returns
    -------
    dict
        ``{"results": [...], "date", "machine", "reference", "notes"}``; each result has the keys
        of :data:`RESULT_KEYS` (``parameter``: Newton's tolerance, the difference step h in rad, or
        the floor's bytes; ``max_error``: rad, m and their time derivatives at ω = 1 1/s, or
        ``None`` for the floor).
    """
    table = benchmark_mechanisms()
    sizes = [int(n) for n in sizes]
    names = list(table) if mechanisms is None else list(mechanisms)
    results, notes = [], []
    peers = peers and pylinkage_available()
    if not peers:
        notes.append("pylinkage not timed: not installed (pip install 'mechanisms[bench]') or not asked for")
    for n in sizes:
        for name in names:
            results += _bench_mechanism(name, table[name], int(n), repeat)
        if peers and "four-bar" in names:
            results += _bench_peers(cast(FourBar, table["four-bar"]), int(n), repeat)
    if "four-bar" in names:
        # the family row: FAMILY_MEMBERS four-bars, fewer when the run's sizes are smaller (a quick run stays quick)
        results += bench_family(min(FAMILY_MEMBERS, max(sizes)), FAMILY_POSITIONS, repeat, peers)
    extended = np.finfo(np.longdouble).eps
    if extended >= np.finfo(float).eps:
        notes.append("numpy.longdouble is double precision on this machine: errors below ~1e-15 are not resolved")
    return {"results": results,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "machine": machine_description(),
            "reference": f"Newton's method in numpy.longdouble (eps = {float(extended):.1e}) on at most "
                         f"{REFERENCE_SAMPLE} positions per run",
            "notes": notes}


def _cell(value, fmt: str) -> str:
    return "—" if value is None else format(value, fmt)


def format_text(report: dict) -> str:
    """The benchmark as a plain-text table, one block per size and mechanism."""
    lines = [f"mechanisms bench — {report['date']} — {report['machine']}",
             f"reference: {report['reference']}; time: best of R runs"]
    lines += [f"note: {note}" for note in report["notes"]]
    header = f"{'method':<22}{'order':>6}{'parameter':>12}{'n':>10}{'ns/position':>14}{'max error':>12}"
    current: Any = None
    for r in report["results"]:
        key = (r["n"] if r["method"] != "pylinkage step" else current[0], r["mechanism"])
        if key != current:
            current = key
            lines += ["", f"{r['mechanism']}, n = {r['n']}", header]
        parameter = r["parameter"]
        parameter = "—" if parameter is None else (f"{parameter:.0e}" if isinstance(parameter, float)
                                                    else f"{parameter} B")
        lines.append(f"{r['method']:<22}{r['order']:>6}{parameter:>12}{r['n']:>10}"
                     f"{_cell(r['ns_per_position'], '.1f'):>14}{_cell(r['max_error'], '.1e'):>12}")
    return "\n".join(lines)


def format_json(report: dict) -> str:
    """The benchmark as JSON (the documented ``results`` and the run's date, machine and notes)."""
    return json.dumps(report, indent=1)


# --- studies for chapter 9 (small sizes, quick) ------------------------------------------------------

QUANTITIES = ("positions", "velocities", "accelerations")


def work_precision(mechanism: Mechanism, n: int = 2000, repeat: int = 5,
                   tolerances: Sequence[float] = NEWTON_TOLERANCES,
                   steps: Sequence[float] = (1e-1, 1e-3, 1e-5, 1e-7)) -> list[dict]:
    """Cost and error of every method for each quantity: the data of a work-precision diagram.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates.
    n : int
        Crank positions, evenly over a turn.
    repeat : int
        Best of this many runs.
    tolerances, steps : sequence of float
        Newton's tolerances; the steps h (rad) of the central differences.

    Returns
    -------
    list of dict
        ``{"method", "parameter", "quantity", "ns_per_position", "error"}``. Each method is timed
        at the order its quantity needs (positions: order 0 …); a central difference is charged the
        closed-form positions it differentiates, one solution for all coordinates per shifted crank
        angle: two (φ ± h) for velocities, three (φ ± h and φ) for accelerations.
    """
    phi = np.arange(n) * (2.0 * math.pi / n)
    ref = reference(mechanism, phi)
    rows = []

    def add(method, parameter, k, seconds, error):
        rows.append({"method": method, "parameter": parameter, "quantity": QUANTITIES[k],
                     "ns_per_position": seconds / n * 1e9, "error": error})

    for k in range(3):
        seconds = best_time(lambda: mechanism.solve(phi, OMEGA, order=k), repeat)
        q0, q1, q2 = _coordinates(mechanism, mechanism.solve(phi, OMEGA, order=k), k)
        errors = coordinate_errors(mechanism, q0, q1, q2, ref)
        add("closed form", None, k, seconds, errors[k])
    guess = np.array([c.value for c in mechanism.coordinates(mechanism.solve(phi - math.radians(1.0), order=0))])
    for tol in tolerances:
        for k in range(3):
            def newton():
                return solve_constraints(mechanism.constraints, guess, phi, OMEGA, 0.0, order=k, tol=tol)
            seconds = best_time(newton, repeat)
            g = newton()
            add("newton", tol, k, seconds, coordinate_errors(mechanism, g.q, g.q_t, g.q_tt, ref)[k])
    angles = _angle_rows(mechanism)
    for k in (1, 2):
        for h in steps:
            def difference():
                return _central_differences(mechanism, phi, h, k, angles)
            seconds = best_time(difference, repeat)
            values = difference()
            add("central difference", h, k, seconds,
                max(float(np.max(np.abs(values[r] - ref[k][r]))) for r in range(len(angles))))
    return rows


def reproducible_reference(mechanism: Mechanism, phi: ArrayLike) -> Reference:
    """:func:`reference` with the same bits on every machine: what a figure of round-off may plot.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates.
    phi : array_like
        Crank angles φ (rad), taken as exact.

    Returns
    -------
    Reference
        ``(q, q_t, q_tt)`` in ``numpy.longdouble``, each of shape (k, n), at φ_t = 1 1/s, φ_tt = 0.

    Notes
    -----
    :func:`reference` starts from the closed form, whose last bits depend on the processor (numpy
    picks its sine, cosine and arctangent by the processor's vector instructions), and so do the
    last bits of its extended-precision result. Here that result is rounded to single precision
    (24 bits: a value 1e-19 from a rounding boundary of single precision is practically never met) and
    polished again by three Newton steps in extended precision (2⁻²⁴ → 2⁻⁴⁸ → below 2⁻⁶⁴, then a
    margin), then differentiated exactly. Extended precision has no vector kernels in numpy: its
    arithmetic is the x87 unit's, its sine and cosine the C library's, the same on every x86-64
    processor. Rounded once to double, its positions are the exact ones correctly rounded (but for
    a value within 1e-19 of a rounding boundary of double precision), on every machine.
    """
    phi_ld = np.atleast_1d(np.asarray(phi)).astype(np.longdouble)
    start = reference(mechanism, phi_ld).q.astype(np.float32).astype(np.longdouble)
    q = newton_steps(mechanism.constraints, start, phi_ld, 3)
    q_t, q_tt = rates(mechanism.constraints, q, phi_ld, np.longdouble(OMEGA), np.longdouble(0.0), 2)
    assert q_t is not None and q_tt is not None   # order 2
    return Reference(q, q_t, q_tt)


def _singular_values_extended(matrix: np.ndarray) -> np.ndarray:
    """Singular values of the (…, k, k) matrices ``matrix`` (numpy.longdouble), largest first.

    One-sided Jacobi rotations (Hestenes) of the columns in extended precision, a fixed number of
    sweeps: only the x87 unit's arithmetic and square root, correctly rounded on every x86-64
    processor, so the result has the same bits on every machine (LAPACK's SVD runs on the BLAS
    library's kernels, chosen by processor). Jacobi keeps small singular values to relative
    accuracy, which is what a condition number near a singular position needs.
    """
    a = np.array(matrix, dtype=np.longdouble)
    k = a.shape[-1]
    one = np.longdouble(1)
    for _ in range(12):                     # quadratic convergence: ample for the k ≤ 10 of a linkage
        for i in range(k - 1):
            for j in range(i + 1, k):
                x, y = a[..., :, i], a[..., :, j]
                alpha, beta, gamma = (x * x).sum(-1), (y * y).sum(-1), (x * y).sum(-1)
                rotate = gamma != 0
                zeta = np.where(rotate, (beta - alpha) / np.where(rotate, 2 * gamma, one), one)
                t = np.where(rotate, np.where(zeta >= 0, one, -one) / (np.abs(zeta) + np.sqrt(one + zeta * zeta)), 0)
                c = one / np.sqrt(one + t * t)
                sn = c * t
                a[..., :, i], a[..., :, j] = (c[..., None] * x - sn[..., None] * y,
                                              sn[..., None] * x + c[..., None] * y)
    return -np.sort(-np.sqrt((a * a).sum(-2)), axis=-1)


def reproducible_jacobian_condition(mechanism: Mechanism, phi: ArrayLike) -> np.ndarray:
    """:func:`jacobian_condition` with the same bits on every machine: what a figure may plot.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates.
    phi : array_like
        Crank angles φ (rad), taken as exact; regular positions (the extended-precision positions
        of :func:`reproducible_reference` are found by Newton's method).

    Returns
    -------
    ndarray
        ``cond₂(Φ_q)`` at each position, double precision.

    Notes
    -----
    Near a singular position cond₂(Φ_q) amplifies the last bits of the positions: computed from the
    closed form, whose sines and cosines differ in their last bits from processor to processor,
    it differs too (relatively about ε_mach · cond). Here Φ_q is evaluated at the positions of
    :func:`reproducible_reference` in extended precision, its singular values found by Jacobi
    rotations in extended precision, and the quotient rounded once to double.
    """
    phi_ld = np.atleast_1d(np.asarray(phi)).astype(np.longdouble)
    q = reproducible_reference(mechanism, phi_ld).q
    _, matrix = jacobian(mechanism.constraints, q, phi_ld)
    singular_values = _singular_values_extended(matrix)
    with np.errstate(divide="ignore"):
        return np.asarray(singular_values[..., 0] / singular_values[..., -1], dtype=float)


def step_errors(mechanism: Mechanism, steps: Sequence[float], n: int = 360) -> dict[str, np.ndarray]:
    """Errors of central differences of positions rounded to double against the step h (rad).

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism with k unknown coordinates.
    steps : sequence of float
        Steps h (rad).
    n : int
        Crank positions, evenly over a turn.

    Returns
    -------
    dict
        ``{"velocities": …, "accelerations": …}``, the largest error over the ``n`` positions and the k
        coordinates for each step (1/s, m/s … and per second squared, at ω = 1 1/s).

    Notes
    -----
    The positions differentiated are the best double precision can hold: the exact ones rounded
    once (:func:`reproducible_reference`), each off by at most half a unit in its last place. Their
    round-off is the smallest any formula can reach, and it is the same on every machine, so the
    errors are too (the closed form's own positions differ in their last bits from processor to
    processor); they are measured against the exact derivatives in extended precision.
    """
    phi = np.arange(n) * (2.0 * math.pi / n)
    exact = reproducible_reference(mechanism, phi)
    angles = _angle_rows(mechanism)

    def rounded(shifted: np.ndarray) -> np.ndarray:
        return reproducible_reference(mechanism, shifted).q.astype(float)

    out = {}
    for k, name in ((1, "velocities"), (2, "accelerations")):
        errors = []
        for h in steps:
            values = _central_differences(mechanism, phi, h, k, angles, rounded)
            errors.append(max(float(np.max(np.abs(values[r] - exact[k][r]))) for r in range(len(angles))))
        out[name] = np.array(errors)
    return out


def logspace(start: float, stop: float, num: int) -> np.ndarray:
    """``numpy.logspace(start, stop, num)`` with the same bits on every machine: steps for a figure.

    Parameters
    ----------
    start, stop : float
        Exponents of the first and last value (powers of ten).
    num : int
        Number of values, evenly spaced in the exponent.

    Returns
    -------
    ndarray
        ``10**x`` for the ``num`` exponents x, in double precision.

    Notes
    -----
    numpy's double-precision power is chosen by the processor's vector instructions, and its last bit
    may differ from machine to machine; a step h that differs in its last bit gives other crank angles
    φ ± h and other round-off. Here the exponents and the powers are computed in extended precision
    (the C library's, the same on every x86-64 processor) and rounded once to double.
    """
    exponents = np.linspace(np.longdouble(start), np.longdouble(stop), num)
    return np.asarray(np.power(np.longdouble(10), exponents), dtype=float)


def rounded_once(function: Callable[..., np.ndarray]) -> Callable[..., np.ndarray]:
    """A numpy function of double-precision arguments, evaluated in extended precision and rounded once.

    Parameters
    ----------
    function : callable
        An elementary function such as ``numpy.arctan2``.

    Returns
    -------
    callable
        The same function of the same (double) arguments, its value computed in ``numpy.longdouble``
        and rounded once to double: correctly rounded but for values within about 1e-19 (relative)
        of a rounding boundary of double precision, and the same on every machine.
    """
    def rounded(*args: ArrayLike) -> np.ndarray:
        extended = [np.asarray(a, dtype=float).astype(np.longdouble) for a in args]
        return np.asarray(function(*extended), dtype=float)
    return rounded


def reproducible_coupler_angles(phi: ArrayLike, crank: float, coupler: float, rocker: float,
                                frame: tuple[float, float], branch: int = 1) -> dict[str, np.ndarray]:
    """The coupler angle ψ by the half-angle formula and by the stable form, the same on every machine.

    Parameters
    ----------
    phi : array_like
        Crank angles φ (rad).
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    frame : tuple of float
        The rocker pivot C = (x_C, y_C) (m).
    branch : int
        +1 or −1.

    Returns
    -------
    dict
        ``{"half-angle": ψ, "stable": ψ}`` (rad), double precision.

    Notes
    -----
    The two formulas of :func:`~mechanisms.linkages.four_bar.half_angle_formula` and
    :func:`~mechanisms.linkages.four_bar.stable_formula`, as a double-precision computer with correctly
    rounded elementary functions evaluates them: 𝒫, 𝒬, ℱ computed in extended precision and rounded
    once to double, the arctangents and ``hypot`` rounded once (:func:`rounded_once`), everything else
    (the subtractions, products, square roots and divisions in which the half-angle formula loses its
    digits) in double precision, whose basic operations are correctly rounded on every processor.
    What differs between machines — the last bit of double precision's sine, cosine and arctangent —
    is not used, so a figure of these round-off errors is the same everywhere (chapter 9).
    """
    p, q, f = (np.asarray(v, dtype=float) for v in _pqf(phi, crank, coupler, rocker, frame, np.longdouble))
    return {
        "half-angle": half_angle_formula(p, q, f, branch, arctan=rounded_once(np.arctan)),
        "stable": stable_formula(p, q, coupler, rocker, branch, arctan2=rounded_once(np.arctan2),
                                 hypot=rounded_once(np.hypot)),
    }


def cost_against_size(mechanism: Mechanism, sizes: Sequence[int], repeat: int = 3,
                      loop_limit: int = 2000) -> dict[str, np.ndarray]:
    """Time per position (ns) of the vectorized closed form (order 0 and 2) and of a loop per angle.

    The loop calls ``solve`` once per crank angle, as a program written without arrays would;
    it is timed only for sizes up to ``loop_limit`` (``nan`` above).
    """
    out: dict[str, list[float]] = {"vectorized, order 0": [], "vectorized, order 2": [], "loop per angle, order 2": []}
    for n in sizes:
        phi = np.arange(n) * (2.0 * math.pi / n)
        for order in (0, 2):
            seconds = best_time(lambda: mechanism.solve(phi, OMEGA, order=order), repeat)
            out[f"vectorized, order {order}"].append(seconds / n * 1e9)
        if n <= loop_limit:
            seconds = best_time(lambda: [mechanism.solve(phi[i:i + 1], OMEGA) for i in range(n)], repeat)
            out["loop per angle, order 2"].append(seconds / n * 1e9)
        else:
            out["loop per angle, order 2"].append(math.nan)
    return {key: np.array(value) for key, value in out.items()}


# --- figures for chapter 9 -------------------------------------------------------------------------

_METHOD_NAMES = {"newton": "Newton's method", "central difference": "central differences"}
_ERROR_UNITS = {"positions": "rad, m", "velocities": "1/s, m/s", "accelerations": "1/s², m/s²"}
_METHOD_STYLE = {"closed form": ("o", "#1f77b4"), "newton": ("s", "#ff7f0e"),
                 "central difference": ("^", "#2ca02c"), "memory floor": ("", "#7f7f7f"),
                 "pylinkage step_fast": ("D", "#d62728"), "pylinkage step": ("v", "#9467bd")}


def plot_work_precision(rows: list[dict], axes=None):
    """Work-precision diagrams: error against time per position, one panel per quantity.

    Newton's points are labelled with their tolerance tol, the central differences with their step h
    (rad). Returns the axes.
    """
    import matplotlib.pyplot as plt

    from ..plot.describe import add_description

    if axes is None:
        _, axes = plt.subplots(1, 3, figsize=(11, 3.6), sharey=True)
    for ax, quantity in zip(axes, QUANTITIES):
        for method, (marker, colour) in _METHOD_STYLE.items():
            chosen = [r for r in rows if r["method"] == method and r["quantity"] == quantity]
            if not chosen:
                continue
            x = [r["ns_per_position"] for r in chosen]
            y = [max(r["error"], 1e-17) for r in chosen]
            ax.plot(x, y, marker=marker, color=colour, ls="-" if len(chosen) > 1 else "",
                    label=_METHOD_NAMES.get(method, method))
            for (xi, yi), text, last in _labels(chosen, x, y):
                # Newton's last (rightmost) point has its label on its left, inside the panel
                last = last and method == "newton"
                ax.annotate(text, (xi, yi), xytext=(-6, -9) if last else (5, 2), textcoords="offset points",
                            fontsize=7, color=colour, ha="right" if last else "left")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.margins(x=0.15)
        ax.xaxis.set_minor_formatter(plt.NullFormatter())
        ax.set_title(f"{quantity} ({_ERROR_UNITS[quantity]})")
        ax.set_xlabel("time per position, ns")
        add_description(ax, f"a work-precision diagram of the {quantity}: each point is one method at one "
                            "setting (Newton's tolerance, the step of the differences), placed at its time per "
                            "position and its largest error; lower and further left is better")
    axes[0].set_ylabel("largest error")
    figure = axes[0].figure
    handles, names = axes[-1].get_legend_handles_labels()
    figure.legend(handles, names, loc="lower center", ncol=len(names), fontsize=8, frameon=False)
    figure.subplots_adjust(bottom=0.24)
    return axes


def _labels(chosen: list[dict], x: list[float], y: list[float]) -> list[tuple[tuple[float, float], str, bool]]:
    """The parameters of a method's points as labels, with a flag for the last one; points whose
    errors are within a factor of three of each other (Newton's tolerances once at round-off) share one
    label (``tol = 10⁻⁸ … 10⁻¹⁴``), so none overlap."""
    groups: list[tuple[tuple[float, float], list[dict]]] = []
    for r, xi, yi in zip(chosen, x, y):
        if r["parameter"] is None:
            continue
        if groups and 1 / 3 < yi / groups[-1][0][1] < 3:
            groups[-1][1].append(r)
        else:
            groups.append(((xi, yi), [r]))
    labels = []
    for k, (where, rows) in enumerate(groups):
        text = setting_label(rows[0]["method"], rows[0]["parameter"])
        if len(rows) > 1:
            text = text[:-1] + rf" \ldots\ 10^{{{math.log10(rows[-1]['parameter']):.0f}}}$"
        labels.append((where, text, k == len(groups) - 1))
    return labels


def setting_label(method: str, value: float) -> str:
    """A method's setting as math text for a figure or a table: Newton's tolerance or the step h (rad).

    Parameters
    ----------
    method : str
        ``"newton"`` (the value is the tolerance tol) or a numerical differentiation (the step h).
    value : float
        The setting, a power of ten.

    Returns
    -------
    str
        E.g. ``"$\\mathrm{tol} = 10^{-10}$"`` or ``"$h = 10^{-5}$"``.
    """
    symbol = r"\mathrm{tol}" if method == "newton" else "h"
    return rf"${symbol} = 10^{{{math.log10(value):.0f}}}$"


def plot_step_errors(steps: Sequence[float], errors: dict[str, np.ndarray], ax=None):
    """The U-shaped error of central differences against the step h, with its two asymptotes.

    Truncation: ``h²/6·|q'''|`` (velocities), ``h²/12·|q''''|`` (accelerations), fitted at the largest
    step; round-off: ``ε_mach/h`` and ``4ε_mach/h²`` times the size of the coordinates (about 1 here).
    """
    import matplotlib.pyplot as plt

    from ..plot.describe import add_description, covering

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4))
    h = np.asarray(steps, dtype=float)
    asymptotes = []
    eps = np.finfo(float).eps
    # the velocities drawn over the accelerations, smaller: for large steps the two errors coincide
    for (name, values), colour, power, size, z in zip(errors.items(), ("#1f77b4", "#d62728"), (1, 2),
                                                      (4, 7), (3, 2)):
        ax.loglog(h, values, "o-", color=colour, ms=size, zorder=z, label=f"{name}: error")
        truncation = values[0] * (h / h[0]) ** 2
        roundoff = (1 if power == 1 else 4) * eps / h**power
        with covering(ax) as drawn:
            ax.loglog(h, truncation, ":", color=colour, lw=1)
            ax.loglog(h, roundoff, "--", color=colour, lw=1)
        asymptotes += drawn.artists
    ax.plot([], [], "k:", lw=1, label=r"truncation $\propto h^2$")
    ax.plot([], [], "k--", lw=1, label=r"round-off $\propto \epsilon_\mathrm{mach}/h$, $\epsilon_\mathrm{mach}/h^2$")
    ax.set_ylim(1e-12, 1e1)
    ax.set_xlabel(r"step $h$, rad")
    ax.set_ylabel("largest error, 1/s or 1/s²")
    ax.legend(fontsize=8)
    add_description(ax, "the error of central differences against the step h: the truncation error falls as "
                        "h² (dotted lines) as the step shrinks, the round-off error grows as ε_mach/h for "
                        "velocities and ε_mach/h² for accelerations (dashed lines), so each error curve has a "
                        "lowest point between the two", asymptotes)
    return ax


CHECK_STEPS = {1: 1e-5, 2: 1e-4}
"""The steps h (rad) of the book's checks: velocities and accelerations by central differences."""


def plot_stored(report: dict, mechanism: str = "four-bar", ax=None,
                methods: Sequence[str] = ("closed form", "memory floor", "newton", "pylinkage")):
    """Time per position against the number of positions, from a stored benchmark run.

    Parameters
    ----------
    report : dict
        A run of :func:`run` (or ``python -m mechanisms bench --format json``).
    mechanism : str
        Its name in the report.
    ax : matplotlib Axes, optional
        Where to draw.
    methods : sequence of str
        What to draw: ``closed form`` and ``memory floor`` at each order, ``newton`` at its tightest
        tolerance, ``central difference`` at the steps of :data:`CHECK_STEPS` (velocities at
        h = 1e-5, accelerations at h = 1e-4 rad), ``pylinkage`` (its ``step`` and ``step_fast``).
    """
    import matplotlib.pyplot as plt

    from ..plot.describe import add_description

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4))
    series: dict[str, tuple[str, int, dict[int, float]]] = {}
    for r in report["results"]:
        method = r["method"]
        if r["mechanism"] != mechanism or method.split()[0] not in {m.split()[0] for m in methods}:
            continue
        if method in ("closed form", "memory floor"):
            key = f"{method}, order {r['order']}"
        elif method == "newton" and r["parameter"] == min(NEWTON_TOLERANCES):
            key = "Newton, " + setting_label(method, r["parameter"])
        elif method == "central difference" and r["parameter"] == CHECK_STEPS[r["order"]]:
            key = f"central difference, order {r['order']}, " + setting_label(method, r["parameter"])
        elif method.startswith("pylinkage"):
            key = method
        else:
            continue
        _, _, best = series.setdefault(key, (method, r["order"], {}))
        best[r["n"]] = min(best.get(r["n"], math.inf), r["ns_per_position"])
    for key, (method, order, by_size) in series.items():
        points = sorted(by_size.items())
        marker, colour = _METHOD_STYLE.get(method, ("o", "k"))
        ls = {0: ":", 1: "--"}.get(order, "-") if method != "newton" else "-"
        ax.loglog(*zip(*points), marker=marker or ".", color=colour, ls=ls, label=key)
    ax.set_xlabel(r"number of positions $N_\varphi$")
    ax.set_ylabel("time per position, ns")
    add_description(ax, f"the time per position of each method against the number of positions solved at once, "
                        f"for the {mechanism}, the best of the repeated runs of a stored benchmark")
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    return ax
