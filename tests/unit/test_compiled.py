"""solver.compiled: whether numba's cache holds a model's kernels (a cold cache compiles first)."""

from __future__ import annotations

import sys

from solver import compiled


def test_kernel_found_only_in_the_cache_in_use(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert not compiled.kernel_cached(*compiled.DYNAMIC_KERNEL)
    version = f"py{sys.version_info.major}{sys.version_info.minor}"
    folder = tmp_path / "dynamic_0123"
    folder.mkdir()
    stem, function = compiled.DYNAMIC_KERNEL
    (folder / f"{stem}.{function}-85.py27.nbi").touch()  # another Python's index: not ours
    assert not compiled.kernel_cached(*compiled.DYNAMIC_KERNEL)
    (folder / f"{stem}.{function}-85.{version}.nbi").touch()
    assert compiled.kernel_cached(*compiled.DYNAMIC_KERNEL)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "missing"))
    assert not compiled.kernel_cached(*compiled.DYNAMIC_KERNEL)


def test_the_dynamic_kernel_is_the_default_methods_stepper():
    """The kernel looked for is the ``advance`` of the default method's stepper module."""
    from solver.models.dynamic.integrate.registry import REGISTRY
    from solver.models.dynamic.options import SimulationOptions

    module, _ = REGISTRY[SimulationOptions().method]
    assert compiled.DYNAMIC_KERNEL == (module, "advance")
