"""Tests of the crank-slider (layer 3): closed form against the generic solver, the worked example,
checks of the analysis sequence, dead centres and bad input."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms import verify
from mechanisms.core.errors import AssemblyError, SingularPositionWarning, InvalidParameterError
from strategies import branches, crank_slider_geometries, finite

PHI = np.radians(np.arange(0.0, 360.0, 10.0))
EXAMPLE = dict(crank=0.08, rod=0.3)  # worked example 5.2 of the textbook page (source 004)
OMEGA = 215.0


def wrap(angle):
    return np.angle(np.exp(1j * angle))


# --- closed form against the generic solver --------------------------------------------------------

@settings(max_examples=40, deadline=None)
@given(geometry=crank_slider_geometries(), branch=branches, omega=st.floats(-300, 300, **finite),
       alpha=st.floats(-1e4, 1e4, **finite))
def test_closed_form_against_generic_solver(geometry, branch, omega, alpha):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    # reference: Newton's method on the loop closure, continued from φ = 0 around the turn
    err_q, err_v, err_a = verify.generic_errors(m, PHI, omega, alpha)
    scale = rod + crank
    assert err_q < 1e-11 * max(scale, 1.0)
    assert err_v < 1e-9 * max(scale, 1.0) * (1 + abs(omega))
    assert err_a < 1e-8 * max(scale, 1.0) * (1 + omega**2 + abs(alpha))
    sol = m.solve(PHI, omega, alpha)
    # the branch, by its definition: the slider on the +x (b = +1) or −x (b = −1) side of the crank pin
    assert np.all(branch * (sol.point("B").x - sol.point("A").x) > 0)
    np.testing.assert_allclose(sol.point("B").y, offset, atol=1e-14 * scale)
    assert not sol.singular.any()


@settings(max_examples=25, deadline=None)
@given(geometry=crank_slider_geometries(full_turn=False), branch=branches, omega=st.floats(-50, 50, **finite))
def test_rocking_crank_inside_its_range_against_generic_solver(geometry, branch, omega):
    crank, rod, offset = geometry
    m = mech.CrankSlider(crank, rod, offset, branch)
    lo, hi = m.assembly_ranges[0]
    margin = 0.05 * (hi - lo)
    phi = np.linspace(lo + margin, hi - margin, 15)
    err_q, err_v, err_a = verify.generic_errors(m, phi, omega)
    # near the ends of the range the rod is almost perpendicular to the guide: derivatives grow like 1/w
    sol = m.solve(phi, omega)
    size = 1 + np.max(np.abs(sol.slider("B").acceleration)) + np.max(np.abs(sol.angle("coupler").alpha))
    assert err_q < 1e-10 * (rod + crank)
    assert err_v < 1e-8 * (rod + crank) * (1 + abs(omega)) * size ** 0.5
    assert err_a < 1e-8 * size


# --- the worked example --------------------------------------------------------------------------

def test_worked_example_against_generic_solver():
    m = mech.CrankSlider(**EXAMPLE)
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    err = verify.generic_errors(m, phi, OMEGA)
    assert err[0] < 1e-14 and err[1] < 1e-10 and err[2] < 1e-8  # rad·m, (rad, m)/s, (rad, m)/s²


def test_worked_example_against_textbook_table_5_5():
    # Table 5.5 of the textbook page (source 004), the analytical row, for "position 2": the crank at
    # φ = 30° (position 1 is φ = 0, the outer dead centre), crank counter-clockwise, slider on +x.
    # Printed: ω2 = −50.1 1/s, ε2 = 5881 1/s², v_C = −10.6 m/s, a_C = −3713 m/s², v_S2 = 13.91 m/s at
    # 131.4°, a_S2 = 3597 m/s² at 201.1°.
    sol = mech.CrankSlider(**EXAMPLE).solve(np.radians([30.0]), OMEGA)
    s2 = sol.point_on("coupler", 0.09)
    assert round(sol.angle("coupler").omega[0], 1) == -50.1
    assert round(sol.angle("coupler").alpha[0]) == 5881
    assert round(sol.slider("B").velocity[0], 1) == -10.6
    assert round(sol.slider("B").acceleration[0]) == -3714  # printed −3713: the source truncates 3713.58
    assert round(s2.speed[0], 2) == 13.91
    assert round(np.degrees(np.angle(s2.velocity[0])), 1) == 131.4
    assert round(abs(s2.acceleration[0])) == 3597
    assert round(np.degrees(np.angle(s2.acceleration[0])) % 360, 1) == 201.1


def test_worked_example_against_hand_formulas():
    # The axial crank-slider by hand (λ = L1/L2, slider on +x, constant ω):
    # sin ψ = −λ sin φ; ψ_t = −λ ω cos φ / cos ψ; ψ_tt = (λ ω² sin φ + sin ψ ψ_t²)/cos ψ  (from
    # differentiating L2 sin ψ = −L1 sin φ twice); s = L1 cos φ + L2 cos ψ and s_t, s_tt by the chain rule.
    l1, l2, w = EXAMPLE["crank"], EXAMPLE["rod"], OMEGA
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    lam = l1 / l2
    psi = -np.arcsin(lam * np.sin(phi))  # |λ sin φ| ≤ 0.27: safe here
    psi_t = -lam * w * np.cos(phi) / np.cos(psi)
    psi_tt = (lam * w**2 * np.sin(phi) + np.sin(psi) * psi_t**2) / np.cos(psi)
    s = l1 * np.cos(phi) + l2 * np.cos(psi)
    s_t = -l1 * w * np.sin(phi) - l2 * np.sin(psi) * psi_t
    s_tt = -l1 * w**2 * np.cos(phi) - l2 * (np.cos(psi) * psi_t**2 + np.sin(psi) * psi_tt)
    sol = mech.CrankSlider(**EXAMPLE).solve(phi, w)
    np.testing.assert_allclose(sol.angle("coupler").angle, psi, atol=1e-15)
    np.testing.assert_allclose(sol.angle("coupler").omega, psi_t, atol=1e-12)
    np.testing.assert_allclose(sol.angle("coupler").alpha, psi_tt, atol=1e-9)
    np.testing.assert_allclose(sol.slider("B").value, s, atol=1e-16)
    np.testing.assert_allclose(sol.slider("B").velocity, s_t, atol=1e-13)
    np.testing.assert_allclose(sol.slider("B").acceleration, s_tt, atol=1e-10)
    # by hand at the dead centres: s = L1 + L2 and L2 − L1, v = 0, a = −ω²L1(1 ± λ)
    np.testing.assert_allclose(sol.slider("B").value[[0, 6]], [0.38, 0.22], atol=1e-16)
    np.testing.assert_allclose(sol.slider("B").velocity[[0, 6]], 0.0, atol=1e-12)
    np.testing.assert_allclose(sol.slider("B").acceleration[[0, 6]],
                               [-w**2 * l1 * (1 + lam), w**2 * l1 * (1 - lam)], rtol=1e-14)


def test_point_on_coupler_interpolates_the_joints():
    # S2 at 0.09 m from A on A→B is A + 0.3 (B − A), with the velocities and accelerations combining
    # the same way (a rigid link's points are linear in the joints along the link)
    sol = mech.CrankSlider(**EXAMPLE).solve(PHI, OMEGA, 500.0)
    s2 = sol.point_on("coupler", 0.09)
    a, b = sol.point("A"), sol.point("B")
    for got, pa, pb in zip(s2.derivatives(), a.derivatives(), b.derivatives()):
        np.testing.assert_allclose(got, pa + 0.3 * (pb - pa), rtol=1e-12, atol=1e-9)
    # a point off the line: 0.05 m to the left, from the lecture's Lagrange form as the reference
    off = sol.point_on("coupler", 0.09, 0.05)
    psi = sol.angle("coupler")
    ref = mech.lagrange_point(a, psi, 0.09 + 0.05j, 0j, 0.0)
    for got, want in zip(off.derivatives(), ref.derivatives()):
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-9)


# --- the checks of the analysis sequence ------------------------------------------------------------

@pytest.mark.parametrize("offset, branch", [(0.0, 1), (0.05, 1), (-0.05, -1)])
def test_checks_of_the_analysis_sequence(offset, branch):
    m = mech.CrankSlider(0.08, 0.3, offset, branch)
    sol = m.solve(PHI, OMEGA)
    assert verify.constraint_residual(m, sol) < 1e-15
    assert verify.distance_deviation(m, sol) < 1e-15
    errors = verify.derivative_errors(m, PHI, OMEGA)
    for name, (v_err, a_err) in errors.items():
        assert v_err < 1e-5, name  # central differences, h = 1e-5: truncation ≈ 1e-8 relative
        assert a_err < 1e-1, name  # second differences, h = 1e-4, against values of order 5000


@pytest.mark.parametrize("order", [0, 1, 2])
def test_orders(order):
    sol = mech.CrankSlider(**EXAMPLE).solve(PHI, OMEGA, order=order)
    for motion in (sol.angle("coupler"), sol.point("B"), sol.slider("B"), sol.point("O")):
        assert motion.order == order
    assert sol.point_on("coupler", 0.09).order == order
    assert set(sol.point_names) == {"O", "A", "B"} and set(sol.angle_names) == {"crank", "coupler"}


def test_branch_minus_one_mirrors_branch_plus_one():
    # Mirroring in the y axis maps (φ, e, b) to (π − φ, e, −b) (hand argument): every x coordinate and
    # its time derivatives change sign, the mirrored crank turns the other way (φ_t → −φ_t, φ_tt → −φ_tt),
    # and the coupler angle becomes π − ψ, so ψ_t → −ψ_t and ψ_tt → −ψ_tt.
    plus = mech.CrankSlider(0.08, 0.3, 0.03, 1).solve(PHI, OMEGA, 100.0)
    minus = mech.CrankSlider(0.08, 0.3, 0.03, -1).solve(np.pi - PHI, -OMEGA, -100.0)
    for got, want in zip(minus.slider("B").derivatives(), plus.slider("B").derivatives()):
        np.testing.assert_allclose(got, -want, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(wrap(minus.angle("coupler").angle - (np.pi - plus.angle("coupler").angle)), 0,
                               atol=1e-14)
    np.testing.assert_allclose(minus.angle("coupler").omega, -plus.angle("coupler").omega, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(minus.angle("coupler").alpha, -plus.angle("coupler").alpha, rtol=1e-12, atol=1e-9)


# --- dead centres, the limiting geometry, assembly -------------------------------------------------------

def test_rod_perpendicular_to_guide_is_marked_and_warned():
    # source 002's limiting geometry r = 2, e = 1, L = 3 with the guide below (y = −1): at φ = 90° the pin
    # is 3 m = L above the guide, the rod stands vertically, s_t = 0/0 there
    m = mech.CrankSlider(2.0, 3.0, -1.0)
    phi = np.radians([0.0, 90.0, 180.0])
    with pytest.warns(SingularPositionWarning, match="90°"):
        sol = m.solve(phi, 1.0)
    np.testing.assert_array_equal(sol.singular, [False, True, False])
    np.testing.assert_allclose(sol.point("B").value[1], -1j, atol=1e-15)  # B right below A
    assert not np.isfinite(sol.slider("B").velocity[1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        positions = m.solve(phi, 1.0, order=0)  # positions only: nothing is unbounded, no warning
    assert positions.singular[1]


def test_outside_the_assembly_range():
    # crank 0.1 m, rod 0.15 m, offset 0.1 m: by hand the pin reaches the guide for sin φ ≥ −1/2,
    # i.e. φ in [−30°, 210°]
    m = mech.CrankSlider(0.1, 0.15, 0.1)
    assert not m.full_revolution
    with pytest.raises(AssemblyError, match="cannot reach") as info:
        m.solve(np.radians([0.0, 240.0, 270.0, 300.0]), 1.0)
    np.testing.assert_allclose(np.degrees(info.value.angles), [240.0, 270.0, 300.0])
    np.testing.assert_allclose(np.degrees(info.value.valid_range), [-30.0, 210.0])
    assert "[-30.00°, 210.00°]" in str(info.value)
    sol = m.solve(np.radians([-30.0, 0.0, 210.0]), 1.0, order=0)  # the ends themselves assemble
    np.testing.assert_allclose(sol.point("B").value[[0, 2]], [np.sqrt(0.1**2 - 0.05**2) + 0.1j,
                                                              -np.sqrt(0.1**2 - 0.05**2) + 0.1j], atol=1e-15)


def test_two_assembly_ranges_are_named():
    # axial, rod 0.1 m < crank 0.2 m: |sin φ| ≤ 1/2, two arcs [−30°, 30°] and [150°, 210°]
    m = mech.CrankSlider(0.2, 0.1)
    with pytest.raises(AssemblyError, match=r"\[-30.00°, 30.00°\] and \[150.00°, 210.00°\]"):
        m.solve(np.radians([90.0]), 1.0)


def test_rod_that_never_reaches_the_guide():
    with pytest.raises(AssemblyError, match="any crank angle"):
        mech.CrankSlider(0.1, 0.1, 0.25)


# --- bad input -------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["crank", "rod"])
@pytest.mark.parametrize("value", [0.0, -0.1, np.nan, np.inf, None, "long"])
def test_bad_lengths(name, value):
    kwargs = dict(EXAMPLE) | {name: value}
    with pytest.raises(InvalidParameterError, match=name):
        mech.CrankSlider(**kwargs)


@pytest.mark.parametrize("offset", [np.nan, np.inf, "up"])
def test_bad_offset(offset):
    with pytest.raises(InvalidParameterError, match="offset"):
        mech.CrankSlider(0.08, 0.3, offset)


@pytest.mark.parametrize("branch", [0, 2, -2, True, 1.5, "+1", None])
def test_unknown_branch(branch):
    with pytest.raises(InvalidParameterError, match="branch"):
        mech.CrankSlider(0.08, 0.3, branch=branch)


def test_bad_angles_and_order():
    m = mech.CrankSlider(**EXAMPLE)
    with pytest.raises(InvalidParameterError, match="phi"):
        m.solve([0.0, np.nan], OMEGA)
    with pytest.raises(InvalidParameterError, match="omega"):
        m.solve([0.0], np.inf)
    with pytest.raises(InvalidParameterError, match="order"):
        m.solve([0.0], OMEGA, order=3)


def test_description_and_registration():
    m = mech.CrankSlider(0.08, 0.3, 0.01, -1)
    assert m.parameters() == {"crank": 0.08, "rod": 0.3, "offset": 0.01}
    assert repr(m) == "CrankSlider(crank=0.08, rod=0.3, offset=0.01, branch=-1)"
    assert mech.registry["crank-slider"] is mech.CrankSlider
    assert m.preserved_distances() == {("O", "A"): 0.08, ("A", "B"): 0.3}


# --- errata of the lecture slides (the crank-slider), checked against the generic solver -----------------
# The lecture measures the coupler angle from the slider to the crank pin, ψ' = ψ + π, and writes the guide
# as b = L1 sin φ − L2 sin ψ' (b = e here); ψ'_t = ψ_t and ψ'_tt = ψ_tt.

def _lecture_reference(branch, omega=215.0, eps=3000.0):
    m = mech.CrankSlider(0.08, 0.3, 0.02, branch)
    phi = np.radians(np.arange(5.0, 360.0, 20.0))
    reference = verify.solve_generic(m, phi, omega, eps)  # Newton + exact derivatives (chapter 2)
    return m, phi, reference.q[0] + np.pi, reference.q_t[0], reference.q_tt[0], omega, eps


def test_erratum_lecture_psi_tt_first_form():
    # slider on the +x side, ψ' = π − arcsin((L1 sin φ − b)/L2); the slide prints
    # ψ_tt = −φ_tt L1 cos φ/(L2 cos ψ) + φ_t² (L1/L2)(sin φ/cos ψ + L1 cos²φ tg ψ/(L2 cos²ψ)),
    # which is right only if its first two "cos ψ" are read as cos(π − ψ), as in the ψ_t line above it.
    m, phi, psi, psi_t, psi_tt, w, eps = _lecture_reference(1)
    l1, l2 = m.crank, m.rod
    tail = l1 * np.cos(phi) ** 2 * np.tan(psi) / (l2 * np.cos(psi) ** 2)
    printed = -eps * l1 * np.cos(phi) / (l2 * np.cos(psi)) + w**2 * l1 / l2 * (np.sin(phi) / np.cos(psi) + tail)
    c = np.cos(np.pi - psi)
    corrected = -eps * l1 * np.cos(phi) / (l2 * c) + w**2 * l1 / l2 * (np.sin(phi) / c + tail)
    np.testing.assert_allclose(corrected, psi_tt, rtol=1e-10, atol=1e-8)
    assert np.max(np.abs(printed - psi_tt)) > 0.1 * np.max(np.abs(psi_tt))
    # the ψ_t of the same slide is right: ψ_t = −φ_t L1 cos φ/(L2 cos(π − ψ))
    np.testing.assert_allclose(-w * l1 * np.cos(phi) / (l2 * c), psi_t, rtol=1e-12, atol=1e-10)


@pytest.mark.parametrize("branch", [1, -1])
def test_erratum_lecture_psi_tt_through_crank_pin(branch):
    # the slide "through the coordinates of point A" prints ψ_tt = (y_tt)_A/(L2 cos ψ) + ψ_t (y_t)_A (L1/L2)
    # sin ψ/cos²ψ; differentiating L2 sin ψ = y_A − b twice gives the factor 1/L2, not L1/L2.
    m, phi, psi, psi_t, psi_tt, w, eps = _lecture_reference(branch)
    l1, l2 = m.crank, m.rod
    y_t = l1 * np.cos(phi) * w
    y_tt = l1 * (np.cos(phi) * eps - np.sin(phi) * w**2)
    printed = y_tt / (l2 * np.cos(psi)) + psi_t * y_t * (l1 / l2) * np.sin(psi) / np.cos(psi) ** 2
    second = psi_t * y_t / l2 * np.sin(psi) / np.cos(psi) ** 2
    corrected = y_tt / (l2 * np.cos(psi)) + second
    np.testing.assert_allclose(corrected, psi_tt, rtol=1e-10, atol=1e-8)
    # the printed form loses (1 − L1/1 m) of the second term: 92 % here, hundreds of rad/s²
    assert np.max(np.abs(printed - psi_tt)) > 0.5 * np.max(np.abs(second)) > 100.0
    np.testing.assert_allclose(y_t / (l2 * np.cos(psi)), psi_t, rtol=1e-12, atol=1e-10)  # ψ_t: printed right


def test_scheme_draws():
    # the drawing primitives name existing joints and links: drawing must not raise
    import matplotlib.pyplot as plt

    m = mech.CrankSlider(0.08, 0.3, -0.02, -1)
    sol = m.solve(np.radians([40.0]), 1.0, order=0)
    ax = mech.plot.draw(m, sol)
    assert len(ax.lines) >= 2
    plt.close(ax.figure)
