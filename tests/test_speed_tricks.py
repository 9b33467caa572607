"""Each speed trick against the plain form the book shows: the same numbers, to stated round-off.

* ``hinge`` (in place) against ``hinge_plain`` (the book's formulas in plain numpy);
* ``unit_vector_fast`` (tangent of the half angle) against ``unit_vector`` (``exp(iθ)``);
* solving in chunks (``linkages.chunks``) against solving all positions at once.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.blocks.circle_circle import hinge, hinge_plain
from mechanisms.blocks.crank import crank_angle, crank_pin
from mechanisms.core.angles import unit_vector, unit_vector_fast
from mechanisms.core.motion import fixed_point
from strategies import crank_rockers, finite

EPS = np.finfo(float).eps


@settings(max_examples=40, deadline=None)
@given(geometry=crank_rockers(), omega=st.floats(-30, 30, **finite), alpha=st.floats(-100, 100, **finite))
def test_hinge_in_place_equals_the_plain_form(geometry, omega, alpha):
    crank, coupler, rocker, frame, branch = geometry
    phi = np.linspace(-np.pi, np.pi, 97)
    pin = crank_pin(crank_angle(phi, omega, alpha), crank)
    pivot = fixed_point(complex(*frame), phi)
    fast, plain = hinge(pin, pivot, coupler, rocker, branch), hinge_plain(pin, pivot, coupler, rocker, branch)
    np.testing.assert_array_equal(fast.singular, plain.singular)
    # the same formulas in another order of operations: a few ulps of each quantity's scale
    size = crank + coupler + rocker + abs(complex(*frame))
    rate = abs(omega) + 1.0
    for a, b, scale in ((fast.point, plain.point, size), (fast.angle_p, plain.angle_p, np.pi),
                        (fast.angle_q, plain.angle_q, np.pi)):
        for k, (x, y) in enumerate(zip(a.derivatives(), b.derivatives())):
            tolerance = 64 * EPS * scale * rate**k * (1.0 + abs(alpha)) ** (k == 2) * (size / min(coupler, rocker))
            np.testing.assert_allclose(x, y, rtol=0, atol=tolerance)


@settings(max_examples=60, deadline=None)
@given(span=st.floats(1e-3, 1e6, **finite), length=st.floats(1e-3, 1e3, **finite))
def test_unit_vector_from_the_half_angle_is_round_off_of_the_plain_one(span, length):
    phi = np.linspace(-span, span, 101)
    # 2.5 ulp per component (the tangent, the square, the division) plus the plain form's 0.5 ulp
    np.testing.assert_allclose(unit_vector_fast(phi, length), unit_vector(phi, length), rtol=0, atol=4 * EPS * length)


def test_solving_in_chunks_equals_solving_at_once():
    from mechanisms.linkages import chunks
    m = mech.FourBar.example()
    phi = np.linspace(0.0, 40.0, 5 * chunks.BLOCK + 17)
    whole = m._solve_block(crank_angle(phi, 3.0, 0.5, 2), 2)
    parts = m.solve(phi, 3.0, 0.5)
    for name in whole.angle_names:
        for x, y in zip(whole.angle(name).derivatives(), parts.angle(name).derivatives()):
            np.testing.assert_allclose(x, y, rtol=0, atol=1e-12 * (1 + np.max(np.abs(y))))
