"""Families of the named linkages: ``FourBar`` and ``CrankSlider`` with dimensions given as arrays of one shape G
(mechanisms/linkages/four_bar.py, crank_slider.py, base.py; the blocks circle_circle.py and circle_line.py with
arrays of lengths, sides and guides).

Every member of a family is compared with the same geometry solved alone (to 1e-13 of the member's own scale),
and, independently of the package's blocks, with the loop-closure equations, the law of cosines (four-bar) and
the slider's position in closed form (crank-slider).
"""

import warnings

import numpy as np
import pytest

from mechanisms.analysis import crank_slider as slider_analysis
from mechanisms.analysis import four_bar as four_bar_analysis
from mechanisms.core.errors import AssemblyError, InvalidParameterError, SingularPositionWarning
from mechanisms.linkages.crank_slider import CrankSlider
from mechanisms.core.motion import PointMotion
from mechanisms.linkages.four_bar import FourBar, four_bar_family
from mechanisms.verify import checks as verify_checks

PHI = np.radians(np.arange(0.0, 360.0, 7.5))
TOLERANCE = 1e-13


def close(family_values, alone_values):
    """Equal to 1e-13 of the larger magnitude of the two (nan where both are nan)."""
    family_values, alone_values = np.asarray(family_values), np.asarray(alone_values)
    both_nan = np.isnan(family_values) & np.isnan(alone_values)
    scale = max(float(np.nanmax(np.abs(alone_values), initial=0.0)), 1.0)
    return bool(np.all(both_nan | (np.abs(family_values - alone_values) <= TOLERANCE * scale)))


# members: a crank-rocker (the benchmark's), another with C off the x axis, a drag-link, a parallelogram
# (a change-point linkage: d + L1 = L2 + L3 and |d − L1| = |L2 − L3|: 3 + 1 = 3 + 1, |3 − 1| = |3 − 1|), and a
# member of the other branch
FOUR_BARS = dict(crank=np.array([1.0, 0.8, 2.0, 1.0, 0.5]),
                 coupler=np.array([3.5, 3.0, 2.5, 3.0, 2.0]),
                 rocker=np.array([3.0, 2.6, 2.2, 1.0, 1.9]),
                 frame=(np.array([4.0, 3.2, 0.6, 3.0, 1.8]), np.array([0.0, 0.5, 0.3, 0.0, -0.4])),
                 branch=np.array([1, -1, 1, 1, -1]))


def four_bar_member(k, **extra):
    x, y = FOUR_BARS["frame"]
    return FourBar(float(FOUR_BARS["crank"][k]), float(FOUR_BARS["coupler"][k]), float(FOUR_BARS["rocker"][k]),
                   (float(x[k]), float(y[k])), int(FOUR_BARS["branch"][k]), **extra)


@pytest.mark.parametrize("keep_side", [False, True])
def test_every_four_bar_member_equals_the_linkage_solved_alone(keep_side):
    family = FourBar(**FOUR_BARS, keep_side=keep_side)
    assert family.family_shape == (5,)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)     # the parallelogram's change points
        solution = family.solve(PHI, omega=12.0, alpha=-3.0)
        assert solution.point("B").value.shape == (5, PHI.size) and solution.assembled.all()
        for k in range(5):
            alone = four_bar_member(k, keep_side=keep_side).solve(PHI, omega=12.0, alpha=-3.0)
            for name in ("A", "B"):
                for ours, theirs in zip(solution.point(name).derivatives(), alone.point(name).derivatives()):
                    assert close(ours[k], theirs), (k, name)
            for name in ("crank", "coupler", "rocker"):
                # angles compared as directions (a wrap by 2π is the same angle)
                assert close(np.angle(np.exp(1j * (solution.angle(name).value[k] - alone.angle(name).value))), 0.0)
                for ours, theirs in zip(solution.angle(name).derivatives()[1:], alone.angle(name).derivatives()[1:]):
                    assert close(ours[k], theirs), (k, name)
            assert np.array_equal(solution.singular[k], alone.singular)
    # the parallelogram passes change points: continued in its mode (the default) it changes sides there
    sides = np.sign(np.imag((solution.point("B").value[3] - solution.point("A").value[3])
                            * np.conj(3.0 - solution.point("A").value[3])))
    assert (len(set(sides[np.abs(sides) > 0])) == 1) == keep_side


