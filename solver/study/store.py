"""The study folder: what a study run keeps on disk, written so that a stop loses nothing done.

Layout of ``DIR``::

    study.toml                     the study file as run (a resume must run the same study)
    study.json                     manifest: title, base case, varied keys, every point's values
    points/p0001.quasistatic.nc    full result of each finished run (results-schema.md)
    points/p0001.quasistatic.json  its record: status ("done" | "failed"), message, metrics, times
    study.nc                       the study Dataset (:func:`study_dataset`), rewritten at the end

Each result file is written atomically, then its record (also atomically): a record exists only
for a finished run, and a run whose record is missing is run again by a resume. Nothing here
runs a model (solver.study.runner does).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
import xarray as xr

from solver.errors import CaseError, Problem
from solver.results.io import atomic_write, load_dataset, save_dataset
from solver.results.summary import RACES

from .metrics import POINT_METRICS

STUDY_FILE = "study.toml"
MANIFEST = "study.json"
POINTS = "points"
DATASET = "study.nc"
MODEL_NAMES = ("quasistatic", "dynamic")
DONE, FAILED = "done", "failed"


def _json_value(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _json_value(v) for k, v in value.items()}
    if isinstance(value, np.generic):
        return _json_value(value.item())
    return value


def _write_json(path: Path, data) -> None:
    text = json.dumps(_json_value(data), indent=1, sort_keys=False)
    atomic_write(path, lambda tmp: Path(tmp).write_text(text + "\n", encoding="utf-8"))


def case_value(case, key: str):
    """The value of dotted case key ``key`` in ``case``: the value given, the default or the
    estimate the case uses (None when the key is absent and has none)."""
    value = case
    for part in key.split("."):
        value = getattr(value, part, None)
        if value is None:
            break
    else:
        return value
    value = case.to_dict()
    for part in key.split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value


class StudyFolder:
    """A study folder on disk (see the module docstring)."""

    def __init__(self, path):
        self.path = Path(path)

    @property
    def points_dir(self) -> Path:
        return self.path / POINTS

    def exists(self) -> bool:
        return (self.path / MANIFEST).is_file()

    def result_path(self, point: str, model: str) -> Path:
        return self.points_dir / f"{point}.{model}.nc"

    def record_path(self, point: str, model: str) -> Path:
        return self.points_dir / f"{point}.{model}.json"

    # ---- writing --------------------------------------------------------------------------------
    def start(self, spec, points, version: str, resume: bool) -> None:
        """Create the folder, or check that a resumed one holds the same study.

        CaseError (key ``output``) when the folder holds another study, or holds this one and
        ``resume`` is False."""
        if self.path.exists() and not self.path.is_dir():
            raise CaseError(Problem("output", f"{self.path} exists and is not a folder"))
        if self.exists():
            old = (self.path / STUDY_FILE).read_text(encoding="utf-8")
            if old != spec.text:
                raise CaseError(
                    Problem(
                        "output",
                        f"{self.path} holds another study (its study.toml differs): give another "
                        "--output folder",
                    )
                )
            if not resume:
                raise CaseError(
                    Problem(
                        "output",
                        f"{self.path} already holds this study: add --resume to run only the "
                        "points not finished, or give another --output folder",
                    )
                )
        elif self.path.is_dir() and any(self.path.iterdir()) and not resume:
            raise CaseError(
                Problem("output", f"{self.path} is not empty: give a new or empty --output folder")
            )
        self.points_dir.mkdir(parents=True, exist_ok=True)
        atomic_write(
            self.path / STUDY_FILE,
            lambda tmp: Path(tmp).write_text(spec.text, encoding="utf-8"),
        )
        keys = list(spec.varied_keys)
        manifest = {
            "title": spec.title,
            "description": spec.description,
            "base": spec.base,
            "software_version": version,
            "varied_keys": keys,
            "points": [
                {
                    "name": p.name,
                    "sweep": p.sweep,
                    "models": list(p.models),
                    "values": p.values,
                    "coordinates": {k: case_value(p.case, k) for k in keys},
                    "title": p.case.title,
                }
                for p in points
            ],
        }
        _write_json(self.path / MANIFEST, manifest)

    def save_run(self, point: str, model: str, record: dict, ds: xr.Dataset | None) -> None:
        """Save one finished run: its result (when there is one), then its record."""
        record = dict(record)
        if ds is not None:
            start = time.perf_counter()
            save_dataset(ds, self.result_path(point, model))
            record["result"] = f"{POINTS}/{point}.{model}.nc"
            record["write_time_s"] = time.perf_counter() - start
        _write_json(self.record_path(point, model), record)

    def save_dataset(self) -> Path:
        return save_dataset(study_dataset(self), self.path / DATASET)

    # ---- reading --------------------------------------------------------------------------------
    def manifest(self) -> dict:
        path = self.path / MANIFEST
        if not path.is_file():
            raise CaseError(
                Problem(
                    "study",
                    f"{self.path} is not a study folder (no {MANIFEST}): give the --output folder "
                    "of a racetrace study run",
                )
            )
        return json.loads(path.read_text(encoding="utf-8"))

    def record(self, point: str, model: str) -> dict | None:
        path = self.record_path(point, model)
        if not path.is_file():
            return None
        try:
            return json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None  # unreadable record: the run counts as not finished

    def finished(self) -> dict[tuple[str, str], dict]:
        """``{(point, model): record}`` of every finished run."""
        out = {}
        for entry in self.manifest()["points"]:
            for model in entry["models"]:
                record = self.record(entry["name"], model)
                if record is not None:
                    out[(entry["name"], model)] = record
        return out

    def load_point(self, point: str, model: str = "dynamic") -> xr.Dataset:
        """The full result of one run; CaseError when it is not there."""
        path = self.result_path(point, model)
        if not path.is_file():
            record = self.record(point, model)
            why = (
                f"it failed: {record.get('message', '')}"
                if record and record.get("status") == FAILED
                else "it has not run (yet)"
            )
            raise CaseError(Problem("point", f"no {model} result for point {point}: {why}"))
        return load_dataset(path)


def _coordinate(values: list):
    if all(isinstance(v, bool) for v in values if v is not None):
        return np.array([str(v).lower() if v is not None else "" for v in values])
    if all(isinstance(v, int | float) for v in values if v is not None):
        return np.array([np.nan if v is None else float(v) for v in values])
    return np.array(["" if v is None else str(v) for v in values])


def study_dataset(folder: StudyFolder) -> xr.Dataset:
    """The study Dataset of a study folder: dimensions ``point``, ``model`` and ``race``.

    Coordinates: ``point`` (p0001...), ``sweep`` and one coordinate per varied key, named by the
    dotted key, holding each point's value of that key (the base case's where a sweep does not
    vary it). Variables: the :data:`~solver.study.metrics.POINT_METRICS` per (point, model[, race])
    (NaN where the run has not finished or failed), ``status`` ("done", "failed", "pending" or
    "not run": the point does not run this model), ``message`` and ``wall_time`` [s].
    """
    manifest = folder.manifest()
    entries = manifest["points"]
    names = [e["name"] for e in entries]
    models = [m for m in MODEL_NAMES if any(m in e["models"] for e in entries)]
    np_, nm = len(names), len(models)
    data = {}
    for name, (dims, _units, _long, _desc) in POINT_METRICS.items():
        shape = (np_, nm, *(len(RACES) for _ in dims))
        data[name] = np.full(shape, np.nan)
    status = np.full((np_, nm), "not run", dtype=object)
    message = np.full((np_, nm), "", dtype=object)
    wall = np.full((np_, nm), np.nan)
    for i, entry in enumerate(entries):
        for j, model in enumerate(models):
            if model not in entry["models"]:
                continue
            record = folder.record(entry["name"], model)
            if record is None:
                status[i, j] = "pending"
                continue
            status[i, j] = record.get("status", FAILED)
            message[i, j] = record.get("message", "")
            wall[i, j] = record.get("wall_time_s") or np.nan
            for name, (dims, *_rest) in POINT_METRICS.items():
                value = (record.get("metrics") or {}).get(name)
                if value is None:
                    continue
                if dims:
                    for k, race in enumerate(RACES):
                        v = value.get(race)
                        data[name][i, j, k] = np.nan if v is None else v
                else:
                    data[name][i, j] = value
    variables = {}
    for name, (dims, units, long_name, description) in POINT_METRICS.items():
        variables[name] = (
            ("point", "model", *dims),
            data[name],
            {"units": units, "long_name": long_name, "description": description},
        )
    variables["status"] = (("point", "model"), status.astype(str), {"long_name": "run status"})
    variables["message"] = (("point", "model"), message.astype(str), {"long_name": "message"})
    variables["wall_time"] = (
        ("point", "model"),
        wall,
        {"units": "s", "long_name": "wall time of the run"},
    )
    coords = {
        "point": ("point", np.array(names), {"long_name": "study point"}),
        "model": ("model", np.array(models), {"long_name": "model"}),
        "race": ("race", np.array(RACES), {"long_name": "race"}),
        "sweep": ("point", np.array([e["sweep"] for e in entries]), {"long_name": "sweep"}),
    }
    for key in manifest["varied_keys"]:
        values = [e["coordinates"].get(key) for e in entries]
        coords[key] = ("point", _coordinate(values), {"long_name": f"case key {key}"})
    attrs = {
        "title": manifest["title"],
        "description": manifest.get("description", ""),
        "base_case": manifest["base"],
        "software_version": manifest.get("software_version", ""),
        "varied_keys": json.dumps(manifest["varied_keys"]),
        "study_folder": str(folder.path.resolve()),
        "racetrace_kind": "study",
    }
    return xr.Dataset(variables, coords=coords, attrs=attrs)
