"""Tests of mechanisms.plot.plans: plans drawn to scale and lettered, instant centres drawn."""

import math

import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
import pytest

import mechanisms as mech
from mechanisms import plot
from mechanisms.plot import plans as plot_plans
from mechanisms.analysis import plans

EXAMPLE = mech.CrankSlider(crank=0.08, rod=0.3)          # example 5.2 of the textbook page


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _example_plans():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0)
    v = plans.velocity_plan(EXAMPLE, sol, points={"S2": ("coupler", 0.09, 0.0)})
    return sol, v, plans.acceleration_plan(EXAMPLE, sol, points={"S2": ("coupler", 0.09, 0.0)}, velocity=v)


def _arrows(ax):
    return [t for t in ax.texts if getattr(t, "arrow_patch", None) is not None]


def test_velocity_plan_is_drawn_to_scale_with_its_letters_and_scale():
    _, v, _ = _example_plans()
    ax = plot_plans.draw_plan(v)
    texts = [t.get_text() for t in ax.texts]
    for letter in ("$p$", "$a$", "$b$", "$s_{2}$"):              # the book's letters, in mathtext
        assert letter in texts
    assert any("0.2 (m/s)/mm" in t for t in texts)          # μ_v = 0.2 (m/s)/mm, the course scale for 17.2 m/s
    arrows = _arrows(ax)
    assert len(arrows) == 4                                 # v_A, v_BA, v_B, v_S2
    # each arrow ends at its vertex divided by the scale: p → b is v_B = −10.604 m/s → −53.02 mm (hand value)
    heads = {tuple(np.round(a.xy, 6)) for a in arrows}
    assert (round(-10.60397794444199 / 0.2, 6), 0.0) in heads
    absolute = [a for a in arrows if a.xyann == (0.0, 0.0)]
    assert len(absolute) == 3
    assert all(mcolors.same_color(a.arrow_patch.get_edgecolor(), plot.VELOCITY_COLOUR) for a in absolute)
    relative = [a for a in arrows if a.xyann != (0.0, 0.0)]
    assert mcolors.same_color(relative[0].arrow_patch.get_edgecolor(), plot.ROLE_COLOURS["coupler"])
    assert ax.get_aspect() == 1.0
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    for label in v.vertices:
        p = v.drawn(label)
        assert x0 < p.real < x1 and y0 < p.imag < y1
    assert ax.get_xlabel() == "mm of the drawing"


def test_acceleration_plan_draws_normal_components_dashed_and_uses_its_colour():
    _, _, a = _example_plans()
    ax = plot_plans.draw_plan(a, names=True)
    texts = [t.get_text() for t in ax.texts]
    for letter in (r"$\pi$", "$a'$", "$n_{2}$", "$b'$", "$s_{2}'$"):
        assert letter in texts
    assert "$a^{n}_{BA}$" in texts and "$a^{t}_{BA}$" in texts
    assert any("50 (m/s²)/mm" in t for t in texts)
    arrows = _arrows(ax)
    # the drawing places everything at positions rounded to 6 decimals of a mm
    normal = [x for x in arrows if tuple(np.round(x.xy, 5)) == tuple(np.round((a.drawn("n2").real,
                                                                                a.drawn("n2").imag), 5))]
    assert normal and normal[0].arrow_patch.get_linestyle() != "solid"
    absolute = [x for x in arrows if x.xyann == (0.0, 0.0)]
    assert all(mcolors.same_color(x.arrow_patch.get_edgecolor(), plot.ACCELERATION_COLOUR) for x in absolute)


def test_slotted_lever_plan_draws_the_coriolis_component():
    m = mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25))
    sol = m.solve(np.radians([64.0]), omega=10.0)
    ax = plot_plans.draw_plan(plans.acceleration_plan(m, sol))
    texts = [t.get_text() for t in ax.texts]
    assert "$a^{k}_{A_{2}A_{3}}$" in texts and "$k$" in texts and "$a_{3}'$" in texts


