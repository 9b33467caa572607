"""Layer 3 foundation: what every mechanism class shares.

A mechanism is a small declarative class: it names its joints and links as the book does,
composes the building blocks of layer 2 in :meth:`Mechanism._solve`, describes its drawing
(:meth:`Mechanism.scheme`), its preserved joint distances and its constraint equations (for
the generic solver of :mod:`mechanisms.verify`), and the parameters of its command-line table.
"""

from __future__ import annotations

import math
import warnings
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ..blocks.crank import crank_angle, crank_pin
from ..core.errors import InvalidParameterError, SingularPositionWarning, UnknownNameError, describe_angles
from ..core.validate import (LENGTH_MAX, LENGTH_MIN, require_branch, require_coordinate, require_finite_array,
                             require_length, require_order)
from ..core.angles import constant
from ..core.motion import AngleMotion, Motion, PointMotion, point_on_link
from .groups import Group

__all__ = [
    "Solution",
    "Mechanism",
    "Parameter",
    "Bar",
    "Ground",
    "Block",
    "Guide",
    "registry",
    "is_family",
    "member_values",
    "family_shape",
    "family_pin",
]


# --- families of linkages: dimensions given as arrays of one shape G --------------------------------------

def is_family(*values: object) -> bool:
    """True if any of ``values`` is an array (or a sequence) rather than one number: a family of linkages."""
    for value in values:
        if type(value) in (float, int):     # the usual one linkage, without numpy's look at it
            continue
        try:
            if np.ndim(value) > 0:    # type: ignore[arg-type]
                return True
        except (TypeError, ValueError):   # a ragged sequence: the family's own checks name it
            return True
    return False


def member_values(name: str, value: object, kind: str) -> np.ndarray:
    """One parameter of a family of linkages, checked member by member: an array of floats.

    Parameters
    ----------
    name : str
        The parameter's name (``"crank"``, ``"frame[0]"`` …).
    value : array_like
        One number or an array of them, one per member.
    kind : str
        ``"length"`` (finite, from LENGTH_MIN to LENGTH_MAX m), ``"coordinate"`` (finite, magnitude at most
        LENGTH_MAX m) or ``"branch"`` (+1 or −1, integers).

    Raises
    ------
    InvalidParameterError
        Naming the first bad member by its index (``crank[3]``), its value and what is required, with how many
        members fail in all; or naming ``name`` when the value is not an array of real numbers.
    """
    if kind == "branch":
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError):
            raw = np.asarray(None)
        if raw.dtype.kind not in "iu":
            raise InvalidParameterError(name, value, "+1 or -1 (one sign, or one per member), as integers")
        array = raw.astype(float)
        bad = (array != 1.0) & (array != -1.0)
    else:
        array = _finite_members(name, value)
        bad = ~((array >= LENGTH_MIN) & (array <= LENGTH_MAX)) if kind == "length" else np.abs(array) > LENGTH_MAX
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        label = f"{name}[{', '.join(map(str, index))}]" if index else name
        member = array[index].item()
        count = int(np.count_nonzero(bad))
        try:
            if kind == "branch":
                require_branch(int(member), label)
            elif kind == "length":
                require_length(label, member)
            else:
                require_coordinate(label, member)
        except InvalidParameterError as error:
            more = f" ({count} members of the family fail)" if count > 1 else ""
            raise InvalidParameterError(label, error.value, error.requirement + more) from None
    return array


