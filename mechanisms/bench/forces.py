"""Layer 6: what forces cost beside kinematics — chapter 11's analysis at 10⁵ positions.

The shipped Watt six-bar (``watt-six-bar``) is given uniform bars as bodies (1 kg per metre of length, the
centre of mass at the middle, J = m L²/12; the ternary rocker as its bar C-B) and gravity, and solved at
:data:`POSITIONS` crank angles: its order-2 kinematics (``Linkage.solve``) and then its joint forces group by
group (:func:`mechanisms.analysis.kinetostatics.linkage_forces`) are timed in the same process, each the best
of :data:`REPEATS` runs. The speed appendix prints the result that ``tools/bench_forces.py`` stores in
``book/forces-cost.json``.
"""

from __future__ import annotations

import platform
import time
import tomllib
from importlib import resources
from typing import Any

import numpy as np

__all__ = ["POSITIONS", "REPEATS", "six_bar_with_masses", "forces_cost"]

POSITIONS = 100_000
"""Crank positions of the timed run."""

REPEATS = 5
"""Runs of each part; the fastest counts (the others were slowed by something else on the machine)."""


def six_bar_with_masses() -> Any:
    """The shipped Watt six-bar with a uniform bar (1 kg/m) for each moving link, and gravity 9.81 m/s²."""
    from ..linkages.linkage_file import linkage_from_dict

    text = resources.files("mechanisms.linkages").joinpath("examples", "watt-six-bar.toml").read_text("utf-8")
    data = tomllib.loads(text)
    bars = {"crank": data["crank"]["length"]}
    for dyad in data["dyad"]:
        for link, length in zip(dyad["links"], dyad["lengths"]):
            bars[link] = length
    data["gravity"] = 9.81
    data["mass"] = [{"body": link, "mass": length, "along": length / 2, "inertia": length ** 3 / 12}
                    for link, length in bars.items()]
    return linkage_from_dict(data, "watt-six-bar.toml with uniform bars")


def _best(run, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def forces_cost(positions: int = POSITIONS, repeats: int = REPEATS) -> dict[str, Any]:
    """Time the six-bar's order-2 kinematics and its forces by Assur groups at ``positions`` crank angles.

    Returns
    -------
    dict
        ``positions``, ``kinematics_s`` and ``forces_s`` (the best run of each, s; the forces given the
        kinematic solution), ``ratio`` = forces_s / kinematics_s, ``ns_per_position`` of each, and the
        machine (``machine``, ``python``, ``numpy``).
    """
    from ..analysis.kinetostatics import linkage_forces

    linkage = six_bar_with_masses()
    phi = np.linspace(0.0, 2.0 * np.pi, positions, endpoint=False)
    solution = linkage.solve(phi, 10.0, 0.0)
    kinematics = _best(lambda: linkage.solve(phi, 10.0, 0.0), repeats)
    forces = _best(lambda: linkage_forces(linkage, solution), repeats)
    return {"positions": positions, "repeats": repeats, "kinematics_s": kinematics, "forces_s": forces,
            "ratio": forces / kinematics, "ns_per_position": {"kinematics": 1e9 * kinematics / positions,
                                                              "forces": 1e9 * forces / positions},
            "machine": f"{platform.machine()}, {platform.processor() or platform.system()}",
            "python": platform.python_version(), "numpy": np.__version__}
