"""The sources' formulas that the book uses and no other test checks, each typed here as printed.

Every formula below is transcribed from its source (the comment names the slide or equation) and
compared with an independent computation: numerical differentiation of positions
(``mechanisms.verify.central_difference``), Newton's method on constraint equations written out
here (``mechanisms.verify.solve_constraints``), or a simulation of a design. The errata page of the
book (book/appendix/errata.md) lists each formula with its status and the test that checks it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import frenet
from mechanisms.analysis.synthesis import synthesize_coupler_output
from mechanisms.verify import central_difference, solve_constraints

PHI = np.radians(np.arange(3.0, 360.0, 11.0))
W = 3.0  # constant crank speed (rad/s) for the numerical derivatives


def d1(function, phi=PHI, omega=W):
    return central_difference(function, phi, omega, 1e-5, 1)


def d2(function, phi=PHI, omega=W):
    return central_difference(function, phi, omega, 1e-4, 2)


def wrap(angle):
    return (angle + np.pi) % (2 * np.pi) - np.pi


# --- source 000, lecture slides (Alyushin 2008): links and their motion ------------------------------

def pole_x(p):
    return 0.2 + 0.3 * np.cos(p)


def pole_y(p):
    return 0.1 + 0.3 * np.sin(2 * p)


def turn(p):
    """Δψ(φ): the link's rotation from its reference position, a non-uniform function of the crank angle."""
    return 0.5 * np.sin(p) + 0.3 * p


ALPHA, BETA = 0.7, -0.4        # material (Lagrange) coordinates of the point
ALPHA_P, BETA_P = 0.1, 0.25    # material coordinates of the pole


def test_lecture_plane_motion_lagrange_and_euler_forms():
    # Slide "from plane-parallel motion to rotation and translation" and the slides on the coupler
    # (Lagrange form): x = x_P + (α − α_P) cos Δψ − (β − β_P) sin Δψ, y = y_P + (α − α_P) sin Δψ + (β − β_P) cos Δψ;
    # x_t = (x_t)_P − ψ_t[(α − α_P) sin Δψ + (β − β_P) cos Δψ], y_t = (y_t)_P + ψ_t[(α − α_P) cos Δψ − (β − β_P) sin Δψ];
    # Euler form x_t = (x_t)_P − ψ_t (y − y_P), y_t = (y_t)_P + ψ_t (x − x_P) (also slide "recommended sequence", step 5).
    # Expected: numerical differentiation of the printed position.
    def x(p):
        return pole_x(p) + (ALPHA - ALPHA_P) * np.cos(turn(p)) - (BETA - BETA_P) * np.sin(turn(p))

    def y(p):
        return pole_y(p) + (ALPHA - ALPHA_P) * np.sin(turn(p)) + (BETA - BETA_P) * np.cos(turn(p))

    # the position itself: a rigid motion keeps the distance to the pole and turns the arm by Δψ
    arm = (x(PHI) - pole_x(PHI)) + 1j * (y(PHI) - pole_y(PHI))
    np.testing.assert_allclose(arm, complex(ALPHA - ALPHA_P, BETA - BETA_P) * np.exp(1j * turn(PHI)), atol=1e-15)
    psi_t, xp_t, yp_t = d1(turn), d1(pole_x), d1(pole_y)
    dpsi = turn(PHI)
    lagrange_xt = xp_t - psi_t * ((ALPHA - ALPHA_P) * np.sin(dpsi) + (BETA - BETA_P) * np.cos(dpsi))
    lagrange_yt = yp_t + psi_t * ((ALPHA - ALPHA_P) * np.cos(dpsi) - (BETA - BETA_P) * np.sin(dpsi))
    euler_xt = xp_t - psi_t * (y(PHI) - pole_y(PHI))
    euler_yt = yp_t + psi_t * (x(PHI) - pole_x(PHI))
    for got, expected in ((lagrange_xt, d1(x)), (lagrange_yt, d1(y)), (euler_xt, d1(x)), (euler_yt, d1(y))):
        np.testing.assert_allclose(got, expected, atol=1e-8)
    # step 5: x_tt = (x_tt)_P − ψ_tt (y − y_P) − ψ_t² (x − x_P) (the y_tt is the corrected one of the errata)
    euler_xtt = d2(pole_x) - d2(turn) * (y(PHI) - pole_y(PHI)) - psi_t**2 * (x(PHI) - pole_x(PHI))
    np.testing.assert_allclose(euler_xtt, d2(x), atol=2e-5)
    # slides "crank-slider" (both): x_tt = (x_tt)_A − ψ_tt (y − y_A) − ψ_t [y_t − (y_t)_A],
    # y_tt = (y_tt)_A + ψ_tt (x − x_A) + ψ_t [x_t − (x_t)_A] (the pole P here plays the crank pin A)
    first_xtt = d2(pole_x) - d2(turn) * (y(PHI) - pole_y(PHI)) - psi_t * (d1(y) - yp_t)
    first_ytt = d2(pole_y) + d2(turn) * (x(PHI) - pole_x(PHI)) + psi_t * (d1(x) - xp_t)
    np.testing.assert_allclose(first_xtt, d2(x), atol=2e-5)
    np.testing.assert_allclose(first_ytt, d2(y), atol=2e-5)
    # the formulas can fail: a sign flipped in the Euler velocity is off by ψ_t·|arm|
    assert np.max(np.abs((xp_t + psi_t * (y(PHI) - pole_y(PHI))) - d1(x))) > 0.1


