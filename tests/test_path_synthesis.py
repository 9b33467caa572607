"""Tests of path synthesis (mechanisms/analysis/path_synthesis.py): coupler curves of a family, the target's
checks, and fits of a coupler point to paths that known four-bars trace (checked by solving the written
linkage file with the general linkage solver, on points of the original curve the fit never saw)."""

import math

import numpy as np
import pytest

from mechanisms import load_linkage
from mechanisms.analysis.path_synthesis import coupler_curves, fit_path, require_target, target_size
from mechanisms.core.errors import InvalidParameterError
from mechanisms.linkages.linkage_file import linkage_from_dict

try:
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib  # type: ignore[no-redef]


def cosine_law_coupler_point(l1, l2, l3, c, u, w, phi, branch):
    """The coupler point by the cosine law, written independently of the package: A = L1·e^{iφ}; the angle
    at A between AC and AB is arccos((L2² + |AC|² − L3²)/(2 L2 |AC|)), on the side ``branch`` of A → C;
    P = A + (u + iw)·e^{iψ}. Returns (P, assembled) with P = nan where |L2 − L3| ≤ |AC| ≤ L2 + L3 fails."""
    a = l1 * np.exp(1j * phi)
    ac = c - a
    reach = np.abs(ac)
    assembled = (reach <= l2 + l3) & (reach >= abs(l2 - l3))
    with np.errstate(invalid="ignore"):
        opening = np.arccos((l2**2 + reach**2 - l3**2) / (2.0 * l2 * reach))
    psi = np.angle(ac) + branch * opening
    point = a + (u + 1j * w) * np.exp(1j * psi)
    return np.where(assembled, point, np.nan), assembled


def test_coupler_curves_of_a_family_against_the_cosine_law():
    rng = np.random.default_rng(7)
    g = 50
    l1, l2, l3 = rng.uniform(0.2, 2.0, (3, g))
    cx, cy, u, w = rng.uniform(-1.5, 1.5, (4, g))
    branch = rng.choice([-1, 1], g)
    phi = np.linspace(-np.pi, np.pi, 73)
    curves = coupler_curves(l1, l2, l3, cx, cy, u, w, phi, branch)
    assert curves.point.shape == curves.assembled.shape == (g, 73)
    expected, assembled = cosine_law_coupler_point(l1[:, None], l2[:, None], l3[:, None], (cx + 1j * cy)[:, None],
                                                   u[:, None], w[:, None], phi, branch[:, None])
    # members that assemble nowhere, everywhere and over part of the turn are all in the family
    assert (~assembled).all(axis=1).any() and assembled.all(axis=1).any() and (~assembled).any(axis=1).sum() > 5
    # the masks agree except at positions within round-off of a limit of assembly
    reach = np.abs((cx + 1j * cy)[:, None] - l1[:, None] * np.exp(1j * phi))
    near_limit = (np.minimum(np.abs(reach - (l2 + l3)[:, None]), np.abs(reach - np.abs(l2 - l3)[:, None])) < 1e-9)
    assert np.array_equal(curves.assembled | near_limit, assembled | near_limit)
    both = curves.assembled & assembled
    assert np.allclose(curves.point[both], expected[both], rtol=0, atol=1e-9)
    assert np.isnan(curves.point[~curves.assembled]).all() and np.isfinite(curves.point[curves.assembled]).all()


def test_coupler_curves_broadcast_numbers_and_arrays():
    phi = np.radians(np.arange(0, 360, 30))
    curves = coupler_curves(crank=[1.0, 1.2], coupler=3.5, rocker=3.0, frame_x=4.0, frame_y=0.0, along=1.75,
                            left=1.0, phi=phi)
    # expected: the cosine law for each crank length
    for k, l1 in enumerate((1.0, 1.2)):
        expected, assembled = cosine_law_coupler_point(l1, 3.5, 3.0, 4.0, 1.75, 1.0, phi, 1)
        assert assembled.all() and np.allclose(curves.point[k], expected, atol=1e-12)
    one = coupler_curves(1.0, 3.5, 3.0, 4.0, 0.0, 1.75, 1.0, phi, -1)
    assert one.point.shape == (12,)


