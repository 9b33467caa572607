"""Layer 4: path synthesis of the four-bar — coupler curves of a whole family at once, and the fit
of a coupler point to a path a user gives (``python -m mechanisms synthesize path``), chapter 12.

A family of four-bars is described by arrays of one shape G (one element per member); solving at N
crank angles gives arrays of shape G + (N,). Every curve is computed by the package's routines for the
crank (:func:`~mechanisms.blocks.crank.crank_pin`) and the two links meeting at a hinge
(:func:`~mechanisms.blocks.circle_circle.hinge`, leniently: a member that does not assemble at a crank
angle is marked there, not raised).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ..blocks.circle_circle import hinge
from ..blocks.crank import crank_pin
from ..core.errors import InvalidParameterError
from ..core.motion import AngleMotion, PointMotion
from ..core.validate import require_angles, require_finite_array

__all__ = ["CouplerCurves", "coupler_curves"]


class CouplerCurves(NamedTuple):
    """The coupler curves of a family of four-bars (:func:`coupler_curves`): two arrays of shape G + (N,)."""

    point: np.ndarray
    """The coupler point P = x + iy (m) of each member (leading axes) at each crank angle (last axis);
    ``nan`` exactly where ``assembled`` is False."""
    assembled: np.ndarray
    """True where the member assembles at that crank angle (the coupler and rocker reach each other)."""


def _family(name: str, value: ArrayLike) -> np.ndarray:
    return require_finite_array(name, value, "m")


def coupler_curves(crank: ArrayLike, coupler: ArrayLike, rocker: ArrayLike, frame_x: ArrayLike, frame_y: ArrayLike,
                   along: ArrayLike, left: ArrayLike, phi: ArrayLike, branch: ArrayLike = 1) -> CouplerCurves:
    """Coupler curves of a family of four-bars, all members and all crank angles in one call.

    Each member is the four-bar of :class:`~mechanisms.linkages.four_bar.FourBar`: crank O → A of
    length L1 about O = (0, 0), coupler A → B of length L2, rocker C → B of length L3 about
    C = (x_C, y_C); the coupler point P is fixed to the coupler at (u, w): u along A → B from A and
    w to the left of it, ``r_P = r_A + (u + iw)·e^{iψ}``.

    Parameters
    ----------
    crank, coupler, rocker : array_like
        L1, L2, L3 (m): positive lengths, arrays of one shape G or numbers (broadcast together
        with the other geometry arguments).
    frame_x, frame_y : array_like
        x_C, y_C (m), the rocker pivot, likewise.
    along, left : array_like
        u, w (m), the coupler point in the coupler's frame, likewise (any sign).
    phi : array_like
        The N crank angles φ (rad), a one-dimensional array (or one number), the same for every
        member.
    branch : int or array_like of int
        σ = +1: B to the left of the directed line A → C at every crank angle; −1: to the right.
        One sign, or one per member (shape G). The side is held at every crank angle, as
        ``FourBar(..., keep_side=True)`` does: a change-point linkage (s + l = p + q) is not
        continued through its change points.

    Returns
    -------
    CouplerCurves
        ``point`` (complex, m) and ``assembled`` (bool), both of shape G + (N,). The points are
        ``nan`` exactly where ``assembled`` is False (a member that does not assemble at that crank
        angle); use the mask, never the ``nan``, to select them.

    Raises
    ------
    InvalidParameterError
        Naming the argument that is not finite, a length that is not positive, a ``branch`` other
        than ±1, ``phi`` that is not one-dimensional, or geometry arrays whose shapes do not
        broadcast together.

    Notes
    -----
    Positions only (order 0): an atlas or a synthesis search needs no rates. For the velocities and
    accelerations of a family, solve :class:`~mechanisms.linkages.four_bar.FourBar` with arrays of
    dimensions. The cost is a few tens of nanoseconds per member and crank angle.

    Examples
    --------
    >>> import numpy as np
    >>> curves = coupler_curves(crank=[1.0, 1.2], coupler=3.5, rocker=3.0, frame_x=4.0, frame_y=0.0,
    ...                         along=1.75, left=1.0, phi=np.radians(np.arange(0, 360, 10)))
    >>> curves.point.shape, bool(curves.assembled.all())
    ((2, 36), True)
    """
    names = ("crank", "coupler", "rocker", "frame_x", "frame_y", "along", "left")
    values = [_family(name, value) for name, value in zip(names, (crank, coupler, rocker, frame_x, frame_y,
                                                                    along, left))]
    sides = require_finite_array("branch", branch)
    if not np.isin(sides, (-1.0, 1.0)).all():
        raise InvalidParameterError("branch", sides[~np.isin(sides, (-1.0, 1.0))][:3].tolist(),
                                    "+1 or -1 (one sign, or one per member)")
    try:
        shape = np.broadcast_shapes(*(v.shape for v in values), sides.shape)
    except ValueError:
        raise InvalidParameterError("crank, coupler, rocker, frame_x, frame_y, along, left, branch",
                                    ", ".join(str(v.shape) for v in (*values, sides)),
                                    "arrays of one shape G (or numbers), which broadcast together") from None
    for name, value in zip(names[:3], values[:3]):
        if (value <= 0.0).any():
            raise InvalidParameterError(name, value[value <= 0.0][:3].tolist(), "positive lengths (m)")
    angles = require_angles("phi", phi)
    if angles.ndim > 1:
        raise InvalidParameterError("phi", f"an array of shape {angles.shape}", "a one-dimensional array of crank angles")
    l1, l2, l3, xc, yc, u, w = values
    return _coupler_points(l1, l2, l3, xc, yc, u, w, np.atleast_1d(angles), sides, shape)


def _coupler_points(l1: np.ndarray, l2: np.ndarray, l3: np.ndarray, xc: np.ndarray, yc: np.ndarray, u: np.ndarray,
                    w: np.ndarray, angles: np.ndarray, sides: np.ndarray,
                    shape: tuple[int, ...]) -> CouplerCurves:
    """:func:`coupler_curves` on checked arrays (broadcasting to ``shape``) and crank angles (N,)."""
    l1, l2, l3, xc, yc, u, w = (np.broadcast_to(v, shape)[..., np.newaxis] for v in (l1, l2, l3, xc, yc, u, w))
    side = np.broadcast_to(sides, shape)[..., np.newaxis]
    # the crank pin of a unit crank, scaled by each member's L1: r_A = L1·e^{iφ}
    unit_pin = crank_pin(AngleMotion(angles), 1.0).value
    pin = PointMotion(l1 * unit_pin)
    pivot = PointMotion(np.broadcast_to(xc + 1j * yc, shape + angles.shape))
    joint = hinge(pin, pivot, l2, l3, side, lenient=True)
    assert joint.assembled is not None                       # lenient: the mask is given
    # r_P = r_A + (u + iw)·(r_B − r_A)/L2
    point = pin.value + (u + 1j * w) * ((joint.point.value - pin.value) / l2)
    return CouplerCurves(point, np.asarray(joint.assembled))


# --- fitting a coupler point to a target path ------------------------------------------------------

TARGET_MIN_POINTS = 5
"""The fewest points a target path may have."""

DEFAULT_TOLERANCE = 0.01
"""A fit is good when its RMS distance (see :class:`PathFit`) is at most this fraction of the target's size."""

