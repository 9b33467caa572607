"""Layer 4: what a course can ask about each mechanism — the assignment tasks, registered by mechanism.

Each mechanism's own analysis module registers its task (:func:`register_assignment`): how a
variant is drawn, when it is a good one (by the mechanism's own analysis), what the sheet shows and
which quantities are asked. The course tools (:mod:`mechanisms.course.assign`) look tasks up here
by the mechanism's command-line name; no other module lists them.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np

from ..linkages.base import Mechanism

__all__ = ["Quantity", "Task", "register_assignment", "assignments", "round_mm", "crank_speed"]


@dataclass(frozen=True)
class Quantity:
    """A quantity a student computes, named as the ``table`` command's CSV column.

    Attributes
    ----------
    column : str
        ``NAME.KEY``, e.g. ``"coupler.omega"`` or ``"B.v"``.
    symbol : str
        The book's symbol (``"ω₂"``), for the sheet.
    meaning : str
        In words, with the sign convention.
    unit : str
    """

    column: str
    symbol: str
    meaning: str
    unit: str


@dataclass(frozen=True)
class Task:
    """What an assignment on one mechanism asks and how its variants are drawn.

    Attributes
    ----------
    name : str
        The mechanism's command-line name.
    title : str
        For the sheet's heading.
    sample : callable
        ``sample(rng) -> (mechanism, omega)``: a candidate variant from a numpy Generator.
    check : callable
        ``check(mechanism) -> list of str``: why the candidate is not a good variant (empty: good).
    data : callable
        ``data(mechanism) -> list of (symbol, meaning, value, unit)``: the sheet's data table.
    quantities : tuple of Quantity
        What is asked at every position.
    conditions : str
        The validity conditions in words (for the course page and the sheet's footer).
    eligible : callable, optional
        ``eligible(mechanism) -> bool array`` over the crank angles 0°, 15°, … 345°: which of them a valid
        variant may be asked at (None: all of them, the positions drawn independently of the mechanism).
    document : callable, optional
        ``document(mechanism, comments) -> str or None``: the variant's own linkage file (TOML), written beside
        its sheet as ``sNN.toml`` (None: the mechanism has none).
    """

    name: str
    title: str
    sample: Callable[[np.random.Generator], tuple[Mechanism, float]]
    check: Callable[..., list[str]]
    data: Callable[..., list[tuple[str, str, str, str]]]
    quantities: tuple[Quantity, ...]
    conditions: str
    eligible: Callable[[Mechanism], np.ndarray] | None = None
    document: Callable[..., str | None] | None = None


_TASKS: dict[str, Task] = {}


def register_assignment(task: Task) -> Task:
    """Register a mechanism's assignment task under its command-line name (``task.name``)."""
    _TASKS[task.name] = task
    return task


def assignments() -> Mapping[str, Task]:
    """The registered tasks by the mechanism's command-line name (a read-only view)."""
    return MappingProxyType(_TASKS)


def round_mm(value: float) -> float:
    """Round a length to whole millimetres (m)."""
    return round(float(value), 3)


def crank_speed(rng: np.random.Generator, low: int, high: int) -> float:
    """A crank speed (1/s) that is a multiple of 5 in [low, high]."""
    return float(5 * rng.integers(low // 5, high // 5 + 1))
