"""The scene export of the site's player (mechanisms.present.scene, issue 17), without a browser.

Every number a page shows comes from a scene's data, so the data must be the package's kinematics:

* frames equal ``solve`` to the quantization (a position is stored as whole steps of ``data["step"]``
  from ``data["origin"]``, so it is off by at most step/2 in x and in y, step·√2/2 in all);
* read-out values equal the kinematics rounded to their digits, checked against closed-form
  formulas written here (the crank-slider's s = r cos φ + √(l² − (r sin φ − e)²) and its velocity),
  not against the package;
* an explorer's members are every combination of the parameters' values, in row-major order, and
  each member keeps to its assembly range: its frames are '0' exactly where the crank angle lies
  outside the range found here by the law of cosines, with no position, no value there, and the
  intervals it stores are those limits;
* rates (read-outs of order 1, velocity and acceleration arrows) are missing at singular frames,
  never NaN: the JSON is strict (``allow_nan=False``);
* the still image is well-formed SVG with one ``.mech-hinge`` per joint, where the joint is;
* sizes: a 72-frame four-bar is a few kilobytes, and an explorer grows linearly with its members, so a
  page's budget (1 MB, tests/test_weights.py) holds explorers of tens of members;
* bad input raises InvalidParameterError (a MechanismError).
"""

from __future__ import annotations

import json
import math
import re
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.linkages.base import Bar, Block, Ground
from mechanisms.present import Line, Parameter, Readout, acceleration, explorer, scene, velocity

SVG = "{http://www.w3.org/2000/svg}"


# --- helpers (independent of the code under test) ------------------------------------------------------

def frame_angles(data) -> np.ndarray:
    """The crank angles (rad) of the frames, as the data stores them (degrees)."""
    return np.radians(np.array(data["phi"], dtype=float))


def solved(mechanism, phi, order=0, omega=1.0):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mech.SingularPositionWarning)
        return mechanism.solve(phi, omega=omega, order=order)


