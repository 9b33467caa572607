"""Tests of mechanisms.verify.jet: exact derivatives along a path, against derivatives taken by hand."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanisms.verify.jet import Jet

xs = st.floats(0.1, 3.0)


@settings(max_examples=50, deadline=None)
@given(x=xs, d1=st.floats(-2, 2), d2=st.floats(-2, 2))
def test_composition_against_hand_derivatives(x, d1, d2):
    # f(u) = sin(u)·sqrt(u) / (1 + u²) + exp(−u) cos(u) along u(t) with u' = d1, u'' = d2;
    # expected: f'(u) and f''(u) differentiated by hand, then the chain rule f' d1, f'' d1² + f' d2
    u = Jet(np.array([x]), np.array([d1]), np.array([d2]))
    got = np.sin(u) * np.sqrt(u) / (1 + u * u) + np.exp(-u) * np.cos(u)

    def f(v):
        return np.sin(v) * np.sqrt(v) / (1 + v**2) + np.exp(-v) * np.cos(v)

    def f1(v):
        g = np.sin(v) * np.sqrt(v)
        g1 = np.cos(v) * np.sqrt(v) + np.sin(v) / (2 * np.sqrt(v))
        h = 1 + v**2
        return (g1 * h - g * 2 * v) / h**2 - np.exp(-v) * (np.cos(v) + np.sin(v))

    def f2(v):
        g = np.sin(v) * np.sqrt(v)
        g1 = np.cos(v) * np.sqrt(v) + np.sin(v) / (2 * np.sqrt(v))
        g2 = -np.sin(v) * np.sqrt(v) + np.cos(v) / np.sqrt(v) - np.sin(v) / (4 * v**1.5)
        h, h1, h2 = 1 + v**2, 2 * v, 2.0
        quotient2 = (g2 * h - g * h2) / h**2 - 2 * h1 * (g1 * h - g * h1) / h**3
        return quotient2 + 2 * np.exp(-v) * np.sin(v)

    np.testing.assert_allclose(got.f, f(x), rtol=1e-14)
    np.testing.assert_allclose(got.d1, f1(x) * d1, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(got.d2, f2(x) * d1**2 + f1(x) * d2, rtol=1e-11, atol=1e-12)


def test_mixed_with_arrays_and_powers():
    # expected: (3 − 2u)³ along u' = 1: value, −6(3 − 2u)², 24(3 − 2u) (by hand)
    u = Jet(np.array([0.5, 1.0]), 1.0, 0.0)
    got = (np.array([3.0, 3.0]) - 2 * u) ** 3
    base = 3 - 2 * np.array([0.5, 1.0])
    np.testing.assert_allclose(got.f, base**3)
    np.testing.assert_allclose(got.d1, -6 * base**2)
    np.testing.assert_allclose(got.d2, 24 * base)
    ratio = 1.0 / u
    np.testing.assert_allclose(ratio.d2, 2 / np.array([0.5, 1.0]) ** 3)


def test_complex_exponential_parts():
    # expected: exp(iθ) along θ' = w: derivative i w exp(iθ), second −w² exp(iθ)
    w = 3.0
    theta = Jet(np.array([0.3]), w, 0.0)
    z = np.exp(1j * theta)
    np.testing.assert_allclose(z.real.d1, -w * np.sin(0.3))
    np.testing.assert_allclose(z.imag.d2, -(w**2) * np.sin(0.3))
