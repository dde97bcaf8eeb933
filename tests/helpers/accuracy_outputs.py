"""Accuracy contract of the outputs a design review signs (docs/numerics.md, "Accuracy contract of
the outputs"): every output of a run at the default settings against a tight run of the same case
(tolerance :data:`REFERENCE_TOLERANCE`) kept as test data (``tests/data/accuracy_reference.json``),
and the energy-balance residual of each run.

The cases (:data:`CASES`): every shipped case (assets/cases: the 209 radial, the 218 heavy
combined, the hybrid spindle under axial preload, combined load and a misalignment fixed in space
and turning with the ring), and a light-load high-speed hybrid that is not shipped (the
7008C-class hybrid spindle at 60 N axial preload and 40 000 rpm), each at its own
``[simulation]`` settings.

Every figure is a mean over the window of the run's energy balance
(:func:`solver.results.energy.balance_start_time`: the analysed window, and never the first shaft
revolution, where the run rings down from its quasi-static start). Regenerate the data (every
case in one go; 3.2 min of CPU with compiling the kernels, each case but the 209 3-5 s) with

    python -m tests.helpers.accuracy_outputs
"""

from __future__ import annotations

import json
import math
import subprocess
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions, simulate
from solver.results.energy import balance_start_time
from solver.results.loaded import loaded_mask

from .accuracy import write_reference

REFERENCE_FILE = Path(__file__).resolve().parents[1] / "data" / "accuracy_reference.json"
REFERENCE_TOLERANCE = 1e-5

#: case label -> (catalogue case, operating changes (SI), what kind of case it is)
CASES = {
    "209-radial": ("209-radial", {}, "radial deep groove, rheology"),
    "spindle-combined-load": ("spindle-combined-load", {}, "hybrid spindle, combined load"),
    "218-heavy-combined": ("218-heavy-combined", {}, "heavy 40 deg, combined load"),
    "spindle-misalignment-ring": (
        "spindle-misalignment-ring",
        {},
        "hybrid spindle, 0.05 deg misalignment turning with the ring",
    ),
    "spindle-misalignment-space": (
        "spindle-misalignment-space",
        {},
        "hybrid spindle, 0.05 deg misalignment fixed in space",
    ),
    "spindle-axial-preload": ("spindle-axial-preload", {}, "hybrid spindle, axial preload"),
    # not shipped: the light preload at the top of the speed range, where the outer contact angle
    # falls to about 2 deg under the centrifugal force
    "spindle-light-high-speed": (
        "spindle-axial-preload",
        {"axial_load": 60.0, "inner_ring_speed": 40000.0 * math.pi / 30.0},
        "hybrid spindle, light load (60 N axial) at high speed (40 000 rpm)",
    ),
}

#: The contract, each output's allowance against the tight run: friction torque, drive power and
#: total losses within 2 %; each loss source within 2 % of the total losses; mean cage speed
#: within 0.1 %; per (ball, race) mean contact angle within 0.005 deg and mean contact load within
#: 0.2 % (of the load, or of 1e-3 of the largest load for a nearly unloaded contact); each race's
#: mean spin-to-roll ratio within 1 % or 5e-4, whichever is larger. The energy balance closes
#: within 1 % of the losses.
TORQUE_RELATIVE = 0.02
POWER_RELATIVE = 0.02
LOSS_RELATIVE = 0.02
SOURCE_RELATIVE = 0.02
CAGE_RELATIVE = 0.001
ANGLE_DEG = 0.005
LOAD_RELATIVE = 0.002
SPIN_RELATIVE = 0.01
SPIN_ABSOLUTE = 5e-4
RESIDUAL_LIMIT = 0.01
#: Allowances of a case, as multiples of the contract's, where two reference-quality runs disagree
#: by more than the contract allows: the 218 heavy case (unsettled, its most loaded ball slides)
#: has per-ball mean contact angles at tolerance 3e-6 and 1e-5 3.33 x ANGLE_DEG (0.017 deg) apart,
#: at the default 1e-4 3.97 x; no tolerance reproduces them closer, and the allowance is twice the
#: reference runs' own spread (as the trajectory contract's long window, tests/helpers/accuracy.py).
#: Its per-ball mean contact loads of two tolerance-1e-5 runs (the stored reference and a run of the
#: same case after the operating-history change of the right-hand side, which reorders its
#: arithmetic) are 0.89 x LOAD_RELATIVE apart: the load allowance is twice that.
CASE_ALLOWANCE = {"218-heavy-combined": {"contact_angle": 6.7, "contact_load": 1.8}}


def case_inputs(label: str):
    """SI inputs of contract case ``label``."""
    name, changes, _ = CASES[label]
    inputs = to_inputs(resolve_case(name))
    if changes:
        inputs = replace(inputs, operating=replace(inputs.operating, **changes))
    return inputs


def run(label: str, **option_changes):
    """The Dataset of contract case ``label`` at its own settings with the given options."""
    return simulate(case_inputs(label), options=SimulationOptions(**option_changes))


