"""The quasi-static Dataset of the speed benchmark's four configurations (benchmarks/quasistatic.py:
the 218 heavy case and the spindle, each with both ball-speed rules) as plain JSON-ready data, and
the reference kept as test data (``tests/data/quasistatic_reference.json``).

The reference holds every variable, coordinate and attribute (values, dims, dtype, attributes),
all but the ``created`` timestamp; floats are written with repr, so they read back bit for bit.
Floats are compared within :data:`TOLERANCE` of the largest magnitude in their variable (a value
near zero, such as an offset that is zero by symmetry, counts at the scale of its variable), and
the attributes that describe the path of the iteration (:data:`PATH_ATTRS`) are not compared: a
change that only makes the solve faster (another start, fewer iterations) may move the solution
within the solver's convergence tolerance but no further. A change of the physics or of the schema
regenerates the reference with

    python -m tests.helpers.quasistatic_reference
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.quasistatic import solve_quasistatic
from solver.models.quasistatic.solver import RING_TOLERANCE, TRACTION_SPEED_TOLERANCE

REFERENCE_FILE = Path(__file__).resolve().parents[1] / "data" / "quasistatic_reference.json"
CASES = ("218-heavy-combined", "spindle-combined-load")
RULES = ("traction", "race_control")
#: attributes that differ between two solves of the same case
VOLATILE_ATTRS = ("created",)
#: attributes that describe how the iteration got to the solution (the number of iterations, the
#: residual it stopped at, the note saying after how many fixed-point iterations): they change with
#: the start and the path; ``solver_residual`` is checked to be within the ring tolerance instead
PATH_ATTRS = ("solver_iterations", "solver_residual", "race_control_note")
#: Largest difference of a float from the reference, relative to the largest magnitude in its
#: variable. The loosest convergence criterion of the solve is the traction balance's fixed point:
#: it stops when the ball speeds (relative to the ring speed) and attitudes [rad] are within
#: TRACTION_SPEED_TOLERANCE of the limit (the ring equilibrium, RING_TOLERANCE, is tighter). Two
#: solves that each stop within it differ by up to twice it, and a rating life (load to the power
#: -3, or -10/3 for a raceway) multiplies a relative change of the loads by up to 10/3: 2 x 10/3 <
#: 10.
TOLERANCE = 10.0 * TRACTION_SPEED_TOLERANCE


def configurations() -> list[tuple[str, str]]:
    """``(case name, ball-speed rule)`` of each configuration."""
    return [(name, rule) for name in CASES for rule in RULES]


def configuration_key(name: str, rule: str) -> str:
    return f"{name}/{rule}"


def inputs_with_rule(name: str, rule: str):
    """The SI inputs of catalogue case ``name`` with ``simulation.quasistatic_ball_speeds``."""
    inputs = to_inputs(resolve_case(name))
    simulation = dataclasses.replace(inputs.simulation, quasistatic_ball_speeds=rule)
    return dataclasses.replace(inputs, simulation=simulation)


def _plain(value):
    """A JSON-ready copy of an attribute value or an array element list."""
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def _array(variable) -> dict:
    values = np.asarray(variable.values)
    return {
        "dims": list(variable.dims),
        "dtype": values.dtype.str,
        "values": _plain(values),
        "attrs": {key: _plain(v) for key, v in variable.attrs.items()},
    }


def describe(ds) -> dict:
    """Every variable, coordinate and attribute of ``ds`` but the volatile ones, JSON-ready."""
    return {
        "data_vars": {name: _array(ds[name].variable) for name in ds.data_vars},
        "coords": {name: _array(ds.coords[name].variable) for name in ds.coords},
        "attrs": {k: _plain(v) for k, v in ds.attrs.items() if k not in VOLATILE_ATTRS},
    }


def load_reference() -> dict:
    return json.loads(REFERENCE_FILE.read_text())


def _floats(value) -> list[float]:
    """The floats of a nested list (or of a float)."""
    if isinstance(value, float):
        return [value]
    if isinstance(value, list):
        return [x for v in value for x in _floats(v)]
    return []


def _close(got, want, tolerance: float) -> bool:
    """``got`` equals ``want`` (nested lists alike), floats within ``tolerance`` (absolute)."""
    if isinstance(want, float) and isinstance(got, float):
        if math.isnan(want):
            return math.isnan(got)
        return got == want or abs(got - want) <= tolerance
    if isinstance(want, list) and isinstance(got, list):
        return len(got) == len(want) and all(
            _close(g, w, tolerance) for g, w in zip(got, want, strict=True)
        )
    return type(got) is type(want) and got == want


def differences(got: dict, want: dict, relative: float = TOLERANCE, where: str = "") -> list[str]:
    """Where ``got`` (a :func:`describe` result) differs from ``want``: keys missing or extra,
    a string, integer or dtype not equal, a float more than ``relative`` times the largest
    magnitude of its variable's values (of the value itself for an attribute) apart. The
    attributes of :data:`PATH_ATTRS` are not compared; ``solver_residual`` must be within
    RING_TOLERANCE."""
    if isinstance(want, dict) and isinstance(got, dict):
        found = []
        for key in sorted(set(want) | set(got)):
            path = f"{where}/{key}"
            if where == "/attrs" and key in PATH_ATTRS:
                if key == "solver_residual" and not got.get(key, math.inf) <= RING_TOLERANCE:
                    found.append(f"{path}: {got.get(key)} above the ring tolerance")
                continue
            if key not in got:
                found.append(f"{path}: missing")
            elif key not in want:
                found.append(f"{path}: not in the reference")
            else:
                found.extend(differences(got[key], want[key], relative, path))
        return found
    magnitudes = [abs(x) for x in _floats(want) + _floats(got) if math.isfinite(x)]
    if _close(got, want, relative * max(magnitudes, default=0.0)):
        return []
    return [f"{where}: {str(got)[:120]} != reference {str(want)[:120]}"]


def build() -> dict:
    """The described Dataset of every configuration."""
    return {
        configuration_key(name, rule): describe(solve_quasistatic(inputs_with_rule(name, rule)))
        for name, rule in configurations()
    }


if __name__ == "__main__":  # pragma: no cover - regenerates the test data
    REFERENCE_FILE.write_text(json.dumps(build(), indent=1, sort_keys=True) + "\n")
    print(f"wrote {REFERENCE_FILE}")
