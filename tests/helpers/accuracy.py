"""Accuracy contract of the dynamic model's integration methods (issue 13, docs/numerics.md).

Four short runs, integrated once with the explicit Dormand–Prince method at tolerance 1e-6 and
kept as test data (``tests/data/dynamic_reference.json``); a run with any method is compared with
them metric by metric. Regenerate the data (a few minutes) with

    python -m tests.helpers.accuracy

Metrics of a run (over the analysed window of its stored summary): per (ball, race) time-mean
contact angle [deg] and load [N], the mean cage speed [rad/s], and each race's trajectory excursion
and band thickness [deg] in its own ring's frame.

A case whose short-run metrics two reference-quality runs do not reproduce (the 218 heavy case)
is also kept as a long run compared over a fixed window (``LONG_WINDOW_CASES``), on the metrics
that such runs do reproduce there.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions, simulate
from solver.results.summary import summary, track_metrics

REFERENCE_FILE = Path(__file__).resolve().parents[1] / "data" / "dynamic_reference.json"
REFERENCE_TOLERANCE = 1e-6
REFERENCE_METHOD = "dopri5"

#: the contract: contact angles [deg], loads (relative), cage speed (relative), excursion and band
#: thickness (relative, or absolute [deg] whichever is larger)
ANGLE_DEG = 0.005
LOAD_RELATIVE = 0.002
CAGE_RELATIVE = 0.0005
TRACK_RELATIVE = 0.02
TRACK_DEG = 0.002

#: case label -> (catalogue case, operating changes (SI), shaft revolutions)
CASES = {
    "spindle_combined": ("spindle-combined-load", {}, 3.0),
    "heavy_218": ("218-heavy-combined", {}, 3.0),
    "misalignment_ring": ("spindle-misalignment-ring", {}, 3.0),
    # light axial preload at high speed: the balls start to skid (spin-to-roll and slip rise)
    "light_high_speed": (
        "spindle-axial-preload",
        {"axial_load": 40.0, "inner_ring_speed": 40000.0 * math.pi / 30.0},
        3.0,
    ),
}


#: cases whose short-run metrics are not reproducible to the contract's precision (two reference-
#: quality runs differ by more than the allowances, docs/numerics.md): label -> (shaft revolutions,
#: first revolution of the window, the metrics that such runs do reproduce over that window)
LONG_WINDOW_CASES = {
    "heavy_218": (30.0, 10.0, ("contact_angle", "contact_load", "cage_speed")),
}
#: Allowances of a long-window case, as multiples of the contract's, where two reference-quality
#: runs disagree by more than the contract allows. The 218 heavy case with the thermally softened
#: traction (its most loaded ball slides): per-ball mean contact angles over revolutions 10-30 at
#: tolerance 3e-6 against 1e-6 differ by 1.16 x ANGLE_DEG (0.0058 deg), at the default 1e-4 by
#: 1.33 x; the allowance is twice the reference runs' own spread.
LONG_WINDOW_ALLOWANCE = {"heavy_218": {"contact_angle": 2.0}}


def case_inputs(label):
    """SI inputs of a contract case."""
    name, changes, _ = CASES[label]
    inputs = to_inputs(resolve_case(name))
    if changes:
        inputs = replace(inputs, operating=replace(inputs.operating, **changes))
    return inputs


def run(label, **option_changes):
    """The Dataset of a contract case with the given options."""
    revolutions = CASES[label][2]
    options = SimulationOptions(
        shaft_revolutions=revolutions, samples_per_revolution=180, **option_changes
    )
    return simulate(case_inputs(label), options=options)


def metrics(ds) -> dict:
    """The compared metrics of a run (plain floats and lists, JSON-ready)."""
    metric = summary(ds)
    start = float(metric["analysis_start_time"])
    window = ds.sel(time=ds["time"] >= start)
    return {
        "contact_angle_deg": window["contact_angle"].mean("time").values.tolist(),
        "contact_load_N": window["contact_load"].mean("time").values.tolist(),
        "cage_speed_rad_s": float(window["cage_speed"].mean("time")),
        "excursion_deg": ds.racetrace.metric("excursion").values.tolist(),
        "band_thickness_deg": ds.racetrace.metric("band_thickness").values.tolist(),
        "analysis_start_time_s": start,
        "steps": int(ds.attrs["steps"]),
        "rhs_evaluations": int(ds.attrs["rhs_evaluations"]),
    }


def window_metrics(ds, start_time: float) -> dict:
    """The contract's metrics over the samples at or after ``start_time`` [s] (a fixed window, the
    same for every run of a case, instead of each run's own analysis window)."""
    window = ds.sel(time=ds["time"] >= start_time - 1e-12)
    angle = window["contact_angle"].values
    azimuth = window["raceway_azimuth"].values
    load = window["contact_load"].values
    excursion, band = [], []
    for race in range(2):
        loaded = load[:, race, :] > 0.0
        e, b = track_metrics(azimuth[:, race, :][loaded], angle[:, race, :][loaded])
        excursion.append(e)
        band.append(b)
    return {
        "contact_angle_deg": window["contact_angle"].mean("time").values.tolist(),
        "contact_load_N": window["contact_load"].mean("time").values.tolist(),
        "cage_speed_rad_s": float(window["cage_speed"].mean("time")),
        "excursion_deg": excursion,
        "band_thickness_deg": band,
    }


