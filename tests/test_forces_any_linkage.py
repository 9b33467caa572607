"""Forces by Assur groups for any linkage of class II groups (issue 29, item 4).

The group-by-group results of :func:`mechanisms.analysis.kinetostatics.joint_forces` are compared with
computations that share none of its code:

* one Newton–Euler system of ALL bodies at once (three equations per body — force x, y and moment —
  every hinge's two components, every sliding pair's normal force and moment, and M_d as unknowns),
  assembled here from the linkage's own list of pairs (``Linkage.pairs()``) and solved by
  ``numpy.linalg.solve`` position by position;
* the power balance (virtual work): ``M_d ω₁ + Σ F·v_P + Σ T ω + Σ(−m a_S·v_S − J_S ε ω) − Σ m g v_Sy = 0``
  from the kinematic solution alone;
* hand statics of the issue's two cases.
"""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import energy, kinetostatics
from mechanisms.core.errors import InvalidParameterError, StructureError
from mechanisms.linkages.groups import link_numbers
from mechanisms.linkages.linkage_file import example_file, linkage_from_dict

PHI = np.linspace(0.1, 0.1 + 2 * np.pi, 24, endpoint=False)


def _cross(a, b):
    return a.real * b.imag - a.imag * b.real


# --- linkage files with masses, loads and gravity --------------------------------------------------------------

