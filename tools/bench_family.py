"""Store the family row of the benchmark (mechanisms.bench.benchmark.bench_family) in book/family-cost.json.

10⁵ four-bars × 360 crank positions solved as families of FourBar, beside pylinkage's numba solver looping over
500 members of the same family, in the same process. Run on an otherwise idle machine, with pylinkage and
numba installed (`.venv/bin/pip install pylinkage numba`): ``.venv/bin/python tools/bench_family.py``; the speed
appendix prints it.
"""

import datetime
import json
import pathlib

from mechanisms.bench.benchmark import bench_family, machine_description, pylinkage_available

if not pylinkage_available():
    raise SystemExit("pylinkage is not installed: the family row compares with its numba solver "
                     "(.venv/bin/pip install pylinkage numba)")
ours, peer = bench_family(repeat=5)
result = {"family": ours, "pylinkage": peer, "ratio": peer["ns_per_position"] / ours["ns_per_position"],
          "repeats": 5, "machine": machine_description(), "date": datetime.date.today().isoformat()}
path = pathlib.Path(__file__).resolve().parent.parent / "book" / "family-cost.json"
path.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
print(f"family {ours['ns_per_position']:.1f} ns, pylinkage loop {peer['ns_per_position']:.1f} ns per "
      f"linkage-position: ratio {result['ratio']:.2f} -> {path}")
