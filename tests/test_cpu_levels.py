"""Every notebook's stored outputs at every numpy CPU level this machine can imitate.

numpy picks its vector kernels (sine, cosine, arctangent, complex products …) by the processor's
instruction set, and their last bits differ: a notebook that prints or plots those bits passes on
the machine that stored it and fails on another. numpy imitates a smaller processor when told to
disable features (``NPY_DISABLE_CPU_FEATURES``), so this test re-executes every notebook, strictly
as ``make test`` does (nbval and the root conftest's byte-for-byte check), in a subprocess at each
level that enables another set of features on this CPU than the default run: on x86-64 all
features, without AVX-512 (``X86_V4 AVX512_ICL AVX512_SPR``, an AVX2 machine) and the baseline
(also without ``X86_V3``); elsewhere (ARM …) each level from numpy's own dispatch targets
(``__cpu_dispatch__``) down to the baseline. Levels that enable the same features here are run
once, and the default level is the main nbval run's. The test's id names the level
(``pytest -v tests/test_cpu_levels.py``; ``--collect-only -q`` lists them without running).

A level above this CPU (AVX-512 on an AVX2 machine) cannot be imitated: a notebook cell that prints a
round-off-sized number or plots one must compute it so that no processor can change it (chapter 9
shows how). The last level comes closest, on any machine: "every elementary function one ulp off"
runs the notebooks with numpy's double-precision sine, cosine, arctangent, power, absolute value of
complex numbers … moved one unit in the last place at random (``tools/nudge_numpy.py``, loaded into
every kernel by an IPython startup file; seed ``NUDGE_SEED``, or ``MECHANISMS_NUDGE_SEED`` from the
environment to try another); it runs only when ``MECHANISMS_NUDGE_SEED`` is set (``make cpu-levels`` sets
it). Before committing a notebook: ``make cpu-levels``.
"""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
X86_LEVELS = (("all features", ()),
              ("without AVX-512", ("X86_V4", "AVX512_ICL", "AVX512_SPR")),
              ("baseline", ("X86_V3", "X86_V4", "AVX512_ICL", "AVX512_SPR")))
TIMEOUT = 3600                          # seconds for one level's notebooks
NUDGE = "every elementary function one ulp off"
NUDGE_SEED = 1


def _features(disabled: tuple[str, ...]) -> tuple[str, ...]:
    """The features numpy enables on this CPU with ``disabled`` disabled, asked of a fresh interpreter."""
    env = dict(os.environ, NPY_DISABLE_CPU_FEATURES=" ".join(disabled))
    code = ("import json; from numpy._core import _multiarray_umath as m; "
            "print(json.dumps(sorted(k for k, v in m.__cpu_features__.items() if v)))")
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return tuple(json.loads(done.stdout))


def cpu_levels() -> list[tuple[str, tuple[str, ...]]]:
    """The levels to run: (name, features disabled), each enabling another feature set here than the
    default run and than every other level."""
    from numpy._core import _multiarray_umath as umath

    dispatch = list(umath.__cpu_dispatch__)
    known = set(dispatch) | set(umath.__cpu_features__)
    if "X86_V3" in dispatch:
        candidates = [(name, tuple(f for f in disabled if f in known)) for name, disabled in X86_LEVELS]
    else:                               # each dispatch target and those above it disabled
        candidates = [("all features", ())] + [
            ("without " + " ".join(dispatch[i:]), tuple(dispatch[i:])) for i in reversed(range(len(dispatch)))]
    seen = {tuple(sorted(k for k, v in umath.__cpu_features__.items() if v))}   # the default run's
    levels = []
    for name, disabled in candidates:
        features = _features(disabled)
        if features not in seen:
            seen.add(features)
            levels.append((name, disabled))
    return levels


def _notebooks() -> list[str]:
    return sorted(p.relative_to(ROOT).as_posix() for folder in ("book", "exercises")
                  for p in (ROOT / folder).glob("[0-9][0-9]-*.ipynb"))


