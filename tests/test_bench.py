"""The benchmark (mechanisms.bench and ``python -m mechanisms bench``) at a tiny size.

No test here asserts a time: the machines that run the tests are shared and their timings
vary. What is tested is that the command runs, reports every method with the documented keys,
and that its errors are right (the reference against the generic solver, the closed form
against the reference).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import mechanisms as mech
from mechanisms import bench
from mechanisms.cli import main


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return bench.run(sizes=[40], repeat=1)


def test_cli_json_has_the_documented_keys(capsys):
    assert main(["bench", "--sizes", "24", "--repeat", "1", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["results"]
    for result in out["results"]:
        assert tuple(result) == bench.RESULT_KEYS
        assert result["n"] >= 1 and result["seconds"] > 0
        assert result["ns_per_position"] == pytest.approx(result["seconds"] / result["n"] * 1e9)
    assert {"date", "machine", "reference", "notes"} <= set(out)


def test_cli_text_and_bad_sizes(capsys):
    assert main(["bench", "--sizes", "16", "--repeat", "1"]) == 0
    text = capsys.readouterr().out
    for word in ("closed form", "newton", "central difference", "memory floor", "four-bar", "slotted-lever"):
        assert word in text
    assert main(["bench", "--sizes", "0"]) == 2
    assert "--sizes" in capsys.readouterr().err


def test_every_method_of_every_mechanism_is_reported(report):
    found = {(r["mechanism"], r["method"], r["order"]) for r in report["results"]}
    for name in ("crank-slider", "four-bar", "slotted-lever", "four-bar (composed)", "watt-six-bar"):
        for order in (0, 1, 2):
            assert (name, "closed form", order) in found
            assert (name, "memory floor", order) in found
        assert (name, "newton", 2) in found
        assert (name, "central difference", 1) in found and (name, "central difference", 2) in found
    newton = [r["parameter"] for r in report["results"] if r["method"] == "newton" and r["mechanism"] == "four-bar"]
    assert newton == list(bench.NEWTON_TOLERANCES)


def test_peers_are_reported_or_their_absence_is_said(report):
    peers = [r for r in report["results"] if r["method"].startswith("pylinkage")]
    if bench.pylinkage_available():
        assert {r["method"] for r in peers} == {"pylinkage step", "pylinkage step_fast"}
        # pylinkage accumulates the crank angle step by step: its error is small but not round-off
        assert all(0 < r["max_error"] < 1e-9 for r in peers)
    else:
        assert not peers
        assert any("pylinkage" in note for note in report["notes"])


def test_errors_are_what_the_methods_deserve(report):
    results = report["results"]
    closed = [r["max_error"] for r in results if r["method"] == "closed form"]
    assert max(closed) <= 1e-14                     # round-off only
    assert all(r["max_error"] is None for r in results if r["method"] == "memory floor")
    for name in ("crank-slider", "four-bar", "slotted-lever"):
        newton = {r["parameter"]: r["max_error"] for r in results
                  if r["method"] == "newton" and r["mechanism"] == name}
        assert newton[1e-14] <= 1e-14 and newton[1e-2] > newton[1e-14]
        first = {r["parameter"]: r["max_error"] for r in results
                 if r["method"] == "central difference" and r["order"] == 1 and r["mechanism"] == name}
        # truncation error ∝ h² while h is large: a step 10× smaller gives about 100× less error
        assert 50 < first[1e-2] / first[1e-3] < 200
        # round-off ∝ 1/h takes over below the best step: h = 1e-6 is worse than 1e-5
        assert first[1e-6] > first[1e-5]


def test_reference_agrees_with_the_generic_solver_and_is_extended():
    m = bench.benchmark_mechanisms()["slotted-lever"]
    phi = np.linspace(0.0, 2.0 * np.pi, 30, endpoint=False)
    q, q_t, q_tt = bench.reference(m, phi, omega=1.5, alpha=0.3)
    assert q.dtype == np.longdouble
    generic = mech.verify.solve_constraints(m.constraints, q[:, 0].astype(float), phi, 1.5, 0.3, tol=1e-15)
    # two independent solutions of the same constraint equations agree to round-off
    assert np.max(np.abs(np.angle(np.exp(1j * (generic.q[0] - q[0].astype(float)))))) <= 1e-15
    assert np.max(np.abs(generic.q_t - q_t.astype(float))) <= 1e-14
    assert np.max(np.abs(generic.q_tt - q_tt.astype(float))) <= 1e-13


def test_coordinate_errors_and_output_bytes():
    m = bench.benchmark_mechanisms()["four-bar"]
    phi = np.linspace(0.0, 2.0 * np.pi, 50)
    ref = bench.reference(m, phi)
    sol = m.solve(phi, omega=1.0, order=1)
    coords = m.coordinates(sol)
    q = np.array([c.value for c in coords])
    q_t = np.array([c.velocity for c in coords])
    errors = bench.coordinate_errors(m, q + 2 * np.pi, q_t, None, ref)   # a whole turn is no error
    assert errors[0] <= 1e-14 and errors[1] <= 1e-14 and math.isnan(errors[2])
    # order 1: two angles with their speeds (real, 8 B), the moving points A and B with their
    # velocities (complex, 16 B). Not counted: the pivots O and C and their zero velocities, and
    # the constant crank speed, which are broadcast views of one number (no memory)
    assert bench.output_bytes(sol) == 50 * (2 * 2 * 8 + 2 * 2 * 16)
    assert bench.output_bytes(m.solve(phi, order=0)) == 50 * (2 * 8 + 2 * 16)
    assert 0 in sol.point("C").value.strides and 0 in sol.angle("crank").omega.strides


def test_composed_linkages_are_measured_on_all_their_coordinates():
    table = bench.benchmark_mechanisms()
    composed, six_bar = table["four-bar (composed)"], table["watt-six-bar"]
    assert isinstance(composed, mech.Linkage) and isinstance(six_bar, mech.Linkage)
    phi = np.linspace(0.0, 2.0 * np.pi, 40, endpoint=False)
    q, q_t, q_tt = bench.reference(six_bar, phi)
    # joints B, D, E (x, y) and the units of the links that turn: more than two coordinates
    assert q.shape[0] > 2
    sol = six_bar.solve(phi, omega=1.0)
    coords = six_bar.coordinates(sol)
    parts = [np.array([c.derivatives()[k] for c in coords]) for k in range(3)]
    assert max(bench.coordinate_errors(six_bar, *parts, (q, q_t, q_tt))) <= 1e-14
    # a wrong row anywhere is seen: shift the last coordinate by 1e-9
    parts[0][-1] += 1e-9
    assert bench.coordinate_errors(six_bar, *parts, (q, q_t, q_tt))[0] >= 0.9e-9
    # the composed four-bar's joint B agrees with the class's (two independent constructions)
    b_class = table["four-bar"].solve(phi, omega=1.0).point("B")
    b_comp = composed.solve(phi, omega=1.0).point("B")
    for k in range(3):
        assert np.max(np.abs(b_class.derivatives()[k] - b_comp.derivatives()[k])) <= 1e-13


def test_best_time_keeps_the_shortest():
    calls = []
    assert bench.best_time(lambda: calls.append(1), 4) >= 0.0
    assert len(calls) == 4


def test_format_text_lists_every_result(report):
    text = bench.format_text(report)
    assert text.count("\n") >= len(report["results"])


def test_reference_fields_are_named_and_unpack_as_a_triple():
    m = mech.FourBar(crank=1.0, coupler=3.0, rocker=2.0, frame=(2.5, 0.0))
    ref = bench.reference(m, [0.5])
    q, q_t, q_tt = ref
    assert ref.q is q and ref.q_t is q_t and ref.q_tt is q_tt
    assert ref.q.shape == (2, 1) and ref.q.dtype == np.longdouble


@pytest.mark.parametrize("name", ["four-bar", "crank-slider"])
def test_central_differences_solve_once_per_shifted_angle(name, monkeypatch):
    # Numerical differentiation is charged what a program pays: one solution of all coordinates
    # at φ + h and one at φ − h (and one at φ for accelerations), not one per coordinate.
    mechanism = bench.benchmark_mechanisms()[name]
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    angles = tuple(isinstance(c, mech.core.motion.AngleMotion)
                   for c in mechanism.coordinates(mechanism.solve(phi, order=0)))
    solve, calls = type(mechanism).solve, []

    def counted(self, *args, **kwargs):
        calls.append(1)
        return solve(self, *args, **kwargs)

    for derivative, solutions in ((1, 2), (2, 3)):
        monkeypatch.setattr(type(mechanism), "solve", counted)
        calls.clear()
        values = bench.benchmark._central_differences(mechanism, phi, 1e-4, derivative, angles)
        monkeypatch.undo()
        assert len(calls) == solutions
        # expected: the package's central_difference applied to each coordinate on its own
        for row, angle in enumerate(angles):
            def coordinate(a, row=row):
                return mechanism.coordinates(mechanism.solve(a, order=0))[row].value
            alone = mech.verify.central_difference(coordinate, phi, 1.0, 1e-4, derivative,
                                                   angle=angle)
            assert np.array_equal(values[row], alone)


def test_setting_labels_are_powers_of_ten_in_math():
    from mechanisms.bench import setting_label
    assert setting_label("newton", 1e-10) == r"$\mathrm{tol} = 10^{-10}$"
    assert setting_label("central difference", 1e-5) == "$h = 10^{-5}$"


# --- the figures of round-off (chapter 9), the same bits on every machine ---------------------------

HALF_ANGLE_GEOMETRY = (1.0, 3.5, 3.0, (-2.0, 3.0))      # chapter 9, §9.6.3


def _nudged(function, rng):
    """``function`` whose double-precision results are moved by one unit in the last place, at random.

    Each element keeps its value (a third of them) or moves one ulp up or down: a faithful double-
    precision sine or arctangent other than numpy's, as another processor's vector kernels may give.
    Complex results have each part moved; ``numpy.abs`` of real numbers (exact) is left alone.
    """
    def nudge(a):
        moved = np.nextafter(a, np.where(rng.random(a.shape) < 0.5, -np.inf, np.inf))
        return np.where(rng.random(a.shape) < 1 / 3, a, moved)

    def wrapper(*args, **kwargs):
        result = function(*args, **kwargs)
        values = np.asarray(result)
        if function in (np.absolute, np.abs) and not np.iscomplexobj(args[0]):
            return result
        if values.dtype == np.float64:
            moved = nudge(values)
        elif values.dtype == np.complex128:
            moved = nudge(values.real) + 1j * nudge(values.imag)
        else:                       # extended precision: the C library's, the same on every machine
            return result
        return moved if isinstance(result, np.ndarray) else moved[()]
    return wrapper


NUDGED = ("sin", "cos", "tan", "arctan", "arctan2", "arcsin", "arccos", "hypot", "exp", "log",
          "power", "tanh", "cbrt", "angle", "absolute", "abs")


def _chapter_9_round_off():
    """What chapter 9 prints or plots of round-off, computed by the package's reproducible functions."""
    from mechanisms.analysis.four_bar import half_angle_denominator_root
    m = bench.benchmark_mechanisms()["four-bar"]
    root = half_angle_denominator_root(*np.radians([2.0, 3.0]), *HALF_ANGLE_GEOMETRY, extended=True)
    offsets = bench.logspace(-1, -12, 23)
    angles = bench.reproducible_coupler_angles(root + offsets, *HALF_ANGLE_GEOMETRY, branch=-1)
    steps = bench.logspace(-2, -6, 5)
    errors = bench.step_errors(m, steps, n=24)
    ng = mech.FourBar(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))   # chapter 9's non-Grashof
    low, high = ng.assembly_intervals()[0]
    near_ends = np.concatenate([low + bench.logspace(-9, -1, 5), high - bench.logspace(-9, -1, 5)])
    cond = bench.reproducible_jacobian_condition(ng, near_ends)
    return [np.array([root]), offsets, angles["half-angle"], angles["stable"], steps,
            errors["velocities"], errors["accelerations"], cond]