def test_lecture_rotation_translation_crank_rocker_and_slider_coordinates():
    # Same slide: rotation about a fixed P(a, b): x = a + (α − a) cos Δφ − (β − b) sin Δφ,
    # y = b + (α − a) sin Δφ + (β − b) cos Δφ; translation: x = α + u_x(t), y = β + u_y(t) (Δφ = 0).
    # Slide "crank": x = α cos Δφ − β sin Δφ, y = α sin Δφ + β cos Δφ. Slide "rocker": the rotation form with (a, b).
    # Slide "slider": x = α + (x_P − α_P), x_t = (x_t)_P, x_tt = (x_tt)_P (likewise y).
    # Expected: complex rotation r = c + (ρ − c)·exp(iΔφ), written independently, and numerical differentiation.
    a, b = 0.4, -0.3
    rho = complex(ALPHA, BETA)
    dphi = turn(PHI)
    rocker = a + (ALPHA - a) * np.cos(dphi) - (BETA - b) * np.sin(dphi) + 1j * (
        b + (ALPHA - a) * np.sin(dphi) + (BETA - b) * np.cos(dphi))
    np.testing.assert_allclose(rocker, complex(a, b) + (rho - complex(a, b)) * np.exp(1j * dphi), atol=1e-15)
    crank = ALPHA * np.cos(dphi) - BETA * np.sin(dphi) + 1j * (ALPHA * np.sin(dphi) + BETA * np.cos(dphi))
    np.testing.assert_allclose(crank, rho * np.exp(1j * dphi), atol=1e-15)
    assert np.max(np.abs(crank - rho * np.exp(-1j * dphi))) > 0.1   # the sense of rotation matters

    # slider: every point moves like the pole P (material coordinates α_P, β_P)
    def slider_x(p):
        return ALPHA + (pole_x(p) - ALPHA_P)

    def slider_y(p):
        return BETA + (pole_y(p) - BETA_P)

    np.testing.assert_allclose(d1(slider_x), d1(pole_x), atol=1e-9)
    np.testing.assert_allclose(d1(slider_y), d1(pole_y), atol=1e-9)
    np.testing.assert_allclose(d2(slider_x), d2(pole_x), atol=1e-6)
    np.testing.assert_allclose(d2(slider_y), d2(pole_y), atol=1e-6)
    np.testing.assert_allclose(slider_x(PHI) - ALPHA, pole_x(PHI) - ALPHA_P, atol=1e-15)   # u_x(t)


# --- lecture: the crank-slider -----------------------------------------------------------------------

L1, L2, B_GUIDE = 0.08, 0.3, 0.02


def lecture_crank_slider(sign):
    """Newton on B = A − L2·exp(iψ) on the guide y = b (ψ the slides' angle, from B to A), continued over PHI.

    sign = +1: B on the crank's −x side (cos ψ > 0, ψ = arcsin …); −1: B on the +x side (ψ = π − arcsin …).
    """
    def constraints(q, phi):
        psi, s = q
        return (L1 * np.cos(phi) - L2 * np.cos(psi) - s, L1 * np.sin(phi) - L2 * np.sin(psi) - B_GUIDE)

    psi0 = math.asin((L1 * math.sin(PHI[0]) - B_GUIDE) / L2)
    if sign < 0:
        psi0 = math.pi - psi0
    s0 = L1 * math.cos(PHI[0]) - L2 * math.cos(psi0)
    return solve_constraints(constraints, np.array([psi0 + 0.01, s0]), PHI, omega=W, alpha=0.0)


