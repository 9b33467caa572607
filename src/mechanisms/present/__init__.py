"""Layer 6, text: Markdown tables and printed numbers (no matplotlib)."""

from .tables import MarkdownTable, difference, magnitude, markdown_table

__all__ = ["MarkdownTable", "markdown_table", "difference", "magnitude"]
