"""Tests of the figures (mechanisms.plot) and tables (mechanisms.present)."""

import matplotlib.pyplot as plt
import numpy as np
import pytest

import mechanisms as mech
from mechanisms import plot
from mechanisms_for_tests import ScotchYoke

PHI = np.radians(np.arange(0, 360, 30.0))


def test_draw_puts_every_joint_and_label():
    yoke = ScotchYoke(0.1)
    sol = yoke.solve(PHI, order=0)
    ax = plot.draw(yoke, sol, index=1)
    labels = sorted(t.get_text() for t in ax.texts)
    assert labels == ["$A$", "$B$", "$O$"]
    hinge_line = [ln for ln in ax.lines if ln.get_marker() == "o"][0]
    np.testing.assert_allclose(hinge_line.get_xdata(), [0.0, 0.1 * np.cos(PHI[1]), 0.1 * np.cos(PHI[1])], atol=1e-15)
    assert ax.get_aspect() == 1.0
    crank_bar = [ln for ln in ax.lines if ln.get_gid() == "crank"][0]
    assert crank_bar.get_color() == plot.ROLE_COLOURS["crank"]
    assert all(ln.get_label().startswith("_") for ln in ax.lines)  # a later legend lists no bars
    plt.close("all")


def test_draw_gives_a_link_the_colour_asked_for_and_the_others_their_roles():
    rockers = mech.SlottedRockers(crank=0.1, pivot=(0.0, 0.3), rocker_pivot=(0.12, 0.38), rocker=0.2)
    sol = rockers.solve(np.radians([60.0]), order=0)
    ax = plot.draw(rockers, sol, colours={"rocker": "#8c564b"})
    bars = {ln.get_gid(): ln.get_color() for ln in ax.lines if ln.get_gid()}
    assert bars == {"lever": "#2ca02c", "crank": "#1f77b4", "rocker": "#8c564b"}
    with pytest.raises(mech.InvalidParameterError, match="no link 'slot'"):
        plot.draw(rockers, sol, colours={"slot": "#8c564b"})
    plt.close("all")


def test_diagram_ticks_every_30_degrees():
    ax = plot.diagram(PHI, {"s": np.cos(PHI), "v": np.sin(PHI)}, "s, m")
    ticks = ax.get_xticks()
    assert np.all(np.diff(ticks) == 30.0) and ticks[0] == 0.0
    assert ax.get_legend() is not None
    plt.close("all")


def test_vectors_along_uses_book_colours():
    sol = ScotchYoke(0.1).solve(PHI, 1.0)
    ax = plot.vectors_along(sol.point("A"), every=2)
    colours = [tuple(np.round(q.get_facecolor()[0][:3], 3)) for q in ax.collections]
    from matplotlib.colors import to_rgb
    assert colours == [tuple(np.round(to_rgb(plot.VELOCITY_COLOUR), 3)),
                       tuple(np.round(to_rgb(plot.ACCELERATION_COLOUR), 3))]
    plt.close("all")


def test_markdown_table():
    table = mech.markdown_table(["φ, °", "s, m"], [[0, 0.38], [30, "—"]], [".0f", ".3f"])
    assert table._repr_markdown_() == "| φ, ° | s, m |\n|---:|---:|\n| 0 | 0.380 |\n| 30 | — |"
    assert str(table) == table.text


def test_draw_positions_draws_each_position_over_its_paths():
    yoke = ScotchYoke(0.1)
    sol = yoke.solve(PHI, order=0)
    ax = plot.draw_positions(yoke, sol, indices=[0, 3, 6], paths={"A": sol.point("A")})
    hinge_sets = [ln for ln in ax.lines if ln.get_marker() == "o"]
    assert len(hinge_sets) == 3 and len(ax.texts) == 0   # three positions, no joint labels
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["A"]
    plt.close("all")


def test_annotate_dimension_writes_its_label():
    _, ax = plt.subplots()
    plot.annotate_dimension(ax, 0j, 0.2 + 0j, "$s$", both=False)
    assert [t.get_text() for t in ax.texts if t.get_text()] == ["$s$"]
    plt.close("all")


