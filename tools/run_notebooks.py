"""Execute notebooks in place and store their outputs, as nbval will compare them.

Usage: python tools/run_notebooks.py [NOTEBOOK ...]   (default: every notebook in book/ and exercises/)

A notebook may be written as a MyST/percent text file and paired with jupytext; this script
executes the .ipynb with the ``python3`` kernel, without timing metadata, so outputs are stable.
"""

import json
import pathlib
import platform
import sys
import time

import nbformat
from nbclient import NotebookClient

ROOT = pathlib.Path(__file__).resolve().parent.parent
TIMES = ROOT / "tools" / "notebook_times.json"


def joined_streams(outputs: list) -> list:
    """Consecutive outputs of one stream (stdout, stderr) joined into one: how a slow cell's printing
    arrives in chunks depends on timing, so the stored form must not (nbval joins them alike)."""
    joined: list = []
    for output in outputs:
        previous = joined[-1] if joined else None
        if (output.get("output_type") == "stream" and previous is not None
                and previous.get("output_type") == "stream" and previous.get("name") == output.get("name")):
            previous["text"] = previous["text"] + output["text"]
        else:
            joined.append(output)
    return joined


def run(path: pathlib.Path) -> float:
    nb = nbformat.read(path, as_version=4)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    start = time.perf_counter()
    NotebookClient(nb, kernel_name="python3", timeout=600, record_timing=False,
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    for index, cell in enumerate(nb.cells):
        cell.metadata.pop("execution", None)
        if cell.cell_type == "code":
            cell.outputs = joined_streams(cell.outputs)
            # an error raised while a figure is displayed (IPython's formatters, e.g. bad mathtext in a
            # label) becomes an error output without failing the cell: never store one
            errors = [o for o in cell.outputs if o.get("output_type") == "error"]
            if errors:
                sys.exit(f"{path}: cell {index} stored an error output, {errors[0].get('ename')}: "
                         f"{errors[0].get('evalue', '')[:200]} (the notebook was not written)")
    nbformat.write(nb, path)
    return time.perf_counter() - start


def main(args: list[str]) -> None:
    paths = [pathlib.Path(a) for a in args] or sorted(
        p for d in ("book", "exercises") for p in (ROOT / d).rglob("*.ipynb") if ".ipynb_checkpoints" not in p.parts)
    for path in paths:
        seconds = run(path)
        print(f"{path}: {seconds:.1f} s", flush=True)
        times = json.loads(TIMES.read_text()) if TIMES.exists() else {}
        times[path.resolve().relative_to(ROOT).as_posix()] = {
            "seconds": round(seconds, 2), "machine": f"{platform.machine()}, {platform.python_version()}"}
        TIMES.write_text(json.dumps(times, indent=1, sort_keys=True) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