def test_four_bar_family_against_loop_closure_and_the_law_of_cosines():
    family = FourBar(**FOUR_BARS, keep_side=True)
    solution = family.solve(PHI, omega=1.0, order=0)
    l1, l2, l3 = (FOUR_BARS[name][:, None] for name in ("crank", "coupler", "rocker"))
    c = (FOUR_BARS["frame"][0] + 1j * FOUR_BARS["frame"][1])[:, None]
    a, b = solution.point("A").value, solution.point("B").value
    psi, xi = solution.angle("coupler").value, solution.angle("rocker").value
    # A on the crank circle at φ; |AB| = L2, |CB| = L3 (loop closure, chapter 4)
    assert np.allclose(a, l1 * np.exp(1j * PHI), rtol=0.0, atol=1e-13)
    assert np.allclose(np.abs(b - a), l2, rtol=0.0, atol=1e-13) and np.allclose(np.abs(b - c), l3, rtol=0.0, atol=1e-13)
    # the loop-closure equations L1 e^{iφ} + L2 e^{iψ} − L3 e^{iξ} = C with the angles of the solution
    assert np.allclose(l1 * np.exp(1j * PHI) + l2 * np.exp(1j * psi) - l3 * np.exp(1j * xi), c, rtol=0.0, atol=1e-12)
    # law of cosines in triangle ABC: |AC|² = L2² + L3² − 2 L2 L3 cos μ, μ the angle at B between B→A and B→C
    mu = psi - xi
    assert np.allclose(np.abs(c - a) ** 2, l2**2 + l3**2 - 2.0 * l2 * l3 * np.cos(mu), rtol=0.0, atol=1e-12)
    # B on the side σ of the directed line A → C, member by member
    cross = np.imag((b - a) * np.conj(c - a))         # AC × AB > 0: B to the left (not at the change points)
    assert ((np.sign(cross) == FOUR_BARS["branch"][:, None]) | (np.abs(cross) < 1e-9)).all()


def test_family_link_angles_at_order_0_are_those_of_the_positions():
    solution = FourBar(**FOUR_BARS, keep_side=True).solve(PHI, order=0)
    a, b = solution.point("A").value, solution.point("B").value
    c = (FOUR_BARS["frame"][0] + 1j * FOUR_BARS["frame"][1])[:, None]
    coupler, rocker = solution.angle("coupler"), solution.angle("rocker")
    # expected: the directions of A → B and C → B computed here from the positions
    assert np.allclose(np.exp(1j * coupler.value), (b - a) / np.abs(b - a), rtol=0.0, atol=1e-14)
    assert np.allclose(np.exp(1j * rocker.value), (b - c) / np.abs(b - c), rtol=0.0, atol=1e-14)
    assert coupler[1].value.shape == (PHI.size,) and coupler.order == 0 and coupler.velocity is None
    assert np.array_equal((2.0 * coupler).value, 2.0 * coupler.value)


def test_family_of_two_dimensions_broadcasts_and_names_members_by_both_indices():
    crank = np.array([[1.0], [0.8]])                        # G = (2, 3) from (2, 1) and (1, 3)
    coupler = np.array([[3.5, 3.4, 3.6]])
    family = FourBar(crank, coupler, 3.0, (4.0, 0.0))
    solution = family.solve(PHI[:5], order=1)
    assert family.family_shape == (2, 3) and solution.point("B").velocity.shape == (2, 3, 5)
    alone = FourBar(0.8, 3.6, 3.0, (4.0, 0.0)).solve(PHI[:5], order=1)
    assert close(solution.point("B").velocity[1, 2], alone.point("B").velocity)
    with pytest.raises(InvalidParameterError, match=r"coupler\[0, 1\]"):
        FourBar(crank, np.array([[3.5, -1.0, 3.6]]), 3.0, (4.0, 0.0))