@pytest.mark.parametrize("change, name", [
    ({"crank": [1.0, -1.0]}, "crank"),
    ({"rocker": 0.0}, "rocker"),
    ({"coupler": [3.5, np.nan]}, "coupler"),
    ({"along": "1"}, "along"),
    ({"branch": 0}, "branch"),
    ({"branch": [1, 2]}, "branch"),
    ({"frame_x": [1.0, 2.0, 3.0]}, "crank, coupler"),
    ({"phi": np.zeros((2, 3))}, "phi"),
    ({"phi": [0.0, np.inf]}, "phi"),
])
def test_coupler_curves_refuse_bad_input_by_name(change, name):
    arguments = dict(crank=[1.0, 1.2], coupler=3.5, rocker=3.0, frame_x=4.0, frame_y=0.0, along=1.75, left=1.0,
                     phi=[0.0, 1.0])
    arguments.update(change)
    with pytest.raises(InvalidParameterError, match=name):
        coupler_curves(**arguments)


def test_target_checks():
    square = [(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 1.2), (0, 0)]
    # the last point repeats the first: a closed curve drops it
    assert len(require_target(square, closed=True)) == 5
    assert len(require_target(square, closed=False)) == 6
    assert target_size(require_target(square)) == pytest.approx(math.hypot(1.0, 1.2))   # bounding box 1 × 1.2
    with pytest.raises(InvalidParameterError, match="at least 5 distinct points"):
        require_target([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0), (1, 0)], name="t.csv")
    with pytest.raises(InvalidParameterError, match="not all on one straight line"):
        require_target([(k, 2 * k + 1) for k in range(8)])
    with pytest.raises(InvalidParameterError, match="finite"):
        require_target([(0, 0), (1, 0), (1, np.nan), (0, 1), (0.5, 1.2)])
    with pytest.raises(InvalidParameterError, match="shape"):
        require_target([[0, 1, 2]] * 6)


def four_bar_path(rng, closed):
    """A random four-bar whose crank turns fully, placed anywhere, and its coupler point's path."""
    while True:
        l1, l2, l3 = rng.uniform(0.2, 3.0, 3)
        c = complex(*rng.uniform(-2.0, 2.0, 2))
        if abs(abs(c) - l1) > abs(l2 - l3) + 0.05 and abs(c) + l1 < l2 + l3 - 0.05:
            break
    u, w = rng.uniform(-1.0, 2.0) * l2, rng.uniform(-1.0, 1.0) * l2
    branch = int(rng.choice([-1, 1]))
    offset = complex(*rng.uniform(-5.0, 5.0, 2))

    def path(phi):
        return cosine_law_coupler_point(l1, l2, l3, c, u, w, phi, branch)[0] + offset
    return path


def linkage_path(fit, phi):
    """P over the crank angles, from the linkage file the fit writes, solved by the general linkage solver."""
    linkage = linkage_from_dict(tomllib.loads(fit.linkage_text()), "fit")
    return linkage.solve(phi, omega=1.0, order=0).point("P").value


def distances(points, polyline):
    """From each point to the nearest vertex of a dense polyline (an upper bound of the distance to it)."""
    return np.min(np.abs(points[:, None] - polyline[None, :]), axis=1)


@pytest.mark.parametrize("seed", [11, 12])
def test_fit_of_a_closed_path_that_a_four_bar_traces(seed):
    path = four_bar_path(np.random.default_rng(seed), closed=True)
    target = path(np.linspace(0.2, 0.2 + 2 * np.pi, 37, endpoint=False))
    fit = fit_path(np.stack([target.real, target.imag], axis=1), closed=True)
    assert fit.good and fit.closed and fit.in_order
    # expected: the original curve at 400 crank angles the fit never saw, against the written linkage's path
    # (general linkage solver at 0.02° steps); size by its definition, the bounding box's diagonal
    check = path(np.linspace(0.0, 2 * np.pi, 400, endpoint=False) + 0.0123)
    solved = linkage_path(fit, np.radians(np.arange(0.0, 360.0, 0.02)))
    size = math.hypot(np.ptp(target.real), np.ptp(target.imag))
    assert np.sqrt(np.mean(distances(check, solved) ** 2)) <= 0.01 * size
    # and the whole path lies along the curve: no extra loop
    assert np.sqrt(np.mean(distances(solved[::20], check) ** 2)) <= 0.01 * size
    assert fit.rms <= 0.01 * fit.size and fit.size == pytest.approx(size)


def test_fit_of_an_open_path_that_a_four_bar_traces():
    path = four_bar_path(np.random.default_rng(21), closed=False)
    target = path(np.linspace(0.5, 2.6, 30))
    fit = fit_path(target, closed=False)
    assert fit.good and fit.in_order and not fit.closed
    check = path(np.linspace(0.52, 2.58, 300))          # the stretch, at angles the fit never saw
    solved = linkage_path(fit, np.radians(np.arange(0.0, 360.0, 0.02)))
    size = math.hypot(np.ptp(target.real), np.ptp(target.imag))
    assert np.sqrt(np.mean(distances(check, solved) ** 2)) <= 0.01 * size