def _groups(notebooks: list[str], count: int) -> list[list[str]]:
    """The notebooks in ``count`` groups of about equal running time (tools/notebook_times.json)."""
    times_file = ROOT / "tools" / "notebook_times.json"
    times = json.loads(times_file.read_text()) if times_file.exists() else {}
    groups: list[list[str]] = [[] for _ in range(count)]
    load = [0.0] * count
    for notebook in sorted(notebooks, key=lambda n: -times.get(n, {}).get("seconds", 10.0)):
        least = load.index(min(load))
        groups[least].append(notebook)
        load[least] += times.get(notebook, {}).get("seconds", 10.0)
    return [g for g in groups if g]


def _failures(report: pathlib.Path, output: str) -> list[str]:
    """The failing cells of one nbval run, from its JUnit report: 'notebook::Cell n: message'."""
    if not report.exists():
        return [f"no test report; pytest said:\n{output[-3000:]}"]
    failures = []
    for case in ElementTree.parse(report).iter("testcase"):
        for problem in list(case.iter("failure")) + list(case.iter("error")):
            where = f"{case.get('classname', '')}::{case.get('name', '')}"
            failures.append(f"{where}: {(problem.get('message') or '').strip()[:2000]}")
    return failures


LEVELS: list[tuple[str, tuple[str, ...] | None]] = list(cpu_levels()) or [("no other level on this CPU", None)]


def _nudge_seed() -> int:
    return int(os.environ.get("MECHANISMS_NUDGE_SEED", "").strip() or NUDGE_SEED)


def _level_id(name: str, disabled: tuple[str, ...] | None) -> str:
    if name == NUDGE:
        return f"{name} (seed {_nudge_seed()})"
    return name if disabled is None else f"{name} ({' '.join(disabled) or 'nothing'} disabled)"


RUN_LEVELS = LEVELS + ([(NUDGE, ())] if os.environ.get("MECHANISMS_NUDGE_SEED", "").strip() else [])
"""The levels this run takes: the nudge is an audit asked for by setting ``MECHANISMS_NUDGE_SEED`` (``make
cpu-levels`` sets it), not part of ``make test``: with seeds 1 and 2 it still moves the anti-aliased pixels of
three drawings (chapter 1 cell 4, chapter 9 cell 2, chapter 10 cell 24), which no real processor has been seen
to do."""


@pytest.mark.parametrize("level", RUN_LEVELS, ids=[_level_id(*level) for level in RUN_LEVELS])
def test_notebooks_at_cpu_level(level, tmp_path):
    """Every notebook re-executed at this numpy CPU level reproduces its stored outputs byte for byte."""
    name, disabled = level
    if disabled is None:                # a CPU with the baseline only: the default run is every level
        baseline = next(d for n, d in X86_LEVELS if n == "baseline")
        from numpy._core import _multiarray_umath as umath
        lowest = baseline if "X86_V3" in umath.__cpu_dispatch__ else tuple(umath.__cpu_dispatch__)
        assert _features(lowest) == _features(()), "cpu_levels() missed a level"
        return
    if name == NUDGE:                   # this CPU's kernels, every result moved by one ulp at random
        sys.path.insert(0, str(ROOT / "tools"))
        try:
            from nudge_numpy import kernel_environment
        finally:
            sys.path.pop(0)
        env = kernel_environment(_nudge_seed(), tmp_path / "ipython")
    else:
        env = dict(os.environ, NPY_DISABLE_CPU_FEATURES=" ".join(disabled))
    groups = _groups(_notebooks(), max(1, min(4, os.cpu_count() or 1)))
    runs = []
    for i, group in enumerate(groups):              # the groups in parallel, one process each
        report = tmp_path / f"group-{i}.xml"
        command = [sys.executable, "-m", "pytest", "-q", "-p", "no:randomly", "--tb=no",
                   f"--junitxml={report}", *group]
        log = (tmp_path / f"group-{i}.log").open("w")
        runs.append((report, log, subprocess.Popen(command, cwd=ROOT, env=env, stdout=log,
                                                   stderr=subprocess.STDOUT)))
    failures = []
    for report, log, process in runs:
        process.wait(timeout=TIMEOUT)
        log.close()
        if process.returncode != 0:
            output = pathlib.Path(log.name).read_text()
            failures += _failures(report, output) or [f"pytest exited with {process.returncode}:\n{output[-3000:]}"]
    assert not failures, (f"at numpy CPU level '{_level_id(name, disabled)}' (NPY_DISABLE_CPU_FEATURES="
                          f"\"{' '.join(disabled)}\") these notebook cells differ from their stored outputs:\n"
                          + "\n".join(failures))


