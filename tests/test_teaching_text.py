"""The teaching text speaks of mechanisms, not of the package (issue 31, the lead's decision 1).

Package matters live in one place per section, a collapsed aside at the section's end::

    :::{admonition} In the package
    :class: dropdown
    ...
    :::

Everywhere else, the prose of the chapters, the exercises and the appendices a student reads does
not name the package's identifiers (``mech.…``, ``keep_side``, ``Solution``, ``nan``, ``order=2``),
test names, pytest or nbval, "the package", "the tests", nor says how a figure was made ("its code
folded", "drawn 0.6 m below the pivots"). Code cells, plain code blocks, the asides and the API pages
(``book/appendix/api*.md``, ``speed.md``, ``status.md``) are exempt: code and its comments are the
package's own place.

The second part checks that every bibliography entry names its author, title and year, or says in
its note which of them its source does not give (issue 31, item 6).
"""

from __future__ import annotations

import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
# the API pages (and every api-*.md), the engineering appendices, and the teacher's page on the
# command-line tool that makes and grades assignments: their subject is the package itself
EXEMPT_PAGES = {"api.md", "speed.md", "status.md", "course.md"}


def teaching_pages() -> list[pathlib.Path]:
    pages = sorted((ROOT / "book").glob("*.md")) + sorted((ROOT / "exercises").glob("*.md"))
    pages += sorted((ROOT / "book" / "appendix").glob("*.md"))
    return [p for p in pages if p.name not in EXEMPT_PAGES and not p.name.startswith("api-")]


# The package's vocabulary. Each pattern is matched against one line of prose from which the
# exempt parts (code, math, roles' targets, comments) are removed; each is narrow enough that
# ordinary English about mechanisms does not match it (see the self-tests below).
VOCABULARY: dict[str, re.Pattern[str]] = {
    "the package's module name (mech. / mechanisms.)": re.compile(r"\bmech(?:anisms)?\.[A-Za-z_]"),
    "an identifier with an underscore in backticks": re.compile(r"`[^`\s]*[A-Za-z0-9]_[A-Za-z0-9][^`]*`"),
    "a call or keyword argument in backticks": re.compile(r"`[A-Za-z_][\w.]*(?:\(|=)[^`]*`"),
    "an attribute in backticks (name.name)": re.compile(r"`[A-Za-z_]\w*\.[A-Za-z_][\w.]*`"),
    "a class, error or warning of the package": re.compile(
        r"`[A-Z][a-z]+(?:[A-Z][a-z0-9]*)+`|\b[A-Z][a-z]+(?:[A-Z][a-z]+)*(?:Error|Warning)\b|`Solution`"),
    "nan or inf as a value": re.compile(r"\bnan\b|\bNaN\b|`inf`|`None`|`True`|`False`"),
    "a test, pytest or nbval": re.compile(r"\bpytest\b|\bnbval\b|\btest_\w+|::\w|\btests/"),
    "'the package' or 'the tests'": re.compile(
        r"\b(?:the|this|its|our) package\b|\bthe package's\b|\b(?:the|its|our) tests\b"
        r"|\bre-execut", re.IGNORECASE),
    "how a cell or figure was made": re.compile(
        r"\b(?:code|cell)s?\b[^.;]{0,40}\bfolded\b|\bfolded\b[^.;]{0,20}\b(?:code|cell)s?\b"
        r"|\bhide-input\b|\bdrawn \d[\d.]* ?m (?:to the|below|above)\b"
        r"|\bturned along its own line\b", re.IGNORECASE),
    "a keyword argument, docstring or flag": re.compile(r"\bkeyword arguments?\b|\bdocstrings?\b"),
}

FENCE = re.compile(r"^\s*(`{3,}|:{3,})\s*(\{[^}]*\})?\s*(.*)$")
ASIDE_TITLE = "In the package"


