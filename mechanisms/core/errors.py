"""Errors and warnings of the package.

Every error names what a student can act on: the parameter and its value, or the crank
angles where a mechanism cannot be assembled, and why.
"""

from __future__ import annotations

import math
import warnings
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "MechanismError",
    "InvalidParameterError",
    "AssemblyError",
    "StructureError",
    "UnknownNameError",
    "MissingDerivativeError",
    "SingularPositionWarning",
    "describe_angles",
    "describe_range",
]


class MechanismError(Exception):
    """Base class of the errors raised by :mod:`mechanisms`."""


class InvalidParameterError(MechanismError, ValueError):
    """A parameter has a value the model cannot use.

    Parameters
    ----------
    name : str
        The parameter's name as the caller wrote it (``"crank"``, ``"rod"`` ...).
    value : object
        The value that was given.
    requirement : str
        What is required, in words ("a finite length > 0 m").
    """

    def __init__(self, name: str, value: object, requirement: str):
        self.name = name
        self.value = value
        self.requirement = requirement
        super().__init__(f"{name} must be {requirement}: got {name} = {value!r}")


class AssemblyError(MechanismError, ValueError):
    """The mechanism cannot be assembled at some crank angles.

    Parameters
    ----------
    reason : str
        Why it cannot be assembled ("the rod cannot reach the guide").
    angles : array_like of float, optional
        The crank angles (rad) where assembly fails; named in the message in degrees.
    valid_range : tuple of float, optional
        The crank-angle interval (rad) in which the mechanism assembles, if known. A full turn (an
        interval of length 2π or more) is not named: "it assembles only for [-180°, 180°]" would
        contradict the error.
    nowhere : bool
        True if the mechanism assembles at no crank angle at all; the message then says so after
        naming the crank angles asked for.
    valid_ranges : sequence of (float, float), optional
        Several crank-angle intervals (rad) in which it assembles (a crank-slider whose rod is too
        short for its offset has two); named like ``valid_range``, which is then not given.
    """

    def __init__(self, reason: str, angles: ArrayLike | None = None, valid_range: tuple[float, float] | None = None,
                 nowhere: bool = False, valid_ranges: Sequence[tuple[float, float]] | None = None):
        self.reason = reason
        self.angles = None if angles is None else np.atleast_1d(np.asarray(angles, dtype=float))
        if valid_range is not None and valid_range[1] - valid_range[0] >= 2.0 * math.pi * (1.0 - 1e-12):
            valid_range = None
        self.valid_range = valid_range
        self.nowhere = nowhere
        named = [] if nowhere else [valid_range] if valid_range is not None else list(valid_ranges or [])
        extra = _extra_digits(self.angles, named)
        message = reason
        if self.angles is not None and self.angles.size:
            message += f" at crank angle(s) {describe_angles(self.angles, digits=6 + extra)}"
        if nowhere:
            message += "; it assembles at no crank angle"
        elif named:
            ranges = " and ".join(describe_range(low, high, decimals=2 + extra) for low, high in named)
            message += f"; it assembles only for crank angles in {ranges}" + (", mod 360°" if len(named) > 1 else "")
        super().__init__(message)


def _extra_digits(angles: np.ndarray | None, ranges: Sequence[tuple[float, float]]) -> int:
    """How many more digits the angles and ranges of a message need so that no failing angle, as printed,
    lies inside a range as printed (127.169° against [-127.17°, 127.17°] would contradict the error)."""
    if angles is None or not angles.size or not ranges:
        return 0
    shown = np.degrees(angles[:6])
    for extra in range(11):
        inside = False
        for low, high in ranges:
            lo, hi = (round(math.degrees(x), 2 + extra) for x in (low, high))
            for value in shown:
                printed = float(f"{value:.{6 + extra}g}")
                if lo <= lo + (printed - lo) % 360.0 <= hi:
                    inside = True
        if not inside:
            return extra
    return 10


class StructureError(MechanismError, ValueError):
    """A linkage is described wrongly: a joint no group finds, a cycle, a duplicate name, a wrong
    number of degrees of freedom, a missing or bad key of a linkage file.

    The message names where (the file, the group, the key) and what is wrong.
    """