def shaft_period(label) -> float:
    """Time of one shaft revolution [s] of a contract case."""
    op = case_inputs(label).operating
    return 2.0 * math.pi / abs(op.inner_ring_speed - op.outer_ring_speed)


def long_run(label, **option_changes):
    """(metrics over the fixed window, Dataset) of a long-window case with the given options."""
    revolutions, first, _ = LONG_WINDOW_CASES[label]
    options = SimulationOptions(
        shaft_revolutions=revolutions, samples_per_revolution=180, **option_changes
    )
    ds = simulate(case_inputs(label), options=options)
    return window_metrics(ds, first * shaft_period(label)), ds


def deviations(got: dict, ref: dict) -> dict:
    """Each metric's worst deviation as a fraction of its allowance (<= 1 meets the contract)."""
    angle = np.abs(np.subtract(got["contact_angle_deg"], ref["contact_angle_deg"])) / ANGLE_DEG
    ref_load = np.asarray(ref["contact_load_N"])
    load_scale = LOAD_RELATIVE * np.maximum(np.abs(ref_load), 1e-3 * np.abs(ref_load).max())
    load = np.abs(np.asarray(got["contact_load_N"]) - ref_load) / load_scale
    cage = abs(got["cage_speed_rad_s"] - ref["cage_speed_rad_s"]) / (
        CAGE_RELATIVE * abs(ref["cage_speed_rad_s"])
    )
    out = {
        "contact_angle": float(angle.max()),
        "contact_load": float(load.max()),
        "cage_speed": float(cage),
    }
    for key in ("excursion_deg", "band_thickness_deg"):
        r = np.asarray(ref[key])
        allow = np.maximum(TRACK_RELATIVE * np.abs(r), TRACK_DEG)
        out[key.removesuffix("_deg")] = float((np.abs(np.asarray(got[key]) - r) / allow).max())
    return out


def load_reference() -> dict:
    return json.loads(REFERENCE_FILE.read_text())


def write_reference(path: Path, data: dict) -> None:
    """Write reference test data as indented JSON, atomically (a temporary file replaced)."""
    path.parent.mkdir(exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1) + "\n")
    tmp.replace(path)


def main():  # pragma: no cover - regenerates the test data
    data = {
        "method": REFERENCE_METHOD,
        "tolerance": REFERENCE_TOLERANCE,
        "samples_per_revolution": 180,
        "cases": {},
    }
    for label in CASES:
        ds = run(label, method=REFERENCE_METHOD, tolerance=REFERENCE_TOLERANCE)
        data["cases"][label] = metrics(ds)
        print(label, "steps", ds.attrs["steps"], "wall", ds.attrs["wall_time_s"], flush=True)
    data["long_window"] = {}
    for label, (revolutions, first, _) in LONG_WINDOW_CASES.items():
        got, ds = long_run(label, method=REFERENCE_METHOD, tolerance=REFERENCE_TOLERANCE)
        data["long_window"][label] = dict(
            got, revolutions=revolutions, window_start_revolution=first
        )
        print(label, revolutions, "revolutions: steps", ds.attrs["steps"], flush=True)
    write_reference(REFERENCE_FILE, data)


if __name__ == "__main__":  # pragma: no cover
    main()
