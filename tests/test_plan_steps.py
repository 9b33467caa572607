"""Tests of the order of construction of a plan (analysis.plans.plan_steps) and its drawing step by step
(plot.plans.draw_plan_step, draw_plan_steps, step_caption)."""

import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import mechanisms as mech
from mechanisms.analysis import plans
from mechanisms.core.errors import InvalidParameterError
from mechanisms.plot import plans as plot_plans

EXAMPLE = mech.CrankSlider(crank=0.08, rod=0.3)          # the textbook's Example 5.2
S2 = {"S2": ("coupler", 0.09, 0.0)}


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _example(phi_deg=30.0):
    sol = EXAMPLE.solve(np.radians([phi_deg]), omega=215.0)
    v = plans.velocity_plan(EXAMPLE, sol, points=S2)
    return sol, v, plans.acceleration_plan(EXAMPLE, sol, points=S2, velocity=v)


def _cross(u, v):
    return u.real * v.imag - u.imag * v.real


def test_crank_slider_steps_follow_the_hand_construction():
    # by hand (chapter 10): p → a; b where the line ⊥ AB through a meets the guide through p; s2 by the image.
    # Accelerations: π → a′; a′ → n2; b′ where the line ⊥ AB through n2 meets the guide through π; s2′.
    _, v, a = _example()
    steps = plans.plan_steps(v)
    assert [s.vertex for s in steps] == ["a", "b", "s2"]
    assert [s.vectors for s in steps] == [("v_A",), ("v_BA", "v_B"), ("v_S2",)]
    assert steps[0].lines == () and steps[2].lines == ()
    (through1, d1, name1), (through2, d2, name2) = steps[1].lines
    assert (through1, name1, through2, name2) == ("a", "v_BA", "p", "v_B")
    # the coupler at φ = 30°: sin ψ = −L1 sin φ / L2 = −0.04/0.3 (hand), so AB = (cos ψ, sin ψ)
    sin_psi = -0.04 / 0.3
    ab = complex(math.sqrt(1 - sin_psi**2), sin_psi)
    assert abs(_cross(d1, 1j * ab)) < 1e-12 and abs(d1) == pytest.approx(1.0)    # ⊥ AB
    assert abs(_cross(d2, 1.0)) < 1e-12                                           # along the guide (x)
    assert [s.vertex for s in plans.plan_steps(a)] == ["a′", "n2", "b′", "s2′"]
    third = plans.plan_steps(a)[2]
    assert [(t, n) for t, _, n in third.lines] == [("n2", "a^t_BA"), ("π", "a_B")]


def test_every_intersection_lies_on_its_lines_and_is_the_closed_form_value():
    # the lines of a step pass through its vertex, and the vertex is the closed-form velocity (acceleration)
    machines = [EXAMPLE, mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05)), mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25)),
                mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22)]
    for machine in machines:
        sol = machine.solve(np.radians([20.0, 110.0, 250.0]), omega=10.0, alpha=4.0)
        for k in range(3):
            v = plans.velocity_plan(machine, sol, index=k)
            a = plans.acceleration_plan(machine, sol, index=k, velocity=v)
            for plan in (v, a):
                steps = plans.plan_steps(plan)
                # every vertex but the pole is found once, every vector drawn once
                assert sorted(s.vertex for s in steps) == sorted(set(plan.vertices) - {plan.pole})
                assert sorted(n for s in steps for n in s.vectors) == sorted(x.name for x in plan.vectors)
                size = max(abs(z) for z in plan.vertices.values())
                for step in steps:
                    if step.lines:
                        assert len(step.lines) == 2
                    for through, direction, _ in step.lines:
                        gap = plan.vertices[step.vertex] - plan.vertices[through]
                        assert abs(_cross(direction, gap)) <= 1e-9 * size
    # the slotted lever's A3: ξ_t (L e^{iξ})·i from the closed form of chapter 5, by the generic solver
    sl = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25))
    sol = sl.solve(np.radians([64.0]), omega=10.0)
    v = plans.velocity_plan(sl, sol)
    generic = mech.verify.solve_generic(sl, np.radians([64.0]), omega=10.0)
    lever = sol.point("A").value[0] - 0.25j
    step = [s for s in plans.plan_steps(v) if s.vertex == "a3"][0]
    assert v.vertices[step.vertex] == pytest.approx(1j * generic.q_t[0, 0] * lever, abs=1e-12)


