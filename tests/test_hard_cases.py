"""The hard cases of chapter 9: singular positions, change points, limits of assembly, extreme scales.

Every expected value comes from outside the closed form under test: the extended-precision
solution of the constraint equations (:func:`mechanisms.bench.reference`, Newton's method in
``numpy.longdouble`` with exact derivatives), a hand calculation of the geometry, or the same
mechanism at another scale. The stated accuracies are those of a backward-stable computation:
near a limit of assembly at distance δ (rad) positions are conditioned like 1/√δ and velocities
like 1/δ, so their errors may be ε/√δ and ε/δ (ε = 2.2e-16), and no more.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.bench import jacobian_condition, reference
from mechanisms.core.errors import AssemblyError, SingularPositionWarning
from mechanisms.linkages.four_bar import _pqf, half_angle_coupler_angle, stable_coupler_angle

EPS = np.finfo(float).eps


def wrap(angle):
    return (np.asarray(angle, dtype=float) + np.pi) % (2.0 * np.pi) - np.pi


def coordinates(m, sol):
    coords = m.coordinates(sol)
    return (np.array([c.value for c in coords]), np.array([c.velocity for c in coords]),
            np.array([c.acceleration for c in coords]))


# --- the singular positions of a non-Grashof linkage ----------------------------------------------------

NON_GRASHOF = dict(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))   # s + l = 5 > p + q = 4.5


def limit_angle():
    # the analytic limit of assembly: |AC| = L2 + L3 (four_bar.assembly_intervals, from the cosine law)
    (low, high), = mech.FourBar(**NON_GRASHOF).assembly_intervals()
    assert low == pytest.approx(-high)
    return high


@pytest.mark.parametrize("delta", [1e-3, 1e-6, 1e-9])
def test_dead_centre_approach_is_finite_and_as_accurate_as_its_conditioning(delta):
    m = mech.FourBar(**NON_GRASHOF)
    phi = np.array([limit_angle() - delta, -limit_angle() + delta])
    sol = m.solve(phi, omega=1.0)          # no SingularPositionWarning: pytest turns it into an error
    assert not sol.singular.any()
    q, q_t, q_tt = coordinates(m, sol)
    ref = reference(m, phi)
    assert np.all(np.isfinite(q_t)) and np.all(np.isfinite(q_tt))
    # positions: conditioned like 1/√δ; velocities like 1/δ (relative), see the module docstring
    assert np.max(np.abs(wrap(q - ref[0].astype(float)))) <= 8 * EPS / math.sqrt(delta)
    assert np.max(np.abs((q_t - ref[1].astype(float)) / ref[1].astype(float))) <= 8 * EPS / delta
    # the velocities really grow like 1/√δ: |ψ_t|·√δ stays near its limit (about 0.38 1/s here)
    assert 0.2 < np.abs(q_t[0, 0]) * math.sqrt(delta) < 0.6


def test_dead_centre_is_flagged_and_beyond_it_is_an_assembly_error():
    m = mech.FourBar(**NON_GRASHOF)
    with pytest.warns(SingularPositionWarning):
        sol = m.solve([limit_angle()], omega=1.0)
    assert sol.singular[0]
    assert np.isfinite(sol.point("B").value[0])            # the position is still finite
    assert np.isnan(sol.angle("coupler").omega[0])          # the velocity is not: flagged, not a number
    with pytest.raises(AssemblyError) as error:
        m.solve([limit_angle() + 1e-9], omega=1.0)
    assert error.value.valid_range == pytest.approx((-limit_angle(), limit_angle()))
    assert "cannot be assembled" in str(error.value)


def test_dead_centre_branch_is_held_up_to_the_limit():
    # B stays on the side +1 (left of A → C): the cross product (C − A) × (B − A) stays positive
    m = mech.FourBar(**NON_GRASHOF, branch=1)
    phi = limit_angle() - np.logspace(-1, -9, 9)
    sol = m.solve(phi, order=0)
    a, b, c = (sol.point(n).value for n in "ABC")
    assert np.all(((c - a).conjugate() * (b - a)).imag > 0)


def test_condition_number_grows_like_one_over_root_delta_at_the_dead_centre():
    m = mech.FourBar(**NON_GRASHOF)
    deltas = np.array([1e-2, 1e-4, 1e-6])
    cond = jacobian_condition(m, limit_angle() - deltas)
    # each factor 100 closer multiplies the condition number by about 10
    assert np.allclose(cond[1:] / cond[:-1], 10.0, rtol=0.05)
    assert jacobian_condition(m, [0.0])[0] < 10.0


# --- the parallelogram's change point -------------------------------------------------------------

def parallelogram():
    # crank = rocker = 1, coupler = frame = 4: a change-point linkage (s + l = p + q)
    return mech.FourBar(crank=1.0, coupler=4.0, rocker=1.0, frame=(4.0, 0.0))


@pytest.mark.parametrize("delta", [1e-2, 1e-4])
def test_parallelogram_stays_a_parallelogram_through_the_change_point(delta):
    m = parallelogram()
    phi = np.array([-delta, delta, math.pi - delta, math.pi + delta])
    sol = m.solve(phi, omega=1.0)
    # by hand: in a parallelogram the rocker stays parallel to the crank (ξ = φ, ξ_t = φ_t)
    # and the coupler parallel to the frame (ψ = 0, ψ_t = 0)
    assert np.max(np.abs(wrap(sol.angle("rocker").angle - phi))) <= 8 * EPS / delta
    assert np.max(np.abs(wrap(sol.angle("coupler").angle))) <= 8 * EPS / delta
    assert np.max(np.abs(sol.angle("rocker").omega - 1.0)) <= 8 * EPS / delta**2
    assert np.max(np.abs(sol.angle("coupler").omega)) <= 8 * EPS / delta**2


def test_parallelogram_change_point_itself_is_flagged():
    m = parallelogram()
    with pytest.warns(SingularPositionWarning):
        sol = m.solve([0.0, math.pi], omega=1.0)
    assert sol.singular.all()
    assert np.all(np.isfinite(sol.point("B").value))
    assert np.all(np.isnan(sol.angle("rocker").omega))
    assert np.isinf(jacobian_condition(m, [0.0])[0]) or jacobian_condition(m, [0.0])[0] > 1e15


# --- the half-angle formula near P + F = 0 --------------------------------------------------------

HALF_ANGLE = (1.0, 3.5, 3.0, (-2.0, 3.0))   # crank, coupler, rocker, frame: P + F changes sign twice


def half_angle_root():
    """The crank angle near 2.4° where P + F = 0, by bisection on the lecture's P and F."""
    def s(phi):
        p, _, f = _pqf(phi, *HALF_ANGLE)
        return float(p + f)
    low, high = math.radians(0.0), math.radians(5.0)
    assert s(low) * s(high) < 0
    for _ in range(200):
        middle = 0.5 * (low + high)
        if s(low) * s(middle) <= 0:
            high = middle
        else:
            low = middle
    return low


