"""Layer 6: course assignments — one variant of a mechanism per student, its sheet and the key.

A teacher runs ``python -m mechanisms assign MECHANISM --students N --seed S --out DIR`` and
gets, for every student, a variant of the same mechanism with its own lengths, crank speed and
crank positions, a printable sheet (``sNN.html`` with the drawing embedded, and the same text
in ``sNN.md`` beside the drawing ``sNN.png``), an answer form (``sNN-answers.csv``), and one
answer key for the class (``key.csv``) with ``variants.json`` recording every variant. The
answers are graded by ``python -m mechanisms check`` (:mod:`mechanisms.grading`).

Every variant is valid: it is drawn at random from ranges that suit the mechanism, rounded to
whole millimetres, and kept only if the mechanism's own analysis says it works over the whole
revolution (see each :class:`Task`'s ``check``). Variant *i* of seed *S* depends only on *S*
and *i*, so a class can grow without changing the variants already handed out.

Column names of the key are those of ``python -m mechanisms table … --format csv``:
``LINK.angle_deg``, ``LINK.omega``, ``LINK.alpha``, ``POINT.x`` …, ``SLIDER.s``, ``SLIDER.v``,
``SLIDER.a`` (and ``SLIDER.coriolis``).
"""

from __future__ import annotations

import base64
import dataclasses
import html
import io
import json
import math
import pathlib
import re
import warnings
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

import numpy as np

from ..analysis.assignments import Quantity, Task, assignments
from ..core.errors import SingularPositionWarning, InvalidParameterError, MechanismError, UnknownNameError
from ..linkages.base import Mechanism, Solution
from ..present.escape import csv_cell, markdown_text
from .csvtext import CourseFileError, csv_lines, write_file
from .moodle import feedback_zip
from .grading import TOLERANCES, Rule, default_rule, kind_of, tolerance_rules, tolerances_path
from .roster import IDENTITY_COLUMNS, Person

TASKS = assignments()
"""The mechanisms an assignment can be set on, by command-line name (registered by each mechanism's
analysis module: :func:`mechanisms.analysis.assignments.register_assignment`)."""

__all__ = [
    "Quantity",
    "Task",
    "Variant",
    "TASKS",
    "quantity_values",
    "make_variant",
    "make_variants",
    "answer_key",
    "KEY_COLUMNS",
    "sheet_markdown",
    "sheet_html",
    "symbol_markdown",
    "symbol_html",
    "write_assignment",
    "assignment_task",
    "key_and_tolerances",
    "plan_floors",
]

KEY_COLUMNS = ("student", "position", "phi_deg")
"""The columns of the key (and of an answer file) before the quantities."""

STEP_DEG = 15
"""The crank positions of a variant are multiples of this angle (degrees)."""

STUDENTS_MAX = 9999
"""The most variants one call makes (``s0001`` … ``s9999``): a class, not a memory's worth."""

_STUDENT_ID = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]{0,63}", re.ASCII)
"""A student id: it names the student's files (``s01.html``, ``s01-answers.csv``), so it is a plain file name on
every system: ASCII letters, digits, ``_`` and ``-``, a letter or digit first, at most 64 characters."""

_RESERVED = {"con", "prn", "aux", "nul", *(f"{port}{n}" for port in ("com", "lpt") for n in range(10))}
"""Names Windows keeps for devices: a file ``CON.html`` cannot be made there."""


def _require_student_id(student: object) -> str:
    if not isinstance(student, str) or not _STUDENT_ID.fullmatch(student) or student.casefold() in _RESERVED:
        raise InvalidParameterError("student", student, "a student id that can name a file: ASCII letters, digits, "
                                    "_ and -, a letter or digit first, at most 64 characters, not a device name "
                                    "(CON, NUL, COM1 …)")
    return student


@dataclass(frozen=True)
class Variant:
    """One student's variant: the mechanism, the crank speed and the crank positions.

    Attributes
    ----------
    student : str
        The student's id (``"s01"``).
    mechanism : Mechanism
    omega : float
        Constant crank angular velocity φ_t (1/s), counter-clockwise.
    positions_deg : tuple of float
        Crank angles φ (degrees) at which the quantities are asked for.
    """

    student: str
    mechanism: Mechanism
    omega: float
    positions_deg: tuple[float, ...]

    def __post_init__(self) -> None:
        _require_student_id(self.student)

    def solve(self) -> Solution:
        """The package's solution at the variant's positions (up to accelerations)."""
        return self.mechanism.solve(np.radians(self.positions_deg), self.omega, 0.0, order=2)

    def record(self) -> dict:
        """The variant as plain data (for ``variants.json``)."""
        parameters = {name: (list(value) if isinstance(value, tuple) else value)
                      for name, value in self.mechanism.parameters().items()}
        branch = getattr(self.mechanism, "branch", None)
        if "branch" not in parameters and branch is not None:   # an assembly the command line does not ask
            parameters["branch"] = branch
        return {"student": self.student, "mechanism": self.mechanism.cli_name, "parameters": parameters,
                "omega": self.omega, "positions_deg": list(self.positions_deg)}