def test_the_slotted_lever_coriolis_step_uses_chapter_5_s_sense():
    # a^k_A2A3 = 2iω₃ v_A2A3 ends at the block's vertex a′, so k = a′ − a^k is drawn before the intersection
    sl = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25))
    sol = sl.solve(np.radians([64.0]), omega=10.0)
    v = plans.velocity_plan(sl, sol)
    a = plans.acceleration_plan(sl, sol, velocity=v)
    steps = plans.plan_steps(a)
    assert [s.vertex for s in steps] == ["a′", "k", "n3", "a3′", "b′"]
    coriolis = a.vector("a^k_A2A3")
    assert (coriolis.tail, coriolis.head) == ("k", "a′")
    # chapter 5: 2ω₃L_t, the signed size across the lever, here 5.974 m/s² at 64° (chapter 5's largest value)
    assert abs(coriolis.value) == pytest.approx(abs(sol.coriolis("A")[0]), rel=1e-12)
    assert abs(coriolis.value) == pytest.approx(5.974, abs=5e-4)
    assert [(t, n) for t, _, n in steps[3].lines] == [("n3", "a^t_A3C"), ("k", "a^r_A2A3")]
    assert plot_plans.step_caption(a, steps[1]) == "draw $a^{k}_{A_{2}A_{3}}$ to end at $a'$: it starts at $k$"


def test_at_the_dead_centre_the_lines_keep_their_directions():
    # at φ = 0 the slider stops: v_B = 0 and v_BA = v_A, yet the guide's line through p is still along x
    _, v, _ = _example(0.0)
    step = plans.plan_steps(v)[1]
    directions = {name: d for _, d, name in step.lines}
    assert abs(_cross(directions["v_B"], 1.0)) < 1e-12
    assert v.of("B") == pytest.approx(0.0, abs=1e-12)


def test_captions_say_what_each_step_does():
    _, v, a = _example()
    texts = [plot_plans.step_caption(v, s) for s in plans.plan_steps(v)]
    assert texts == ["from $p$ draw $v_{A}$, to $a$",
                     "the lines of $v_{BA}$ through $a$ and of $v_{B}$ through $p$ meet at $b$",
                     "$s_{2}$ by the image of its link; draw $v_{S_{2}}$"]
    assert plot_plans.step_caption(a, plans.plan_steps(a)[1]) == "from $a'$ draw $a^{n}_{BA}$, to $n_{2}$"


def test_a_step_is_drawn_with_the_vectors_so_far_and_its_lines():
    _, v, a = _example()
    ax = plot_plans.draw_plan_step(a, 3)
    arrows = [t for t in ax.texts if getattr(t, "arrow_patch", None) is not None]
    assert len(arrows) == 4                         # a_A, a^n_BA, a^t_BA, a_B; not yet a_S2
    dotted = [line for line in ax.lines if line.get_linestyle() == ":"]
    assert len(dotted) == 2                          # the line ⊥ AB through n2 and the guide through π
    assert ax.get_title().startswith("step 3: the lines of")
    # the frame is the finished plan's, so that the panels of a sequence compare
    full = plot_plans.draw_plan(a)
    assert ax.get_xlim() == pytest.approx(full.get_xlim()) and ax.get_ylim() == pytest.approx(full.get_ylim())
    first = plot_plans.draw_plan_step(v, 1, caption=False)
    assert first.get_title() == "step 1"
    assert [line for line in first.lines if line.get_linestyle() == ":"] == []


def test_all_steps_in_one_figure():
    _, v, a = _example()
    fig, axes = plot_plans.draw_plan_steps(a, columns=2)
    assert len(axes) == 4 and len(fig.axes) == 4
    assert [ax.get_title().split(":")[0] for ax in axes] == ["step 1", "step 2", "step 3", "step 4"]


@pytest.mark.parametrize("step", [0, 4, -1, 1.5, True, "2"])
def test_a_step_out_of_range_is_refused_by_name(step):
    _, v, _ = _example()
    with pytest.raises(InvalidParameterError, match="step"):
        plot_plans.draw_plan_step(v, step)


@pytest.mark.parametrize("kwargs", [{"columns": 0}, {"columns": 4}, {"panel": 0.0}, {"panel": float("nan")}])
def test_bad_grid_parameters_are_refused_by_name(kwargs):
    _, v, _ = _example()
    with pytest.raises(InvalidParameterError, match=next(iter(kwargs))):
        plot_plans.draw_plan_steps(v, **kwargs)
