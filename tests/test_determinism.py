"""Re-executing the notebooks changes no stored output byte (issue 17).

Every re-execution that changes an output (a PNG re-encoded with a new date, an animation with new
random ids, a memory address) commits new bytes that every clone downloads forever. Two tests:

* ``test_no_output_holds_what_changes_from_run_to_run`` (fast, static): no committed output holds a
  known non-deterministic pattern: jshtml animations (``anim_`` + random hex), a PNG text chunk or
  ``tIME`` chunk with a date, an SVG ``<dc:date>``, a memory address ``at 0x…``, a timestamp, a random
  UUID or temporary path, widget model ids, execution-timing metadata of a cell.
* the comparison on re-execution, without a second run: ``tests/conftest.py`` hooks nbval's own
  execution of every cell (``make test`` re-executes every notebook under nbval) and compares every
  output it produced (stream text, ``text/plain``, ``text/html``, ``text/markdown``, ``image/png`` …
  and their metadata) with the committed one, exactly (:func:`nbval_cell_changes`). Comparing with
  what the previous execution stored is the same test as "execute twice in a row": the committed
  outputs are the first run (``make notebooks`` stores them), nbval's is the second. The message
  names the notebook, the cell (number and first line), the output and what changed in it.

Cells tagged ``nbval-ignore-output`` (the measured times of chapter 9) are not compared: they change
by nature. They must hold short text only (no image, no HTML, at most 2 kB), so what they add to the
history is small; ``nbval-skip`` cells are not executed by nbval and not compared here either.

The notebooks are compared on the machine that stored them: PNG bytes depend on matplotlib, FreeType
and the fonts, so a machine with other versions re-renders them differently (then re-execute with
``make notebooks`` there, which is what this test guards).
"""

from __future__ import annotations

import base64
import difflib
import json
import pathlib
import re
import struct
import zlib

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
IGNORED_TAGS = {"nbval-ignore-output", "nbval-skip"}
IGNORED_OUTPUT_LIMIT = 2_000        # bytes of text an ignored cell may print


def notebooks() -> list[pathlib.Path]:
    return sorted(p for folder in ("book", "exercises") for p in (ROOT / folder).rglob("*.ipynb")
                  if ".ipynb_checkpoints" not in p.parts)


def relative(path: pathlib.Path) -> str:
    return path.relative_to(ROOT).as_posix()


def tags(cell) -> set[str]:
    return set(cell.get("metadata", {}).get("tags", []))


def where(name: str, index: int, cell) -> str:
    first = (cell.source.strip().splitlines() or [""])[0][:70]
    return f"{name}, cell {index} ({first!r})"


def describe(output) -> str:
    kind = output.get("output_type", "?")
    return f"{kind} {output.get('name', '')}".strip() if kind == "stream" else kind


# --- what changes from run to run, found in the stored outputs --------------------------------------------

TEXT_PATTERNS = {
    "a jshtml animation (random anim_ ids)": re.compile(r"anim_[0-9a-f]{16,}|class=\"animation\""),
    "a memory address": re.compile(r"\bat 0x[0-9a-fA-F]{4,}"),
    "a timestamp": re.compile(r"\b(19|20)\d\d-[01]\d-[0-3]\d[T ][0-2]\d:[0-5]\d"),
    "an SVG date": re.compile(r"<dc:date>|CreationDate|ModDate"),
    "a random UUID": re.compile(r"\b[0-9a-f]{8}-[0-9a-f]{4}-[1-5][0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}\b"),
    "a temporary path": re.compile(r"/tmp/tmp[\w-]{6,}|\\Temp\\tmp\w{6,}|/var/folders/"),
}
# Patterns that are stable where they are: (notebook, text in the cell's source) → what it may print, each with
# its reason.
STABLE = {
    # the date of the stored benchmark result that the cell reads (bench-result.json), not of the run
    ("book/09-speed.ipynb", 'open("bench-result.json")'): ("a timestamp",),
}
VOLATILE_MIME = {"application/vnd.jupyter.widget-view+json", "application/vnd.jupyter.widget-state+json"}


