"""Layer 5 helper: exact first and second derivatives along a path (second-order jets).

A :class:`Jet` carries a value ``f`` with its first and second derivatives ``f'``, ``f''``
with respect to one parameter (time, or a step along a direction). Arithmetic and the numpy
functions a constraint equation uses follow the chain rule, so derivatives of any constraint
function written with ``+ − * /``, ``np.sin``, ``np.cos``, ``np.sqrt``, ``np.exp`` are exact to
round-off, without finite differences. This is what makes the generic solver of
:mod:`mechanisms.verify` an independent, high-accuracy reference for the closed forms.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["Jet"]


def _parts(x):
    if isinstance(x, Jet):
        return x.f, x.d1, x.d2
    return x, 0.0, 0.0


class Jet:
    """A value with its first and second derivatives: ``(f, f', f'')``."""

    __array_priority__ = 100  # numpy arrays defer to Jet in mixed arithmetic

    def __init__(self, f: ArrayLike, d1: ArrayLike = 0.0, d2: ArrayLike = 0.0):
        # arrays or numbers of any float type (double, extended): numpy's arithmetic decides
        self.f: Any = f
        self.d1: Any = d1
        self.d2: Any = d2

    # arithmetic --------------------------------------------------------------
    def __add__(self, other):
        a, a1, a2 = _parts(other)
        return Jet(self.f + a, self.d1 + a1, self.d2 + a2)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.f, -self.d1, -self.d2)

    def __pos__(self):
        return self

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        a, a1, a2 = _parts(other)
        return Jet(self.f * a, self.d1 * a + self.f * a1,
                   self.d2 * a + 2.0 * self.d1 * a1 + self.f * a2)

    __rmul__ = __mul__

    def reciprocal(self) -> Jet:
        """``1/f`` with its derivatives."""
        inv = 1.0 / self.f
        return Jet(inv, -self.d1 * inv**2, (2.0 * self.d1**2 * inv - self.d2) * inv**2)

    def __truediv__(self, other):
        if isinstance(other, Jet):
            return self * other.reciprocal()
        return Jet(self.f / other, self.d1 / other, self.d2 / other)

    def __rtruediv__(self, other):
        return self.reciprocal() * other

    def __pow__(self, n):
        if n == 2:
            return self * self
        g = self.f ** n
        g1 = n * self.f ** (n - 1)
        g2 = n * (n - 1) * self.f ** (n - 2)
        return self._chain(g, g1, g2)

    def _chain(self, g, g1, g2):
        """Compose with a scalar function g: value g, g' = g1, g'' = g2 at f."""
        return Jet(g, g1 * self.d1, g2 * self.d1**2 + g1 * self.d2)

    @property
    def real(self):
        return Jet(np.real(self.f), np.real(self.d1), np.real(self.d2))

    @property
    def imag(self):
        return Jet(np.imag(self.f), np.imag(self.d1), np.imag(self.d2))

    # numpy functions -----------------------------------------------------------
    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        if method != "__call__" or kwargs:
            return NotImplemented
        if ufunc in _BINARY:
            a, b = inputs
            a = a if isinstance(a, Jet) else Jet(a)
            return _BINARY[ufunc](a, b)
        if ufunc in _UNARY:
            (x,) = inputs
            return _UNARY[ufunc](x)
        return NotImplemented

    def __repr__(self) -> str:
        return f"Jet({self.f!r}, {self.d1!r}, {self.d2!r})"


def _sin(x: Jet) -> Jet:
    s, c = np.sin(x.f), np.cos(x.f)
    return x._chain(s, c, -s)


def _cos(x: Jet) -> Jet:
    s, c = np.sin(x.f), np.cos(x.f)
    return x._chain(c, -s, -c)


def _sqrt(x: Jet) -> Jet:
    r = np.sqrt(x.f)
    return x._chain(r, 0.5 / r, -0.25 / (r * x.f))


def _exp(x: Jet) -> Jet:
    e = np.exp(x.f)
    return x._chain(e, e, e)


_UNARY = {
    np.sin: _sin,
    np.cos: _cos,
    np.sqrt: _sqrt,
    np.exp: _exp,
    np.negative: Jet.__neg__,
    np.positive: Jet.__pos__,
    np.square: lambda x: x * x,
}
_BINARY = {
    np.add: Jet.__add__,
    np.subtract: Jet.__sub__,
    np.multiply: Jet.__mul__,
    np.true_divide: Jet.__truediv__,
}