def test_chapter_9_round_off_has_the_same_bits_when_numpys_elementary_functions_differ(monkeypatch):
    # The closest this machine comes to an AVX-512 processor: every double-precision sine, cosine,
    # arctangent, power … that numpy computes is moved by one ulp at random (a faithful function other
    # than this machine's). What the chapter plots must not move at all. (It checks only calls made
    # through numpy's functions by name; operators such as complex multiplication are not covered.)
    expected = _chapter_9_round_off()
    for seed in range(3):
        rng = np.random.default_rng(seed)
        with monkeypatch.context() as patch:
            for name in NUDGED:
                patch.setattr(np, name, _nudged(getattr(np, name), rng))
            got = _chapter_9_round_off()
        for a, b in zip(got, expected):
            assert a.tobytes() == b.tobytes()


def test_the_nudge_changes_the_closed_forms_round_off(monkeypatch):
    # The test above can fail: the package's own closed form does change under the nudge.
    m = bench.benchmark_mechanisms()["four-bar"]
    phi = np.radians(np.arange(0.0, 360.0, 7.0))
    plain = np.array([c.value for c in m.coordinates(m.solve(phi, order=0))])
    rng = np.random.default_rng(0)
    with monkeypatch.context() as patch:
        for name in NUDGED:
            patch.setattr(np, name, _nudged(getattr(np, name), rng))
        nudged = np.array([c.value for c in m.coordinates(m.solve(phi, order=0))])
    assert nudged.tobytes() != plain.tobytes()
    assert np.max(np.abs(nudged - plain)) < 1e-14