def test_difference_prints_round_off_as_a_bound():
    assert mech.difference(3.4e-6, unit="m") == "3.4e-06 m"
    assert mech.difference(2.2e-16, unit="m") == "< 1e-12 m"
    assert mech.difference(-5e-13, floor=1e-14) == "-5.0e-13"


def test_magnitude_is_the_nearest_power_of_ten():
    # expected by hand: log10(4.8e-11) = -10.32 and log10(3.6e-13) = -12.44 round to -10 and -12
    assert mech.magnitude(4.8e-11) == "≈ 1e-10" and mech.magnitude(5.1e-11) == "≈ 1e-10"
    assert mech.magnitude(-3.6e-13) == "≈ 1e-12" and mech.magnitude(12.0) == "≈ 1e1"
    assert mech.magnitude(0.0) == "0" and mech.magnitude(float("inf")) == "inf"


def test_paths_of_a_full_turn_are_closed():
    yoke = ScotchYoke(0.1)
    ax = plot.trajectories(yoke.solve(PHI, order=0), ["A"])
    line = ax.lines[0]
    assert len(line.get_xdata()) == len(PHI) + 1 and line.get_xdata()[0] == line.get_xdata()[-1]
    half = plot.trajectories(yoke.solve(PHI[:6], order=0), ["A"])   # half a turn: left open
    assert len(half.lines[0].get_xdata()) == 6
    plt.close("all")


def test_figures_are_stored_as_palette_pngs_that_look_the_same():
    import io

    from PIL import Image

    from mechanisms.plot.workarounds import palette_png

    yoke = ScotchYoke(0.1)
    ax = plot.draw(yoke, yoke.solve(PHI, order=0), index=2)
    plot.trajectories(yoke.solve(PHI, order=0), ["A"], ax=ax)
    fig = ax.figure
    full = io.BytesIO()
    fig.canvas.print_figure(full, format="png", bbox_inches="tight", dpi=fig.dpi, facecolor="white")
    light = palette_png(fig)
    assert light == palette_png(fig)                       # deterministic: same figure, same bytes
    assert len(light) < 0.6 * len(full.getvalue())
    reference = np.asarray(Image.open(io.BytesIO(full.getvalue())).convert("RGB"), dtype=int)
    stored = Image.open(io.BytesIO(light))
    assert stored.mode == "P" and len(stored.getcolors(256)) <= 64
    difference = np.abs(np.asarray(stored.convert("RGB"), dtype=int) - reference)
    assert difference.shape == reference.shape
    # the same picture: almost every pixel within a few levels, none far off in a flat colour
    assert np.mean(difference.max(axis=2) <= 24) > 0.99
    plt.close("all")



def test_a_short_crank_keeps_its_colour_among_many_paths():
    # forty paths in four colours (teal #17a589 among them) and a short crank in the crank's blue
    # #1f77b4, as in chapter 4's atlas: median cut alone put the blue into the teal's box and the
    # stored crank came out teal (no pixel of the blue left); its pixels must keep the crank's blue
    import io

    from PIL import Image

    from mechanisms.plot.workarounds import palette_png

    fig, ax = plt.subplots(figsize=(6, 5), dpi=100)
    t = np.linspace(0, 2 * np.pi, 400)
    for k in range(40):
        ax.plot(np.cos(t) * (1 + 0.02 * k), np.sin(2 * t) * (0.5 + 0.01 * k),
                color=("#17a589", "#8c564b", "#bcbd22", "#5d6d7e")[k % 4], lw=1.5)
    ax.plot([0, 0.3], [0, 0.1], color="#1f77b4", lw=2)
    stored = np.asarray(Image.open(io.BytesIO(palette_png(fig))).convert("RGB"), dtype=int)
    assert np.sum(np.all(stored == [0x1F, 0x77, 0xB4], axis=2)) > 50
    plt.close("all")