def quantity_values(solution: Solution, column: str, mechanism: Mechanism | None = None) -> np.ndarray:
    """The values of a key column (``NAME.KEY`` as in the ``table`` CSV) at the solution's positions.

    Angles are in degrees, wrapped to [0, 360). With the ``mechanism`` (a linkage file's, with its masses),
    ``driving_torque`` (N·m) and ``JOINT.F``, the magnitude of the force in the hinge at JOINT (N), come from
    :func:`mechanisms.analysis.kinetostatics.linkage_forces`.
    """
    if mechanism is not None and (column == "driving_torque" or column.endswith(".F")):
        from ..analysis.kinetostatics import linkage_forces

        forces = linkage_forces(mechanism, solution)
        if column == "driving_torque":
            return np.asarray(forces.driving_torque, dtype=float)
        joint = column[:-2]
        if joint in forces.forces:
            return np.abs(np.asarray(forces.forces[joint]))
        raise UnknownNameError("hinge", joint, list(forces.forces))
    name, _, key = column.partition(".")
    if name in solution.angle_names and key in ("angle_deg", "omega", "alpha"):
        angle = solution.angle(name)
        if key == "angle_deg":
            return np.degrees(angle.value) % 360.0
        return np.asarray(angle.omega if key == "omega" else angle.alpha, dtype=float)
    if name in solution.slider_names:
        slider = solution.slider(name)
        if key in ("s", "v", "a"):
            return np.asarray({"s": slider.value, "v": slider.velocity, "a": slider.acceleration}[key], dtype=float)
        if key in solution.extras.get(name, {}):
            return np.asarray(solution.extras[name][key], dtype=float)
    if name in solution.point_names:
        point = solution.point(name)
        parts = {"x": point.value.real, "y": point.value.imag, "vx": point.velocity.real,
                 "vy": point.velocity.imag, "ax": point.acceleration.real, "ay": point.acceleration.imag}
        if key in parts:
            return np.asarray(parts[key], dtype=float)
    known = ([f"{n}.{k}" for n in solution.angle_names for k in ("angle_deg", "omega", "alpha")]
             + [f"{n}.{k}" for n in solution.slider_names for k in ("s", "v", "a", *solution.extras.get(n, {}))]
             + [f"{n}.{k}" for n in solution.point_names for k in ("x", "y", "vx", "vy", "ax", "ay")])
    raise UnknownNameError("quantity", column, known)


