"""Text alternatives of figures (issue 32): ``mechanisms.plot.describe``, ``mechanisms.present.describe``, the
descriptions of scenes, the notebook formatter and the Sphinx extension ``_ext/figure_alt.py``.

Every expected number is worked out by hand in a comment (a crank-slider at φ = 90°, a sine over a turn).
"""

from __future__ import annotations

import base64
import hashlib
import json
import math
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import mechanisms as mech  # noqa: E402
from mechanisms.core.errors import InvalidParameterError  # noqa: E402
from mechanisms.plot.describe import add_description, describe_figure  # noqa: E402
from mechanisms.plot.workarounds import described_png, palette_png  # noqa: E402
from mechanisms.present.describe import plain_text, value_text  # noqa: E402
from mechanisms.present.scene import Readout, scene, velocity  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "_ext"))
import figure_alt  # noqa: E402

SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


# --- words and numbers -------------------------------------------------------------------------------------

@pytest.mark.parametrize("value, unit, expected", [
    (0.123456, "m", "0.123 m"),           # three significant figures
    (-1.2e-5, "m", "−1.2×10⁻⁵ m"),        # a real minus and a power of ten, not 1.2e-05
    (1e-7, "", "10⁻⁷"),
    (90.0, "°", "90°"),                    # degrees without a space
    (-1e-17, "m/s", "−10⁻¹⁷ m/s"),
    (0.2, "", "0.2"),
    (4680.4, "m/s²", "4680 m/s²"),       # no power of ten from 10⁻⁴ to 10⁶
    (0.000782, "%", "0.000782%"),
    (2.0e6, "", "2×10⁶"),
    (math.nan, "", "undefined"),
    (math.inf, "m", "∞ m"),
])
def test_value_text(value, unit, expected):
    assert value_text(value, unit) == expected


def test_value_text_writes_round_off_of_zero_as_zero_and_never_minus_zero():
    # 1e-17 is below 10⁻⁹ of a figure whose largest value is 0.3: a sighted reader sees 0
    assert value_text(-1e-17, "m", tiny=0.3e-9) == "0 m"
    assert value_text(-0.0) == "0"


@pytest.mark.parametrize("x", [0.2, 0.1 + 0.2, 1 / 3, 2.675, 123456.5, 7.0e-6])
def test_value_text_does_not_move_with_the_last_bit(x):
    # one ulp either way is round-off a processor may add: the text is the same
    assert value_text(np.nextafter(x, 0.0)) == value_text(x) == value_text(np.nextafter(x, 1.0))


@pytest.mark.parametrize("text, expected", [
    ("$L_1$", "L₁"),
    (r"crank angle $\varphi$, °", "crank angle φ, °"),
    ("$v_{BA}$", "v_BA"),                  # no Unicode subscript B: written after _
    ("$h^2$", "h²"),
    (r"$\mu_v$ = 0.01 (m/s)/mm", "μᵥ = 0.01 (m/s)/mm"),
    (r"$\epsilon_\mathrm{mach}/h$", "ε_mach/h"),
    (r"$\mathrm{tol} = 10^{-10}$", "tol = 10⁻¹⁰"),
    ("no math, 100%", "no math, 100%"),
])
def test_plain_text(text, expected):
    assert plain_text(text) == expected


# --- figures of the package --------------------------------------------------------------------------------

def crank_slider_at_90():
    m = mech.CrankSlider(crank=0.1, rod=0.3)
    return m, m.solve(np.radians([90.0]), omega=10.0)


def test_draw_says_the_mechanism_its_angle_and_where_the_joints_are():
    m, sol = crank_slider_at_90()
    ax = mech.plot.draw(m, sol)
    text = describe_figure(ax.figure)
    # by hand: A = L1·(cos 90°, sin 90°) = (0, 0.1) m; B on the axis at x = √(L2² − L1²) = √0.08 = 0.28284 m
    assert "crank-slider (crank = 0.1 m, rod = 0.3 m" in text
    assert "crank angle φ = 90°" in text
    assert "O (0, 0), A (0, 0.1), B (0.283, 0)" in text
    assert "links crank O–A and coupler A–B" in text and "fixed pivot at O" in text and "block at B" in text
    # its bars, hinges and letters are not described again as anonymous lines
    assert "unlabelled" not in text and "path" not in text


