"""Plans and instant centres of any linkage of class II groups (mechanisms.analysis.plans).

The plans are constructed from the joints' positions and the crank's motion only, group by group, as on
paper. Every expected value here is independent of that construction: the linkage's own solution (the
closed-form blocks of layer 2 differentiated analytically, ``Linkage.solve``) for velocities,
accelerations and angular rates, and the plane-motion formula v(X) = v_P + iω(X − P) on that solution
for the instant centres.
"""

import dataclasses
import itertools
import math

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import plans
from mechanisms.core.errors import InvalidParameterError
from mechanisms.linkages.groups import PRP, RPP, RPR, RRP, RRR, Crank, Line, LinkPoint, Triad
from mechanisms.linkages.linkage_file import example_files

ANGLES_DEG = (10.0, 75.0, 140.0, 205.0, 290.0)
OMEGA, ALPHA = 7.0, -3.0


def _assembled(linkage, angles_deg=ANGLES_DEG):
    """The crank angles (rad) of ``angles_deg`` at which the linkage assembles, away from the interval ends."""
    phi = np.radians(np.asarray(angles_deg))
    inside = [p for p in phi if any(lo + 0.05 < (p - lo) % (2 * math.pi) + lo < hi - 0.05
                                    for lo, hi in linkage.assembly_intervals())]
    assert inside, "no test angle inside the assembly intervals"
    return np.array(inside)


# --- linkages with the groups the shipped files do not have --------------------------------------------

def guide_on_crank():
    """RRP on a moving guide: the rod C → B ends in a block B on the line along the crank (O → A)."""
    return mech.Linkage({"O": 0j, "C": 0.1 + 0.05j},
                        [Crank("O", "A", length=0.1),
                         RRP("B", "C", "rod", "block", 0.0, 0.3, 1, 0j, "crank")], name="guide on the crank")


def crossing_blocks():
    """PRP: a block on the crank's line through A across the crank, hinged to a block on the fixed x axis."""
    return mech.Linkage({"O": 0j},
                        [Crank("O", "A", length=0.1),
                         PRP("J", Line("crank", 0.1 + 0j, math.pi / 2), Line("frame", 0j, 0.0), "first", "second")],
                        name="crossing blocks")


def yoke_on_rocker():
    """RPP on a moving guide: a four-bar whose rocker C → B carries the guide of a yoke; the block at A."""
    return mech.Linkage({"O": 0j, "C": 0.4 + 0.05j},
                        [Crank("O", "A", length=0.1), RRR("B", "A", "C", "coupler", "rocker", 0.35, 0.3, 1),
                         RPP("Y", "A", Line("rocker", 0j, 0.0), math.radians(80.0), "block", "yoke")],
                        name="yoke on a rocker")


def lever_on_moving_pivot():
    """RPR with a moving pivot: a lever about the rocker's point E, slotted through a block on the crank pin A;
    its point D drives a slider on a fixed guide (RRP); and a four-bar written from the fixed pivot (C, A)."""
    return mech.Linkage({"O": 0j, "C": 0.4 + 0.05j},
                        [Crank("O", "A", length=0.1), RRR("B", "C", "A", "rocker", "coupler", 0.3, 0.35, -1),
                         LinkPoint("E", "rocker", 0.15, 0.1),
                         RPR("A", "E", "lever", "block", "D", 0.5),
                         RRP("H", "D", "rod", "ram", 0.0, 0.3, 1, -0.05j)], name="lever on a moving pivot")


def triad():
    a, g1, g2 = 0.1 + 0j, 0.5 + 0j, 0.3 + 0.5j
    d, e, f = 0.2 + 0.3j, 0.4 + 0.35j, 0.35 + 0.2j
    bars = (("A", "D", abs(a - d)), ("G1", "F", abs(g1 - f)), ("G2", "E", abs(g2 - e)),
            ("D", "E", abs(d - e)), ("E", "F", abs(e - f)), ("D", "F", abs(d - f)))
    return mech.Linkage({"O": 0, "G1": g1, "G2": g2},
                        [Crank("O", "A", length=0.1), Triad(("D", "E", "F"), bars, (d, e, f))], name="triad")


BUILT = {"guide on the crank": guide_on_crank, "crossing blocks": crossing_blocks,
         "yoke on a rocker": yoke_on_rocker, "lever on a moving pivot": lever_on_moving_pivot}


def _linkages():
    return [pytest.param(lambda name=name: mech.load_linkage(name), id=name) for name in example_files()] + [
        pytest.param(make, id=name) for name, make in BUILT.items()]