def _positions(rng: np.random.Generator, count: int) -> tuple[float, ...]:
    choices = rng.choice(360 // STEP_DEG, size=count, replace=False)
    return tuple(float(STEP_DEG * c) for c in sorted(choices))


def student_ids(count: int) -> list[str]:
    """``s01`` … (zero-padded to the width of the count, at least two digits)."""
    width = max(2, len(str(count)))
    return [f"s{i:0{width}d}" for i in range(1, count + 1)]


def make_variant(task: Task | str, seed: int, index: int, student: str | None = None, positions: int = 3,
                 max_tries: int = 10_000, retry: int = 0) -> Variant:
    """Variant number ``index`` (0-based) of ``seed``: drawn until the task's checks pass.

    Parameters
    ----------
    task : Task or str
        The assignment, or its mechanism's command-line name.
    seed : int
        A whole number ≥ 0 (any size): the same seed gives the same variants.
    index : int
        The variant's number, ≥ 0.
    student : str, optional
        The student's id (default ``s`` and index + 1); it names the student's files, so it must be a plain file
        name (ASCII letters, digits, ``_``, ``-``).
    positions : int
        Crank positions per variant, 1 to 24. A task with ``eligible`` (a linkage file's) draws them among the
        crank angles where the candidate is eligible, and refuses a candidate with too few.
    retry : int
        0, or the number of the draw that replaces a variant equal to an earlier one (:func:`make_variants`).

    Raises
    ------
    InvalidParameterError
        For an unknown mechanism, a bad seed, index, student id or number of positions.
    MechanismError
        If no valid variant was found in ``max_tries`` draws (the ranges do not suit the checks).
    """
    task = _task(task)
    if not _whole(positions) or not 1 <= positions <= 360 // STEP_DEG:
        raise InvalidParameterError("positions", positions, f"a whole number from 1 to {360 // STEP_DEG}")
    if not _whole(seed) or seed < 0:
        raise InvalidParameterError("seed", seed, "a whole number ≥ 0")
    if not _whole(index) or index < 0:
        raise InvalidParameterError("index", index, "a whole number ≥ 0")
    student = _require_student_id(f"s{index + 1:02d}" if student is None else student)
    seed, index = int(seed), int(index)
    # two independent streams: the positions do not depend on how many candidates were rejected
    spawn = (index,) if not retry else (index, retry)
    lengths, angles = (np.random.default_rng(s) for s in np.random.SeedSequence(seed, spawn_key=spawn).spawn(2))
    for _ in range(max_tries):
        try:
            mechanism, omega = task.sample(lengths)
            if task.check(mechanism):
                continue
            if task.eligible is None:
                return Variant(student, mechanism, omega, _positions(angles, positions))
            allowed = np.flatnonzero(task.eligible(mechanism))
        except MechanismError:
            continue
        if allowed.size >= positions:
            chosen = angles.choice(allowed, size=positions, replace=False)
            return Variant(student, mechanism, omega, tuple(float(STEP_DEG * c) for c in sorted(chosen)))
    raise MechanismError(f"no valid {task.name} variant in {max_tries} draws (seed {seed}, variant {index})")


def make_variants(task: Task | str, students: int, seed: int, positions: int = 3) -> list[Variant]:
    """One variant per student, ``s01`` … ``sNN``; variant *i* depends only on the seed and *i*.

    ``students`` is a whole number from 1 to :data:`STUDENTS_MAX`; ``seed`` and ``positions`` as for
    :func:`make_variant`.
    """
    if not _whole(students) or not 1 <= students <= STUDENTS_MAX:
        raise InvalidParameterError("students", students, f"a whole number from 1 to {STUDENTS_MAX}")
    task = _task(task)
    variants: list[Variant] = []
    seen: set[str] = set()
    for i, student in enumerate(student_ids(students)):
        variant = make_variant(task, seed, i, student, positions)
        if task.document is not None:     # a linkage file's variants: each different from the ones before
            for retry in range(1, 1000):
                fingerprint = f"{task.document(variant.mechanism)}{variant.omega!r}{variant.positions_deg!r}"
                if fingerprint not in seen:
                    break
                variant = make_variant(task, seed, i, student, positions, retry=retry)
            seen.add(fingerprint)
        variants.append(variant)
    return variants


def _whole(value: object) -> bool:
    """True for a whole number of Python or numpy (not a bool, a float or a string)."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _task(task: Task | str) -> Task:
    if isinstance(task, Task):
        return task
    if task not in TASKS:
        raise InvalidParameterError("mechanism", task, "one of " + ", ".join(TASKS))
    return TASKS[task]


def assignment_task(name: str, ask: Sequence[str] | None = None) -> Task:
    """The task of ``assign NAME``: a named mechanism's (:data:`TASKS`), else a linkage file's or a shipped
    example's (:func:`mechanisms.course.variants.read_assignment_file`), asking the columns ``ask`` (default: the
    task's own).

    Raises
    ------
    StructureError
        A file that cannot be read or is no valid linkage.
    InvalidParameterError, UnknownNameError
        An empty, repeated or unknown column in ``ask`` (the known ones listed).
    """
    columns = None
    if ask is not None:
        columns = [c.strip() for c in ask]
        if not columns or not all(columns) or len(set(columns)) != len(columns):
            raise InvalidParameterError("--ask", ",".join(ask), "a comma-separated list of different columns")
    if name in TASKS:
        task = TASKS[name]
        if columns is None:
            return task
        known = {q.column: q for q in task.quantities}
        for column in columns:
            if column not in known:
                raise UnknownNameError("quantity", column, list(known))
        return dataclasses.replace(task, quantities=tuple(known[c] for c in columns))
    from ..linkages.linkage_file import example_files
    from .variants import read_assignment_file

    if not pathlib.Path(name).exists() and name not in example_files():
        raise InvalidParameterError("MECHANISM", name, f"one of {', '.join(TASKS)}, a linkage file or a shipped "
                                    f"example ({', '.join(example_files())})")
    return read_assignment_file(name).task(columns)


def answer_key(task: Task | str, variants: Sequence[Variant]) -> list[dict]:
    """Rows of the key: ``student``, ``position`` (1, 2 …), ``phi_deg`` and one value per quantity."""
    return key_and_tolerances(task, variants)[0]


PLAN_RELATIVE = 0.03
"""The relative tolerance of an answer read off a plan (``assign --plan``): chapter 10 (§10.2) finds a careful hand
drawing accurate to about a millimetre, 1–3 % of the vectors of a plan drawn within 100 mm."""
PLAN_READING_MM = 1.0
"""How far (mm) a length read off a careful drawing may be from the exact one (chapter 10, §10.2)."""
PLAN_ANGLE_DEG = 1.0
"""How far (°) an angle read off a drawing with a protractor may be."""


def _link_length(mechanism: Mechanism, link: str) -> float | None:
    """The longest distance between the link's first joint and another of its joints (m), if known."""
    pole = mechanism.links.get(link)
    joints = getattr(mechanism, "link_joints", None)
    distances = mechanism.preserved_distances()
    if callable(joints) and link in joints():
        mine = set(joints()[link])
        found = [d for (p, q), d in distances.items() if pole in (p, q) and {p, q} <= mine]
    else:
        found = [d for (p, q), d in distances.items() if pole in (p, q)]
    return max(found) if found else None


def plan_floors(mechanism: Mechanism, solution: Solution, columns: Sequence[str]) -> dict[str, np.ndarray]:
    """The absolute tolerance of each column at each position for answers read off a drawing (``--plan``).

    Each position's plans are drawn, as chapter 10 draws them, at the smallest course scale that keeps the
    largest velocity (acceleration) of a joint within 100 mm (:func:`~mechanisms.analysis.plans.nice_scale`):
    μ_v, μ_a; the linkage at the scale μ_l that keeps its farthest joint within 100 mm. A reading is good to
    :data:`PLAN_READING_MM`: a length to μ_l·1 mm, a velocity to μ_v·1 mm, an acceleration to μ_a·1 mm, a link's
    angular velocity (acceleration) to μ_v·1 mm (μ_a·1 mm) over its length, an angle to :data:`PLAN_ANGLE_DEG`.
    Columns not read off a plan (forces) keep their kind's floor.
    """
    from ..analysis.plans import nice_scale

    points = [solution.point(name) for name in solution.point_names]
    shape = np.shape(solution.phi)

    def scale(values: list[np.ndarray]) -> np.ndarray:
        largest = np.max(np.abs(np.asarray(values)), axis=0) if values else np.zeros(shape)
        return np.array([nice_scale(max(float(v), 1e-12)) for v in np.reshape(largest, -1)]).reshape(shape)

    mu_l = scale([np.full(shape, np.max(np.abs(np.asarray([p.value for p in points]))))])
    mu_v = scale([np.asarray(p.velocity) for p in points])
    mu_a = scale([np.asarray(p.acceleration) for p in points])
    floors: dict[str, np.ndarray] = {}
    for column in columns:
        kind = kind_of(column)
        reading = {"length": mu_l, "velocity": mu_v, "acceleration": mu_a}.get(kind)
        if reading is not None:
            floors[column] = reading * PLAN_READING_MM
        elif kind == "angle":
            floors[column] = np.full(shape, PLAN_ANGLE_DEG)
        elif kind in ("angular velocity", "angular acceleration"):
            length = _link_length(mechanism, column.rpartition(".")[0])
            base = mu_v if kind == "angular velocity" else mu_a
            floors[column] = (base * PLAN_READING_MM / length if length else
                              np.full(shape, TOLERANCES[kind].floor))
        else:
            floors[column] = np.full(shape, TOLERANCES[kind].floor)
    return floors


def key_and_tolerances(task: Task | str, variants: Sequence[Variant], tolerance: Sequence[str] = (),
                       plan: bool = False) -> tuple[list[dict], list[dict], dict[str, dict[str, str]]]:
    """The key's rows, the tolerance of each of its values (rows of the same layout) and, per student, each
    column's tolerance in words for the sheet.

    ``tolerance`` are ``--tolerance`` options (:func:`~mechanisms.course.grading.parse_tolerance`); ``plan``
    the tolerances of answers read off a drawing (:func:`plan_floors`, relative :data:`PLAN_RELATIVE`), unless an
    option sets a column's own.
    """
    task = _task(task)
    columns = [q.column for q in task.quantities]
    rules = tolerance_rules(columns, tolerance, PLAN_RELATIVE if plan else None)
    defaults = tolerance_rules(columns, (), PLAN_RELATIVE if plan else None)
    rows, tolerances, words = [], [], {}
    for variant in variants:
        with warnings.catch_warnings():
            warnings.simplefilter("error", SingularPositionWarning)   # a valid variant has no singular position
            solution = variant.solve()
        values = {q.column: quantity_values(solution, q.column, variant.mechanism) for q in task.quantities}
        floors = plan_floors(variant.mechanism, solution, columns) if plan else {}
        text: dict[str, str] = {}
        for column in columns:
            unit = TOLERANCES[kind_of(column)].unit
            if column in floors and rules[column].floor == defaults[column].floor:
                text[column] = ((f"{100 * rules[column].relative:g} %, at least " if rules[column].relative else "")
                                + f"{PLAN_READING_MM:g} mm of the drawing: "
                                + ", ".join(f"{f:.2g}" for f in floors[column]) + f" {unit}"
                                if kind_of(column) != "angle" else f"{PLAN_ANGLE_DEG:g} {unit}")
            else:
                floors.pop(column, None)
                text[column] = rules[column].text(unit)
        words[variant.student] = text
        for i, phi in enumerate(variant.positions_deg):
            row = {"student": variant.student, "position": i + 1, "phi_deg": phi}
            row.update({column: float(v[i]) for column, v in values.items()})
            rows.append(row)
            tolerances.append({"student": variant.student, "position": i + 1, "phi_deg": phi} | {
                column: (Rule(rules[column].relative, float(floors[column][i])) if column in floors
                         else rules[column]).of(float(values[column][i])) for column in columns})
    return rows, tolerances, words


def _write_csv(path: pathlib.Path, columns: Sequence[str], rows: Sequence[dict], what: str) -> None:
    """A CSV file of the assignment (:func:`~mechanisms.course.csvtext.csv_lines`): text (ids, names, e-mails,
    identifiers) spreadsheet-safe, numbers as numbers (quantities to full precision)."""
    write_file(path, csv_lines([columns, *([row.get(c) for c in columns] for row in rows)]), what)


# --- sheets ---------------------------------------------------------------------------------------------

def drawing_png(variant: Variant) -> bytes:
    """The variant's mechanism drawn at its first position, as PNG bytes (no time stamp)."""
    import matplotlib.pyplot as plt

    from .. import plot

    phi = math.radians(variant.positions_deg[0])
    solution = variant.mechanism.solve(np.array([phi]), variant.omega, order=0)
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    plot.draw(variant.mechanism, solution, 0, ax=ax)
    ax.set_title(f"{variant.student}: the mechanism at φ = {variant.positions_deg[0]:g}°", fontsize=10)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110, bbox_inches="tight", metadata={"Software": None})
    plt.close(fig)
    return buffer.getvalue()