def test_letters_in_the_book_s_notation():
    # the chapter 10 letters: digits as subscripts, ′ as a prime, π as \pi (hand-written expectations)
    assert plot_plans.vertex_label("a3′") == "$a_{3}'$"
    assert plot_plans.vertex_label("π") == r"$\pi$"
    assert plot_plans.vertex_label("n4") == "$n_{4}$"
    assert plot_plans.vector_label("a^{k}_{A3A2}") == "$a^{k}_{A_{3}A_{2}}$"
    assert plot_plans.vector_label("v_{BA}") == "$v_{BA}$"
    assert plot_plans.segment_label("n2", "b′") == "$n_{2}b'$"
    assert plot_plans.segment_label("π", "a′") == r"$\pi a'$"


@pytest.mark.parametrize("case", ["shaper", "crank-slider", "slotted lever", "four-bar"])
def test_no_two_letters_of_a_plan_overlap(case):
    # the plans of chapter 10: every letter and vector name is placed clear of the others
    machines = {"shaper": (mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22),
                           330.0, None),
                "crank-slider": (EXAMPLE, 30.0, {"S2": ("coupler", 0.09, 0.0)}),
                "slotted lever": (mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25)), 64.0, None),
                "four-bar": (mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05)), 60.0, {"M": ("coupler", 0.2, 0.12)})}
    m, phi, points = machines[case]
    sol = m.solve(np.radians([phi]), omega=10.0)
    v = plans.velocity_plan(m, sol, points=points)
    a = plans.acceleration_plan(m, sol, points=points, velocity=v)
    fig, axes = plot_plans.draw_plans(m, sol, v, a, figsize=(9.5, 10.0))
    fig.canvas.draw()
    for ax in axes[1:]:
        boxes = [t.get_bbox_patch().get_window_extent() for t in ax.texts if t.get_bbox_patch() is not None]
        assert len(boxes) >= 4
        for i, first in enumerate(boxes):
            for second in boxes[:i]:
                assert not first.overlaps(second)


def test_draw_plans_puts_the_mechanism_above_its_two_plans():
    sol, v, a = _example_plans()
    fig, axes = plot_plans.draw_plans(EXAMPLE, sol, v, a)
    assert len(axes) == 3
    assert axes[1].get_title() == "velocity plan" and axes[2].get_title() == "acceleration plan"
    assert "$S_{2}$" in [t.get_text() for t in axes[0].texts]
    fig, axes = plot_plans.draw_plans(EXAMPLE, sol, v)
    assert len(axes) == 2


def test_draw_plans_moves_the_joint_letters_it_is_given():
    sol, v, a = _example_plans()
    fig, axes = plot_plans.draw_plans(EXAMPLE, sol, v, a, label_offset={"A": (10, 3)})
    letters = {t.get_text(): t for t in axes[0].texts}
    assert letters["$A$"].xyann == (10, 3)                     # as asked, in points
    assert letters["$B$"].xyann != (10, 3)                     # the others where draw puts them


def test_instant_centres_of_a_four_bar_are_marked_and_labelled():
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05))
    sol = m.solve(np.radians([60.0]), omega=10.0, order=0)
    centres = plans.instant_centres(m, sol)
    ax = plot_plans.draw_instant_centres(m, sol, centres)
    texts = [t.get_text() for t in ax.texts]
    for name in ("02", "13"):                               # the stars: the centre's name alone
        assert f"$P_{{{name}}}$" in texts
    for joint, name in (("O", "01"), ("A", "12"), ("B", "23"), ("C", "03")):   # a hinge is a centre
        assert f"${joint} = P_{{{name}}}$" in texts
    stars = [ln for ln in ax.lines if ln.get_marker() == "*"]
    assert len(stars) == 2                                  # P02 and P13 are not joints
    centre = centres[(0, 2)]
    assert any(np.allclose([ln.get_xdata()[0], ln.get_ydata()[0]], [centre.real, centre.imag]) for ln in stars)
    x0, x1 = ax.get_xlim()
    assert x0 < centres[(1, 3)].real < x1


