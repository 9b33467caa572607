"""Tests of ``python -m mechanisms assign`` and ``python -m mechanisms check``, run as a teacher runs them."""

from __future__ import annotations

import csv
import os
import pathlib
import re
import subprocess
import zipfile
import sys

import pytest

from mechanisms.cli import main


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "mechanisms", *args], capture_output=True, text=True, timeout=120,
                          cwd=cwd)


def test_assign_then_check_the_key(tmp_path):
    out = tmp_path / "course"
    made = run("assign", "crank-slider", "--students", "3", "--seed", "2026", "--out", str(out))
    assert made.returncode == 0, made.stderr
    assert "crank-slider: 3 variants (s01 … s03), seed 2026" in made.stdout
    names = sorted(p.name for p in out.iterdir())
    assert names == ["key-tolerances.csv", "key.csv"] + [f"s0{i}{suffix}" for i in (1, 2, 3) for suffix in (
        "-answers.csv", ".html", ".md", ".png", ".toml")] + ["variants.json"]
    checked = run("check", str(out / "key.csv"), str(out / "key.csv"), "--marks", str(tmp_path / "marks.csv"))
    assert checked.returncode == 0, checked.stderr
    assert "Class: 45 of 45 answers right (100 %)." in checked.stdout      # 3 students × 3 positions × 5
    assert len(list(csv.DictReader((tmp_path / "marks.csv").open()))) == 45


