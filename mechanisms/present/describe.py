"""Layer 6: the words of the figures' text alternatives — numbers, points, math and mechanisms as text.

No matplotlib here: the scenes' still images (:mod:`mechanisms.present.scene`) and the figures
(:mod:`mechanisms.plot.describe`) describe themselves with the same words. Numbers are rounded to
three significant figures after rounding to nine, so that a last-bit difference of a processor cannot
move them: the same figure has the same text on every machine.
"""

from __future__ import annotations

import math
import re
from typing import Mapping, Sequence

import numpy as np

from ..linkages.base import Bar, Block, Ground, Guide, Mechanism

__all__ = ["plain_text", "value_text", "angle_text", "point_text", "extent_text", "series", "sentence",
           "mechanism_name", "position_sentence"]

# --- words and numbers ----------------------------------------------------------------------------------

_TEX_SYMBOLS = {
    r"\varphi": "φ", r"\phi": "φ", r"\psi": "ψ", r"\xi": "ξ", r"\omega": "ω", r"\Omega": "Ω", r"\alpha": "α",
    r"\beta": "β", r"\gamma": "γ", r"\delta": "δ", r"\Delta": "Δ", r"\epsilon": "ε", r"\varepsilon": "ε",
    r"\theta": "θ", r"\lambda": "λ", r"\mu": "μ", r"\nu": "ν", r"\pi": "π", r"\rho": "ρ", r"\sigma": "σ",
    r"\tau": "τ", r"\eta": "η", r"\zeta": "ζ", r"\kappa": "κ", r"\chi": "χ", r"\cdot": "·", r"\times": "×",
    r"\infty": "∞", r"\propto": "∝", r"\approx": "≈", r"\leq": "≤", r"\geq": "≥", r"\le": "≤", r"\ge": "≥",
    r"\pm": "±", r"\ldots": "…", r"\dots": "…", r"\circ": "°", r"\prime": "′", r"\to": "→", r"\sum": "Σ",
    r"\partial": "∂", r"\sqrt": "√", r"\,": " ", r"\;": " ", r"\:": " ", r"\!": "", r"\ ": " ", r"\quad": " ",
    r"\%": "%", r"\{": "{", r"\}": "}",
}
_SUB = str.maketrans("0123456789+-=()aehijklmnoprstuvx", "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ")
_SUP = str.maketrans("0123456789+-=()ni", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁿⁱ")
_SUB_CHARS = set("0123456789+-=()aehijklmnoprstuvx")
_SUP_CHARS = set("0123456789+-=()ni")


_FORMATTING = (r"\\(?:mathrm|mathit|mathbf|mathcal|mathbb|boldsymbol|text|operatorname|mathsf|bar|hat|vec|tilde"
               r"|overline)\s*\{([^{}]*)\}")
"""A command that sets its argument in a font or with an accent: the text keeps the argument."""


def _script(text: str, marker: str) -> str:
    """A sub- or superscript in Unicode where every character has a form, else ``_text`` / ``^text``."""
    chars, table = (_SUB_CHARS, _SUB) if marker == "_" else (_SUP_CHARS, _SUP)
    if text and set(text) <= chars:
        return text.translate(table)
    if len(text) == 1 and marker == "^" and text == "′":
        return text
    return marker + text


def _math(tex: str) -> str:
    r"""The text of one piece of mathtext (between dollars): ``\varphi_{1}`` → ``φ₁``."""
    text = re.sub(_FORMATTING, r"{\1}", tex)
    text = re.sub(r"\\(?:left|right|big|Big)\s*", "", text)
    text = re.sub(r"\\frac\s*\{([^{}]*)\}\s*\{([^{}]*)\}", r"\1/\2", text)
    # a symbol's character; a command not known, its name (an escaped character, the character)
    text = re.sub(r"\\([A-Za-z]+|.)", lambda m: _TEX_SYMBOLS.get("\\" + m.group(1), m.group(1)), text)
    text = re.sub(r"([_^])(?:\{([^{}]*)\}|(\S))", lambda m: _script(m.group(2) or m.group(3) or "", m.group(1)),
                  text)
    return text.replace("{", "").replace("}", "")


def plain_text(text: str) -> str:
    r"""A figure's text (matplotlib mathtext) as a screen reader reads it: ``"$v_B$, m/s"`` → ``"v_B, m/s"``.

    Greek letters and symbols become their Unicode characters, sub- and superscripts Unicode sub- and
    superscripts where every character has one (``$L_1$`` → ``L₁``, ``$h^2$`` → ``h²``), else they are
    written after ``_`` or ``^`` (``$v_{BA}$`` → ``v_BA``); braces and formatting commands go.

    Parameters
    ----------
    text : str
        A title, label or legend entry; the parts between dollars are mathtext.

    Returns
    -------
    str
    """
    parts = re.split(r"(?<!\\)\$", str(text))
    out = [part if index % 2 == 0 else _math(part) for index, part in enumerate(parts)]
    return re.sub(r"\s+", " ", "".join(out).replace(r"\$", "$")).strip()


def _rounded(value: float, digits: int = 3) -> float:
    """``value`` to ``digits`` significant figures, after nine: a last bit of round-off cannot move it."""
    return float(f"{float(f'{value:.9g}'):.{digits}g}")


def value_text(value: float, unit: str = "", digits: int = 3, tiny: float = 0.0) -> str:
    """A number as a description writes it: three significant figures, a real minus, ``×10`` powers.

    Parameters
    ----------
    value : float
        The number; infinite is ``∞``, not a number is ``undefined``.
    unit : str
        Its unit, after a space (``°`` and ``%`` without one).
    digits : int
        Significant figures.
    tiny : float
        A value smaller in size is written ``0``: the round-off of a value that is zero (a sighted
        reader sees zero), e.g. 10⁻⁹ of the largest value of the figure.

    Returns
    -------
    str
        ``0.25 m``, ``−1.2×10⁻⁵ m``, ``90°``; never ``-0``.
    """
    value = float(value)
    if math.isnan(value):
        return "undefined"
    if math.isinf(value):
        text = "∞" if value > 0 else "−∞"
    else:
        rounded = 0.0 if abs(value) < tiny else _rounded(value, digits)
        if rounded == 0:
            text = "0"
        elif 1e-4 <= abs(rounded) < 1e6:        # 4680, 0.000782: no power of ten
            text = f"{rounded:.{digits}g}"
            if "e" in text:
                text = f"{rounded:.0f}"
        else:
            text = f"{rounded:.{digits}g}"
        if "e" in text:
            mantissa, exponent = text.split("e")
            power = f"10{str(int(exponent)).translate(_SUP)}"
            text = power if mantissa in ("1", "-1") else f"{mantissa}×{power}"
            text = ("-" + text) if mantissa == "-1" else text
        text = text.replace("-", "−")
    if not unit:
        return text
    return f"{text}{unit}" if unit in ("°", "%") else f"{text} {unit}"


def point_text(point: complex, unit: str = "m", tiny: float = 0.0) -> str:
    """A point of the plane as a description writes it: ``(0.0866, 0.05) m`` (coordinates below ``tiny``: 0)."""
    return (f"({value_text(point.real, tiny=tiny)}, {value_text(point.imag, tiny=tiny)})"
            + (f" {unit}" if unit else ""))


def series(items: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    items = [item for item in items if item]
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


def sentence(text: str) -> str:
    """``text`` as a sentence: its first word capitalised (not a symbol: ``s``, ``v_B`` stay), a full stop."""
    text = text.strip()
    if not text:
        return ""
    if re.match(r"(?:[a-z]{2,}|a [a-z]{2,})\b", text):      # a word, not a symbol (s, v_B, φ)
        text = text[0].upper() + text[1:]
    return text if text.endswith((".", "!", "?")) else text + "."




def angle_text(radians: float, symbol: str = "φ") -> str:
    """A crank angle as a description writes it, in degrees from 0 to 360 to a tenth: ``φ = 30°``."""
    degrees = _rounded(math.degrees(float(radians)), 9) % 360.0
    degrees = round(degrees, 1) % 360.0
    return f"{symbol} = {degrees:g}°" if symbol else f"{degrees:g}°"


def mechanism_name(mechanism: Mechanism) -> str:
    """What a mechanism is called in a sentence: ``crank-slider``, a linkage file's name, or its class's."""
    name = getattr(mechanism, "name", None) or mechanism.cli_name
    if not name:
        name = re.sub(r"(?<=[a-z])(?=[A-Z])", " ", type(mechanism).__name__).lower()
    return str(name)


def _parameters(mechanism: Mechanism) -> str:
    """The mechanism's parameters as :meth:`~mechanisms.linkages.base.Mechanism.describe` writes them."""
    text = mechanism.describe()
    text = text.split(": ", 1)[1] if ": " in text else ""
    return re.sub(r"(?<![\w.])-(?=\d)", "−", text)


def position_sentence(mechanism: Mechanism, where: Mapping[str, complex], phi: float,
                      letters: Mapping[str, str] | None = None, symbol: str = "φ") -> str:
    """What a drawing of a mechanism at one position shows: its links, supports and joints, with coordinates.

    Parameters
    ----------
    mechanism : Mechanism
        What is drawn (its :meth:`~mechanisms.linkages.base.Mechanism.scheme`).
    where : mapping
        ``{joint: position}`` (complex, m) at that position; joints missing or not finite are left out.
    phi : float
        The crank angle (rad).
    letters : mapping, optional
        ``{package name: page letter}``: the joints are named as the page names them.
    symbol : str
        The crank angle's symbol.

    Returns
    -------
    str
        Two or three sentences.
    """
    letters = dict(letters or {})

    def name(joint: str) -> str:
        label = letters.get(joint, joint)
        return _joint_name(label) if re.fullmatch(r"[A-Za-z]+\d*", label) else plain_text(label)

    parameters = _parameters(mechanism)
    head = f"The {mechanism_name(mechanism)}" + (f" ({parameters})" if parameters else "")
    head += f" drawn at crank angle {angle_text(phi, symbol)}"
    links, pivots, blocks, guides = [], [], [], 0
    for item in mechanism.scheme():
        if isinstance(item, Bar):
            links.append(f"{item.link} {'–'.join(name(j) for j in item.joints)}"
                         + (f" ({item.role})" if item.role not in item.link else ""))
        elif isinstance(item, Ground):
            pivots.append(name(item.joint))
        elif isinstance(item, Block):
            blocks.append(name(item.joint))
        elif isinstance(item, Guide):
            guides += 1
    parts = [head + (": links " + series(links) if links else "")]
    if pivots:
        parts.append(f"fixed pivot{'s' if len(pivots) > 1 else ''} at {series(pivots)}")
    if blocks:
        parts.append(f"sliding block{'s' if len(blocks) > 1 else ''} at {series(blocks)}"
                     + (f" ({guides} fixed guide{'s' if guides > 1 else ''})" if guides else ""))
    finite = {j: p for j, p in where.items() if math.isfinite(p.real) and math.isfinite(p.imag)}
    tiny = 1e-9 * max([abs(p) for p in finite.values()], default=0.0)
    shown = [f"{name(j)} {point_text(p, '', tiny)}" for j, p in finite.items()]
    text = sentence("; ".join(parts))
    if shown:
        text += " " + sentence("Joints (x, y) in m: " + ", ".join(shown))
    return text


def _joint_name(name: str) -> str:
    """A joint's name as read: ``O2`` → ``O₂`` (as the drawings set it, digits as a subscript)."""
    match = re.fullmatch(r"([A-Za-z]+?)(\d*)", name)
    if match is None:
        return name
    return match.group(1) + match.group(2).translate(_SUB)


def extent_text(points: Sequence[complex] | np.ndarray, unit: str = "m") -> str:
    """Where points of the plane lie: ``x from 0.2 to 0.4 m, y constant at 0 m`` (their bounding box).

    Coordinates smaller than 10⁻⁹ of the largest are round-off of a zero and read ``0``.
    """
    values = np.asarray(points, dtype=complex).ravel()
    values = values[np.isfinite(values)]
    if values.size == 0:
        return "no finite points"
    tiny = 1e-9 * float(np.max(np.abs(values)))
    out = []
    for name, coordinate in (("x", values.real), ("y", values.imag)):
        low = value_text(float(coordinate.min()), tiny=tiny)
        high = value_text(float(coordinate.max()), tiny=tiny)
        out.append(f"{name} constant at {value_text(float(coordinate.max()), unit, tiny=tiny)}" if low == high
                   else f"{name} from {low} to {value_text(float(coordinate.max()), unit, tiny=tiny)}")
    return ", ".join(out)