# --- the plans equal the solution ---------------------------------------------------------------------------

@pytest.mark.parametrize("make", _linkages())
def test_plans_of_every_linkage_equal_its_solution(make):
    linkage = make()
    phi = _assembled(linkage)
    solution = linkage.solve(phi, OMEGA, ALPHA)
    for k in range(len(phi)):
        v = plans.velocity_plan(linkage, solution, k)
        a = plans.acceleration_plan(linkage, solution, k, velocity=v)
        speeds = max(abs(solution.point(n).velocity[k]) for n in solution.point_names)
        accelerations = max(abs(solution.point(n).acceleration[k]) for n in solution.point_names)
        for name in solution.point_names:      # every joint is a vertex of both plans
            assert abs(v.of(name) - solution.point(name).velocity[k]) <= 1e-9 * speeds, name
            assert abs(a.of(name) - solution.point(name).acceleration[k]) <= 1e-9 * accelerations, name
        rate_scale = max(abs(solution.angle(n).omega[k]) for n in solution.angle_names)
        epsilon_scale = max(abs(solution.angle(n).alpha[k]) for n in solution.angle_names)
        for name in solution.angle_names:      # every turning link's rates, read off the plans
            assert v.rates[name] == pytest.approx(solution.angle(name).omega[k], abs=1e-9 * rate_scale), name
            assert a.rates[name] == pytest.approx(solution.angle(name).alpha[k], abs=1e-9 * epsilon_scale), name
        for name in set(v.rates) - set(solution.angle_names):    # a block on a fixed guide translates
            assert v.rates[name] == 0.0 and a.rates[name] == 0.0, name
        assert v.closure() <= 1e-12 * speeds and a.closure() <= 1e-12 * accelerations


def test_a_six_bar_dyad_of_two_moving_joints_is_drawn_from_both():
    # Watt's F: v_F = v_E + v_FE = v_D + v_FD with D fixed; Stephenson's E is on the coupler: both known
    linkage = mech.load_linkage("jansen")       # E from D (upper triangle) and F (link k): both move
    solution = linkage.solve(np.radians([75.0]), OMEGA, ALPHA)
    v = plans.velocity_plan(linkage, solution)
    assert (("v_D", "v_ED"), ("v_F", "v_EF")) in v.equations
    assert v.vector("v_EF").tail == "f" and v.vector("v_ED").tail == "d"
    # v_ED ⊥ DE and v_EF ⊥ FE, as drawn
    where = v.positions
    assert abs(v.component("v_ED", where["E"] - where["D"])) < 1e-12
    assert abs(v.component("v_EF", where["E"] - where["F"])) < 1e-12


def test_a_guide_on_a_moving_link_has_its_coriolis_component():
    linkage = guide_on_crank()
    solution = linkage.solve(np.radians([40.0]), OMEGA, ALPHA)
    v = plans.velocity_plan(linkage, solution)
    a = plans.acceleration_plan(linkage, solution, velocity=v)
    # the block's sliding along the crank: v_BB1 = v_B − iω₁B (B1 the crank's point under B), by hand
    b = solution.point("B")
    sliding = b.velocity[0] - 1j * OMEGA * b.value[0]
    assert v.value("v_BB1") == pytest.approx(sliding, abs=1e-12)
    assert a.value("a^k_BB1") == pytest.approx(2j * OMEGA * sliding, abs=1e-10)
    assert a.vector("a^k_BB1").kind == "coriolis"


def test_a_class_three_group_is_refused_by_name():
    linkage = triad()
    solution = linkage.solve(np.radians([0.0]), 1.0)
    with pytest.raises(plans.PlanError, match="group D, E, F .*class III"):
        plans.velocity_plan(linkage, solution)


def test_a_link_point_on_a_block_and_extra_points_are_refused_cleanly():
    linkage = mech.load_linkage("shaper")
    solution = linkage.solve(np.radians([30.0]), OMEGA)
    with pytest.raises(InvalidParameterError, match="ram"):
        plans.velocity_plan(linkage, solution, points={"S": ("ram", 0.1, 0.0)})
    with pytest.raises(InvalidParameterError, match="index"):
        plans.velocity_plan(linkage, solution, index=3)