def test_a_centre_at_infinity_is_drawn_as_an_arrow():
    sol = EXAMPLE.solve(np.radians([30.0]), omega=215.0, order=0)
    ax = plot_plans.draw_instant_centres(EXAMPLE, sol, plans.instant_centres(EXAMPLE, sol))
    assert "$P_{03}$ at ∞" in [t.get_text() for t in ax.texts]


def _four_bar_centre_velocities():
    """Chapter 4's crank-rocker at 60°: its centres, A and B, and their velocities from P02."""
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05))
    sol = m.solve(np.radians([60.0]), omega=10.0)
    centres = plans.instant_centres(m, sol)
    where = {n: sol.point(n).value[0] for n in "AB"}
    _, velocities = plans.velocities_from_centre(centres[(0, 2)], where["A"], sol.point("A").velocity[0], where)
    return m, sol, centres, where, velocities


def test_velocities_from_the_centre_are_drawn_at_the_points():
    _, _, centres, where, velocities = _four_bar_centre_velocities()
    _, ax = plt.subplots()
    plot_plans.draw_centre_velocities(ax, centres[(0, 2)], where, velocities, scale=0.1)
    arrows = _arrows(ax)
    assert len(arrows) == 2
    tip = where["B"] + 0.1 * velocities["B"]
    assert any(np.allclose(a.xy, (tip.real, tip.imag)) for a in arrows)
    assert all(mcolors.same_color(a.arrow_patch.get_edgecolor(), plot.VELOCITY_COLOUR) for a in arrows)


def test_the_letters_of_the_instant_centres_do_not_overlap():
    m = mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05))
    for mechanism, phi in ((m, 60.0), (EXAMPLE, 30.0)):
        sol = mechanism.solve(np.radians([phi]), omega=10.0, order=0)
        ax = plot_plans.draw_instant_centres(mechanism, sol, plans.instant_centres(mechanism, sol))
        renderer = ax.figure.canvas.get_renderer()
        boxes = [t.get_window_extent(renderer) for t in ax.texts if t.get_text()]
        assert len(boxes) >= 6
        for k, first in enumerate(boxes):
            assert not any(first.overlaps(second) for second in boxes[k + 1:])


def test_the_key_names_kennedy_s_lines_the_rays_and_the_velocity_scale():
    m, sol, centres, where, velocities = _four_bar_centre_velocities()
    ax = plot_plans.draw_instant_centres(m, sol, centres)
    plot_plans.draw_centre_velocities(ax, centres[(0, 2)], where, velocities, scale=0.1, centre_label="$P_{02}$")
    keys = [t.get_text() for t in ax.get_legend().get_texts()]
    assert keys == ["lines of Kennedy's theorem", "rays from $P_{02}$", "velocities, 1 m/s drawn as 0.1 m"]


def test_vector_table_lists_every_vector_with_its_segment_length_and_direction():
    sol, v, a = _example_plans()
    text = plot_plans.vector_table(v, a)._repr_markdown_()
    lines = text.splitlines()
    assert lines[0] == "| vector | on the plan | magnitude, m/s or m/s² | length, mm | direction, ° |"
    assert len(lines) == 2 + len(v.vectors) + len(a.vectors)
    # v_A = ω1·L1 = 17.2 m/s drawn 86 mm at μ_v = 0.2 (m/s)/mm, at 30° + 90° = 120° (hand calculation)
    assert lines[2] == "| $v_{A}$ | $pa$ | 17.20 | 86.00 | 120.0 |"
    only_velocities = plot_plans.vector_table(v)._repr_markdown_().splitlines()[0]
    assert "magnitude, m/s |" in only_velocities


