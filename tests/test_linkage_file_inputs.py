"""Linkage files and composed linkages (issue 28, part 2): every input gets a right answer or the package's error.

Each expected value comes from an independent computation: integer arithmetic (``10**20 % 360``), an
intersection of two lines by hand in fractions, the generic Newton solver :func:`mechanisms.verify.solve_generic`
started from the file's own guess (not from the continuation under test), or an error's text.
"""

from __future__ import annotations

import math
import os
import tracemalloc
import warnings
from fractions import Fraction

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis.structure import structure_of
from mechanisms.core.angles import reduce_degrees
from mechanisms.core.errors import InvalidParameterError, MechanismError, StructureError
from mechanisms.linkages.linkage_file import linkage_from_dict, load_linkage
from mechanisms.verify import solve_generic

FOUR_BAR = """\
name = "four-bar"
[frame]
O = [0.0, 0.0]
C = [0.4, 0.0]
[crank]
pivot = "O"
pin = "A"
length = 0.1
[[dyad]]
type = "RRR"
joint = "B"
from = ["A", "C"]
lengths = [0.35, 0.30]
"""


def write(tmp_path, text: str, name: str = "linkage.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def refused(path, *words: str) -> str:
    """Load the file; it must be refused with a StructureError naming the file and each of ``words``."""
    with pytest.raises(StructureError) as caught:
        load_linkage(path)
    message = str(caught.value)
    assert str(path) in message, message
    for word in words:
        assert word in message, message
    return message


# --- reduce_degrees ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("degrees", [1e20, 2.0**70, -1e300, 1e9, 370.0, -190.0, 540.0, 180.0, -180.0, 0.0, 12.5])
def test_reduce_degrees_is_the_exact_remainder(degrees):
    # expected: the remainder of the double's exact value mod 360 in exact rational arithmetic, shifted
    # into (-180, 180]
    exact = Fraction(degrees) % 360
    if exact > 180:
        exact -= 360
    assert reduce_degrees(degrees) == float(exact)
    assert isinstance(reduce_degrees(degrees), float)


def test_reduce_degrees_of_an_array_and_of_a_huge_int():
    # 10**20 ≡ 280 (mod 360): 10**20 is divisible by 8 and ≡ 10 (mod 45); 280 ≡ −80 in (−180, 180]
    assert (10**20) % 360 == 280
    np.testing.assert_array_equal(reduce_degrees(np.array([[350.0, 370.0], [1e20, -180.0]])),
                                  [[-10.0, 10.0], [-80.0, 180.0]])
    assert reduce_degrees(10**20) == -80.0
    # an int is reduced as the integer it is, not as the double nearest it: 2**53 + 1 ≡ 33 (mod 360), by hand:
    # 2**53 ≡ 0 (mod 8) and 2**12 ≡ 1 (mod 45) so 2**53 = (2**12)**4·32 ≡ 32 (mod 45): 2**53 ≡ 32 (mod 360);
    # 10**k ≡ 10 (mod 45) for every k ≥ 1 (100 ≡ 10), so 10**400 ≡ 280 ≡ −80 like 10**20
    assert (2**53 + 1) % 360 == 33 and (10**400) % 360 == 280
    assert reduce_degrees(2**53 + 1) == 33.0 and reduce_degrees(10**400) == -80.0


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf"), "10", True, None, 1j, [1.0, "a"],
                                 np.array([1.0, np.nan])])
def test_reduce_degrees_refuses_what_is_not_a_finite_angle(bad):
    with pytest.raises(InvalidParameterError, match="slot_angle_deg"):
        reduce_degrees(bad, "slot_angle_deg")


# --- the items of the issue ---------------------------------------------------------------------------------

GUIDE_ON_THE_ROCKER = """
[[dyad]]
type = "RRP"
joint = "H"
from = "B"
length = 0.3
guide = {{ through = "C", toward = "{toward}" }}
"""


def test_a_guide_toward_its_own_joint_is_refused_at_load(tmp_path):
    path = write(tmp_path, FOUR_BAR + GUIDE_ON_THE_ROCKER.format(toward="C"))
    refused(path, "[[dyad]] #2", "'guide.toward'", "no direction")


