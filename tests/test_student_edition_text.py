"""The student edition's exercise pages say what is true of that edition (issue 19).

The student edition (`make book-student`, in `_build/student/_build/html`) has no worked solutions, so
its exercise pages must not tell a student to open one ("Try each before you open its solution",
"(open the solution)"). The pages' introductions say it per edition with ``{only} student_edition``
and ``{only} not student_edition`` (the tag is set by `_ext/student_edition.py`); every exercise and
every self-check question carries its short answer in an *Answer* dropdown, which both editions show.

`make test` builds both editions before pytest; run alone after `make book-student` (without it pytest stops
at collection and says so, tests/conftest.py).
"""

from __future__ import annotations

import html as html_module
import pathlib
import re

import pytest

pytestmark = pytest.mark.needs_site("student")

# wording that points a reader to a worked solution on the page
SOLUTION_WORDING = re.compile(
    r"open\s+(?:the|its|a|each|their)\s+(?:worked\s+)?solutions?"
    r"|before\s+you\s+open"
    r"|solutions?\s+(?:below|follows?)"
    r"|worked\s+solution\s+follows",
    re.IGNORECASE,
)


@pytest.fixture
def student_site(built_site) -> pathlib.Path:
    return built_site("student")


def exercise_pages(site: pathlib.Path) -> list[pathlib.Path]:
    pages = sorted((site / "exercises").glob("*.html"))
    assert pages, f"the student edition in {site} has no exercise pages"
    return pages


def visible_text(html: str) -> str:
    """The page's text as a reader sees it: no scripts, styles or tags, entities decoded."""
    html = re.sub(r"<(script|style)\b.*?</\1>", " ", html, flags=re.S | re.I)
    return " ".join(html_module.unescape(re.sub(r"<[^>]+>", " ", html)).split())


def test_the_student_edition_does_not_send_students_to_solutions(student_site):
    # expected: none of the wording of SOLUTION_WORDING (the full edition's intro says it, in {only})
    for page in exercise_pages(student_site):
        text = visible_text(page.read_text(encoding="utf8"))
        found = sorted({m.group(0) for m in SOLUTION_WORDING.finditer(text)})
        assert not found, (f"{page.relative_to(student_site)}: the student edition has no solutions, "
                           f"yet the page says {found}")
        assert "student edition gives the short answers" in text, \
            f"{page.relative_to(student_site)}: the student edition's introduction is missing"


def test_every_exercise_has_its_level_and_answer_in_the_student_edition(student_site):
    # expected: one "Answer" dropdown per exercise, more for the self-check questions (at least two), and
    # every exercise title marked ✍ or ⌨ and with its level, ★ to ★★★
    for page in exercise_pages(student_site):
        html = page.read_text(encoding="utf8")
        exercises = html.count('class="exercise admonition')
        answers = len(re.findall(r"<summary[^>]*>.*?Answer.*?</summary>", html, flags=re.S))
        assert exercises >= 6, f"{page.relative_to(student_site)}: {exercises} exercises, fewer than 6"
        assert answers >= exercises + 2, \
            f"{page.relative_to(student_site)}: {answers} answers for {exercises} exercises and the self-check"
        titles = re.findall(r'<p class="admonition-title">\s*<span class="caption-number">Exercise [0-9.]+\s*</span>'
                            r"(.*?)</p>", html, flags=re.S)
        unmarked = [t.strip() for t in titles if not re.search(r"[✍⌨] ★{1,3} ", t)]
        assert len(titles) == exercises and not unmarked, \
            f"{page.relative_to(student_site)}: exercise titles without a mark (✍ or ⌨) and a level (★ to ★★★): {unmarked}"
