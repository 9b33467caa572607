"""Write book/appendix/status.md: each notebook's execution time and the pinned versions.

Run by `make book` before the build, so the page always describes the site it is part of.
Execution times come from tools/notebook_times.json, which tools/run_notebooks.py updates
whenever it executes a notebook (the time it took then, on the machine it ran on).
"""

import json
import pathlib
import platform
import re
import tomllib
from importlib import metadata

ROOT = pathlib.Path(__file__).resolve().parent.parent
TIMES = ROOT / "tools" / "notebook_times.json"
PAGE = ROOT / "book" / "appendix" / "status.md"


def pinned() -> list[tuple[str, str, str]]:
    """(extra, package, pinned version) for every `==` pin in pyproject.toml's extras."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    rows = []
    for extra, requirements in project["optional-dependencies"].items():
        for requirement in requirements:
            match = re.fullmatch(r"([A-Za-z0-9_.\-]+)==(\S+)", requirement)
            if match:
                rows.append((extra, match.group(1), match.group(2)))
    return rows


def main() -> None:
    times = json.loads(TIMES.read_text()) if TIMES.exists() else {}
    lines = ["# Status of the book", "",
             "This page is for readers who run the book's notebooks themselves, and for teachers who",
             "install it for a course: how long each notebook takes and which versions of the tools",
             "the book was checked with. Nothing in it is needed to follow the chapters.", "",
             "Every chapter and exercise notebook is executed ahead of time and stored with its outputs;",
             "`make test` re-executes each one and compares the outputs (nbval, strict). The times below",
             "are those of the last execution by `tools/run_notebooks.py`.", "",
             "## Notebooks", "", "| notebook | execution time, s | executed on |", "|:---|---:|:---|"]
    for name in sorted(times):
        entry = times[name]
        lines.append(f"| `{name}` | {entry['seconds']:.1f} | {entry['machine']} |")
    total = sum(e["seconds"] for e in times.values())
    lines += ["", f"In all {len(times)} notebooks, {total:.0f} s.", "",
              "## Pinned versions", "",
              "The versions the book was built and tested with (the extras of `pyproject.toml`).", "",
              "| extra | package | pinned | installed here |", "|:---|:---|:---|:---|"]
    for extra, package, version in pinned():
        try:
            installed = metadata.version(package)
        except metadata.PackageNotFoundError:
            installed = "not installed"
        lines.append(f"| {extra} | `{package}` | {version} | {installed} |")
    lines += ["", f"Site built with Python {platform.python_version()}.", ""]
    PAGE.write_text("\n".join(lines), encoding="utf-8")


if __name__ == "__main__":
    main()