def _finite_members(name: str, value: Any) -> np.ndarray:
    """``value`` as an array of finite floats, or raise naming the first member that is not finite by its index."""
    try:
        return require_finite_array(name, value, "m")
    except InvalidParameterError:
        try:
            raw = None if value is None or isinstance(value, (str, bytes)) else np.asarray(value, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raw = None
        if raw is None or raw.ndim == 0 or np.isfinite(raw).all():
            raise
        bad = ~np.isfinite(raw)
        index = ", ".join(str(int(i)) for i in np.argwhere(bad)[0])
        count = int(np.count_nonzero(bad))
        more = f" ({count} members of the family fail)" if count > 1 else ""
        raise InvalidParameterError(f"{name}[{index}]", raw[bad][0].item(), "a finite number (m)" + more) from None


def family_pin(crank: AngleMotion, length: np.ndarray | float) -> PointMotion:
    """The crank pin A = L1·e^{iφ} of every member of a family (lengths of shape G + (1,), N crank angles): arrays
    G + (N,). The unit vector and its rates are computed once for the N angles, then scaled by each member's L1."""
    unit = crank_pin(crank, 1.0)
    return PointMotion(*(None if v is None else length * v for v in unit.derivatives()))


def family_shape(**arrays: np.ndarray) -> tuple[int, ...]:
    """The shape G of a family: the parameters' shapes broadcast together, or raise naming them all."""
    try:
        return np.broadcast_shapes(*(np.shape(v) for v in arrays.values()))
    except ValueError:
        raise InvalidParameterError(", ".join(arrays), ", ".join(str(np.shape(v)) for v in arrays.values()),
                                    "arrays of one shape G (or numbers), which broadcast together") from None


class Solution:
    """The kinematics of a mechanism over an array of crank positions.

    Angles, points and sliders are looked up by the names the book uses:
    ``sol.angle("coupler").omega``, ``sol.point("B").velocity``, ``sol.slider("B").value``.

    Attributes
    ----------
    phi : ndarray
        Crank angles φ (rad).
    order : int
        0, 1 or 2: positions, up to velocities, up to accelerations.
    singular : ndarray of bool
        True where a velocity or acceleration is unbounded or undetermined (a singular position);
        those values are ``inf`` (unbounded) or ``nan`` (undetermined) on purpose and a :class:`SingularPositionWarning` was issued.

    A family of linkages (a mechanism whose dimensions are arrays of shape G) has N crank angles ``phi``
    and every other array of shape G + (N,): one row of positions per member.
    """

    def __init__(self, phi: np.ndarray, order: int, *, angles: dict[str, AngleMotion],
                 points: dict[str, PointMotion], links: dict[str, str],
                 sliders: dict[str, Motion] | None = None,
                 extras: dict[str, dict[str, Any]] | None = None,
                 singular: np.ndarray | None = None, assembled: np.ndarray | None = None):
        self._assembled = assembled
        self.phi = phi
        self.order = order
        self._angles = angles
        self._points = points
        self._links = links
        self._sliders = sliders or {}
        self.extras = extras or {}
        self.singular = np.zeros(np.shape(phi), dtype=bool) if singular is None else singular

    def __len__(self) -> int:
        return int(np.size(self.phi))

    @property
    def assembled(self) -> np.ndarray:
        """True where the mechanism assembles (the shape of :attr:`singular`).

        All True unless the mechanism was solved leniently (a family with ``lenient=True``): there, where a
        member does not assemble, its angles and points are ``nan`` and ``singular`` is False.
        """
        if self._assembled is None:
            return np.ones(np.shape(self.singular), dtype=bool)
        return self._assembled

    @property
    def angle_names(self) -> list[str]:
        """Names of the links whose angles are known (``crank``, ``coupler`` …)."""
        return list(self._angles)

    @property
    def point_names(self) -> list[str]:
        """Names of the joints (``O``, ``A``, ``B`` …)."""
        return list(self._points)

    @property
    def slider_names(self) -> list[str]:
        """Names of the sliding pairs."""
        return list(self._sliders)

    @staticmethod
    def _lookup(table: dict, name: str, what: str):
        """``table[name]``, or :class:`UnknownNameError` (a :class:`KeyError` too) for a name it does not have,
        whatever the name's type (an unhashable one included)."""
        if not isinstance(name, str) or name not in table:
            raise UnknownNameError(what, name, table)
        return table[name]

    def angle(self, link: str) -> AngleMotion:
        """The angle of a link (rad) with ω (1/s) and ε (1/s²) (attributes ``omega``, ``alpha``).

        Raises
        ------
        UnknownNameError
            If the mechanism has no link of that name (also a :class:`KeyError`).
        """
        return self._lookup(self._angles, link, "link")

    def point(self, name: str) -> PointMotion:
        """A named joint ``x + iy`` (m) with its velocity and acceleration.

        Raises
        ------
        UnknownNameError
            If the mechanism has no joint of that name (also a :class:`KeyError`).
        """
        return self._lookup(self._points, name, "point")

    def slider(self, name: str) -> Motion:
        """A sliding pair: position along its guide (m), its velocity and acceleration.

        Raises
        ------
        UnknownNameError
            If the mechanism has no sliding pair of that name (also a :class:`KeyError`).
        """
        return self._lookup(self._sliders, name, "slider")

    def coriolis(self, name: str) -> np.ndarray:
        """The Coriolis acceleration 2ω·s_t of the block at a sliding pair on a rotating guide (m/s²).

        The block slides along the guide with relative speed s_t while the guide turns at ω (chapter 5);
        the term points along the guide's left normal, and this is its signed component there (its
        magnitude a^k is the absolute value). Known from order 1 on.

        Raises
        ------
        UnknownNameError
            If the solution knows no Coriolis term at that name: no sliding pair on a rotating guide
            there, or a solution of order 0 (also a :class:`KeyError`).
        """
        known = {joint: values["coriolis"] for joint, values in self.extras.items() if "coriolis" in values}
        return np.asarray(self._lookup(known, name, "sliding pair on a rotating guide"))

    def scaled(self, factor: float) -> "Solution":
        """The same solution with every length multiplied by ``factor`` (points, sliders, extras; angles kept).

        :meth:`Mechanism.solve` uses it to bring back a mechanism solved at a scale of its own; a power of
        two as ``factor`` makes it exact.
        """
        def times(table: dict) -> dict:
            return {name: motion * factor for name, motion in table.items()}

        extras = {joint: {key: None if value is None else np.asarray(value) * factor for key, value in values.items()}
                  for joint, values in self.extras.items()}
        return Solution(self.phi, self.order, angles=self._angles, points=times(self._points), links=self._links,
                        sliders=times(self._sliders), extras=extras, singular=self.singular,
                        assembled=self._assembled)

    def with_points(self, points: dict[str, PointMotion]) -> "Solution":
        """The same solution with more named points (a coupler point, an instant centre) to look up."""
        return Solution(self.phi, self.order, angles=self._angles, points={**self._points, **points},
                        links=self._links, sliders=self._sliders, extras=self.extras, singular=self.singular,
                        assembled=self._assembled)

    def point_on(self, link: str, along: float, left: float = 0.0) -> PointMotion:
        """A point fixed to a link, computed now (on demand).

        Parameters
        ----------
        link : str
            The link's name (``"coupler"`` …).
        along : float
            Distance u (m) from the link's first joint along the link.
        left : float
            Distance w (m) to the left of the link (counter-clockwise side).

        Raises
        ------
        UnknownNameError
            If the mechanism has no link of that name (also a :class:`KeyError`).
        InvalidParameterError
            If ``along`` or ``left`` is not a finite number of magnitude at most 2^500 m.
        """
        first_joint = self._lookup(self._links, link, "link")
        along, left = require_coordinate("along", along), require_coordinate("left", left)
        return point_on_link(self.point(first_joint), self.angle(link), along, left)


@dataclass(frozen=True)
class Parameter:
    """A parameter of a mechanism as the command line asks for it.

    ``kind`` is ``"length"`` (a finite length > 0, m), ``"number"`` (finite), ``"angle"``
    (degrees on the command line, radians for the class), ``"pair"`` (two numbers ``A,B``, m)
    or ``"branch"`` (+1 or -1).
    """

    name: str
    kind: str
    help: str
    default: object = None


# Drawing primitives: a mechanism describes what to draw, layer 6 draws it.
@dataclass(frozen=True)
class Bar:
    """A link drawn as a bar through joints, in the colour of its role."""

    link: str
    joints: tuple[str, ...]
    role: str


@dataclass(frozen=True)
class Ground:
    """A pivot fixed to the frame, drawn with hatching."""

    joint: str


@dataclass(frozen=True)
class Block:
    """A sliding block at a joint, turned to a link's angle (by name) or a fixed angle (rad)."""

    joint: str
    angle: str | float = 0.0


@dataclass(frozen=True)
class Guide:
    """A fixed straight guide through ``through`` (m) at ``angle`` (rad), drawn hatched."""

    through: complex
    angle: float = 0.0


registry: dict[str, type["Mechanism"]] = {}

_SCALE_BAND = 2.0**64
"""A mechanism whose largest length is within [1/_SCALE_BAND, _SCALE_BAND] m is solved as it is."""


def _scale_of(mechanism: "Mechanism") -> float:
    """1.0, or the power of four 4^k ≤ the mechanism's largest length (m) when that is outside the band where
    squares of lengths are safe: the mechanism is then solved with its lengths divided by 4^k (exact)."""
    values = mechanism.preserved_distances().values()
    if mechanism.family_shape:      # a family is solved at one scale, its largest member's
        sizes = [float(np.max(np.abs(v), initial=0.0)) for v in values]
    else:
        sizes = [abs(float(v)) for v in values]
    size = max(sizes, default=1.0)
    if not math.isfinite(size) or size == 0.0 or 1.0 / _SCALE_BAND <= size <= _SCALE_BAND:
        return 1.0
    _, exponent = math.frexp(size)           # size = m·2^exponent, m in [0.5, 1)
    return 4.0 ** ((exponent - 1) // 2)


def _finite_at(solution: Solution, where: np.ndarray) -> bool:
    """True if every joint's position is finite at the positions of ``where``."""
    return all(bool(np.all(np.isfinite(np.broadcast_to(solution.point(name).value, where.shape)[where])))
               for name in solution.point_names)


class Mechanism(ABC):
    """Base class of the book's mechanisms.

    Subclasses set ``cli_name`` and ``cli_parameters`` (which registers them for the
    command-line table), ``links`` (link name → first joint) and implement ``_solve``,
    ``scheme``, ``preserved_distances``, ``coordinates`` and ``constraints``.
    """

    cli_name: ClassVar[str | None] = None
    cli_parameters: ClassVar[tuple[Parameter, ...]] = ()
    links: ClassVar[dict[str, str]] = {}
    benchmark: ClassVar[bool] = False
    """True for the mechanisms that ``python -m mechanisms bench`` measures (at :meth:`example`)."""
    always_assembles: ClassVar[bool] = False
    """True for a mechanism that assembles at every crank angle (a slotted lever)."""
    family_shape: tuple[int, ...] = ()
    """The shape G of a family of linkages (dimensions given as arrays), ``()`` for one linkage."""
    family_parameters: tuple[str, ...] = ()
    """The names of the parameters a family was given as arrays."""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.cli_name:
            registry[cls.cli_name] = cls

    def solve(self, phi: ArrayLike, omega: ArrayLike = 1.0, alpha: ArrayLike = 0.0, order: int = 2) -> Solution:
        """Kinematics over an array of crank angles.

        Parameters
        ----------
        phi : array_like
            Crank angles φ (rad).
        omega : float or array_like
            Crank angular velocity φ_t (1/s).
        alpha : float or array_like
            Crank angular acceleration φ_tt (1/s²).
        order : int
            0 positions only, 1 up to velocities, 2 up to accelerations.

        Returns
        -------
        Solution
            Every position, the singular ones included: where the constraints' Jacobian is singular to
            within round-off (a singular position: a change point, a block at its lever's pivot, parallel
            lines, two joints that coincide) ``Solution.singular`` is True, the unbounded or undefined
            values there are ``inf`` or ``nan`` on purpose, and a :class:`SingularPositionWarning` says so.
            Nowhere else is a value ``nan``.

        Raises
        ------
        InvalidParameterError
            Naming ``phi``, ``omega``, ``alpha`` or ``order`` (see :func:`~mechanisms.blocks.crank.crank_angle`).
        AssemblyError
            Naming the crank angles at which the mechanism cannot be assembled.

        Notes
        -----
        A mechanism whose largest length lies outside [2^-64, 2^64] m is solved at a scale of its
        own: its lengths divided by a power of four (exact, so the positions are those of the
        mechanism itself to rounding) and the lengths of the solution multiplied back, so that no
        square of a length overflows or underflows (lengths from 2^-510 to 2^510 m).
        """
        order = require_order(order)
        crank = crank_angle(phi, omega, alpha, order)
        scale = _scale_of(self)
        inner = None if scale == 1.0 else self._rescaled(1.0 / scale)
        solution = self._solve(crank, order) if inner is None else inner._solve(crank, order).scaled(scale)
        if solution.singular.any() and (order or not _finite_at(solution, solution.singular)):
            where = np.broadcast_to(solution.phi, solution.singular.shape)[solution.singular]
            members = ""
            if self.family_shape:      # name the first member, and say how many there are
                rows = solution.singular.reshape(-1, solution.singular.shape[-1]).any(axis=-1)
                first = np.unravel_index(int(np.argmax(rows)), self.family_shape)
                count = int(np.count_nonzero(rows))
                members = f" of member {', '.join(map(str, first))}" + (f" and {count - 1} more" if count > 1 else "")
            warnings.warn(
                f"{type(self).__name__}: velocities/accelerations are unbounded or undetermined (a singular "
                f"position) at crank angle(s) {describe_angles(where)}{members}; "
                "see Solution.singular",
                SingularPositionWarning, stacklevel=2)
        return solution

    def _family_columns(self, phi: np.ndarray, *values: Any) -> tuple[tuple[int, ...], list[Any]]:
        """For a family's solve: the shape G + (N,) of its results and ``values`` (its dimensions, shape G) as
        columns G + (1,) against the N crank angles (unchanged for one linkage); ``phi`` must be one-dimensional."""
        shape = self.family_shape
        if shape and np.ndim(phi) != 1:
            raise InvalidParameterError("phi", f"an array of shape {np.shape(phi)}",
                                        "a one-dimensional array of crank angles (the same N for every member)")
        return shape + np.shape(phi), [np.asarray(v)[..., np.newaxis] if shape else v for v in values]

    @staticmethod
    def _family_motions(crank: AngleMotion, full: tuple[int, ...], order: int) -> tuple[AngleMotion, PointMotion]:
        """A family's crank motion and its crank pivot O at the origin, as views of shape ``full`` (no memory)."""
        still = constant(0j, full)
        return (AngleMotion(*(None if v is None else np.broadcast_to(v, full) for v in crank.derivatives())),
                PointMotion(still, *([still] * order)))

    @staticmethod
    def _first_failing(assembled: np.ndarray) -> tuple[tuple[int, ...], str]:
        """The index of the first member of a family that does not assemble at every crank angle, and words
        saying how many fail (``"3 members fail"``)."""
        rows = ~assembled.all(axis=-1)
        count = int(np.count_nonzero(rows))
        return tuple(int(i) for i in np.argwhere(rows)[0]), f"{count} member{'s fail' if count != 1 else ' fails'}"

    def require_one_linkage(self, what: str) -> None:
        """Raise :class:`InvalidParameterError` if this is a family of linkages: ``what`` is defined for one
        linkage (solve the family, or make one mechanism per member)."""
        if self.family_shape:
            raise InvalidParameterError(", ".join(self.family_parameters), f"arrays of shape {self.family_shape}",
                                        f"one number each ({what}: defined for one linkage; make one mechanism "
                                        "per member)")

    def _rescaled(self, factor: float) -> "Mechanism | None":
        """The same mechanism with every length multiplied by ``factor`` (a power of four), or ``None`` if the
        class cannot make one (it is then solved as it is)."""
        return None

    @classmethod
    def example(cls) -> "Mechanism":
        """The book's example of this mechanism (the benchmark measures it where ``benchmark`` is set)."""
        raise NotImplementedError(f"{cls.__name__} has no example: give it one in its module")

    def assembly_intervals(self) -> list[tuple[float, float]]:
        """Crank-angle intervals (rad, start < stop) in which the mechanism assembles.

        The one assembly-range API of every mechanism. A crank that turns fully has one interval
        of length 2π (``[(θ_OC − π, θ_OC + π)]``); a mechanism that never assembles, none. A mechanism
        that assembles at every crank angle sets ``always_assembles = True`` and gets ``[(−π, π)]``;
        one that does not says where it does by overriding this method.
        """
        if self.always_assembles:
            return [(-math.pi, math.pi)]
        raise NotImplementedError(f"{type(self).__name__} does not say where it assembles (assembly_intervals); "
                                  "solve() raises AssemblyError, naming the crank angles, where it does not")

    def full_turn(self) -> bool:
        """True if the crank can turn a full revolution (one assembly interval of length 2π)."""
        intervals = self.assembly_intervals()
        return len(intervals) == 1 and intervals[0][1] - intervals[0][0] >= 2.0 * math.pi * (1.0 - 1e-12)

    def groups(self) -> tuple[Group, ...]:
        """The mechanism's structure: its crank, then its Assur groups in the order they are solved.

        Empty for a mechanism that does not describe it; the plans and instant centres need it
        (:mod:`mechanisms.linkages.groups`).
        """
        return ()

    @abstractmethod
    def _solve(self, crank: AngleMotion, order: int) -> Solution:
        """Compose the building blocks for the given crank motion."""

    @abstractmethod
    def scheme(self) -> Sequence[Bar | Ground | Block | Guide]:
        """What to draw: bars, frame pivots, blocks and guides."""

    @abstractmethod
    def preserved_distances(self) -> dict[tuple[str, str], float]:
        """Pairs of joints on one rigid link and the distance between them (m)."""

    # The generic solver's view: unknown coordinates q and constraint equations Φ(q, φ) = 0.
    @abstractmethod
    def coordinates(self, solution: Solution) -> list[Motion]:
        """The unknowns q (angles, slider positions) taken from a solution, in constraint order."""

    @abstractmethod
    def constraints(self, q: Sequence[Any], phi: Any) -> tuple:
        """Residuals of the constraint equations Φ(q, φ); zero when assembled.

        Written with numpy operations only (``+ - * /``, ``np.sin``, ``np.cos``, ``np.sqrt``),
        so that :mod:`mechanisms.verify` can differentiate them exactly.
        """

    def parameters(self) -> dict[str, object]:
        """The mechanism's parameters by their command-line names."""
        return {p.name: getattr(self, p.name) for p in self.cli_parameters}

    def describe(self) -> str:
        """One line naming the mechanism and its parameters with units (one linkage, not a family)."""
        self.require_one_linkage("a one-line description")
        parts = []
        for p in self.cli_parameters:
            value = getattr(self, p.name)
            if p.kind == "branch":
                parts.append(f"{p.name} = {value:+d}")
            elif p.kind == "pair":
                parts.append(f"{p.name} = ({value[0]:g}, {value[1]:g}) m")
            elif p.kind == "angle":
                parts.append(f"{p.name} = {math.degrees(value):g}°")
            else:
                parts.append(f"{p.name} = {value:g} m" if p.kind == "length" else f"{p.name} = {value:g}")
        return f"{self.cli_name or type(self).__name__}: " + ", ".join(parts)

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.parameters().items())
        return f"{type(self).__name__}({args})"