def test_guides_carried_by_moving_links_are_drawn_with_them():
    from mechanisms.linkages.groups import PRP, Crank, Line

    # a slot across the crank at its pin A (0.1 m along it, at 90° to it) and a fixed guide x = 0.2 m:
    # at φ = 30° the slot is the line through A = 0.1·e^{i30°} in the direction 120° (by hand)
    slotted = mech.Linkage({"O": 0}, [Crank("O", "A", length=0.1),
                                      PRP("K", Line("crank", 0.1 + 0j, np.pi / 2), Line("frame", 0.2 + 0j, np.pi / 2),
                                          "K1", "K2")])
    sol = slotted.solve(np.radians([30.0]), order=0)
    ((link, through, angle, blocks),) = plot.moving_guides(slotted, sol)
    assert link == "crank" and blocks == ["K"]
    np.testing.assert_allclose(through, 0.1 * np.exp(1j * np.pi / 6), atol=1e-15)
    np.testing.assert_allclose(angle, np.radians(120.0), atol=1e-15)
    ax = plot.draw(slotted, sol, label_offset={"O": (-12.0, 3.0)})
    slot = [ln for ln in ax.lines if ln.get_color() == plot.ROLE_COLOURS["crank"] and ln.get_linewidth() < 2]
    assert len(slot) == 1                          # the slot, thin, in the crank's colour
    x, y = slot[0].get_xdata(), slot[0].get_ydata()
    k = complex(sol.point("K").value[0])
    assert min(x) < k.real < max(x) and min(y) < k.imag < max(y)   # it reaches past the block K
    offsets = {t.get_text(): t.xyann for t in ax.texts}
    assert offsets["$O$"] == (-12.0, 3.0)
    # a name not listed sits 10 points from its joint, away from its bars: A's, not along A → O
    a = complex(*offsets["$A$"])
    assert abs(a) == pytest.approx(10.0)
    toward_o = -sol.point("A").value[0]
    assert abs(np.angle(a / toward_o)) >= np.pi / 4 - 1e-12
    plt.close("all")


def test_the_yokes_slot_is_drawn_and_fixed_guides_stay_in_the_scheme():
    # the Scotch yoke's slot is carried by the yoke, at 90° to the fixed guide (its file); the book's
    # mechanism classes carry no moving guide, so their drawings are unchanged
    yoke = mech.load_linkage("scotch-yoke")
    ((link, through, angle, blocks),) = plot.moving_guides(yoke, yoke.solve([0.5], order=0))
    assert (link, blocks) == ("yoke", ["A"])
    np.testing.assert_allclose([through, angle], [0.1 * np.cos(0.5), np.pi / 2], atol=1e-15)
    crank_slider = mech.CrankSlider.example()
    assert plot.moving_guides(crank_slider, crank_slider.solve([0.5], order=0)) == []


def test_joint_names_are_set_as_italic_points():
    # the book writes points in italic math with digits as subscripts: A → $A$, O2 → $O_2$
    assert plot.point_label("A") == "$A$"
    assert plot.point_label("O2") == "$O_{2}$"
    assert plot.point_label("A3") == "$A_{3}$"
    assert plot.point_label("foot-1") == "foot-1"


def test_draw_writes_the_pages_own_letters_for_the_joints_it_is_given():
    yoke = ScotchYoke(0.1)
    ax = plot.draw(yoke, yoke.solve(PHI, order=0), labels={"A": "E"})
    texts = sorted(t.get_text() for t in ax.texts)
    assert "$E$" in texts and "$A$" not in texts and "$O$" in texts
    plt.close("all")


def test_vector_key_states_each_scale_in_the_book_s_units():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="$B$")
    legend = plot.vector_key(ax, scale_velocity=0.04, scale_acceleration=6e-6, of="$P$")
    texts = [text.get_text() for text in legend.get_texts()]
    assert texts == ["$B$", "velocity of $P$: 0.04 m per m/s", r"acceleration of $P$: $6\cdot10^{-6}$ m per m/s²"]
    colours = [handle.get_color() for handle in legend.legend_handles[1:]]
    assert colours == [plot.VELOCITY_COLOUR, plot.ACCELERATION_COLOUR]
    only = plot.vector_key(plt.subplots()[1], scale_acceleration=1e-5)
    assert [text.get_text() for text in only.get_texts()] == ["acceleration: $10^{-5}$ m per m/s²"]
    with pytest.raises(mech.InvalidParameterError, match="scale_velocity"):
        plot.vector_key(ax, scale_velocity=-1.0)
    plt.close("all")
