"""Start-up of the package (issue 20): ``import mechanisms`` imports nothing heavy, names load when first
used, and the benchmark's start-up section (``python -m mechanisms bench --only startup``) reports the times.

No test here times anything against a target: the benchmark reports the times, the tests check behaviour.
"""

from __future__ import annotations

import json
import subprocess
import sys

from mechanisms.bench.startup import StartupCommand, format_startup_text, startup_times
from mechanisms.cli import main


def _modules_after(code: str) -> set[str]:
    out = subprocess.run([sys.executable, "-c", code + "; import sys; print(' '.join(sys.modules))"],
                         capture_output=True, text=True, check=True).stdout
    return set(out.split())


def test_import_mechanisms_imports_neither_numpy_nor_matplotlib():
    modules = _modules_after("import mechanisms")
    assert not {m for m in modules if m.split(".")[0] in ("numpy", "matplotlib")}
    assert {m for m in modules if m.startswith("mechanisms")} == {"mechanisms"}


def test_a_name_imports_its_module_when_first_used():
    modules = _modules_after("import mechanisms; mechanisms.CrankSlider; mechanisms.Motion")
    assert {"numpy", "mechanisms.linkages.crank_slider", "mechanisms.core.motion"} <= modules
    assert "matplotlib" not in modules and "mechanisms.verify" not in modules


def test_the_table_command_imports_no_plotting_and_no_course_tools():
    modules = _modules_after("import sys; sys.argv = ['mechanisms', 'table', 'crank-slider', '--crank', '0.08', "
                             "'--rod', '0.3', '--omega', '215', '--positions', '12']; import mechanisms.cli as c; "
                             "c.main()")
    assert not {m for m in modules if m.split(".")[0] == "matplotlib" or m.startswith("mechanisms.course.assign")
                or m.startswith("mechanisms.analysis")}


def test_startup_times_report_best_median_and_target():
    commands = (StartupCommand("empty", ("-c", "pass"), 60.0), StartupCommand("reference", ("-c", "pass")))
    report = startup_times(repeat=2, commands=commands)
    first, second = report["results"]
    assert first["name"] == "empty" and first["command"] == "python -c pass" and first["runs"] == 2
    assert 0 < first["best"] <= first["median"] and first["met"] is True    # nothing takes a minute
    assert second["target"] is None and second["met"] is None
    text = format_startup_text(report)
    assert "empty" in text and "yes" in text and "60000" in text


def test_bench_command_only_startup_as_json(capsys):
    assert main(["bench", "--only", "startup", "--repeat", "1", "--format", "json"]) == 0
    report = json.loads(capsys.readouterr().out)
    names = [r["name"] for r in report["startup"]["results"]]
    assert names[2:] == ["import mechanisms", "import mechanisms; first use", "table crank-slider, 12 positions"]
    assert [r["target"] for r in report["startup"]["results"]][2::2] == [0.15, 0.3]   # issue 20's targets
    assert "results" not in report      # the methods were not run