def test_half_angle_formula_loses_digits_near_p_plus_f_zero_and_the_stable_form_does_not():
    root = half_angle_root()
    offsets = np.array([1e-2, 1e-5, 1e-8, 1e-11])
    phi = root + offsets
    m = mech.FourBar(crank=1.0, coupler=3.5, rocker=3.0, frame=(-2.0, 3.0), branch=-1)
    ref = reference(m, phi)[0][0].astype(float)
    lecture = half_angle_coupler_angle(phi, *HALF_ANGLE, branch=-1)
    stable = stable_coupler_angle(phi, *HALF_ANGLE, branch=-1)
    lecture_error = np.abs(wrap(lecture - ref))
    stable_error = np.abs(wrap(stable - ref))
    assert np.max(stable_error) <= 8 * EPS
    assert np.max(np.abs(wrap(m.solve(phi, order=0).angle("coupler").angle - ref))) <= 8 * EPS
    # the lecture's form: cancellation in Q − √(Q² + P² − F²), divided by P + F → 0
    assert lecture_error[-1] > 1e3 * EPS
    assert lecture_error[-1] > 100 * lecture_error[0]


def test_half_angle_formula_at_p_plus_f_zero_divides_zero_by_zero():
    root = half_angle_root()
    p, _, f = _pqf(root, *HALF_ANGLE)
    if p + f == 0.0:    # the bisection may land exactly on the root or next to it
        assert np.isnan(half_angle_coupler_angle(root, *HALF_ANGLE, branch=-1))
    stable = stable_coupler_angle(root, *HALF_ANGLE, branch=-1)
    assert np.isfinite(stable)


# --- the crank-slider whose coupler is exactly L1 + e ---------------------------------------------

def test_crank_slider_with_rod_equal_to_crank_plus_offset():
    m = mech.CrankSlider(crank=1.0, rod=1.5, offset=0.5)     # full revolution, just: L2 = L1 + e
    assert m.full_revolution
    # at φ = −90° the pin is L1 + e = L2 below the guide: the rod is perpendicular to it
    with pytest.warns(SingularPositionWarning):
        sol = m.solve([-math.pi / 2], omega=1.0)
    assert sol.singular[0]
    assert sol.slider("B").value[0] == pytest.approx(0.0, abs=1e-15)      # B right above O (by hand)
    assert not np.isfinite(sol.slider("B").velocity[0])
    # a thousandth of a radian away everything is finite and accurate
    phi = np.array([-math.pi / 2 - 1e-3, -math.pi / 2 + 1e-3])
    sol = m.solve(phi, omega=1.0)
    q, q_t, _ = coordinates(m, sol)
    ref = reference(m, phi)
    assert np.max(np.abs(wrap(q[0] - ref[0][0].astype(float)))) <= 8 * EPS / math.sqrt(1e-6)
    assert np.max(np.abs(q_t - ref[1].astype(float))) <= 8 * EPS / 1e-6 * 10


