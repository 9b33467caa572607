"""The book's colours are readable (issue 32): every colour a figure or a scene draws a line in keeps a
contrast of at least 3:1 against white, the background of the figures and of the player in the site's
light and dark modes (WCAG 2.1 success criterion 1.4.11, non-text contrast); the vectors' colours, in
which the scenes also write the vectors' labels, at least 4.5:1 (1.4.3, text).

The contrast ratio is computed here from WCAG 2.1's definitions, not taken from the package:
relative luminance L = 0.2126 R + 0.7152 G + 0.0722 B of the linearised sRGB channels
(c/12.92 if c ≤ 0.04045 else ((c + 0.055)/1.055)^2.4, c = channel/255), and the ratio
(L_lighter + 0.05)/(L_darker + 0.05).
"""

from __future__ import annotations

import colorsys

import pytest

from mechanisms.present import colours

WHITE = "#ffffff"
LINE = 3.0     # WCAG 1.4.11: graphical objects
TEXT = 4.5     # WCAG 1.4.3: normal-size text


def channels(colour: str) -> tuple[int, int, int]:
    return int(colour[1:3], 16), int(colour[3:5], 16), int(colour[5:7], 16)


def relative_luminance(colour: str) -> float:
    def linear(c: int) -> float:
        s = c / 255.0
        return s / 12.92 if s <= 0.04045 else ((s + 0.055) / 1.055) ** 2.4
    r, g, b = (linear(c) for c in channels(colour))
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(a: str, b: str) -> float:
    lighter, darker = sorted((relative_luminance(a), relative_luminance(b)), reverse=True)
    return (lighter + 0.05) / (darker + 0.05)


def test_the_formula_by_hand():
    # black on white: (1 + 0.05)/(0 + 0.05) = 21
    assert contrast("#000000", WHITE) == pytest.approx(21.0)
    # #767676, the familiar lightest grey with 4.5:1 on white: 118/255 = 0.46275,
    # L = ((0.46275 + 0.055)/1.055)^2.4 = 0.18116, ratio 1.05/(0.18116 + 0.05) = 4.542
    assert contrast("#767676", WHITE) == pytest.approx(4.542, abs=1e-3)
    # #949494, just above 3:1: 148/255 = 0.58039, L = 0.60227^2.4 = 0.29614, ratio 1.05/0.34614 = 3.033;
    # #aaaaaa, below it: 170/255 = 0.66667, L = 0.68404^2.4 = 0.40198, ratio 1.05/0.45198 = 2.323
    assert contrast("#949494", WHITE) == pytest.approx(3.033, abs=1e-3)
    assert contrast("#aaaaaa", WHITE) == pytest.approx(2.323, abs=1e-3)
    # the ratio does not depend on the order
    assert contrast(WHITE, "#1f77b4") == contrast("#1f77b4", WHITE)


def line_colours() -> dict[str, str]:
    found = {f"ROLE_COLOURS[{role!r}]": c for role, c in colours.ROLE_COLOURS.items()}
    found |= {f"PATH_COLOURS[{k}]": c for k, c in enumerate(colours.PATH_COLOURS)}
    found |= {"PATH_COLOUR": colours.PATH_COLOUR, "VELOCITY_COLOUR": colours.VELOCITY_COLOUR,
              "ACCELERATION_COLOUR": colours.ACCELERATION_COLOUR}
    return found


@pytest.mark.parametrize(("name", "colour"), line_colours().items())
def test_every_line_colour_has_3_to_1_on_white(name, colour):
    assert contrast(colour, WHITE) >= LINE, f"{name} = {colour} has {contrast(colour, WHITE):.2f}:1 on white"


@pytest.mark.parametrize("name", ["VELOCITY_COLOUR", "ACCELERATION_COLOUR"])
def test_the_vectors_labels_are_readable_text(name):
    colour = getattr(colours, name)
    assert contrast(colour, WHITE) >= TEXT, f"{name} = {colour} has {contrast(colour, WHITE):.2f}:1 on white"


def test_the_slider_outline_shows_on_its_block():
    # the block's outline separates its fill from the white around it: it must stand out from both
    slider = colours.ROLE_COLOURS["slider"]
    assert contrast(slider, colours.BLOCK_FILL) >= LINE
    assert contrast(slider, WHITE) >= LINE


def hue(colour: str) -> float:
    return 360.0 * colorsys.rgb_to_hsv(*(c / 255.0 for c in channels(colour)))[0]


# matplotlib's "tab10" colours the book used before issue 32, too faint on white: each darker stand-in
# keeps its hue (within 6°), so a reader who knew the old figures finds the same orange, cyan, pink and
# olive; the grey of a path stays a neutral grey.
FORMER = {
    "ROLE_COLOURS['point']": "#ff7f0e",
    "PATH_COLOURS[1]": "#ff7f0e",
    "PATH_COLOURS[3]": "#bcbd22",
    "VELOCITY_COLOUR": "#17becf",
    "ACCELERATION_COLOUR": "#e377c2",
}


@pytest.mark.parametrize(("name", "former"), FORMER.items())
def test_darker_colours_keep_their_hue(name, former):
    colour = line_colours()[name]
    assert contrast(former, WHITE) < LINE <= contrast(colour, WHITE)   # it was too faint, it is not
    difference = abs(hue(colour) - hue(former)) % 360.0
    assert min(difference, 360.0 - difference) <= 6.0, f"{name}: {former} → {colour} changes the hue"


def test_the_path_is_a_grey_fainter_than_the_links():
    r, g, b = channels(colours.PATH_COLOUR)
    assert r == g == b
    fainter = relative_luminance(colours.PATH_COLOUR)
    assert all(fainter > relative_luminance(c) for c in colours.ROLE_COLOURS.values())


def test_the_vectors_differ_from_every_path_and_link():
    # distinct colours: a vector is never drawn in the colour of a path or of a link
    drawn = set(colours.PATH_COLOURS) | set(colours.ROLE_COLOURS.values()) | {colours.PATH_COLOUR}
    assert {colours.VELOCITY_COLOUR, colours.ACCELERATION_COLOUR}.isdisjoint(drawn)
