"""Composed linkages (chapter 7): every book mechanism composed from its groups against its hand-written
class, the generic solver on composed six-bars and class III groups, random linkages (hypothesis)
against the generic solver in extended precision, and the structure of the shipped files."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import mechanisms as mech
from mechanisms.analysis.structure import mobility, structure_of
from mechanisms.core.errors import AssemblyError, SingularPositionWarning, StructureError
from mechanisms.linkages.composed import Linkage
from mechanisms.linkages.groups import PRP, RPP, RPR, RRP, RRR, Crank, Line, LinkPoint, Triad
from mechanisms.linkages.linkage_file import example_files, linkage_from_dict, load_linkage
from mechanisms.verify import checks
from mechanisms.verify.newton import newton_steps

PHI = np.radians(np.arange(0.0, 360.0, 7.5))


def same_motion(a, b, tol: float) -> None:
    """Two motions agree in value, velocity and acceleration to ``tol`` times their scale."""
    for x, y in zip(a.derivatives(), b.derivatives()):
        scale = 1.0 + float(np.max(np.abs(x)))
        assert np.max(np.abs(np.asarray(x) - np.asarray(y))) <= tol * scale


def angles_agree(a, b, tol: float) -> None:
    assert np.max(np.abs(np.angle(np.exp(1j * (a.value - b.value))))) <= tol
    same_motion(mech.AngleMotion(0 * a.value, a.velocity, a.acceleration),
                mech.AngleMotion(0 * b.value, b.velocity, b.acceleration), tol)


# --- the book's mechanisms, composed -----------------------------------------------------------------------

def composed_pairs():
    """(class instance, the same mechanism composed, names to compare: links, points, sliders)."""
    yield (mech.FourBar(crank=1.0, coupler=3.5, rocker=3.0, frame=(4.0, 0.0), branch=1),
           Linkage({"O": 0, "C": 4}, [Crank("O", "A", length=1.0),
                                       RRR("B", "A", "C", "coupler", "rocker", 3.5, 3.0, 1)]),
           (["coupler", "rocker"], ["A", "B"], []))
    yield (mech.FourBar(crank=0.1, coupler=0.35, rocker=0.3, frame=(0.4, 0.05), branch=-1),
           Linkage({"O": 0, "C": 0.4 + 0.05j}, [Crank("O", "A", length=0.1),
                                                 RRR("B", "A", "C", "coupler", "rocker", 0.35, 0.3, -1)]),
           (["coupler", "rocker"], ["A", "B"], []))
    for branch in (1, -1):
        yield (mech.CrankSlider(crank=1.0, rod=3.5, offset=0.5, branch=branch),
               Linkage({"O": 0}, [Crank("O", "A", length=1.0),
                                  RRP("B", "A", "coupler", "B", 0.0, 3.5, branch, 0.5j)]),
               (["coupler"], ["A", "B"], ["B"]))
    yield (mech.LambdaMechanism(crank=2.0, half_coupler=6.5, ground=5.0),
           Linkage({"O": 0, "C": -5}, [Crank("O", "A", length=2.0),
                                       RRR("B", "A", "C", "coupler", "rocker", 6.5, 6.5, -1),
                                       LinkPoint("P", "coupler", 13.0)]),
           (["coupler", "rocker"], ["A", "B", "P"], []))
    yield (mech.SlottedLever(crank=1.0, pivot=(0.0, 2.0)),
           Linkage({"O": 0, "C": 2j}, [Crank("O", "A", length=1.0),
                                       RPR("A", "C", "lever", "A", joint="B", length=3.0)]),
           (["lever"], ["A", "B"], ["A"]))
    yield (mech.SlottedLever(crank=2.0, pivot=(0.5, 0.3)),         # a rotating lever
           Linkage({"O": 0, "C": 0.5 + 0.3j}, [Crank("O", "A", length=2.0), RPR("A", "C", "lever", "A")]),
           (["lever"], ["A"], ["A"]))
    yield (mech.Shaper.example(), load_linkage("shaper"),
           (["lever", "rod"], ["A", "B", "G"], [("A", "block"), ("G", "ram")]))
    yield (mech.RockerInBlock.example(),
           Linkage({"O": 0, "C": 4j}, [Crank("O", "A", length=2.0), RPR("C", "A", "rocker", "C")]),
           (["rocker"], ["A"], ["C"]))
    m = mech.SlottedRockers.example()
    yield (m, Linkage({"O": 0, "C": complex(*m.pivot), "O2": complex(*m.rocker_pivot)},
                      [Crank("O", "A", length=m.crank), RPR("A", "C", "lever", "A"),
                       RRP("D", "O2", "rocker", "D", 0.0, m.rocker, m.branch, 0j, "lever")]),
           (["lever", "rocker"], ["A", "D"], ["A", "D"]))
    m = mech.SliderOnCoupler.example()
    yield (m, Linkage({"O": 0}, [Crank("O", "A", length=m.crank),
                                 RRP("B", "A", "coupler", "B", 0.0, m.rod, 1, 1j * m.offset),
                                 PRP("E", Line("coupler", 0j, 0.0), Line("frame", complex(*m.guide_point), m.guide_angle),
                                     "E_coupler", "E")]),
           (["coupler"], ["A", "B", "E"], ["B", "E", "E_coupler"]))


@pytest.mark.parametrize("pair", list(composed_pairs()), ids=lambda p: repr(p[0])[:40])
def test_every_book_mechanism_composed_agrees_with_its_class(pair):
    cls_mechanism, composed, (links, points, sliders) = pair
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPositionWarning)
        phi = PHI + 0.013      # off the exact singular positions
        a, b = cls_mechanism.solve(phi, 2.5, -0.7), composed.solve(phi, 2.5, -0.7)
    for name in links:
        angles_agree(a.angle(name), b.angle(name), 1e-13)
    for name in points:
        same_motion(a.point(name), b.point(name), 1e-13)
    for name in sliders:
        ours, theirs = name if isinstance(name, tuple) else (name, name)
        same_motion(a.slider(ours), b.slider(theirs), 1e-13)


def test_composed_four_bar_and_crank_slider_are_bit_identical_to_the_classes():
    """The same blocks in the same order: the same doubles, not just close ones (benchmark's 1e-14 claim)."""
    phi = np.linspace(0, 2 * np.pi, 100_001)
    pairs = list(composed_pairs())
    for cls_mechanism, composed, (links, points, _) in (pairs[0], pairs[2]):
        a, b = cls_mechanism.solve(phi, 3.0, 1.0), composed.solve(phi, 3.0, 1.0)
        for name in points:
            assert np.array_equal(a.point(name).acceleration, b.point(name).acceleration)
        for name in links:
            assert np.array_equal(a.angle(name).alpha, b.angle(name).alpha)


@pytest.mark.parametrize("name", example_files())
def test_shipped_files_pass_the_checks_of_the_analysis_sequence(name):
    linkage = load_linkage(name)
    phi = np.radians(np.arange(0.0, 360.0, 10.0)) + 0.01
    solution = linkage.solve(phi, 2.0, 0.5)
    scale = max(abs(v) for v in linkage.frame.values()) + max(linkage.preserved_distances().values())
    assert checks.constraint_residual(linkage, solution) < 1e-14 * scale * 10
    assert checks.distance_deviation(linkage, solution) < 1e-14 * scale * 10
    errors = checks.generic_errors(linkage, phi, 2.0, 0.5)
    assert errors[0] < 1e-13 * scale and errors[1] < 1e-12 * scale and errors[2] < 1e-11 * scale
    derivative = checks.derivative_errors(linkage, phi, 2.0)
    speeds = max(float(np.max(np.abs(solution.point(n).velocity))) for n in solution.point_names)
    assert max(v for v, _ in derivative.values()) < 1e-6 * (1 + speeds)


def test_composed_six_bar_matches_the_generic_solver_in_extended_precision():
    """Positions from the closed forms against Newton's method on the same constraints in long double."""
    linkage = load_linkage("watt-six-bar")
    phi = np.linspace(0.0, 2 * np.pi, 97)
    closed = linkage.solve(phi, order=0)
    q = np.array([c.value for c in linkage.coordinates(closed)], dtype=np.longdouble)
    reference = newton_steps(linkage.constraints, q, phi.astype(np.longdouble), 3)
    assert np.max(np.abs(linkage.constraints(list(reference), phi.astype(np.longdouble)))) < 1e-18
    error = np.abs(q - reference)            # angles, rad: the closed forms to a few units of round-off
    assert np.max(error) < 50 * np.finfo(float).eps


# --- class III ----------------------------------------------------------------------------------------

def triad_linkage(guess_shift: complex = 0.01) -> Linkage:
    a, g1, g2 = 0.1 + 0j, 0.5 + 0j, 0.3 + 0.5j
    d, e, f = 0.2 + 0.3j, 0.4 + 0.35j, 0.35 + 0.2j
    bars = (("A", "D", abs(a - d)), ("G1", "F", abs(g1 - f)), ("G2", "E", abs(g2 - e)),
            ("D", "E", abs(d - e)), ("E", "F", abs(e - f)), ("D", "F", abs(d - f)))
    return Linkage({"O": 0, "G1": g1, "G2": g2},
                   [Crank("O", "A", length=0.1), Triad(("D", "E", "F"), bars, (d + guess_shift, e, f))])


def test_class_three_group_is_found_by_newton_and_reported():
    linkage = triad_linkage()
    report = structure_of(linkage)
    assert report.mobility == 1 and report.mechanism_class == "III"
    assert "class III" in report.text() and "Newton" in report.text()
    phi = np.radians(np.arange(-120.0, 20.0, 5.0))
    solution = linkage.solve(phi, 1.5, 0.3)
    # the assembly at φ = 0 is the one the group was built from
    assert abs(linkage.solve([0.0], order=0).point("D").value[0] - (0.2 + 0.3j)) < 1e-14
    errors = checks.generic_errors(linkage, phi, 1.5, 0.3)
    assert errors[0] < 1e-13 and errors[1] < 1e-12 and errors[2] < 1e-10
    assert checks.distance_deviation(linkage, solution) < 1e-14


def test_class_three_group_says_where_it_assembles():
    linkage = triad_linkage()
    (low, high), = linkage.assembly_intervals()
    assert low < 0.0 < high < math.radians(30)
    with pytest.raises(AssemblyError, match="group D, E, F") as error:
        linkage.solve(np.radians([0.0, 40.0]))
    assert error.value.angles is not None and np.allclose(error.value.angles, np.radians([40.0]))


# --- structure ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("name, moving, pairs, kinds", [
    ("watt-six-bar", 5, 7, ["crank", "RRR", "point", "RRR"]),
    ("stephenson-six-bar", 5, 7, ["crank", "RRR", "point", "RRR"]),
    ("jansen", 7, 10, ["crank", "RRR", "RRR", "point", "RRR", "point"]),
    ("shaper", 5, 7, ["crank", "RPR", "RRP"]),
    ("beam-pump", 5, 7, ["crank", "RRR", "point", "RRP"]),
    ("scotch-yoke", 3, 4, ["crank", "RPP"]),
    ("format-example", 7, 10, ["crank", "RRR", "RPR", "point", "RRP"]),
])
def test_structure_of_the_shipped_files(name, moving, pairs, kinds):
    """n and p counted by hand from each file's drawing; W = 3n − 2p = 1 by the formula, independently."""
    report = structure_of(load_linkage(name))
    assert (report.moving_links, report.lower_pairs) == (moving, pairs)
    assert report.mobility == mobility(moving, pairs) == 1
    assert [g.kind for g in report.groups] == [{"point": "point"}.get(k, k) for k in kinds]


