"""Layer 3 helper: solve a long array of crank positions in chunks that fit the processor's cache.

A closed form is a chain of some dozens of array operations. Over a million positions each
operation writes an array of 8–16 MB and the next one reads it back: far more than the
processor's cache holds, so the chain waits on main memory. Over a block of some thirty thousand
positions the temporaries stay in the cache, and the memory they use is reused by the next block;
each block's results are copied once into the arrays over all positions. Every operation of the
closed forms is elementwise, so the result is that of solving all positions at once, to round-off
(numpy's vector loops may round an element differently depending on where its array starts in
memory); for the four-bar at a million positions it is about one and a half times as fast.
"""

from __future__ import annotations

from typing import Callable, cast

import numpy as np

from .base import Solution
from ..core.errors import AssemblyError
from ..core.angles import constant
from ..core.motion import AngleMotion, Motion, PointMotion

__all__ = ["BLOCK", "solve_in_chunks", "solve_in_blocks"]

BLOCK = 32768
"""Positions per block: a complex temporary of a block is 512 kB, and the some dozen that a
closed form keeps at once fit in the processor's cache (the best of 4096 … 65536 in chapter 9)."""


class _Gather:
    """Arrays over all positions, filled block by block, shaped like the first block's solution.

    An array that a block shares with another (a joint's position and the end of a link) is
    gathered once. A block's array that is a broadcast view of one number (a fixed pivot, a
    constant crank speed) stays a broadcast view over all positions, as long as every block
    holds the same number.
    """

    def __init__(self, first: Solution, n: int):
        self.n = n
        self._slots: dict[int, int] = {}       # id of a first-block array → index in self._arrays
        self._arrays: list[np.ndarray] = []
        self._layout = self._walk(first)

    def _slot(self, array) -> int | None:
        if array is None:
            return None
        if id(array) not in self._slots:
            array = np.asarray(array)
            self._slots[id(array)] = len(self._arrays)
            self._arrays.append(constant(array[0], (self.n,)) if _constant(array)
                                else np.empty(self.n, dtype=array.dtype))
        return self._slots[id(array)]

    @staticmethod
    def _parts(part: Solution):
        motions: list[tuple[str, str, Motion]] = [("angle", name, part.angle(name)) for name in part.angle_names
                                                  if name != "crank"]
        motions += [("point", name, part.point(name)) for name in part.point_names]
        motions += [("slider", name, part.slider(name)) for name in part.slider_names]
        return motions

    def _walk(self, part: Solution):
        layout = [(kind, name, type(motion), [self._slot(d) for d in motion.derivatives()])
                  for kind, name, motion in self._parts(part)]
        extras = {joint: {key: self._slot(value) for key, value in values.items()}
                  for joint, values in part.extras.items()}
        return layout, extras, self._slot(part.singular)

    def store(self, part: Solution, where: slice) -> None:
        layout, extras, singular = self._layout
        for (_, _, _, slots), (_, _, motion) in zip(layout, self._parts(part)):
            for slot, values in zip(slots, motion.derivatives()):
                if slot is not None:
                    self._put(slot, where, values)
        for joint, values in extras.items():
            for key, slot in values.items():
                self._put(slot, where, part.extras[joint][key])
        self._put(singular, where, part.singular)

    def _put(self, slot: int, where: slice, values: np.ndarray) -> None:
        target = self._arrays[slot]
        if _constant(target):
            number = target[0]
            if _constant(values) and _same(values[0], number):
                return
            # a number that changes from one block to the next: an array after all
            self._arrays[slot] = np.empty(self.n, dtype=target.dtype)
            self._arrays[slot][:where.start] = number
            target = self._arrays[slot]
        target[where] = values

    def solution(self, crank: AngleMotion, order: int, links: dict[str, str]) -> Solution:
        layout, extras, singular = self._layout
        array = self._arrays.__getitem__
        groups: dict[str, dict[str, Motion]] = {"angle": {"crank": crank}, "point": {}, "slider": {}}
        for kind, name, cls, slots in layout:
            groups[kind][name] = cls(*(None if slot is None else array(slot) for slot in slots))
        extras = {joint: {key: array(slot) for key, slot in values.items()} for joint, values in extras.items()}
        return Solution(crank.value, order, angles=cast(dict[str, AngleMotion], groups["angle"]),
                        points=cast(dict[str, PointMotion], groups["point"]), links=links,
                        sliders=groups["slider"], extras=extras, singular=array(singular))


def _same(a, b) -> bool:
    """Two numbers equal, or both not a number."""
    return bool(a == b or (a != a and b != b))


def _constant(array: np.ndarray) -> bool:
    """True for a one-dimensional broadcast view of one number (a zero stride)."""
    return array.ndim == 1 and array.strides[0] == 0 and array.size > 0


def solve_in_chunks(solve: Callable[[AngleMotion, int], Solution], crank: AngleMotion, order: int,
                    links: dict[str, str], block: int = BLOCK) -> Solution:
    """``solve(crank, order)`` over blocks of at most ``block`` positions, gathered into one solution.

    Parameters
    ----------
    solve : callable
        A mechanism's solution of one block: crank motion and order →
        :class:`~mechanisms.base.Solution`, elementwise in the positions, with the crank's own
        motion under the name ``"crank"``.
    crank : AngleMotion
        The crank's motion over all positions.
    order : int
        0, 1 or 2.
    links : dict
        The mechanism's links (name → first joint).
    block : int
        Positions per block; arrays of up to four blocks, and arrays that are not one-dimensional,
        are solved at once.

    Notes
    -----
    Where a block cannot be assembled, the whole array is solved at once instead, so that the
    :class:`~mechanisms.errors.AssemblyError` names every crank angle that fails.
    """
    phi = crank.value
    if np.ndim(phi) != 1 or phi.size <= 4 * block:
        return solve(crank, order)
    gather = None
    try:
        for start in range(0, phi.size, block):
            where = slice(start, start + block)
            part = solve(crank[where], order)
            if gather is None:
                gather = _Gather(part, phi.size)
            gather.store(part, where)
            del part
    except AssemblyError:
        return solve(crank, order)
    assert gather is not None   # more than four blocks: the loop ran
    return gather.solution(crank, order, links)


solve_in_blocks = solve_in_chunks
"""The name of :func:`solve_in_chunks` in version 0.1 (kept for one release)."""