def _name_line(person: Person | None, escape: Callable[[str], str]) -> str:
    """The sheet's line for the student's name: filled in from the class list (each part through ``escape``, for
    the sheet's format), else to be written."""
    if person is None or not (person.name or person.identifier):
        return "Name: ______________________   Group: ________"
    who = escape(person.name) if person.name else "______________________"
    return f"Name: {who}" + (f"   Identifier: {escape(person.identifier)}" if person.identifier else "")


def _sheet_parts(task: Task, variant: Variant, tolerances: Mapping[str, str] | None = None) -> dict:
    if tolerances is None:
        tolerances = {q.column: default_rule(q.column).text(TOLERANCES[kind_of(q.column)].unit) for q in task.quantities}
    symbols = [q.symbol for q in task.quantities]
    plain = all(symbols) and len(set(symbols)) == len(symbols)     # else the answer table names the columns
    return {
        "tolerances": tolerances,
        "label": {q.column: (q.symbol if plain else "") for q in task.quantities},
        "title": f"{task.title}: assignment {variant.student}",
        "data": task.data(variant.mechanism) + [
            ("φ_t = ω_1", "crank angular velocity, constant, counter-clockwise", f"{variant.omega:g}", "1/s")],
        "positions": ", ".join(f"{p:g}°" for p in variant.positions_deg),
        "header": list(KEY_COLUMNS) + [q.column for q in task.quantities],
    }