_SAMPLES = 64          # points of a curve after resampling by arc length (the coarse comparison)
_POSITIONS = 128       # crank angles of a candidate's coupler curve in the coarse search
_DENSE = 7200          # crank angles of the fitted path when it is measured (0.05° apart)
_DESIGNS_CLOSED = 40_000   # random designs of the coarse search, closed target
_DESIGNS_OPEN = 6_000      # and open target (each is compared along many stretches)


@dataclass(frozen=True)
class PathFit:
    """A four-bar whose coupler point P traces a target path (:func:`fit_path`).

    The linkage is the four-bar of :class:`~mechanisms.linkages.four_bar.FourBar` placed in the
    plane: crank pivot O, rocker pivot C, crank O → A (L1), coupler A → B (L2), rocker C → B (L3),
    B on the side ``branch`` of A → C, and P at (u, w) on the coupler (u along A → B, w to its left).

    Attributes
    ----------
    crank, coupler, rocker : float
        L1, L2, L3 (m).
    pivot, frame : complex
        O and C, x + iy (m).
    along, left : float
        u, w (m).
    branch : int
        σ = ±1.
    size : float
        The target's size (m): the diagonal of its bounding box.
    rms, largest : float
        RMS and largest distance (m) from the target's points to P's path (the path drawn over a full
        turn of the crank at 0.05° steps, as a polyline).
    in_order : bool
        P passes the target's points in their order (either way round) within one turn of the crank:
        for a closed target, once round; an open target, along a stretch of less than a turn. A fit out of
        order (P doubling back, or reaching the points on different turns) is not :attr:`good`.
    closed : bool
        Whether the target was a closed curve.
    tolerance : float
        The fraction of ``size`` that :attr:`good` asks of the RMS distances.
    """

    crank: float
    coupler: float
    rocker: float
    pivot: complex
    frame: complex
    along: float
    left: float
    branch: int
    size: float
    rms: float
    largest: float
    in_order: bool
    closed: bool
    tolerance: float = DEFAULT_TOLERANCE

    def path(self, phi: ArrayLike) -> np.ndarray:
        """P (complex, m) at crank angles φ (rad, counter-clockwise from +x), ``nan`` where it does not assemble."""
        c = self.frame - self.pivot
        angles = np.atleast_1d(require_angles("phi", phi))
        return self.pivot + coupler_curves(self.crank, self.coupler, self.rocker, c.real, c.imag, self.along,
                                           self.left, angles, self.branch).point

    @property
    def relative_rms(self) -> float:
        """The fit's RMS distance as a fraction of the target's size, :attr:`rms`/:attr:`size`."""
        return self.rms / self.size

    @property
    def good(self) -> bool:
        """True when :attr:`relative_rms` is at most :attr:`tolerance` and P passes the points :attr:`in_order`."""
        return self.relative_rms <= self.tolerance and self.in_order

    @property
    def frame_length(self) -> float:
        """d = |OC| (m)."""
        return abs(self.frame - self.pivot)

    def linkage_text(self, name: str = "Four-bar fitted to a path") -> str:
        """The linkage file (TOML) of the fit: frame O and C, the crank, the RRR dyad at B, the point P."""
        def number(value: float) -> str:
            return repr(float(value))

        o, c = self.pivot, self.frame
        text = name.replace("\\", "\\\\").replace('"', '\\"')
        return "\n".join([
            "# A four-bar whose coupler point P traces a target path (python -m mechanisms synthesize path).",
            f"# RMS distance from the target to P's path: {100 * self.rms / self.size:.3g} % of the target's size "
            f"{self.size:.6g} m (the diagonal of its bounding box); largest {100 * self.largest / self.size:.3g} %.",
            f'name = "{text}"',
            "",
            "[frame]",
            f"O = [{number(o.real)}, {number(o.imag)}]          # the crank's pivot",
            f"C = [{number(c.real)}, {number(c.imag)}]          # the rocker's pivot",
            "",
            "[crank]",
            'pivot = "O"',
            'pin = "A"',
            f"length = {number(self.crank)}",
            "",
            "[[dyad]]                # the coupler A-B and the rocker C-B",
            'type = "RRR"',
            'joint = "B"',
            'from = ["A", "C"]',
            f"lengths = [{number(self.coupler)}, {number(self.rocker)}]",
            f"branch = {self.branch:+d}",
            'links = ["coupler", "rocker"]',
            "",
            "[[point]]               # the coupler point that traces the path",
            'name = "P"',
            'link = ["A", "B"]',
            f"along = {number(self.along)}",
            f"left = {number(self.left)}",
            "",
        ])