def test_lenient_four_bar_family_marks_what_does_not_assemble():
    # member 0 assembles everywhere; member 1 never (C = (10, 0) with L1 + L2 + L3 = 4); member 2 (a triple
    # rocker: 1 + 4 > 2 + 2.5) only where |L2 − L3| ≤ |AC| ≤ L2 + L3
    l1, l2, l3 = np.array([1.0, 1.0, 2.0]), np.array([3.5, 1.5, 2.0]), np.array([3.0, 1.5, 2.5])
    x = np.array([4.0, 10.0, 4.0])
    solution = FourBar(l1, l2, l3, (x, 0.0), lenient=True).solve(PHI, omega=2.0)
    reach = np.abs(x[:, None] - l1[:, None] * np.exp(1j * PHI))     # |AC|, computed here
    inside = (reach < (l2 + l3)[:, None] - 1e-9) & (reach > np.abs(l2 - l3)[:, None] + 1e-9)
    outside = (reach > (l2 + l3)[:, None] + 1e-9) | (reach < np.abs(l2 - l3)[:, None] - 1e-9)
    assert solution.assembled[0].all() and not solution.assembled[1].any()
    assert inside[2].any() and outside[2].any()
    assert solution.assembled[inside].all() and not solution.assembled[outside].any()
    for motion in (solution.point("B"), solution.angle("coupler"), solution.angle("rocker")):
        assert np.isnan(motion.value[outside]).all() and np.isnan(motion.velocity[outside]).all()
        assert np.isfinite(motion.value[inside]).all()
    assert not solution.singular[outside].any()
    # strictly, the family names the first member that fails
    with pytest.raises(AssemblyError, match="member 1 of the family"):
        FourBar(l1, l2, l3, (x, 0.0)).solve(PHI)


def test_one_four_bar_solved_leniently_marks_the_crank_angles_outside_its_intervals():
    linkage = FourBar(2.0, 2.0, 2.5, (4.0, 0.0), lenient=True)      # a triple rocker: 2 + 4 > 2 + 2.5
    solution = linkage.solve(PHI, order=0)
    (lo, hi), *rest = FourBar(2.0, 2.0, 2.5, (4.0, 0.0)).assembly_intervals()   # analytic, chapter 4
    intervals = [(lo, hi), *rest]
    within = np.zeros(PHI.shape, bool)
    for start, stop in intervals:
        within |= (np.mod(PHI - start, 2 * np.pi) < stop - start)
    assert np.array_equal(solution.assembled, within) and 0 < within.sum() < PHI.size
    assert np.isnan(solution.point("B").value[~within]).all()


@pytest.mark.filterwarnings("ignore::mechanisms.core.errors.SingularPositionWarning")   # the parallelogram's
def test_four_bar_family_function_is_the_class():
    old = four_bar_family(FOUR_BARS["crank"], FOUR_BARS["coupler"], FOUR_BARS["rocker"], *FOUR_BARS["frame"], PHI,
                          omega=3.0, branch=FOUR_BARS["branch"], order=1)
    new = FourBar(**FOUR_BARS, keep_side=True).solve(PHI, omega=3.0, order=1)
    assert np.array_equal(old.points["B"].velocity, new.point("B").velocity, equal_nan=True)   # nan: change points
    assert np.array_equal(old.angles["rocker"].value, new.angle("rocker").value)


# --- crank-sliders ------------------------------------------------------------------------------------------

SLIDERS = dict(crank=np.array([0.1, 0.08, 0.05, 0.12]), rod=np.array([0.3, 0.35, 0.2, 0.4]),
               offset=np.array([0.0, 0.02, -0.03, 0.05]), branch=np.array([1, -1, 1, -1]))


def test_every_crank_slider_member_equals_the_linkage_solved_alone_and_the_closed_form():
    solution = CrankSlider(**SLIDERS).solve(PHI, omega=20.0, alpha=5.0)
    assert solution.point("B").acceleration.shape == (4, PHI.size) and solution.assembled.all()
    for k in range(4):
        alone = CrankSlider(*(float(SLIDERS[n][k]) for n in ("crank", "rod", "offset")),
                            int(SLIDERS["branch"][k])).solve(PHI, omega=20.0, alpha=5.0)
        for ours, theirs in zip(solution.point("B").derivatives(), alone.point("B").derivatives()):
            assert close(ours[k], theirs)
        for ours, theirs in zip(solution.slider("B").derivatives(), alone.slider("B").derivatives()):
            assert close(ours[k], theirs)
        for ours, theirs in zip(solution.angle("coupler").derivatives(), alone.angle("coupler").derivatives()):
            assert close(ours[k], theirs)
    # closed form (chapter 3): x_B = L1 cos φ + σ √(L2² − (L1 sin φ − e)²), y_B = e
    l1, l2, e, sigma = (SLIDERS[n][:, None] for n in ("crank", "rod", "offset", "branch"))
    x_b = l1 * np.cos(PHI) + sigma * np.sqrt(l2**2 - (l1 * np.sin(PHI) - e) ** 2)
    assert np.allclose(solution.point("B").value, x_b + 1j * e, rtol=0.0, atol=1e-14)
    assert np.allclose(solution.slider("B").value, x_b, rtol=0.0, atol=1e-14)