@pytest.mark.parametrize("case", ["shaper", "slotted lever at 0°"])
def test_every_letter_is_nearest_to_its_own_vertex_and_every_name_beside_its_vector(case):
    # chapter 10's shaper at 330° (a′ beside k, a^r by the short k → a3′, a^t along π a3′) and
    # exercise 10.3's lever at 0° (a3 beside b): a reader takes a letter for the nearest vertex
    machines = {"shaper": (mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22),
                           330.0, (9.5, 10.0)),
                "slotted lever at 0°": (mech.SlottedLever(crank=0.1, pivot=(0.0, 0.3)), 0.0, (8.0, 7.4))}
    m, phi, size = machines[case]
    sol = m.solve(np.radians([phi]), omega=10.0)
    v = plans.velocity_plan(m, sol)
    a = plans.acceleration_plan(m, sol, velocity=v)
    fig, axes = plot_plans.draw_plans(m, sol, v, a, figsize=size)
    fig.canvas.draw()
    for ax, plan in zip(axes[1:], (v, a)):
        drawn = {plot_plans.vertex_label(label): plan.drawn(label) for label in plan.vertices}
        lines = {plot_plans.vector_label(x.latex): (plan.drawn(x.tail), plan.drawn(x.head))
                 for x in plan.vectors if abs(plan.drawn(x.head) - plan.drawn(x.tail)) > 1e-9}
        placed = {t.get_text(): complex(*t.get_position()) for t in ax.texts}
        boxes = {t.get_text(): t.get_window_extent().transformed(ax.transData.inverted()) for t in ax.texts}
        for letter, point in drawn.items():
            if letter not in placed:                 # shares a label with a vertex at the same place
                continue
            others = [abs(placed[letter] - z) for name, z in drawn.items() if abs(z - point) > 1.0]
            assert abs(placed[letter] - point) < min(others), letter
        t = np.linspace(0.0, 1.0, 101)
        for name, (tail, head) in lines.items():
            if name not in placed:                   # an absolute vector, or too short to be named
                continue
            box = boxes[name]                        # the distance from the name's box to each line
            gaps = {}
            for other, (p, q) in lines.items():
                z = p + t * (q - p)
                dx = np.maximum(np.maximum(box.x0 - z.real, z.real - box.x1), 0.0)
                dy = np.maximum(np.maximum(box.y0 - z.imag, z.imag - box.y1), 0.0)
                gaps[other] = np.min(np.hypot(dx, dy))
            assert gaps[name] < 7.5, name           # beside its own vector, mm of the drawing


def _gaps_in_points(ax):
    """For each boxed text of a drawn plan: its gap (pt) to the nearest other box, vertex dot and arrowhead.

    Measured on the drawn artists: the white boxes, the dots (3.5 pt across) and the arrowheads'
    outlines as matplotlib drew them.
    """
    ax.figure.canvas.draw()
    to_points = 72.0 / ax.figure.dpi
    texts = [t for t in ax.texts if t.get_bbox_patch() is not None]
    boxes = [t.get_bbox_patch().get_window_extent() for t in texts]
    dots = [ax.transData.transform((ln.get_xdata()[0], ln.get_ydata()[0])) for ln in ax.lines
            if ln.get_marker() == "o"]
    heads = []
    s = np.linspace(0.0, 1.0, 21)[:, None]
    for arrow in _arrows(ax):
        tip, corner, _, other = arrow.arrow_patch.get_path().vertices[2:6]   # the filled head: a triangle
        heads += [a + s * (b - a) for a, b in ((tip, corner), (corner, other), (other, tip))]

    def to_box(box, xy):
        xy = np.atleast_2d(xy)
        dx = np.maximum(np.maximum(box.x0 - xy[:, 0], xy[:, 0] - box.x1), 0.0)
        dy = np.maximum(np.maximum(box.y0 - xy[:, 1], xy[:, 1] - box.y1), 0.0)
        return float(np.min(np.hypot(dx, dy))) * to_points

    gaps = {}
    for k, (text, box) in enumerate(zip(texts, boxes)):
        between = [np.hypot(max(box.x0 - o.x1, o.x0 - box.x1, 0.0), max(box.y0 - o.y1, o.y0 - box.y1, 0.0))
                   * to_points for j, o in enumerate(boxes) if j != k]
        gaps[text.get_text()] = (min(between), min(to_box(box, d) for d in dots) - 1.75,
                                 min(to_box(box, h) for h in heads))
    return gaps