def test_a_guide_toward_a_joint_at_the_same_place_is_refused_at_load(tmp_path):
    # E is placed at C on the rocker C-B (along = left = 0): C -> E has no direction
    point = '[[point]]\nname = "E"\nlink = ["C", "B"]\nalong = 0.0\n'
    path = write(tmp_path, FOUR_BAR + point + GUIDE_ON_THE_ROCKER.format(toward="E"))
    refused(path, "[[dyad]] #2", "'guide.toward'", "one point")


def test_a_guide_toward_another_joint_of_the_link_is_a_guide(tmp_path):
    # the rocker's guide through C toward B: H is on the line C -> B, at 0.3 m from B (checked by distances)
    solution = load_linkage(write(tmp_path, FOUR_BAR + GUIDE_ON_THE_ROCKER.format(toward="B"))).solve(
        np.radians([0.0, 40.0]), 1.0, order=0)
    c, b, h = (solution.point(j).value for j in "CBH")
    np.testing.assert_allclose(np.abs(h - b), 0.3, atol=1e-12)
    np.testing.assert_allclose(((h - c) / (b - c)).imag, 0.0, atol=1e-12)     # on the line C -> B


@pytest.mark.parametrize("pivot", ["A", "O"])
def test_a_lever_on_its_own_block_is_refused_at_load(tmp_path, pivot):
    path = write(tmp_path, FOUR_BAR + f"""
[[dyad]]
type = "RPR"
block = "{pivot}"
pivot = "{pivot}"
""")
    refused(path, "[[dyad]] #2", "'pivot'", "no direction")


def test_a_lever_whose_pivot_is_a_fixed_joint_at_the_blocks_place_is_refused(tmp_path):
    # P is a frame joint at the crank's pivot O: the block on O and the pivot P are one point
    path = write(tmp_path, FOUR_BAR.replace('C = [0.4, 0.0]', 'C = [0.4, 0.0]\nP = [0.0, 0.0]') + """
[[dyad]]
type = "RPR"
block = "O"
pivot = "P"
""")
    refused(path, "[[dyad]] #2", "one point")


def test_a_hinge_between_two_fixed_joints_at_one_place_is_refused(tmp_path):
    path = write(tmp_path, FOUR_BAR.replace('C = [0.4, 0.0]', 'C = [0.4, 0.0]\nD = [0.4, 0.0]') + """
[[dyad]]
type = "RRR"
joint = "K"
from = ["C", "D"]
lengths = [0.1, 0.1]
""")
    refused(path, "[[dyad]] #2", "'from'", "one point")


PRP = FOUR_BAR + """
[[dyad]]
type = "PRP"
joint = "K"
guides = [{{ through = [{x1}, {y1}], angle_deg = {a1} }}, {{ through = [{x2}, {y2}], angle_deg = {a2} }}]
"""


@pytest.mark.parametrize("a2", [0.0, 180.0, 360.0, -1e20 + 0.0])
def test_parallel_fixed_guides_of_a_prp_are_refused_at_load(tmp_path, a2):
    # -1e20 ≡ -280 ≡ 80 (mod 360)? no: 10**20 ≡ 280, so -1e20 ≡ -280 ≡ 80; only 0/180/360 are parallel
    path = write(tmp_path, PRP.format(x1=0.0, y1=0.0, a1=0.0, x2=0.0, y2=1.0, a2=a2))
    if a2 == -1e20:
        load_linkage(path)                     # 80° to the first guide: it crosses it
        return
    refused(path, "[[dyad]] #2", "'guides'", "parallel")


def test_crossing_fixed_guides_of_a_prp_give_the_crossing_at_every_position(tmp_path):
    # the guides y = x (through (0, 0) at 45°) and through (1, 0) at 135° (y = 1 - x) cross at (1/2, 1/2), by
    # hand: x = 1 - x; K is at 1/√2 along the first and 1/√2 along the second guide from their points
    path = write(tmp_path, PRP.format(x1=0.0, y1=0.0, a1=45.0, x2=1.0, y2=0.0, a2=135.0))
    linkage = load_linkage(path)
    phi = np.radians(np.arange(0.0, 360.0, 30.0)).reshape(3, 4)
    solution = linkage.solve(phi, omega=5.0, alpha=2.0)
    k = solution.point("K")
    half = float(Fraction(1, 2))
    for derivative, expected in ((k.value, complex(half, half)), (k.velocity, 0j), (k.acceleration, 0j)):
        assert np.shape(derivative) == phi.shape
        np.testing.assert_allclose(derivative, expected, atol=1e-15)
    for slider in ("K1", "K2"):
        travel = solution.slider(slider)
        assert np.shape(travel.value) == phi.shape
        np.testing.assert_allclose(travel.value, math.sqrt(0.5), atol=1e-15)


