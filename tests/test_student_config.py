"""Tests of tools/student_config.py: the student edition's configuration is the book's, with the solutions hidden."""

from __future__ import annotations

import importlib.util
import pathlib

import yaml

ROOT = pathlib.Path(__file__).resolve().parent.parent
spec = importlib.util.spec_from_file_location("student_config", ROOT / "tools" / "student_config.py")
student_config = importlib.util.module_from_spec(spec)
spec.loader.exec_module(student_config)


def test_the_student_configuration(tmp_path):
    output = tmp_path / "student" / "_config.yml"
    assert student_config.main([str(output)]) == 0
    book = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf8"))
    student = yaml.safe_load(output.read_text(encoding="utf8"))
    assert student["sphinx"]["config"]["hide_solutions"] is True
    assert student["sphinx"]["config"]["html_copy_source"] is False
    assert student["title"] == book["title"] + " (student edition)"
    # the local extensions, the book's and the student edition's, resolve to _ext/ from the new place
    extensions = student["sphinx"]["local_extensions"]
    assert set(extensions) == set(book["sphinx"].get("local_extensions", {})) | {"student_edition"}
    for path in extensions.values():
        assert (output.parent / path).resolve() == (ROOT / "_ext").resolve()
    assert (ROOT / "_ext" / "student_edition.py").is_file()
    # everything else is the book's own configuration
    for part in (book, student):
        part.pop("title")
        part["sphinx"].pop("local_extensions", None)
        for key in ("hide_solutions", "html_copy_source"):
            part["sphinx"]["config"].pop(key, None)
    assert student == book
