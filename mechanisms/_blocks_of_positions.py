"""Layer 3 helper: solve a long array of crank positions block by block, in the processor's cache.

A closed form is a chain of some dozens of array operations. Over a million positions each
operation writes an array of 8–16 MB and the next one reads it back: far more than the
processor's cache holds, so the chain waits on main memory. Over a block of some ten thousand
positions the temporaries stay in the cache, and the memory they use is reused by the next block;
each block's results are copied once into the arrays over all positions. Every operation of the
closed forms is elementwise, so the result is that of solving all positions at once, to round-off
(numpy's vector loops may round an element differently depending on where its array starts in
memory); it comes about one and a half times as fast (chapter 8).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from .base import Solution
from .errors import AssemblyError
from .motion import AngleMotion, Motion

__all__ = ["BLOCK", "solve_in_blocks"]

BLOCK = 8192
"""Positions per block: a complex temporary of 8192 positions is 128 kB."""


class _Gather:
    """Arrays over all positions, filled block by block, shaped like the first block's solution."""

    def __init__(self, first: Solution, n: int):
        self.n = n
        self._targets: dict[int, np.ndarray] = {}     # id of a block's array → the full array
        self._zeros: set[int] = set()                  # full arrays that are still all zero
        self._layout = self._walk(first, allocate=True)

    def _target(self, array, allocate: bool):
        if array is None:
            return None
        key = id(array)
        if allocate and key not in self._targets:
            array = np.asarray(array)
            if array.any():
                self._targets[key] = np.empty(self.n, dtype=array.dtype)
            else:
                # zeros (a fixed point's position at the origin, its velocity and acceleration): memory
                # that the system hands out zeroed and that is written only if a block is not zero
                self._targets[key] = np.zeros(self.n, dtype=array.dtype)
                self._zeros.add(id(self._targets[key]))
        return self._targets.get(key)

    def _walk(self, part: Solution, allocate: bool = False):
        motions = [("angle", name, part.angle(name)) for name in part.angle_names if name != "crank"]
        motions += [("point", name, part.point(name)) for name in part.point_names]
        motions += [("slider", name, part.slider(name)) for name in part.slider_names]
        layout = [(kind, name, type(motion), [self._target(d, allocate) for d in motion.derivatives()])
                  for kind, name, motion in motions]
        extras = {joint: {key: self._target(value, allocate) for key, value in values.items()}
                  for joint, values in part.extras.items()}
        return layout, extras, self._target(part.singular, allocate)

    def store(self, part: Solution, where: slice) -> None:
        motions = [part.angle(name) for name in part.angle_names if name != "crank"]
        motions += [part.point(name) for name in part.point_names]
        motions += [part.slider(name) for name in part.slider_names]
        layout, extras, singular = self._layout
        for (_, _, _, targets), motion in zip(layout, motions):
            for target, values in zip(targets, motion.derivatives()):
                if target is not None:
                    self._put(target, where, values)
        for joint, values in extras.items():
            for key, target in values.items():
                self._put(target, where, part.extras[joint][key])
        self._put(singular, where, part.singular)

    def _put(self, target: np.ndarray, where: slice, values: np.ndarray) -> None:
        if id(target) in self._zeros and not values.any():
            return
        target[where] = values

    def solution(self, crank: AngleMotion, order: int, links: dict[str, str]) -> Solution:
        layout, extras, singular = self._layout
        groups: dict[str, dict[str, Motion]] = {"angle": {"crank": crank}, "point": {}, "slider": {}}
        for kind, name, cls, targets in layout:
            groups[kind][name] = cls(*targets)
        return Solution(crank.value, order, angles=groups["angle"], points=groups["point"], links=links,
                        sliders=groups["slider"], extras=extras, singular=singular)


def solve_in_blocks(solve: Callable[[AngleMotion, int], Solution], crank: AngleMotion, order: int,
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
    return gather.solution(crank, order, links)
