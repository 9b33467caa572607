"""What each speed trick of the closed forms buys: its time against the plain form the book shows.

``python -m mechanisms.bench.tricks [--positions N] [--repeat R] [--format text|json]`` times, on the
same inputs, each fast form and its plain form (best of R runs, ns per position) and reports the
largest difference between their results (the tests bound it: ``tests/test_speed_tricks.py``):

* the hinge in place (:func:`~mechanisms.blocks.circle_circle.hinge`) against the book's formulas in
  plain numpy (:func:`~mechanisms.blocks.circle_circle.hinge_plain`), at order 2;
* the unit vector from the tangent of the half angle against ``exp(iθ)``;
* a four-bar solved in cache-sized chunks (:mod:`mechanisms.linkages.chunks`) against all at once.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Callable, Sequence

import numpy as np

from ..blocks.circle_circle import hinge, hinge_plain
from ..blocks.crank import crank_angle, crank_pin
from ..core.angles import unit_vector, unit_vector_fast
from ..core.motion import fixed_point
from ..linkages.four_bar import FourBar
from .benchmark import best_time, machine_description

__all__ = ["measure_tricks", "format_text", "main"]


def _largest_difference(first: Any, second: Any) -> float:
    return float(np.max(np.abs(np.asarray(first) - np.asarray(second))))


def measure_tricks(positions: int = 1_000_000, repeat: int = 5) -> dict:
    """Time each trick and its plain form on ``positions`` crank angles (best of ``repeat``).

    Returns
    -------
    dict
        ``{"machine", "positions", "repeat", "rows": [{"trick", "plain_ns", "fast_ns", "speed_up",
        "max_difference"}]}``; times in ns per position.
    """
    phi = np.linspace(-np.pi, np.pi, positions)
    four_bar = FourBar.example()
    crank = crank_angle(phi, 1.0, 0.0, 2)
    pin = crank_pin(crank, 1.0)
    pivot = fixed_point(4.0 + 0j, phi)
    cases: list[tuple[str, Callable[[], Any], Callable[[], Any], Callable[[Any], Any]]] = [
        ("hinge in place (order 2)", lambda: hinge(pin, pivot, 3.5, 3.0), lambda: hinge_plain(pin, pivot, 3.5, 3.0),
         lambda h: h.angle_q.acceleration),
        ("unit vector from tan(θ/2)", lambda: unit_vector_fast(phi), lambda: unit_vector(phi), lambda u: u),
        ("four-bar in chunks (order 2)", lambda: four_bar.solve(phi), lambda: four_bar._solve_block(crank, 2),
         lambda s: s.angle("rocker").acceleration),
    ]
    rows = []
    for name, fast, plain, result in cases:
        fast_s, plain_s = best_time(fast, repeat), best_time(plain, repeat)
        rows.append({"trick": name, "plain_ns": plain_s / positions * 1e9, "fast_ns": fast_s / positions * 1e9,
                     "speed_up": plain_s / fast_s, "max_difference": _largest_difference(result(fast()), result(plain()))})
    return {"machine": machine_description(), "positions": positions, "repeat": repeat, "rows": rows}


def format_text(report: dict) -> str:
    """The report as a small table."""
    lines = [f"{report['machine']}; {report['positions']} positions, best of {report['repeat']} runs",
             f"{'trick':<30}{'plain ns':>10}{'fast ns':>10}{'speed-up':>10}{'max diff':>11}"]
    for r in report["rows"]:
        lines.append(f"{r['trick']:<30}{r['plain_ns']:>10.1f}{r['fast_ns']:>10.1f}{r['speed_up']:>10.2f}"
                     f"{r['max_difference']:>11.1e}")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m mechanisms.bench.tricks``: print the report (text or JSON)."""
    parser = argparse.ArgumentParser(prog="python -m mechanisms.bench.tricks", description=__doc__.splitlines()[0])
    parser.add_argument("--positions", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--format", choices=("text", "json"), default="text")
    args = parser.parse_args(argv)
    report = measure_tricks(max(1, args.positions), max(1, args.repeat))
    print(json.dumps(report, indent=1) if args.format == "json" else format_text(report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