def prose_lines(text: str) -> list[tuple[int, str]]:
    """The lines of a MyST page a student reads as prose, with their numbers (1-based).

    Dropped: the YAML header, code cells and code blocks, display math, directive options, HTML
    comments and the *In the package* asides (with everything nested in them).
    """
    lines = text.splitlines()
    out: list[tuple[int, str]] = []
    start = 0
    if lines and lines[0].strip() == "---":           # front matter
        end = next((k for k in range(1, len(lines)) if lines[k].strip() == "---"), 0)
        start = end + 1
    stack: list[tuple[str, bool]] = []                  # open fences: (marker, exempt)
    in_math = in_comment = False
    for k in range(start, len(lines)):
        line = lines[k]
        stripped = line.strip()
        if in_comment:
            in_comment = "-->" not in line
            continue
        if stripped.startswith("<!--"):
            in_comment = "-->" not in stripped
            continue
        match = FENCE.match(line)
        if match:
            marker, directive, rest = match.groups()
            if stack and marker == stack[-1][0] and directive is None and not rest:
                stack.pop()                              # closes the innermost fence
                continue
            if directive is not None or marker.startswith("`"):
                exempt = (marker.startswith("`") and (directive is None or "code" in directive
                                                      or directive in ("{math}",)))
                exempt |= directive == "{admonition}" and rest.strip() == ASIDE_TITLE
                exempt = exempt or (bool(stack) and stack[-1][1])
                stack.append((marker, exempt))
                if not exempt and rest.strip():          # a directive's title is read as prose
                    out.append((k + 1, rest))
                continue
        if stack and stack[-1][1]:
            continue
        if in_math:                                      # display math ends at the next $$
            in_math = "$$" not in stripped
            continue
        if stripped.startswith("$$"):
            in_math = stripped == "$$" or "$$" not in stripped[2:]
            continue
        if re.match(r"^\s*:[\w-]+:", line):              # a directive's option
            continue
        out.append((k + 1, line))
    return out


def clean(line: str) -> str:
    """A prose line without its math, roles and their targets, links' targets and labels."""
    line = re.sub(r"\$[^$]*\$", " ", line)                   # inline math
    line = re.sub(r"\{[\w:-]+\}`[^`]*`", " ", line)          # {term}`…`, {ref}`…`, {doc}`…`
    line = re.sub(r"\]\([^)]*\)", "]", line)                # [text](target)
    line = re.sub(r"^\s*\([\w-]+\)=\s*$", " ", line)        # (label)=
    return line


def hits(page: pathlib.Path) -> list[str]:
    found = []
    for number, line in prose_lines(page.read_text(encoding="utf8")):
        text = clean(line)
        for reason, pattern in VOCABULARY.items():
            match = pattern.search(text)
            if match:
                found.append(f"{page.relative_to(ROOT)}:{number}: {reason}: {match.group(0)!r}")
    return found


def test_there_are_teaching_pages():
    names = {p.name for p in teaching_pages()}
    # expected: the chapters, their exercises and the appendices a student reads, no API page
    assert {"09-speed.md", "errata.md", "glossary.md", "notation.md"} <= names
    assert not names & {"api.md", "api-core.md", "speed.md", "status.md", "course.md"}


@pytest.mark.parametrize("page", teaching_pages(), ids=lambda p: str(p.relative_to(ROOT)))
def test_the_teaching_text_does_not_speak_of_the_package(page):
    found = hits(page)
    assert not found, (
        f"{len(found)} place(s) where the teaching text names the package's matters; move each into "
        "the section's ':::{admonition} In the package' aside (decision 1 of issue 31), or say it "
        "in the student's words:\n" + "\n".join(found))


# --- self-tests: the patterns catch the issue's examples and leave ordinary English alone ---------

ISSUE_EXAMPLES = [
    "The rule of the package is `keep_side=True`.",
    "It returns `nan` for the rates.",
    "The flag `Solution.singular` says so.",
    "the cell that draws it is folded",
    "The figure's code is folded; its time axis is marked.",
    "drawn 0.6 m to the right of the guide",
    "each box turned along its own line",
    "Test: `tests/test_motion.py::test_rocker_acceleration_erratum`",
    "the tests re-execute and compare with what you read",
    "call `mech.plot.draw(m, sol)` to see it",
    "solve it with `order=2`",
    "it raises an AssemblyError there",
    "nbval compares the outputs",
]

ORDINARY_ENGLISH = [
    "The coupler and the rocker fold onto the line $OC$: the folded limit position.",
    "The four-bar is one of the simplest plane mechanisms.",
    "Crank, coupler and rocker are the links of these mechanisms. Then the slider moves.",
    "The stretched and the folded positions bound the swing of the rocker.",
    "Each exercise ends with its short answer, folded under *Answer*.",
    "The angle $\\psi_{tt}$ of {term}`singular position <singular position>` is (see {ref}`eq-a_b`).",
    "Newton's method tests whether the step is small; the checks of §2.5 test the result.",
    "A solution of the constraint equations is a position of the linkage.",
    "the time ratio $K = 1.5$ and the angle $\\mu_1$",
]