def test_crank_slider_beyond_reach_is_an_assembly_error():
    m = mech.CrankSlider(crank=1.0, rod=1.5 - 1e-6, offset=0.5)   # cannot reach at φ = −90°
    with pytest.raises(AssemblyError):
        m.solve([-math.pi / 2], omega=1.0)
    m.solve([0.0, math.pi / 2], omega=1.0)                       # elsewhere it assembles


# --- the slotted lever whose block passes through the pivot ---------------------------------------

def test_slotted_lever_block_through_the_pivot_is_finite():
    m = mech.SlottedLever(crank=1.0, pivot=(1.0, 0.0))
    assert m.kind == "through pivot"
    phi = np.array([-1e-9, 0.0, 1e-9, 1.0])
    sol = m.solve(phi, omega=2.0)                  # no SingularPositionWarning
    assert not sol.singular.any()
    # inscribed-angle theorem: the lever turns at half the crank's speed
    assert np.allclose(sol.angle("lever").omega, 1.0, rtol=0, atol=1e-15)
    # at the pivot the block slides at the crank pin's speed r·ω = 2 m/s (by hand)
    assert sol.slider("A").velocity[1] == pytest.approx(2.0, abs=1e-15)
    assert sol.slider("A").value[1] == 0.0


# --- very unequal lengths, very large and very small scales, large crank angles -----------------

def test_very_unequal_lengths_crank_slider():
    crank, rod = 1e-8, 1.0
    m = mech.CrankSlider(crank=crank, rod=rod)
    phi = np.linspace(0.0, 2.0 * np.pi, 25)
    sol = m.solve(phi, omega=1.0)
    # by hand, to O(L1⁴): s = L1 cos φ + L2 − (L1 sin φ)²/(2 L2), and its derivative at ω = 1
    # s_t = −L1 sin φ − L1² sin φ cos φ / L2
    expected = crank * np.cos(phi) + rod - (crank * np.sin(phi)) ** 2 / (2 * rod)
    assert np.max(np.abs(sol.slider("B").value - expected)) <= 2 * EPS
    expected_t = -crank * np.sin(phi) - crank**2 * np.sin(phi) * np.cos(phi) / rod
    # the slider's speed is 1e-8 m/s, and it is right to the last digits of that speed
    assert np.max(np.abs(sol.slider("B").velocity - expected_t)) <= 4 * EPS * crank


def test_very_unequal_lengths_four_bar_against_reference():
    m = mech.FourBar(crank=1e-8, coupler=3.5, rocker=3.0, frame=(4.0, 0.0))
    phi = np.linspace(0.0, 2.0 * np.pi, 25)
    q, q_t, q_tt = coordinates(m, m.solve(phi, omega=1.0))
    ref = reference(m, phi)
    # the rocker's swing is ~1e-8 rad: its speed must still be right to many digits, relative to the crank
    assert np.max(np.abs(q_t - ref[1].astype(float))) <= 1e-8 * 1e-7
    assert np.max(np.abs(q_tt - ref[2].astype(float))) <= 1e-8 * 1e-7


@pytest.mark.parametrize("scale", [1e-150, 1e-50, 1e50, 1e150])
@pytest.mark.parametrize("name", ["crank-slider", "four-bar", "slotted-lever"])
def test_scale_invariance(name, scale):
    from mechanisms.bench import benchmark_mechanisms
    unit = benchmark_mechanisms()[name]
    parameters = {k: (tuple(scale * v for v in value) if isinstance(value, tuple) else
                      value if k == "branch" else scale * value)
                  for k, value in unit.parameters().items()}
    scaled = type(unit)(**parameters)
    phi = np.linspace(0.0, 2.0 * np.pi, 37)
    a, b = unit.solve(phi, omega=3.0), scaled.solve(phi, omega=3.0)
    # the same mechanism at another scale: angles equal, lengths proportional (geometry)
    for link in a.angle_names:
        for x, y in zip(a.angle(link).derivatives(), b.angle(link).derivatives()):
            assert np.max(np.abs(wrap(x - y))) <= 16 * EPS * (1 + np.max(np.abs(x)))
    for point in a.point_names:
        for x, y in zip(a.point(point).derivatives(), b.point(point).derivatives()):
            assert np.max(np.abs(x - y / scale)) <= 16 * EPS * (1 + np.max(np.abs(x)))


