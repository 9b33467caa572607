"""Layer 6: tables for people — Markdown tables in notebooks and the site."""

from __future__ import annotations

import contextlib
import math
import re
import textwrap
import warnings
from typing import Iterator, Sequence

from ..core.errors import MechanismError

__all__ = ["MarkdownTable", "markdown_table", "number", "difference", "magnitude", "show_messages"]


class MarkdownTable:
    """A table that a notebook shows as Markdown (and as the same text in plain output)."""

    def __init__(self, text: str):
        self.text = text

    def _repr_markdown_(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return self.text

    __str__ = __repr__


def number(value: float | complex | None, fmt: str = ".4g", unit: str = "") -> str:
    """A number for people, as the book prints it.

    Parameters
    ----------
    value : float, complex or None
        The number; ``None`` (a quantity that does not apply) is printed as ``—``. A complex number
        (a point or a vector of the plane) is printed as ``(x, y)``.
    fmt : str
        Format spec of each number (``".4f"``). A number that rounds to zero in it is printed without
        a sign: ``-0.0001`` with ``".3f"`` gives ``0.000``, never ``-0.000``.
    unit : str
        Appended after a space.

    Examples
    --------
    >>> number(-1e-17, ".4f", "m")
    '0.0000 m'
    >>> number(0.3 - 2e-17j, ".4f")
    '(0.3000, 0.0000)'
    """
    if value is None:
        text = "—"
    elif isinstance(value, complex):
        text = f"({number(value.real, fmt)}, {number(value.imag, fmt)})"
    else:
        text = format(value, fmt)
        if "-" in text and _rounds_to_zero(text):
            text = format(0.0, fmt)
    return f"{text} {unit}".rstrip()


def _cell(value, fmt: str) -> str:
    """One cell: a string as it is, a number as :func:`number` prints it (``None`` as ``—``)."""
    if isinstance(value, str):
        return value
    return number(value, fmt)


def _rounds_to_zero(text: str) -> bool:
    """Whether a formatted number shows only zeros (its exponent aside): ``"-0.000"``, ``"-0e+00"``."""
    mantissa = re.split(r"[eE]", text, maxsplit=1)[0]
    digits = re.findall(r"[0-9]", mantissa)
    return bool(digits) and set(digits) == {"0"} and not re.search(r"(?i)inf|nan", text)


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence], formats: str | Sequence[str] = ".4g",
                   align: str | None = None) -> MarkdownTable:
    """Build a Markdown table.

    Parameters
    ----------
    headers : sequence of str
        Column headings, with units (``"ω2, 1/s"``).
    rows : sequence of sequences
        The cells; numbers are formatted (see :func:`number`; ``None`` is ``—``), strings kept.
    formats : str or sequence of str
        Format spec for numbers, one for all columns or one per column (``".3f"``). A number that
        rounds to zero in its format is printed without a sign (``0.000``, never ``-0.000``).
    align : str, optional
        One letter per column: ``l``, ``c`` or ``r`` (default: right).
    """
    if isinstance(formats, str):
        formats = [formats] * len(headers)
    align = align or "r" * len(headers)
    rule = {"l": ":---", "c": ":---:", "r": "---:"}
    lines = ["| " + " | ".join(headers) + " |", "|" + "|".join(rule[a] for a in align) + "|"]
    for row in rows:
        lines.append("| " + " | ".join(_cell(v, f) for v, f in zip(row, formats)) + " |")
    return MarkdownTable("\n".join(lines))


def difference(value: float, floor: float = 1e-12, unit: str = "") -> str:
    """A checked difference for people: ``"3.4e-06 m"``, or ``"< 1e-12 m"`` at round-off.

    The digits of a round-off difference change with the order of floating-point operations;
    printing them would make the book's stored outputs fragile and suggest a precision that is
    not there. Below ``floor`` (relative to values of order 1) the difference is printed as a bound.
    """
    text = f"< {floor:.0e}" if abs(value) < floor else f"{value:.1e}"
    return f"{text} {unit}".rstrip()


def magnitude(value: float) -> str:
    """The power of ten nearest to a round-off error, for people: ``"≈ 1e-10"`` for 4.8e-11.

    An error made of rounding changes its digits with the order of floating-point operations, but
    rarely its order of magnitude; chapter 9 compares such errors with estimates like ε_mach/Δφ.
    """
    if value == 0.0:
        return "0"
    if not math.isfinite(value):
        return str(value)
    return f"≈ 1e{round(math.log10(abs(value)))}"


@contextlib.contextmanager
def show_messages(width: int = 76) -> Iterator[None]:
    """Print the package's warnings and errors raised in a ``with`` block, instead of stopping there.

    Each warning is printed as it is raised (every time, not once per place), and an error of the
    package (:class:`~mechanisms.MechanismError`) ends the block and is printed; the cell goes on
    after the block. Other exceptions are not caught. A notebook shows what the package says with
    ``with mech.show_messages(): sol = m.solve(...)``.

    Parameters
    ----------
    width : int
        The printed lines' width in characters: the message is wrapped, prefixed with its class
        name (``AssemblyError: …``).
    """
    def show(kind: type, message: object) -> None:
        print(textwrap.fill(f"{kind.__name__}: {message}", width))

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        except MechanismError as error:
            for item in caught:
                show(item.category, item.message)
            caught.clear()
            show(type(error), error)
        for item in caught:
            show(item.category, item.message)
