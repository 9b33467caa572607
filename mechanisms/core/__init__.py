"""Layer 1, the core: the motion of a link and its points, angles, link types, errors and validation.

Modules: :mod:`~mechanisms.core.motion` (a value with two time derivatives; plane motion in Euler
and Lagrange form), :mod:`~mechanisms.core.angles` (one wrapping convention, directions, unit
vectors), :mod:`~mechanisms.core.links` (the lecture's link types), :mod:`~mechanisms.core.errors`
(the package's errors and warnings) and :mod:`~mechanisms.core.validate` (one validation path).
"""
