"""Fuzz tests of the command line (issue 28, beside tests/test_fuzz.py): random argv for ``table`` and
``structure``, run in-process. Every run ends with exit 0 and output, or exit 2 and a message on standard error;
never an exception escaping ``main`` and never a traceback. A JSON table that succeeds has one row per position
asked for (the count by hand from START:STOP:STEP or --positions).

Derandomized (tests/conftest.py's profile), a few hundred examples, in seconds.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import warnings

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechanisms.cli import main
from mechanisms.linkages import registry

FUZZ = settings(derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow], max_examples=300)

JUNK = ["", " ", "nan", "-inf", "1e400", "-1e400", "-0", "−5", "1,5", "1_000", "0x1", "١٢", "\x00", "1e-400",
        "5e-324", "1e308", "9" * 60, "+1", "-1", "0", "0.1", "0.3", "2", "0.4,0", "-0.4,0.05", "1,2,3", "a=b:c",
        "S=coupler:0.1", "S=crank:0.1,-0.02", "S=rocker:1", "S=coupler:1e300", "0:360:30", "0:360:0", "-90:90:30",
        "360:0:30", "0:1:1e-300", "1e15:1.0000000000001e15:30", "-1.7e308:1.7e308:1e308", "text", "csv", "json",
        "xml", "/tmp", "/dev/null", "jansen", "κ"]
OPTIONS = ["--crank", "--rod", "--offset", "--coupler", "--rocker", "--frame", "--pivot", "--branch", "--omega",
           "--alpha", "--angles", "--positions", "--point", "--format", "--half-coupler", "--ground", "--lever",
           "--ram-height", "--rocker-pivot", "--guide-point", "--guide-angle", "--nope"]
VALID = {"crank-slider": ["--crank", "0.08", "--rod", "0.3"],
         "four-bar": ["--crank", "0.1", "--coupler", "0.35", "--rocker", "0.3", "--frame", "0.4,0"]}


@st.composite
def argv(draw):
    head = draw(st.sampled_from([["table", name] for name in sorted(registry)]
                                + [["table", "scotch-yoke"], ["table", "jansen"], ["table", "/tmp"], ["structure"],
                                   ["structure", "watt-six-bar"], ["structure", "/tmp"], ["structure", "x.toml"]]))
    tokens = list(head)
    if head[0] == "table" and head[1] in VALID and draw(st.booleans()):
        tokens += VALID[head[1]] + ["--omega", "10"]            # mostly valid, then perturbed
    for _ in range(draw(st.integers(0, 4))):
        tokens.append(draw(st.sampled_from(OPTIONS)))
        tokens.append(draw(st.one_of(st.sampled_from(JUNK), st.text(max_size=6))))
    if draw(st.booleans()):
        tokens += ["--format", draw(st.sampled_from(["json", "csv", "text"]))]
    return tokens


def run(args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")             # a warning escaping the table would be output of its own
        status = main(args)
    return status, out.getvalue(), err.getvalue()


def expected_rows(args):
    """The positions a table asks for, by hand: --positions N, or ceil((STOP − START)/STEP) from --angles."""
    values = dict(zip(args[::2], args[1::2])) | dict(zip(args[1::2], args[2::2]))
    if "--angles" in values:
        start, stop, step = (float(v) for v in values["--angles"].split(":"))
        return max(1, math.ceil((stop - start) / step - 1e-9))
    return int(values.get("--positions", 12))


@FUZZ
@given(args=argv())
def test_table_and_structure_take_any_arguments(args):
    status, out, err = run(args)            # an exception escaping main fails the test by itself
    assert "Traceback" not in err and "Traceback" not in out
    assert status in (0, 2), (args, status, err)
    if status == 2:
        assert err.strip(), "a failure says why"
        assert "error: " in err
    else:
        assert out.strip(), "a success prints something"
    if status == 0 and args[0] == "table" and "--help" not in args and "-h" not in args \
            and args[-2:] == ["--format", "json"]:
        assert len(json.loads(out)["rows"]) == expected_rows(args)
