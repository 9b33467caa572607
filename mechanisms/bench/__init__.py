"""The benchmark: time per position against error for the closed forms, the generic solver and
numerical differentiation (``python -m mechanisms bench``; chapter 9 and its appendix).

* :mod:`~mechanisms.bench.benchmark` — the runs, the extended-precision reference, the report;
* the figures of chapter 9 (imported with matplotlib only when drawn);
* :mod:`~mechanisms.bench.startup` — how long ``import mechanisms`` and the command line take to start.
"""

from .benchmark import *  # noqa: F401,F403
from .benchmark import (__all__, cost_against_size, plot_step_errors, plot_stored, plot_work_precision,  # noqa: F401
                        step_errors, work_precision)
from .startup import STARTUP_COMMANDS, StartupCommand, format_startup_text, startup_times  # noqa: F401
