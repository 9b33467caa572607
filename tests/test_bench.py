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
