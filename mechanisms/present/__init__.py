"""Layer 6, text and scenes (no matplotlib): Markdown tables, printed numbers, and the moving figures'
data for the site's player (:mod:`~mechanisms.present.scene`)."""

from .scene import Arrow, Line, On, Parameter, Readout, Scene, acceleration, explorer, scene, velocity
from .tables import MarkdownTable, difference, magnitude, markdown_table, number, show_messages

__all__ = ["MarkdownTable", "markdown_table", "number", "difference", "magnitude", "show_messages", "Scene", "scene", "explorer", "Parameter",
           "Readout", "Arrow", "Line", "On", "velocity", "acceleration"]
