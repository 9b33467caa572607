"""The driving crank: a link turning a full revolution about a fixed pivot."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..core.validate import ALPHA_MAX, OMEGA_MAX, require_angles, require_order, require_rates
from ..core.angles import constant
from ..core.motion import AngleMotion, PointMotion, point_on_link

__all__ = ["crank_angle", "crank_pin"]


def crank_angle(phi: ArrayLike, omega: ArrayLike, alpha: ArrayLike = 0.0, order: int = 2) -> AngleMotion:
    """The crank's angle φ with φ_t = ω and φ_tt = ε, as arrays over the positions.

    Parameters
    ----------
    phi : array_like
        Crank angles φ (rad), counter-clockwise from +x: finite real numbers, |φ| ≤ 2^52 rad.
    omega : float or array_like
        Angular velocity φ_t (1/s) at each position: one number or one per crank angle (an array
        that broadcasts to the shape of ``phi``), each finite, |ω| ≤ 1e50 1/s.
    alpha : float or array_like
        Angular acceleration φ_tt (1/s²) at each position, likewise; |ε| ≤ 1e100 1/s².
    order : int
        0, 1 or 2: how many time derivatives to keep.

    Raises
    ------
    InvalidParameterError
        Naming ``phi``, ``omega``, ``alpha`` or ``order`` when it is not of the kind or range above
        (None, a string, a bool, a complex number, NaN, an array of the wrong shape …).

    Notes
    -----
    A constant ω or ε is kept as a read-only view of one number
    (:func:`~mechanisms.motion.constant`), which takes no memory.
    """
    order = require_order(order)
    phi = require_angles("phi", phi)
    rates = (("omega", omega, OMEGA_MAX, "1/s"), ("alpha", alpha, ALPHA_MAX, "1/s²"))
    checked = [require_rates(name, value, phi.shape, high, unit) for name, value, high, unit in rates]
    if order == 0:
        return AngleMotion(phi)
    derivatives = []
    for value in checked[:order]:
        # a constant rate is a broadcast view of one number (no memory); an array is copied
        derivatives.append(constant(float(value), phi.shape) if value.ndim == 0
                           else np.broadcast_to(value, phi.shape).astype(float))
    return AngleMotion(phi, *derivatives)


def crank_pin(angle: AngleMotion, length: float, pivot: complex = 0.0) -> PointMotion:
    """The crank pin A at distance L1 from the pivot O: ``r_A = r_O + L1·exp(iφ)``."""
    return point_on_link(complex(pivot), angle, length)