def test_jansen_has_two_ternary_links():
    links = load_linkage("jansen").link_joints()
    assert sorted(len(j) for name, j in links.items() if name != "frame") == [2, 2, 2, 2, 2, 3, 3]


# --- bad input ----------------------------------------------------------------------------------------

FOUR_BAR = {"name": "four-bar", "frame": {"O": [0, 0], "C": [4, 0]},
            "crank": {"pivot": "O", "pin": "A", "length": 1.0},
            "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [3.5, 3.0]}]}


def edited(**changes):
    import copy

    data = copy.deepcopy(FOUR_BAR)
    for key, value in changes.items():
        if value is None:
            data.pop(key)
        else:
            data[key] = value
    return data


@pytest.mark.parametrize("data, message", [
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "X"], "lengths": [3.5, 3.0]}]),
     r"joint 'X', which no group finds"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "E"], "lengths": [3.5, 3.0]},
                  {"type": "RRR", "joint": "E", "from": ["B", "C"], "lengths": [1.0, 1.0]}]),
     r"need each other \(a cycle\)"),
    (edited(dyad=[{"type": "RRR", "joint": "C", "from": ["A", "O"], "lengths": [3.5, 3.0]}]),
     r"joint 'C' is found twice"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [3.5, -3.0]}]),
     r"\[\[dyad\]\] #1 \('B'\): key 'lengths': must be a length > 0 m"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [3.5, 0.0]}]),
     r"key 'lengths': must be a length > 0 m"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"]}]), r"missing key 'lengths'"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"], "lenghts": [3.5, 3.0]}]),
     r"missing key 'lengths' \(and unknown 'lenghts': misspelt\?\)"),
    (edited(dyad=[{"type": "RRX", "joint": "B"}]), r"key 'type': must be one of RRR"),
    (edited(crank=None), r"missing \[crank\]"),
    (edited(frame=None), r"missing \[frame\]"),
    (edited(crank={"pivot": "O", "pin": "A", "length": True}), r"key 'length': must be a length > 0 m"),
    (edited(frame={"O": [0, 0], "C": "4,0"}), r"\[frame\]: key 'C': must be a point"),
    (edited(crank={"pivot": "Q", "pin": "A", "length": 1.0}), r"needs joint 'Q'"),
    (edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [3.5, 3.0], "branch": 0}]),
     r"key 'branch': must be \+1 or -1"),
    (edited(point=[{"name": "E", "link": ["O", "B"], "along": 1.0}]), r"not on one link"),
    (edited(point=[{"name": "E", "link": ["A", "B"]}]), r"give its place"),
    (edited(extra=1), r"unknown key 'extra'"),
])
def test_bad_files_get_an_error_naming_the_file_group_and_cause(data, message):
    with pytest.raises(StructureError, match=message) as error:
        linkage_from_dict(data, "my.toml")
    assert str(error.value).startswith("my.toml")