@pytest.mark.parametrize("turns", [0, 1e6, 1e12])
def test_large_crank_angles_are_reduced_exactly(turns):
    m = mech.FourBar(crank=1.0, coupler=3.5, rocker=3.0, frame=(4.0, 0.0))
    phi = 2.0 * np.pi * turns + np.linspace(0.0, 2.0 * np.pi, 13)
    q, q_t, _ = coordinates(m, m.solve(phi, omega=1.0))
    ref = reference(m, phi)    # sin and cos of the same double angles, in extended precision
    assert np.max(np.abs(wrap(q - ref[0].astype(float)))) <= 8 * EPS
    assert np.max(np.abs(q_t - ref[1].astype(float))) <= 8 * EPS


def test_reference_agrees_with_the_generic_solver():
    # two independent solutions of the same constraint equations
    m = mech.FourBar(**NON_GRASHOF)
    phi = np.linspace(-2.0, 2.0, 9)
    ref = reference(m, phi)
    generic = mech.verify.solve_constraints(m.constraints, ref[0][:, 0].astype(float), phi, 1.0, 0.0, tol=1e-15)
    assert np.max(np.abs(wrap(generic.q - ref[0].astype(float)))) <= 8 * EPS
    assert np.max(np.abs(generic.q_t - ref[1].astype(float))) <= 64 * EPS


# --- limits of assembly found by the package itself (regressions from an audit) -------------------

@settings(max_examples=60, deadline=None)
@given(crank=st.floats(0.05, 1.0), rod=st.floats(0.05, 1.0), offset=st.floats(-0.5, 0.5))
def test_crank_slider_at_the_ends_of_its_own_ranges(crank, rod, offset):
    # expected (by the mathematics): at a limit of assembly the rod stands perpendicular to the
    # guide, so the rates are unbounded: marked singular, never a huge finite number, never an error
    from mechanisms.linkages.crank_slider import CrankSlider
    try:
        m = CrankSlider(crank, rod, offset)
    except mech.AssemblyError:
        return                                    # the rod never reaches the guide
    if m.full_revolution:
        return
    ends = np.array([end for interval in m.assembly_ranges for end in interval])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mech.SingularPositionWarning)
        sol = m.solve(ends, 1.0)
    v = sol.slider("B").velocity
    assert np.all(sol.singular | (np.abs(v) < 1e3 * (crank + rod)))
    assert np.all(~np.isfinite(v[sol.singular]))


@settings(max_examples=60, deadline=None)
@given(lengths=st.tuples(st.floats(0.05, 1.0), st.floats(0.05, 1.0), st.floats(0.05, 1.0)),
       frame=st.tuples(st.floats(0.05, 1.0), st.floats(-0.3, 0.3)))
def test_four_bar_at_the_ends_of_its_own_intervals(lengths, frame):
    from mechanisms.linkages.four_bar import FourBar
    try:
        m = FourBar(*lengths, frame)
        intervals = m.assembly_intervals()
    except mech.AssemblyError:
        return
    ends = np.array([end for interval in intervals for end in interval
                     if abs(interval[1] - interval[0]) < 2 * np.pi - 1e-9])
    if ends.size == 0:
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mech.SingularPositionWarning)
        sol = m.solve(ends, 1.0)
    w = sol.angle("rocker").omega
    assert np.all(sol.singular | (np.abs(w) < 1e4))


def test_an_undetermined_slider_velocity_is_nan_and_an_unbounded_one_inf():
    import warnings

    from mechanisms import CrankSlider
    # L2 = L1 + e exactly: at φ = −90° the pin is L2 below the guide and moves along it (its velocity
    # across the guide is zero), so the rates are 0/0; the one-sided velocities are 1 ∓ 1.2247 m/s
    # (by hand: s_t = ω(−L1 sin φ ∓ L1 cos φ·(L1 sin φ − e)/c_B) → 1 ∓ √1.5 as φ → −90°)
    m = CrankSlider(crank=1.0, rod=1.5, offset=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = m.solve(np.radians([-90.0]) + np.array([-1e-5, 0.0, 1e-5]), omega=1.0)
        v = sol.slider("B").velocity
        assert sol.singular.tolist() == [False, True, False]
        assert np.isnan(v[1]) and np.isnan(sol.angle("coupler").omega[1])
        assert sorted(v[[0, 2]]) == pytest.approx([1 - np.sqrt(1.5), 1 + np.sqrt(1.5)], abs=5e-3)
        # the ends of a rocking range (L2 < L1): there the rates are truly unbounded
        rocking = CrankSlider(crank=1.0, rod=0.8)
        ends = rocking.solve(np.array(rocking.assembly_intervals()[0]), omega=1.0)
        assert np.all(np.isinf(ends.slider("B").velocity)) and ends.singular.all()