@pytest.mark.parametrize("sign", [1, -1])
def test_lecture_crank_slider_angle_and_angular_velocity(sign):
    # Slide "crank-slider": b = L1 sin φ − L2 sin ψ; near side ψ = arcsin((L1 sin φ − b)/L2), ψ_t = φ_t L1 cos φ/(L2 cos ψ);
    # far side sin(π − ψ) = (L1 sin φ − b)/L2, ψ = π − arcsin(…), ψ_t = −φ_t L1 cos φ/(L2 cos(π − ψ)).
    # Slide "through the coordinates of A": y_A = L1 sin φ, ψ = arcsin((y_A − b)/L2) or π − arcsin(…),
    # ψ_t = (y_t)_A/(L2 cos ψ) or −(y_t)_A/(L2 cos(π − ψ)).
    # Slide "another way to write the constraints": L1 sin φ + L2 sin ψ'' = H, with ψ'' = ψ + π the angle from A to B.
    # Expected: Newton on the loop closure with its exact derivatives.
    ref = lecture_crank_slider(sign)
    psi, psi_t = ref.q[0], ref.q_t[0]
    y_a, y_a_t = L1 * np.sin(PHI), L1 * np.cos(PHI) * W
    np.testing.assert_allclose(L1 * np.sin(PHI) - L2 * np.sin(psi), B_GUIDE, atol=1e-14)
    if sign > 0:
        printed = np.arcsin((L1 * np.sin(PHI) - B_GUIDE) / L2)
        printed_a = np.arcsin((y_a - B_GUIDE) / L2)
        printed_t = W * L1 * np.cos(PHI) / (L2 * np.cos(psi))
        printed_t_a = y_a_t / (L2 * np.cos(psi))
    else:
        printed = np.pi - np.arcsin((L1 * np.sin(PHI) - B_GUIDE) / L2)
        printed_a = np.pi - np.arcsin((y_a - B_GUIDE) / L2)
        printed_t = -W * L1 * np.cos(PHI) / (L2 * np.cos(np.pi - psi))
        printed_t_a = -y_a_t / (L2 * np.cos(np.pi - psi))
    for got in (printed, printed_a):
        np.testing.assert_allclose(wrap(got - psi), 0.0, atol=1e-12)
    for got in (printed_t, printed_t_a):
        np.testing.assert_allclose(got, psi_t, atol=1e-10)
    # the other case's formula gives the other branch: the two cases are needed
    other = np.arcsin((y_a - B_GUIDE) / L2)
    other = np.pi - other if sign > 0 else other
    assert np.min(np.abs(wrap(other - psi))) > 1.0
    np.testing.assert_allclose(L1 * np.sin(PHI) + L2 * np.sin(psi + np.pi), B_GUIDE, atol=1e-14)   # H = b


# --- lecture: the crank-rocker -----------------------------------------------------------------------

CR = dict(l1=1.0, l2=3.5, l3=3.0, a=4.0, b=0.5)


def lecture_crank_rocker():
    l1, l2, l3, a, b = CR.values()

    def constraints(q, phi):      # the slides' system: L1 cos φ + L2 cos ψ − L3 cos ξ = a, likewise sin = b
        psi, xi = q
        return (l1 * np.cos(phi) + l2 * np.cos(psi) - l3 * np.cos(xi) - a,
                l1 * np.sin(phi) + l2 * np.sin(psi) - l3 * np.sin(xi) - b)

    p, q = a - l1 * math.cos(PHI[0]), b - l1 * math.sin(PHI[0])
    f = (p * p + q * q + l2 * l2 - l3 * l3) / (2 * l2)
    psi0 = 2 * math.atan((q + math.sqrt(q * q + p * p - f * f)) / (p + f))
    xi0 = math.atan2(l2 * math.sin(psi0) - q, l2 * math.cos(psi0) - p)
    return solve_constraints(constraints, np.array([psi0 + 0.01, xi0 - 0.01]), PHI, omega=W, alpha=2.0)


