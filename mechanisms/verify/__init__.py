"""Layer 5, verification: the generic solver, numerical differentiation and the checks.

* :mod:`~mechanisms.verify.jet` — numbers with exact first and second derivatives;
* :mod:`~mechanisms.verify.newton` — Newton's method on the constraint equations, in any float type;
* :mod:`~mechanisms.verify.differences` — numerical time derivatives;
* :mod:`~mechanisms.verify.checks` — the checks of the analysis sequence.
"""

from .checks import constraint_residual, derivative_errors, distance_deviation, generic_errors
from .differences import central_difference
from .newton import GenericSolution, newton_history, solve_constraints, solve_generic

__all__ = [
    "GenericSolution",
    "solve_constraints",
    "newton_history",
    "solve_generic",
    "central_difference",
    "constraint_residual",
    "distance_deviation",
    "derivative_errors",
    "generic_errors",
]