def test_the_nudge_changes_the_closed_forms_condition_number_near_a_singular_position(monkeypatch):
    # The test above can fail for the condition number too: computed from the closed form's positions
    # (jacobian_condition), cond near the ends of the swing moves under the nudge.
    ng = mech.FourBar(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))
    low, high = ng.assembly_intervals()[0]
    near_ends = np.concatenate([low + bench.logspace(-9, -1, 5), high - bench.logspace(-9, -1, 5)])
    plain = bench.jacobian_condition(ng, near_ends)
    rng = np.random.default_rng(1)
    with monkeypatch.context() as patch:
        for name in NUDGED:
            patch.setattr(np, name, _nudged(getattr(np, name), rng))
        nudged = bench.jacobian_condition(ng, near_ends)
    assert nudged.tobytes() != plain.tobytes()


def test_reproducible_condition_number_is_the_exact_one():
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.prec = 200
    ng = mech.FourBar(crank=2.0, coupler=2.0, rocker=2.5, frame=(3.0, 0.0))
    low, high = ng.assembly_intervals()[0]
    phi = np.array([low + 1e-9, 0.5 * (low + high), high - 1e-6])
    got = bench.reproducible_jacobian_condition(ng, phi)
    # expected: Φ_q of the four-bar by hand at the extended-precision positions, its singular values
    # by mpmath's SVD at 200 bits. Φ = L1 e^{iφ} + L2 e^{iψ} − L3 e^{iξ} − C, q = (ψ, ξ):
    # Φ_q = [[−L2 sin ψ, L3 sin ξ], [L2 cos ψ, −L3 cos ξ]]
    q = bench.reproducible_reference(ng, phi).q
    for n in range(phi.size):
        psi, xi = (mpmath.mpf(str(v)) for v in (q[0, n], q[1, n]))
        matrix = mpmath.matrix([[-2 * mpmath.sin(psi), 2.5 * mpmath.sin(xi)],
                                [2 * mpmath.cos(psi), -2.5 * mpmath.cos(xi)]])
        sigma = mpmath.svd_r(matrix, compute_uv=False)
        expected = float(max(sigma) / min(sigma))
        assert got[n] == pytest.approx(expected, rel=1e-12)
    # and the singular values of a matrix with one tiny: [[1, 1], [1, 1 + δ]], σ₁σ₂ = |det| = δ,
    # σ₁² + σ₂² = 3 + (1 + δ)² (the Frobenius norm), so σ₂ = δ/σ₁
    delta = 2.0 ** -40                       # 1 + δ exact in double
    from mechanisms.bench.benchmark import _singular_values_extended
    sigma = _singular_values_extended(np.array([[[1.0, 1.0], [1.0, 1.0 + delta]]], dtype=np.longdouble))[0]
    big = mpmath.sqrt((3 + (1 + mpmath.mpf(delta)) ** 2 + mpmath.sqrt((3 + (1 + mpmath.mpf(delta)) ** 2) ** 2
                                                                     - 4 * mpmath.mpf(delta) ** 2)) / 2)
    assert float(sigma[0]) == pytest.approx(float(big), rel=1e-15)
    assert float(sigma[1]) == pytest.approx(float(mpmath.mpf(delta) / big), rel=1e-6)   # ε_ext·cond ≈ 4e-7