@pytest.mark.filterwarnings("ignore::mechanisms.core.errors.SingularPositionWarning")   # at the limits of reach
def test_lenient_crank_slider_family_marks_a_rod_that_cannot_reach():
    # member 1: the rod 0.1 m, the crank 0.2 m: the pin is out of reach where |L1 sin φ − e| > L2
    crank, rod = np.array([0.1, 0.2]), np.array([0.3, 0.1])
    solution = CrankSlider(crank, rod, lenient=True).solve(PHI, omega=1.0)
    reachable = np.abs(crank[:, None] * np.sin(PHI)) <= rod[:, None] - 1e-12     # computed here
    unreachable = np.abs(crank[:, None] * np.sin(PHI)) > rod[:, None] + 1e-12
    assert solution.assembled[0].all() and unreachable[1].any() and reachable[1].any()
    assert solution.assembled[reachable].all() and not solution.assembled[unreachable].any()
    assert np.isnan(solution.point("B").value[unreachable]).all() and not solution.singular[unreachable].any()
    assert np.isfinite(solution.slider("B").velocity[reachable & ~solution.singular]).all()
    with pytest.raises(AssemblyError, match="member 1 of the family"):
        CrankSlider(crank, rod).solve(PHI)
    with pytest.raises(AssemblyError, match="member 1 of the family cannot be assembled at any crank angle"):
        CrankSlider([0.1, 0.1], [0.3, 0.1], offset=[0.0, 0.5])


# --- bad input ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("change, name", [
    ({"crank": [1.0, -1.0]}, r"crank\[1\]"),
    ({"crank": [1.0, 0.0, -2.0]}, r"crank\[1\].*2 members"),
    ({"rocker": [np.nan, 3.0]}, r"rocker\[0\]"),
    ({"coupler": "3.5"}, "coupler"),
    ({"frame": ([4.0, np.inf], 0.0)}, r"frame\[0\]\[1\]"),
    ({"frame": ([4.0, 0.0], 0.0)}, "frame"),
    ({"coupler": [3.5, 3.4, 3.3]}, "crank, coupler"),
    ({"branch": [1, 0]}, r"branch\[1\]"),
    ({"branch": [1.0, -1.0]}, "branch"),
    ({"lenient": "yes"}, "lenient"),
])
def test_four_bar_family_refuses_bad_members_by_index(change, name):
    arguments = dict(crank=[1.0, 0.9], coupler=3.5, rocker=3.0, frame=(4.0, [0.0, 0.1]))
    arguments.update(change)
    with pytest.raises(InvalidParameterError, match=name):
        FourBar(**arguments)


@pytest.mark.parametrize("change, name", [
    ({"rod": [0.3, -0.3]}, r"rod\[1\]"),
    ({"offset": [0.0, np.nan]}, r"offset\[1\]"),
    ({"branch": [[1], [2]]}, r"branch\[1, 0\]"),
    ({"rod": [0.3, 0.3, 0.3]}, "crank, rod"),
])
def test_crank_slider_family_refuses_bad_members_by_index(change, name):
    arguments = dict(crank=[0.1, 0.12], rod=0.3, offset=0.0)
    arguments.update(change)
    with pytest.raises(InvalidParameterError, match=name):
        CrankSlider(**arguments)


def test_a_family_needs_one_dimensional_crank_angles():
    with pytest.raises(InvalidParameterError, match="phi"):
        FourBar([1.0, 0.9], 3.5, 3.0, (4.0, 0.0)).solve(np.zeros((2, 2)))
    with pytest.raises(InvalidParameterError, match="phi"):
        CrankSlider([0.1, 0.12], 0.3).solve(np.zeros((2, 2)))


four_bars = FourBar([1.0, 0.9], 3.5, 3.0, (4.0, 0.0))
sliders = CrankSlider([0.1, 0.12], 0.3)