def test_a_group_with_too_few_bars_is_not_mobile_with_one_degree_of_freedom():
    linkage = triad_linkage()
    group = linkage.groups()[1]
    assert isinstance(group, Triad)
    with pytest.raises(StructureError, match=r"D, E, F.*W = 2.*6 bars, not 5"):
        Linkage(linkage.frame, [linkage.groups()[0], Triad(group.joints, group.bars[:5], group.guess)])


def test_two_cranks_are_refused():
    with pytest.raises(StructureError, match="one driving crank"):
        Linkage({"O": 0, "C": 4}, [Crank("O", "A", length=1.0), Crank("C", "B", "second", length=1.0)])
    with pytest.raises(StructureError, match="one table"):
        linkage_from_dict(edited(crank=[{"pivot": "O", "pin": "A", "length": 1.0}] * 2), "two.toml")


def test_a_linkage_that_does_not_assemble_everywhere_names_the_group_and_the_angles():
    data = edited(dyad=[{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [2.5, 1.0]}])
    linkage = linkage_from_dict(data, "short.toml")
    with pytest.raises(AssemblyError, match=r"RRR B \(from A, C\) cannot be assembled") as error:
        linkage.solve(np.radians([0.0, 90.0, 180.0]))
    # by hand: |AC|² = 1 + 16 − 8 cos φ exceeds (2.5 + 1)² where cos φ < 0.59375: at 90° and 180°
    assert np.allclose(error.value.angles, np.radians([90.0, 180.0]))
    (low, high), = linkage.assembly_intervals()
    assert low == pytest.approx(-math.acos(0.59375), abs=1e-10)
    assert high == pytest.approx(math.acos(0.59375), abs=1e-10)


