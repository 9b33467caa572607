"""The notation appendix lists every symbol once, with one meaning (issue 19, item 1).

``book/appendix/notation.md`` is the single source of truth for the book's symbols: its tables
(symbol, meaning, unit, chapter …) give each symbol one meaning and the chapter that introduces it.
A symbol cell that appears twice fails, and says whether the two rows give it different meanings.
One exception: the table of the Frenet-frame method (chapter 8) may repeat a symbol of the other
tables with its own meaning, because that chapter keeps the letters of its source, and only while
the appendix says so in that section.
"""

from __future__ import annotations

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
APPENDIX = ROOT / "book" / "appendix" / "notation.md"
KEEPS_ITS_LETTERS = re.compile(r"keeps\s+(the\s+letters\s+of\s+its\s+source|its\s+source's\s+letters)", re.I)


def cells(line: str) -> list[str]:
    """The cells of a Markdown table row; a ``|`` inside ``$…$`` or escaped as ``\\|`` is not a border."""
    out, cell, math = [], "", False
    text = line.strip().strip("|")
    i = 0
    while i < len(text):
        ch = text[i]
        if ch == "\\" and i + 1 < len(text):
            cell += text[i:i + 2]
            i += 2
            continue
        if ch == "$":
            math = not math
        if ch == "|" and not math:
            out.append(cell)
            cell = ""
        else:
            cell += ch
        i += 1
    out.append(cell)
    return [" ".join(c.split()) for c in out]


def sections(text: str) -> list[tuple[str, str, list[dict[str, str]]]]:
    """(title, the prose before its tables, rows as {header: cell}) for every ``##`` section."""
    found = []
    for block in re.split(r"^## ", text, flags=re.M)[1:]:
        title, _, body = block.partition("\n")
        lines = body.splitlines()
        prose, rows, header = [], [], None
        for k, line in enumerate(lines):
            if line.lstrip().startswith("|"):
                row = cells(line)
                if header is None:
                    header = [h.lower() for h in row]
                elif not all(set(c) <= set(":- ") for c in row):
                    rows.append(dict(zip(header, row)))
                continue
            header = None if not line.strip() else header
            if not rows:
                prose.append(line)
        found.append((title.strip(), "\n".join(prose), rows))
    return found


def symbol_rows() -> list[tuple[str, str, dict[str, str]]]:
    """(section title, section prose, row) for every row of every table with a symbol column."""
    return [(title, prose, row) for title, prose, rows in sections(APPENDIX.read_text(encoding="utf8"))
            for row in rows if "symbol" in row]


def test_the_parser_reads_tables():
    # expected by hand: two sections, three rows; a | inside $…$ is part of its cell
    text = ("# Notation\n\n## A\n\n| symbol | meaning | unit | chapter |\n|---|---|---|---|\n"
            "| $x$ | a length | m | 1 |\n| $\\lvert v \\rvert$, $|v|$ | a speed | m/s | 2 |\n\n"
            "## B, which keeps the letters of its source\n\nIt keeps the letters of its source.\n\n"
            "| symbol | meaning |\n|---|---|\n| $x$ | another length |\n")
    (a, _, rows_a), (b, prose_b, rows_b) = sections(text)
    assert [r["symbol"] for r in rows_a] == ["$x$", "$\\lvert v \\rvert$, $|v|$"]
    assert rows_a[1]["meaning"] == "a speed" and rows_a[1]["chapter"] == "2"
    assert rows_b == [{"symbol": "$x$", "meaning": "another length"}]
    assert KEEPS_ITS_LETTERS.search(prose_b)


def test_the_appendix_has_its_tables():
    rows = symbol_rows()
    assert len(rows) >= 40, f"only {len(rows)} symbols in {APPENDIX.relative_to(ROOT)}"
    for title, _, row in rows:
        assert row.get("meaning"), f"§{title}: {row['symbol']} has no meaning"
        if "chapter" in row:
            assert row["chapter"], f"§{title}: {row['symbol']} has no chapter that introduces it"


def test_every_symbol_once():
    seen: dict[str, tuple[str, str, str]] = {}
    problems = []
    for title, prose, row in symbol_rows():
        symbol, meaning = row["symbol"], row["meaning"]
        if symbol not in seen:
            seen[symbol] = (title, prose, meaning)
            continue
        first_title, first_prose, first_meaning = seen[symbol]
        frenet = [t for t, p in ((title, prose), (first_title, first_prose)) if "frenet" in t.lower()]
        if len(frenet) == 1 and title != first_title:
            section_prose = prose if "frenet" in title.lower() else first_prose
            if KEEPS_ITS_LETTERS.search(section_prose):
                continue          # chapter 8 keeps its source's letters, and the appendix says so
        kind = "with different meanings" if meaning != first_meaning else "twice"
        problems.append(f"{symbol} {kind}: §{first_title} ({first_meaning!r}) and §{title} ({meaning!r})")
    assert problems == [], "the notation appendix lists a symbol more than once:\n" + "\n".join(problems)


# --- the package's docstrings and messages speak the book's notation -------------------------------------
# The API pages render the docstrings, and the error messages reach the reader too: a symbol the
# appendix gives one meaning must not appear there with another (issue 19's list: Φ is the constraint
# vector, not an inertia force; α, β are a point's reference coordinates, not an angular acceleration,
# which is ε; K, μ₁ are the time ratio and the transmission angle, not the paper's K_v, γ; angular
# rates are in 1/s). A source's own letter may be named as the source's ("the paper writes … K_v").

SOURCE = ROOT / "mechanisms"
NOT_THE_BOOKS = {
    "rad/s": "angular rates are in 1/s",
    "Φ = −m": "the inertia force is F_in (Φ is the constraint vector)",
    "M_Φ": "the inertia moment is M_in",
    "Q_loads": "the loads' reduced torque is M_red",
    "B1B2": "the rocker's end in the limit positions is B₀, B_x",
    "(iα − ω²)": "the angular acceleration is ε",
    "α = θ_tt": "the angular acceleration is ε",
    "J_S α": "the angular acceleration is ε",
    "sin μ =": "the angle between a link and a line is η (μ is the transmission angle)",
    "ε/δ": "a round-off estimate is ε_mach/Δφ (ε, δ are an acceleration and the speed fluctuation)",
    "J Δx": "Newton's step is Φ_q Δq = −Φ (J is a moment of inertia)",
    "u + iv": "a point of a link is (u + iw) (v is a velocity)",
}
PAPER_NAMES = re.compile(r"\bK_v\b|\bγ\b")          # the synthesis paper's letters for K and μ₁


def test_the_docstrings_and_messages_use_the_books_symbols():
    found = []
    for path in sorted(SOURCE.rglob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            for text, why in NOT_THE_BOOKS.items():
                if text in line:
                    found.append(f"{path.relative_to(ROOT)}:{number}: {text!r}: {why}")
    assert not found, "\n".join(found)


def test_the_synthesis_speaks_of_k_and_mu_naming_the_papers_letters_once():
    text = (SOURCE / "analysis" / "synthesis.py").read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if PAPER_NAMES.search(line)]
    assert len(lines) == 1 and "the paper writes" in lines[0], lines
