"""Layer 6: the command-line tool, ``python -m mechanisms``.

``table`` prints the kinematic table of a mechanism over crank positions, like the classic
course programs do for 12 positions. Every mechanism class that sets ``cli_name`` appears
as a ``table`` subcommand with its ``cli_parameters``; degrees at the interface, radians inside.
``assign`` and ``check`` set and grade course assignments (:mod:`mechanisms.course.assign`,
:mod:`mechanisms.course.grading`).
"""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path
import math
import os
import pathlib
import re
import sys
import warnings
from typing import Any, Callable, Iterator, Sequence, cast

import numpy as np

from .linkages.base import Mechanism, Solution, registry
from .linkages.linkage_file import FORMAT_SUMMARY, load_linkage
from .core.errors import AssemblyError, SingularPositionWarning, InvalidParameterError, MechanismError
from .core.angles import reduce_degrees
from .core.motion import Motion

__all__ = ["main", "kinematic_table", "parse_number", "parse_angles", "parse_angles_deg", "to_radians", "parse_point",
           "MAX_POSITIONS"]

MAX_POSITIONS = 10_000_000
"""The most crank positions a table may have (a larger one would not fit in memory as text), and the largest
size the benchmark takes (``bench --sizes``)."""

MAX_REPEAT = 1000
"""The most runs ``bench --repeat`` takes (each run times every method at every size)."""


_NUMBER = re.compile(r"[-+]?((\d+\.?\d*|\.\d+)(e[-+]?\d+)?|inf|infinity|nan)", re.IGNORECASE | re.ASCII)
_WHOLE = re.compile(r"[-+]?\d+", re.ASCII)


def _number_hint(text: str) -> str:
    """What is wrong with a number that is not one, in the few cases that have a likely cause."""
    if "\u2013" in text:
        return " (write the minus sign as '-', not the en dash '–')"
    if "," in text:
        return " (the decimal separator is a point: 0.5, not 0,5)"
    return ""


def parse_number(text: str) -> float:
    """The one parser of the command line's numbers: a decimal or scientific number (``-1e3``, ``.5``,
    ``-5e-2``, also with the Unicode minus ``−``) in ASCII → float. ``nan`` and ``inf`` are read too (as floats are) and refused by the parameter's own
    validation, which names the parameter; anything else (a comma, a Unicode digit, ``1_000``, hex)
    raises :class:`ValueError`."""
    if isinstance(text, str):
        text = text.strip().replace("\u2212", "-")      # the Unicode minus that word processors write
    if not isinstance(text, str) or not _NUMBER.fullmatch(text):
        raise ValueError(f"not a number: {text!r}{_number_hint(text) if isinstance(text, str) else ''}")
    return float(text)


def _cli_number(text: str) -> float:
    """:func:`parse_number` for argparse: a value that is not a number is a usage error naming the option."""
    try:
        return parse_number(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number (e.g. 0.3, -1e3), got {text!r}"
                                         f"{_number_hint(text)}") from None


def _cli_whole(text: str) -> int:
    """A whole number in ASCII digits for argparse (``12``, ``-3``); its range is checked where it is used."""
    text = text.strip().replace("\u2212", "-")
    if not _WHOLE.fullmatch(text):
        raise argparse.ArgumentTypeError(f"expected a whole number (e.g. 12), got {text!r}{_number_hint(text)}")
    return int(text)


def _angle_range(text: str) -> tuple[float, float, int]:
    """``START:STOP:STEP`` (°) → (start, step, count), checked as :func:`parse_angles_deg` says."""
    try:
        start, stop, step = (parse_number(v) for v in text.split(":"))
    except ValueError:
        raise InvalidParameterError("--angles", text, "START:STOP:STEP in degrees, e.g. 0:360:30") from None
    if not all(math.isfinite(v) for v in (start, stop, step)):
        raise InvalidParameterError("--angles", text, "START:STOP:STEP of finite numbers of degrees")
    with np.errstate(over="ignore"):
        count_exact = (stop - start) / step if step != 0 else math.nan   # may overflow to ±inf
    if not count_exact > 0:
        raise InvalidParameterError("--angles", text, "START:STOP:STEP with a step other than 0 that goes from "
                                    "START towards STOP")
    if count_exact > MAX_POSITIONS:
        raise InvalidParameterError("--angles", text, f"at most {MAX_POSITIONS} positions")
    # count the positions first: np.arange with a fractional step may include STOP by round-off
    count = max(1, math.ceil(count_exact - 1e-9))   # START itself at least
    if not math.isfinite(start + step * (count - 1)):   # e.g. -1e308:1.7e308:1e308 runs past the largest double
        raise InvalidParameterError("--angles", text, "START:STOP:STEP whose angles are finite numbers of degrees")
    return start, step, count


def _angles_between(start: float, step: float, first: int, stop: int) -> np.ndarray:
    """The angles (°) of positions ``first`` … ``stop − 1`` of the range START, START + STEP, …"""
    return start + step * np.arange(first, stop)


def parse_angles_deg(text: str) -> np.ndarray:
    """``START:STOP:STEP`` in degrees (stop excluded) → the crank angles in degrees, as asked (not reduced).

    A range shorter than one step gives START alone (one position); a step that leads away from
    STOP, a step of 0, or more than :data:`MAX_POSITIONS` positions is an
    :class:`~mechanisms.core.errors.InvalidParameterError` naming ``--angles``.
    """
    start, step, count = _angle_range(text)
    return _angles_between(start, step, 0, count)


def to_radians(degrees: Any, name: str) -> Any:
    """Degrees as a person gives them → radians for the package: reduced exactly first, in degrees
    (:func:`~mechanisms.core.angles.reduce_degrees`: ``fmod`` by 360°), so that 1e15° is the same
    direction as 280°, to the last digit; radians are taken only of the reduced angle. ``name`` is the
    option named by the error for a value that is not a finite number."""
    reduced = reduce_degrees(degrees, name)
    return math.radians(reduced) if isinstance(reduced, float) else np.radians(reduced)


def parse_angles(text: str) -> np.ndarray:
    """``START:STOP:STEP`` in degrees (stop excluded) → crank angles in rad, each reduced to (−π, π].

    The angles of :func:`parse_angles_deg`, reduced exactly in degrees before they become radians
    (:func:`to_radians`).
    """
    return to_radians(parse_angles_deg(text), "--angles")