def test_a_missing_file_and_a_broken_file(tmp_path):
    with pytest.raises(StructureError, match="no such file"):
        load_linkage(tmp_path / "none.toml")
    broken = tmp_path / "broken.toml"
    broken.write_text("name = [\n")
    with pytest.raises(StructureError, match="broken.toml: not a valid TOML file"):
        load_linkage(broken)


# --- random linkages against the generic solver ------------------------------------------------------------

coordinate = st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False)


@st.composite
def random_linkages(draw):
    """A crank, an RRR and a second group of a random kind, built around a random assembled pose at φ = 0,
    as a linkage file's contents."""
    crank = draw(st.floats(0.1, 0.5))
    c = complex(draw(coordinate), draw(coordinate)) + 2.0
    b = complex(draw(coordinate), draw(coordinate)) + 1.0 + 1.0j
    a = complex(crank, 0.0)
    side = 1 if ((c - a).conjugate() * (b - a)).imag > 0 else -1
    data = {"frame": {"O": [0.0, 0.0], "C": [c.real, c.imag]}, "crank": {"pivot": "O", "pin": "A", "length": crank},
            "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [abs(b - a), abs(b - c)],
                      "branch": side}],
            "point": [{"name": "E", "link": ["C", "B"], "along": draw(st.floats(0.2, 1.5)),
                       "left": draw(st.floats(-0.3, 0.3))}]}
    kind = draw(st.sampled_from(["RRR", "RRP", "RPR", "PRP", "RPP", "RRP-moving"]))
    h = complex(draw(coordinate), draw(coordinate)) * 0.5 + 3.0 + 1.0j     # where the new joint sits at φ = 0
    angle = draw(st.floats(-180.0, 180.0))
    # the new joint's position at φ = 0 is fixed by h through the choice of the guide or pivot
    e_guess = None
    if kind == "RRR":
        d = h + complex(draw(coordinate), draw(coordinate)) * 0.5 + 0.8
        data["frame"]["D"] = [d.real, d.imag]
        data["dyad"].append({"type": "RRR", "joint": "H", "from": ["E", "D"], "lengths": ["E-H", abs(h - d)],
                             "branch": "side"})
        e_guess = ("E", "D")
    elif kind == "RRP":
        data["dyad"].append({"type": "RRP", "joint": "H", "from": "E", "length": "E-H",
                             "guide": {"through": [h.real, h.imag], "angle_deg": angle}, "branch": "along"})
        e_guess = ("E", None)
    elif kind == "RRP-moving":
        data["dyad"].append({"type": "RRP", "joint": "H", "from": "O", "length": "O-H",
                             "guide": {"through": "B", "toward": "C", "angle_deg": angle}, "branch": "along"})
        e_guess = ("O", None)
    elif kind == "RPR":
        data["frame"]["D"] = [h.real, h.imag]
        data["dyad"].append({"type": "RPR", "block": "E", "pivot": "D", "joint": "H2", "length": 0.7})
    elif kind == "PRP":
        data["dyad"].append({"type": "PRP", "joint": "H",
                             "guides": [{"through": "C", "toward": "B", "angle_deg": angle},
                                        {"through": [h.real, h.imag], "angle_deg": angle + 60.0}]})
    else:
        data["dyad"].append({"type": "RPP", "joint": "H", "block": "E",
                             "guide": {"through": [h.real, h.imag], "angle_deg": angle},
                             "slot_angle_deg": draw(st.sampled_from([45.0, 90.0, 120.0]))})
    return data, e_guess, h