@pytest.mark.parametrize("ask", [
    four_bars.assembly_intervals, four_bars.full_turn, four_bars.change_points, four_bars.linkage_data,
    four_bars.describe, four_bars.groups, four_bars.scheme, lambda: four_bars.lengths,
    lambda: four_bar_analysis.transmission_extremes(four_bars), lambda: four_bar_analysis.limit_positions(four_bars),
    lambda: four_bar_analysis.coupler_curve(four_bars, 1.0),
    sliders.assembly_intervals, sliders.linkage_data, sliders.describe,
    lambda: slider_analysis.dead_centres(sliders), lambda: slider_analysis.stroke(sliders),
    lambda: slider_analysis.transmission_min(sliders), lambda: slider_analysis.time_ratio(sliders),
    lambda: slider_analysis.slider_extremes(sliders), lambda: slider_analysis.approximate_slider(sliders, [0.1]),
    lambda: verify_checks.distance_deviation(four_bars, four_bars.solve(np.array([0.1]))),
    lambda: verify_checks.generic_errors(four_bars, [0.1]),
])
def test_what_is_defined_for_one_linkage_refuses_a_family_by_name(ask):
    with pytest.raises(InvalidParameterError, match="crank"):
        ask()


def test_what_works_per_position_works_per_member():
    # the transmission angle of each member is that of the member solved alone (a formula on the angles)
    family = four_bars.solve(PHI)
    mu = four_bar_analysis.transmission_angle(family)
    alone = four_bar_analysis.transmission_angle(FourBar(0.9, 3.5, 3.0, (4.0, 0.0)).solve(PHI))
    assert mu.shape == (2, PHI.size) and close(mu[1], alone)
    gamma = slider_analysis.transmission_angle(sliders.solve(PHI))
    assert close(gamma[1], slider_analysis.transmission_angle(CrankSlider(0.12, 0.3).solve(PHI)))


def test_a_singular_member_is_named_in_the_warning():
    # member 1 is a parallelogram (change points at 0° and 180°); member 0 the benchmark's crank-rocker
    with pytest.warns(SingularPositionWarning, match=r"0°, 180° of member 1"):
        solution = FourBar([1.0, 1.0], [3.5, 3.0], [3.0, 1.0], ([4.0, 3.0], 0.0)).solve(PHI)
    assert not solution.singular[0].any() and solution.singular[1, [0, 24]].all()


def test_a_family_of_huge_linkages_is_solved_at_a_scale_of_its_own():
    scale = 1e100
    family = FourBar(np.array([1.0, 0.9]) * scale, 3.5 * scale, 3.0 * scale, (4.0 * scale, 0.0))
    solution = family.solve(PHI, omega=2.0)
    # expected: the same linkage at unit scale, multiplied by the scale (solved alone)
    alone = FourBar(0.9, 3.5, 3.0, (4.0, 0.0)).solve(PHI, omega=2.0)
    assert close(solution.point("B").velocity[1] / scale, alone.point("B").velocity)


@pytest.mark.parametrize("solve", ["hinge", "hinge_plain"])
def test_deferred_hinge_angles_are_the_angles_computed_at_once(solve):
    from mechanisms.blocks import circle_circle

    function = getattr(circle_circle, solve)
    pin = PointMotion(np.array([[1.0 + 0.5j, 0.2 + 1.0j], [0.9 + 0.1j, -5.0 + 0.0j]]))
    pivot = PointMotion(np.full((2, 2), 4.0 + 0.0j))
    lengths = np.array([[3.5], [3.0]])
    now = function(pin, pivot, lengths, 3.0, 1, lenient=True)
    later = function(pin, pivot, lengths, 3.0, 1, lenient=True, deferred_angles=True)
    assert isinstance(later.angle_p, circle_circle.DeferredAngle)
    # the last position does not assemble: |pin − pivot| = 9 m > 3 + 3 m
    assert not now.assembled[1, 1] and not later.assembled[1, 1] and now.assembled.sum() == 3
    for a, b in ((now.angle_p, later.angle_p), (now.angle_q, later.angle_q)):
        assert np.array_equal(a.value, b.value, equal_nan=True)


@pytest.mark.parametrize("order", [0, 2])
def test_a_coupler_point_of_a_family_is_that_of_each_member(order):
    family = FourBar([1.0, 0.9], 3.5, 3.0, (4.0, 0.0)).solve(PHI, omega=5.0, order=order)
    point = family.point_on("coupler", 1.0, 0.5)
    alone = FourBar(0.9, 3.5, 3.0, (4.0, 0.0)).solve(PHI, omega=5.0, order=order).point_on("coupler", 1.0, 0.5)
    for ours, theirs in zip(point.derivatives()[:order + 1], alone.derivatives()[:order + 1]):
        assert close(ours[1], theirs)
    # expected, independently: P = A + (u + iw)·(B − A)/L2 from the positions of A and B
    a, b = family.point("A").value, family.point("B").value
    assert np.allclose(point.value, a + (1.0 + 0.5j) * (b - a) / 3.5, rtol=0.0, atol=1e-14)