def test_a_marked_angle_keeps_its_sign():
    # the coupler of a crank-slider with offset above the pin: ψ = −32°, marked from 0° down to −32°
    fig, ax = plt.subplots()
    mech.plot.annotate_angle(ax, 0j, 0.0, np.radians(-32.0), r"$\psi$", 0.1)
    assert "The angle ψ is marked at (0, 0) m, from 0° to −32°." in describe_figure(fig)


def test_units_with_digits_are_units():
    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [2.0, 3.0], label="ω")
    ax.set_ylabel("largest error, 1/s or 1/s²")
    ax.set_xlabel("time, s")
    assert describe_figure(fig).startswith("A graph of largest error in 1/s or 1/s² against time in s.")


def test_draw_names_joints_by_the_page_letters():
    m, sol = crank_slider_at_90()
    text = describe_figure(mech.plot.draw(m, sol, labels={"B": "C"}).figure)
    assert "C (0.283, 0)" in text and "coupler A–C" in text


def test_diagram_gives_each_curve_its_extremes_and_where_they_are():
    phi = np.radians(np.arange(0.0, 361.0, 1.0))
    ax = mech.plot.diagram(phi, {"$s$": np.sin(phi)}, "$s$, m")
    text = describe_figure(ax.figure)
    # sin φ over a turn: highest 1 at 90°, lowest −1 at 270°
    assert "A graph of s in m against crank angle φ in degrees" in text
    assert "lowest −1 m at φ = 270°" in text and "highest 1 m at φ = 90°" in text


def test_a_rising_curve_and_a_horizontal_line_of_a_plain_matplotlib_graph():
    fig, ax = plt.subplots()
    ax.semilogy([1.0, 2.0, 3.0], [1e-3, 1e-5, 2e-7], label="error")
    ax.axhline(1e-4, ls="--")
    ax.set_xlabel("$h$, rad")
    text = describe_figure(fig)
    assert "logarithmic y axis" in text
    assert "Curve error: falls from 0.001 at h = 1 rad to 2×10⁻⁷ at h = 3 rad" in text
    assert "a dashed line: horizontal at 0.0001" in text


def test_markers_of_a_graph_beside_points_of_a_drawing():
    fig, (graph, drawing) = plt.subplots(1, 2)
    graph.plot([0.0, 90.0, 180.0], [1.0, 2.0, 1.5])
    graph.plot([47.8, 235.0], [109.0, 149.0], "o")
    graph.set_xlabel(r"crank angle $\varphi$, °")
    drawing.set_aspect("equal")
    drawing.plot(0.5, 0.25, "o")
    text = describe_figure(fig)
    assert "an unlabelled marker: 109 at φ = 47.8° and 149 at φ = 235°" in text
    assert "1 marked point at (0.5, 0.25)" in text


def test_paths_vectors_and_their_key():
    # a point on a circle of radius 0.1 m turning at ω = 10 1/s: |v| = ωr = 1 m/s, |a| = ω²r = 10 m/s² everywhere
    m = mech.CrankSlider(crank=0.1, rod=0.3)
    turn = m.solve(np.radians(np.arange(0.0, 360.0, 5.0)), omega=10.0)
    ax = mech.plot.trajectories(turn, ["A", "B"])
    mech.plot.vectors_along(turn.point("A"), every=9, ax=ax, scale_velocity=0.01, scale_acceleration=0.001)
    mech.plot.vector_key(ax, scale_velocity=0.01, scale_acceleration=0.001)
    text = describe_figure(ax.figure)
    assert "Paths of A and B over a whole turn of the crank." in text
    assert "Velocity vectors at 8 points of a path, all 1 m/s long." in text
    assert "Acceleration vectors at 8 points of a path, all 10 m/s² long." in text
    # A on the crank circle: x and y from −0.1 to 0.1 m; B on the axis from L2 − L1 = 0.2 to L2 + L1 = 0.4 m
    assert "Path A: closed, x from −0.1 to 0.1 m, y from −0.1 to 0.1 m" in text
    assert "path B: closed, x from 0.2 to 0.4 m, y constant at 0 m" in text
    assert "Key: velocity: 0.01 m per m/s; acceleration: 0.001 m per m/s²" in text


def test_a_constant_curve_with_round_off_is_constant():
    # |A| of a crank of 0.1 m: 0.1 m at every angle, up to round-off of cos and sin
    phi = np.radians(np.arange(0.0, 360.0, 1.0))
    ax = mech.plot.diagram(phi, {"$A$": np.abs(0.1 * np.exp(1j * phi))}, "distance, m")
    assert "Curve A: constant at 0.1 m" in describe_figure(ax.figure)