def _finish(data, e_guess, h):
    """Fill the lengths and branches that make the random group pass through h at φ = 0."""
    if e_guess is None:
        return data
    base = Linkage({k: complex(*v) for k, v in data["frame"].items()},
                   [Crank("O", "A", length=data["crank"]["length"]),
                    RRR("B", "A", "C", "AB", "CB", *data["dyad"][0]["lengths"], data["dyad"][0]["branch"]),
                    LinkPoint("E", "", data["point"][0]["along"], data["point"][0]["left"], axis=("C", "B"))])
    pose = base.solve([0.0], order=0)
    known = pose.point(e_guess[0]).value[0]
    dyad = data["dyad"][1]
    if dyad["type"] == "RRR":
        dyad["lengths"][0] = abs(h - known)
        d = pose.point("D").value[0]
        dyad["branch"] = 1 if ((d - known).conjugate() * (h - known)).imag > 0 else -1
    else:
        guide = dyad["guide"]
        if isinstance(guide["through"], str):      # the guide on the rod C -> B: through B
            b, c = pose.point("B").value[0], pose.point("C").value[0]
            direction = (c - b) / abs(c - b) * np.exp(1j * np.radians(guide["angle_deg"]))
            through = b
        else:
            through = complex(*guide["through"])
            direction = np.exp(1j * np.radians(guide["angle_deg"]))
        # put the joint on the guide where it is h's projection; the length follows
        target = through + ((h - through) * direction.conjugate()).real * direction
        dyad["length"] = abs(target - known)
        foot = through + ((known - through) * direction.conjugate()).real * direction
        dyad["branch"] = 1 if ((target - foot) * direction.conjugate()).real >= 0 else -1
    return data


