"""Store what forces cost beside kinematics (mechanisms.bench.forces) in book/forces-cost.json.

Run on an otherwise idle machine: ``.venv/bin/python tools/bench_forces.py``; the speed appendix prints it.
"""

import datetime
import json
import pathlib

from mechanisms.bench.forces import forces_cost

result = forces_cost()
result["date"] = datetime.date.today().isoformat()
path = pathlib.Path(__file__).resolve().parent.parent / "book" / "forces-cost.json"
path.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
print(f"forces {result['ns_per_position']['forces']:.0f} ns, kinematics {result['ns_per_position']['kinematics']:.0f} "
      f"ns per position: ratio {result['ratio']:.2f} -> {path}")
