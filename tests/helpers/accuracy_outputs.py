"""Accuracy contract of the outputs a design review signs (docs/numerics.md, "Accuracy contract"):
friction torque, drive power, losses by source, cage speed and mean contact angles of shipped
cases at the default settings against tight runs (tolerance :data:`REFERENCE_TOLERANCE`) kept as
test data (``tests/data/accuracy_reference.json``), and the energy-balance residual of each run.

Every figure is a mean over the run's own analysed window (``analysis_start_time`` to the end,
solver.results.summary). Regenerate the data (several minutes) with

    python -m tests.helpers.accuracy_outputs
"""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions, simulate

from .accuracy import write_reference

REFERENCE_FILE = Path(__file__).resolve().parents[1] / "data" / "accuracy_reference.json"
REFERENCE_TOLERANCE = 1e-5
#: shipped cases checked, each at its own [simulation] settings (10 shaft revolutions)
CASES = ("209-radial", "spindle-combined-load", "218-heavy-combined")
#: the contract: friction torque and total losses within 2 % of the tight run, mean cage speed
#: within 0.1 %, energy balance within 1 %
TORQUE_RELATIVE = 0.02
LOSS_RELATIVE = 0.02
CAGE_RELATIVE = 0.001
RESIDUAL_LIMIT = 0.01


def run(name: str, **option_changes):
    """The Dataset of shipped case ``name`` at its own settings with the given options."""
    return simulate(to_inputs(resolve_case(name)), options=SimulationOptions(**option_changes))


def outputs(ds) -> dict:
    """The contract's outputs of a run over its analysed window (plain floats, JSON-ready)."""
    metric = ds.racetrace.metric
    start = float(metric("analysis_start_time"))
    window = ds.sel(time=ds["time"] >= start)
    sources = [str(s) for s in window["loss_source"].values]
    by_source = window["power_loss"].mean("time").values
    return {
        "friction_torque_N_m": float(window["friction_torque"].mean()),
        "drive_power_W": float(window["drive_power"].mean()),
        "total_power_loss_W": float(window["total_power_loss"].mean()),
        "power_loss_W": dict(zip(sources, (float(v) for v in by_source), strict=True)),
        "cage_speed_rad_s": float(metric("mean_cage_speed")),
        "mean_contact_angle_deg": [float(v) for v in metric("mean_contact_angle").values],
        "energy_balance_residual": float(metric("energy_balance_residual")),
        "analysis_start_time_s": start,
        "end_time_s": float(ds["time"].values[-1]),
        "steps": int(ds.attrs["steps"]),
    }


def deviation(got: dict, reference: dict, key: str = "friction_torque_N_m") -> float:
    """Relative deviation of output ``key`` from the reference's."""
    ref = reference[key]
    return abs(got[key] - ref) / abs(ref)


def load_reference() -> dict:
    return json.loads(REFERENCE_FILE.read_text())


def _commit() -> str:  # pragma: no cover - provenance of the regenerated data
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=True
        )
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main():  # pragma: no cover - regenerates the test data
    data = {
        "made_with": (
            "python -m tests.helpers.accuracy_outputs: each shipped case at its own [simulation] "
            f"settings, default method, tolerance {REFERENCE_TOLERANCE:g}; means over each run's "
            "analysed window"
        ),
        "commit": _commit(),
        "tolerance": REFERENCE_TOLERANCE,
        "cases": {},
    }
    for name in CASES:
        ds = run(name, tolerance=REFERENCE_TOLERANCE)
        got = outputs(ds)
        if not math.isfinite(got["friction_torque_N_m"]):
            raise SystemExit(f"{name}: no finite friction torque")
        data["cases"][name] = got
        print(name, json.dumps(got), flush=True)
    write_reference(REFERENCE_FILE, data)


if __name__ == "__main__":  # pragma: no cover
    main()