class UnknownNameError(MechanismError, KeyError):
    """A link, joint, point or slider was asked for by a name the mechanism does not have.

    It is also a :class:`KeyError` (a solution's lookups are lookups by name), so code that caught
    the bare ``KeyError`` of earlier versions still catches it; unlike a bare ``KeyError`` its message
    reads as a sentence and names the known names.

    Parameters
    ----------
    what : str
        What was looked up (``"link"``, ``"point"``, ``"slider"``).
    name : object
        The name given.
    known : iterable of str
        The names there are.
    """

    def __init__(self, what: str, name: object, known):
        self.what = what
        self.name = name
        self.known = list(known)
        super().__init__(f"no {what} named {name!r}; known: {', '.join(self.known) or 'none'}")

    def __str__(self) -> str:            # KeyError's own __str__ would print the repr of the message
        return str(self.args[0])


class MissingDerivativeError(MechanismError, TypeError):
    """A velocity or an acceleration was asked for that the solution did not compute.

    A solution computes the time derivatives up to the ``order`` it was solved with (0 positions,
    1 velocities, 2 accelerations); the missing ones are ``None`` in :class:`~mechanisms.core.motion.Motion`,
    and :attr:`~mechanisms.core.motion.Motion.d1` and :attr:`~mechanisms.core.motion.Motion.d2` raise this
    error instead of returning them. It is also a :class:`TypeError`, the error that arithmetic on the
    missing ``None`` raised before, so a caller that caught that still catches it.

    Parameters
    ----------
    needed : int
        The derivative asked for: 1 (velocity) or 2 (acceleration).
    order : int
        The order of the motion that was asked, 0 or 1.
    """

    def __init__(self, needed: int, order: int):
        self.needed = needed
        self.order = order
        what, solve = ("velocities", "order ≥ 1") if needed == 1 else ("accelerations", "order=2")
        super().__init__(f"{what} were not computed: solve with {solve} (this motion has order={order})")


class SingularPositionWarning(UserWarning):
    """Velocities or accelerations are unbounded or undetermined at some crank angles: a singular
    (locking) position.

    At a singular position the constraint Jacobian Φ_q is singular (the glossary's *singular
    position*: e.g. the limits of a non-Grashof four-bar, a change point, a slider whose coupler is
    perpendicular to its guide), so the driven links' rates cannot follow from the crank's: they are
    unbounded (``inf`` where the routine knows it, as for a crank-slider at an end of its crank's
    range; the four-bar gives ``nan`` there) or undetermined (``nan``: the constraints admit more than
    one rate, as at a change point, or the one-sided limits differ, as for L₂ = L₁ + |e|). The
    solution marks these angles in ``Solution.singular`` and sets those values on purpose; this
    warning says so, so nothing is NaN silently. (The limit, or dead-centre, positions of an output
    are not singular: the output is at rest there.)
    """


def __getattr__(name: str) -> type:
    """``DeadCentreWarning``, the old name of :class:`SingularPositionWarning` (deprecated, one release)."""
    if name == "DeadCentreWarning":
        warnings.warn("mechanisms: DeadCentreWarning is now SingularPositionWarning (the book's 'dead centre' "
                      "is a limit position of the output, not a singular one); the old name goes in 0.3",
                      DeprecationWarning, stacklevel=2)
        return SingularPositionWarning
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def describe_angles(angles: ArrayLike, limit: int = 6, digits: int = 6) -> str:
    """Return crank angles (rad) as a short list in degrees (``digits`` significant), for messages."""
    deg = np.degrees(np.atleast_1d(np.asarray(angles, dtype=float)))
    shown = ", ".join(f"{d:.{digits}g}°" for d in deg[:limit])  # exact enough to find the position again
    if deg.size > limit:
        shown += f", … ({deg.size} angles in all)"
    return shown


def describe_range(low: float, high: float, decimals: int = 2) -> str:
    """A crank-angle interval (rad) for messages: ``[-44.43°, 224.43°]``."""
    return f"[{math.degrees(low):.{decimals}f}°, {math.degrees(high):.{decimals}f}°]"