def test_points_marked_on_a_drawing_are_listed_together():
    fig, ax = plt.subplots()
    ax.set_aspect("equal")
    for x, y in ((0.0, 0.0), (1.0, 2.0), (1.0, 2.0)):
        ax.plot(x, y, "o")
    ax.set_xlabel("mm of the drawing")
    ax.set_ylabel("mm of the drawing")
    text = describe_figure(fig)
    assert text == "A drawing to scale, both axes in mm of the drawing. 2 marked points at (0, 0), (1, 2)."


def test_panels_are_numbered_in_reading_order_with_their_place():
    fig, (left, right) = plt.subplots(1, 2)
    left.plot([0, 1], [0, 1], label="first")
    right.plot([0, 1], [1, 0], label="second")
    text = describe_figure(fig)
    assert text.startswith("2 panels.")
    assert text.index("Panel 1 (left)") < text.index("Curve first") < text.index("Panel 2 (right)") \
        < text.index("Curve second")


def test_what_every_panel_shows_alike_is_said_once_before_the_panels():
    fig, (left, right) = plt.subplots(1, 2)
    for ax, label in ((left, "first"), (right, "second")):
        add_description(ax, "the same crank at 30 degrees")
        ax.plot([0, 1], [0, 1], label=label)
    text = describe_figure(fig)
    assert text.count("The same crank at 30 degrees.") == 1
    assert text.index("In every panel: The same crank at 30 degrees.") < text.index("Panel 1 (left)") \
        < text.index("Curve first") < text.index("Panel 2 (right)") < text.index("Curve second")


def test_a_sentence_of_a_figure_function_comes_first_and_its_artists_are_not_repeated():
    fig, ax = plt.subplots()
    line, = ax.plot([0.0, 1.0, 2.0], [0.0, 1.0, 0.0])
    add_description(ax, "a tent drawn by hand", [line])
    text = describe_figure(fig)
    assert "A tent drawn by hand." in text and "unlabelled" not in text


@pytest.mark.parametrize("bad", ["", "   ", None, 3])
def test_add_description_refuses_an_empty_sentence(bad):
    fig, ax = plt.subplots()
    with pytest.raises(InvalidParameterError, match="sentence"):
        add_description(ax, bad)


def test_an_empty_figure_has_an_empty_description():
    fig, _ = plt.subplots()
    assert describe_figure(fig) == ""


# --- in a notebook -------------------------------------------------------------------------------------------

def test_the_notebook_png_is_the_palette_png_with_the_description_beside_it():
    m, sol = crank_slider_at_90()
    fig = mech.plot.draw(m, sol).figure
    data, metadata = described_png(fig)
    assert data == palette_png(fig)                    # the stored image does not change
    assert metadata == {"alt": describe_figure(fig)} and "crank-slider" in metadata["alt"]


def test_ipython_stores_the_description_in_the_output_metadata():
    from IPython.core.interactiveshell import InteractiveShell

    from mechanisms.plot.workarounds import light_figures_in_notebooks

    shell = InteractiveShell.instance()
    try:
        light_figures_in_notebooks()
        m, sol = crank_slider_at_90()
        fig = mech.plot.draw(m, sol).figure
        data, metadata = shell.display_formatter.format(fig)
        assert data["image/png"] == palette_png(fig)
        assert "B (0.283, 0)" in metadata["image/png"]["alt"]
    finally:
        InteractiveShell.clear_instance()


def test_import_mechanisms_imports_no_ipython():
    code = "import sys, mechanisms; print('IPython' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


# --- scenes ---------------------------------------------------------------------------------------------------

def test_a_scene_still_has_a_title_and_a_description():
    m = mech.CrankSlider(crank=0.1, rod=0.3)
    s = scene(m, paths=["B"], arrows=[velocity("B")], title="an axial crank-slider", still_angle=math.pi / 2,
              omega=10.0, readout=[Readout("ψ", "°", lambda sol, mm: np.degrees(sol.angle("coupler").value), 1)])
    svg = ET.fromstring(re.search(r"<svg.*?</svg>", s.html(), re.S).group(0))
    assert svg.get("role") == "img"
    title, desc = svg.find(f"{SVG}title"), svg.find(f"{SVG}desc")
    assert title is not None and title.text == "an axial crank-slider"
    assert desc is not None and desc.text == s.description
    # by hand at φ = 90°: A = (0, 0.1) m, B = (0.283, 0) m; v_B = −ωL1(sin φ + λ sin 2φ / (2√(1 − λ² sin² φ)))
    # = −10·0.1·(1 + 0) = −1 m/s, along −x; ψ = −asin(L1/L2) = −asin(1/3) = −19.47°, printed to 1 decimal
    assert "crank angle φ = 90°" in s.description
    assert "A (0, 0.1), B (0.283, 0)" in s.description
    assert "v_B = 1 m/s, pointing at 180° from the x axis" in s.description
    assert "ψ = −19.5°" in s.description
    # B travels from L2 − L1 = 0.2 m to L2 + L1 = 0.4 m along the axis
    assert "Path of B (x from 0.2 to 0.4 m, y constant at 0 m)" in s.description
    assert "72 positions" in s.description


