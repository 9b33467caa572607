"""Layer 7: a Moodle quiz that grades itself — ``python -m mechanisms assign … --moodle-quiz quiz.xml``.

The file is Moodle XML (*Question bank → Import → Moodle XML format*): one question category named after the
assignment, holding one *Embedded answers (Cloze)* question per variant. Each question's text is HTML: the
variant's data, its drawing (a PNG embedded in the file as a ``<file encoding="base64">`` element of the
question text and shown by ``<img src="@@PLUGINFILE@@/sNN.png">``, as Moodle's importer,
``qformat_xml::import_text_with_files``, expects), and a table with one numerical sub-question per asked value,
``{1:NUMERICAL:=VALUE:TOLERANCE}``: the key's value and the key's tolerance (``key-tolerances.csv``) written
with ``repr``, so that they are the key's numbers to the last digit. A teacher adds "a random question from
this category" to a quiz; each student draws a variant and Moodle grades each value.

Text that comes from a file (a linkage's name, its joints' and links' names) is escaped for HTML, and its
braces are written as character references (``&#123;``, ``&#125;``) so that no text can open a Cloze
sub-question (Moodle's ``qtype_multianswer_extract_question`` looks for ``{N:TYPE:…}`` in the question's HTML
source). No name of a class list goes into the quiz: variants are drawn at random, not handed to a person.
"""

from __future__ import annotations

import base64
import html
import pathlib
import xml.etree.ElementTree as ET
from typing import Sequence

from ..analysis.assignments import Task
from .assign import Variant, _sheet_parts, drawing_png, key_and_tolerances, symbol_html
from .csvtext import write_file
from .grading import read_key

__all__ = ["cloze_text", "quiz_xml", "write_quiz"]


def cloze_text(text: str) -> str:
    """Text for the HTML of a Cloze question: escaped for HTML, its braces as character references."""
    return html.escape(text).replace("{", "&#123;").replace("}", "&#125;")


def _number(value: float) -> str:
    return repr(float(value))


def quiz_xml(task: Task, variants: Sequence[Variant], values: Sequence[dict], tolerances: Sequence[dict],
             pngs: Sequence[bytes] | None = None) -> bytes:
    """The Moodle XML of the quiz: a category and one Cloze question per variant.

    ``values`` and ``tolerances`` are the key's rows and their tolerances (:func:`mechanisms.course.assign.
    key_and_tolerances`, or the key files read back), in the key's order.
    """
    quiz = ET.Element("quiz")
    category = ET.SubElement(quiz, "question", type="category")
    ET.SubElement(ET.SubElement(category, "category"), "text").text = \
        "$course$/top/" + f"{task.title} ({task.name})".replace("/", "//")
    info = ET.SubElement(category, "info", format="html")
    ET.SubElement(info, "text").text = (f"<p>{cloze_text(task.title)}: {len(variants)} variants, one drawn at random "
                                        "for each student.</p>")
    for number, variant in enumerate(variants):
        rows = [r for r in values if r["student"] == variant.student]
        tols = [t for t in tolerances if t["student"] == variant.student]
        png = drawing_png(variant) if pngs is None else pngs[number]
        parts = _sheet_parts(task, variant)
        question = ET.SubElement(quiz, "question", type="cloze")
        ET.SubElement(ET.SubElement(question, "name"), "text").text = f"{task.name} {variant.student}"
        body = ET.SubElement(question, "questiontext", format="html")
        data = "".join(f"<tr><td>{symbol_html(s).replace('{', '&#123;').replace('}', '&#125;')}</td>"
                       f"<td>{cloze_text(m)}</td><td>{cloze_text(v)}</td><td>{cloze_text(u)}</td></tr>"
                       for s, m, v, u in parts["data"])
        asked = "".join(f"<tr><td><code>{cloze_text(q.column)}</code></td><td>{cloze_text(q.meaning)}</td>"
                        f"<td>{cloze_text(q.unit)}</td></tr>" for q in task.quantities)
        answers = []
        for row, tol in zip(rows, tols):
            cells = "".join(f"<td>{{1:NUMERICAL:={_number(row[q.column])}:{_number(tol[q.column])}}}</td>"
                            for q in task.quantities)
            answers.append(f"<tr><td>{row['position']}</td><td>{row['phi_deg']:g}</td>{cells}</tr>")
        header = "".join(f"<th>{cloze_text(q.column)}, {cloze_text(q.unit)}</th>" for q in task.quantities)
        ET.SubElement(body, "text").text = (
            f"<h3>{cloze_text(task.title)}: variant {cloze_text(variant.student)}</h3>"
            f'<p><img src="@@PLUGINFILE@@/{variant.student}.png" alt="The mechanism of variant '
            f'{cloze_text(variant.student)}"></p>'
            f"<table border=\"1\"><tr><th>symbol</th><th>meaning</th><th>value</th><th>unit</th></tr>{data}</table>"
            f"<p>Find, at the crank angles φ = {cloze_text(parts['positions'])}:</p>"
            f"<table border=\"1\"><tr><th>column</th><th>quantity</th><th>unit</th></tr>{asked}</table>"
            "<p>Angles counter-clockwise from +x, in [0°, 360°); each value is right within its tolerance (the "
            "larger of a percentage of the exact value and an absolute amount).</p>"
            f"<table border=\"1\"><tr><th>position</th><th>φ, °</th>{header}</tr>{''.join(answers)}</table>")
        image = ET.SubElement(body, "file", name=f"{variant.student}.png", path="/", encoding="base64")
        image.text = base64.b64encode(png).decode("ascii")
        feedback = ET.SubElement(question, "generalfeedback", format="html")
        ET.SubElement(feedback, "text").text = ""
        ET.SubElement(question, "penalty").text = "0.3333333"
        ET.SubElement(question, "hidden").text = "0"
        ET.SubElement(question, "idnumber").text = f"{task.name}-{variant.student}"
    ET.indent(quiz, space=" ")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(quiz, encoding="utf-8") + b"\n"


def write_quiz(task: Task, variants: Sequence[Variant], path: str | pathlib.Path,
               key: str | pathlib.Path | None = None, tolerance: Sequence[str] = (), plan: bool = False) -> pathlib.Path:
    """Write the Moodle quiz of the variants to ``path``.

    With ``key`` (the ``key.csv`` that ``assign`` wrote for the same variants), the values and tolerances are read
    back from it and its tolerance file, so that the quiz grades exactly as ``check`` does; otherwise they are
    computed (:func:`~mechanisms.course.assign.key_and_tolerances` with ``tolerance`` and ``plan``).
    """
    if key is not None:
        read = read_key(key)
        values = [{"student": s, "position": p, "phi_deg": read.phi[s, p], **read.values[s, p]}
                  for s, p in read.values]
        tolerances = [{"student": s, "position": p, **read.tolerances[s, p]} for s, p in read.tolerances]
    else:
        values, tolerances, _ = key_and_tolerances(task, variants, tolerance, plan)
    path = pathlib.Path(path)
    write_file(path, quiz_xml(task, variants, values, tolerances), "Moodle quiz")
    return path
