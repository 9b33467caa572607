"""numpy's double-precision elementary functions one unit in the last place off, at random: another processor.

numpy picks the vector kernels of its sine, cosine, arctangent, power, absolute value of complex numbers …
by the processor's instructions (AVX-512, AVX2, baseline), and their last bits differ from machine to
machine. A machine can imitate a smaller processor (``NPY_DISABLE_CPU_FEATURES``) but not a larger one;
this module imitates *any* other one. Imported with the environment variable ``MECHANISMS_NUDGE_SEED`` set
to a whole number, it replaces numpy's functions by name (``numpy.sin``, ``numpy.arctan2``,
``numpy.logspace`` … :data:`NUDGED`) by wrappers whose double-precision results move each element one ulp
up or down (``numpy.nextafter``), in directions drawn from a generator seeded by that number: a faithful
function other than this machine's, as another processor's may be. A result that extended precision finds
exact (sin 0 = 0, cos 0 = 1, |3 + 4i| = 5, |0.3 + 0i| = 0.3, 10² = 100) is left alone: every faithful
function returns it. Extended precision (the C library's, the same on every x86-64 processor), single
precision and numpy's real absolute value (exact) are left alone too.

matplotlib's own calls are left alone (its drawing ends in whole pixels, and its logarithmic axes test
whether log10 of a tick is a whole number, which a real processor's correctly rounded kernel keeps).
What it cannot move: operators (``z * w`` of complex numbers, ``x ** y``, ``abs(z)``), which numpy calls
without looking its functions up by name, calls of the functions with ``out=`` or ``where=``, and
the matrix products of the BLAS library (its own kernels by processor).

To run notebooks under it, every kernel must import it before the notebook's first cell: an IPython
startup file in a fresh ``IPYTHONDIR`` (:func:`kernel_environment`); nbval's kernel
(``--nbval-current-env``) takes its environment from pytest's. From the command line::

    python tools/nudge_numpy.py SEED book/04-four-bar.ipynb ...   # strict nbval of those notebooks, nudged
"""

from __future__ import annotations

import functools
import os
import pathlib
import subprocess
import sys
import tempfile
from typing import Any, Callable

import numpy as np

SEED_VARIABLE = "MECHANISMS_NUDGE_SEED"
NUDGED = ("sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "sinh", "cosh", "tanh", "hypot",
          "exp", "expm1", "exp2", "log", "log10", "log2", "log1p", "power", "float_power", "cbrt",
          "absolute", "abs", "angle", "logspace")
"""numpy's functions moved (by their names in the ``numpy`` namespace)."""
_EXACT_TYPES = {np.dtype(np.float64): np.longdouble, np.dtype(np.complex128): np.clongdouble}


def _extended(value: Any) -> Any:
    """A double-precision argument in extended precision; anything else as it is."""
    if isinstance(value, (bool, np.bool_)):
        return value
    if isinstance(value, (int, float, complex)) or (isinstance(value, (np.ndarray, np.generic))
                                                   and np.dtype(value.dtype) in _EXACT_TYPES):
        array = np.asarray(value)
        if array.dtype.kind in "iu":
            return value
        return array.astype(_EXACT_TYPES.get(array.dtype, np.longdouble))
    if isinstance(value, (list, tuple)):
        return _extended(np.asarray(value))
    return value


