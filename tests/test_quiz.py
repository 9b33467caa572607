"""Tests of ``assign … --moodle-quiz``: Moodle XML with one Cloze question per variant, equal to the key."""

from __future__ import annotations

import base64
import csv
import html
import re
import xml.etree.ElementTree as ET

import pytest

from mechanisms.cli import main

CLOZE = re.compile(r"\{1:NUMERICAL:=([^:}]+):([^}]+)\}")


def _quiz(tmp_path, name, *extra):
    out = tmp_path / "out"
    assert main(["assign", name, "--students", "3", "--seed", "9", "--out", str(out), "--moodle-quiz",
                 str(tmp_path / "quiz.xml"), *extra]) == 0
    key = list(csv.DictReader((out / "key.csv").open(encoding="utf-8")))
    tolerances = list(csv.DictReader((out / "key-tolerances.csv").open(encoding="utf-8")))
    return ET.parse(tmp_path / "quiz.xml").getroot(), key, tolerances


@pytest.mark.parametrize("name", ["four-bar", "watt-six-bar"])
def test_one_cloze_question_per_variant_with_the_keys_values_and_tolerances(tmp_path, name):
    root, key, tolerances = _quiz(tmp_path, name)
    assert root.tag == "quiz"
    category, *questions = root.findall("question")
    assert category.get("type") == "category" and category.find("category/text").text.startswith("$course$/top/")
    assert [q.get("type") for q in questions] == ["cloze"] * 3
    columns = list(key[0])[3:]
    for number, question in enumerate(questions):
        student = f"s0{number + 1}"
        text = question.find("questiontext/text").text
        assert question.find("questiontext").get("format") == "html"
        # the drawing: a file of the question text, referred to by @@PLUGINFILE@@
        image = question.find("questiontext/file")
        assert image.get("name") == f"{student}.png" and image.get("encoding") == "base64"
        assert base64.b64decode(image.text).startswith(b"\x89PNG")
        assert f'src="@@PLUGINFILE@@/{student}.png"' in text
        rows = [r for r in key if r["student"] == student]
        tols = [t for t in tolerances if t["student"] == student]
        expected = [(float(r[c]), float(t[c])) for r, t in zip(rows, tols) for c in columns]
        found = [(float(v), float(t)) for v, t in CLOZE.findall(text)]
        assert found == expected            # the same doubles, in the key's order


def test_text_from_a_file_cannot_inject_html_or_cloze(tmp_path):
    from mechanisms.linkages.linkage_file import example_file

    path = tmp_path / "evil.toml"
    source = example_file("watt-six-bar").read_text(encoding="utf-8")
    path.write_text(source.replace('name = "Watt six-bar"', 'name = "<b>x</b> {1:NUMERICAL:=0:1} # ~ / \\""'),
                    encoding="utf-8")
    root, key, _ = _quiz(tmp_path, str(path))
    for question in root.findall("question[@type='cloze']"):
        text = question.find("questiontext/text").text
        assert "<b>" not in text and "&lt;b&gt;x&lt;/b&gt;" in text
        # the name's braces are character references: Moodle's parser sees only the asked values
        assert "&#123;1:NUMERICAL:=0:1&#125;" in text
        assert len(CLOZE.findall(text)) == 3 * (len(key[0]) - 3)
        assert html.unescape(text).count("{1:NUMERICAL:=0:1}") == 1