def test_lecture_crank_rocker_positions_determinants_and_rate_equations():
    # Slides "crank-rocker": P = a − L1 cos φ, Q = b − L1 sin φ, P cos ψ + Q sin ψ = F = (P² + Q² + L2² − L3²)/(2 L2);
    # ξ = arccos((L2 cos ψ − P)/L3), ξ = arcsin((L2 sin ψ − Q)/L3) ("4 variants": the pair that agrees is the answer);
    # rate system (b): −ψ_t L2 sin ψ + ξ_t L3 sin ξ = φ_t L1 sin φ, ψ_t L2 cos ψ − ξ_t L3 cos ξ = −φ_t L1 cos φ;
    # Δ = L2 L3 sin(ψ − ξ), Δ_ξt = φ_t L1 L2 sin(ψ − φ), and the second differentiated equation
    # ψ_tt L2 cos ψ − ξ_tt L3 cos ξ = −φ_tt L1 cos φ + φ_t² L1 sin φ + ψ_t² L2 sin ψ − ξ_t² L3 sin ξ.
    # Expected: Newton on the slides' own loop equations, with exact derivatives.
    l1, l2, l3, a, b = CR.values()
    ref = lecture_crank_rocker()
    psi, xi = ref.q
    psi_t, xi_t = ref.q_t
    psi_tt, xi_tt = ref.q_tt
    phi_t, phi_tt = W, 2.0
    p, q = a - l1 * np.cos(PHI), b - l1 * np.sin(PHI)
    f = (p**2 + q**2 + l2**2 - l3**2) / (2 * l2)
    np.testing.assert_allclose(p * np.cos(psi) + q * np.sin(psi), f, atol=1e-12)
    cos_xi, sin_xi = (l2 * np.cos(psi) - p) / l3, (l2 * np.sin(psi) - q) / l3
    np.testing.assert_allclose(cos_xi + 1j * sin_xi, np.exp(1j * xi), atol=1e-12)
    # the arccosine gives ±ξ and the arcsine ξ or π − ξ; exactly one of each pair is right
    both = np.abs(wrap(np.arccos(cos_xi) - xi)) < 1e-9
    np.testing.assert_array_equal(both, np.abs(wrap(-np.arccos(cos_xi) - xi)) > 1e-9)
    # (b) holds with the solver's rates
    np.testing.assert_allclose(-psi_t * l2 * np.sin(psi) + xi_t * l3 * np.sin(xi), phi_t * l1 * np.sin(PHI), atol=1e-10)
    np.testing.assert_allclose(psi_t * l2 * np.cos(psi) - xi_t * l3 * np.cos(xi), -phi_t * l1 * np.cos(PHI), atol=1e-10)
    # the determinants, expanded as printed, against the determinant of the matrix itself
    matrix = np.stack([np.stack([-l2 * np.sin(psi), l3 * np.sin(xi)], -1),
                       np.stack([l2 * np.cos(psi), -l3 * np.cos(xi)], -1)], -2)
    np.testing.assert_allclose(np.linalg.det(matrix), l2 * l3 * np.sin(psi - xi), atol=1e-12)
    right = np.stack([phi_t * l1 * np.sin(PHI), -phi_t * l1 * np.cos(PHI)], -1)
    m_xi = matrix.copy()
    m_xi[..., :, 1] = right
    np.testing.assert_allclose(np.linalg.det(m_xi), phi_t * l1 * l2 * np.sin(psi - PHI), atol=1e-11)
    np.testing.assert_allclose(phi_t * l1 * np.sin(psi - PHI) / (l3 * np.sin(psi - xi)), xi_t, atol=1e-10)   # ξ_t
    # the second differentiated equation, as printed
    lhs = psi_tt * l2 * np.cos(psi) - xi_tt * l3 * np.cos(xi)
    rhs = (-phi_tt * l1 * np.cos(PHI) + phi_t**2 * l1 * np.sin(PHI) + psi_t**2 * l2 * np.sin(psi)
           - xi_t**2 * l3 * np.sin(xi))
    np.testing.assert_allclose(lhs, rhs, atol=1e-9)
    # the first, as printed, does not hold (sine and cosine swapped: see the errata); as corrected, it does
    lhs1 = -psi_tt * l2 * np.sin(psi) + xi_tt * l3 * np.sin(xi)
    printed1 = (phi_tt * l1 * np.cos(PHI) + phi_t**2 * l1 * np.sin(PHI) + psi_t**2 * l2 * np.cos(psi)
                - xi_t**2 * l3 * np.cos(xi))
    corrected1 = (phi_tt * l1 * np.sin(PHI) + phi_t**2 * l1 * np.cos(PHI) + psi_t**2 * l2 * np.cos(psi)
                  - xi_t**2 * l3 * np.cos(xi))
    np.testing.assert_allclose(lhs1, corrected1, atol=1e-9)
    assert np.max(np.abs(lhs1 - printed1)) > 1.0


# --- lecture: slotted links --------------------------------------------------------------------------

R_CRANK, PIVOT = 0.1, 0.05 + 0.3j


def pin(p):
    return R_CRANK * np.exp(1j * p)


