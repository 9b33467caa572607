"""Layer 5: numerical time derivatives of a function of the crank angle (central differences)."""

from __future__ import annotations

from typing import Callable

import numpy as np
from numpy.typing import ArrayLike

from ..core.angles import wrap_angle

__all__ = ["central_difference"]


def central_difference(function: Callable[[np.ndarray], np.ndarray], phi: ArrayLike, omega: float, step: float = 1e-4,
                       derivative: int = 1, angle: bool = False) -> np.ndarray:
    """Numerical time derivative of a function of the crank angle, at constant ω.

    Parameters
    ----------
    function : callable
        ``g(φ)``: positions (m, complex or real) or angles (rad) at crank angles φ.
    phi : array_like
        Crank angles (rad).
    omega : float
        Constant crank speed φ_t (1/s).
    step : float
        Step h in the crank angle (rad).
    derivative : int
        1: ``g_t ≈ ω (g(φ+h) − g(φ−h)) / 2h``; 2: ``g_tt ≈ ω² (g(φ+h) − 2g(φ) + g(φ−h)) / h²``.
    angle : bool
        Treat g as an angle: differences are wrapped to (−π, π].

    Notes
    -----
    Truncation error O(h²) against round-off O(ε_mach/h) (first) or O(ε_mach/h²) (second): the best
    step is about 1e-5 for the first and 1e-4 for the second derivative (chapter 9).
    """
    phi = np.asarray(phi, dtype=float)
    ahead, behind = function(phi + step), function(phi - step)
    if derivative == 1:
        diff = wrap_angle(ahead - behind) if angle else ahead - behind
        return omega * diff / (2.0 * step)
    here = function(phi)
    if angle:
        return omega**2 * (wrap_angle(ahead - here) - wrap_angle(here - behind)) / step**2
    return omega**2 * (ahead - 2.0 * here + behind) / step**2