def _shaper_cluster():
    """A hand-built acceleration plan: the crowd of chapter 10's shaper at 330°, in round mm.

    The pole π; a′ (a_A); k at the end of the Coriolis component a′k; a3′ 15 mm below k (the sliding
    component k a3′, short); b′ far left on the line π a3′ produced (a_B). μ_a = 1 (m/s²)/mm.
    """
    vertices = {"π": 0j, "a′": -43 + 25j, "k": -50.5 + 27j, "a3′": -54 + 12j, "b′": -90 + 20j}
    vector = plans.PlanVector
    vectors = (vector("a_A", "π", "a′", "absolute", "crank", vertices["a′"]),
               vector("a^k_A3A2", "a′", "k", "coriolis", "lever", vertices["k"] - vertices["a′"]),
               vector("a^r_A3A2", "k", "a3′", "sliding", "lever", vertices["a3′"] - vertices["k"]),
               vector("a_A3", "π", "a3′", "absolute", "lever", vertices["a3′"]),
               vector("a_B", "π", "b′", "absolute", "lever", vertices["b′"]))
    return plans.AccelerationPlan("acceleration", 0.0, "π", vertices, {}, vectors, (), {}, 1.0)


@pytest.mark.parametrize("case", ["hand-built crowd", "shaper", "slotted lever", "slotted lever at 0°",
                                  "crank-slider", "four-bar"])
def test_no_letter_touches_another_letter_a_vertex_or_an_arrowhead(case):
    # the rule: every letter and name keeps a gap of a quarter of its font size (2.5 pt for the 10 pt
    # names, 2.75 pt for the 11 pt letters; 2 pt asked here, for the measuring) from every other
    # letter, every vertex dot and every arrowhead, its own vertex's included
    if case == "hand-built crowd":
        ax = plot_plans.draw_plan(_shaper_cluster())
        axes = [ax]
    else:
        machines = {"shaper": (mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22),
                               330.0, None, (9.5, 10.0)),
                    "slotted lever": (mech.SlottedLever(crank=0.1, pivot=(0.0, 0.25)), 64.0, None, (9.5, 9.0)),
                    "slotted lever at 0°": (mech.SlottedLever(crank=0.1, pivot=(0.0, 0.3)), 0.0, None, (8.0, 7.4)),
                    "crank-slider": (EXAMPLE, 30.0, {"S2": ("coupler", 0.09, 0.0)}, (9.5, 8.6)),
                    "four-bar": (mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05)), 60.0, {"M": ("coupler", 0.2, 0.12)},
                                 (9.5, 9.2))}
        m, phi, points, size = machines[case]
        sol = m.solve(np.radians([phi]), omega=10.0)
        v = plans.velocity_plan(m, sol, points=points)
        a = plans.acceleration_plan(m, sol, points=points, velocity=v)
        _, axes = plot_plans.draw_plans(m, sol, v, a, figsize=size)
        axes = axes[1:]
    for ax in axes:
        for text, (label, vertex, head) in _gaps_in_points(ax).items():
            assert min(label, vertex, head) >= 2.0, (text, label, vertex, head)


def test_a_short_vector_in_a_crowd_keeps_its_name_beside_it():
    # the hand-built crowd: the name of the short sliding component k a3′ has few places; it chooses
    # before the letters, so it stays beside its own vector, nearer to it than to the long π b′ below
    ax = plot_plans.draw_plan(_shaper_cluster())
    ax.figure.canvas.draw()
    names = {t.get_text(): t for t in ax.texts}
    assert "$a^{r}_{A_{3}A_{2}}$" in names and "$k$" in names
    box = names["$a^{r}_{A_{3}A_{2}}$"].get_window_extent().transformed(ax.transData.inverted())
    t = np.linspace(0.0, 1.0, 201)

    def gap(p, q):
        z = p + t * (q - p)
        dx = np.maximum(np.maximum(box.x0 - z.real, z.real - box.x1), 0.0)
        dy = np.maximum(np.maximum(box.y0 - z.imag, z.imag - box.y1), 0.0)
        return np.min(np.hypot(dx, dy))

    own, other = gap(-50.5 + 27j, -54 + 12j), gap(0j, -90 + 20j)
    assert own < other and own < 4.0


