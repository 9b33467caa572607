"""Edges of the package (issue 18): near-degenerate geometries, extreme scales, and every example of the issue.

Expected values come from outside the function under test: the constraint equations solved in extended
precision (:func:`mechanisms.bench.reference`: Newton's method in ``numpy.longdouble``, eps 1.1e-19, with
exact derivatives), hand calculations, or the same mechanism at another scale (a power of two scales
every length exactly). A geometry at distance δ from a special case is a general geometry: its answer is
the true one for the given doubles (as accurate as its conditioning allows), or the position is flagged
``singular`` — never a confident wrong number.
"""

from __future__ import annotations

import io
import contextlib
import json
import math
import warnings

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.bench import reference
from mechanisms.cli import main
from mechanisms.core.errors import AssemblyError, InvalidParameterError, MechanismError, UnknownNameError
from mechanisms.linkages.linkage_file import example_files, load_linkage
from mechanisms.verify import solve_generic

EPS = np.finfo(float).eps
# the package's own mechanisms (other test modules register classes of their own in the same registry)
PACKAGE_CLASSES = [cls for cls in mech.linkages.registry.values() if cls.__module__.startswith("mechanisms.")]
DISTANCES = [1e-6, 1e-8, 1e-10, 1e-12, 1e-15]


def quiet_solve(m, phi, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return m.solve(phi, **kw)


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a, dtype=float)))


# --- the slotted lever whose pivot is δ·r off the crank circle --------------------------------------

@pytest.mark.parametrize("delta", DISTANCES)
def test_slotted_lever_near_its_pivot_is_the_general_lever_or_flagged(delta):
    # C = (0, r(1 + δ)): the pin passes δ·r below the pivot at φ = 90°. Not the through-pivot case.
    m = mech.SlottedLever(crank=1.0, pivot=(0.0, 1.0 + delta))
    assert m.kind == "oscillating"
    phi = np.pi / 2 + np.array([0.0, 1e-3, -0.3])
    sol = quiet_solve(m, phi, omega=1.0, alpha=0.5)
    ok = ~sol.singular
    # flagged only where no double-precision answer is meaningful: the block within 1e-12 of the pivot
    assert np.all(sol.singular == (np.abs(sol.slider("A").value) <= 1e-11))
    if not ok.any():
        return
    q, q_t, q_tt = reference(m, phi[ok], 1.0, 0.5)
    kappa = 1.0 / np.maximum(np.abs(sol.slider("A").value[ok]), 1e-300)     # condition: 1/L (L in units of r)
    xi, s = sol.angle("lever"), sol.slider("A")
    assert np.all(np.abs(wrapped(xi.value[ok] - q[0].astype(float))) <= 8 * EPS * kappa)
    assert np.all(np.abs(s.value[ok] - q[1].astype(float)) <= 8 * EPS)
    assert np.all(np.abs(xi.omega[ok] - q_t[0].astype(float)) <= 8 * EPS * kappa**2)
    # L_tt without the cancellation of |d_t|² − L_t² (issue 18: up to 1200 ε·κ lost): a few ε·κ of ξ_t²·L
    scale = np.abs(q_t[0].astype(float)) ** 2 * np.abs(s.value[ok]) + 1.0
    assert np.all(np.abs(s.acceleration[ok] - q_tt[1].astype(float)) <= 16 * EPS * kappa * scale)


def test_the_issue_lever_5e_10_off_the_circle():
    # issue 18: solved as if through the pivot, ξ off by 1.6 rad and ω₃ = 0.5 instead of −2e9 1/s.
    # By hand: A − C = (0, −5e-10) at φ = 90°, so ξ = −90°; ω₃ = Im(conj(d)·d_t)/L² = −ω·r·L/L² = −1/5e-10 = −2e9.
    m = mech.SlottedLever(crank=1.0, pivot=(0.0, 1.0 + 5e-10))
    sol = quiet_solve(m, [math.pi / 2], omega=1.0)
    assert m.kind == "oscillating" and not sol.singular[0]
    assert sol.angle("lever").value[0] == pytest.approx(-math.pi / 2, abs=1e-6)
    assert sol.angle("lever").omega[0] == pytest.approx(-2e9, rel=1e-6)


def test_through_pivot_only_when_exactly_on_the_circle():
    # r = 5/8, C = (3/8, 1/2): exactly on the circle (9/64 + 16/64 = 25/64); C' one ulp off it is not
    assert mech.SlottedLever(0.625, (0.375, 0.5)).kind == "through pivot"
    assert mech.SlottedLever(0.625, (0.375, np.nextafter(0.5, 1.0))).kind == "oscillating"
    assert mech.SlottedLever(0.1, (0.1 * math.cos(0.7), 0.1 * math.sin(0.7))).kind != "through pivot" or \
        (0.1 * math.cos(0.7)) ** 2 + (0.1 * math.sin(0.7)) ** 2 == 0.01