def _with_masses(data: dict, gravity: float = 9.81, seed: int = 1) -> dict:
    """The linkage data with a mass on every link and block, a force and a torque on two bodies, and gravity."""
    data = copy.deepcopy(data)
    linkage = linkage_from_dict(data)
    rng = np.random.default_rng(seed)
    names = [name for name in linkage.link_joints() if name != "frame"]
    data["mass"] = [{"body": name, "mass": float(rng.uniform(0.5, 3.0)), "along": float(rng.uniform(-0.05, 0.2)),
                     "left": float(rng.uniform(-0.05, 0.05)), "inertia": float(rng.uniform(0.001, 0.05))}
                    for name in names]
    data["load"] = [{"body": names[-1], "force": [float(rng.uniform(-300, 300)), float(rng.uniform(-300, 300))],
                     "along": 0.05, "left": -0.02},
                    {"body": names[len(names) // 2], "torque": float(rng.uniform(-20, 20))}]
    data["gravity"] = gravity
    return data


def _example(name: str) -> dict:
    with open(example_file(name), "rb") as handle:
        return tomllib.load(handle)


FOUR_BAR_CA = {"name": "four-bar from C, A", "frame": {"O": [0.0, 0.0], "C": [0.4, 0.05]},
               "crank": {"pivot": "O", "pin": "A", "length": 0.1},
               "dyad": [{"type": "RRR", "joint": "B", "from": ["C", "A"], "lengths": [0.3, 0.35], "branch": -1,
                         "links": ["rocker", "coupler"]}]}

GUIDE_ON_CRANK = {"name": "block on a guide of the crank", "frame": {"O": [0.0, 0.0], "D": [0.25, 0.1]},
                  "crank": {"pivot": "O", "pin": "A", "length": 0.1},
                  "dyad": [{"type": "RRP", "joint": "B", "from": "D", "length": 0.35,
                            "guide": {"through": "O", "toward": "A", "angle_deg": 0.0}, "links": ["rod", "block"]}]}

RPP = {"name": "yoke", "frame": {"O": [0.0, 0.0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.1},
       "dyad": [{"type": "RPP", "joint": "Y", "block": "A", "guide": {"through": [0.0, -0.05], "angle_deg": 20.0},
                 "slot_angle_deg": 75.0, "links": ["block", "yoke"]}]}

PRP = {"name": "two blocks", "frame": {"O": [0.0, 0.0], "C": [0.45, 0.1]},
       "crank": {"pivot": "O", "pin": "A", "length": 0.1},
       "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [0.35, 0.3], "links": ["coupler", "rocker"]},
                {"type": "PRP", "joint": "K", "guides": [{"through": "C", "toward": "B", "angle_deg": 10.0},
                                                         {"through": [0.2, 0.0], "angle_deg": 80.0}],
                 "links": ["K1", "K2"]}]}

GUIDE_ON_ROCKER = {"name": "slider on the rocker", "frame": {"O": [0.0, 0.0], "C": [0.45, 0.1]},
                   "crank": {"pivot": "O", "pin": "A", "length": 0.1},
                   "dyad": [{"type": "RRR", "joint": "B", "from": ["A", "C"], "lengths": [0.35, 0.3],
                             "links": ["coupler", "rocker"]},
                            {"type": "RRP", "joint": "H", "from": "A", "length": 0.6,
                             "guide": {"through": "C", "toward": "B", "angle_deg": 0.0}, "links": ["rod", "H"]}]}

CASES = {name: _example(name) for name in ("watt-six-bar", "stephenson-six-bar", "shaper", "scotch-yoke",
                                            "beam-pump", "jansen", "format-example")}
CASES |= {"four-bar-CA": FOUR_BAR_CA, "guide-on-crank": GUIDE_ON_CRANK, "rpp": RPP, "prp": PRP,
          "guide-on-rocker": GUIDE_ON_ROCKER}


def _solve(linkage, omega=12.0, alpha=-3.0):
    return linkage.solve(PHI, omega, alpha)


# --- the independent computation: one Newton–Euler system of every body -------------------------------------------

class Bodies:
    """Geometry of each body as the test reads it from the linkage (not from kinetostatics)."""

    def __init__(self, linkage, solution):
        self.linkage, self.solution = linkage, solution
        self.items = {name: item for name, item in linkage._links.items() if name != "frame"}

    def turns(self, name):
        return name in self.solution.angle_names

    def point(self, name, along, left):
        item = self.items[name]
        if self.turns(name):
            return self.solution.point_on(name, along, left)
        return self.solution.point(item.pole) + complex(along, left)

    def alpha(self, name):
        return self.solution.angle(name).alpha if self.turns(name) else 0.0

    def omega(self, name):
        return self.solution.angle(name).omega if self.turns(name) else 0.0

    def direction(self, name):
        if self.turns(name):
            return np.exp(1j * self.solution.angle(name).value)
        return np.exp(1j * self.linkage._block_angle(name)) * np.ones(PHI.shape)

    def resolve(self, body):
        if body in self.items:
            return body
        blocks = [n for n, item in self.items.items() if item.role == "slider" and item.pole == body]
        assert len(blocks) == 1, body
        return blocks[0]


def newton_euler(linkage, solution):
    """M_d, the hinge forces by (joint, giver, taker) and the sliding pairs' (N, M) by block, from all bodies at once."""
    bodies = Bodies(linkage, solution)
    number = link_numbers(linkage.groups())
    names = list(bodies.items)
    rows = {name: 3 * i for i, name in enumerate(names)}
    pairs = linkage.pairs()
    size = 2 * len(pairs) + 1
    assert 3 * len(names) == size, "a linkage of W = 1: 3n = 2p + 1"
    n = PHI.size
    A = np.zeros((n, size, size))
    b = np.zeros((n, size))
    reference = {name: solution.point(bodies.items[name].pole).value for name in names}

    def put(body, column, force, point, couple=0.0, sign=1.0):
        """Unknown column's unit contribution (a force ``force`` at ``point`` and a couple) on ``body``."""
        if body == "frame":
            return
        r = rows[body]
        A[:, r, column] += sign * np.real(force)
        A[:, r + 1, column] += sign * np.imag(force)
        A[:, r + 2, column] += sign * (_cross(point - reference[body], force) + couple)

    def known(body, force, point, couple=0.0):
        r = rows[body]
        b[:, r] -= np.real(force)
        b[:, r + 1] -= np.imag(force)
        b[:, r + 2] -= _cross(point - reference[body], force) + couple

    columns = {}
    for k, pair in enumerate(pairs):
        giver, taker = sorted((pair.first, pair.second), key=lambda x: number[x])
        at = solution.point(pair.joint).value
        c = 2 * k
        if pair.kind == "R":
            for body, sign in ((taker, 1.0), (giver, -1.0)):
                put(body, c, 1.0 + 0j, at, sign=sign)
                put(body, c + 1, 1j, at, sign=sign)
            columns[(pair.joint, giver, taker)] = c
        else:
            block = next(x for x in (pair.first, pair.second)
                         if x != "frame" and bodies.items[x].role == "slider" and bodies.items[x].pole == pair.joint)
            normal = 1j * bodies.direction(block)
            for body, sign in ((taker, 1.0), (giver, -1.0)):
                put(body, c, normal, at, sign=sign)
                put(body, c + 1, 0j, at, couple=1.0, sign=sign)
            columns[block] = c
    crank = linkage.groups()[0]
    A[:, rows[crank.link] + 2, size - 1] = 1.0
    masses = energy._file_masses(linkage)
    for body, props in masses.items():
        name = bodies.resolve(body)
        centre = bodies.point(name, props.along, props.left)
        known(name, -props.mass * centre.acceleration - 1j * props.mass * linkage.gravity, centre.value,
              -props.inertia * bodies.alpha(name))
    for load in linkage.loads:
        name = bodies.resolve(load["body"])
        if "torque" in load:
            known(name, 0j, reference[name], load["torque"])
        else:
            point = bodies.point(name, load["along"], load["left"]).value
            known(name, complex(*load["force"]), point)
    u = np.linalg.solve(A, b[..., None])[..., 0]
    hinges = {key: u[:, c] + 1j * u[:, c + 1] for key, c in columns.items() if isinstance(key, tuple)}
    slides = {key: (u[:, c], u[:, c + 1]) for key, c in columns.items() if isinstance(key, str)}
    return u[:, -1], hinges, slides


def _close(found, expected, scale):
    assert np.abs(found - expected).max() <= 1e-9 * scale, np.abs(found - expected).max() / scale


@pytest.mark.parametrize("name", sorted(CASES))
def test_group_by_group_equals_one_system_of_all_bodies(name):
    linkage = linkage_from_dict(_with_masses(CASES[name]), f"{name}.toml")
    solution = _solve(linkage)
    result = kinetostatics.linkage_forces(linkage, solution)
    torque, hinges, slides = newton_euler(linkage, solution)
    scale = max(np.abs(f).max() for f in hinges.values()) + np.abs(torque).max()
    _close(result.driving_torque, torque, scale)
    at_joint = {}
    for joint, _, _ in hinges:
        at_joint[joint] = at_joint.get(joint, 0) + 1
    for (joint, giver, taker), force in hinges.items():
        key = joint if at_joint[joint] == 1 else f"{joint}:{giver}/{taker}"
        assert result.bodies[key] == (giver, taker)
        _close(result.forces[key], force, scale)
    assert set(result.forces) == {j if at_joint[j] == 1 else f"{j}:{g}/{t}" for j, g, t in hinges}
    assert set(result.sliding) == set(slides)
    for block, (N, M) in slides.items():
        _close(result.sliding[block].magnitude, N, scale)
        _close(result.sliding[block].moment, M, scale)


@pytest.mark.parametrize("name", sorted(CASES))
def test_power_balance_of_every_linkage(name):
    # virtual work: the joint forces do no work, so M_d ω₁ + the loads' power + the inertia forces' power
    # + the weights' power = 0, every term from the kinematic solution alone
    linkage = linkage_from_dict(_with_masses(CASES[name], seed=7), f"{name}.toml")
    omega = -9.0
    solution = _solve(linkage, omega, 4.0)
    bodies = Bodies(linkage, solution)
    result = kinetostatics.linkage_forces(linkage, solution)
    power = result.driving_torque * omega
    scale = np.abs(power).max()
    for body, props in energy._file_masses(linkage).items():
        name_ = bodies.resolve(body)
        centre = bodies.point(name_, props.along, props.left)
        inertia = -props.mass * centre.acceleration - 1j * props.mass * linkage.gravity
        parts = (np.real(np.conj(centre.velocity) * inertia),
                 -props.inertia * bodies.alpha(name_) * bodies.omega(name_))
        power = power + parts[0] + parts[1]
        scale = max(scale, np.abs(parts[0]).max(), np.abs(parts[1]).max())
    for load in linkage.loads:
        name_ = bodies.resolve(load["body"])
        if "torque" in load:
            part = load["torque"] * bodies.omega(name_)
        else:
            velocity = bodies.point(name_, load["along"], load["left"]).velocity
            part = np.real(np.conj(velocity) * complex(*load["force"]))
        power = power + part
        scale = max(scale, np.abs(part).max())
    assert np.abs(power).max() <= 1e-9 * scale


# --- the two cases, by hand ------------------------------------------------------------------------------

def test_four_bar_written_from_C_A_by_virtual_work_and_as_its_named_twin():
    # massless, at rest, a torque T on the rocker: M_d φ_t + T ξ_t = 0, so M_d = −T ξ_t/φ_t (ξ_t from the kinematics)
    data = copy.deepcopy(FOUR_BAR_CA) | {"load": [{"body": "rocker", "torque": -8.0}]}
    linkage = linkage_from_dict(data)
    solution = linkage.solve(PHI, 1.0)
    result = kinetostatics.linkage_forces(linkage, solution)
    ratio = solution.angle("rocker").omega / solution.angle("crank").omega
    assert np.allclose(result.driving_torque, 8.0 * ratio, rtol=1e-12, atol=1e-12)
    # the coupler is a two-force member: the force at A (crank on coupler) lies along A–B
    AB = solution.point("B").value - solution.point("A").value
    assert np.abs(_cross(AB / np.abs(AB), result.force("A"))).max() <= 1e-12 * np.abs(result.force("A")).max()
    # the named four-bar with the same geometry: B to the left of A → C, as B is to the right of C → A here
    named = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05), branch=1)
    named_solution = named.solve(PHI, 1.0)
    assert np.allclose(named_solution.point("B").value, solution.point("B").value, rtol=0, atol=1e-13)
    twin = kinetostatics.joint_forces(named, named_solution, {}, [energy.Torque("rocker", -8.0)], gravity=0.0)
    assert np.allclose(twin.driving_torque, result.driving_torque, rtol=1e-12, atol=1e-12)
    # the hinge at B: the rocker (body 2 here) on the coupler (body 3); in the named one coupler on rocker
    assert result.bodies["B"] == ("rocker", "coupler") and twin.bodies["B"] == ("coupler", "rocker")
    assert np.allclose(result.force("B"), -twin.force("B"), rtol=1e-12, atol=1e-9)


def test_block_on_a_guide_of_the_crank_by_virtual_work():
    # massless, a torque T on the rod D–B: M_d = −T θ_t/φ_t; and the block on the crank's guide: the crank and the
    # block turn together, so a torque on the block is the crank's own business: M_d = −T
    linkage = linkage_from_dict(copy.deepcopy(GUIDE_ON_CRANK) | {"load": [{"body": "rod", "torque": 5.0}]})
    solution = linkage.solve(PHI, 3.0)
    result = kinetostatics.linkage_forces(linkage, solution)
    ratio = solution.angle("rod").omega / 3.0
    assert np.allclose(result.driving_torque, -5.0 * ratio, rtol=1e-12, atol=1e-12)
    block = linkage_from_dict(copy.deepcopy(GUIDE_ON_CRANK) | {"load": [{"body": "block", "torque": 5.0}]})
    on_block = kinetostatics.linkage_forces(block, block.solve(PHI, 3.0))
    assert np.allclose(on_block.driving_torque, -5.0, rtol=1e-12)
    # the rod's moment about B (the block's hinge): (D − B) × R_D + T = 0, so (B − D) × R_D = T
    DB = solution.point("B").value - solution.point("D").value
    assert np.allclose(_cross(DB, result.force("D")), 5.0, rtol=1e-12)


def test_a_named_crank_slider_and_its_linkage_file_twin_give_the_same_forces():
    named = mech.CrankSlider(0.08, 0.3, 0.02)
    masses = {"crank": energy.LinkMass(2.0, 0.02, 0.0, 0.004), "coupler": energy.LinkMass(1.5, 0.1, 0.01, 0.02),
              "B": energy.LinkMass(1.2)}
    loads = [energy.Force("B", -500.0), energy.Torque("coupler", 3.0)]
    data = {"frame": {"O": [0.0, 0.0]}, "crank": {"pivot": "O", "pin": "A", "length": 0.08},
            "dyad": [{"type": "RRP", "joint": "B", "from": "A", "length": 0.3,
                      "guide": {"through": [0.0, 0.02], "angle_deg": 0.0}, "links": ["coupler", "slider"]}],
            "mass": [{"body": "crank", "mass": 2.0, "along": 0.02, "inertia": 0.004},
                     {"body": "coupler", "mass": 1.5, "along": 0.1, "left": 0.01, "inertia": 0.02},
                     {"body": "slider", "mass": 1.2}],
            "load": [{"body": "B", "force": [-500.0, 0.0]}, {"body": "coupler", "torque": 3.0}], "gravity": 9.81}
    linkage = linkage_from_dict(data)
    one = kinetostatics.joint_forces(named, named.solve(PHI, 50.0, 2.0), masses, loads, 9.81)
    two = kinetostatics.linkage_forces(linkage, linkage.solve(PHI, 50.0, 2.0))
    scale = np.abs(one.driving_torque).max()
    assert np.abs(one.driving_torque - two.driving_torque).max() <= 1e-12 * scale
    for joint in "OAB":
        assert np.abs(one.force(joint) - two.force(joint)).max() <= 1e-12 * scale * 100
    assert np.abs(one.force("guide") - two.sliding["slider"].force).max() <= 1e-12 * scale * 100


# --- what it refuses -------------------------------------------------------------------------------------------------

def test_a_triad_is_refused_naming_the_group():
    data = {"frame": {"O": [0.0, 0.0], "C": [0.4, 0.0], "G": [0.2, -0.3]},
            "crank": {"pivot": "O", "pin": "A", "length": 0.1},
            "triad": [{"joints": ["D", "E", "F"], "guess": {"D": [-0.01, -0.28], "E": [0.17, -0.19], "F": [0.0, -0.08]},
                       "bars": [["A", "D", 0.3], ["C", "E", 0.3], ["G", "F", 0.3], ["D", "E", 0.2], ["E", "F", 0.2],
                                ["D", "F", 0.2]]}]}
    linkage = linkage_from_dict(data, "triad.toml")
    solution = linkage.solve([0.0], 1.0)
    with pytest.raises(StructureError, match=r"group D, E, F .*class III"):
        kinetostatics.linkage_forces(linkage, solution)


def test_unknown_bodies_are_named_with_the_known_ones():
    linkage = linkage_from_dict(copy.deepcopy(CASES["shaper"]))
    solution = linkage.solve(PHI, 5.0)
    with pytest.raises(InvalidParameterError, match=r"crank, block, lever, rod, ram, A, G.*'nope'"):
        kinetostatics.joint_forces(linkage, solution, {"nope": energy.LinkMass(1.0)})
    with pytest.raises(InvalidParameterError, match="given once"):
        kinetostatics.joint_forces(linkage, solution, {"ram": energy.LinkMass(1.0), "G": energy.LinkMass(1.0)})


def test_massless_unloaded_linkage_has_zero_forces():
    linkage = linkage_from_dict(copy.deepcopy(CASES["watt-six-bar"]))
    result = kinetostatics.linkage_forces(linkage, linkage.solve(PHI, 10.0))
    assert not np.any(result.driving_torque) and all(not np.any(f) for f in result.forces.values())


def test_force_rows_and_columns_for_the_command_line():
    linkage = linkage_from_dict(_with_masses(CASES["shaper"]))
    solution = linkage.solve(PHI[:3], 10.0)
    result = kinetostatics.linkage_forces(linkage, solution)
    rows = kinetostatics.force_rows(result)
    assert len(rows) == 3
    assert rows[1]["driving_torque"] == float(result.driving_torque[1])
    assert rows[2]["joints"]["B"] == {"Fx": float(result.forces["B"][2].real), "Fy": float(result.forces["B"][2].imag)}
    assert set(rows[0]["sliding"]) == {"block", "ram"}
    flat = kinetostatics.force_columns(rows[0])
    assert flat["forces.driving_torque"] == rows[0]["driving_torque"]
    assert flat["forces.sliding.ram.N"] == rows[0]["sliding"]["ram"]["N"]


@pytest.mark.parametrize("mechanism", [mech.SlottedLever.example(), mech.Shaper.example()],
                         ids=["slotted-lever", "shaper"])
def test_named_slotted_mechanisms_go_through_the_same_code(mechanism):
    # the independent route: the power balance of chapter 7, M_d = (dT/dt + dV/dt − P_loads)/φ_t
    masses = {"lever": energy.LinkMass(2.0, 0.2, 0.01, 0.1), "crank": energy.LinkMass(1.0, 0.1, 0.0, 0.02)}
    loads = [energy.Force("A", 3.0 + 1.0j), energy.Torque("lever", -2.0)]
    solution = mechanism.solve(PHI, 10.0, 1.0)
    result = kinetostatics.joint_forces(mechanism, solution, masses, loads, 9.81)
    expected = energy.driving_torque(solution, masses, loads, 9.81)
    assert np.abs(result.driving_torque - expected).max() <= 1e-10 * np.abs(expected).max()