class Nudged:
    """A numpy function whose double-precision results are moved one ulp at random (see the module)."""

    def __init__(self, name: str, function: Callable, rng: np.random.Generator):
        self.name, self.function, self.rng = name, function, rng
        functools.update_wrapper(self, function)   # type: ignore[arg-type]

    def __getattr__(self, attribute: str) -> Any:  # a ufunc's reduce, nin … unmoved
        return getattr(self.function, attribute)

    def __repr__(self) -> str:
        return f"<nudged {self.function!r}>"

    def __eq__(self, other: object) -> bool:       # a table keyed by numpy.cos finds the ufunc that
        return other is self or other is self.function  # __array_ufunc__ receives (mechanisms.verify.jet)

    def __hash__(self) -> int:
        return hash(self.function)

    def _exact(self, args: tuple, kwargs: dict) -> np.ndarray | None:
        """The same call in extended precision, or None where it cannot be made."""
        try:
            if self.name == "logspace":
                extended = {k: v for k, v in kwargs.items() if k != "dtype"}
                return np.asarray(self.function(*[np.asarray(a, dtype=np.longdouble) for a in args[:2]], *args[2:],
                                                **{k: _extended(v) if k == "base" else v
                                                   for k, v in extended.items()}))
            return np.asarray(self.function(*[_extended(a) for a in args],
                                            **{k: v for k, v in kwargs.items() if k != "dtype"}))
        except (TypeError, ValueError):
            return None

    def _moved(self, values: np.ndarray, exact: np.ndarray | None) -> np.ndarray:
        direction = np.where(self.rng.random(values.shape) < 0.5, -np.inf, np.inf)
        moved = np.nextafter(values, direction)
        keep = ~np.isfinite(values) | ~np.isfinite(moved)
        if exact is not None and exact.shape == values.shape:
            keep |= values == exact
        return np.where(keep, values, moved)

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        result = self.function(*args, **kwargs)
        if "out" in kwargs or "where" in kwargs:
            return result
        if str(sys._getframe(1).f_globals.get("__name__", "")).startswith("matplotlib"):
            return result                       # its geometry ends in pixels; its log axes test decades
        if self.name in ("abs", "absolute") and args and not np.iscomplexobj(args[0]):
            return result                       # |x| of a real number is exact
        values = np.asarray(result)
        if np.dtype(values.dtype) not in _EXACT_TYPES or values.size == 0:
            return result
        exact = self._exact(args, kwargs)
        if values.dtype == np.complex128:
            parts = (exact.real, exact.imag) if exact is not None else (None, None)
            moved = self._moved(values.real, parts[0]) + 1j * self._moved(values.imag, parts[1])
        else:
            moved = self._moved(values, exact)
        return moved if isinstance(result, np.ndarray) else moved[()]


def nudged_functions(seed: int) -> dict[str, Nudged]:
    """numpy's functions :data:`NUDGED` wrapped, by name, with one generator seeded by ``seed``."""
    rng = np.random.default_rng(seed)
    found = {name: getattr(np, name) for name in NUDGED}
    return {name: function if isinstance(function, Nudged) else Nudged(name, function, rng)
            for name, function in found.items()}


def install(seed: int) -> None:
    """Replace numpy's functions :data:`NUDGED` by their nudged wrappers, directions from ``seed``."""
    for name, function in nudged_functions(seed).items():
        setattr(np, name, function)


def kernel_environment(seed: int, folder: pathlib.Path) -> dict[str, str]:
    """The environment in which every IPython kernel started (nbval's) runs nudged with ``seed``:
    an IPython startup file in ``folder`` (a fresh ``IPYTHONDIR``) that imports this module."""
    startup = folder / "profile_default" / "startup"
    startup.mkdir(parents=True, exist_ok=True)
    (startup / "00-nudge-numpy.py").write_text(
        f"import sys\nsys.path.insert(0, {str(pathlib.Path(__file__).resolve().parent)!r})\n"
        "import nudge_numpy\nsys.path.pop(0)\n")
    return dict(os.environ, IPYTHONDIR=str(folder), **{SEED_VARIABLE: str(seed)})


if os.environ.get(SEED_VARIABLE, "").strip():
    install(int(os.environ[SEED_VARIABLE]))


if __name__ == "__main__" and len(sys.argv) >= 2:
    with tempfile.TemporaryDirectory() as folder:
        environment = kernel_environment(int(sys.argv[1]), pathlib.Path(folder))
        sys.exit(subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:randomly", "--tb=short",
                                 *sys.argv[2:]], cwd=pathlib.Path(__file__).resolve().parent.parent,
                                env=environment).returncode)