def test_through_pivot_lever_angle_is_reduced_exactly_at_huge_crank_angles():
    # issue 18: ξ = (φ + γ)/2 + π/2 not reduced, 8e-3 rad off at φ ≈ 1e15. By hand: exp(iξ) =
    # exp(iφ/2)·exp(i(γ/2 + π/2)), with numpy's correctly reduced cosine and sine of the exact φ/2.
    m = mech.SlottedLever(crank=1.0, pivot=(0.0, 1.0))
    phi = np.array([1e15, 3.3e15, -2.7e14, 123456789.0])
    xi = m.solve(phi, order=0).angle("lever").value
    expected = np.exp(0.5j * phi) * np.exp(1j * (math.pi / 4 + math.pi / 2))
    assert np.all(np.abs(np.angle(np.exp(1j * xi) / expected)) <= 4 * EPS * 8)


# --- the four-bar δ from the change-point condition -------------------------------------------------

@pytest.mark.parametrize("delta", DISTANCES)
def test_grashof_crank_rocker_near_the_change_point_keeps_its_branch(delta):
    # L1 = 1, L2 = 3, L3 = 2, d = 2 + δ: s + l = 4 < p + q = 4 + δ (Grashof), 1e-10 … 1e-15 from a change
    # point; issue 18: it took the other mode below φ = 0. Expected: one branch, ξ(−90°) = ξ(270°), and the
    # extended-precision solution of the constraints.
    m = mech.FourBar(crank=1.0, coupler=3.0, rocker=2.0, frame=(2.0 + delta, 0.0))
    assert m.change_points() == ()
    phi = np.radians(np.array([-90.0, 270.0, 45.0, -45.0, 180.0]))
    sol = quiet_solve(m, phi, omega=1.0)
    xi = sol.angle("rocker").value
    assert xi[0] == pytest.approx(xi[1], abs=1e-13)
    q, q_t, _ = reference(m, phi)
    assert np.all(np.abs(wrapped(xi - q[1].astype(float))) <= 1e-13)
    assert np.all(np.abs(sol.angle("rocker").omega - q_t[1].astype(float)) <= 1e-12)


def test_change_points_only_when_the_equalities_hold_exactly():
    assert mech.FourBar(1.0, 3.0, 1.0, (3.0, 0.0)).change_points() == (0.0, math.pi)    # parallelogram
    assert mech.FourBar(1.0, 3.0, 1.0, (3.0 + 4 * EPS, 0.0)).change_points() == ()
    assert mech.FourBar(1.0, 3.0, 2.0, (2.0, 0.0)).change_points() == (0.0,)


@pytest.mark.parametrize("start", [1e-3, -1e-3, 1e-5, 1e-7, math.pi + 1e-5, math.pi - 1e-7])
def test_generic_solver_stays_on_the_parallelogram_near_its_change_point(start):
    # issue 18: started 1e-7 … 1e-3 rad from a change point it jumped to the antiparallelogram. Expected
    # (by hand): a parallelogram's rocker stays parallel to its crank, ξ = φ.
    m = mech.FourBar(crank=1.0, coupler=3.0, rocker=1.0, frame=(3.0, 0.0))
    phi = start + np.linspace(0.0, 2.0 * np.pi, 25)
    generic = solve_generic(m, phi, order=0)
    assert np.max(np.abs(wrapped(generic.q[1] - phi))) <= 1e-7


@pytest.mark.parametrize("delta", [1e-6, 1e-9, 1e-12])
def test_generic_solver_converges_next_to_a_non_grashof_limit(delta):
    # issue 18: no convergence 1e-9 rad from the limit. Expected: the extended-precision solution, to the
    # conditioning of the position there (ε/√δ).
    m = mech.FourBar(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))
    (_, high), = m.assembly_intervals()
    phi = np.array([high - delta])
    generic = solve_generic(m, phi, order=1)
    q, _, _ = reference(m, phi)
    assert np.all(np.abs(wrapped(generic.q[:, 0] - q[:, 0].astype(float))) <= 64 * EPS / math.sqrt(delta))


# --- singular rows, not lost tables --------------------------------------------------------------------

def test_a_deltoid_with_crank_equal_to_frame_is_tabulated_from_zero():
    # issue 18: φ = 0 puts A on C; the whole table was lost with "assembles only for [-180°, 180°]".
    m = mech.FourBar(crank=1.0, coupler=2.0, rocker=2.0, frame=(1.0, 0.0))
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    with pytest.warns(mech.SingularPositionWarning):
        sol = m.solve(phi, omega=1.0)
    assert sol.singular.tolist() == [True] + [False] * 11
    assert np.all(np.isfinite(sol.point("B").value[1:]))
    q, _, _ = reference(m, phi[1:])
    assert np.all(np.abs(wrapped(sol.angle("rocker").value[1:] - q[1].astype(float))) <= 1e-13)


