"""The command line's inputs and outputs (issue 28): angles of any size reduced exactly, output that cannot
be written, and junk in every option — a right answer or a clean message, never a traceback.

Expected values: cosines of the exactly reduced angles from a Taylor series in exact rational arithmetic
(:mod:`fractions`, π to 60 digits), independent of numpy and of the package.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import io
import json
import os
import subprocess
import sys
from fractions import Fraction

import pytest

from mechanisms import cli
from mechanisms.cli import main

PI = Fraction("3.14159265358979323846264338327950288419716939937510582097494459")


def exact_cos(degrees: Fraction) -> Fraction:
    """cos of an angle in degrees, reduced exactly modulo 360 and summed as a Taylor series in fractions
    (|x| ≤ 2π: 60 terms leave an error below 1e-40)."""
    x = (degrees % 360) * PI / 180
    term, total = Fraction(1), Fraction(1)
    for k in range(1, 60):
        term = -term * x * x / ((2 * k - 1) * (2 * k))
        total += term
    return total


def run(args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(args)
    return status, out.getvalue(), err.getvalue()


# --- angles of any size -----------------------------------------------------------------------------------

@pytest.mark.parametrize("start", ["1e15", "1e10", "123456789012.5", "-4.5e15"])
def test_huge_crank_angles_are_reduced_exactly_before_radians(start):
    # the yoke's slider is at s = r cos φ (by hand), r = 0.1 m; φ reduced exactly in degrees
    status, out, err = run(["table", "scotch-yoke", "--omega", "1", "--angles", f"{start}:{float(start) + 100}:30",
                            "--format", "csv"])
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 4
    for k, row in enumerate(rows):
        asked = Fraction(float(start)) + 30 * k          # every one of these sums is a double, exactly
        assert Fraction(row["phi_deg"]) == asked         # the angle as asked, not its remainder
        assert Fraction(row["crank.angle_deg"]) == asked
        expected = float(Fraction(1, 10) * exact_cos(asked))
        assert float(row["A.x"]) == pytest.approx(expected, abs=2e-17)
        assert float(row["Y.x"]) == pytest.approx(expected, abs=2e-17)


def test_an_angle_parameter_is_reduced_exactly_and_shown_as_asked():
    # the slider on a coupler with its guide at 1e15° = 280° + 2777777777777 turns (fractions: 10**15 % 360 = 280)
    assert Fraction(10**15) % 360 == 280
    base = ["table", "slider-on-coupler", "--crank", "0.08", "--rod", "0.3", "--guide-point", "0.2,0", "--omega",
            "3", "--positions", "6", "--format", "json"]
    status, huge, err = run(base + ["--guide-angle", "1e15"])
    assert status == 0, err
    status, plain, err = run(base + ["--guide-angle", "280"])
    assert status == 0, err
    huge_data, plain_data = json.loads(huge), json.loads(plain)
    assert huge_data["parameters"]["guide_angle_deg"] == 1e15
    assert plain_data["parameters"]["guide_angle_deg"] == 280.0
    assert huge_data["rows"] == plain_data["rows"]


def test_angles_as_asked_and_as_solved():
    assert cli.parse_angles_deg("350:400:20").tolist() == [350.0, 370.0, 390.0]
    # 370° is 10°, 390° is 30°: exactly, in radians of the remainder
    assert cli.to_radians(370.0, "--angles") == pytest.approx(float(10 * PI / 180), abs=1e-18)


# --- output that cannot be written ------------------------------------------------------------------------

class Full(io.StringIO):
    """An output whose disk is full."""

    def write(self, text):
        raise OSError(errno.ENOSPC, "No space left on device")


class Gone(io.StringIO):
    """An output whose reader has gone (a broken pipe)."""

    def write(self, text):
        raise BrokenPipeError(errno.EPIPE, "Broken pipe")


class Closed(io.StringIO):
    def __init__(self):
        super().__init__()
        self.close()


@pytest.fixture
def course(tmp_path):
    assert main(["assign", "crank-slider", "--students", "1", "--seed", "3", "--out", str(tmp_path / "c")]) == 0
    return tmp_path / "c"


def commands(folder):
    return {
        "table": ["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--omega", "1"],
        "table json": ["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame",
                       "0.4,0", "--omega", "1", "--format", "json"],
        "table file": ["table", "jansen", "--omega", "1", "--format", "csv"],
        "structure": ["structure", "watt-six-bar"],
        "assign": ["assign", "four-bar", "--students", "1", "--seed", "1", "--out", str(folder / "again")],
        "check": ["check", str(folder / "key.csv"), str(folder / "key.csv")],
        "bench": ["bench", "--only", "startup", "--format", "json"],
        "help": ["table", "crank-slider", "--help"],
    }


@pytest.fixture
def quick_bench(monkeypatch):
    import mechanisms.bench as bench
    monkeypatch.setattr(bench, "startup_times", lambda repeat: {"python": "test", "results": []})


@pytest.mark.parametrize("name", ["table", "table json", "table file", "structure", "assign", "check", "bench",
                                  "help"])
@pytest.mark.parametrize("stream, status, message", [
    (Full, 2, "error: cannot write to standard output: No space left on device\n"),
    (Closed, 2, "error: standard output is closed\n"),
    (lambda: None, 2, "error: standard output is closed\n"),
    (Gone, 1, ""),                      # a reader that stopped early: quietly, as Python's documentation says
])
def test_output_that_cannot_be_written_is_one_line_not_a_traceback(name, stream, status, message, course,
                                                                   quick_bench, monkeypatch):
    err = io.StringIO()
    monkeypatch.setattr(sys, "stdout", stream())
    monkeypatch.setattr(sys, "stderr", err)
    args = commands(course)[name]
    if name == "help" and stream is not Full and stream is not Gone and stream is not Closed:
        # argparse shows help on standard error when there is no standard output at all
        assert main(args) == 0 and "usage:" in err.getvalue()
        return
    assert main(args) == status
    assert err.getvalue() == message


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize("args", [["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--omega", "1",
                                   "--positions", "5000"], ["structure", "jansen"], ["--help"]])
def test_a_full_disk_and_a_closed_output_in_a_real_process(args):
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "mechanisms", *args], stdout=full, stderr=subprocess.PIPE,
                              text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr == "error: cannot write to standard output: No space left on device\n"
    closed = subprocess.run([sys.executable, "-m", "mechanisms", *args], stderr=subprocess.PIPE, text=True,
                            timeout=120, preexec_fn=lambda: os.close(1))
    if args == ["--help"]:     # argparse shows help on standard error instead
        assert closed.returncode == 0 and "usage:" in closed.stderr
    else:
        assert closed.returncode == 2
        assert closed.stderr == "error: standard output is closed\n"


def test_a_reader_that_stops_early_is_not_a_traceback():
    # `python -m mechanisms table … | head -1`: the pipe breaks after the first line
    with subprocess.Popen([sys.executable, "-m", "mechanisms", "table", "crank-slider", "--crank", "0.08", "--rod",
                           "0.3", "--omega", "1", "--positions", "200000", "--format", "csv"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE) as process:
        assert process.stdout is not None and process.stderr is not None
        assert process.stdout.readline().startswith(b"phi_deg,")
        process.stdout.close()
        status = process.wait(timeout=120)
        assert status == 1
        assert process.stderr.read() == b""


# --- junk in every option -------------------------------------------------------------------------------------

SLIDER = ["table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--omega", "1"]


@pytest.mark.parametrize("extra, named", [
    (["--angles", ""], "--angles"),
    (["--angles", "0:360:0"], "--angles"),
    (["--angles", "0:360:-30"], "--angles"),
    (["--angles", "0:1:1e-9"], "--angles must be at most 10000000 positions"),
    (["--angles", "-1.7e308:1.7e308:1e308"], "--angles"),
    (["--angles", "0:1e400:1"], "--angles"),
    (["--angles", "0,360,30"], "--angles"),
    (["--positions", "0"], "--positions"),
    (["--positions", "-0"], "--positions"),
    (["--positions", "-3"], "--positions"),
    (["--positions", "10000001"], "--positions"),
    (["--positions", "1e3"], "--positions"),
    (["--positions", "١٢"], "--positions"),
    (["--positions", "99999999999999999999999999"], "--positions"),
    (["--omega", "nan"], "omega"),
    (["--omega", "1e400"], "omega"),
    (["--omega", "1e60"], "omega must be of magnitude at most"),
    (["--omega", "–5"], "en dash"),
    (["--omega", "1,5"], "decimal separator"),
    (["--omega", "1_000"], "--omega"),
    (["--omega", ""], "--omega"),
    (["--alpha", "inf"], "alpha"),
    (["--offset", "1e400"], "offset"),
    (["--point", "S=rocker:0.1"], "on one of the links crank, coupler"),
    (["--point", "S=coupler:nan"], "--point"),
    (["--point", "S=coupler:1e300"], "along"),
    (["--point", ""], "--point"),
    (["--format", "xml"], "--format"),
])
def test_junk_in_an_option_is_a_message_naming_it(extra, named):
    arguments = list(SLIDER)
    if extra[0] in arguments:
        arguments[arguments.index(extra[0]) + 1] = extra[1]
    else:
        arguments += extra
    status, out, err = run(arguments)
    assert status == 2 and out == ""
    assert named in err and "Traceback" not in err
    assert "error: " in err.strip().splitlines()[-1]   # usage lines (argparse) and one message, no traceback


def test_the_unicode_minus_is_a_minus():
    # expected: "−90:90:30" and "−5" (U+2212, as word processors write them) are the same input as
    # "-90:90:30" and "-5", so the two tables are the same text
    plain = run(list(SLIDER) + ["--angles", "-90:90:30", "--omega", "-5"])
    typeset = run(list(SLIDER) + ["--angles", "\u221290:90:30", "--omega", "\u22125"])
    assert plain[0] == 0 and typeset == plain


@pytest.mark.parametrize("arguments, named", [
    (["table", "/tmp", "--omega", "1"], "is a folder, not a linkage file"),
    (["structure", "/tmp"], "is a folder, not a linkage file"),
    (["table", "no-such-mechanism.toml", "--omega", "1"], "no such file"),
    (["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame", "0.4", "--omega",
      "1"], "--frame"),
    (["table", "four-bar", "--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame", "0.4,0", "--omega",
      "1", "--branch", "0"], "--branch"),
    (["table", "slider-on-coupler", "--crank", "0.08", "--rod", "0.3", "--guide-point", "0.2,0", "--omega", "1",
      "--guide-angle", "inf"], "--guide-angle"),
    (["bench", "--sizes", "99999999999999"], "--sizes"),
    (["bench", "--sizes", "1,x"], "--sizes"),
    (["bench", "--repeat", "100000"], "--repeat"),
    (["assign", "crank-slider", "--students", "١"], "--students"),
    (["check", "/tmp", "/tmp", "--relative", "nan"], "--relative"),
])
def test_junk_elsewhere_is_a_message_too(arguments, named):
    status, out, err = run(arguments)
    assert status == 2
    assert named in err and "Traceback" not in err


def test_negative_zero_and_tiny_values_are_numbers():
    # −0 is 0 (an axial crank-slider: s at φ = 0 is L1 + L2 = 0.38 m by hand)
    status, out, err = run(SLIDER + ["--offset", "-0", "--omega", "-0", "--positions", "1", "--format", "json"])
    assert status == 0, err
    row = json.loads(out)["rows"][0]
    assert row["sliders"]["B"]["s"] == pytest.approx(0.38, rel=1e-15)
    assert row["links"]["crank"]["omega"] == 0.0


def test_names_in_a_csv_table_never_start_a_formula():
    # expected (OWASP, by hand): a point named "+1+2" or "@SUM(1)" heads its columns as "'+1+2.x" …, and the
    # numbers below stay numbers (the crank pin's x at 0° is L₁ = 0.08 m, written as 0.08)
    status, out, err = run(list(SLIDER) + ["--positions", "1", "--point", "+1+2=coupler:0.1",
                                           "--point", "@SUM(1)=coupler:0.1", "--format", "csv"])
    assert status == 0, err
    header, first = out.splitlines()[:2]
    names = header.split(",")
    assert "'+1+2.x" in names and "'@SUM(1).ay" in names
    assert not any(n[:1] in "=+-@" for n in names)
    assert first.split(",")[names.index("A.x")] == "0.08"