INSTRUCTIONS = (
    "Angles are measured counter-clockwise from the +x axis; the crank turns about O = (0, 0) at constant "
    "speed, counter-clockwise. Give numbers with at least four significant figures, in the units asked for, "
    "with a decimal point. Hand in the answer form (the CSV file {student}-answers.csv, or the lines below) "
    "with every cell filled in; leave a cell empty only if you have no answer.")


TOLERANCE_NOTE = (
    "An answer is right when it differs from the exact value by at most its tolerance: the larger of the "
    "percentage of the exact value and the absolute amount given for it; angles are compared modulo 360°.")


def _md(text: str) -> str:
    """Text for a Markdown table cell (a ``|`` would end the cell)."""
    return text.replace("|", "\\|")


_SYMBOL = re.compile(r"([A-Za-zα-ωΑ-Ω])(?:([_^])([A-Za-z0-9]+))?")
"""A letter of a symbol with its optional index: ``ψ_tt``, ``x_C``, ``L_1``, ``a^k`` (the tasks' notation)."""


def symbol_markdown(symbol: str) -> str:
    """A task's symbol as Markdown math, as the book sets it: ``ψ_tt`` → ``$ψ_{tt}$`` (empty stays empty)."""
    if not symbol:
        return ""
    body = _SYMBOL.sub(lambda m: m[1] + (f"{m[2]}{{{m[3]}}}" if m[2] else ""), symbol)
    return f"${_md(body)}$"


