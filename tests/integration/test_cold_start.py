"""The kernels a cold start compiles (empty numba cache): each shared kernel once, whatever the
model or the call site (benchmarks/cold_start.py: the app's warm-up, then a first dynamic run)."""

from __future__ import annotations

import json
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: Kernels whose call sites once differed only in argument types (arrays vs tuples of floats,
#: literal vs plain ints and bools), each compiled several times.
ONCE = [
    "solver.physics.traction.ellipse_traction_into",
    "solver.physics.rheology.contact_constants",
    "solver.models.quasistatic.kernels._static_excess",
    "solver.models.quasistatic.kernels._bisect_component",
    "solver.models.quasistatic.kernels.ring_residual_and_jacobian",
    "solver.models.dynamic.kernels.rhs_into",
    "solver.models.dynamic.integrate.dopri5.dp5_accept",
    "solver.models.dynamic.integrate.imex.ark_accept",
    "solver.models.dynamic.integrate.control.rejected",
]


@pytest.mark.slow
def test_a_cold_start_compiles_each_shared_kernel_once(tmp_path):
    figures = tmp_path / "cold.json"
    command = [sys.executable, str(ROOT / "benchmarks" / "cold_start.py"), "--json", str(figures)]
    subprocess.run(command, check=True, capture_output=True, timeout=1800)
    phases = json.loads(figures.read_text())
    variants = Counter(name for phase in phases.values() for name, *_ in phase["records"])
    assert {name: variants[name] for name in ONCE} == dict.fromkeys(ONCE, 1)