@pytest.mark.parametrize("sentence", ISSUE_EXAMPLES)
def test_the_vocabulary_catches_the_issues_examples(sentence):
    # expected: each sentence quoted (or paraphrased) in issue 31, item 1, is caught
    text = clean(sentence)
    assert any(p.search(text) for p in VOCABULARY.values()), sentence


@pytest.mark.parametrize("sentence", ORDINARY_ENGLISH)
def test_the_vocabulary_leaves_ordinary_english_alone(sentence):
    # expected: sentences about mechanisms, written for students, are not caught
    text = clean(sentence)
    assert not [r for r, p in VOCABULARY.items() if p.search(text)], sentence


def test_prose_lines_skip_code_asides_math_and_options(tmp_path):
    page = "\n".join([
        "---", "jupytext: {}", "---",                    # 1-3: front matter
        "Prose one.",                                    # 4
        "```{code-cell} ipython3", "mech.plot(`nan`)", "```",   # 5-7
        ":::{admonition} In the package", ":class: dropdown",   # 8-9
        "`keep_side=True` and `nan`.", ":::",            # 10-11
        "$$", "x_t = `nan`", "$$",                       # 12-14
        ":::{exercise} A title", ":label: ex-a_b",       # 15-16
        "Prose two.", ":::",                             # 17-18
        "<!-- test_x -->",                               # 19
        "$$h_t = `nan`,", "h_tt = 0.$$",                 # 20-21: display math closed on its last line
        "Prose three.",                                  # 22
    ])
    # expected, by reading the page above: the three prose lines and the exercise's title (line 15)
    assert [n for n, _ in prose_lines(page)] == [4, 15, 17, 22]


# --- the bibliography (issue 31, item 6) ----------------------------------------------------------

BIB = ROOT / "book" / "references.bib"
ENTRY = re.compile(r"@(\w+)\s*\{\s*([^,\s]+)\s*,(.*?)\n\}", re.S)
FIELD = re.compile(r"^\s*(\w+)\s*=", re.M)


def bib_entries() -> dict[str, tuple[str, dict[str, str]]]:
    entries = {}
    for kind, key, body in ENTRY.findall(BIB.read_text(encoding="utf8")):
        fields = {}
        names = list(FIELD.finditer(body))
        for i, name in enumerate(names):
            end = names[i + 1].start() if i + 1 < len(names) else len(body)
            fields[name.group(1).lower()] = " ".join(body[name.end():end].split()).rstrip(",")
        entries[key] = (kind.lower(), fields)
    return entries


def test_the_bibliography_has_entries():
    # expected: the four sources and the further-reading books (bibliography.md names them)
    keys = set(bib_entries())
    assert {"alyushin2008", "pylypaka2019", "zaitsev_synthesis", "tmm_textbook_p31"} <= keys
    assert len(keys) >= 13


@pytest.mark.parametrize("key", sorted(bib_entries()))
def test_every_entry_gives_author_title_and_year_or_says_which_is_not_given(key):
    kind, fields = bib_entries()[key]
    note = fields.get("note", "").lower()
    assert "title" in fields, f"{key}: no title"
    for field in ("author", "year"):
        present = field in fields and fields[field].strip("{} ") not in ("", "n.d.", "nd", "?")
        said = f"{field} not given in the source" in note or f"{field}s not given in the source" in note \
            or (field in note and "not given in the source" in note)
        assert present or said, (f"{key}: no {field}, and its note does not say "
                                 f"'{field} not given in the source'")
    if kind in ("book",):
        assert "publisher" in fields, f"{key}: a book without its publisher"
    if kind in ("article",):
        assert "journal" in fields, f"{key}: an article without its journal"
    if kind == "misc":
        assert "howpublished" in fields or "publisher" in fields or "venue" in note, \
            f"{key}: say where it was published (howpublished), or that the source does not say"


@pytest.mark.parametrize("page", teaching_pages(), ids=lambda p: str(p.relative_to(ROOT)))
def test_every_package_aside_is_collapsed(page):
    # expected (decision 1): ':::{admonition} In the package' followed at once by ':class: dropdown'
    lines = page.read_text(encoding="utf8").splitlines()
    wrong = [k + 1 for k, line in enumerate(lines)
             if re.match(r"^\s*:{3,}\s*\{admonition\}\s*In the package\s*$", line)
             and (k + 1 >= len(lines) or lines[k + 1].strip() != ":class: dropdown")]
    assert not wrong, f"{page.relative_to(ROOT)}: an 'In the package' aside that is not collapsed, lines {wrong}"
