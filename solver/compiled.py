"""Whether numba's cache already holds the compiled kernels of a model (a "cold" cache makes the
first run of a fresh install compile for several seconds before its first step)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

# (module file stem, function) of a kernel compiled only for the dynamic model: the stepper of
# the default method "auto" (solver.models.dynamic.integrate.imex)
DYNAMIC_KERNEL = ("imex", "advance")


def kernel_cached(module_stem: str, function: str) -> bool:
    """True if the numba cache folder in use (``NUMBA_CACHE_DIR``, set on ``import solver``)
    holds an index for ``function`` of module ``module_stem`` for this Python version."""
    folder = os.environ.get("NUMBA_CACHE_DIR")
    if not folder or not Path(folder).is_dir():
        return False
    version = f"py{sys.version_info.major}{sys.version_info.minor}"
    pattern = f"{module_stem}.{function}-*.{version}.nbi"
    return next(Path(folder).rglob(pattern), None) is not None


def dynamic_model_compiled() -> bool:
    """Whether the dynamic model's kernels are compiled already (False: the first run compiles)."""
    import solver  # noqa: F401 - configures NUMBA_CACHE_DIR

    return kernel_cached(*DYNAMIC_KERNEL)