def test_triad_links_that_are_not_names_are_refused_at_load(tmp_path):
    path = write(tmp_path, TRIAD + "links = [1, 2, 3, 4]\n")
    refused(path, "[[triad]] #1", "'links'")


def test_triad_links_as_a_string_are_refused(tmp_path):
    path = write(tmp_path, TRIAD + 'links = "DEFG"\n')
    refused(path, "[[triad]] #1", "'links'")


def test_the_structure_of_a_triad_with_named_links():
    # a Python-made linkage with a link named by a number is refused when it is made, not when it is printed
    from mechanisms.linkages.groups import Crank, Triad
    bars = (("A", "D", 0.3), ("C", "E", 0.3), ("G", "F", 0.3), ("D", "E", 0.2), ("E", "F", 0.2), ("D", "F", 0.2))
    guess = (complex(-0.01, -0.28), complex(0.17, -0.19), complex(0.0, -0.08))
    frame = {"O": 0j, "C": 0.4 + 0j, "G": 0.2 - 0.3j}
    with pytest.raises(StructureError, match="named 1"):
        mech.Linkage(frame, [Crank("O", "A", length=0.1), Triad(("D", "E", "F"), bars, guess, 0.0, (1, 2, 3, 4))])
    named = mech.Linkage(frame, [Crank("O", "A", length=0.1),
                                 Triad(("D", "E", "F"), bars, guess, 0.0, ("DEF", "AD", "CE", "GF"))])
    assert "DEF" in structure_of(named).text()


TRIAD = """\
[frame]
O = [0.0, 0.0]
C = [0.4, 0.0]
G = [0.2, -0.3]
[crank]
pivot = "O"
pin = "A"
length = 0.1
[[triad]]
joints = ["D", "E", "F"]
bars = [["A", "D", 0.3], ["C", "E", 0.3], ["G", "F", 0.3], ["D", "E", 0.2], ["E", "F", 0.2], ["D", "F", 0.2]]
guess = { D = [-0.01, -0.28], E = [0.17, -0.19], F = [0.0, -0.08] }
"""
GUESS = [-0.01, -0.28, 0.17, -0.19, 0.0, -0.08]          # the file's guess as the generic solver's q


def test_a_triad_at_crank_angles_past_a_turn_is_the_same_as_before_it(tmp_path):
    linkage = load_linkage(write(tmp_path, TRIAD))
    # expected: the generic Newton solver from the file's guess at -10°, continued to 10° (not the continuation
    # of blocks/bars.py): 350°…370° are the crank positions of -10°…10°
    phi = np.radians(np.arange(-10.0, 10.5, 2.0))
    reference = solve_generic(linkage, phi, 3.0, 0.0, order=2, guess=np.array(GUESS), tol=1e-14)
    solution = linkage.solve(phi + 2.0 * math.pi, omega=3.0)
    for i, joint in enumerate("DEF"):
        for got, want in ((solution.point(joint).value, reference.q[2 * i] + 1j * reference.q[2 * i + 1]),
                          (solution.point(joint).velocity, reference.q_t[2 * i] + 1j * reference.q_t[2 * i + 1]),
                          (solution.point(joint).acceleration,
                           reference.q_tt[2 * i] + 1j * reference.q_tt[2 * i + 1])):
            np.testing.assert_allclose(got, want, atol=1e-9)
    # and a turn the other way, and many turns away
    for turns in (-1, 7, -1000):
        again = linkage.solve(phi + 2.0 * math.pi * turns, omega=3.0, order=0)
        np.testing.assert_allclose(again.point("D").value, reference.q[0] + 1j * reference.q[1], atol=1e-9)