_DIGEST = """
import hashlib, math, numpy as np
from mechanisms import bench
m = bench.benchmark_mechanisms()["four-bar"]
ref = bench.reproducible_reference(m, np.arange(72) * (2.0 * math.pi / 72))
errors = bench.step_errors(m, [1e-2, 1e-5, 1e-8], n=36)
parts = [a for v in ref for a in (v.astype(float), (v - v.astype(float)).astype(float))] + list(errors.values())
print(hashlib.sha256(b"".join(np.ascontiguousarray(p).tobytes() for p in parts)).hexdigest())
"""


def test_the_reproducible_reference_and_step_errors_have_the_same_bits_at_every_level():
    # expected: the digest at the default level (this machine's own) equals the digest at every other level
    # (both the extended-precision values, high and low parts, and the step errors of chapter 9's figure)
    def digest(disabled: tuple[str, ...]) -> str:
        env = dict(os.environ, NPY_DISABLE_CPU_FEATURES=" ".join(disabled))
        done = subprocess.run([sys.executable, "-c", _DIGEST], env=env, cwd=ROOT, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr[-2000:]
        return done.stdout.strip()

    default = digest(())
    for name, disabled in LEVELS:
        if disabled is not None:
            assert digest(disabled) == default, f"reproducible_reference or step_errors differ at level '{name}'"


def test_the_reproducible_reference_solves_the_constraints_in_extended_precision():
    # expected: the constraint residual at the reproducible positions is at extended precision's round-off
    # (machine epsilon 1.1e-19 on x86-64, lengths of order 1 m: a few 1e-19 m), and the positions agree with
    # bench.reference's to the same order (both are roots of the same equations next to the same branch)
    import math

    import numpy as np

    from mechanisms import bench

    m = bench.benchmark_mechanisms()["four-bar"]
    phi = np.arange(36) * (2.0 * math.pi / 36)
    ref = bench.reproducible_reference(m, phi)
    residual = max(float(np.max(np.abs(r))) for r in m.constraints(ref.q, phi.astype(np.longdouble)))
    assert residual < 50 * float(np.finfo(np.longdouble).eps)
    assert float(np.max(np.abs(ref.q - bench.reference(m, phi).q))) < 50 * float(np.finfo(np.longdouble).eps)


_KERNEL_CHECK = """
import nbformat, numpy as np
from nbclient import NotebookClient
nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
    "import math, numpy as np\\n"
    "x = np.linspace(0.1, 3.0, 1000)\\n"
    "moved = np.sin(x) != [math.sin(v) for v in x]\\n"
    "print(type(np.sin).__name__, int(moved.sum()), float(np.sin(0.0)), float(np.abs(3 + 4j)))")])
NotebookClient(nb, kernel_name="python3", timeout=120).execute()
print(nb.cells[0].outputs[0]["text"].strip())
"""


def test_the_nudge_reaches_every_kernel_and_moves_only_inexact_results(tmp_path):
    # expected: a kernel started in the nudge level's environment has numpy.sin replaced (class Nudged), moves
    # most of 1000 sines off the C library's (glibc's sin agrees with numpy's but for a few in 1000; the nudge
    # moves every result that is not exact, so several hundred differ), and leaves sin 0 = 0 and |3 + 4i| = 5
    sys.path.insert(0, str(ROOT / "tools"))
    try:
        from nudge_numpy import kernel_environment
    finally:
        sys.path.pop(0)
    env = kernel_environment(NUDGE_SEED, tmp_path / "ipython")
    done = subprocess.run([sys.executable, "-c", _KERNEL_CHECK], env=env, cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    name, moved, sine, modulus = done.stdout.split()[-4:]
    assert name == "Nudged" and int(moved) > 300 and float(sine) == 0.0 and float(modulus) == 5.0