def test_the_file_twin_of_a_four_bar_gives_the_named_plans_and_centres():
    named = mech.FourBar(crank=0.1, coupler=0.35, rocker=0.3, frame=(0.4, 0.05), branch=1)
    twin = mech.Linkage({"O": 0j, "C": 0.4 + 0.05j},
                        [Crank("O", "A", length=0.1), RRR("B", "A", "C", "coupler", "rocker", 0.35, 0.3, 1)])
    phi = np.radians([35.0])
    s1, s2 = named.solve(phi, OMEGA, ALPHA), twin.solve(phi, OMEGA, ALPHA)
    for build in (plans.velocity_plan, plans.acceleration_plan):
        p1, p2 = build(named, s1), build(twin, s2)
        assert [x.name for x in p1.vectors] == [x.name for x in p2.vectors]
        for x, y in zip(p1.vectors, p2.vectors):
            assert x.value == pytest.approx(y.value, abs=1e-12 * max(abs(z.value) for z in p1.vectors))
    c1, c2 = plans.instant_centres(named, s1), plans.instant_centres(twin, s2)
    assert c1.pairs == c2.pairs and c1.lines == c2.lines
    assert all(c1[p] == pytest.approx(c2[p], abs=1e-12) for p in c1.finite)


# --- instant centres -------------------------------------------------------------------------------------

def _field(linkage, solution, k):
    """Each link's velocity field from the solution: link → (a joint's position, its velocity, ω)."""
    fields = {"frame": (0j, 0j, 0.0)}
    for link, joints in linkage.link_joints().items():
        if link == "frame":
            continue
        joint = joints[0]
        omega = float(solution.angle(link).omega[k]) if link in solution.angle_names else 0.0
        fields[link] = (complex(solution.point(joint).value[k]), complex(solution.point(joint).velocity[k]), omega)
    return fields


def _centre_cases():
    """(linkage, Kennedy's lines used?): every linkage both ways; the class III group by Kennedy's lines only
    (it has no plan, so no velocities to fall back on)."""
    cases = []
    for case in _linkages():
        make, = case.values
        cases += [pytest.param(make, True, id=f"{case.id}-Kennedy"),
                  pytest.param(make, False, id=f"{case.id}-velocities only")]
    return cases + [pytest.param(triad, True, id="class III-Kennedy")]


@pytest.mark.parametrize("make, kennedy", _centre_cases())
def test_instant_centres_of_every_linkage_obey_the_velocities(make, kennedy, monkeypatch):
    linkage = make()
    if not kennedy:     # every centre that is not a pair's from the velocities (ω₁ = 1 plan on the positions)
        monkeypatch.setattr(plans, "_kennedy", lambda lines, size: None)
    # the class III group near its guess (φ = 0), where Newton's continuation starts; the others at the test angles
    phi = np.radians([-20.0, 0.0, 10.0]) if make is triad else _assembled(linkage)
    solution = linkage.solve(phi, OMEGA, ALPHA)
    size = max(abs(p - q) for p in linkage.frame.values() for q in linkage.frame.values()) + max(
        linkage.preserved_distances().values())
    for k in range(len(phi)):
        centres = plans.instant_centres(linkage, solution, k)
        n = len(centres.links)
        assert len(centres.pairs) == n * (n - 1) // 2
        fields = _field(linkage, solution, k)
        speed = max(abs(f[1]) for f in fields.values()) + 1e-300
        by_number = {number: link for link, number in centres.links.items()}
        for i, j in centres.pairs:
            (pi, vi, wi), (pj, vj, wj) = fields[by_number[i]], fields[by_number[j]]

            def relative(x):       # v_i(X) − v_j(X) by the plane-motion formula
                return (vi + 1j * wi * (x - pi)) - (vj + 1j * wj * (x - pj))
            if centres.is_finite(i, j):
                # the centre is the point of equal velocities (for P_i0: v(X) = iω_i(X − P_i0) at every X)
                assert abs(relative(centres[(i, j)])) <= 1e-9 * speed, (by_number[i], by_number[j])
            else:
                # at infinity: the relative motion is a translation across the centre's direction
                direction = centres.infinite[(i, j)]
                assert abs(wi - wj) <= 1e-9 * OMEGA, (by_number[i], by_number[j])
                assert abs((relative(0j) * direction.conjugate()).real) <= 1e-9 * speed
        for link, joints in linkage.link_joints().items():      # the absolute centres, joint by joint
            number = centres.links[link]
            if link == "frame" or not centres.is_finite(0, number):
                continue
            centre, omega = centres[(0, number)], fields[link][2]
            for joint in joints:
                velocity = complex(solution.point(joint).velocity[k])
                expected = 1j * omega * (complex(solution.point(joint).value[k]) - centre)
                assert abs(velocity - expected) <= 1e-9 * speed + 1e-9 * abs(omega) * size, (link, joint)
        assert plans.kennedy_deviation(centres) < 1e-9
        assert bool(centres.lines) == kennedy or len(centres.pairs) == len(centres.joints)