def symbol_html(symbol: str) -> str:
    """A task's symbol as HTML, as the book sets it: letters in italics, an index after ``_`` as a subscript
    and after ``^`` as a superscript (``x_C`` → ``<i>x</i><sub><i>C</i></sub>``), digits upright."""
    def index(text: str) -> str:
        return re.sub(r"([^\W\d_]+)", r"<i>\1</i>", text)

    out, end = [], 0
    for match in _SYMBOL.finditer(symbol):
        out.append(html.escape(symbol[end:match.start()]))
        out.append(f"<i>{match[1]}</i>")
        if match[2]:
            tag = "sub" if match[2] == "_" else "sup"
            out.append(f"<{tag}>{index(match[3])}</{tag}>")
        end = match.end()
    out.append(html.escape(symbol[end:]))
    return "".join(out)


def sheet_markdown(task: Task | str, variant: Variant, image: str | None = None, person: Person | None = None,
                   tolerances: Mapping[str, str] | None = None) -> str:
    """The sheet as Markdown; ``image`` is the drawing's file name (omitted if None); ``person`` the student of
    the class list (None: a line to write the name on); ``tolerances`` each column's tolerance in words (default:
    the kind's, :func:`~mechanisms.course.grading.default_rule`)."""
    task = _task(task)
    parts = _sheet_parts(task, variant, tolerances)
    lines = [f"# {parts['title']}", "", _name_line(person, markdown_text), ""]
    if image:
        lines += [f"![The mechanism of {variant.student}]({image})", ""]
    lines += ["## Data", "", "| symbol | meaning | value | unit |", "|---|---|---|---|"]
    lines += [f"| {symbol_markdown(symbol)} | " + " | ".join(_md(c) for c in rest) + " |"
              for symbol, *rest in parts["data"]]
    lines += ["", "## Task", "", f"Find, at the crank angles $φ$ = {parts['positions']}:", "",
              "| column | symbol | quantity | unit | tolerance |", "|---|---|---|---|---|"]
    lines += [f"| `{q.column}` | {symbol_markdown(q.symbol)} | {_md(q.meaning)} | {_md(q.unit)} | "
              f"{_md(parts['tolerances'][q.column])} |" for q in task.quantities]
    lines += ["", INSTRUCTIONS.format(student=variant.student), "", TOLERANCE_NOTE, "", "## Answers", "",
              "| position | $φ$, ° | " + " | ".join(f"{symbol_markdown(parts['label'][q.column]) or _md(q.column)}, "
                                                    f"{q.unit}" for q in task.quantities)
              + " |",
              "|---|---|" + "---|" * len(task.quantities)]
    lines += [f"| {i + 1} | {p:g} | " + " | ".join(" " for _ in task.quantities) + " |"
              for i, p in enumerate(variant.positions_deg)]
    lines += ["", "The answer form, to be filled in:", "", "```", ",".join(parts["header"])]
    lines += [f"{variant.student},{i + 1},{p:g}" + "," * len(task.quantities)
              for i, p in enumerate(variant.positions_deg)]
    lines += ["```", "", f"Every variant of this assignment is valid: {task.conditions}.", ""]
    return "\n".join(lines)


_CSS = """
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 46em; margin: 1.5em auto; color: #222; }
h1 { font-size: 1.4em; margin-bottom: 0.2em; } h2 { font-size: 1.1em; margin-top: 1.2em; }
table { border-collapse: collapse; margin: 0.5em 0; } td, th { border: 1px solid #999; padding: 0.25em 0.6em; }
th { background: #eee; text-align: left; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.answers { width: 100%; table-layout: fixed; } table.answers td { height: 1.8em; }
table.answers th { font-size: 0.85em; overflow-wrap: anywhere; } code, pre { font-family: "DejaVu Sans Mono", monospace; }
pre { background: #f5f5f5; padding: 0.5em; white-space: pre-wrap; overflow-wrap: anywhere; }
.name { margin: 0.5em 0 1em; } img { max-width: 100%; }
.small { font-size: 0.85em; color: #555; }
@media print { body { margin: 0; max-width: none; } pre { background: none; border: 1px solid #999; }
  @page { size: A4; margin: 15mm; } }
"""


def _numeric(text: str) -> str:
    """The class attribute of a table cell: numbers (and pairs of numbers) align right."""
    try:
        [float(t) for t in text.strip("()").split(",")]
    except ValueError:
        return ""
    return ' class="num"'