def png_chunks(data: bytes) -> list[tuple[bytes, bytes]]:
    """(type, content) of every chunk of a PNG file."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    chunks, at = [], 8
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunks.append((kind, data[at + 8:at + 8 + length]))
        at += 12 + length
    return chunks


def png_text(data: bytes) -> dict[str, str]:
    """The text chunks of a PNG (tEXt, zTXt, iTXt) as key → value, and tIME as 'tIME'."""
    found = {}
    for kind, content in png_chunks(data):
        if kind == b"tEXt":
            key, _, value = content.partition(b"\0")
            found[key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"zTXt":
            key, _, rest = content.partition(b"\0")
            found[key.decode("latin-1")] = zlib.decompress(rest[1:]).decode("latin-1")
        elif kind == b"iTXt":
            key, _, rest = content.partition(b"\0")
            flag, rest = rest[0], rest[2:]
            _, _, rest = rest.partition(b"\0")          # language tag
            _, _, text = rest.partition(b"\0")          # translated keyword
            found[key.decode("utf8")] = (zlib.decompress(text) if flag else text).decode("utf8")
        elif kind == b"tIME":
            found["tIME"] = content.hex()
    return found


def volatile(output) -> list[tuple[str, str]]:
    """What in one stored output changes from run to run: (kind of pattern, where)."""
    found = []
    texts = [("text", output.get("text", ""))] if output.get("output_type") == "stream" else []
    for mime, value in output.get("data", {}).items():
        if mime in VOLATILE_MIME:
            found.append(("random model ids", mime))
        elif mime == "image/png":
            chunks = png_text(base64.b64decode(value))
            dated = {k: v for k, v in chunks.items() if k == "tIME" or re.search(r"date|time", k, re.I)
                     or TEXT_PATTERNS["a timestamp"].search(v)}
            if dated:
                found.append(("a PNG date", f"image/png: {dated}"))
        elif isinstance(value, str):
            texts.append((mime, value))
    for mime, text in texts:
        for what, pattern in TEXT_PATTERNS.items():
            hit = pattern.search(text)
            if hit:
                found.append((what, f"{mime}: …{text[max(0, hit.start() - 30):hit.end() + 30]!r}…"))
    return found


def test_the_png_reader_finds_dates():
    # a PNG made here with a tEXt date and a tIME chunk: both found; matplotlib's Software key is not a date
    def chunk(kind, content):
        return struct.pack(">I", len(content)) + kind + content + struct.pack(">I", zlib.crc32(kind + content))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0))
           + chunk(b"tEXt", b"Software\0Matplotlib version3.10") + chunk(b"tEXt", b"Creation Time\x002024-05-01 10:00")
           + chunk(b"tIME", bytes(7)) + chunk(b"IEND", b""))
    found = png_text(png)
    assert found["Software"] == "Matplotlib version3.10" and "Creation Time" in found and "tIME" in found
    output = nbformat.v4.new_output("display_data", data={"image/png": base64.b64encode(png).decode()})
    assert len(volatile(output)) == 1 and "Creation Time" in volatile(output)[0][1]
    clean = nbformat.v4.new_output("stream", name="stdout", text="φ = 30°, s = 0.4494 m\n")
    assert volatile(clean) == []
    dirty = nbformat.v4.new_output("execute_result", data={"text/plain": "<Foo at 0x7f3a2b1c>"}, execution_count=1)
    assert volatile(dirty)[0][0] == "a memory address"


def test_no_output_holds_what_changes_from_run_to_run():
    problems = []
    for path in notebooks():
        nb = nbformat.read(path, as_version=4)
        for index, cell in enumerate(nb.cells):
            if cell.cell_type != "code":
                continue
            timing = cell.get("metadata", {}).get("execution")
            if timing:
                problems.append(f"{where(relative(path), index, cell)}: execution-timing metadata {dict(timing)}")
            allowed = {what for (name, source), whats in STABLE.items() for what in whats
                       if name == relative(path) and source in cell.source}
            for k, output in enumerate(cell.get("outputs", [])):
                problems += [f"{where(relative(path), index, cell)}, output {k} ({describe(output)}): {what}: {detail}"
                             for what, detail in volatile(output) if what not in allowed]
            if tags(cell) & IGNORED_TAGS:
                size = sum(len(json.dumps(o, ensure_ascii=False).encode()) for o in cell.get("outputs", []))
                kinds = {m for o in cell.get("outputs", []) for m in o.get("data", {})
                         if m not in ("text/plain", "text/markdown")}
                if kinds or size > IGNORED_OUTPUT_LIMIT:
                    problems.append(f"{where(relative(path), index, cell)}: its outputs are not compared "
                                    f"(nbval-ignore-output) but hold {sorted(kinds) or f'{size} bytes'}: "
                                    "an ignored cell may print short text only")
    assert problems == [], "stored outputs that change from run to run:\n" + "\n".join(problems)


# --- executing once more --------------------------------------------------------------------------------------

def difference(old, new) -> str:
    """Where two values of an output differ, briefly."""
    if isinstance(old, str) and isinstance(new, str):
        if len(old) > 2000 or len(new) > 2000:
            at = next((k for k, (a, b) in enumerate(zip(old, new)) if a != b), min(len(old), len(new)))
            return f"{len(old)} → {len(new)} characters, first difference at character {at}"
        lines = list(difflib.unified_diff(old.splitlines(), new.splitlines(), "stored", "now", n=0, lineterm=""))
        return "\n      " + "\n      ".join(lines[:12])
    return f"{old!r:.200} → {new!r:.200}"


def changed_outputs(name: str, stored_cells, executed_cells) -> list[str]:
    """Every difference between the stored and the re-executed outputs of the code cells (ignored cells
    apart), one line each, naming the notebook, the cell, the output and what changed."""
    problems = []
    for index, (old, new) in enumerate(zip(stored_cells, executed_cells)):
        if old.cell_type != "code" or tags(old) & IGNORED_TAGS:
            continue
        here = where(name, index, old)
        if old.get("execution_count") != new.get("execution_count"):
            problems.append(f"{here}: execution count {old.get('execution_count')} → {new.get('execution_count')}")
        if [describe(o) for o in old.outputs] != [describe(o) for o in new.outputs]:
            problems.append(f"{here}: outputs {[describe(o) for o in old.outputs]} → {[describe(o) for o in new.outputs]}")
            continue
        for k, (a, b) in enumerate(zip(old.outputs, new.outputs)):
            label = f"{here}, output {k} ({describe(a)})"
            for key in sorted(set(a) | set(b)):
                if key in ("data", "metadata") and isinstance(a.get(key, {}), dict):
                    for mime in sorted(set(a.get(key, {})) | set(b.get(key, {}))):
                        if a.get(key, {}).get(mime) != b.get(key, {}).get(mime):
                            what = mime if key == "data" else f"metadata {mime}"
                            problems.append(f"{label}: {what} changed: "
                                            f"{difference(a.get(key, {}).get(mime), b.get(key, {}).get(mime))}")
                elif a.get(key) != b.get(key):
                    problems.append(f"{label}: {key} changed: {difference(a.get(key), b.get(key))}")
    return problems


def test_changed_outputs_names_notebook_cell_and_output_type():
    stored = [nbformat.v4.new_code_cell("plot()", execution_count=1, outputs=[
        nbformat.v4.new_output("stream", name="stdout", text="s = 0.4494 m\n"),
        nbformat.v4.new_output("display_data", data={"image/png": "iVBORw0KGgoAAAA", "text/plain": "<Figure>"})]),
        nbformat.v4.new_code_cell("time()", execution_count=2, metadata={"tags": ["nbval-ignore-output"]},
                                  outputs=[nbformat.v4.new_output("stream", name="stdout", text="1.2 ms\n")])]
    same = [nbformat.from_dict(c) for c in stored]
    assert changed_outputs("book/x.ipynb", stored, same) == []
    changed = [nbformat.from_dict(c) for c in stored]
    changed[0].outputs[1].data["image/png"] = "iVBORw0KGgoBBBB"
    changed[0].outputs[0].text = "s = 0.4495 m\n"
    changed[1].outputs[0].text = "1.3 ms\n"            # an ignored cell: not compared
    problems = changed_outputs("book/x.ipynb", stored, changed)
    assert len(problems) == 2
    assert problems[0].startswith("book/x.ipynb, cell 0 ('plot()'), output 0 (stream stdout): text changed")
    assert problems[1].startswith("book/x.ipynb, cell 0 ('plot()'), output 1 (display_data): image/png changed")


def nbval_cell_changes(item) -> list[str]:
    """The same comparison on nbval's own execution of one cell (``item``, an nbval cell item, after its
    ``runtest``), for a conftest hook that spares the second execution::

        @pytest.hookimpl(hookwrapper=True)
        def pytest_runtest_call(item):
            yield
            if type(item).__name__ == "IPyNbCell":
                from test_determinism import nbval_cell_changes
                problems = nbval_cell_changes(item)
                assert problems == [], "re-executing changes stored outputs:\n" + "\n".join(problems)

    nbval gathers a cell's streams of one name into one output and its kernel's execution counts skip
    ``nbval-skip`` cells, so streams are gathered alike on the stored side and counts are not compared.
    """
    from nbval.plugin import coalesce_streams

    outputs = getattr(item, "test_outputs", None)
    if outputs is None or tags(item.cell) & IGNORED_TAGS or item.cell.get("execution_count") is None:
        return []

    def gathered(cell_outputs):
        copies = [nbformat.from_dict({k: None if k == "execution_count" else v for k, v in o.items()})
                  for o in cell_outputs]
        return coalesce_streams(copies)

    stored = nbformat.v4.new_code_cell(item.cell.source, outputs=gathered(item.cell.outputs))
    now = nbformat.v4.new_code_cell(item.cell.source, outputs=gathered(outputs))
    name = pathlib.Path(str(item.fspath)).resolve()
    name = relative(name) if ROOT in name.parents else name.name
    return [p.replace(", cell 0 ", f", cell {item.cell_num} ", 1)
            for p in changed_outputs(name, [stored], [now])]
