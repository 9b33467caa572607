"""Sphinx extension: exercises numbered by chapter ("Exercise 3.2"), not through the whole book.

sphinx-exercise makes each exercise an enumerable node. Sphinx numbers such nodes through the
whole book when the table of contents is not numbered, and ours is not (the chapter numbers are
part of the titles), so chapter 3's first exercise was "Exercise 11". Once Sphinx has assigned
the numbers, this extension renumbers the exercises of each page ``exercises/NN-…`` as NN.1,
NN.2 … in the page's order. The exercise titles, the solutions' titles and every reference
then read the same number, because sphinx-exercise takes them all from Sphinx's table.
"""

from __future__ import annotations

import re

from sphinx.application import Sphinx
from sphinx.environment import BuildEnvironment

EXERCISE_PAGE = re.compile(r"(?:^|/)exercises/(\d+)-")


def number_by_chapter(app: Sphinx, env: BuildEnvironment) -> list[str]:
    """Replace the book-wide numbers of the exercises by (chapter, position on the page)."""
    for docname, numbers_by_type in env.toc_fignumbers.items():
        page = EXERCISE_PAGE.search(docname)
        numbers = numbers_by_type.get("exercise")
        if page and numbers:
            chapter = int(page.group(1))
            for position, node_id in enumerate(sorted(numbers, key=numbers.get), start=1):
                numbers[node_id] = (chapter, position)
    return []


def setup(app: Sphinx) -> dict:
    # after Sphinx's own TocTreeCollector (priority 500) has assigned the numbers
    app.connect("env-get-updated", number_by_chapter, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