@settings(max_examples=60, deadline=None)
@given(random_linkages())
def test_random_linkage_files_agree_with_the_generic_solver(case):
    data = _finish(*case)
    try:
        linkage = linkage_from_dict(data, "random.toml")
        phi = np.linspace(-0.05, 0.05, 5)
        with warnings.catch_warnings():
            warnings.simplefilter("error", SingularPositionWarning)
            solution = linkage.solve(phi, 1.3, 0.4)
    except (AssemblyError, SingularPositionWarning):
        assume(False)
        return
    # a well-conditioned pose: the generic solver's Jacobian is far from singular
    from mechanisms.verify.newton import jacobian

    q = np.array([c.value for c in linkage.coordinates(solution)])
    _, jac = jacobian(linkage.constraints, q, phi)
    condition = float(np.max(np.linalg.cond(jac)))
    assume(condition < 1e6)
    errors = checks.generic_errors(linkage, phi, 1.3, 0.4)
    tolerance = 1e-15 * condition * 100
    assert errors[0] < tolerance * 10
    assert errors[1] < tolerance * 100
    assert errors[2] < tolerance * 1000
    assert checks.distance_deviation(linkage, solution) < 1e-13


def test_energy_of_a_linkage_file_with_masses():
    """A crank-slider file with masses: its kinetic energy against ½ m v² + ½ J_S ω² summed by hand."""
    from mechanisms.analysis import energy

    data = {"frame": {"O": [0.0, 0.0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
            "dyad": [{"type": "RRP", "joint": "B", "from": "A", "length": 0.4,
                      "guide": {"through": [0.0, 0.0], "angle_deg": 0.0}, "links": ["rod", "B"]}],
            "mass": [{"body": "rod", "mass": 2.0, "along": 0.2, "inertia": 0.03},
                     {"body": "B", "mass": 1.5}]}
    linkage = linkage_from_dict(data, "masses.toml")
    masses = energy.linkage_masses(linkage)
    assert set(masses) == {"rod", "B"} and masses["rod"].inertia == 0.03
    phi = np.radians(np.arange(0.0, 360.0, 30.0)) + 0.1
    solution = linkage.solve(phi, 5.0)
    kinetic = energy.kinetic_energy(solution, masses).value
    centre = solution.point_on("rod", 0.2)
    rod = solution.angle("rod")
    by_hand = (0.5 * 2.0 * np.abs(centre.velocity) ** 2 + 0.5 * 0.03 * rod.omega**2
               + 0.5 * 1.5 * solution.slider("B").velocity ** 2)
    np.testing.assert_allclose(kinetic, by_hand, rtol=1e-13)