def require_target(points: ArrayLike, name: str = "target", closed: bool = True) -> np.ndarray:
    """A target path checked: its points as complex numbers x + iy (m), in order.

    Parameters
    ----------
    points : array_like
        Shape (n, 2) (x, y in m) or (n,) complex.
    name : str
        What the messages call the target (the command line gives its file).
    closed : bool
        A closed curve: a last point equal to the first is dropped (the curve closes by itself).

    Raises
    ------
    InvalidParameterError
        Naming ``name``: fewer than :data:`TARGET_MIN_POINTS` points (distinct), a coordinate that is not
        finite, all points coincident, or all on one straight line.
    """
    array = np.asarray(points)
    if array.dtype.kind == "c" and array.ndim == 1:
        xy = np.stack([require_finite_array(name, array.real, "m"), require_finite_array(name, array.imag, "m")], axis=1)
    else:
        xy = require_finite_array(name, points, "m")
        if xy.ndim != 2 or xy.shape[1] != 2:
            raise InvalidParameterError(name, f"an array of shape {xy.shape}", "points x, y (m): an array of shape (n, 2)")
    target = xy[:, 0] + 1j * xy[:, 1]
    if closed and len(target) > 1 and target[-1] == target[0]:
        target = target[:-1]
    distinct = len(np.unique(target))
    if distinct < TARGET_MIN_POINTS:
        raise InvalidParameterError(name, f"{distinct} distinct point{'s' if distinct != 1 else ''}",
                                    f"at least {TARGET_MIN_POINTS} distinct points")
    size = target_size(target)
    centred = (target - target.mean()) / size
    # the smaller singular value of the centred points: the target's thickness across its best line
    thickness = np.linalg.svd(np.stack([centred.real, centred.imag]), compute_uv=False)[-1] / np.sqrt(len(target))
    if thickness <= 1e-9:
        raise InvalidParameterError(name, "points on one straight line",
                                    "points that are not all on one straight line (a curve)")
    return target


def target_size(target: np.ndarray) -> float:
    """The size of a target path (m): the diagonal of its bounding box."""
    return float(np.hypot(np.ptp(target.real), np.ptp(target.imag)))