def sheet_html(task: Task | str, variant: Variant, png: bytes | None = None, person: Person | None = None,
               tolerances: Mapping[str, str] | None = None) -> str:
    """The sheet as one self-contained HTML page (the drawing embedded as a base64 PNG); ``person`` and
    ``tolerances`` as for :func:`sheet_markdown`."""
    task = _task(task)
    parts = _sheet_parts(task, variant, tolerances)
    e = html.escape
    png = drawing_png(variant) if png is None else png
    out = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
           f"<title>{e(parts['title'])}</title>", f"<style>{_CSS}</style>", "</head>", "<body>",
           f"<h1>{e(parts['title'])}</h1>",
           f'<p class="name">{_name_line(person, e).replace("   ", " &nbsp; ")}</p>',
           f'<img alt="The mechanism of {e(variant.student)}" src="data:image/png;base64,'
           f'{base64.b64encode(png).decode("ascii")}">',
           "<h2>Data</h2>", "<table><tr><th>symbol</th><th>meaning</th><th>value</th><th>unit</th></tr>"]
    out += [f'<tr><td>{symbol_html(s)}</td><td>{e(m)}</td><td{_numeric(v)}>{e(v)}</td><td>{e(u)}</td></tr>'
            for s, m, v, u in parts["data"]]
    out += ["</table>", "<h2>Task</h2>", f"<p>Find, at the crank angles <i>φ</i> = {e(parts['positions'])}:</p>",
            "<table><tr><th>column</th><th>symbol</th><th>quantity</th><th>unit</th><th>tolerance</th></tr>"]
    out += [f"<tr><td><code>{e(q.column)}</code></td><td>{symbol_html(q.symbol)}</td><td>{e(q.meaning)}</td>"
            f"<td>{e(q.unit)}</td><td>{e(parts['tolerances'][q.column])}</td></tr>" for q in task.quantities]
    out += ["</table>", f"<p>{e(INSTRUCTIONS.format(student=variant.student))}</p>", f"<p>{e(TOLERANCE_NOTE)}</p>",
            "<h2>Answers</h2>", '<table class="answers"><tr><th>position</th><th><i>φ</i>, °</th>'
            + "".join(f"<th>{symbol_html(parts['label'][q.column]) or e(q.column)}, {e(q.unit)}</th>"
                      for q in task.quantities) + "</tr>"]
    out += [f'<tr><td class="num">{i + 1}</td><td class="num">{p:g}</td>' + "<td></td>" * len(task.quantities)
            + "</tr>" for i, p in enumerate(variant.positions_deg)]
    form = [",".join(parts["header"])] + [f"{variant.student},{i + 1},{p:g}" + "," * len(task.quantities)
                                          for i, p in enumerate(variant.positions_deg)]
    out += ["</table>", "<p>The answer form, to be filled in:</p>", f"<pre>{e(chr(10).join(form))}</pre>",
            f'<p class="small">Every variant of this assignment is valid: {e(task.conditions)}.</p>',
            "</body>", "</html>", ""]
    return "\n".join(out)


def variant_comments(task: Task, variant: Variant, seed: int | None) -> list[str]:
    """The comment lines at the head of a variant's linkage file: whose it is and the crank's motion."""
    return [f"Assignment {task.name}, variant {variant.student}" + (f" (seed {seed})" if seed is not None else "")
            + ": written by python -m mechanisms assign.",
            f"The crank turns counter-clockwise at omega = {variant.omega!r} 1/s (constant: alpha = 0).",
            "Asked at the crank angles phi_deg = " + ", ".join(repr(p) for p in variant.positions_deg) + "."]


def linkage_text(task: Task, variant: Variant, seed: int | None) -> str | None:
    """The variant as a linkage file (TOML), loadable by :func:`mechanisms.load_linkage`: for a linkage file's
    assignment its own document, for a named mechanism its ``linkage_data()`` (the same linkage composed of
    its groups); None for a mechanism that has neither."""
    comments = variant_comments(task, variant, seed)
    if task.document is not None:
        return task.document(variant.mechanism, comments)
    data = getattr(variant.mechanism, "linkage_data", None)
    if data is None:
        return None
    from .variants import toml_text          # variants imports this module

    return toml_text(data(), comments)


def _identity(person: Person) -> dict[str, str]:
    return {"name": person.name, "email": person.email, "identifier": person.identifier}