def test_a_triad_at_angles_on_the_far_side_of_its_range_is_solved_there(tmp_path):
    # the group assembles over about [-17°, 213°] from its guess at 0°: 200° is reached going up, and -160°
    # is the same crank position; expected: the generic solver continued from the guess over 0°…200°
    linkage = load_linkage(write(tmp_path, TRIAD))
    path = np.radians(np.arange(0.0, 200.5, 0.5))
    reference = solve_generic(linkage, path, 1.0, 0.0, order=0, guess=np.array(GUESS), tol=1e-14)
    solution = linkage.solve(np.radians([-160.0, 200.0]), omega=1.0, order=0)
    np.testing.assert_allclose(solution.point("D").value, reference.q[0, -1] + 1j * reference.q[1, -1], atol=1e-9)


@pytest.mark.parametrize("huge", ["1e20", "1e9", "-1e300", "9007199254740993"])
def test_a_huge_guess_angle_is_reduced_exactly_and_costs_nothing(tmp_path, huge):
    # expected: the same linkage with the guess angle reduced by exact rational arithmetic (Fraction % 360)
    value = Fraction(float(huge)) if "e" in huge else Fraction(int(huge))
    reduced = float(value % 360)
    with_huge = load_linkage(write(tmp_path, TRIAD + f"guess_angle_deg = {huge}\n", "huge.toml"))
    with_reduced = load_linkage(write(tmp_path, TRIAD + f"guess_angle_deg = {reduced!r}\n", "reduced.toml"))
    assert with_huge.groups()[1].guess_angle == pytest.approx(math.radians(reduced - 360 * (reduced > 180)),
                                                              abs=1e-15)
    tracemalloc.start()
    try:
        outcome = with_huge.solve(np.radians([0.0, 10.0]), 1.0, order=0).point("D").value
        expected = with_reduced.solve(np.radians([0.0, 10.0]), 1.0, order=0).point("D").value
        np.testing.assert_array_equal(outcome, expected)
    except MechanismError as error:            # a guess not valid at that crank angle: both refuse alike
        with pytest.raises(type(error)):
            with_reduced.solve(np.radians([0.0, 10.0]), 1.0, order=0)
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    assert peak < 50e6                          # np.arange over 1e9° in 2° steps would need 3.7 GB


def test_every_angle_of_a_file_is_reduced_in_degrees(tmp_path):
    # 1e20° ≡ 280° (integer arithmetic above): a guide at 1e20° is the guide at 280°
    base = FOUR_BAR + """
[[dyad]]
type = "RRP"
joint = "H"
from = "B"
length = 0.5
guide = {{ through = [0.0, 0.6], angle_deg = {angle} }}
"""
    phi = np.radians(np.arange(0.0, 360.0, 45.0))
    a = load_linkage(write(tmp_path, base.format(angle="1e20"), "a.toml")).solve(phi, 1.0, order=0)
    b = load_linkage(write(tmp_path, base.format(angle="280.0"), "b.toml")).solve(phi, 1.0, order=0)
    np.testing.assert_array_equal(a.point("H").value, b.point("H").value)


# --- load_linkage's argument and the file ------------------------------------------------------------------

@pytest.mark.parametrize("argument", [None, 3, 1.5, ["a.toml"], {"a": 1}, object()])
def test_load_linkage_refuses_what_is_not_a_path(argument):
    with pytest.raises(StructureError, match="path"):
        load_linkage(argument)


def test_load_linkage_refuses_a_nul_and_a_name_too_long():
    with pytest.raises(StructureError, match="NUL"):
        load_linkage("x\0")
    with pytest.raises(StructureError, match="cannot be read"):
        load_linkage("a" * 5000)


def test_load_linkage_names_the_file_and_the_cause(tmp_path):
    assert "is a folder" in refused(tmp_path)
    assert "no such file" in refused(tmp_path / "nope.toml")
    bad_utf8 = tmp_path / "latin.toml"
    bad_utf8.write_bytes(b'name = "caf\xe9"\n')
    assert "not a valid TOML" in refused(bad_utf8)
    assert "not a valid TOML" in refused(write(tmp_path, "name = \n", "broken.toml"))
    if os.geteuid() != 0:                        # root reads any file
        locked = write(tmp_path, FOUR_BAR, "locked.toml")
        locked.chmod(0)
        assert "cannot be read" in refused(locked)


