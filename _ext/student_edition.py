"""Sphinx extension of the student edition: gated solutions leave nothing on the page.

With ``hide_solutions = True`` sphinx-exercise 1.2.1 makes a ``solution-start`` directive produce
nothing, but the cells between it and its ``solution-end`` (the worked solution's code and
text) stay in the document, and so does the ``solution-end`` node, which the HTML writer cannot
write: the build fails ("departing unknown node type: solution_end_node"). This extension
replaces ``solution-start`` by a directive that, in that case, leaves a marker; a transform then
removes the marker, everything after it up to the matching ``solution-end``, and that end.
It also turns off the theme's download button, whose links would give the page's source,
solutions included (Jupyter Book 1 does not pass ``html.use_download_button`` on to the theme),
and sets the Sphinx tag ``student_edition``, so that a page can say what is true of its edition:
text in ``{only} student_edition`` appears in the student edition alone, text in
``{only} not student_edition`` in the full edition alone (the exercise pages' introductions: the
full edition has worked solutions to open, the student edition has not). With
``hide_solutions = False`` it changes nothing.

Only the student edition loads it (see ``tools/student_config.py``).
"""

from __future__ import annotations

from docutils import nodes
from sphinx.transforms import SphinxTransform
from sphinx_exercise.directive import SolutionStartDirective
from sphinx_exercise.nodes import solution_end_node


class hidden_solution_start(nodes.Element):
    """Where a hidden gated solution begins (removed before the page is written)."""


class HiddenSolutionStart(SolutionStartDirective):
    """``solution-start`` that marks a hidden solution instead of dropping only the directive."""

    def run(self):
        result = super().run()  # records the directive in sphinx-exercise's structure check
        if self.env.app.config.hide_solutions:
            return [hidden_solution_start(label=self.arguments[0])]
        return result


class RemoveHiddenSolutions(SphinxTransform):
    """Remove each hidden solution: the marker, the nodes after it, up to its ``solution-end``."""

    default_priority = 5  # after sphinx-exercise's structure check (1), before its merging (10)

    def apply(self, **kwargs) -> None:
        for marker in list(self.document.findall(hidden_solution_start)):
            parent = marker.parent
            start = parent.index(marker)
            end = start
            while end < len(parent.children) and not isinstance(parent.children[end], solution_end_node):
                end += 1
            if end == len(parent.children):
                raise ValueError(f"solution-start {marker['label']!r} in {self.env.docname} has no "
                                 "solution-end at the same level")
            del parent.children[start:end + 1]


STUDENT_TAG = "student_edition"


def _student_edition(app, config) -> None:
    """No download button, and the tag that ``{only}`` directives test, when solutions are hidden."""
    if config.hide_solutions:
        config.html_theme_options = {**(config.html_theme_options or {}), "use_download_button": False}
        app.tags.add(STUDENT_TAG)


def setup(app):
    app.setup_extension("sphinx_exercise")
    app.add_node(hidden_solution_start)
    app.add_directive("solution-start", HiddenSolutionStart, override=True)
    app.add_transform(RemoveHiddenSolutions)
    app.connect("config-inited", _student_edition)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