def write_assignment(task: Task | str, variants: Sequence[Variant], out: str | pathlib.Path,
                     seed: int | None = None, people: Sequence[Person] | None = None, tolerance: Sequence[str] = (),
                     plan: bool = False) -> dict[str, list[pathlib.Path]]:
    """Write the sheets, answer forms, the key and ``variants.json`` into ``out`` (created if missing).

    ``people`` (one per variant, in order: :func:`mechanisms.course.roster.read_roster`) puts each student's
    name on the sheet and the columns ``name``, ``email``, ``identifier`` in the key and ``variants.json``.

    What a person wrote is made safe for each file: escaped for HTML (:func:`html.escape`) and for Markdown
    (:func:`~mechanisms.present.escape.markdown_text`) on the sheets; in the key and the answer forms every text
    cell that a spreadsheet could take for a formula (``=``, ``+``, ``-``, ``@``, tab, carriage return first) is
    written with a leading ``'`` (:func:`~mechanisms.present.escape.csv_cell`), numbers as numbers. Files are
    named by the student ids only (``s01.html``), never by names, so nothing of a class list reaches a path.

    Returns
    -------
    dict
        ``{"sheets": [...], "forms": [...], "key": [path], "variants": [path], "linkages": [...],
        "tolerances": [path], "moodle": [path]}``; ``moodle`` holds ``moodle-feedback.zip`` when every person is
        a participant of Moodle's grading worksheet: each student's sheet (``.html``), answer form and linkage
        file in the folder Moodle's *Upload multiple feedback files in a zip* gives to that participant
        (:func:`mechanisms.course.moodle.feedback_zip`).

    Raises
    ------
    InvalidParameterError
        If ``people`` is not one per variant, or two variants have the same student id (ignoring case).
    CourseFileError
        If the folder or a file cannot be written (the message names it and the cause).
    """
    task = _task(task)
    out = pathlib.Path(out)
    written: dict[str, list[pathlib.Path]] = {"sheets": [], "forms": [], "key": [], "variants": [], "linkages": [],
                                              "tolerances": [], "moodle": []}
    if people is not None and len(people) != len(variants):
        raise InvalidParameterError("people", len(people), f"one person per variant ({len(variants)})")
    ids = [_require_student_id(v.student).casefold() for v in variants]
    if len(set(ids)) != len(ids):     # s01 and S01 would be one file where names ignore case
        twice = sorted({v.student for v in variants if ids.count(v.student.casefold()) > 1})
        raise InvalidParameterError("variants", ", ".join(twice), "variants of different student ids (ignoring "
                                    "case: each id names the student's files)")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as failure:
        raise CourseFileError(f"output folder {out}: cannot be made ({failure.strerror or failure})") from None
    who = dict(zip((v.student for v in variants), people or ()))
    handout: dict[str, list[tuple[str, bytes]]] = {}     # each student's files, for Moodle's feedback zip
    columns = list(KEY_COLUMNS) + [q.column for q in task.quantities]
    rows, tolerances, words = key_and_tolerances(task, variants, tolerance, plan)
    for variant in variants:
        png = drawing_png(variant)
        write_file(out / f"{variant.student}.png", png, "drawing")
        document = linkage_text(task, variant, seed)
        if document is not None:
            path = out / f"{variant.student}.toml"
            write_file(path, document, "linkage file")
            written["linkages"].append(path)
        person = who.get(variant.student)
        text_of = words[variant.student]
        for suffix, text in ((".html", sheet_html(task, variant, png, person, text_of)),
                             (".md", sheet_markdown(task, variant, f"{variant.student}.png", person, text_of))):
            path = out / f"{variant.student}{suffix}"
            write_file(path, text, "sheet")
            written["sheets"].append(path)
        form = out / f"{variant.student}-answers.csv"
        _write_csv(form, columns, [{"student": variant.student, "position": i + 1, "phi_deg": p}
                                   for i, p in enumerate(variant.positions_deg)], "answer form")
        written["forms"].append(form)
        handout[variant.student] = [(path.name, path.read_bytes()) for path in
                                    (out / f"{variant.student}.html", form, out / f"{variant.student}.toml")
                                    if path.name != f"{variant.student}.toml" or document is not None]
    key = out / "key.csv"
    if who:      # who each student is, after the id: student,name,email,identifier,position,phi_deg,…
        rows = [{"student": row["student"], **_identity(who[row["student"]])} | row for row in rows]
        columns = [columns[0], *IDENTITY_COLUMNS, *columns[1:]]
    _write_csv(key, columns, rows, "answer key")
    written["key"].append(key)
    _write_csv(tolerances_path(key), [c for c in columns if c not in IDENTITY_COLUMNS], tolerances, "tolerance file")
    written["tolerances"].append(tolerances_path(key))
    record = out / "variants.json"
    records = [((v.record() | ({"file": f"{v.student}.toml"} if written["linkages"] else {})) if task.document is None else
                {"student": v.student, "mechanism": task.name, "file": f"{v.student}.toml", "omega": v.omega,
                 "alpha": 0.0, "positions_deg": list(v.positions_deg)})
               | (_identity(who[v.student]) if who else {}) for v in variants]
    write_file(record, json.dumps({"mechanism": task.name, "seed": seed, "variants": records}, indent=1,
                                  ensure_ascii=False) + "\n", "variants record")
    written["variants"].append(record)
    archive = feedback_zip(handout, who)
    if archive is not None:
        path = out / "moodle-feedback.zip"
        write_file(path, archive, "Moodle feedback files archive")
        written["moodle"].append(path)
    return written