def test_the_same_seed_gives_the_same_files(tmp_path):
    for folder in ("a", "b"):
        assert main(["assign", "four-bar", "--students", "2", "--seed", "7", "--out", str(tmp_path / folder)]) == 0
    for name in ("key.csv", "s01.html", "s02.md", "s01.png", "variants.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name
    assert main(["assign", "four-bar", "--students", "2", "--seed", "8", "--out", str(tmp_path / "c")]) == 0
    assert (tmp_path / "c" / "key.csv").read_bytes() != (tmp_path / "a" / "key.csv").read_bytes()


def test_without_a_seed_the_seed_is_printed_and_repeats_the_run(tmp_path, capsys):
    assert main(["assign", "slotted-lever", "--students", "2", "--out", str(tmp_path / "a")]) == 0
    seed = re.search(r"seed (\d+)", capsys.readouterr().out).group(1)
    assert main(["assign", "slotted-lever", "--students", "2", "--seed", seed, "--out", str(tmp_path / "b")]) == 0
    assert (tmp_path / "a" / "key.csv").read_bytes() == (tmp_path / "b" / "key.csv").read_bytes()


def test_check_reports_wrong_answers_and_file_problems(tmp_path, capsys):
    assert main(["assign", "four-bar", "--students", "2", "--seed", "3", "--out", str(tmp_path)]) == 0
    rows = list(csv.DictReader((tmp_path / "key.csv").open()))
    rows[0]["rocker.omega"] = repr(float(rows[0]["rocker.omega"]) * 1.1)
    rows.append(dict(rows[1], student="s77"))
    with (tmp_path / "answers.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    capsys.readouterr()
    status = main(["check", str(tmp_path / "key.csv"), str(tmp_path / "answers.csv")])
    out = capsys.readouterr().out
    assert status == 1                       # graded, with a problem in the answer file
    assert "s01: 17 of 18 right (94 %)" in out
    assert re.search(r"wrong +position 1 \(φ = \d+°\) rocker\.omega: answer .* off by .*, [+-]10 %", out)
    assert "unknown student id 's77'" in out


@pytest.mark.parametrize(("content", "message"), [
    ("student,position,psi\ns01,1,2\n", "column(s) not in the key: 'psi'"),
    ("name,position\ns01,1\n", "no column 'student'"),
    ("", "empty"),
])
def test_check_refuses_bad_files_with_a_message(tmp_path, content, message):
    assert main(["assign", "crank-slider", "--students", "1", "--seed", "1", "--out", str(tmp_path)]) == 0
    (tmp_path / "bad.csv").write_text(content)
    result = run("check", str(tmp_path / "key.csv"), str(tmp_path / "bad.csv"))
    assert result.returncode == 2
    assert result.stderr.startswith("error: answer file") and message in result.stderr
    assert "Traceback" not in result.stderr


def test_check_refuses_a_bad_tolerance(tmp_path):
    assert main(["assign", "crank-slider", "--students", "1", "--seed", "1", "--out", str(tmp_path)]) == 0
    result = run("check", str(tmp_path / "key.csv"), str(tmp_path / "key.csv"), "--relative", "150")
    assert result.returncode == 2 and "--relative must be a percentage from 0 to less than 100" in result.stderr
    # a stricter tolerance than the default is fine, and the key still passes
    result = run("check", str(tmp_path / "key.csv"), str(tmp_path / "key.csv"), "--relative", "0.1")
    assert result.returncode == 0 and "max(0.1 % of |key|, floor)" in result.stdout


def test_check_with_a_missing_key(tmp_path):
    result = run("check", str(tmp_path / "nothing.csv"), str(tmp_path / "nothing.csv"))
    assert result.returncode == 2 and "no such file" in result.stderr and "Traceback" not in result.stderr


def test_assign_refuses_bad_requests(tmp_path):
    result = run("assign", "gear-train", "--students", "3", "--out", str(tmp_path))
    assert result.returncode == 2 and "MECHANISM must be one of crank-slider" in result.stderr
    assert "a linkage file or a shipped example" in result.stderr
    result = run("assign", "four-bar", "--students", "0", "--out", str(tmp_path))
    assert result.returncode == 2 and "students must be a whole number from 1 to 9999" in result.stderr
    result = run("assign", "four-bar", "--students", "2", "--positions", "30", "--out", str(tmp_path))
    assert result.returncode == 2 and "positions must be a whole number from 1 to 24" in result.stderr
    assert "Traceback" not in result.stderr


def test_table_is_unchanged(capsys):
    # the table subcommand still runs beside the new ones
    assert main(["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--omega", "215", "--positions", "4",
                 "--format", "csv"]) == 0
    rows = list(csv.DictReader(capsys.readouterr().out.splitlines()))
    # by hand: at φ = 0 the slider is at L1 + L2 = 0.38 m
    assert len(rows) == 4 and float(rows[0]["B.s"]) == pytest.approx(0.38)


# --- the example run of the page "Using this book in a course" ------------------------------------------

COURSE_PAGE = pathlib.Path(__file__).resolve().parent.parent / "book" / "course.md"


def matches_shortened(shown: list[str], actual: list[str]) -> bool:
    """True if ``actual`` is ``shown`` with each line "…" standing for one or more omitted lines."""
    pattern = "".join(r"(?:.*\n)+" if line == "…" else re.escape(line) + r"\n" for line in shown)
    return re.fullmatch(pattern, "".join(line + "\n" for line in actual)) is not None


def test_matches_shortened():
    assert matches_shortened(["a", "…", "d"], ["a", "b", "c", "d"])
    assert not matches_shortened(["a", "…", "d"], ["a", "d"])          # "…" stands for at least one line
    assert not matches_shortened(["a", "c"], ["a", "b", "c"])
    assert matches_shortened(["…", "c"], ["a", "b", "c"])


def test_the_course_page_shows_what_the_tool_does(tmp_path):
    page = COURSE_PAGE.read_text(encoding="utf8")
    # the files the page shows as input (a caption that is a file name), then its sessions in order
    files = re.findall(r"```\{code-block\} text\n:caption: ([\w./-]+)\n\n(.*?)\n```", page, flags=re.S)
    assert [name for name, _ in files] == ["answers/s01.csv", "answers/s02.csv", "answers/s03.csv", "answers/s04.csv",
                                           "worksheet.csv", "answers/kovalenko.csv", "answers/nunez.csv"]
    (tmp_path / "answers").mkdir()
    for name, text in files:
        (tmp_path / name).write_text(text + "\n", encoding="utf8")
    sessions = re.findall(r"```console\n\$ (.*?)\n(.*?)\n```", page, flags=re.S)
    assert len(sessions) == 5
    env = dict(os.environ, PATH=os.path.dirname(sys.executable) + os.pathsep + os.environ.get("PATH", ""))
    for command, shown in sessions:
        assert command.startswith("python -m mechanisms ")
        result = subprocess.run(command, shell=True, cwd=tmp_path, env=env, capture_output=True, text=True,
                                timeout=120)
        assert result.stderr == ""
        assert matches_shortened(shown.splitlines(), result.stdout.splitlines()), \
            f"the page shows for `{command}`:\n{shown}\n\nbut the tool prints:\n{result.stdout}"
    # the quiz's first answer box, as the page quotes it: the key's value and tolerance (to the last digits a
    # machine's libm may change)
    box = re.search(r"`\{1:NUMERICAL:=([-0-9.e]+):([-0-9.e]+)\}`", page)
    key = next(csv.DictReader(open(tmp_path / "quiz" / "key.csv", encoding="utf8")))
    tolerance = next(csv.DictReader(open(tmp_path / "quiz" / "key-tolerances.csv", encoding="utf8")))
    assert (key["student"], key["position"]) == ("s01", "1")
    assert float(box.group(1)) == pytest.approx(float(key["B.s"]), rel=1e-12)
    assert float(box.group(2)) == pytest.approx(float(tolerance["B.s"]), rel=1e-12)
    assert float(box.group(2)) == pytest.approx(0.01 * float(box.group(1)), rel=1e-12)   # 1 % of the value
    # the sheets reach Moodle: one folder per participant of the worksheet, named as Moodle's importer reads it
    with zipfile.ZipFile(tmp_path / "moodle" / "moodle-feedback.zip") as archive:
        names = archive.namelist()
    assert names == [f"s0{i}_{number}_assignfeedback_file/s0{i}{suffix}"
                     for i, number in ((1, 2318104), (2, 2318105), (3, 2318106))
                     for suffix in (".html", "-answers.csv", ".toml")]
    # the worksheet the Moodle example writes, as the page shows it
    graded = re.search(r"```\{code-block\} text\n:caption: worksheet-graded.csv \(written by check\)\n\n(.*?)\n```",
                       page, flags=re.S).group(1)
    assert (tmp_path / "worksheet-graded.csv").read_text(encoding="utf8") == graded + "\n"
    sheet = re.search(r"```\{code-block\} md\n:caption: course/s01.md \(shortened\)\n\n(.*?)\n```", page,
                      flags=re.S).group(1)
    actual = (tmp_path / "course" / "s01.md").read_text(encoding="utf8").splitlines()
    assert matches_shortened(sheet.splitlines(), actual)