def test_six_bar_centres_come_from_kennedy_and_the_rest_from_the_velocities():
    linkage = mech.load_linkage("watt-six-bar")
    solution = linkage.solve(np.radians([75.0]), order=0)
    centres = plans.instant_centres(linkage, solution)
    assert len(centres.pairs) == 15
    assert len(centres.joints) == 7          # the seven hinges
    # each centre found by Kennedy's theorem lies on both of its lines
    for target, ways in centres.lines.items():
        for first, second in ways:
            p, q, r = centres[first], centres[second], centres[target]
            assert abs(((q - p).conjugate() * (r - p)).imag) <= 1e-9 * abs(q - p) * max(abs(r - p), 1.0)


def test_instant_centres_of_the_shaper_class_are_those_of_its_linkage_file():
    # the class and the shipped file describe the same machine with the same link names (block, lever,
    # rod, ram); the file's centres are checked against the velocities in the tests above
    shaper = mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22)
    linkage = mech.load_linkage("shaper")
    phi = np.radians([30.0])
    ours = plans.instant_centres(shaper, shaper.solve(phi, order=1))
    theirs = plans.instant_centres(linkage, linkage.solve(phi, order=1))
    assert ours.links == theirs.links and len(ours.links) == 6
    assert ours.pairs == theirs.pairs and len(ours.pairs) == 15
    for pair in theirs.pairs:
        assert ours.is_finite(*pair) == theirs.is_finite(*pair)
        if theirs.is_finite(*pair):
            assert abs(ours[pair] - theirs[pair]) <= 1e-12
        else:
            assert abs(ours.infinite[pair] - theirs.infinite[pair]) <= 1e-12


def test_instant_centres_refuse_a_mechanism_naming_a_link_twice():
    class TwoSliders(mech.Shaper):          # the block and the ram both called "slider"
        def groups(self):
            crank, block, end, rod = super().groups()
            return (crank, dataclasses.replace(block, slider="slider"), end,
                    dataclasses.replace(rod, slider="slider"))

    shaper = TwoSliders(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22)
    solution = shaper.solve(np.radians([30.0]), order=0)
    with pytest.raises(InvalidParameterError, match="slider"):
        plans.instant_centres(shaper, solution)


# --- the report of both plans ---------------------------------------------------------------------------

def test_plan_report_gives_every_vector_with_its_length_at_the_scale():
    linkage = mech.load_linkage("watt-six-bar")
    report = plans.plan_report(linkage, math.radians(30.0), 10.0, 2.0, scale_v=0.02, scale_a=0.5)
    names = [(row.quantity, row.name) for row in report.rows]
    assert ("velocity", "v_A") in names and ("acceleration", "a^t_FD") in names
    first = report.rows[0]
    # by hand: v_A = ω₁ l_OA = 10 × 0.1 = 1 m/s, at 30° + 90° = 120°, drawn 1 / 0.02 = 50 mm from p to a
    assert (first.name, first.segment, first.unit) == ("v_A", "pa", "m/s")
    assert first.magnitude == pytest.approx(1.0) and first.length_mm == pytest.approx(50.0)
    assert first.direction_deg == pytest.approx(120.0)
    accel = next(row for row in report.rows if row.name == "a_A")
    # by hand: a_A = (iε₁ − ω₁²)(A − O) = 0.1 (2i − 100) e^{i30°}: |a_A| = 0.1 √(100² + 2²)
    assert accel.magnitude == pytest.approx(0.1 * math.hypot(100.0, 2.0))
    assert accel.length_mm == pytest.approx(accel.magnitude / 0.5)
    assert report.as_dict()["scale_a"] == 0.5 and len(report.as_dict()["vectors"]) == len(report.rows)


@pytest.mark.parametrize("kwargs, name", [({"phi": math.nan}, "phi"), ({"omega": "fast"}, "omega"),
                                          ({"scale_v": 0.0}, "scale_v"), ({"scale_a": -1.0}, "scale_a")])
def test_plan_report_names_a_bad_argument(kwargs, name):
    arguments = {"phi": 0.5, "omega": 10.0} | kwargs
    with pytest.raises(InvalidParameterError, match=name):
        plans.plan_report(mech.load_linkage("shaper"), **arguments)