def test_lecture_slotted_link_angle_and_current_length():
    # Slide "slotted mechanism: angular characteristics": sin ψ = (b − y_A)/L_TEK, cos ψ = (a − x_A)/L_TEK,
    # tg ψ = (b − y_A)/(a − x_A), L_TEK² = (a − x_A)² + (b − y_A)², ψ_t = cos²ψ [(y_t)_A (x_A − a) − (x_t)_A (y_A − b)]/(a − x_A)²;
    # slide "guide with a fixed axis": (L_TEK)_t = −[(x_t)_A (a − x_A) + (y_t)_A (b − y_A)]/L_TEK
    # = [(x_t)_A (x_A − a) + (y_t)_A (y_A − b)]/L_TEK; slide "guide with a moving axis": tg(π − ψ) = (y_A − b)/(a − x_A).
    # Expected: the angle and length of C − A (atan2, hypot) differentiated numerically.
    a, b = PIVOT.real, PIVOT.imag
    x, y = pin(PHI).real, pin(PHI).imag
    xt, yt = d1(lambda p: pin(p).real), d1(lambda p: pin(p).imag)
    psi = np.angle(PIVOT - pin(PHI))
    length = np.sqrt((a - x) ** 2 + (b - y) ** 2)
    np.testing.assert_allclose(length, np.abs(PIVOT - pin(PHI)), atol=1e-15)
    np.testing.assert_allclose(np.sin(psi), (b - y) / length, atol=1e-14)
    np.testing.assert_allclose(np.cos(psi), (a - x) / length, atol=1e-14)
    ok = np.abs(a - x) > 0.02      # the tangent forms are singular where the lever is vertical
    np.testing.assert_allclose(np.tan(psi)[ok], ((b - y) / (a - x))[ok], rtol=1e-12)
    np.testing.assert_allclose(np.tan(np.pi - psi)[ok], ((y - b) / (a - x))[ok], rtol=1e-12)
    psi_t = np.cos(psi) ** 2 * (yt * (x - a) - xt * (y - b)) / (a - x) ** 2
    np.testing.assert_allclose(psi_t[ok], d1(lambda p: np.angle(PIVOT - pin(p)))[ok], atol=1e-8)
    numeric_lt = d1(lambda p: np.abs(PIVOT - pin(p)))
    np.testing.assert_allclose(-(xt * (a - x) + yt * (b - y)) / length, numeric_lt, atol=1e-9)
    np.testing.assert_allclose((xt * (x - a) + yt * (y - b)) / length, numeric_lt, atol=1e-9)
    assert np.max(np.abs((xt * (a - x) + yt * (b - y)) / length - numeric_lt)) > 0.1   # the sign matters


def test_lecture_angle_between_coupler_and_guide():
    # Slide "angle between the coupler and the fixed direction of the slider": guide y = m + x tg γ, written
    # A x + B y + C = 0 with A = tg γ, B = −1, C = m; the crank pin F is on the side of the origin (y_F < y_K),
    # the slider D on the guide ahead of the foot K, coupler FD of length L5, θ its angle from F to D.
    # Printed: sin μ = h/L5, θ = γ + μ (y_F < y_K), θ_t = μ_t, θ_tt = μ_tt, μ_t = h_t/(L5 cos μ),
    # μ_tt = h_tt/(L5 cos μ) + μ_t sin μ h_t/(L5 cos²μ); h is the distance ≥ 0, here −1 times the slide's signed
    # h = −sign(C)(A x + B y + C)/√(A² + B²), with h_t, h_tt in their corrected form (errata).
    # The slide before: x_N, y_N of (6), h = |DN| of (7) and μ' = θ_guide + arcsin(h/L) (the same rule).
    # Expected: Newton on F + L5 exp(iθ) = (0, m) + s exp(iγ), with exact derivatives.
    m, gamma, l5 = 0.3, 0.3, 0.4

    def constraints(q, phi):
        theta, s = q
        return (R_CRANK * np.cos(phi) + l5 * np.cos(theta) - s * np.cos(gamma),
                R_CRANK * np.sin(phi) + l5 * np.sin(theta) - m - s * np.sin(gamma))

    ref = solve_constraints(constraints, np.array([gamma + 0.3, 0.5]), PHI, omega=W, alpha=0.0)
    theta, theta_t, theta_tt = ref.q[0], ref.q_t[0], ref.q_tt[0]
    f = pin(PHI)
    fa = -W**2 * f   # crank pin at constant ω
    fv = 1j * W * f
    A, B, C = np.tan(gamma), -1.0, m
    norm = np.hypot(A, B)
    signed = -np.sign(C) * (A * f.real + B * f.imag + C) / norm
    assert np.all(signed < 0)     # F and the origin on the same side, as the slide says
    h = -signed
    h_t = np.sign(C) * (A * fv.real + B * fv.imag) / norm
    h_tt = np.sign(C) * (A * fa.real + B * fa.imag) / norm
    mu = np.arcsin(h / l5)
    mu_t = h_t / (l5 * np.cos(mu))
    mu_tt = h_tt / (l5 * np.cos(mu)) + mu_t * np.sin(mu) * h_t / (l5 * np.cos(mu) ** 2)
    np.testing.assert_allclose(wrap(gamma + mu - theta), 0.0, atol=1e-12)
    np.testing.assert_allclose(mu_t, theta_t, atol=1e-10)
    np.testing.assert_allclose(mu_tt, theta_tt, atol=1e-8)
    assert np.max(np.abs(wrap(gamma - mu - theta))) > 0.1       # the other sign is the other side
    # the slide before: foot N of the perpendicular from F, h = |FN|, coupler angle = guide angle + arcsin(h/L)
    t = np.tan(gamma)
    x_n = (f.real + (f.imag - m) * t) / (1 + t**2)
    y_n = (m + f.real * t + f.imag * t**2) / (1 + t**2)
    np.testing.assert_allclose(np.sqrt((x_n - f.real) ** 2 + (y_n - f.imag) ** 2), h, atol=1e-14)
    np.testing.assert_allclose(wrap(gamma + np.arcsin(np.hypot(x_n - f.real, y_n - f.imag) / l5) - theta), 0.0,
                               atol=1e-12)