def test_logspace_is_the_powers_of_ten_correctly_rounded():
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.prec = 200
    for start, stop, num in ((-1, -8, 15), (-1, -12, 23), (-2, -6, 9), (0, 3, 4)):
        got = bench.logspace(start, stop, num)
        # 10**x for the exact exponents start + k (stop − start)/(num − 1), rounded once by mpmath
        expected = [float(mpmath.power(10, mpmath.mpf(start) + k * (mpmath.mpf(stop) - start) / (num - 1)))
                    for k in range(num)]
        assert got.tolist() == expected


def test_reproducible_coupler_angles_are_the_formulas_with_correctly_rounded_functions():
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.prec = 200
    crank, coupler, rocker, (a, b) = HALF_ANGLE_GEOMETRY
    phi = [0.04212263556548 + 10.0 ** -k for k in range(1, 13)] + [1.0, 2.5, -2.0]
    got = bench.reproducible_coupler_angles(phi, *HALF_ANGLE_GEOMETRY, branch=-1)
    for i, angle in enumerate(phi):
        x = mpmath.mpf(angle)
        # 𝒫, 𝒬, ℱ exact (mpmath) and rounded once; then the formulas in Python floats, whose
        # +, −, ×, ÷ and square root are correctly rounded, with mpmath's arctangents rounded once
        p_exact, q_exact = a - crank * mpmath.cos(x), b - crank * mpmath.sin(x)
        p, q = float(p_exact), float(q_exact)
        f = float((p_exact**2 + q_exact**2 + coupler**2 - rocker**2) / (2 * coupler))
        t = (q - math.sqrt(q * q + p * p - f * f)) / (p + f)
        assert got["half-angle"][i] == 2.0 * float(mpmath.atan(t)), i
        r = float(mpmath.hypot(p, q))
        height = math.sqrt((coupler + rocker + r) * (coupler + rocker - r) * (r - (coupler - rocker))
                           * (r + (coupler - rocker))) / (2.0 * coupler)
        foot = (r * r + (coupler - rocker) * (coupler + rocker)) / (2.0 * coupler)
        psi = float(mpmath.atan2(q, p)) - float(mpmath.atan2(height, foot))
        if psi <= -math.pi or psi > math.pi:      # not met at these angles: the sum is in (−π, π]
            pytest.fail("the test's angles should not need wrapping")
        assert got["stable"][i] == psi, i