def test_fit_with_fixed_pivots_and_constraints():
    # a crank-rocker with pivots O = (0.1, 0.2), C = (0.5, 0.15); L1 0.08, L2 0.35, L3 0.3: crank shortest and
    # 0.08 + 0.35 < 0.3 + |OC| (|OC| = 0.403): Grashof, crank-rocker
    o, c = 0.1 + 0.2j, 0.5 + 0.15j
    phi = np.linspace(0.0, 2 * np.pi, 41, endpoint=False)
    target = o + cosine_law_coupler_point(0.08, 0.35, 0.3, c - o, 0.2, 0.1, phi, 1)[0]
    fit = fit_path(target, pivots=(o, c), crank_rocker=True, min_transmission=math.radians(20.0))
    assert fit.pivot == o and fit.frame == c
    assert fit.good
    # the constraints, checked on the written linkage solved over a turn: the crank is the shortest link and
    # turns fully (every position assembles), and the transmission angle (at B, between BA and BC) stays
    # within 20°…160°
    linkage = linkage_from_dict(tomllib.loads(fit.linkage_text()), "fit")
    solution = linkage.solve(np.radians(np.arange(0.0, 360.0, 0.5)), omega=1.0, order=0)
    a, b = solution.point("A").value, solution.point("B").value
    mu = np.abs(np.angle((a - b) / (c - b)))
    assert np.degrees(mu.min()) >= 20.0 - 1e-6 and np.degrees(mu.max()) <= 160.0 + 1e-6
    assert fit.crank < min(fit.coupler, fit.rocker, abs(c - o))


def test_a_path_no_four_bar_traces_is_reported_poor():
    # a square: its corners are points of infinite curvature, which a coupler curve (analytic) cannot have
    corners = np.array([0, 1, 1 + 1j, 1j, 0])
    target = np.concatenate([corners[k] + np.linspace(0, 1, 12, endpoint=False) * (corners[k + 1] - corners[k])
                             for k in range(4)])
    fit = fit_path(target)
    assert not fit.good and fit.relative_rms > 0.01


def test_the_written_file_loads(tmp_path):
    path = four_bar_path(np.random.default_rng(3), closed=True)
    fit = fit_path(path(np.linspace(0.0, 2 * np.pi, 30, endpoint=False)))
    file = tmp_path / "fit.toml"
    file.write_text(fit.linkage_text(), encoding="utf-8")
    linkage = load_linkage(file)
    phi = np.radians(np.arange(0.0, 360.0, 10.0))
    # the file's P against the fit's own geometry by the cosine law (O, C, lengths, u, w, branch)
    expected = fit.pivot + cosine_law_coupler_point(fit.crank, fit.coupler, fit.rocker, fit.frame - fit.pivot,
                                                    fit.along, fit.left, phi, fit.branch)[0]
    assert np.allclose(linkage.solve(phi, omega=1.0, order=0).point("P").value, expected, atol=1e-9 * fit.size)
    assert np.allclose(fit.path(phi), expected, atol=1e-12 * fit.size)


def crossings(points):
    """How many pairs of non-adjacent segments of a closed polyline cross (by the signs of cross products)."""
    a, b = points, np.roll(points, -1)
    count = 0
    for i in range(len(points)):
        for j in range(i + 2, len(points) - (1 if i == 0 else 0)):
            def side(p, q, r):
                return np.sign(((q - p) * np.conj(r - p)).imag)
            if side(a[i], b[i], a[j]) != side(a[i], b[i], b[j]) and side(a[j], b[j], a[i]) != side(a[j], b[j], b[i]):
                count += 1
    return count


def test_fit_of_a_figure_eight():
    # a figure-eight coupler curve: the first seeded random four-bar whose path crosses itself exactly once
    rng = np.random.default_rng(2024)
    while True:
        path = four_bar_path(rng, closed=True)
        if crossings(path(np.linspace(0.0, 2 * np.pi, 120, endpoint=False))) == 1:
            break
    target = path(np.linspace(0.1, 0.1 + 2 * np.pi, 45, endpoint=False))
    fit = fit_path(target)
    assert fit.good and fit.in_order
    check = path(np.linspace(0.0, 2 * np.pi, 400, endpoint=False) + 0.0077)
    solved = linkage_path(fit, np.radians(np.arange(0.0, 360.0, 0.02)))
    size = math.hypot(np.ptp(target.real), np.ptp(target.imag))
    assert np.sqrt(np.mean(distances(check, solved) ** 2)) <= 0.01 * size
    assert crossings(solved[::60]) == 1                  # the fit crosses itself once too: a figure eight