def _printed_distance_rates(r, r_t, r_tt):
    """The lecture's printed rates of a distance |r| ("two rockers" slides: h and L_tek), as printed:
    (·)_t = (x x_t + y y_t)/h and (·)_tt = −(·)_t (x x_t + y y_t)/h² + (x x_tt + y y_tt)/h + (x_t² + y_t²)/h."""
    x, y = r.real, r.imag
    length = np.sqrt(x**2 + y**2)
    dot = x * r_t.real + y * r_t.imag
    length_t = dot / length
    length_tt = (-length_t * dot / length**2 + (x * r_tt.real + y * r_tt.imag) / length
                 + (r_t.real**2 + r_t.imag**2) / length)
    return length, length_t, length_tt

def test_lecture_two_rockers_remaining_formulas():
    # Slides "two rockers with a slotted pair" 2 and 3 (those not in tests/test_slotted.py::test_two_rockers_lecture_formulas):
    # (y_t)_K = ξ_t (x_K − a)/cos²ξ + tg ξ (x_t)_K,
    # (y_tt)_K = ξ_tt (x_K − a)/cos²ξ + 2(x_K − a) sin ξ ξ_t²/cos³ξ + 2 ξ_t (x_t)_K/cos²ξ + tg ξ (x_tt)_K,
    # h² = (x_K − m)² + (y_K − n)², h_t = [(x_K − m)(x_t)_K + (y_K − n)(y_t)_K]/h,
    # h_tt = −h_t[…]/h² + [(x_K − m)(x_tt)_K + (y_K − n)(y_tt)_K]/h + [(x_t)_K² + (y_t)_K²]/h,
    # y_D = b + tg ξ (x_D − a), (x_t)_D = [(m θ_t/cos²θ − a ξ_t/cos²ξ)(tg θ − tg ξ) − x_D(θ_t/cos²θ − ξ_t/cos²ξ)(tg θ − tg ξ)]/(tg θ − tg ξ)²,
    # (y_t)_D = ξ_t (x_D − a)/cos²ξ + tg ξ (x_t)_D, L² = (x_D − a)² + (y_D − b)², (L)_t = […]/L,
    # (L)_tt = −(L)_t[(x_D − a)(x_t)_D + (y_D − b)(y_t)_D]/L² + [(x_D − a)(x_tt)_D + (y_D − b)(y_tt)_D]/L + [(x_t)_D² + (y_t)_D²]/L.
    # Expected: positions from the package (angles ξ, θ; K as the foot of the perpendicular from O2 on O1B, D as
    # the meeting point of the two lines, computed here), differentiated numerically; the printed formulas take the
    # angles' rates ξ_t, ξ_tt, θ_t from the package (checked against the generic solver in tests/test_slotted.py).
    a, b, m_, n = 0.0, 0.3, 0.15, 0.4
    omega = 8.0
    mech_ = mech.SlottedRockers(0.1, (a, b), (m_, n), 0.3)
    phi = np.radians(np.arange(2.0, 360.0, 9.0))
    sol = mech_.solve(phi, omega, 0.0)
    xi, xi_t, xi_tt = sol.angle("lever").value, sol.angle("lever").omega, sol.angle("lever").alpha
    theta, theta_t = sol.angle("rocker").value, sol.angle("rocker").omega
    o1, o2 = complex(a, b), complex(m_, n)

    def foot(p):
        x = mech_.solve(p, omega, 0.0, order=0).angle("lever").value
        e = np.exp(1j * x)
        return o1 + ((np.conj(e) * (o2 - o1)).real) * e

    def meet(p):
        s = mech_.solve(p, omega, 0.0, order=0)
        x, t = s.angle("lever").value, s.angle("rocker").value
        # O1 + u e^{iξ} = O2 + v e^{iθ}: solved by Cramer's rule, independently of the slide
        e1, e2 = np.exp(1j * x), np.exp(1j * t)
        u = (np.conj(e2) * (o2 - o1)).imag / (np.conj(e2) * e1).imag
        return o1 + u * e1

    def dd1(fn):
        return central_difference(fn, phi, omega, 1e-5, 1)

    def dd2(fn):
        return central_difference(fn, phi, omega, 1e-4, 2)

    k = foot(phi)
    x_k = k.real
    k_t, k_tt = dd1(foot), dd2(foot)
    regular = np.abs(np.cos(xi)) > 0.2
    c2 = np.cos(xi) ** 2
    y_k_t = xi_t * (x_k - a) / c2 + np.tan(xi) * k_t.real
    y_k_tt = (xi_tt * (x_k - a) / c2 + 2 * (x_k - a) * np.sin(xi) * xi_t**2 / np.cos(xi) ** 3
              + 2 * xi_t * k_t.real / c2 + np.tan(xi) * k_tt.real)
    np.testing.assert_allclose(y_k_t[regular], k_t.imag[regular], atol=1e-7)
    np.testing.assert_allclose(y_k_tt[regular], k_tt.imag[regular], atol=1e-3)
    h, h_t, h_tt = _printed_distance_rates(k - o2, k_t, k_tt)
    np.testing.assert_allclose(h_t, dd1(lambda p: np.abs(foot(p) - o2)), atol=1e-7)
    np.testing.assert_allclose(h_tt, dd2(lambda p: np.abs(foot(p) - o2)), atol=1e-3)
    d = meet(phi)
    x_d, y_d = d.real, d.imag
    d_t, d_tt = dd1(meet), dd2(meet)
    np.testing.assert_allclose(y_d[regular], (b + np.tan(xi) * (x_d - a))[regular], atol=1e-12)
    tt, tx = np.tan(theta), np.tan(xi)
    ok = regular & (np.abs(np.cos(theta)) > 0.2) & (np.abs(tt - tx) > 0.2)
    x_d_t = ((m_ * theta_t / np.cos(theta) ** 2 - a * xi_t / c2) * (tt - tx)
             - x_d * (theta_t / np.cos(theta) ** 2 - xi_t / c2) * (tt - tx)) / (tt - tx) ** 2
    y_d_t = xi_t * (x_d - a) / c2 + tx * d_t.real
    assert ok.sum() > 10
    np.testing.assert_allclose(x_d_t[ok], d_t.real[ok], rtol=1e-6, atol=1e-7)
    np.testing.assert_allclose(y_d_t[ok], d_t.imag[ok], atol=1e-7)
    length, length_t, length_tt = _printed_distance_rates(d - o1, d_t, d_tt)
    np.testing.assert_allclose(length_t, dd1(lambda p: np.abs(meet(p) - o1)), atol=1e-7)
    np.testing.assert_allclose(length_tt, dd2(lambda p: np.abs(meet(p) - o1)), atol=1e-3)
    # the formulas can fail: without the velocity squares the second derivative is off
    assert np.max(np.abs(length_tt - (d_t.real**2 + d_t.imag**2) / length
                         - dd2(lambda p: np.abs(meet(p) - o1)))) > 1e-2