def test_an_explorer_says_what_its_sliders_change():
    from mechanisms.present.scene import Parameter, explorer

    e = explorer(lambda rod: mech.CrankSlider(crank=0.1, rod=rod),
                 [Parameter("rod", "L_2", "m", [0.2, 0.3, 0.4])], title="rod length", still={"rod": 0.3})
    assert "a slider for L₂ from 0.2 m to 0.4 m in 3 steps; the image shows L₂ = 0.3 m" in e.description
    assert "rod = 0.3 m" in e.description


# --- the Sphinx extension ---------------------------------------------------------------------------------------

def test_notebook_alternatives_find_an_output_by_the_hash_of_its_bytes():
    png = b"\x89PNG not really"
    notebook = {"cells": [{"cell_type": "code", "outputs": [
        {"output_type": "display_data", "data": {"image/png": base64.b64encode(png).decode()},
         "metadata": {"image/png": {"alt": "a  curve\nof s"}}},
        {"output_type": "display_data", "data": {"image/png": base64.b64encode(b"other").decode()},
         "metadata": {}}]}]}
    assert figure_alt.notebook_alternatives(notebook) == {hashlib.sha256(png).hexdigest(): "a curve of s"}


@pytest.mark.parametrize("alt, missing", [("", True), ("   ", True), ("_images/abc.png", True),
                                          ("abc.png", True), ("A graph of s against φ.", False)])
def test_missing_alternative(alt, missing):
    from docutils import nodes

    assert figure_alt.missing_alternative(nodes.image(uri="_images/abc.png", alt=alt)) is missing


def test_a_book_gets_the_alt_from_the_notebook_and_fails_on_a_figure_without_one(tmp_path):
    from sphinx.application import Sphinx

    fig, ax = plt.subplots()
    ax.plot([0.0, 90.0, 180.0], [0.0, 1.0, 0.0], label="tent")
    described, metadata = described_png(fig)
    bare = palette_png(plt.subplots()[0])

    def output(data: bytes, meta: dict) -> dict:
        return {"output_type": "display_data", "data": {"image/png": base64.b64encode(data).decode(),
                                                        "text/plain": ["<Figure>"]}, "metadata": meta}

    notebook = {"nbformat": 4, "nbformat_minor": 5, "metadata": {"kernelspec": {
        "name": "python3", "display_name": "Python 3", "language": "python"}}, "cells": [
        {"cell_type": "markdown", "id": "a", "metadata": {}, "source": "# Figures"},
        {"cell_type": "code", "id": "b", "metadata": {}, "execution_count": 1, "source": "plt.show()",
         "outputs": [output(described, {"image/png": metadata})]},
        {"cell_type": "code", "id": "c", "metadata": {}, "execution_count": 2, "source": "plt.show()",
         "outputs": [output(bare, {})]}]}
    source = tmp_path / "src"
    source.mkdir()
    (source / "index.ipynb").write_text(json.dumps(notebook))
    (source / "conf.py").write_text(f"import sys\nsys.path.insert(0, {str(ROOT / '_ext')!r})\n"
                                    "extensions = ['myst_nb', 'figure_alt']\nnb_execution_mode = 'off'\n")
    app = Sphinx(str(source), str(source), str(tmp_path / "html"), str(tmp_path / "doctrees"), "html",
                 status=None, warning=(warnings := __import__("io").StringIO()), freshenv=True)
    app.build()
    page = (tmp_path / "html" / "index.html").read_text()
    alts = re.findall(r'<img alt="([^"]*)"', page)
    # the tent rises from 0 at x = 0 to 1 at x = 90 and falls back: its description, as the page's alt
    assert len(alts) == 2 and "highest 1 at 90" in alts[0] and alts[0] == metadata["alt"]
    assert "has no text alternative" in warnings.getvalue() and "index" in warnings.getvalue()
    assert warnings.getvalue().count("has no text alternative") == 1