def _shaper_tangential_crowd():
    """A hand-built acceleration plan: chapter 10's shaper at 330° with the lever's components, round mm.

    As :func:`_shaper_cluster`, with n3 1 mm from the pole (a short normal component π n3), the
    tangential component n3 a3′ running almost along π b′, between π a′ above it and π d′ (the
    ram's a_D, along −x) below it. μ_a = 1 (m/s²)/mm.
    """
    vertices = {"π": 0j, "a′": -43 + 25j, "k": -50.5 + 27j, "a3′": -54 + 12j, "b′": -90 + 20j,
                "n3": -0.3 - 1.0j, "d′": -85 + 0j}
    vector = plans.PlanVector

    def v(name, tail, head, kind, link):
        return vector(name, tail, head, kind, link, vertices[head] - vertices[tail])

    vectors = (v("a_A", "π", "a′", "absolute", "crank"), v("a^k_A3A2", "a′", "k", "coriolis", "lever"),
               v("a^r_A3A2", "k", "a3′", "sliding", "lever"), v("a^n_A3C", "π", "n3", "normal", "lever"),
               v("a^t_A3C", "n3", "a3′", "tangential", "lever"), v("a_A3", "π", "a3′", "absolute", "lever"),
               v("a_B", "π", "b′", "absolute", "lever"), v("a_D", "π", "d′", "absolute", "rod"))
    return plans.AccelerationPlan("acceleration", 0.0, "π", vertices, {}, vectors, (), {}, 1.0)