# --- source 004, textbook page 31: Table 5.5 ---------------------------------------------------------


def test_textbook_table_5_5_percentage_errors():
    # Table 5.5, row "error, %": (plans − analytical)/analytical·100 for ω2, ε2, v_C, a_C, v_S2, a_S2.
    # Printed: −0.2, −0.8, −1.9, −0.37, −0.8, 1.4. Expected: the ratio recomputed from the two printed rows;
    # a_C uses the unrounded −3713.58 of the analytical solution (tests/test_crank_slider.py), a_S2 is truncated.
    plans = np.array([-50.0, 5833.3, -10.4, -3700.0, 13.8, 3650.0])
    analytical = np.array([-50.1, 5881.0, -10.6, -3713.58, 13.91, 3597.0])
    printed = np.array([-0.2, -0.8, -1.9, -0.37, -0.8, 1.4])
    error = (plans - analytical) / analytical * 100.0
    np.testing.assert_allclose(error[:5], printed[:5], atol=0.05)
    assert math.floor(error[5] * 10) / 10 == printed[5]
    assert np.all(np.abs(error) < 2.0)     # the page's conclusion: within acceptable limits
    sol = mech.CrankSlider(0.08, 0.3).solve(np.radians([30.0]), 215.0)
    assert sol.slider("B").acceleration[0] == pytest.approx(-3713.58, abs=0.01)


# --- source 003, Zaitsev and Evgrafov: synthesis -----------------------------------------------------