def outputs(ds, start_time: float | None = None) -> dict:
    """The contract's outputs of a run over its energy-balance window, or from ``start_time`` [s]
    (a reference's window: runs at two tolerances may settle a revolution apart, and per-ball
    means over a load zone depend on the window) (plain floats and lists, JSON-ready;
    per-(ball, race) lists are [ball][race])."""
    start = balance_start_time(ds, float(ds.racetrace.metric("analysis_start_time")))
    if start_time is not None:
        start = start_time
    window = ds.sel(time=ds["time"] >= start - 1e-12 * max(abs(start), 1.0))
    sources = [str(s) for s in window["loss_source"].values]
    by_source = window["power_loss"].mean("time").values
    load = window["contact_load"].transpose("ball", "race", "time")
    angle = window["contact_angle"].transpose("ball", "race", "time")
    loaded = loaded_mask(load.values, angle.values)
    spin = window["spin_to_roll"].transpose("ball", "race", "time").values
    spin_means = [float(np.mean(spin[:, k, :][loaded[:, k, :]])) for k in range(2)]
    return {
        "friction_torque_N_m": float(window["friction_torque"].mean()),
        "drive_power_W": float(window["drive_power"].mean()),
        "total_power_loss_W": float(window["total_power_loss"].mean()),
        "power_loss_W": dict(zip(sources, (float(v) for v in by_source), strict=True)),
        "cage_speed_rad_s": float(window["cage_speed"].mean()),
        "contact_angle_deg": angle.mean("time").values.tolist(),
        "contact_load_N": load.mean("time").values.tolist(),
        "spin_to_roll": spin_means,
        "energy_balance_residual": float(ds.racetrace.metric("energy_balance_residual")),
        "window_start_time_s": float(window["time"].values[0]),
        "end_time_s": float(ds["time"].values[-1]),
        "steps": int(ds.attrs["steps"]),
    }


def deviation(got: dict, reference: dict, key: str = "friction_torque_N_m") -> float:
    """Relative deviation of scalar output ``key`` from the reference's."""
    ref = reference[key]
    return abs(got[key] - ref) / abs(ref)


def deviations(got: dict, reference: dict) -> dict:
    """Each output's worst deviation from the reference as a fraction of its allowance (<= 1
    meets the contract), and the energy-balance residual as a fraction of its limit."""
    total = reference["total_power_loss_W"]
    source_error = max(
        abs(got["power_loss_W"][s] - reference["power_loss_W"][s])
        for s in reference["power_loss_W"]
    )
    angle = np.abs(np.subtract(got["contact_angle_deg"], reference["contact_angle_deg"]))
    ref_load = np.asarray(reference["contact_load_N"])
    load_scale = LOAD_RELATIVE * np.maximum(np.abs(ref_load), 1e-3 * np.abs(ref_load).max())
    load = np.abs(np.asarray(got["contact_load_N"]) - ref_load) / load_scale
    ref_spin = np.asarray(reference["spin_to_roll"])
    spin_scale = np.maximum(SPIN_RELATIVE * np.abs(ref_spin), SPIN_ABSOLUTE)
    spin = np.abs(np.asarray(got["spin_to_roll"]) - ref_spin) / spin_scale
    return {
        "friction_torque": deviation(got, reference) / TORQUE_RELATIVE,
        "drive_power": deviation(got, reference, "drive_power_W") / POWER_RELATIVE,
        "total_power_loss": deviation(got, reference, "total_power_loss_W") / LOSS_RELATIVE,
        "power_loss_by_source": source_error / (SOURCE_RELATIVE * abs(total)),
        "cage_speed": deviation(got, reference, "cage_speed_rad_s") / CAGE_RELATIVE,
        "contact_angle": float(np.nanmax(angle)) / ANGLE_DEG,
        "contact_load": float(np.nanmax(load)),
        "spin_to_roll": float(spin.max()),
        "energy_balance_residual": abs(got["energy_balance_residual"]) / RESIDUAL_LIMIT,
    }


def within_contract(label: str, worst: dict) -> bool:
    """Whether the deviations ``worst`` (:func:`deviations`) of case ``label`` meet the contract
    with the case's allowances (:data:`CASE_ALLOWANCE`)."""
    allowance = CASE_ALLOWANCE.get(label, {})
    return all(value <= allowance.get(key, 1.0) for key, value in worst.items())


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
            "python -m tests.helpers.accuracy_outputs: each case of CASES at its own [simulation] "
            f"settings, default method, tolerance {REFERENCE_TOLERANCE:g}; means over each run's "
            "energy-balance window"
        ),
        "commit": _commit(),
        "tolerance": REFERENCE_TOLERANCE,
        "cases": {},
    }
    for label in CASES:
        began = time.process_time()
        ds = run(label, tolerance=REFERENCE_TOLERANCE)
        got = outputs(ds)
        if not math.isfinite(got["friction_torque_N_m"]):
            raise SystemExit(f"{label}: no finite friction torque")
        data["cases"][label] = got
        print(label, "steps", got["steps"], f"CPU {time.process_time() - began:.1f} s", flush=True)
    write_reference(REFERENCE_FILE, data)


if __name__ == "__main__":  # pragma: no cover
    main()