@pytest.mark.parametrize("size", [(5.0, 5.0), (6.0, 3.5)])
def test_a_name_is_nearer_its_own_vector_than_any_other_it_does_not_run_along(size):
    # the rule: a reader takes a vector's name for that of the line nearest to the name's middle, so
    # the tangential component's name must be nearer n3 a3′ than π a′ above it or π d′ below it (π a3′
    # and π b′ run along it and do not count), and lie across neither (chapter 10's shaper plan once
    # set it on π a′)
    _, ax = plt.subplots(figsize=size)
    plot_plans.draw_plan(_shaper_tangential_crowd(), ax=ax)
    ax.figure.canvas.draw()
    names = {t.get_text(): t for t in ax.texts}
    name = "$a^{t}_{A_{3}C}$"
    assert name in names
    box = names[name].get_window_extent().transformed(ax.transData.inverted())
    middle = complex((box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2)
    t = np.linspace(0.0, 1.0, 401)

    def to_middle(p, q):
        return np.min(np.abs(p + t * (q - p) - middle))

    def across(p, q):
        z = p + t * (q - p)
        return np.any((z.real > box.x0) & (z.real < box.x1) & (z.imag > box.y0) & (z.imag < box.y1))

    own = to_middle(-0.3 - 1.0j, -54 + 12j)
    for p, q in ((0j, -43 + 25j), (0j, -85 + 0j)):           # π a′ and π d′
        assert own + 0.5 <= to_middle(p, q), (own, p, q)
        assert not across(p, q), (p, q)


@pytest.mark.parametrize("case", ["slotted lever at 0°", "slotted lever at 64°"])
def test_the_mechanism_s_letters_lie_inside_its_frame(case):
    # exercise 10.3's and §10.6's narrow lever drawings: B at the bottom sat on the frame, C at the
    # top ran into the title; draw_plans widens the limits until every letter is inside
    pivot, phi, size = {"slotted lever at 0°": (0.3, 0.0, (8.0, 7.4)),
                        "slotted lever at 64°": (0.25, 64.0, (9.5, 9.0))}[case]
    m = mech.SlottedLever(crank=0.1, pivot=(0.0, pivot))
    sol = m.solve(np.radians([phi]), omega=10.0)
    v = plans.velocity_plan(m, sol)
    fig, axes = plot_plans.draw_plans(m, sol, v, plans.acceleration_plan(m, sol, velocity=v), figsize=size)
    fig.canvas.draw()
    frame = axes[0].get_window_extent()
    for text in axes[0].texts:
        if text.get_text():
            box = text.get_window_extent()
            assert (box.x0 >= frame.x0 and box.x1 <= frame.x1 and box.y0 >= frame.y0
                    and box.y1 <= frame.y1), text.get_text()


def test_short_components_are_named_as_long_ones():
    # the four-bar's normal component a′n2 (about 10 mm) and the shaper's Coriolis component a′k
    # (about 7 mm) carry their names, as the crank-slider's a′n2 and the slotted lever's a′k do
    cases = [(mech.FourBar(0.1, 0.35, 0.3, (0.4, 0.05)), 60.0, "$a^{n}_{BA}$", (9.5, 9.2)),
             (mech.Shaper(crank=0.1, pivot=(0.0, -0.4), lever=0.6, rod=0.15, ram_height=0.22), 330.0,
              "$a^{k}_{A_{2}A_{3}}$", (9.5, 10.0))]
    for m, phi, name, size in cases:
        sol = m.solve(np.radians([phi]), omega=10.0)
        v = plans.velocity_plan(m, sol)
        _, axes = plot_plans.draw_plans(m, sol, v, plans.acceleration_plan(m, sol, velocity=v), figsize=size)
        assert name in [t.get_text() for t in axes[2].texts]


@pytest.mark.parametrize("name", ["watt-six-bar", "jansen", "shaper", "scotch-yoke"])
def test_plans_and_centres_of_a_linkage_file_are_drawn(name):
    linkage = mech.load_linkage(name)
    solution = linkage.solve(np.radians([75.0]), 10.0, 2.0)
    velocity = plans.velocity_plan(linkage, solution)
    acceleration = plans.acceleration_plan(linkage, solution, velocity=velocity)
    fig, axes = plot_plans.draw_plans(linkage, solution, velocity, acceleration)
    # every vector longer than a hair is an arrow of its plan
    for ax, plan in zip(axes[1:], (velocity, acceleration)):
        drawn = [v for v in plan.vectors if abs(plan.drawn(v.head) - plan.drawn(v.tail)) >= 1e-9]
        assert len(_arrows(ax)) == len(drawn)
    centres = plans.instant_centres(linkage, solution)
    ax = plot_plans.draw_instant_centres(linkage, solution, centres)
    # a star for every finite centre that is not a joint of the drawing
    stars = [line for line in ax.lines if line.get_marker() == "*"]
    joints = list(centres.positions.values())
    expected = [p for p in centres.finite.values() if min(abs(p - q) for q in joints) > 1e-12]
    assert len(stars) == len(expected)


def test_a_plan_drawing_does_not_change_when_numpys_elementary_functions_move_by_an_ulp(monkeypatch):
    # numpy's sines, cosines, hypot … one ulp off at random (tools/nudge_numpy.py: another processor):
    # the plans' vertices, the candidates and scores of their letters move in their last bits; what is
    # drawn (arrows, letters and where they go) must not move at all. Expected: the drawing without the
    # nudge, in the same process.
    from test_scene import nudged_numpy

    def drawing():
        _, v, a = _example_plans()
        out = []
        for plan in (v, a):
            ax = plot_plans.draw_plan(plan)
            out.append([(t.get_text(), tuple(map(float, t.get_position())),
                         tuple(map(float, getattr(t, "xy", (0.0, 0.0))))) for t in ax.texts])
            plt.close(ax.figure)
        return out

    expected = drawing()
    for seed in range(2):
        with monkeypatch.context() as patch:
            for name, function in nudged_numpy(seed).items():
                patch.setattr(np, name, function)
            assert drawing() == expected


def test_free_directions_break_exact_ties_the_same_way_under_an_ulp(monkeypatch):
    # lines through a point straight up and straight down: the directions 0° and 180° are both 90°
    # from them and equally far from the preferred "up", an exact tie, which goes to the first
    # direction in the order of angles, 0° (by hand), on every processor
    from test_scene import nudged_numpy
    from mechanisms.plot.plans import _free_directions
    occupied = [1j, -1j]
    assert _free_directions(occupied)[0] == pytest.approx(1.0, abs=1e-12)
    for seed in range(8):
        with monkeypatch.context() as patch:
            for name, function in nudged_numpy(seed).items():
                patch.setattr(np, name, function)
            assert _free_directions(occupied)[0] == pytest.approx(1.0, abs=1e-12)