def test_zaitsev_evgrafov_design_formulas_by_simulation():
    # Printed: φ_x = 360°/(K_v + 1), φ_w = 360° K_v/(K_v + 1); a = 2 L3 cos(φ_x/2), λ = ctg²(φ_x/2 + γ),
    # L2 = a(λ + 1) + a√((λ + 1)λ) (valid here, γ ≥ 90° − φ_x/2: see the errata), L1 = √((2 L2 a − a²)/(2(1 − cos φ_x)));
    # X_C = L3 − L2 cos γ + L1, Y_C = L2 sin γ, OC = √(X_C² + Y_C²); the coupler's rate
    # φ2' = −L1 L3 sin(q − φ3)/(L2 L3 sin(φ2 − φ3)); the transmission angle in the second limit position = φ_x/2.
    # Expected: a simulation of the designed linkage by Newton on its loop, started in the paper's first limit
    # position (crank along +x, rocker along −x); limit positions where the coupler's rate changes sign.
    k_v, gamma, l3 = 1.2, math.radians(40.0), 1.0
    phi_x = math.radians(360.0 / (k_v + 1))
    phi_w = math.radians(360.0 * k_v / (k_v + 1))
    assert phi_w / phi_x == pytest.approx(k_v) and phi_w + phi_x == pytest.approx(2 * math.pi)
    a = 2 * l3 * math.cos(phi_x / 2)
    lam = 1 / math.tan(phi_x / 2 + gamma) ** 2
    l2 = a * (lam + 1) + a * math.sqrt((lam + 1) * lam)
    l1 = math.sqrt((2 * l2 * a - a * a) / (2 * (1 - math.cos(phi_x))))
    xc, yc = l3 - l2 * math.cos(gamma) + l1, l2 * math.sin(gamma)
    oc = math.sqrt(xc**2 + yc**2)
    design = synthesize_coupler_output(k_v, gamma, rocker=l3)
    assert (design.crank, design.coupler, *design.frame) == pytest.approx((l1, l2, xc, yc))

    def constraints(q, phi):
        psi, xi = q
        return (l1 * np.cos(phi) + l2 * np.cos(psi) - l3 * np.cos(xi) - xc,
                l1 * np.sin(phi) + l2 * np.sin(psi) - l3 * np.sin(xi) - yc)

    phi = np.linspace(0.0, 2 * np.pi, 7201)
    ref = solve_constraints(constraints, np.array([math.pi - gamma, math.pi]), phi, omega=1.0, max_step=0.002)
    psi, xi = ref.q
    assert abs(complex(xc, yc)) == pytest.approx(oc)
    np.testing.assert_allclose(np.exp(1j * xi[0]), -1.0, atol=1e-9)          # first limit position as designed
    assert ref.q_t[0][0] == pytest.approx(0.0, abs=1e-9)
    printed_rate = -l1 * l3 * np.sin(phi - xi) / (l2 * l3 * np.sin(psi - xi))
    np.testing.assert_allclose(printed_rate, ref.q_t[0], atol=1e-9)
    # the other limit position: the sign change of the coupler's rate inside the turn
    rate = ref.q_t[0][1:-1]
    change = np.nonzero(np.sign(rate[:-1]) != np.sign(rate[1:]))[0]
    assert len(change) == 1
    i = change[0] + 1
    second = phi[i] - rate[i - 1] * (phi[i + 1] - phi[i]) / (rate[i] - rate[i - 1])
    assert min(second, 2 * math.pi - second) == pytest.approx(phi_x, abs=1e-5)
    delta = abs(wrap(psi[i] - xi[i]))
    assert min(delta, math.pi - delta) == pytest.approx(phi_x / 2, abs=2e-3)
    delta0 = abs(wrap(psi[0] - xi[0]))
    assert min(delta0, math.pi - delta0) == pytest.approx(gamma, abs=1e-9)


# --- source 002, Pylypaka and Chepizhnyi: the lambda mechanism ----------------------------------------

@pytest.mark.parametrize("r, b, d", [(2.0, 6.5, 5.0), (2.0, 6.5, 11.0)])
def test_lambda_mechanism_joint_c_18_to_20(r, b, d):
    # (17) x_A = r cos ψ, y_A = r sin ψ; (18) x_C = r cos ψ − b cos γ, y_C = r sin ψ + b sin γ; (19) x_C = −d + b cos ε,
    # y_C = b sin ε; (20) the two equal; (5) y_A = (1/k) sin ks with r = 1/k and ψ = ks.
    # Expected: the lambda mechanism's joint B (the source's C) from the four-bar closed form (tested against the
    # generic solver in tests/test_lambda_mechanism.py); γ from the printed (21) via
    # mechanisms.analysis.frenet.lambda_mechanism_gamma.
    psi = np.radians(np.arange(5.0, 360.0, 15.0))
    sol = mech.LambdaMechanism(r, b, d).solve(psi, order=0)
    gamma = frenet.lambda_mechanism_gamma(psi, r, b, d)
    k = 1 / r
    np.testing.assert_allclose(sol.point("A").value, r * np.cos(psi) + 1j * r * np.sin(psi), atol=1e-13)
    np.testing.assert_allclose(sol.point("A").value.imag, np.sin(k * (r * psi)) / k, atol=1e-13)
    x_c, y_c = r * np.cos(psi) - b * np.cos(gamma), r * np.sin(psi) + b * np.sin(gamma)
    np.testing.assert_allclose(x_c + 1j * y_c, sol.point("B").value, atol=1e-9)       # the source's C is B
    eps = np.arctan2(y_c, x_c + d)              # (19) solved for ε
    np.testing.assert_allclose(-d + b * np.cos(eps) + 1j * b * np.sin(eps), x_c + 1j * y_c, atol=1e-9)   # (19), (20)
    assert np.max(np.abs((r * np.cos(psi) + b * np.cos(gamma)) - x_c)) > 1.0   # the sign in (18) matters