def test_a_linkage_that_never_assembles_says_so_once():
    m = mech.FourBar(crank=1.0, coupler=1.0, rocker=1.0, frame=(10.0, 0.0))
    with pytest.raises(AssemblyError) as info:
        m.solve(np.radians([0.0, 30.0]))
    text = str(info.value)
    assert text.endswith("it assembles at no crank angle") and "at no crank angle at crank angle" not in text


# --- scale: 2^±500 ----------------------------------------------------------------------------------------

def _cases():
    for cls in sorted(PACKAGE_CLASSES, key=lambda c: c.__name__):
        yield cls.__name__, cls.example()
    for name in example_files():
        yield name, load_linkage(name)


@pytest.mark.parametrize("exponent", [500, -500])
@pytest.mark.parametrize("name, m", list(_cases()), ids=[n for n, _ in _cases()])
def test_a_mechanism_scaled_by_a_power_of_two_gives_the_same_numbers_bit_for_bit(name, m, exponent):
    # Expected: the unscaled mechanism's results, times 2^exponent, exactly (every length scaled by a
    # power of two; the algorithm is scale-invariant, and the package solves at a scale of its own).
    factor = 2.0**exponent
    big = m._rescaled(factor)
    assert big is not None
    phi = np.radians(np.arange(0.0, 360.0, 15.0)) + 0.01
    try:
        small = quiet_solve(m, phi, omega=3.0, alpha=0.5)
    except AssemblyError:
        phi = np.radians(np.arange(-30.0, 31.0, 15.0)) + 0.01
        small = quiet_solve(m, phi, omega=3.0, alpha=0.5)
    scaled = quiet_solve(big, phi, omega=3.0, alpha=0.5)
    for point in small.point_names:
        for a, b in zip(small.point(point).derivatives(), scaled.point(point).derivatives()):
            np.testing.assert_array_equal(np.asarray(b) / factor, a)
    for link in small.angle_names:
        for a, b in zip(small.angle(link).derivatives(), scaled.angle(link).derivatives()):
            np.testing.assert_array_equal(b, a)
    np.testing.assert_array_equal(scaled.singular, small.singular)


def test_the_ends_of_the_supported_ranges():
    big = mech.CrankSlider(crank=2.0**509, rod=3 * 2.0**508)
    sol = big.solve([0.3], omega=1e50, alpha=1e100)
    assert all(np.all(np.isfinite(d)) for d in sol.point("B").derivatives())
    for bad in (dict(crank=2.0**511, rod=2.0**511), dict(crank=2.0**-511, rod=1.0), dict(crank=1.0, rod=1e160)):
        with pytest.raises(InvalidParameterError):
            mech.CrankSlider(**bad)
    with pytest.raises(InvalidParameterError, match="omega"):
        mech.CrankSlider(crank=1.0, rod=3.0).solve([0.3], omega=1e160)


# --- the remaining examples of the issue -------------------------------------------------------------------

def run(args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(args)
    return status, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("extra", [["--omega", "-1e3"], ["--offset", "-5e-2", "--omega", "1"],
                                   ["--omega", "1", "--angles", "-90:90:30"]])
def test_negative_numbers_in_scientific_notation_reach_the_options(extra):
    status, out, err = run(["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", *extra, "--format", "json"])
    assert status == 0, err
    table = json.loads(out)
    if "-1e3" in extra:
        assert table["parameters"]["omega"] == -1000.0
    if "-5e-2" in extra:
        assert table["parameters"]["offset"] == -0.05
    if "-90:90:30" in extra:
        assert [row["phi_deg"] for row in table["rows"]] == [-90.0, -60.0, -30.0, 0.0, 30.0, 60.0]


def test_foreign_exceptions_are_the_packages_own():
    m = mech.CrankSlider(crank=1.0, rod=3.0)
    with pytest.raises(InvalidParameterError, match="omega"):        # was numpy's broadcasting ValueError
        m.solve([0.1, 0.2, 0.3], omega=[1.0, 2.0])
    with pytest.raises(InvalidParameterError, match="order"):        # was a TypeError/ValueError
        m.solve([0.1], order=np.array([1, 2]))
    sol = m.solve([0.1])
    for lookup in (sol.angle, sol.point, sol.slider):
        with pytest.raises(UnknownNameError) as info:                # was a bare KeyError
            lookup("rocker")
        assert isinstance(info.value, KeyError) and isinstance(info.value, MechanismError)
    with pytest.raises(InvalidParameterError, match="crank"):        # was OverflowError or NaN
        mech.CrankSlider(crank=10**400, rod=3.0)


@pytest.mark.parametrize("make", [lambda: mech.CrankSlider(crank=True, rod=3.0),
                                  lambda: mech.FourBar(1.0, 3.5, 3.0, frame="12"),
                                  lambda: mech.FourBar(1.0, 3.5, 3.0, (4.0, 0.0), keep_side="False"),
                                  lambda: mech.CrankSlider(crank=1.0, rod=3.0).solve(None)])
def test_no_silent_coercions(make):
    with pytest.raises(InvalidParameterError) as info:
        make()
    assert "nan" not in str(info.value)