def _resample(curves: np.ndarray, phi: np.ndarray, count: int, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """``count`` points equally spaced by arc length along each row of ``curves`` (G, N), and the value of
    ``phi`` (N,) or (G, N) interpolated there (for a closed curve the last segment joins the last point to
    the first, and ``phi`` continues by 2π). Rows of zero length give their first point."""
    rows, n = curves.shape
    phi = np.broadcast_to(phi, curves.shape)
    if closed:
        curves = np.concatenate([curves, curves[:, :1]], axis=1)
        phi = np.concatenate([phi, phi[:, :1] + 2.0 * np.pi], axis=1)
    segments = np.abs(np.diff(curves, axis=1))
    cumulative = np.concatenate([np.zeros((rows, 1)), np.cumsum(segments, axis=1)], axis=1)
    total = cumulative[:, -1:]
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(total > 0.0, cumulative / total, 0.0)
    fraction[:, -1] = 1.0
    # every row's fractions lie in [0, 1]; shifting row r by 2r makes one sorted array for searchsorted
    width = fraction.shape[1]
    shift = 2.0 * np.arange(rows)[:, np.newaxis]
    queries = np.arange(count) / (count if closed else count - 1)
    found = np.searchsorted((fraction + shift).ravel(), (queries + shift).ravel(), side="right") - 1
    local = np.clip(found.reshape(rows, count) - (np.arange(rows) * width)[:, np.newaxis], 0, width - 2)
    start = np.take_along_axis(fraction, local, axis=1)
    step = np.take_along_axis(fraction, local + 1, axis=1) - start
    with np.errstate(invalid="ignore", divide="ignore"):
        weight = np.where(step > 0.0, (queries - start) / step, 0.0)
    weight = np.clip(weight, 0.0, 1.0)

    def along(values: np.ndarray) -> np.ndarray:
        first = np.take_along_axis(values, local, axis=1)
        return first + weight * (np.take_along_axis(values, local + 1, axis=1) - first)

    return along(curves), along(phi)


@dataclass
class _Candidate:
    """A design in the target's normalised frame (target centred, size 1): O, C − O, L1, L2, L3, u, w; the
    branch; the crank angles at the target's resampled points; and the coarse score."""

    geometry: np.ndarray
    branch: int
    phi: np.ndarray
    score: float


def _full_turn(geometry: np.ndarray, margin: float = 1e-3) -> np.ndarray:
    """True where the crank of a geometry (…, 9) turns fully, with a margin (relative to the sum of the
    lengths) from the change-point linkages: |d − L1| ≥ |L2 − L3| and d + L1 ≤ L2 + L3."""
    d = np.hypot(geometry[..., 2], geometry[..., 3])
    l1, l2, l3 = geometry[..., 4], geometry[..., 5], geometry[..., 6]
    slack = margin * (d + l1 + l2 + l3)
    return ((l1 > 0) & (l2 > 0) & (l3 > 0) & (np.abs(d - l1) - np.abs(l2 - l3) >= slack)
            & ((l2 + l3) - (d + l1) >= slack))


def _transmission_bounds(geometry: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest and largest transmission angle μ (rad) over a full turn of a geometry (…, 9) whose crank
    turns fully: μ at |AC| = |d − L1| and at |AC| = d + L1, by the cosine law of triangle ABC."""
    d = np.hypot(geometry[..., 2], geometry[..., 3])
    l1, l2, l3 = geometry[..., 4], geometry[..., 5], geometry[..., 6]
    cosine = [np.clip((l2**2 + l3**2 - reach**2) / (2.0 * l2 * l3), -1.0, 1.0) for reach in (d - l1, d + l1)]
    return np.arccos(cosine[0]), np.arccos(cosine[1])


class _Rules:
    """The constraints of a search, in the target's normalised frame."""

    def __init__(self, pivots: tuple[complex, complex] | None, crank_rocker: bool, min_transmission: float | None,
                 reach: float = 50.0):
        self.pivots = pivots
        self.crank_rocker = crank_rocker
        self.min_transmission = min_transmission
        self.reach = reach

    def allowed(self, geometry: np.ndarray) -> np.ndarray:
        ok = _full_turn(geometry)
        ok &= np.all(np.abs(geometry) <= self.reach, axis=-1)
        if self.crank_rocker:
            d = np.hypot(geometry[..., 2], geometry[..., 3])
            ok &= geometry[..., 4] < np.minimum(np.minimum(geometry[..., 5], geometry[..., 6]), d)
        if self.min_transmission is not None:
            with np.errstate(invalid="ignore", divide="ignore"):
                low, high = _transmission_bounds(geometry)
            ok &= (low >= self.min_transmission) & (high <= np.pi - self.min_transmission)
        return ok


def _sample(rng: np.random.Generator, count: int, rules: _Rules) -> tuple[np.ndarray, np.ndarray]:
    """``count`` normalised designs (O = 0, C = 1) that the rules allow, and their branches."""
    chunks, total = [], 0
    while total < count:
        n = 4 * count
        l1, l2, l3 = np.exp(rng.uniform(np.log(0.05), np.log(4.0), (3, n)))
        u = rng.uniform(-1.0, 2.0, n) * l2
        w = rng.uniform(-1.5, 1.5, n) * l2
        zeros, ones = np.zeros(n), np.ones(n)
        geometry = np.stack([zeros, zeros, ones, zeros, l1, l2, l3, u, w], axis=1)
        # the rules on shape (not on place or size) hold for every similar copy of a design
        keep = geometry[_Rules(None, rules.crank_rocker, rules.min_transmission, np.inf).allowed(geometry)]
        chunks.append(keep)
        total += len(keep)
    geometry = np.concatenate(chunks)[:count]
    return geometry, rng.choice([-1, 1], len(geometry))


def _curves(geometry: np.ndarray, branch: ArrayLike, phi: np.ndarray) -> np.ndarray:
    """Coupler curves (G, N) of geometries (G, 9) in the plane: O + the curve about O."""
    g = geometry.T
    curves = _coupler_points(g[4], g[5], g[6], g[2], g[3], g[7], g[8], phi, np.asarray(branch, dtype=float),
                             (len(geometry),)).point
    return curves + (g[0] + 1j * g[1])[:, np.newaxis]


def _placed(geometry: np.ndarray, scale: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """Normalised designs (O = 0, C = 1) moved by z → scale·z + shift (complex, one per design)."""
    placed = geometry * np.abs(scale)[:, np.newaxis]
    placed[:, 0], placed[:, 1] = shift.real, shift.imag
    placed[:, 2], placed[:, 3] = scale.real, scale.imag
    return placed


def _coarse_closed(target: np.ndarray, samples: np.ndarray, phi: np.ndarray,
                   pivots: tuple[complex, complex] | None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Scores of closed candidate curves (resampled ``samples`` (G, M) with crank angles ``phi``) against a
    closed target (M,), over every starting point and both directions; with the best similarity z → a·z + b
    (or the one the fixed pivots set). Returns (score, a, b, crank angles at the target's points)."""
    m = len(target)
    centred = target - target.mean()
    norm = float(np.sum(np.abs(centred) ** 2))
    spectrum = np.fft.fft(target if pivots else centred)
    best = np.full(len(samples), np.inf)
    scale = np.ones(len(samples), dtype=complex)
    shift = np.zeros(len(samples), dtype=complex)
    angles = np.zeros(samples.shape)
    index = np.arange(m)
    for reverse in (False, True):
        curves, along = (samples[:, ::-1], phi[:, ::-1]) if reverse else (samples, phi)
        if pivots:
            a = np.full(len(curves), pivots[1] - pivots[0])
            moved = a[:, np.newaxis] * curves + pivots[0]
            # Σ|t_k − w_{k−s}|² = Σ|t|² + Σ|w|² − 2 Re Σ t_k conj(w_{k−s}); the last sum by the FFT for every s
            correlation = np.fft.ifft(spectrum * np.conj(np.fft.fft(moved, axis=1)), axis=1)
            residual = (np.sum(np.abs(target) ** 2) + np.sum(np.abs(moved) ** 2, axis=1)[:, np.newaxis]
                        - 2.0 * correlation.real)
            s = np.argmin(residual, axis=1)
            b = np.full(len(curves), pivots[0])
        else:
            mean = curves.mean(axis=1)
            spread = curves - mean[:, np.newaxis]
            energy = np.sum(np.abs(spread) ** 2, axis=1)
            correlation = np.fft.ifft(spectrum * np.conj(np.fft.fft(spread, axis=1)), axis=1)
            with np.errstate(invalid="ignore", divide="ignore"):
                residual = norm - np.abs(correlation) ** 2 / energy[:, np.newaxis]
            residual[~(energy > 0)] = np.inf
            s = np.argmin(residual, axis=1)
            with np.errstate(invalid="ignore", divide="ignore"):
                a = np.take_along_axis(correlation, s[:, np.newaxis], axis=1)[:, 0] / energy
            b = target.mean() - a * mean
        score = np.take_along_axis(residual, s[:, np.newaxis], axis=1)[:, 0] / norm
        better = score < best
        best[better], scale[better], shift[better] = score[better], a[better], b[better]
        # target point k lies at curve sample k − s
        matched = np.take_along_axis(along, (index[np.newaxis, :] - s[:, np.newaxis]) % m, axis=1)
        angles[better] = matched[better]
    return best, scale, shift, angles


_FRACTIONS = np.array([0.06, 0.1, 0.15, 0.22, 0.3, 0.4, 0.52, 0.66, 0.82, 0.97])
_OPEN_POINTS = 40      # points of an open target resampled by arc length, for the crank angles' first guess
_FIT_POINTS = 200      # the most points of a target the refinement fits
"""The fractions of a closed coupler curve's length an open target may span, tried in the coarse search."""


def _coarse_open(target: np.ndarray, samples: np.ndarray, phi: np.ndarray,
                 pivots: tuple[complex, complex] | None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Scores of closed candidate curves (resampled ``samples`` (G, K) with crank angles ``phi``) against an
    open target: the best stretch of each curve (start, length, direction) under the best similarity (or the
    one the fixed pivots set). ``target`` holds the open target's points (any number; it is resampled for each
    stretch length). Returns (score, a, b, crank angles at :data:`_OPEN_POINTS` points of the target equally
    spaced by arc length).

    A stretch of L consecutive samples is compared with the target resampled at L points; for every start at
    once, the sums Σ t_k·conj(c_{s+k}) are one circular correlation (FFT) and the sums of the window's points
    and squares are differences of cumulative sums.
    """
    rows, k = samples.shape
    spectrum = np.fft.fft(samples, axis=1)
    doubled = np.concatenate([samples, samples], axis=1)
    sums = np.concatenate([np.zeros((rows, 1)), np.cumsum(doubled, axis=1)], axis=1)
    squares = np.concatenate([np.zeros((rows, 1)), np.cumsum(np.abs(doubled) ** 2, axis=1)], axis=1)
    best = np.full(rows, np.inf)
    scale = np.ones(rows, dtype=complex)
    shift = np.zeros(rows, dtype=complex)
    angles = np.zeros((rows, _OPEN_POINTS))
    unwrapped = np.concatenate([phi, phi + 2.0 * np.pi, phi[:, :1] + 4.0 * np.pi], axis=1)
    where = np.linspace(0.0, 1.0, _OPEN_POINTS)
    for fraction in _FRACTIONS:
        length = max(8, int(round(fraction * k)))
        resampled, _ = _resample(target[np.newaxis], np.arange(len(target), dtype=float), length, closed=False)
        for reverse in (False, True):
            t = resampled[0, ::-1] if reverse else resampled[0]
            mean_t = t.mean()
            centred = t - mean_t
            norm = float(np.sum(np.abs(centred) ** 2))
            padded = np.zeros(k, dtype=complex)
            padded[:length] = centred if not pivots else t
            # correlation[s] = Σ_k t_k conj(c_{s+k})
            correlation = np.conj(np.fft.ifft(np.conj(np.fft.fft(padded)) * spectrum, axis=1))
            window = sums[:, length:length + k] - sums[:, :k]
            energy_raw = squares[:, length:length + k] - squares[:, :k]
            if pivots:
                a0, b0 = pivots[1] - pivots[0], pivots[0]
                # Σ|t − (a c + b)|² over the window
                moved_energy = (abs(a0) ** 2 * energy_raw + 2.0 * (np.conj(b0) * a0 * window).real
                                + length * abs(b0) ** 2)
                residual = (np.sum(np.abs(t) ** 2) + moved_energy - 2.0 * (np.conj(a0) * correlation).real
                            - 2.0 * (np.sum(t) * np.conj(b0)).real)
                a = np.full(rows, a0)
            else:
                energy = energy_raw - np.abs(window) ** 2 / length
                with np.errstate(invalid="ignore", divide="ignore"):
                    residual = norm - np.abs(correlation) ** 2 / energy
                residual[~(energy > 1e-9 * norm)] = np.inf
            s = np.argmin(residual, axis=1)
            score = np.take_along_axis(residual, s[:, np.newaxis], axis=1)[:, 0] / norm
            better = score < best
            if not better.any():
                continue
            best[better] = score[better]
            picked = np.take_along_axis(correlation, s[:, np.newaxis], axis=1)[:, 0]
            if pivots:
                scale[better], shift[better] = pivots[1] - pivots[0], pivots[0]
            else:
                mean_c = np.take_along_axis(window, s[:, np.newaxis], axis=1)[:, 0] / length
                energy_s = np.take_along_axis(energy, s[:, np.newaxis], axis=1)[:, 0]
                a = picked / energy_s
                scale[better] = a[better]
                shift[better] = (mean_t - a * mean_c)[better]
            # the target's points equally spaced by arc length, as sample indices of the curve
            index = s[better, np.newaxis] + (1.0 - where if reverse else where)[np.newaxis] * (length - 1)
            base = np.floor(index).astype(int)
            low = np.take_along_axis(unwrapped[better], base, axis=1)
            high = np.take_along_axis(unwrapped[better], base + 1, axis=1)
            angles[better] = low + (index - base) * (high - low)
    return best, scale, shift, angles


def _refine(target: np.ndarray, start: _Candidate, rules: _Rules, iterations: int) -> _Candidate:
    """Levenberg–Marquardt on the distances from the target's points to the curve: the unknowns are the
    design (all of O, C − O, L1, L2, L3, u, w; without O and C when the pivots are fixed) and the crank angle
    at each target point, so that at the optimum each residual is the distance from a target point to the
    curve along its normal. Steps the rules do not allow are refused like steps that do not improve."""
    free = np.arange(4, 9) if rules.pivots else np.arange(9)
    geometry, phi, branch = start.geometry.copy(), start.phi.copy(), start.branch
    m = len(target)

    def residual(g: np.ndarray, angles: np.ndarray) -> np.ndarray | None:
        if not rules.allowed(g):
            return None
        return _curves(g[np.newaxis], branch, angles)[0] - target

    r = residual(geometry, phi)
    if r is None or not np.isfinite(r).all():
        return _Candidate(geometry, branch, phi, np.inf)
    cost = float(np.sum(np.abs(r) ** 2))
    damping = 1e-3
    for _ in range(iterations):
        # central differences: the design's unknowns as members of one family, the crank angles all at once
        step = 1e-6 * (1.0 + np.abs(geometry[free]))
        # one family: the design moved each way along each unknown, and the design itself (last), each at
        # the crank angles and at the crank angles moved each way
        members = np.repeat(geometry[np.newaxis], 2 * len(free) + 1, axis=0)
        members[np.arange(len(free)), free] += step
        members[len(free) + np.arange(len(free)), free] -= step
        moved = _curves(members, branch, np.concatenate([phi, phi + 1e-6, phi - 1e-6]))
        design = (moved[:len(free), :m] - moved[len(free):-1, :m]).T / (2.0 * step)         # (M, free)
        along = (moved[-1, m:2 * m] - moved[-1, 2 * m:]) / 2e-6                              # (M,)
        if not (np.isfinite(design).all() and np.isfinite(along).all()):
            break
        # the normal equations [[A, B], [Bᵀ, D]] with D diagonal (each crank angle moves its own point only):
        # the crank angles are eliminated (Schur complement), leaving a system of the design's unknowns
        a_matrix = (np.conj(design).T @ design).real                                        # (free, free)
        b_matrix = (np.conj(design) * along[:, np.newaxis]).real                             # (M, free)
        d_diagonal = np.abs(along) ** 2                                                      # (M,)
        g_design = (np.conj(design).T @ r).real
        g_angle = (np.conj(along) * r).real
        improved = False
        while damping < 1e12:
            d_damped = d_diagonal * (1.0 + damping) + 1e-12
            reduced = a_matrix + damping * np.diag(np.diag(a_matrix) + 1e-12) \
                - (b_matrix / d_damped[:, np.newaxis]).T @ b_matrix
            try:
                delta_design = np.linalg.solve(reduced, -(g_design - b_matrix.T @ (g_angle / d_damped)))
            except np.linalg.LinAlgError:
                damping *= 10.0
                continue
            delta_angle = -(g_angle + b_matrix @ delta_design) / d_damped
            delta = np.concatenate([delta_design, delta_angle])
            trial = geometry.copy()
            trial[free] += delta[:len(free)]
            trial_phi = phi + delta[len(free):]
            trial_r = residual(trial, trial_phi)
            trial_cost = np.inf if trial_r is None else float(np.sum(np.abs(trial_r) ** 2))
            if trial_r is not None and trial_cost < cost:
                # go on while a step gains more than a millionth and the fit is not already far inside
                # any tolerance (an RMS distance of 1e-5 of the target's size)
                improved = cost - trial_cost > 1e-6 * cost and trial_cost > 1e-10 * m
                geometry, phi, r, cost = trial, trial_phi, trial_r, trial_cost
                damping = max(damping / 3.0, 1e-9)
                break
            damping *= 4.0
        if not improved:
            break
    return _Candidate(geometry, branch, phi, cost / m)


def _arc_fractions(points: np.ndarray, closed: bool) -> np.ndarray:
    """Where each point of a polyline lies along it, as a fraction of its length (closed: with the segment
    from the last point back to the first)."""
    ends = np.append(points, points[0]) if closed else points
    lengths = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(ends)))])
    return lengths[:len(points)] / lengths[-1]


def _distances(points: np.ndarray, polyline: np.ndarray, closed: bool) -> np.ndarray:
    """The distance from each point to a polyline (m), exactly (to its nearest segment)."""
    start = polyline if closed else polyline[:-1]
    end = np.roll(polyline, -1) if closed else polyline[1:]
    edge = end - start
    length2 = np.abs(edge) ** 2
    out = np.empty(len(points))
    chunk = max(1, 4_000_000 // len(start))
    for lo in range(0, len(points), chunk):
        p = points[lo:lo + chunk, np.newaxis]
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(length2 > 0, ((p - start) * np.conj(edge)).real / length2, 0.0)
        foot = start + np.clip(t, 0.0, 1.0) * edge
        out[lo:lo + chunk] = np.min(np.abs(p - foot), axis=1)
    return out


def fit_path(target: ArrayLike, closed: bool = True, pivots: tuple[complex, complex] | None = None,
             crank_rocker: bool = False, min_transmission: float | None = None,
             tolerance: float = DEFAULT_TOLERANCE, seed: int = 0, name: str = "target") -> PathFit:
    """Fit a four-bar's coupler point P to a target path (path generation, chapter 12).

    Parameters
    ----------
    target : array_like
        The path's points in order, shape (n, 2) (x, y in m) or (n,) complex; n ≥ 5.
    closed : bool
        True: a closed curve, matched as a whole (P's whole path against the whole target, wherever
        either starts and in either direction). False: an open stretch, matched by a stretch of P's path.
    pivots : (complex, complex), optional
        Fixed pivots O (the crank's) and C (the rocker's), x + iy (m); by default they are free.
    crank_rocker : bool
        Only crank-rockers (the crank shortest, Grashof). By default also double-cranks; either way the
        crank turns fully.
    min_transmission : float, optional
        The smallest transmission angle μ allowed over the turn (rad): μ_min ≥ it and μ_max ≤ π − it.
    tolerance : float
        :attr:`PathFit.good` asks RMS distances of at most this fraction of the target's size.
    seed : int
        The seed of the random designs of the coarse search (the same seed, the same fit).
    name : str
        What messages call the target.

    Returns
    -------
    PathFit
        The best four-bar found, with the distances that measure the fit; check :attr:`PathFit.good`.

    Raises
    ------
    InvalidParameterError
        For a target :func:`require_target` refuses, or constraints that are not numbers of their kind.

    Notes
    -----
    The search works on the target moved and scaled to size 1 (centred on its bounding box).

    1. Sample: random designs with O = (0, 0), C = (1, 0) (lengths L1, L2, L3 log-uniform in 0.05 to 4,
       u and w in proportion to L2, both branches), kept when the crank turns fully and the constraints
       on shape hold; their coupler curves solved as one family (:func:`coupler_curves`), resampled at
       equal arc lengths. A similar copy of a design (scaled, turned, moved) traces a similar curve, so
       one sample stands for all its copies: the best similarity z → a·z + b for each start and direction
       is found in closed form (least squares of complex numbers; all starts at once by the FFT).
       With fixed pivots, a and b are set by O and C.
    2. Refine the best dozen by Levenberg–Marquardt (:func:`_refine`): the design and a crank angle per
       target point, so that the residuals become the normal distances from the target to P's path.
    3. Measure the best on P's path drawn at 0.05° steps.
    """
    target = require_target(target, name, closed)
    tolerance = _positive_fraction("tolerance", tolerance)
    if min_transmission is not None and not (0.0 <= float(min_transmission) < np.pi / 2):
        raise InvalidParameterError("min_transmission", min_transmission, "an angle from 0 to π/2 rad (0° to 90°)")
    size = target_size(target)
    centre = 0.5 * complex(np.ptp(target.real) + 2 * target.real.min(), np.ptp(target.imag) + 2 * target.imag.min())
    unit = (target - centre) / size
    frame = None
    if pivots is not None:
        o, c = ((complex(v) - centre) / size for v in pivots)
        if not (np.isfinite(o) and np.isfinite(c)) or o == c:
            raise InvalidParameterError("pivots", pivots, "two distinct points O and C with finite coordinates (m)")
        frame = (o, c)
    rules = _Rules(frame, crank_rocker, None if min_transmission is None else float(min_transmission))
    rng = np.random.default_rng(seed)
    count = _DESIGNS_CLOSED if closed else _DESIGNS_OPEN
    designs, branches = _sample(rng, count, rules)
    phi = np.linspace(0.0, 2.0 * np.pi, _POSITIONS, endpoint=False)
    samples_count = _SAMPLES if closed else 4 * _SAMPLES
    goal = _resample(unit[np.newaxis], np.arange(len(unit), dtype=float), _SAMPLES if closed else _OPEN_POINTS,
                     closed)[0][0]
    scores: list[np.ndarray] = []
    scales: list[np.ndarray] = []
    shifts: list[np.ndarray] = []
    angles: list[np.ndarray] = []
    for lo in range(0, len(designs), 5000):
        curves = _curves(designs[lo:lo + 5000], branches[lo:lo + 5000], phi)
        samples, sample_phi = _resample(curves, phi, samples_count, closed=True)
        if closed:
            score, a, b, at = _coarse_closed(goal, samples, sample_phi, frame)
        else:
            score, a, b, at = _coarse_open(unit, samples, sample_phi, frame)
        for store, value in ((scores, score), (scales, a), (shifts, b), (angles, at)):
            store.append(value)
    score, scale, shift, at = (np.concatenate(v) for v in (scores, scales, shifts, angles))
    placed = _placed(designs, scale, shift)
    # the turn of the design by a = |a|·e^{iθ} turns the crank angles by θ
    at = at + np.angle(scale)[:, np.newaxis]
    order = [i for i in np.argsort(score)[:60] if rules.allowed(placed[i])][:12]
    # the refinement fits the target's own points (at most _FIT_POINTS of them), not the resampled ones, which lie
    # on chords between them; each starts at the crank angle of its place along the target (by arc length)
    chosen = np.unique(np.linspace(0, len(unit) - 1, min(len(unit), _FIT_POINTS)).round().astype(int))
    points = unit[chosen]
    where = _arc_fractions(unit, closed)[chosen]
    known = np.arange(len(goal)) / len(goal) if closed else np.linspace(0.0, 1.0, len(goal))

    def start(i: int) -> _Candidate:
        angles_i = np.unwrap(np.concatenate([at[i], at[i][:1]]) if closed else at[i])
        place = np.append(known, 1.0) if closed else known
        return _Candidate(placed[i], int(branches[i]), np.interp(where, place, angles_i), float(score[i]))

    refined = [_refine(points, start(i), rules, 30) for i in order]
    refined.sort(key=lambda c: c.score)
    finals = [_refine(points, c, rules, 300) for c in refined[:3]]
    # the closest fit that passes the target's points in order (else the closest)
    best = min(finals, key=lambda c: (not _in_order(c.phi, closed), c.score)) if finals else None
    if best is None or not np.isfinite(best.score):
        raise InvalidParameterError("constraints", "no design", "constraints that some four-bar meets")
    g = best.geometry
    o = centre + size * complex(g[0], g[1])
    c = o + size * complex(g[2], g[3])
    if pivots is not None:                  # the given pivots themselves, not their round trip through the frame
        o, c = complex(pivots[0]), complex(pivots[1])
    l1, l2, l3, u, w = (size * v for v in g[4:9])
    dense = np.linspace(0.0, 2.0 * np.pi, _DENSE, endpoint=False)
    path = o + coupler_curves(l1, l2, l3, (c - o).real, (c - o).imag, u, w, dense, best.branch).point
    forward = _distances(target, path, closed=True)
    return PathFit(crank=float(l1), coupler=float(l2), rocker=float(l3), pivot=o, frame=c, along=float(u),
                   left=float(w), branch=best.branch, size=size, rms=float(np.sqrt(np.mean(forward**2))),
                   largest=float(forward.max()), in_order=_in_order(best.phi, closed), closed=closed,
                   tolerance=tolerance)


def _in_order(phi: np.ndarray, closed: bool) -> bool:
    """Whether crank angles at consecutive target points all step the same way, and go once round (closed) or
    less than once (open)."""
    if closed:
        steps = np.diff(np.append(phi, phi[0]))
        steps = (steps + np.pi) % (2.0 * np.pi) - np.pi         # each step the short way round
        return bool((np.all(steps > 0) or np.all(steps < 0)) and abs(abs(steps.sum()) - 2.0 * np.pi) < 1e-6)
    steps = np.diff(phi)
    return bool((np.all(steps > 0) or np.all(steps < 0)) and abs(phi[-1] - phi[0]) < 2.0 * np.pi)


def _positive_fraction(name: str, value: float) -> float:
    number = require_finite_array(name, value)
    if number.ndim or not number > 0:
        raise InvalidParameterError(name, value, "a positive number")
    return float(number)


def fit_report(fit: PathFit) -> list[str]:
    """The fit in words, a line each: the linkage, the distances (as a fraction of the target's size), its
    Grashof class, whether the crank turns fully and its transmission angles; or, for a poor fit, that no
    four-bar found fits better."""
    from ..linkages.four_bar import FourBar
    from .four_bar import grashof_class, transmission_extremes

    def percent(value: float) -> str:
        return f"{100.0 * value / fit.size:.3g} % ({value:.3g} m)"

    o, c = fit.pivot, fit.frame
    grashof = grashof_class(fit.crank, fit.coupler, fit.rocker, fit.frame_length)
    low, high = transmission_extremes(FourBar(fit.crank, fit.coupler, fit.rocker, ((c - o).real, (c - o).imag),
                                              fit.branch))
    lines = [
        f"four-bar: crank pivot O = ({o.real:.6g}, {o.imag:.6g}) m, rocker pivot C = ({c.real:.6g}, {c.imag:.6g}) m, "
        f"crank L1 = {fit.crank:.6g} m, coupler L2 = {fit.coupler:.6g} m, rocker L3 = {fit.rocker:.6g} m, "
        f"branch {fit.branch:+d}; P at u = {fit.along:.6g} m, w = {fit.left:.6g} m on the coupler A -> B",
        f"target size {fit.size:.6g} m (the diagonal of its bounding box)",
        f"distance from the target to P's path: RMS {percent(fit.rms)}, largest {percent(fit.largest)} of the size",
    ]
    turn = "once round in one turn of the crank" if fit.closed else "along less than a turn of the crank"
    lines.append(f"P passes the target's points in their order, {turn}: {'yes' if fit.in_order else 'no'}")
    lines += [
        f"Grashof class: {grashof.name}; the crank turns fully: {'yes' if grashof.crank_rotates else 'no'}",
        f"transmission angle: from {np.degrees(low):.1f}° to {np.degrees(high):.1f}° over the turn, minimum "
        f"{np.degrees(min(low, np.pi - high)):.1f}° (the acute angle between coupler and rocker)",
    ]
    if not fit.good and fit.relative_rms <= fit.tolerance:
        lines.append("no four-bar found passes the target's points in their order within the tolerance")
    elif not fit.good:
        lines.append(f"no four-bar found fits better than {100.0 * fit.relative_rms:.3g} % of the target's size "
                     f"(RMS; the tolerance is {100.0 * fit.tolerance:.3g} %)")
    return lines