def test_a_bytes_path_and_a_path_object_are_paths(tmp_path):
    path = write(tmp_path, FOUR_BAR)
    assert load_linkage(os.fsencode(str(path))).name == load_linkage(path).name == "four-bar"


# --- wrong keys and values, swept ----------------------------------------------------------------------------

SWEEP = [
    # (what replaces, by what, the words the error must hold)
    ("length = 0.1", 'length = "0.1"', ["[crank]", "'length'"]),
    ("length = 0.1", "length = 0.0", ["[crank]", "'length'"]),
    ("length = 0.1", "length = -0.1", ["[crank]", "'length'"]),
    ("length = 0.1", "length = nan", ["[crank]", "'length'"]),
    ("length = 0.1", "length = inf", ["[crank]", "'length'"]),
    ("length = 0.1", "length = true", ["[crank]", "'length'"]),
    ("length = 0.1", "length = 1e300", ["crank", "length"]),
    ("length = 0.1", "length = [0.1]", ["[crank]", "'length'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, -0.30]", ["[[dyad]] #1", "'lengths'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, nan]", ["[[dyad]] #1", "'lengths'"]),
    ("lengths = [0.35, 0.30]", "lengths = []", ["[[dyad]] #1", "'lengths'"]),
    ("lengths = [0.35, 0.30]", "lengths = { a = 1 }", ["[[dyad]] #1", "'lengths'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, 0.30]\nbranch = 0", ["[[dyad]] #1", "'branch'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, 0.30]\nbranch = 2", ["[[dyad]] #1", "'branch'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, 0.30]\nbranch = true", ["[[dyad]] #1", "'branch'"]),
    ("lengths = [0.35, 0.30]", 'lengths = [0.35, 0.30]\nbranch = "+1"', ["[[dyad]] #1", "'branch'"]),
    ("lengths = [0.35, 0.30]", "lengths = [0.35, 0.30]\nbranch = nan", ["[[dyad]] #1", "'branch'"]),
    ('from = ["A", "C"]', 'from = ["A", "A"]', ["[[dyad]] #1", "'from'"]),
    ('from = ["A", "C"]', 'from = ["A", "Z"]', ["'Z'", "no group finds"]),
    ('from = ["A", "C"]', 'from = "A"', ["[[dyad]] #1", "'from'"]),
    ('from = ["A", "C"]', 'from = ["A", "B"]', ["B"]),
    ('joint = "B"', 'joint = "A"', ["'A'", "twice"]),
    ('joint = "B"', 'joint = ""', ["[[dyad]] #1", "'joint'"]),
    ('joint = "B"', "joint = 1", ["[[dyad]] #1", "'joint'"]),
    ('type = "RRR"', 'type = "RRRR"', ["[[dyad]] #1", "'type'"]),
    ('type = "RRR"', "type = [1]", ["[[dyad]] #1", "'type'"]),
    ('O = [0.0, 0.0]', 'O = [0.0, nan]', ["[frame]", "'O'"]),
    ('O = [0.0, 0.0]', 'O = [0.0]', ["[frame]", "'O'"]),
    ('O = [0.0, 0.0]', 'O = "origin"', ["[frame]", "'O'"]),
    ('O = [0.0, 0.0]', 'O = [true, 0.0]', ["[frame]", "'O'"]),
    ('pivot = "O"', 'pivot = "Q"', ["'Q'"]),
    ('pin = "A"', 'pin = "C"', ["'C'"]),
    ('name = "four-bar"', "name = 4", ["'name'"]),
    ('name = "four-bar"', 'name = "x"\ndescription = 1', ["'description'"]),
    ('name = "four-bar"', 'name = "x"\nwhat = 1', ["'what'"]),
    ('[[dyad]]', '[dyad]', ["dyad"]),
]


@pytest.mark.parametrize("old, new, words", SWEEP)
def test_each_wrong_value_is_refused_by_name(tmp_path, old, new, words):
    assert old in FOUR_BAR
    refused(write(tmp_path, FOUR_BAR.replace(old, new, 1)), *words)


GROUPS = {
    "RRP": ('type = "RRP"\njoint = "H"\nfrom = "B"\nlength = 0.5\nguide = { through = [0.0, 0.6], angle_deg = 0.0 }\n',
            [("length = 0.5", "length = 0"), ("length = 0.5", "length = nan"), ('from = "B"', 'from = "B"\nbranch = -2'),
             ("angle_deg = 0.0", "angle_deg = nan"), ("angle_deg = 0.0", 'angle_deg = "0"'),
             ("through = [0.0, 0.6]", "through = [0.0]"), ("through = [0.0, 0.6]", "through = 5"),
             ('joint = "H"', 'joint = "B"'), ('from = "B"', 'from = "Z"'),
             ("guide = {", 'guide = { toward = "C", '), ("through = [0.0, 0.6]", 'through = "C", toward = "Z"')]),
    "RPR": ('type = "RPR"\nblock = "A"\npivot = "C"\njoint = "D"\nlength = 0.6\n',
            [("length = 0.6", "length = -0.6"), ('joint = "D"', 'joint = "A"'), ('block = "A"', 'block = "C"'),
             ('joint = "D"\n', ""), ('pivot = "C"', 'pivot = "Z"')]),
    "PRP": ('type = "PRP"\njoint = "K"\nguides = [{ through = "B", toward = "C" }, { through = [0.0, 0.2], '
            'angle_deg = 90.0 }]\n',
            [("angle_deg = 90.0", "angle_deg = nan"), ('toward = "C"', 'toward = "B"'),
             ('toward = "C"', 'toward = "O"'), ("guides = [", "guides = [{ through = [0.0, 0.0] }, "),
             ('joint = "K"', 'joint = "C"')]),
    "RPP": ('type = "RPP"\njoint = "Y"\nblock = "A"\nguide = { through = [0.0, 0.0], angle_deg = 0.0 }\n'
            'slot_angle_deg = 90.0\n',
            [("slot_angle_deg = 90.0", "slot_angle_deg = 180.0"), ("slot_angle_deg = 90.0", "slot_angle_deg = 0"),
             ("slot_angle_deg = 90.0", "slot_angle_deg = 1e20"), ("slot_angle_deg = 90.0", "slot_angle_deg = inf"),
             ('block = "A"', 'block = "Y"')]),
}


@pytest.mark.parametrize("kind, index", [(k, i) for k, (_, cases) in GROUPS.items() for i in range(len(cases))])
def test_each_group_type_refuses_its_wrong_values_by_place(tmp_path, kind, index):
    table, cases = GROUPS[kind]
    text = FOUR_BAR + "[[dyad]]\n" + table
    load_linkage(write(tmp_path, text, "good.toml"))        # the group as given is a good one
    old, new = cases[index]
    assert old in table
    path = write(tmp_path, FOUR_BAR + "[[dyad]]\n" + table.replace(old, new, 1))
    if (kind, new) == ("RPP", "slot_angle_deg = 1e20"):
        # 1e20° ≡ 280° (mod 360), not parallel to the guide: a good value, reduced exactly
        load_linkage(path)
        return
    message = refused(path)
    assert "[[dyad]] #2" in message or "twice" in message or "no group finds" in message, message


@pytest.mark.parametrize("table, words", [
    ('[[point]]\nname = "E"\nlink = ["A", "B"]\nalong = nan\n', ["[[point]] #1", "'along'"]),
    ('[[point]]\nname = "E"\nlink = ["A", "C"]\nalong = 0.1\n', ["not on one link"]),
    ('[[point]]\nname = "E"\nlink = ["A", "A"]\nalong = 0.1\n', ["[[point]] #1", "'link'"]),
    ('[[point]]\nname = "B"\nlink = ["A", "B"]\nalong = 0.1\n', ["'B'", "twice"]),
    ('[[point]]\nname = "E"\nlink = ["A", "B"]\ndistances = [0.1, 0.1]\nbranch = 3\n', ["[[point]] #1", "'branch'"]),
    ('[[point]]\nname = "E"\nlink = ["A", "B"]\ndistances = [0.01, 0.01]\n', ["triangle"]),
    ('[[point]]\nname = "E"\nlink = "nolink"\nalong = 0.1\n', ["nolink"]),
    ('[[point]]\nname = "E"\nlink = ["A", "B"]\nalong = 0.1\n[[point]]\nname = "E"\nlink = ["A", "B"]\nalong = 0.2\n',
     ["'E'", "twice"]),
    ('[[mass]]\nbody = "nope"\nmass = 1.0\n', ["[[mass]] #1", "'body'", "nope"]),
    ('[[mass]]\nbody = "AB"\nmass = -1.0\n', ["[[mass]] #1", "'mass'"]),
    ('[[mass]]\nbody = "AB"\nmass = nan\n', ["[[mass]] #1", "'mass'"]),
    ('[[mass]]\nbody = "AB"\nmass = 1.0\n[[mass]]\nbody = "AB"\nmass = 2.0\n', ["[[mass]] #2", "twice"]),
])
def test_points_and_masses_refuse_their_wrong_values(tmp_path, table, words):
    refused(write(tmp_path, FOUR_BAR + table), *words)


def test_a_mass_on_a_link_or_a_block_is_kept():
    data = {"frame": {"O": [0.0, 0.0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
            "dyad": [{"type": "RRP", "joint": "B", "from": "A", "length": 0.3,
                      "guide": {"through": [0.0, 0.0], "angle_deg": 0.0}}],
            "mass": [{"body": "AB", "mass": 1.0}, {"body": "B", "mass": 2.0}]}
    assert set(linkage_from_dict(data).masses) == {"AB", "B"}


@pytest.mark.parametrize("triad_change, words", [
    (("guess = {", 'guess = { G = [0.0, 0.0], '), ["[[triad]] #1", "'guess'"]),
    (('["A", "D", 0.3]', '["A", "D", 0.0]'), ["[[triad]] #1", "'bars'"]),
    (('["A", "D", 0.3]', '["A", "D", nan]'), ["[[triad]] #1", "'bars'"]),
    (('["A", "D", 0.3]', '["A", "D"]'), ["[[triad]] #1", "'bars'"]),
    (('["A", "D", 0.3], ', ""), ["[[triad]] #1", "degrees of freedom"]),
    (('joints = ["D", "E", "F"]', 'joints = "DEF"'), ["[[triad]] #1", "'joints'"]),
    (('D = [-0.01, -0.28]', 'D = [-0.01, inf]'), ["[[triad]] #1", "'guess.D'"]),
])
def test_a_triad_refuses_its_wrong_values(tmp_path, triad_change, words):
    old, new = triad_change
    assert old in TRIAD
    refused(write(tmp_path, TRIAD.replace(old, new, 1)), *words)


@pytest.mark.parametrize("data", [None, [], "x", {"frame": [], "crank": {}}, {1: 2, "a": 3},
                                  {"frame": {"O": [0, 0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
                                   "dyad": [{"type": "RRR", 1: 2}]}])
def test_linkage_from_dict_refuses_what_is_not_a_linkage(data):
    with pytest.raises(StructureError):
        linkage_from_dict(data)


# --- cost ------------------------------------------------------------------------------------------------------

def test_ten_thousand_points_on_a_link_solve_in_bounded_memory():
    n = 10_000
    data = {"frame": {"O": [0.0, 0.0], "C": [0.4, 0.0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
            "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [0.35, 0.30]}],
            "point": [{"name": f"E{i}", "link": ["A", "B"], "along": 1e-4 * i, "left": 0.01} for i in range(n)]}
    linkage = linkage_from_dict(data)
    phi = np.radians([0.0, 90.0])
    tracemalloc.start()
    try:
        solution = linkage.solve(phi, 1.0, order=0)
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    # every pair of the 10,002 joints of the coupler would be 5e7 distances, several GB; a bound that grows
    # with the points, not their pairs, is a few MB
    assert peak < 100e6, peak
    # and the last point is where the link's frame puts it: A + (u + iw)·(B − A)/|AB|, u = 0.9999 m, w = 0.01 m
    a, b = solution.point("A").value, solution.point("B").value
    expected = a + complex(1e-4 * (n - 1), 0.01) * (b - a) / np.abs(b - a)
    np.testing.assert_allclose(solution.point(f"E{n - 1}").value, expected, atol=1e-12)
    assert len(linkage.preserved_distances()) <= 2 * (n + 10)


def test_the_preserved_distances_still_hold_the_rigid_link():
    # a point moved off its link changes its distance to A or to B: the check must see it
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        linkage = load_linkage("watt-six-bar")
        solution = linkage.solve(np.radians(np.arange(0.0, 360.0, 30.0)), 1.0, order=0)
        from mechanisms.verify.checks import distance_deviation
        assert distance_deviation(linkage, solution) < 1e-12
    pairs = set(linkage.preserved_distances())
    for joints in linkage.link_joints().values():
        for joint in joints[1:]:
            assert any(joint in pair for pair in pairs)


# --- issue 29: loads and gravity in the file ------------------------------------------------------------------

SLIDER = FOUR_BAR + """\
[[dyad]]
type = "RRP"
joint = "H"
from = "B"
length = 0.3
guide = { through = [0.0, 0.3], angle_deg = 0.0 }
links = ["rod", "ram"]
"""


@pytest.mark.parametrize("table, words", [
    ('[[load]]\nbody = "nope"\ntorque = 1.0\n', ["[[load]] #1", "'body'", "nope", "AB", "CB", "rod", "ram", "H"]),
    ('[[load]]\nbody = "AB"\n', ["[[load]] #1", "exactly one of force"]),
    ('[[load]]\nbody = "AB"\ntorque = 1.0\nforce = [1.0, 0.0]\n', ["[[load]] #1", "exactly one of force"]),
    ('[[load]]\nbody = "AB"\nforce = [1.0]\n', ["[[load]] #1", "'force'"]),
    ('[[load]]\nbody = "AB"\nforce = [1.0, nan]\n', ["[[load]] #1", "'force'"]),
    ('[[load]]\nbody = "AB"\nforce = ["1", 0.0]\n', ["[[load]] #1", "'force'"]),
    ('[[load]]\nbody = "AB"\nforce = [1.0, 0.0]\nalong = inf\n', ["[[load]] #1", "'along'"]),
    ('[[load]]\nbody = "AB"\ntorque = "big"\n', ["[[load]] #1", "'torque'"]),
    ('[[load]]\nbody = "AB"\ntorque = 1.0\nalong = 0.1\n', ["[[load]] #1", "'along'", "no point"]),
    ('[[load]]\nbody = 3\ntorque = 1.0\n', ["[[load]] #1", "'body'"]),
    ('[[load]]\nbody = "AB"\ntorque = 1.0\nsize = 2\n', ["[[load]] #1", "unknown key 'size'"]),
    ('[[load]]\nbody = "AB"\ntorque = 1.0\n[[load]]\nbody = "frame"\ntorque = 1.0\n', ["[[load]] #2", "'frame'"]),
    ('[[mass]]\nbody = "ram"\nmass = 1.0\n[[mass]]\nbody = "H"\nmass = 2.0\n', ["[[mass]] #2", "twice"]),
    ('[[mass]]\nbody = "A"\nmass = 1.0\n', ["[[mass]] #1", "no body 'A'"]),
    ('[[mass]]\nbody = "ram"\nmass = 1.0\ninertia = -1.0\n', ["[[mass]] #1", "'inertia'"]),
])
def test_loads_refuse_their_wrong_values(tmp_path, table, words):
    refused(write(tmp_path, SLIDER + table), *words)


@pytest.mark.parametrize("value", ["nan", "inf", '"down"', "true", "[9.81]"])
def test_gravity_must_be_a_finite_number(tmp_path, value):
    refused(write(tmp_path, f"gravity = {value}\n" + SLIDER), "'gravity'")


def test_loads_and_gravity_are_kept():
    import tomllib
    data = tomllib.loads("gravity = 9.81\n" + SLIDER + '[[load]]\nbody = "H"\nforce = [-800.0, 5]\nleft = 0.01\n'
                         '[[load]]\nbody = "CB"\ntorque = -15\n[[mass]]\nbody = "ram"\nmass = 3.0\n')
    linkage = linkage_from_dict(data)
    assert linkage.gravity == 9.81
    assert linkage.loads == [{"body": "H", "force": (-800.0, 5.0), "along": 0.0, "left": 0.01},
                             {"body": "CB", "torque": -15.0}]
    assert linkage_from_dict(tomllib.loads(SLIDER)).gravity == 0.0
    # for the energy functions a block that only translates is named by its joint, a link by its name
    from mechanisms.analysis import energy
    assert set(energy.linkage_masses(linkage)) == {"H"}
    loads = energy.linkage_loads(linkage)
    assert [load.body for load in loads] == ["H", "CB"]