def joints_of(mechanism) -> set[str]:
    """The mechanism's joints, as its own solution names them (independent of how the scene reads the scheme)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mech.SingularPositionWarning)
        return set(mechanism.solve(np.array([0.3]), order=0).point_names)


def slider_position(r, l, e, phi):
    """Crank-slider, branch +1: s = r cos φ + √(l² − (r sin φ − e)²) (chapter 3, from the two constraints)."""
    return r * np.cos(phi) + np.sqrt(l**2 - (r * np.sin(phi) - e) ** 2)


def slider_velocity(r, l, e, phi, omega):
    """ds/dt of the formula above: (−r sin φ − (r sin φ − e) r cos φ / √(l² − (r sin φ − e)²)) · ω."""
    h = r * np.sin(phi) - e
    return (-r * np.sin(phi) - h * r * np.cos(phi) / np.sqrt(l**2 - h**2)) * omega


def assert_rounded(stored, exact, digits, what):
    """``stored`` is ``exact`` rounded to ``digits`` decimals (where ``exact`` is not within round-off of a tie)."""
    unit = 10.0 ** -digits
    for k, (s, x) in enumerate(zip(stored, exact)):
        assert s is not None, f"{what}: frame {k} has no value, expected {x}"
        fraction = abs(x / unit - math.floor(x / unit) - 0.5)
        if fraction < 1e-6:            # a tie to within round-off: either neighbour is right
            assert abs(s - x) <= unit * (0.5 + 1e-6), f"{what}: frame {k}: {s} for {x}"
        else:
            assert s == round(x, digits), f"{what}: frame {k}: stored {s}, expected {round(x, digits)} ({x!r})"


def four_bar_cosine_bounds(crank, coupler, rocker, d):
    """A four-bar with C = (d, 0) assembles where lo ≤ cos φ ≤ hi (law of cosines in the triangle O A C:
    |AC|² = L1² + d² − 2 L1 d cos φ, and |L2 − L3| ≤ |AC| ≤ L2 + L3)."""
    lo = (crank**2 + d**2 - (coupler + rocker) ** 2) / (2 * crank * d)   # coupler and rocker stretched in line
    hi = (crank**2 + d**2 - (coupler - rocker) ** 2) / (2 * crank * d)   # coupler and rocker folded in line
    return lo, hi


def four_bar_intervals_degrees(crank, coupler, rocker, d):
    """The assembly arcs (start mod 360, length) in degrees, from the bounds on cos φ."""
    lo, hi = four_bar_cosine_bounds(crank, coupler, rocker, d)
    if lo > 1 or hi < -1:
        return []
    beta_max = 180.0 if lo <= -1 else math.degrees(math.acos(lo))   # |φ| ≤ β_max
    beta_min = 0.0 if hi >= 1 else math.degrees(math.acos(hi))      # |φ| ≥ β_min
    if beta_min == 0.0 and beta_max == 180.0:
        return [(180.0, 360.0)]
    if beta_min == 0.0:
        return [((-beta_max) % 360.0, 2 * beta_max)]
    if beta_max == 180.0:
        return [(beta_min, 360.0 - 2 * beta_min)]
    return sorted([(beta_min, beta_max - beta_min), (360.0 - beta_max, beta_max - beta_min)])


def arcs(intervals_degrees):
    """Stored intervals [[a, b], …] (degrees) as sorted (start mod 360, length)."""
    return sorted((a % 360.0, b - a) for a, b in intervals_degrees)


def still_svg(s) -> ET.Element:
    found = re.search(r"<svg\b.*?</svg>", s.html(), re.S)
    assert found, "the figure's HTML has no <svg> still image"
    return ET.fromstring(found.group(0))       # raises if it is not well-formed XML


def by_class(svg: ET.Element, name: str) -> list[ET.Element]:
    return [e for e in svg.iter() if name in (e.get("class") or "").split()]


def stored_ok_without_nan(s):
    text = json.dumps(s.data, allow_nan=False)   # raises ValueError on NaN or infinity
    json.loads(text, parse_constant=lambda c: pytest.fail(f"the JSON holds {c}"))
    json.loads(s.json(), parse_constant=lambda c: pytest.fail(f"the page's JSON holds {c}"))


# --- frames equal solve ---------------------------------------------------------------------------------------

MECHANISMS = {
    "crank-slider": lambda: mech.CrankSlider(crank=0.1, rod=0.35, offset=0.02),
    "four-bar": lambda: mech.FourBar(1.0, 3.5, 3.0, frame=(4.0, 0.0)),
    "four-bar, pivot off the axis": lambda: mech.FourBar(0.3, 0.9, 0.7, frame=(0.8, 0.25), branch=-1),
    "slotted lever": lambda: mech.SlottedLever(crank=1.0, pivot=(0.0, 2.0)),
    "rotating slotted lever": lambda: mech.SlottedLever(crank=1.0, pivot=(0.0, 0.4)),
}


@pytest.mark.parametrize("name", list(MECHANISMS))
@pytest.mark.parametrize("frames", [72, 37])
def test_frames_equal_solve(name, frames):
    m = MECHANISMS[name]()
    s = scene(m, frames=frames, start=0.3)
    data = s.data
    phi = frame_angles(data)
    assert len(phi) == frames
    # the frames are evenly spaced from start
    expected_phi = 0.3 + np.arange(frames) * 2 * math.pi / frames
    assert np.allclose(phi, expected_phi, atol=1e-7), "frames are not evenly spaced from start"
    sol = solved(m, expected_phi)
    tolerance = data["step"] * math.sqrt(2) / 2 * (1 + 1e-9) + 1e-12
    assert set(data["members"][0]["xy"]) >= joints_of(m), "a joint of the scheme has no positions"
    for joint in sol.point_names:
        got = s.position(joint)
        exact = np.broadcast_to(sol.point(joint).value, expected_phi.shape)
        error = np.max(np.abs(got - exact))
        assert error <= tolerance, f"{name}, joint {joint}: off by {error:.3g} m (step {data['step']:.3g} m)"


def test_positions_of_the_crank_slider_are_the_closed_form():
    r, l, e = 0.1, 0.35, 0.02
    s = scene(mech.CrankSlider(crank=r, rod=l, offset=e))
    phi = frame_angles(s.data)
    tolerance = s.data["step"] * math.sqrt(2) / 2 * (1 + 1e-9)
    assert np.max(np.abs(s.position("A") - r * np.exp(1j * phi))) <= tolerance
    assert np.max(np.abs(s.position("B") - (slider_position(r, l, e, phi) + 1j * e))) <= tolerance
    assert np.max(np.abs(s.position("O"))) <= tolerance


def test_block_angles_and_extra_points_equal_solve():
    m = mech.SlottedLever(crank=1.0, pivot=(0.0, 2.0))
    s = scene(m, points={"M": lambda sol, mm: sol.point_on("lever", 1.0)}, lines=[Line(("O", "C"))])
    phi = frame_angles(s.data)
    sol = solved(m, phi)
    lever = s.data["members"][0]["angles"]["lever"]
    assert np.max(np.abs(np.array(lever) - sol.angle("lever").value)) <= 0.5e-5 + 1e-12
    # the point 1 m from C along the lever, computed here from the lever angle
    xi = sol.angle("lever").value
    tolerance = s.data["step"] * math.sqrt(2) / 2 * (1 + 1e-9)
    assert np.max(np.abs(s.position("M") - (2j + np.exp(1j * xi)))) <= tolerance
    assert s.data["dots"] == ["M"]


# --- read-outs ---------------------------------------------------------------------------------------------------

def crank_slider_readout():
    return [Readout("s", "m", lambda sol, m: sol.point("B").value.real, digits=4),
            Readout("v_B", "m/s", lambda sol, m: sol.point("B").velocity.real, digits=3, order=1)]


def test_readout_equals_the_closed_form_rounded():
    r, l, e, omega = 0.1, 0.35, 0.02, 2.0
    s = scene(mech.CrankSlider(crank=r, rod=l, offset=e), readout=crank_slider_readout(), omega=omega)
    phi = frame_angles(s.data)
    values = s.data["members"][0]["values"]
    assert [item["digits"] for item in s.data["readout"]] == [4, 3]
    assert_rounded(values[0], slider_position(r, l, e, phi), 4, "s")
    assert_rounded(values[1], slider_velocity(r, l, e, phi, omega), 3, "v_B at ω = 2 rad/s")


def test_two_parameter_explorer_is_row_major_and_each_member_is_its_mechanism():
    r, rods, offsets = 0.1, [0.25, 0.3, 0.35], [0.0, 0.02, -0.03, 0.05]
    s = explorer(lambda rod, offset: mech.CrankSlider(crank=r, rod=rod, offset=offset),
                 [Parameter("rod", "L₂", "m", rods), Parameter("offset", "e", "m", offsets)],
                 readout=crank_slider_readout(), frames=36)
    data = s.data
    assert len(data["members"]) == len(rods) * len(offsets)
    assert data["keys"] == [[rod, offset] for rod in rods for offset in offsets]
    assert [p["name"] for p in data["parameters"]] == ["rod", "offset"]
    phi = frame_angles(data)
    for i, rod in enumerate(rods):
        for j, offset in enumerate(offsets):
            index = i * len(offsets) + j
            assert s.member_index(rod=rod, offset=offset) == index
            values = data["members"][index]["values"]
            assert_rounded(values[0], slider_position(r, rod, offset, phi), 4, f"s of rod {rod}, e {offset}")
            assert_rounded(values[1], slider_velocity(r, rod, offset, phi, 1.0), 3, f"v_B of rod {rod}, e {offset}")
            tolerance = data["step"] * math.sqrt(2) / 2 * (1 + 1e-9)
            got = s.position("B", index)
            assert np.max(np.abs(got - (slider_position(r, rod, offset, phi) + 1j * offset))) <= tolerance


# --- assembly ranges -----------------------------------------------------------------------------------------

# crank lengths of a four-bar with coupler 1.4, rocker 2.5, C = (2, 0): a crank that turns fully (0.5), one
# arc around 180° (1.5), two arcs (2.2, 3.0), one arc across 0° (4.5)
FAMILY = dict(coupler=1.4, rocker=2.5, d=2.0, cranks=[0.5, 1.5, 2.2, 3.0, 4.5])


def four_bar_family(frames=72, **options):
    f = FAMILY
    return explorer(lambda crank: mech.FourBar(crank, f["coupler"], f["rocker"], frame=(f["d"], 0.0)),
                    [Parameter("crank", "L₁", "m", f["cranks"])], frames=frames, paths=["B"], **options)


@pytest.mark.parametrize("frames", [72, 100])
def test_explorer_members_keep_to_their_assembly_ranges(frames):
    f = FAMILY
    s = four_bar_family(frames, readout=[Readout("ψ", "°", lambda sol, m: np.degrees(sol.angle("coupler").value), 1)])
    phi = frame_angles(s.data)
    kinds = set()
    for index, crank in enumerate(f["cranks"]):
        member = s.data["members"][index]
        lo, hi = four_bar_cosine_bounds(crank, f["coupler"], f["rocker"], f["d"])
        cosine = np.cos(phi)
        inside = (cosine > lo) & (cosine < hi)
        clear = (np.abs(cosine - lo) > 1e-9) & (np.abs(cosine - hi) > 1e-9)   # not on a limit itself
        bits = np.array([c == "1" for c in member["valid"]])
        assert len(member["valid"]) == frames
        wrong = np.flatnonzero((bits != inside) & clear)
        assert wrong.size == 0, (f"crank {crank}: frames {wrong.tolist()} (φ = {np.degrees(phi[wrong]).round(1).tolist()}°)"
                                 f" are marked {'valid' if bits[wrong[0]] else 'invalid'} against the law of cosines")
        for joint, xy in member["xy"].items():
            assert len(xy) in (2, 2 * frames)           # two numbers: a point that does not move, stored once
            missing = np.isnan(s.position(joint, index))
            assert missing.shape == (frames,)
            for k in np.flatnonzero(missing == bits):
                raise AssertionError(f"crank {crank}, joint {joint}, frame {k}: "
                                     f"position {'missing' if bits[k] else 'present'}")
        assert all((v is None) == (not bits[k]) for k, v in enumerate(member["values"][0])), \
            f"crank {crank}: read-out values where it does not assemble, or none where it does"
        expected = four_bar_intervals_degrees(crank, f["coupler"], f["rocker"], f["d"])
        got = arcs(member["intervals"])
        assert len(got) == len(expected), f"crank {crank}: intervals {member['intervals']}, expected arcs {expected}"
        for (a0, n0), (a1, n1) in zip(got, expected):
            assert abs((a0 - a1 + 180) % 360 - 180) <= 2e-3 and abs(n0 - n1) <= 2e-3, \
                f"crank {crank}: stored intervals {member['intervals']}, expected arcs {expected} (start, length)"
        # the stored intervals are the mechanism's own, in degrees
        own = mech.FourBar(crank, f["coupler"], f["rocker"], frame=(f["d"], 0.0)).assembly_intervals()
        assert member["intervals"] == [[round(math.degrees(a), 3), round(math.degrees(b), 3)] for a, b in own]
        kinds.add((len(expected), bits.all()))
    assert kinds == {(1, True), (1, False), (2, False)}, "the family does not cover the kinds it is meant to"


def test_partial_crank_slider_is_valid_exactly_where_the_rod_reaches_the_guide():
    r, l, e = 1.0, 0.8, 0.5      # the rod reaches the guide only where |r sin φ − e| ≤ l
    s = scene(mech.CrankSlider(crank=r, rod=l, offset=e), readout=crank_slider_readout())
    phi = frame_angles(s.data)
    member = s.data["members"][0]
    reach = np.abs(r * np.sin(phi) - e)
    bits = np.array([c == "1" for c in member["valid"]])
    clear = np.abs(reach - l) > 1e-9
    assert np.array_equal(bits[clear], (reach < l)[clear])
    assert 0 < bits.sum() < len(bits)
    ok = np.flatnonzero(bits)
    assert_rounded([member["values"][0][k] for k in ok], slider_position(r, l, e, phi[ok]), 4, "s")
    # arcs where |sin φ| bound: sin φ ∈ [(e − l)/r, (e + l)/r] = [−0.3, 1.3]: one arc from asin(−0.3) to π − asin(−0.3)
    a = math.degrees(math.asin((e - l) / r))
    [(start, length)] = arcs(member["intervals"])
    assert start == pytest.approx(a % 360, abs=2e-3) and length == pytest.approx(180 - 2 * a, abs=2e-3)


def test_position_is_nan_outside_the_assembly_range():
    s = four_bar_family()
    index = s.member_index(crank=3.0)
    bits = np.array([c == "1" for c in s.data["members"][index]["valid"]])
    for joint in ("A", "B"):
        where = s.position(joint, index)
        assert np.array_equal(np.isnan(where.real), ~bits)


# --- rates at singular frames --------------------------------------------------------------------------------

def test_rates_are_missing_at_singular_frames_never_nan():
    # a parallelogram (L1 = L3, L2 = |OC|): B = A + 3 m, v_B = v_A, a_B = a_A; at φ = 0 and 180° all four
    # joints are in line (change points) and the rates are not determined there
    omega = 2.0
    m = mech.FourBar(1.0, 3.0, 1.0, frame=(3.0, 0.0), branch=1)
    s = scene(m, frames=72, omega=omega, arrows=[velocity("B"), acceleration("B")],
              readout=[Readout("ω_2", "rad/s", lambda sol, mm: sol.angle("coupler").omega, 3, order=1),
                       Readout("x_B", "m", lambda sol, mm: sol.point("B").value.real, 3)])
    stored_ok_without_nan(s)
    data = s.data
    phi = frame_angles(data)
    singular = np.isclose(np.cos(phi) ** 2, 1.0, atol=1e-12)
    assert np.flatnonzero(singular).tolist() == [0, 36]
    member = data["members"][0]
    for index, arrow in enumerate(data["arrows"]):
        vector = member["vectors"][index]
        for k in range(len(phi)):
            assert (vector[2 * k] is None) == singular[k] and (vector[2 * k + 1] is None) == singular[k], \
                f"{arrow['label']} at frame {k} (φ = {data['phi'][k]}°): {vector[2 * k:2 * k + 2]}"
    omega_2 = member["values"][0]
    assert [k for k, v in enumerate(omega_2) if v is None] == [0, 36]
    assert all(v == 0.0 for k, v in enumerate(omega_2) if not singular[k]), "a parallelogram's coupler does not turn"
    # positions are kept at the singular frames (the drawing is there, only the rates are not)
    assert all(v is not None for v in member["values"][1])
    assert np.all(np.isfinite(s.position("B")))
    # the arrows are the vectors: v_B = iω e^{iφ}, a_B = −ω² e^{iφ}, at the stored scale
    step = data["step"]
    for index, exact in ((0, 1j * omega * np.exp(1j * phi)), (1, -omega**2 * np.exp(1j * phi))):
        scale = data["scales"][data["arrows"][index]["kind"]]       # drawn length per unit (m per m/s …)
        v = member["vectors"][index]
        got = np.array([complex(v[2 * k], v[2 * k + 1]) * step / scale if not singular[k] else 0j
                        for k in range(len(phi))])
        error = np.max(np.abs(got - np.where(singular, 0, exact)))
        assert error <= step / scale * math.sqrt(2) / 2 * (1 + 1e-9), f"{data['arrows'][index]['label']}: off by {error}"
        # the longest arrow of a kind is drawn a quarter of the mechanism's size long: the larger side of the box
        # round its joints over the turn, here x from −1 m (A at 180°) to 4 m (B at 0°): 5 m
        longest = np.max(np.abs(got)) * scale
        assert longest == pytest.approx(0.25 * 5.0, rel=2e-3)


def test_json_is_strict_for_a_family_with_partial_members_and_arrows():
    s = four_bar_family(arrows=[velocity("B"), acceleration("B")],
                        readout=[Readout("ω_3", "rad/s", lambda sol, m: sol.angle("rocker").omega, 3, order=1)])
    stored_ok_without_nan(s)
    script = re.search(r'<script type="application/json" class="mech-scene">(.*?)</script>', s.html(), re.S)
    assert script and json.loads(script.group(1)) == json.loads(s.json())


# --- the still image -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", list(MECHANISMS))
def test_still_is_svg_with_one_hinge_per_joint(name):
    m = MECHANISMS[name]()
    s = scene(m, paths=["B"], arrows=[velocity("A")], title="a <title> & more")
    svg = still_svg(s)
    assert svg.tag == f"{SVG}svg" and "mech-still" in svg.get("class").split()
    hinges = by_class(svg, "mech-hinge")
    names = [h.get("data-joint") for h in hinges]
    assert sorted(names) == sorted(joints_of(m)), f"hinges {names}, joints {sorted(joints_of(m))}"
    bars = [item for item in m.scheme() if isinstance(item, Bar)]
    assert len(by_class(svg, "mech-bar")) == len(bars)
    assert len(by_class(svg, "mech-path")) == 1
    # each hinge is where its joint is at the still's frame (written to 6 significant digits: well within a step)
    member, frame = s.still
    for hinge in hinges:
        where = s.position(hinge.get("data-joint"), member)[frame]
        assert float(hinge.get("cx")) == pytest.approx(where.real, abs=s.data["step"] / 2)
        assert float(hinge.get("cy")) == pytest.approx(where.imag, abs=s.data["step"] / 2)


def test_still_of_an_explorer_shows_the_chosen_member():
    s = four_bar_family(still={"crank": 3.0})
    member, frame = s.still
    assert member == s.member_index(crank=3.0)
    assert s.data["members"][member]["valid"][frame] == "1", "the still frame is one where the member does not assemble"
    assert len(by_class(still_svg(s), "mech-hinge")) == 4


def test_still_has_every_joint_when_the_first_member_does_not_assemble():
    # a coupler of 1.0 m cannot close the loop with the rocker (1 m) over C at 4 m: the first member never
    # assembles; the still (and so the player, which moves the still's elements) must still have the
    # four joints
    s = explorer(lambda coupler: mech.FourBar(1.0, coupler, 1.0, frame=(4.0, 0.0)),
                 [Parameter("coupler", "L₂", "m", [1.0, 2.5, 3.5])])
    assert s.data["members"][0]["valid"] == "0" * 72
    hinges = sorted(h.get("data-joint") for h in by_class(still_svg(s), "mech-hinge"))
    assert hinges == ["A", "B", "C", "O"], \
        f"the still of an explorer whose first member does not assemble has hinges {hinges}"


def test_a_still_of_a_member_that_assembles_nowhere_is_refused():
    # the coupler of 1.0 m and the rocker of 1 m reach at most 2 m from C, |AC| >= 4 - 1 = 3 m: no frame
    with pytest.raises(mech.InvalidParameterError, match=r"still must be .*assembles at a frame"):
        explorer(lambda coupler: mech.FourBar(1.0, coupler, 1.0, frame=(4.0, 0.0)),
                 [Parameter("coupler", "L₂", "m", [1.0, 2.5, 3.5])], still={"coupler": 1.0})


def test_still_has_every_joint_at_a_still_angle_where_it_does_not_assemble():
    s = scene(mech.FourBar(3.0, 1.4, 2.5, frame=(2.0, 0.0)), still_angle=0.0)   # assembles for |φ| in [11°, 101°]
    hinges = sorted(h.get("data-joint") for h in by_class(still_svg(s), "mech-hinge"))
    assert hinges == ["A", "B", "C", "O"], f"still at a crank angle where it does not assemble: hinges {hinges}"


# --- sizes -----------------------------------------------------------------------------------------------------

def coupler_readout():
    return [Readout("ψ", "°", lambda sol, m: np.degrees(sol.angle("coupler").value), 1)]


def test_a_four_bar_scene_is_light():
    s = scene(mech.FourBar(1.0, 3.5, 3.0, frame=(4.0, 0.0)), frames=72, paths=["B"], readout=coupler_readout())
    assert s.nbytes < 20_000, f"a 72-frame four-bar scene weighs {s.nbytes} bytes"
    assert s.nbytes == len(s.html().encode())


def test_a_point_that_does_not_move_is_stored_once_and_read_at_every_frame():
    # the four-bar's pivots O = (0, 0) and C = (4, 0) m (given, not computed) are stored as one pair each
    s = scene(mech.FourBar(1.0, 3.5, 3.0, frame=(4.0, 0.0)), frames=72, paths=["B"])
    xy = s.data["members"][0]["xy"]
    assert len(xy["O"]) == 2 and len(xy["C"]) == 2 and len(xy["B"]) == 2 * 72
    step = s.data["step"]
    for name, where in (("O", 0.0), ("C", 4.0 + 0.0j)):
        assert np.all(np.abs(s.position(name) - where) <= step), name
    assert 'data-joint="C"' in s.html() and re.search(r'cx="4(\.0*)?"', s.html()) is not None


def test_bytes_grow_linearly_with_members():
    def family(n):
        return explorer(lambda coupler: mech.FourBar(1.0, coupler, 3.0, frame=(4.0, 0.0)),
                        [Parameter("coupler", "L₂", "m", list(np.linspace(3.2, 4.5, n)))], paths=["B"],
                        readout=coupler_readout()).nbytes

    sizes = {n: family(n) for n in (1, 5, 10, 20)}
    per_member = [(sizes[b] - sizes[a]) / (b - a) for a, b in ((1, 5), (5, 10), (10, 20))]
    assert max(per_member) <= 1.25 * min(per_member), f"bytes by members {sizes}: per member {per_member}"
    assert max(per_member) < 6_000, f"a member of 72 frames costs {max(per_member):.0f} bytes"
    # the budget of a page (1 MB) holds a two-parameter explorer of 100 members with room to spare
    assert sizes[1] + 99 * max(per_member) < 700_000, sizes


# --- bad input ------------------------------------------------------------------------------------------------

def test_bad_input_raises_invalid_parameter_error():
    m = mech.FourBar(1.0, 3.5, 3.0, frame=(4.0, 0.0))
    assert issubclass(mech.InvalidParameterError, mech.MechanismError)
    for frames in (0, -5, 3601):
        with pytest.raises(mech.InvalidParameterError):
            scene(m, frames=frames)
    three = [Parameter(name, name, "m", [1.0, 2.0]) for name in ("crank", "coupler", "rocker")]
    with pytest.raises(mech.InvalidParameterError):
        explorer(lambda crank, coupler, rocker: mech.FourBar(crank, coupler, rocker, frame=(4.0, 0.0)), three)
    # no member closes its loop: the coupler and rocker together are shorter than |AC| ≥ 4 − 1 m
    with pytest.raises(mech.InvalidParameterError):
        explorer(lambda coupler: mech.FourBar(1.0, coupler, 1.0, frame=(4.0, 0.0)),
                 [Parameter("coupler", "L₂", "m", [0.5, 1.0, 1.5])])
    with pytest.raises(mech.InvalidParameterError):
        scene(mech.FourBar(1.0, 0.5, 0.5, frame=(5.0, 0.0)))


def test_member_index_of_values_not_in_the_explorer_raises_invalid_parameter_error():
    s = four_bar_family()
    assert s.member_index(crank=2.2) == 2
    with pytest.raises(mech.InvalidParameterError):
        s.member_index(crank=2.0)            # not one of the slider's values
    with pytest.raises(mech.InvalidParameterError):
        s.member_index(rod=0.5)              # not a parameter of this explorer


def test_labels_can_use_the_pages_letters_while_the_player_keeps_the_joints():
    lever = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.3))
    html = scene(lever, frames=8, labels={"C": "O_1"}).html()
    label = re.search(r'<text class="mech-label" data-joint="C"[^>]*>(.*?)</text>', html).group(1)
    assert label.startswith("O<tspan") and ">1</tspan>" in label   # O with a subscript 1
    plain = scene(lever, frames=8).html()
    assert re.search(r'data-joint="C"[^>]*>C</text>', plain)
    assert plain.count('class="mech-label"') == html.count('class="mech-label"')


def test_a_link_can_have_a_colour_of_its_own_in_the_scene_and_its_still():
    rockers = mech.SlottedRockers(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2)
    brown = "#8C564B"
    s = scene(rockers, frames=8, colours={"rocker": brown})
    bars = {part["link"]: part["colour"] for part in s.data["parts"] if "bar" in part}
    assert bars == {"lever": "#2ca02c", "crank": "#1f77b4", "rocker": "#8c564b"}
    plain = {part["link"]: part["colour"] for part in scene(rockers, frames=8).data["parts"] if "bar" in part}
    assert plain["rocker"] == "#2ca02c"                  # by role, the lever's green, without the option
    assert 'stroke="#8c564b"' in s.html()


@pytest.mark.parametrize("colours, cause", [({"slot": "#8c564b"}, "no link 'slot'"),
                                            ({"rocker": "brown"}, "'rocker' has 'brown'"),
                                            ({"rocker": "#8c564"}, "'rocker' has '#8c564'")])
def test_a_colour_for_a_link_the_mechanism_lacks_or_not_hex_is_refused(colours, cause):
    rockers = mech.SlottedRockers(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2)
    with pytest.raises(mech.InvalidParameterError, match="colours") as caught:
        scene(rockers, frames=8, colours=colours)
    assert cause in str(caught.value)


# --- the same scene on every processor ---------------------------------------------------------------------

def nudged_numpy(seed: int) -> dict:
    """numpy's elementary functions one ulp off at random (tools/nudge_numpy.py): another processor's."""
    import pathlib
    import sys
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tools"))
    try:
        from nudge_numpy import nudged_functions
    finally:
        sys.path.pop(0)
    return nudged_functions(seed)


def test_a_scene_does_not_change_when_numpys_elementary_functions_move_by_an_ulp(monkeypatch):
    # A four-bar explorer with velocity and acceleration arrows (their scales come from |v|, numpy's absolute
    # value of complex numbers) and a coupler point: positions and vectors differ in their last bits from
    # processor to processor; what a scene stores must not (the chapter 8 explorer failed at numpy's baseline).
    def build(rod):
        return mech.FourBar(0.1, rod, 0.3, (0.4, 0.05), branch=1)

    def make():
        return explorer(build, [Parameter("rod", "L_2", "m", [0.33, 0.35, 0.37])], frames=36,
                        arrows=[velocity("B"), acceleration("B")], points={"P": mech.present.On("coupler", 0.2, 0.05)},
                        paths=["P"]).json()

    expected = make()
    data = json.loads(expected)
    # the numbers computed from the whole figure are stored to 6 significant digits
    for value in [data["step"] * 4000, data["size"] / 0.025, *data["scales"].values()]:
        assert value == float(f"{value:.6g}")
    for seed in range(3):
        with monkeypatch.context() as patch:
            for name, function in nudged_numpy(seed).items():
                patch.setattr(np, name, function)
            moved = make()
        assert moved == expected, f"seed {seed}"
