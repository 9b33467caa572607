"""Layer 6, figures (imports matplotlib): drawings of mechanisms, diagrams, animations, plans.

* :mod:`~mechanisms.plot.drawing` — the book's style, drawings, trajectories, diagrams, animations;
* :mod:`~mechanisms.plot.plans` — velocity and acceleration plans, instant centres;
* :mod:`~mechanisms.plot.describe` — every figure's text alternative (:func:`describe_figure`), from what the
  figure functions say they drew (:func:`add_description`) and from the figure's artists;
* :mod:`~mechanisms.plot.workarounds` — the documented workarounds of matplotlib's behaviour.

``import mechanisms`` does not import this package; ``mechanisms.plot`` imports it when first used.
"""

from . import describe, plans
from .describe import add_description, describe_figure
from .drawing import *  # noqa: F401,F403  (the drawing functions are the package's figure API)
from .drawing import __all__ as _drawing_all

__all__ = list(_drawing_all) + ["plans", "describe", "describe_figure", "add_description"]