def parse_point(text: str) -> tuple[str, str, float, float]:
    """``NAME=LINK:U[,W]`` → (name, link, u, w) with u, w in m (the book's point fixed to a link)."""
    try:
        name, rest = text.split("=", 1)
        link, coords = rest.split(":", 1)
        values = [parse_number(v) for v in coords.split(",")]
        if not name or not link or len(values) not in (1, 2) or not all(map(math.isfinite, values)):
            raise ValueError
    except ValueError:
        raise InvalidParameterError("--point", text, "NAME=LINK:U or NAME=LINK:U,W (m), e.g. S2=coupler:0.09") from None
    return name, link, values[0], values[1] if len(values) == 2 else 0.0


def _pair(text: str) -> tuple[float, float]:
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected two numbers A,B, got {text!r}")
    try:
        return parse_number(parts[0]), parse_number(parts[1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected two numbers A,B, got {text!r}") from None


def _branch(text: str) -> int:
    if text.strip() not in ("1", "+1", "-1"):
        raise argparse.ArgumentTypeError(f"expected +1 or -1, got {text!r}")
    return int(text)


_KINDS: dict[str, Callable[[str], Any]] = {"length": _cli_number, "number": _cli_number, "angle": _cli_number,
                                          "pair": _pair, "branch": _branch}


def _class_value(parameter, value):
    """A command-line value as the mechanism's class takes it: angles from degrees to radians (reduced
    exactly first, :func:`to_radians`)."""
    if parameter.kind == "angle" and value is not None:
        return to_radians(value, f"--{parameter.name.replace('_', '-')}")
    return value


def _number(value: float):
    """A JSON-safe number: unbounded values (singular positions) become null."""
    value = float(value)
    return value if math.isfinite(value) else None


def kinematic_table(mechanism: Mechanism, solution: Solution,
                    points: Sequence[tuple[str, str, float, float]] = (), phi_deg: Any = None) -> list[dict]:
    """Rows of the kinematic table: one dict per crank position, keys as in docs/DESIGN.md's JSON.

    ``phi_deg``, if given, holds the crank angles as they were asked for (°, one per position of the
    solution, before the exact reduction of :func:`to_radians`): they are printed as ``phi_deg`` and as
    the crank's ``angle_deg``, so that ``--angles 1e15:…`` shows 1e15°, not its remainder 280°. By
    default both come from the solution's φ.
    """
    extra = {name: solution.point_on(link, u, w) for name, link, u, w in points}
    all_points = {name: solution.point(name) for name in solution.point_names} | extra
    asked = np.degrees(solution.phi) if phi_deg is None else np.asarray(phi_deg, dtype=float).reshape(-1)
    # the crank: the link whose angle is φ itself
    crank = {name for name in solution.angle_names if np.array_equal(solution.angle(name).value, solution.phi)}
    rows = []
    for i in range(len(solution)):
        links = {}
        for name in solution.angle_names:
            a = solution.angle(name)
            degrees = asked[i] if name in crank else np.degrees(a.value[i])
            links[name] = {"angle_deg": _number(degrees), "omega": _number(a.omega[i]),
                           "alpha": _number(a.alpha[i])}
        pts = {}
        for name, p in all_points.items():
            pts[name] = {"x": _number(p.x[i]), "y": _number(p.y[i]),
                         "vx": _number(p.velocity[i].real), "vy": _number(p.velocity[i].imag),
                         "ax": _number(p.acceleration[i].real), "ay": _number(p.acceleration[i].imag)}
        sliders = {}
        for name in solution.slider_names:
            s: Motion = solution.slider(name)
            sliders[name] = {"s": _number(s.value[i]), "v": _number(s.velocity[i]), "a": _number(s.acceleration[i])}
            for key, values in solution.extras.get(name, {}).items():
                sliders[name][key] = _number(values[i])
        rows.append({"phi_deg": _number(round(float(asked[i]), 9)), "links": links, "points": pts,
                     "sliders": sliders})
    return rows


def _flat(row: dict) -> dict:
    flat = {"phi_deg": row["phi_deg"]}
    for group in ("links", "points", "sliders"):
        for name, values in row[group].items():
            for key, value in values.items():
                flat[f"{name}.{key}"] = value
    if "forces" in row:
        from .analysis.kinetostatics import force_columns
        flat |= force_columns(row["forces"])
    return flat


def _blocks(row: dict, group: str) -> dict:
    """A group of a row as the text table's blocks (the forces: a block each for M_d, a joint, a sliding pair)."""
    if group != "forces":
        return row[group]
    if "forces" not in row:        # a table without --forces imports no analysis
        return {}
    from .analysis.kinetostatics import force_blocks
    return force_blocks(row["forces"])


_UNITS = {"angle_deg": "°", "omega": "1/s", "alpha": "1/s²", "x": "m", "y": "m", "vx": "m/s", "vy": "m/s",
          "ax": "m/s²", "ay": "m/s²", "s": "m", "v": "m/s", "a": "m/s²", "coriolis": "m/s²",
          "M_d": "N·m", "Fx": "N", "Fy": "N", "N": "N", "M": "N·m"}

CHUNK = 4096
"""Crank positions solved, formatted and written at a time: the table's memory does not grow with its length."""


def _readable(value: float | None, scale: float) -> str:
    """Six significant digits; round-off below 1e-12 of the column's scale printed as 0."""
    if value is None:
        return "—"
    return "0" if abs(value) <= 1e-12 * scale else f"{value:.6g}"


class _Table:
    """The kinematic table of a mechanism over crank positions, solved and written chunk by chunk.

    Every pass over the positions solves them again, :data:`CHUNK` at a time, so that no array or row
    over all positions is ever held: CSV and JSON are written in one pass, the text table (a block
    per link, point and slider, its columns aligned) in one pass that measures the columns and one
    per block that writes it.
    """

    def __init__(self, mechanism: Mechanism, degree_chunks: Callable[[], Iterator[np.ndarray]], omega: float,
                 alpha: float, points: Sequence[tuple[str, str, float, float]], asked: dict[str, Any] | None = None,
                 forces: bool = False):
        """``degree_chunks()`` yields the crank angles in degrees as asked, a chunk at a time; ``asked`` holds the
        mechanism's parameters as given on the command line (angles in degrees), for the JSON head; ``forces``
        adds each row's joint forces and driving torque (:func:`~mechanisms.analysis.kinetostatics.force_rows`)."""
        self.mechanism, self.degree_chunks, self.omega, self.alpha = mechanism, degree_chunks, omega, alpha
        self.points, self.asked, self.forces = points, asked, forces

    def phi_chunks(self) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """Each chunk's crank angles as asked (°) and as solved (rad, reduced exactly: :func:`to_radians`)."""
        for degrees in self.degree_chunks():
            yield degrees, to_radians(degrees, "--angles")

    def solutions(self, order: int = 2) -> Iterator[tuple[np.ndarray, Solution]]:
        """The solution of each chunk of positions, with its angles as asked (°) (singular positions:
        unbounded values, no warning)."""
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SingularPositionWarning)  # unbounded values print as — / null
            for degrees, phi in self.phi_chunks():
                yield degrees, self.mechanism.solve(phi, self.omega, self.alpha, order=order)

    def rows(self):
        """The rows of each chunk (lists of dicts, keys as in docs/DESIGN.md's JSON)."""
        for degrees, solution in self.solutions():
            rows = kinematic_table(self.mechanism, solution, self.points, phi_deg=degrees)
            if self.forces:
                from .analysis.kinetostatics import force_rows, linkage_forces
                for row, forces in zip(rows, force_rows(linkage_forces(self.mechanism, solution))):
                    row["forces"] = forces
            yield rows

    def check(self) -> list[str]:
        """Solve every position once (positions only) before anything is written: an input that cannot be
        assembled gets its error, naming every crank angle that fails, and no half-written table.
        Returns the names of the mechanism's joints."""
        failed: list[np.ndarray] = []
        first: AssemblyError | None = None
        joints: list[str] = []
        for index, (degrees, phi) in enumerate(self.phi_chunks()):
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", SingularPositionWarning)
                    # the first chunk to the full order, so that the crank's speed is checked too
                    solution = self.mechanism.solve(phi, self.omega, self.alpha, order=0 if index else 2)
                joints = solution.point_names
                if not index and self.forces:    # a class III group is refused before anything is written
                    from .analysis.kinetostatics import linkage_forces
                    linkage_forces(self.mechanism, solution)
                if not index:    # the points' distances too (the links are named by _table, after this)
                    for _, link, u, w in self.points:
                        if link in self.mechanism.links:
                            solution.point_on(link, u, w)
            except AssemblyError as error:
                first = first or error
                # named as asked (1e15°, not its remainder 280°)
                where = np.isin(phi, error.angles) if error.angles is not None else np.ones(phi.shape, bool)
                failed.append(np.radians(degrees[where]) if where.any() or error.angles is None else error.angles)
        if first is not None:
            raise AssemblyError(first.reason, np.concatenate(failed), first.valid_range)
        return joints

    def write_json(self, out) -> None:
        # as the command line takes them: angles in degrees, named like the rows' angle_deg
        mechanism = self.mechanism
        parameters = {f"{p.name}_deg" if p.kind == "angle" else p.name:
                      (self.asked[p.name] if self.asked and p.name in self.asked
                       else math.degrees(cast(float, value)) if p.kind == "angle" else value)
                      for p, value in zip(mechanism.cli_parameters, mechanism.parameters().values())}
        if not mechanism.cli_parameters:      # a linkage file: its name and its path
            parameters = dict(mechanism.parameters())
        name = mechanism.cli_name or getattr(mechanism, "name", type(mechanism).__name__)
        head = json.dumps({"mechanism": name, "parameters": parameters |
                           {"omega": self.omega, "alpha": self.alpha}}, indent=1, ensure_ascii=False)
        out.write(head[:-2] + ',\n "rows": [')    # the same text as json.dumps of the whole, indent 1
        separator = "\n"
        for rows in self.rows():
            for row in rows:
                out.write(separator + "\n".join("  " + line for line in
                                                json.dumps(row, indent=1, ensure_ascii=False).split("\n")))
                separator = ",\n"
        out.write("\n ]\n}" if separator == ",\n" else "]\n}")

    def write_csv(self, out) -> None:
        """CSV through the course tools' one writer: names (a point's, a linkage file's joints) are text made
        safe for a spreadsheet (no cell starts a formula), numbers stay numbers."""
        from .course.csvtext import csv_lines

        header: list[str] | None = None
        for rows in self.rows():
            flats = [_flat(r) for r in rows]
            if header is None:
                header = list(flats[0])
                out.write(csv_lines([header]))
            out.write(csv_lines([[f.get(k) for k in header] for f in flats]))

    def _columns(self) -> dict[tuple[str, str], dict[str, tuple[float, dict[int, float], bool]]]:
        """Per block and column: the largest |value|, the largest |value| per printed width, and whether a
        value is unbounded — enough to know each column's width whatever its round-off threshold."""
        columns: dict[tuple[str, str], dict[str, tuple[float, dict[int, float], bool]]] = {}
        for rows in self.rows():
            for row in rows:
                for group in ("links", "points", "sliders", "forces"):
                    for name, values in _blocks(row, group).items():
                        block = columns.setdefault((group, name), {})
                        for key, value in values.items():
                            scale, by_width, none = block.get(key, (0.0, {}, False))
                            if value is None:
                                none = True
                            else:
                                size = abs(value)
                                width = len(f"{value:.6g}")
                                by_width[width] = max(by_width.get(width, 0.0), size)
                                scale = max(scale, size)
                            block[key] = (scale, by_width, none)
        return columns

    def write_text(self, out) -> None:
        mechanism = self.mechanism
        out.write(f"{mechanism.describe()}; omega = {self.omega:g} 1/s, alpha = {self.alpha:g} 1/s²")
        columns = self._columns()
        phi_width = max((len(f"{row['phi_deg']:.1f}") for rows in self.rows() for row in rows), default=0)
        for group, label in (("links", "link"), ("points", "point"), ("sliders", "slider"), ("forces", "force:")):
            for (kind, name), block in columns.items():
                if kind != group:
                    continue
                keys = list(block)
                headers = ["φ, °"] + [f"{k.removesuffix('_deg')}, {_UNITS.get(k, '')}".rstrip(", ") for k in keys]
                widths = [max(len(headers[0]), phi_width)]
                for k in keys:
                    scale, by_width, none = block[k]
                    printed = [w for w, size in by_width.items() if size > 1e-12 * scale]
                    small = any(size <= 1e-12 * scale for size in by_width.values()) or none
                    widths.append(max([len(headers[len(widths)])] + printed + ([1] if small else [])))
                out.write(f"\n\n{label} {name}\n" + "  ".join(h.rjust(w) for h, w in zip(headers, widths)))
                for rows in self.rows():
                    lines = []
                    for r in rows:
                        cells = [f"{r['phi_deg']:.1f}"] + [_readable(_blocks(r, group)[name][k], block[k][0])
                                                           for k in keys]
                        lines.append("  ".join(c.rjust(w) for c, w in zip(cells, widths)))
                    out.write("\n" + "\n".join(lines))


def _table(args: argparse.Namespace, out) -> None:
    if args.mechanism == "file":
        mechanism: Mechanism = load_linkage(args.path)
    else:
        cls = registry[args.mechanism]
        mechanism = cls(**{p.name: _class_value(p, getattr(args, p.name)) for p in cls.cli_parameters})
    positions = 12 if args.positions is None else args.positions
    if args.angles is None and not 1 <= positions <= MAX_POSITIONS:
        raise InvalidParameterError("--positions", positions, f"a whole number from 1 to {MAX_POSITIONS}")
    points = [parse_point(p) for p in args.point]
    first, step, count = _angle_range(args.angles) if args.angles is not None else (0.0, 360.0 / positions, positions)

    def degree_chunks() -> Iterator[np.ndarray]:       # made a chunk at a time: no array over all positions
        for start in range(0, count, CHUNK):
            if args.angles is not None:
                yield _angles_between(first, step, start, min(start + CHUNK, count))
            else:
                yield np.arange(start, min(start + CHUNK, count)) * 360.0 / positions

    asked = {p.name: getattr(args, p.name) for p in mechanism.cli_parameters} if args.mechanism != "file" else None
    table = _Table(mechanism, degree_chunks, args.omega, args.alpha, points, asked, getattr(args, "forces", False))
    joints = table.check()
    for name, link, _, _ in points:
        if name in joints or [n for n, *_ in points].count(name) > 1:
            raise InvalidParameterError("--point", name, "a new name, not a joint's or another point's")
        if link not in mechanism.links:
            raise InvalidParameterError("--point", f"{name}={link}",
                                        f"on one of the links {', '.join(mechanism.links)}")
    {"json": table.write_json, "csv": table.write_csv, "text": table.write_text}[args.format](out)
    if args.format != "csv":   # the CSV writer ends every row with its newline
        out.write("\n")


class _Parser(argparse.ArgumentParser):
    """argparse's parser, but help written to standard output fails as the commands' output does (an
    :class:`_OutputError`), instead of being dropped silently when the output is full or closed."""

    def _print_message(self, message: str, file: Any = None) -> None:
        if message and file is not None and file is sys.stdout:
            _Output(file).write(message)
        else:
            super()._print_message(message, file)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m mechanisms``."""
    parser = _Parser(prog="python -m mechanisms",
                                     description="Kinematics of planar linkage mechanisms: the book's tool.")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    table = commands.add_parser("table", help="kinematic table of a mechanism or a linkage file over crank positions",
                                description="Print the kinematic table of a mechanism, or of the linkage in a file "
                                            "(table FILE.toml …), over crank positions.",
                                epilog=FORMAT_SUMMARY, formatter_class=argparse.RawDescriptionHelpFormatter)
    kinds = table.add_subparsers(dest="mechanism", metavar="MECHANISM")
    for name, cls in sorted(registry.items()):
        sub = kinds.add_parser(name, help=(cls.__doc__ or name).strip().splitlines()[0],
                               description=(cls.__doc__ or name).strip().splitlines()[0])
        for p in cls.cli_parameters:
            sub.add_argument(f"--{p.name.replace('_', '-')}", dest=p.name, type=_KINDS[p.kind],
                             required=p.default is None, default=p.default, help=p.help)
        _add_table_options(sub)
    sub = kinds.add_parser("file", help="a linkage file: table FILE.toml … (its format: table file --help)",
                           description="The kinematic table of the linkage described in a TOML file.",
                           epilog=FORMAT_SUMMARY, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub.add_argument("path", metavar="FILE.toml", help="the linkage file, or the name of a shipped example")
    _add_table_options(sub)
    sub.add_argument("--forces", action="store_true",
                     help="add the driving torque and the joint forces from the file's [[mass]], [[load]] and gravity "
                          "(N, N·m; a file with none of them: all zero)")
    structure = commands.add_parser(
        "structure", help="structural analysis of a linkage file: links, pairs, degrees of freedom, Assur groups",
        description="Print the links, the kinematic pairs, the degrees of freedom by the structural "
                    "(Kutzbach–Grübler) formula and the Assur groups in the order they are solved.",
        epilog=FORMAT_SUMMARY, formatter_class=argparse.RawDescriptionHelpFormatter)
    structure.add_argument("path", metavar="FILE.toml", help="the linkage file, or the name of a shipped example")
    structure.add_argument("--format", choices=("text", "json"), default="text")
    plan = commands.add_parser(
        "plan", help="velocity and acceleration plans of a linkage file at one crank angle, vector by vector",
        description="Construct the velocity and acceleration plans at one crank angle as on paper (group by "
                    "group) and print each vector: its name, its segment on the plan, its length in mm at "
                    "the scale, its value and its direction; --out draws both plans beside the linkage.",
        epilog=FORMAT_SUMMARY, formatter_class=argparse.RawDescriptionHelpFormatter)
    plan.add_argument("path", metavar="FILE.toml", help="the linkage file, or the name of a shipped example")
    plan.add_argument("--angle", type=_cli_number, required=True, help="crank angle φ, degrees")
    plan.add_argument("--omega", type=_cli_number, required=True, help="crank angular velocity ω1, 1/s")
    plan.add_argument("--alpha", type=_cli_number, default=0.0, help="crank angular acceleration ε1, 1/s² (default 0)")
    plan.add_argument("--scale-v", type=_cli_number, default=None, dest="scale_v",
                      help="μ_v, (m/s)/mm (default: the smallest course scale within 100 mm)")
    plan.add_argument("--scale-a", type=_cli_number, default=None, dest="scale_a",
                      help="μ_a, (m/s²)/mm (default: the smallest course scale within 100 mm)")
    plan.add_argument("--out", default=None, metavar="PLAN.svg|png", help="draw the plans into this file")
    plan.add_argument("--format", choices=("text", "json"), default="text")
    _add_course_commands(commands)
    _add_bench_command(commands)
    _add_synthesize_command(commands)
    return parser


def _add_synthesize_command(commands) -> None:
    """The subcommand ``synthesize path``: a four-bar whose coupler point traces a target path."""
    synthesize = commands.add_parser("synthesize", help="design a linkage for a task: synthesize path TARGET.csv",
                                     description="Design a linkage for a task.")
    tasks = synthesize.add_subparsers(dest="task", metavar="TASK")
    path = tasks.add_parser(
        "path", help="a four-bar whose coupler point P traces a target path (x,y in m)",
        description="Fit a four-bar's coupler point P to the path in TARGET.csv (header x,y; x and y in m, one point "
                    "a row, in order; a closed curve unless --open) and write the linkage file. It prints the RMS and "
                    "largest distance from the target to P's path as a percentage of the target's size (the "
                    "diagonal of its bounding box), the Grashof class and the transmission angles. A fit whose RMS "
                    "distance is above --tolerance is reported, no file is written, and the exit status is 1.")
    path.add_argument("target", metavar="TARGET.csv", help="the target path: header x,y, then x,y in m per row")
    path.add_argument("--out", required=True, metavar="LINKAGE.toml", help="the linkage file to write")
    path.add_argument("--open", action="store_true", help="the target is an open stretch, not a closed curve")
    path.add_argument("--fixed-pivots", dest="fixed_pivots", default=None, metavar="X1,Y1,X2,Y2",
                      help="the crank's pivot O = (X1, Y1) and the rocker's pivot C = (X2, Y2), m")
    path.add_argument("--crank-rocker", dest="crank_rocker", action="store_true",
                      help="only crank-rockers (default: also double-cranks; the crank turns fully either way)")
    path.add_argument("--min-transmission", dest="min_transmission", type=_cli_number, default=None, metavar="DEG",
                      help="the smallest transmission angle allowed over the turn, degrees (0 to 90)")
    path.add_argument("--tolerance", type=_cli_number, default=1.0, metavar="PERCENT",
                      help="the largest RMS distance accepted, percent of the target's size (default 1)")


def _read_target(path: str) -> np.ndarray:
    """The points (n, 2) of a target file: header ``x,y``, then two numbers (m) a row; or a
    :class:`~mechanisms.course.csvtext.CourseFileError` naming the file, the line and the cause."""
    from .course.csvtext import CourseFileError, header_key, read_csv_text

    where = f"target path {path}"
    rows = read_csv_text(path, "target path").rows
    header = [header_key(cell.value) for cell in rows[0].cells]
    if header != ["x", "y"]:
        raise CourseFileError(f"{where}, line {rows[0].line}: the first line must be the header x,y (got "
                              f"{','.join(cell.value for cell in rows[0].cells)!r})")
    points = []
    for row in rows[1:]:
        if len(row.cells) != 2:
            raise CourseFileError(f"{where}, line {row.line}: expected two numbers x,y (m), got {len(row.cells)} "
                                  "cells")
        values = []
        for axis, cell in zip("xy", row.cells):
            try:
                value = parse_number(cell.value)
            except ValueError:
                raise CourseFileError(f"{where}, line {row.line}: {axis} is not a number: {cell.value!r}"
                                      f"{_number_hint(cell.value)}") from None
            if not math.isfinite(value):
                raise CourseFileError(f"{where}, line {row.line}: {axis} must be a finite number of metres, got "
                                      f"{cell.value!r}")
            values.append(value)
        points.append(values)
    return np.array(points, dtype=float).reshape(-1, 2)


def _synthesize(args: argparse.Namespace) -> tuple[str, int]:
    """``synthesize path TARGET.csv --out LINKAGE.toml``: the fit's report, and exit status 1 for a poor fit."""
    from .analysis.path_synthesis import fit_path, fit_report
    from .course.csvtext import write_file

    pivots = None
    if args.fixed_pivots is not None:
        try:
            x1, y1, x2, y2 = (parse_number(v) for v in args.fixed_pivots.split(","))
        except ValueError:
            raise InvalidParameterError("--fixed-pivots", args.fixed_pivots,
                                        "four numbers X1,Y1,X2,Y2 (m): the crank's pivot and the rocker's") from None
        if not all(map(math.isfinite, (x1, y1, x2, y2))) or (x1, y1) == (x2, y2):
            raise InvalidParameterError("--fixed-pivots", args.fixed_pivots, "two distinct points of finite "
                                        "coordinates X1,Y1,X2,Y2 (m)")
        pivots = (complex(x1, y1), complex(x2, y2))
    if args.min_transmission is not None and not 0.0 <= args.min_transmission < 90.0:
        raise InvalidParameterError("--min-transmission", args.min_transmission, "an angle from 0° to below 90°")
    if not 0.0 < args.tolerance <= 100.0:
        raise InvalidParameterError("--tolerance", args.tolerance, "a percentage above 0 and at most 100")
    points = _read_target(args.target)
    fit = fit_path(points, closed=not args.open, pivots=pivots, crank_rocker=args.crank_rocker,
                   min_transmission=None if args.min_transmission is None else math.radians(args.min_transmission),
                   tolerance=args.tolerance / 100.0, name=f"target path {args.target}")
    kind = "an open stretch" if args.open else "a closed curve"
    lines = [f"target path {args.target}: {len(points)} points, {kind}"] + fit_report(fit)
    if not fit.good:
        lines.append(f"no linkage file written ({args.out})")
        return "\n".join(lines), 1
    write_file(args.out, fit.linkage_text(), "linkage file")
    lines.append(f"linkage file written: {args.out} (the coupler point is the [[point]] named P)")
    return "\n".join(lines), 0


def _add_table_options(sub: argparse.ArgumentParser) -> None:
    """The options every ``table`` takes: the crank's motion, the positions, extra points, the format."""
    sub.add_argument("--omega", type=_cli_number, required=True, help="crank angular velocity ω1, 1/s")
    sub.add_argument("--alpha", type=_cli_number, default=0.0, help="crank angular acceleration ε1, 1/s² (default 0)")
    where = sub.add_mutually_exclusive_group()
    where.add_argument("--angles", help="crank angles START:STOP:STEP in degrees, stop excluded")
    where.add_argument("--positions", type=_cli_whole, default=None, help="N positions evenly over a turn (default 12)")
    sub.add_argument("--point", action="append", default=[], metavar="NAME=LINK:U[,W]",
                     help="a point fixed to LINK, U m along it from its first joint, W m to its left")
    sub.add_argument("--format", choices=("text", "csv", "json"), default="text")


def _structure(args: argparse.Namespace) -> str:
    from .analysis.structure import structure_of

    report = structure_of(load_linkage(args.path))
    return report.json() if args.format == "json" else report.text()


_PLAN_SUFFIXES = (".png", ".svg")


def _plan(args: argparse.Namespace) -> str:
    """``plan FILE.toml --angle DEG --omega W``: every vector of both plans, and the drawing if asked."""
    from .analysis.plans import plan_report

    out_path = None
    if args.out is not None:
        out_path = Path(args.out)
        if out_path.suffix.lower() not in _PLAN_SUFFIXES:
            raise InvalidParameterError("--out", args.out, "a file name ending in .png or .svg")
    linkage = load_linkage(args.path)
    report = plan_report(linkage, to_radians(args.angle, "--angle"), args.omega, args.alpha,
                         args.scale_v, args.scale_a)
    if out_path is not None:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from .plot.plans import draw_plans

        figure, _ = draw_plans(linkage, report.solution, report.velocity, report.acceleration)
        try:
            figure.savefig(out_path, format=out_path.suffix.lower()[1:])
        except OSError as error:
            raise InvalidParameterError("--out", args.out, f"a file that can be written ({error.strerror})") from None
        finally:
            plt.close(figure)
    if args.format == "json":
        data = {"file": str(args.path), "angle_deg": args.angle, "omega": args.omega, "alpha": args.alpha}
        return json.dumps(data | report.as_dict(), ensure_ascii=False, indent=1)
    lines = [f"{linkage.describe()}: plans at φ = {args.angle:g}°, ω1 = {args.omega:g} 1/s, ε1 = {args.alpha:g} 1/s²",
             f"μ_v = {report.velocity.scale:g} (m/s)/mm, μ_a = {report.acceleration.scale:g} (m/s²)/mm"]
    lines.append(f"{'plan':<13}{'vector':<12}{'segment':<9}{'length, mm':>11}{'value':>14}  {'unit':<5}{'direction, °':>13}")
    for row in report.rows:
        lines.append(f"{row.quantity:<13}{row.name:<12}{row.segment:<9}{row.length_mm:>11.2f}"
                     f"{row.magnitude:>14.6g}  {row.unit:<5}{row.direction_deg:>13.2f}")
    if out_path is not None:
        lines.append(f"drawn into {out_path}")
    return "\n".join(lines)


def _add_bench_command(commands) -> None:
    """The subcommand ``bench``: time per position against error (:mod:`mechanisms.bench`)."""
    bench = commands.add_parser(
        "bench", help="time per position against error: closed form, Newton, finite differences, peers",
        description="Time every method of chapter 9 on the crank-slider, the four-bar, the slotted lever and two "
                    "composed linkages (the four-bar from its groups, the Watt six-bar file), side by side in one "
                    "process: time per position (best of R runs) and the largest error against "
                    "an extended-precision reference. pylinkage is timed too when installed (the bench extra).")
    bench.add_argument("--sizes", default="1000,100000,1000000", metavar="N,N,…",
                       help="numbers of crank positions (default 1000,100000,1000000)")
    bench.add_argument("--repeat", type=_cli_whole, default=3, metavar="R", help="best of R runs (default 3)")
    bench.add_argument("--format", choices=("text", "json"), default="text")
    bench.add_argument("--only", choices=("methods", "startup"), default=None,
                       help="only the methods' times, or only the start-up times (import mechanisms, a 12-row "
                            "table: fresh interpreters, best of max(R, 3) runs); default both")


def _bench(args: argparse.Namespace) -> str:
    from . import bench

    sizes_needed = f"whole numbers N,N,… from 1 to {MAX_POSITIONS}"
    if not all(_WHOLE.fullmatch(v.strip()) for v in args.sizes.split(",")):
        raise InvalidParameterError("--sizes", args.sizes, sizes_needed)
    sizes = [int(v) for v in args.sizes.split(",")]
    if not 1 <= min(sizes) <= max(sizes) <= MAX_POSITIONS:   # each size is an array of that many positions
        raise InvalidParameterError("--sizes", args.sizes, sizes_needed)
    if not 1 <= args.repeat <= MAX_REPEAT:
        raise InvalidParameterError("--repeat", args.repeat, f"a whole number from 1 to {MAX_REPEAT}")
    report: dict[str, Any] = bench.run(sizes, args.repeat) if args.only != "startup" else {}
    if args.only != "methods":
        report["startup"] = bench.startup_times(max(args.repeat, 3))
    if args.format == "json":
        return json.dumps(report, indent=1) if args.only == "startup" else bench.format_json(report)
    parts = [bench.format_text(report)] if args.only != "startup" else []
    return "\n\n".join(parts + ([bench.format_startup_text(report["startup"])] if "startup" in report else []))


def _add_course_commands(commands) -> None:
    """The subcommands ``assign`` and ``check``: course assignments (:mod:`mechanisms.assign`) and
    their grading (:mod:`mechanisms.grading`)."""
    from .course.grading import DEFAULT_RELATIVE

    assign = commands.add_parser(
        "assign", help="make a variant of a mechanism or a linkage file for every student: sheets and an answer key",
        description="Make N valid variants of a mechanism or of the linkage in a file (lengths, crank speed, crank "
                    "positions), a printable sheet for each (HTML and Markdown), an answer form for each, one "
                    "answer key (key.csv) with its tolerances (key-tolerances.csv) and, for a file, each "
                    "variant's own linkage file (sNN.toml). A file's [variants] table may set the ranges "
                    "(see mechanisms.course.variants).")
    assign.add_argument("mechanism", metavar="MECHANISM|FILE.toml",
                        help="crank-slider, four-bar, slotted-lever, a linkage file or a shipped example's name")
    assign.add_argument("--students", type=_cli_whole, default=None,
                        help="number of students N (variants s01 … sNN); with --roster, the list's length")
    assign.add_argument("--roster", metavar="CLASS.csv",
                        help="the class list: a CSV file with a name (or first and last name), e-mail and/or "
                             "identifier column, one student a row (a Moodle grading worksheet will do); the "
                             "sheets carry the names, the key the names, e-mails and identifiers")
    assign.add_argument("--seed", type=_cli_whole, default=None,
                        help="seed of the random variants (default: a new one, printed so the run can be repeated)")
    assign.add_argument("--positions", type=_cli_whole, default=3, help="crank positions per variant (default 3)")
    assign.add_argument("--out", default="assignment", help="output folder (default ./assignment)")
    assign.add_argument("--ask", metavar="COLUMN,…", default=None,
                        help="the quantities asked, as the table's CSV columns (JOINT.x|y|vx|vy|ax|ay, "
                             "LINK.angle_deg|omega|alpha, BLOCK.s|v|a; with masses JOINT.F, driving_torque); "
                             "default: the output joint's motion and every link's rates")
    assign.add_argument("--tolerance", action="append", default=[], metavar="TARGET=VALUE",
                        help="a tolerance: TARGET a column or a kind (angle, length, velocity, acceleration, "
                             "angular-velocity, angular-acceleration, force, torque), VALUE a percentage and/or an "
                             "absolute amount: B.vx=2%%, angle=0.5deg, velocity=2%%,0.01 (repeatable)")
    assign.add_argument("--plan", action="store_true",
                        help="answers read off a drawing: 3 %% and 1 mm of the plan at its scale (chapter 10)")
    assign.add_argument("--moodle-quiz", metavar="QUIZ.xml", default=None, dest="moodle_quiz",
                        help="also write a Moodle quiz (Moodle XML): one Cloze question per variant, graded by Moodle")
    check = commands.add_parser(
        "check", help="grade answer files against an answer key",
        description="Grade answer files against the key written by `assign`: per student and per quantity, what is "
                    "right, what is wrong and by how much, and which answers are missing or unreadable.")
    check.add_argument("key", metavar="KEY.csv", help="the answer key written by `assign`")
    check.add_argument("answers", metavar="ANSWERS.csv|SUBMISSIONS.zip", nargs="+",
                       help="one or more answer files, or Moodle's archive of submissions (Download all "
                            "submissions): its CSV files are read in memory, each one the answers of the account "
                            "that handed it in (with --moodle)")
    check.add_argument("--relative", type=_cli_number, default=None, metavar="PERCENT",
                       help=f"relative tolerance in %% (default: the key's tolerances, key-tolerances.csv beside it, "
                            f"else {100 * DEFAULT_RELATIVE:g}); each kind of quantity also has an absolute floor")
    check.add_argument("--tolerance", action="append", default=[], metavar="TARGET=VALUE",
                       help="a tolerance instead of the key's, as for assign: B.vx=2%%, angle=0.5deg (repeatable)")
    check.add_argument("--marks", metavar="FILE.csv", help="also write every mark to this CSV file")
    check.add_argument("--moodle", metavar="WORKSHEET.csv",
                       help="fill Moodle's grading worksheet (exported from the assignment, in any language) with each "
                            "student's grade and a feedback comment, found by identifier or e-mail (the key must "
                            "come from assign --roster); every other cell is left as it was. With an archive of "
                            "submissions, it also tells which account handed in each file")
    check.add_argument("--moodle-out", metavar="FILE.csv",
                       help="where to write the filled worksheet (default: WORKSHEET-graded.csv beside it)")
    check.add_argument("--grades", metavar="FILE.csv",
                       help="also write the grades as a plain CSV for any platform: student, identifier, name, "
                            "email, grade (percent), feedback")


def _assign(args: argparse.Namespace) -> str:
    import secrets

    from .course.assign import assignment_task, make_variants, write_assignment
    from .course.roster import read_roster

    people = read_roster(args.roster) if args.roster else None
    if people is not None and args.students is not None and args.students != len(people):
        raise InvalidParameterError("--students", args.students, f"the number of students of the class list "
                                    f"{args.roster} ({len(people)}), or left out")
    if people is None and args.students is None:
        raise InvalidParameterError("--students", None, "a whole number ≥ 1, or a class list given with --roster")
    seed = args.seed if args.seed is not None else secrets.randbelow(10**6)
    task = assignment_task(args.mechanism, None if args.ask is None else args.ask.split(","))
    variants = make_variants(task, len(people) if people else args.students, seed, args.positions)
    written = write_assignment(task, variants, args.out, seed=seed, people=people, tolerance=args.tolerance,
                               plan=args.plan)
    quiz = []
    if args.moodle_quiz:
        from .course.quiz import write_quiz

        write_quiz(task, variants, args.moodle_quiz, written["key"][0])
        quiz = [f"  Moodle quiz   {args.moodle_quiz}   (import into the question bank: Moodle XML format)"]
    first, last = variants[0].student, variants[-1].student
    roster = ([f"  class list    {args.roster}: {first} is {people[0].label}, {last} is {people[-1].label} "
               "(names on the sheets; names, e-mails, identifiers in the key)"] if people else [])
    return "\n".join([
        f"{args.mechanism}: {len(variants)} variants ({first} … {last}), seed {seed}, written to {args.out}/:",
        f"  sheets        {first}.html … {last}.html and {first}.md … {last}.md (drawings {first}.png …)",
        f"  answer forms  {first}-answers.csv … {last}-answers.csv",
        f"  answer key    {written['key'][0].name}   (keep it from the students)",
        f"  tolerances    {written['tolerances'][0].name}   (each answer's tolerance, as the sheets state it)",
        *([f"  linkage files {first}.toml … {last}.toml (each student's linkage, loadable by the package)"]
          if written["linkages"] else []),
        f"  variants      {written['variants'][0].name}", *roster,
        *([f"  to Moodle     {written['moodle'][0].name}   (each student's sheet, form and file, for Grading action → "
           "Upload multiple feedback files in a zip)"] if written["moodle"] else []), *quiz,
        f"Grade with: python -m mechanisms check {written['key'][0]} ANSWERS.csv …"])


def _check(args: argparse.Namespace) -> tuple[str, int]:
    from .course.grading import check_files, read_key
    from .course.moodle import answer_files, read_worksheet

    if args.relative is not None and not (math.isfinite(args.relative) and 0.0 <= args.relative < 100.0):
        raise InvalidParameterError("--relative", args.relative, "a percentage from 0 to less than 100")
    key = read_key(args.key)
    sheet = read_worksheet(args.moodle) if args.moodle else None
    files, problems, notes = answer_files(args.answers, key, sheet)
    report = check_files(key, files, relative=None if args.relative is None else args.relative / 100.0,
                         tolerance=args.tolerance, problems=problems)
    if args.marks:
        from .course.csvtext import write_file

        write_file(args.marks, report.csv(), "--marks file")
    text = "\n".join([report.text(), *notes])
    if sheet is not None:
        from .course.moodle import fill_worksheet

        worksheet = pathlib.Path(args.moodle)
        out = args.moodle_out or worksheet.with_name(f"{worksheet.stem}-graded{worksheet.suffix or '.csv'}")
        filled = fill_worksheet(report, sheet, out)
        text += (f"\nMoodle worksheet: {len(filled.filled)} grades and feedback comments written to {filled.path}"
                 + (f" ({len(filled.untouched)} other row(s) left as they were)" if filled.untouched else "")
                 + "; upload it in the assignment: Grading action → Upload grading worksheet.")
    if args.grades:
        from .course.moodle import grades_csv

        from .course.csvtext import write_file

        write_file(args.grades, grades_csv(report), "--grades file")
        text += f"\nGrades (percent) and feedback written to {args.grades}."
    return text, (1 if report.problems else 0)


_UNSIGNED = r"(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
_NEGATIVE_VALUE = re.compile(rf"^-{_UNSIGNED}([,:][-+]?{_UNSIGNED})*$|^-inf(inity)?$|^-?nan$", re.IGNORECASE)


def _join_negative_pairs(argv: Sequence[str]) -> list[str]:
    """``--omega -1e3``, ``--frame -0.4,0.05``, ``--angles -90:90:30`` → ``--omega=-1e3`` …: argparse would
    take a value that starts with − and is not a plain decimal for an option of its own."""
    out: list[str] = []
    for token in argv:
        if out and out[-1].startswith("--") and "=" not in out[-1] and token.startswith("-") \
                and _NEGATIVE_VALUE.match(token):
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


def _file_table(argv: list[str]) -> list[str]:
    """``table FILE.toml …`` → ``table file FILE.toml …``: a table of anything that is not a mechanism's name is
    the table of a linkage file."""
    if len(argv) > 1 and argv[0] == "table" and not argv[1].startswith("-") and argv[1] not in registry \
            and argv[1] != "file":
        return [argv[0], "file", *argv[1:]]
    return argv


class _OutputError(Exception):
    """Standard output cannot be written: it is closed, its disk is full, its reader has gone."""

    def __init__(self, cause: BaseException | None):
        self.cause = cause
        super().__init__("standard output is closed" if cause is None else
                         f"cannot write to standard output: {getattr(cause, 'strerror', None) or cause}")


class _Output:
    """Standard output as the commands write it: every failure to write becomes an :class:`_OutputError`, so
    that ``main`` answers it in one place (and a failure to read a file is never taken for it)."""

    def __init__(self, stream: Any):
        self.stream = stream

    def write(self, text: str) -> None:
        if self.stream is None:
            raise _OutputError(None)
        try:
            self.stream.write(text)
        except OSError as error:
            raise _OutputError(error) from None
        except ValueError:                       # a stream closed in this process
            raise _OutputError(None) from None

    def flush(self) -> None:
        if self.stream is not None:
            try:
                self.stream.flush()
            except OSError as error:
                raise _OutputError(error) from None
            except ValueError:
                raise _OutputError(None) from None


def _error(message: str) -> None:
    """A one-line message on standard error (if there is one to write to)."""
    try:
        if sys.stderr is not None:
            sys.stderr.write(f"error: {message}\n")
            sys.stderr.flush()
    except (OSError, ValueError):
        pass


def _output_failed(error: _OutputError) -> int:
    """The answer to standard output that cannot be written: a broken pipe (the reader, e.g. ``head``, stopped
    early) ends quietly with status 1, as Python's documentation recommends; a closed or full output is said on
    standard error, with status 2. Either way the process's own output is pointed at the null device, so that
    Python's last flush at exit finds nothing to fail on (it would print a traceback)."""
    stream = sys.stdout
    if stream is not None and stream is sys.__stdout__:
        try:
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, stream.fileno())
            os.close(null)
        except (OSError, ValueError):
            pass
    if isinstance(error.cause, BrokenPipeError):
        return 1
    _error(str(error))
    return 2


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 bad input).

    ``check`` returns 1 when it graded the answers but found problems in the answer files
    (unknown student ids, repeated rows …), and 2 when a file could not be graded at all. Output that
    cannot be written gives 2 and a message (a closed or full standard output), or 1 and no message (a
    broken pipe: the reader stopped early); never a traceback.
    """
    out = _Output(sys.stdout)
    try:
        status = _main(argv, out)
        out.flush()
    except _OutputError as error:
        return _output_failed(error)
    return status


def _main(argv: Sequence[str] | None, out: _Output) -> int:
    """:func:`main`, writing its results to ``out``."""
    parser = build_parser()
    try:     # a usage error (argparse has printed it) or --help: an exit status, not an exception
        args = parser.parse_args(_file_table(_join_negative_pairs(sys.argv[1:] if argv is None else list(argv))))
    except SystemExit as stop:
        return stop.code if isinstance(stop.code, int) else 2
    if args.command is None:
        out.write(parser.format_help())
        return 0
    if args.command in ("bench", "structure", "plan"):
        try:
            text = (_bench(args) if args.command == "bench" else _structure(args) if args.command == "structure"
                    else _plan(args))
        except MechanismError as error:
            _error(str(error))
            return 2
        out.write(text + "\n")
        return 0
    if args.command == "synthesize":
        if args.task is None:
            _error("name a task: path (see `synthesize --help`)")
            return 2
        try:
            text, status = _synthesize(args)
        except MechanismError as error:
            _error(str(error))
            return 2
        out.write(text + "\n")
        return status
    if args.command in ("assign", "check"):
        try:
            if args.command == "assign":
                text, status = _assign(args), 0
            else:
                text, status = _check(args)
        except MechanismError as error:
            _error(str(error))
            return 2
        except OSError as error:
            _error(f"{error.filename or ''}: {error.strerror}")
            return 2
        out.write(text + "\n")
        return status
    if args.command == "table" and args.mechanism is None:
        _error("name a mechanism: " + ", ".join(sorted(registry)) + " (see `table --help`)")
        return 2
    try:
        _table(args, out)
    except MechanismError as error:
        _error(str(error))
        return 2
    return 0