def test_the_extended_root_of_p_plus_f_changes_sign_at_the_next_double():
    mpmath = pytest.importorskip("mpmath")
    from mechanisms.analysis.four_bar import half_angle_denominator_root
    mpmath.mp.prec = 200
    crank, coupler, rocker, (a, b) = HALF_ANGLE_GEOMETRY

    def p_plus_f(angle):          # exact 𝒫 + ℱ at a double φ (mpmath, 200 bits)
        p, q = a - crank * mpmath.cos(mpmath.mpf(angle)), b - crank * mpmath.sin(mpmath.mpf(angle))
        return p + (p**2 + q**2 + coupler**2 - rocker**2) / (2 * coupler)

    low, high = np.radians([2.0, 3.0])
    root = half_angle_denominator_root(low, high, *HALF_ANGLE_GEOMETRY, extended=True)
    after = float(np.nextafter(root, high))
    assert mpmath.sign(p_plus_f(root)) == mpmath.sign(p_plus_f(low)) != mpmath.sign(p_plus_f(after))
    # the default, double precision, keeps its behaviour: its 𝒫 + ℱ carries round-off of a few
    # 1e-16 m, and the slope of 𝒫 + ℱ is of order 1 m/rad, so its root is within about 1e-15 rad
    plain = half_angle_denominator_root(low, high, *HALF_ANGLE_GEOMETRY)
    assert abs(plain - root) < 1e-14
