"""Shipped study results against their study files and a fresh solve.

The fast test checks that each shipped study Dataset (assets/studies/results/<study>.study.nc) was
made from its study file as it is now: its ``results_fingerprint`` covers every point's case
values, the models and ``solver.RESULTS_VERSION``. The slow test solves every finished
quasi-static point again and the dynamic run of the last point of each sweep (the sweep's far
end; the whole set of dynamic runs would take CI many minutes), and compares the metrics a study
keeps: a change that moves them must bump RESULTS_VERSION (and regenerate the files with
tools/make_study_results.py).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import solver
from solver.study.worker import run_one

STUDIES = Path(__file__).resolve().parents[2] / "assets" / "studies"
STUDY_FILES = sorted(STUDIES.glob("*.toml"))
REGENERATE = "python tools/make_study_results.py"

#: Relative agreement of a quasi-static metric (a deterministic Newton solve).
QUASISTATIC_RTOL = 1e-6
#: Relative agreement of a dynamic metric that averages over the analysed window (an explicit run
#: of a few revolutions moves by a few tenths of a percent with rounding-level changes).
DYNAMIC_RTOL = 2e-2
#: The dynamic metrics compared: window means and extremes. Peak-to-peak measures of a short run
#: (excursion, band thickness and width) and the settling time follow the transient and are not.
DYNAMIC_METRICS = ("mean_contact_angle", "peak_pressure", "largest_load", "cage_slip")


def _shipped(study_file: Path):
    path = STUDIES / "results" / f"{study_file.stem}.study.nc"
    assert path.is_file(), f"{path.name} is missing: run {REGENERATE}"
    return solver.load_dataset(path)


def test_every_shipped_study_has_its_results():
    assert STUDY_FILES, "no shipped study found"
    names = {f"{p.stem}.study.nc" for p in STUDY_FILES}
    kept = {p.name for p in (STUDIES / "results").glob("*.study.nc")}
    assert kept == names, f"shipped study results {sorted(kept)} do not match {sorted(names)}"


@pytest.mark.parametrize("study_file", STUDY_FILES, ids=lambda p: p.stem)
def test_shipped_study_is_current(study_file):
    shipped = _shipped(study_file)
    study = solver.Study.from_file(study_file)
    assert shipped.attrs.get("results_fingerprint") == study.fingerprint(), (
        f"{study_file.stem}.study.nc was not made from {study_file.name} and results version "
        f"{solver.RESULTS_VERSION} as they are now: run {REGENERATE}"
    )
    assert int(shipped.attrs["results_version"]) == solver.RESULTS_VERSION
    assert list(shipped["point"].values) == [p.name for p in study.points()]


def _compare(name, model, shipped_value, fresh_value, scale, rtol, where) -> None:
    if math.isnan(shipped_value):
        assert math.isnan(fresh_value), f"{where}: {name} is {fresh_value}, shipped NaN"
        return
    moved = abs(fresh_value - shipped_value) / scale
    assert moved <= rtol, (
        f"{where}: {model} {name} moved from {shipped_value:.6g} to {fresh_value:.6g} "
        f"({moved:.2e} of its largest value, allowed {rtol:g}) while solver.RESULTS_VERSION is "
        f"still {solver.RESULTS_VERSION}: if the change is meant, bump RESULTS_VERSION in "
        f"solver/results/provenance.py and run {REGENERATE}"
    )


@pytest.mark.slow
@pytest.mark.parametrize("study_file", STUDY_FILES, ids=lambda p: p.stem)
def test_shipped_study_matches_a_fresh_solve(study_file):
    shipped = _shipped(study_file)
    study = solver.Study.from_file(study_file)
    checked = 0
    points = study.points()
    last_of_sweep = {p.sweep: p.name for p in points}  # the last point of each sweep
    for point in points:
        for model in point.models:
            row = shipped.sel(point=point.name, model=model)
            if str(row["status"].values) != "done":
                continue
            if model == "dynamic" and last_of_sweep[point.sweep] != point.name:
                continue
            record, _ds = run_one(point.case, model)
            where = f"{study_file.stem} {point.name} ({point.label()})"
            assert record["status"] == "done", f"{where}: {model} now fails: {record['message']}"
            # a quasi-static point keeps the metrics of one bearing, or those of a bearing set
            names = DYNAMIC_METRICS if model == "dynamic" else tuple(record["metrics"])
            rtol = DYNAMIC_RTOL if model == "dynamic" else QUASISTATIC_RTOL
            for name in names:
                fresh = record["metrics"][name]
                column = shipped[name].sel(model=model)
                finite = np.abs(column.values[np.isfinite(column.values)])
                scale = float(finite.max()) if finite.size and finite.max() > 0 else 1.0
                if isinstance(fresh, dict):  # per race, or per bearing of a set
                    dim = "race" if "race" in shipped[name].dims else "bearing"
                    for label, value in fresh.items():
                        shipped_value = float(row[name].sel({dim: label}))
                        _compare(name, model, shipped_value, value, scale, rtol, f"{where} {label}")
                else:
                    _compare(name, model, float(row[name]), float(fresh), scale, rtol, where)
            checked += 1
    assert checked, f"{study_file.stem}: no finished point to check"


#: The columns of the speed table of ``spindle-pair-db-speed`` in docs/studies.md: the study
#: variable each column prints, the bearing it takes (None: the set's), and the factor from the
#: variable's SI unit to the column's unit.
PAIR_SPEED_COLUMNS = (
    ("bearing_axial_load", 0, 1.0),  # Fa front N
    ("bearing_axial_load", 1, 1.0),  # Fa rear N
    ("axial_stiffness", None, 1e-6),  # N/m -> N/µm
    ("radial_stiffness", None, 1e-6),  # N/m -> N/µm
    ("tilt_stiffness", None, 1e-3),  # N m/rad -> N m/mrad
)


def _pair_speed_table() -> list[list[str]]:
    """The rows (cells as text) of the speed table of ``spindle-pair-db-speed`` in
    docs/studies.md."""
    text = (Path(__file__).resolve().parents[2] / "docs" / "studies.md").read_text("utf-8")
    header = (
        "| preload | speed rpm | Fa front N | Fa rear N | k_ax N/µm | k_rad N/µm "
        "| k_tilt N m/mrad |"
    )
    assert header in text, "the speed table of spindle-pair-db-speed is not in docs/studies.md"
    rows = []
    for line in text.split(header, 1)[1].splitlines()[2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip("|").split("|")])
    return rows


def test_the_pair_speed_table_in_the_docs_is_the_shipped_study():
    """Each number of the table, in its column's unit, is the shipped study's value to the
    digits printed (within half a unit of its third significant digit)."""
    shipped = _shipped(STUDIES / "spindle-pair-db-speed.toml").sel(model="quasistatic")
    sweeps = [str(s) for s in shipped["sweep"].values]
    speeds = shipped["operating.inner_ring_speed_rpm"].values
    rows = _pair_speed_table()
    assert len(rows) == 8
    for preload, speed, *cells in rows:
        word = preload.split()[0].rstrip(",")  # light, medium, heavy or spring
        match = [
            i
            for i, sweep in enumerate(sweeps)
            if word in sweep
            and speeds[i] == float(speed.replace(" ", ""))
            and ("fixed" in preload) == ("fixed position" in sweep)
        ]
        assert len(match) == 1, (preload, speed, match)
        point = shipped.isel(point=match[0])
        for cell, (name, bearing, factor) in zip(cells, PAIR_SPEED_COLUMNS, strict=True):
            value = point[name] if bearing is None else point[name].isel(bearing=bearing)
            assert float(cell) == pytest.approx(float(value) * factor, rel=5.1e-3), (
                preload,
                speed,
                name,
            )
