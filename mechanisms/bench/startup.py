"""How long the package and its command line take to start: wall time of fresh interpreters.

``python -m mechanisms bench`` reports it beside the solvers' times (``--only startup`` alone). Each
command runs in a new interpreter (:func:`subprocess.run`), once to warm the caches (the bytecode of
every module imported), then ``repeat`` times; the report gives the best and the median wall time and
the target of each. A bare interpreter and ``import numpy`` are measured as what no change in this
package can go below.

Where the environment disables writing bytecode (``PYTHONDONTWRITEBYTECODE``), the runs keep theirs in
a temporary folder (``PYTHONPYCACHEPREFIX``), as an installed package would have it, and the report
says so.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from typing import Sequence

__all__ = ["StartupCommand", "STARTUP_COMMANDS", "startup_times", "format_startup_text"]


@dataclass(frozen=True)
class StartupCommand:
    """A command timed in a fresh interpreter.

    Attributes
    ----------
    name : str
        What it is, as the report prints it.
    arguments : tuple of str
        The interpreter's arguments (``("-c", "import mechanisms")``).
    target : float or None
        The wall time (s) it should not exceed; None for a reference that is not this package's.
    """

    name: str
    arguments: tuple[str, ...]
    target: float | None = None


TABLE_ARGUMENTS = ("-m", "mechanisms", "table", "crank-slider", "--crank", "0.08", "--rod", "0.3", "--omega", "215",
                   "--positions", "12")

STARTUP_COMMANDS: tuple[StartupCommand, ...] = (
    StartupCommand("python (nothing imported)", ("-c", "pass")),
    StartupCommand("import numpy", ("-c", "import numpy")),
    StartupCommand("import mechanisms", ("-c", "import mechanisms"), 0.15),
    StartupCommand("import mechanisms; first use", ("-c", "import mechanisms; mechanisms.CrankSlider")),
    StartupCommand("table crank-slider, 12 positions", TABLE_ARGUMENTS, 0.3),
)
"""What is timed: the issue's two targets (``import mechanisms`` ≤ 0.15 s, a 12-row table ≤ 0.3 s) and the
references beside them (an empty interpreter, numpy, the first use of a name, which imports numpy and the
mechanisms)."""


@dataclass(frozen=True)
class StartupTime:
    """The wall times of one command (s)."""

    name: str
    command: str
    best: float
    median: float
    runs: int
    target: float | None

    @property
    def met(self) -> bool | None:
        """Whether the best time is within the target (None: no target)."""
        return None if self.target is None else self.best <= self.target


def _environment(folder: str) -> tuple[dict[str, str], str]:
    environ = dict(os.environ)
    note = ""
    if environ.pop("PYTHONDONTWRITEBYTECODE", None) is not None or sys.flags.dont_write_bytecode:
        environ["PYTHONPYCACHEPREFIX"] = folder
        note = ("bytecode kept in a temporary folder for these runs (PYTHONDONTWRITEBYTECODE is set here; an "
                "installed package has its bytecode)")
    return environ, note


def _wall_time(arguments: Sequence[str], environ: dict[str, str]) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, *arguments], env=environ, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.PIPE)
    return time.perf_counter() - start


def startup_times(repeat: int = 5, commands: Sequence[StartupCommand] = STARTUP_COMMANDS) -> dict:
    """Time each command in fresh interpreters: a warm-up run, then the best and median of ``repeat`` runs.

    Parameters
    ----------
    repeat : int
        Timed runs per command (at least 1), after one warm-up run.
    commands : sequence of StartupCommand
        What to time (default :data:`STARTUP_COMMANDS`).

    Returns
    -------
    dict
        ``{"python": sys.executable, "notes": [...], "results": [{"name", "command", "best", "median", "runs",
        "target", "met"}, ...]}``, times in seconds.

    Raises
    ------
    subprocess.CalledProcessError
        If a command fails (its standard error is attached).
    """
    repeat = max(1, int(repeat))
    results = []
    with tempfile.TemporaryDirectory(prefix="mechanisms-startup-") as folder:
        environ, note = _environment(folder)
        for command in commands:
            _wall_time(command.arguments, environ)          # warm-up: bytecode, file-system caches
            times = [_wall_time(command.arguments, environ) for _ in range(repeat)]
            entry = StartupTime(command.name, "python " + " ".join(command.arguments), min(times),
                                statistics.median(times), repeat, command.target)
            results.append(asdict(entry) | {"met": entry.met})
    return {"python": sys.executable, "notes": [note] if note else [], "results": results}


def format_startup_text(report: dict) -> str:
    """The start-up times as a plain-text table (milliseconds), with each target and whether it is met."""
    lines = [f"start-up: wall time of a fresh interpreter ({report['python']}), best and median of "
             f"{report['results'][0]['runs'] if report['results'] else 0} runs after a warm-up"]
    lines += [f"note: {note}" for note in report["notes"]]
    lines += ["", f"{'command':<36}{'best, ms':>10}{'median, ms':>12}{'target, ms':>12}  met"]
    for r in report["results"]:
        target = "—" if r["target"] is None else f"{1000 * r['target']:.0f}"
        met = "" if r["met"] is None else ("yes" if r["met"] else "NO")
        lines.append(f"{r['name']:<36}{1000 * r['best']:>10.0f}{1000 * r['median']:>12.0f}{target:>12}  {met}")
    return "\n".join(lines)
