"""The study folder: what a study run keeps on disk, written so that a stop loses nothing done.

Layout of ``DIR``::

    study.toml                     the study file as run (a resume must run the same study)
    study.json                     manifest: title, base case, varied keys, every point's values,
                                   and the inputs that determine the points (resolved base case,
                                   run options, solver sources hash) that a resume checks
    points/p0001.quasistatic.nc    full result of each finished run (results-schema.md)
    points/p0001.quasistatic.json  its record: status ("done" | "failed"), message, metrics, times
    study.nc                       the study Dataset (:func:`study_dataset`), rewritten at the end

Each result file is written atomically, then its record (also atomically): a record exists only
for a finished run, and a run whose record is missing is run again by a resume. A stop in the
middle of a write (``kill -9``) can leave a temporary file (``points/.p0001.dynamic.nc.*.tmp``);
a resume removes those and says so.

Reading validates everything read (:meth:`StudyFolder.manifest`, :meth:`StudyFolder.record`,
:func:`solver.study.open_study`): a folder whose ``study.json`` or a run record is not what this
module writes raises :class:`~solver.errors.CaseError` ("not a study folder: ..."), never a
traceback. Nothing here runs a model (solver.study.runner does).
"""

from __future__ import annotations

import json
import math
import os
import re
import stat
import time
from pathlib import Path

import numpy as np
import xarray as xr

from solver.errors import CaseError, Problem
from solver.results.io import atomic_write, load_dataset, save_dataset
from solver.results.provenance import RESULTS_VERSION, study_fingerprint
from solver.results.summary import RACES

from .metrics import POINT_METRICS, SET_STUDY_METRIC_NAMES, set_point_metric_table

STUDY_FILE = "study.toml"
MANIFEST = "study.json"
POINTS = "points"
DATASET = "study.nc"
MODEL_NAMES = ("quasistatic", "dynamic")
DONE, FAILED = "done", "failed"
#: Largest ``study.json`` read, in bytes (a study of 5 000 points writes a few MB).
MAX_MANIFEST_BYTES = 64_000_000
#: Largest run record read, in bytes (a record is a few hundred bytes).
MAX_RECORD_BYTES = 1_000_000
_POINT_NAME = re.compile(r"p\d{4,6}")
_CASE_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)+")
# what atomic_write leaves behind when the process dies between creating and moving its file
_TEMPORARY = re.compile(
    r"\.(p\d+\.(quasistatic|dynamic)\.(nc|json)|study\.(toml|json|nc))\.[A-Za-z0-9_]+\.tmp"
)
_SCALAR = (str, int, float, bool, type(None))


def _json_value(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _json_value(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_value(v) for v in value]
    if isinstance(value, np.generic):
        return _json_value(value.item())
    return value


def _write_json(path: Path, data) -> None:
    text = json.dumps(_json_value(data), indent=1, sort_keys=False)
    atomic_write(path, lambda tmp: Path(tmp).write_text(text + "\n", encoding="utf-8"))


def _not_a_study(folder: Path, why: str) -> CaseError:
    return CaseError(
        Problem(
            "study",
            f"not a study folder: {folder}: {why}. Give the --output folder of a racetrace study "
            "run",
        )
    )


def _read_json(path: Path, limit: int, folder: Path, name: str, hint: str = ""):
    """The JSON value in the regular file ``path`` (at most ``limit`` bytes); CaseError naming
    ``folder``, the file's ``name`` and ``hint`` otherwise (a FIFO is never opened, deep nesting
    is refused)."""

    def wrong(why: str) -> CaseError:
        return _not_a_study(folder, f"{name} {why}{hint}")

    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode):
            raise wrong("is not a regular file")
        if info.st_size > limit:
            raise wrong(f"is larger than {limit / 1e6:g} MB")
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as handle:
            if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):
                raise wrong("is not a regular file")
            raw = handle.read(limit + 1)
    except OSError as error:
        raise wrong(f"cannot be read ({error.strerror})") from None
    if len(raw) > limit:
        raise wrong(f"is larger than {limit / 1e6:g} MB")
    try:
        return json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise wrong("is not UTF-8 text") from None
    except RecursionError:
        raise wrong("nests values hundreds of levels deep") from None
    except ValueError as error:
        raise wrong(f"is not JSON ({error})") from None


def _number(value) -> bool:
    return value is None or (isinstance(value, int | float) and not isinstance(value, bool))


def _manifest_problem(data) -> str:
    """What is wrong with a manifest read from study.json ("" when it is one)."""
    if not isinstance(data, dict):
        return f"study.json holds {type(data).__name__}, not the manifest (a JSON object)"
    for key in ("title", "base"):
        if not isinstance(data.get(key), str):
            return f"study.json: {key!r} is missing or not text"
    for key in ("description", "software_version"):
        if not isinstance(data.get(key, ""), str):
            return f"study.json: {key!r} is not text"
    keys = data.get("varied_keys")
    if not isinstance(keys, list) or not all(
        isinstance(k, str) and _CASE_KEY.fullmatch(k) for k in keys
    ):
        return "study.json: 'varied_keys' is missing or not a list of dotted case keys"
    if len(set(keys)) != len(keys):
        return "study.json: 'varied_keys' names a key twice"
    points = data.get("points")
    if not isinstance(points, list) or not points:
        return "study.json: 'points' is missing or not a non-empty list"
    names = set()
    for i, entry in enumerate(points):
        where = f"study.json: points[{i}]"
        if not isinstance(entry, dict):
            return f"{where} is {type(entry).__name__}, not a point (a JSON object)"
        name = entry.get("name")
        if not isinstance(name, str) or not _POINT_NAME.fullmatch(name):
            return f"{where}: 'name' is missing or not a point name such as p0001"
        if name in names:
            return f"{where}: point {name} appears twice"
        names.add(name)
        if not isinstance(entry.get("sweep"), str):
            return f"{where}: 'sweep' is missing or not text"
        models = entry.get("models")
        if (
            not isinstance(models, list)
            or not models
            or not all(isinstance(m, str) and m in MODEL_NAMES for m in models)
            or len(set(models)) != len(models)
        ):
            return f"{where}: 'models' is missing or not a list of {' and '.join(MODEL_NAMES)}"
        if not isinstance(entry.get("values", {}), dict):
            return f"{where}: 'values' is not a JSON object"
        coordinates = entry.get("coordinates")
        if not isinstance(coordinates, dict) or not all(
            isinstance(coordinates.get(k), _SCALAR) for k in keys
        ):
            return (
                f"{where}: 'coordinates' is missing or holds a value that is not a number or text"
            )
    if not isinstance(data.get("results_fingerprint", ""), str):
        return "study.json: 'results_fingerprint' is not text"
    version = data.get("results_version", 0)
    if isinstance(version, bool) or not isinstance(version, int):
        return "study.json: 'results_version' is not a whole number"
    changes = data.get("solver_changes", [])
    if not isinstance(changes, list) or not all(isinstance(c, dict) for c in changes):
        return "study.json: 'solver_changes' is not a list of JSON objects"
    return ""


def _record_problem(record) -> str:
    """What is wrong with a run record ("" when it is one)."""
    if not isinstance(record, dict):
        return f"holds {type(record).__name__}, not a run record (a JSON object)"
    if record.get("status") not in (DONE, FAILED):
        return f"'status' is not {DONE!r} or {FAILED!r}"
    if not isinstance(record.get("message", ""), str):
        return "'message' is not text"
    if not _number(record.get("wall_time_s")):
        return "'wall_time_s' is not a number"
    metrics = record.get("metrics")
    metrics = {} if metrics is None else metrics
    if not isinstance(metrics, dict):
        return "'metrics' is not a JSON object"
    for name, (dims, *_rest) in POINT_METRICS.items():
        value = metrics.get(name)
        if dims:
            if value is not None and not (
                isinstance(value, dict) and all(_number(value.get(r)) for r in RACES)
            ):
                return f"metric {name!r} is not a number per race"
        elif not _number(value):
            return f"metric {name!r} is not a number"
    for name in SET_STUDY_METRIC_NAMES:  # a bearing set's point: numbers, or one per bearing
        value = metrics.get(name)
        if isinstance(value, dict):
            if not all(isinstance(b, str) and _number(v) for b, v in value.items()):
                return f"metric {name!r} is not a number per bearing"
        elif not _number(value):
            return f"metric {name!r} is not a number"
    return ""


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


def _dotted(data, prefix: str = "") -> dict:
    """``{"operating": {"axial_load_N": 500.0}}`` -> ``{"operating.axial_load_N": 500.0}``."""
    out = {}
    stack = [(prefix, data)]
    while stack:
        name, value = stack.pop()
        if isinstance(value, dict) and value:
            stack.extend((f"{name}.{k}" if name else str(k), v) for k, v in value.items())
        else:
            out[name] = value
    return out


def _changed_keys(old: dict, new: dict, limit: int = 6) -> str:
    """``operating.axial_load_N 500.0 -> 1500.0, ...`` for the keys whose values differ."""
    old, new = _dotted(old), _dotted(new)
    changes = [
        f"{key} {old.get(key, '(absent)')!r} -> {new.get(key, '(absent)')!r}"
        for key in sorted(set(old) | set(new))
        if old.get(key, "(absent)") != new.get(key, "(absent)")
    ]
    more = f" and {len(changes) - limit} more" if len(changes) > limit else ""
    return ", ".join(changes[:limit]) + more


def study_inputs(spec, base, solver_sources: str) -> dict:
    """What determines the study's points besides its study file, as JSON values: the resolved
    base case (its values, whether it came from a file or the catalogue), the ``[run]`` options
    and the hash of the solver's sources (the one that keys the compiled kernels)."""
    return json.loads(
        json.dumps(
            _json_value(
                {
                    "base_case": base.to_dict(),
                    "run": dict(spec.run),
                    "solver_sources": solver_sources,
                }
            )
        )
    )


def points_fingerprint(points) -> str:
    """The :func:`~solver.results.provenance.study_fingerprint` of a study's points (every model
    each point runs)."""
    return study_fingerprint((p.name, model, p.case) for p in points for model in p.models)


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
    def start(
        self,
        spec,
        points,
        version: str,
        resume: bool,
        inputs: dict | None = None,
        restart: bool = False,
        accept_solver_change: bool = False,
        log=None,
    ) -> None:
        """Create the folder, or check that a resumed one holds the same study made from the
        same inputs.

        ``inputs``: :func:`study_inputs` of this run (None: not checked nor recorded). CaseError
        (key ``output``) when the folder holds another study; holds this one and neither
        ``resume`` nor ``restart`` is given; or, on resume, when an input changed (the base case,
        the run options, or the solver: that one is accepted with ``accept_solver_change``, and
        recorded in the manifest's ``solver_changes``). ``restart`` deletes the runs of a study
        folder and starts again. A resume removes temporary files a killed run left behind.
        ``log``: callable(str) for what was removed."""
        if self.path.exists() and not self.path.is_dir():
            raise CaseError(Problem("output", f"{self.path} exists and is not a folder"))
        solver_changes: list = []
        if self.exists() and restart:
            removed = self._clear()
            if log is not None:
                log(f"restart: removed {removed} file(s) of the previous runs in {self.path}")
        elif self.exists():
            old = self._read_study_text()
            if old != spec.text:
                raise CaseError(
                    Problem(
                        "output",
                        f"{self.path} holds another study (its study.toml differs): give another "
                        "--output folder, or add --restart to delete its runs and run this study "
                        "there",
                    )
                )
            if not resume:
                raise CaseError(
                    Problem(
                        "output",
                        f"{self.path} already holds this study: add --resume to run only the "
                        "points not finished, --restart to run them all again, or give another "
                        "--output folder",
                    )
                )
            manifest = self.manifest()
            solver_changes = list(manifest.get("solver_changes", []))
            if inputs is not None:
                change = self._check_inputs(manifest, inputs, accept_solver_change, version)
                if change is not None:
                    solver_changes.append(change)
                    if log is not None:
                        log(
                            f"resume: solver changed ({change['from']} -> {change['to']}); "
                            "accepted and recorded in study.json (solver_changes)"
                        )
            removed = self.remove_temporary_files()
            if removed and log is not None:
                log(
                    f"resume: removed {len(removed)} half-written file(s) left by a stopped run: "
                    + ", ".join(removed[:5])
                    + (" ..." if len(removed) > 5 else "")
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
        manifest["results_version"] = RESULTS_VERSION
        manifest["results_fingerprint"] = points_fingerprint(points)
        if inputs is not None:
            manifest["inputs"] = inputs
        if solver_changes:
            manifest["solver_changes"] = solver_changes
        _write_json(self.path / MANIFEST, manifest)

    def _read_study_text(self) -> str:
        path = self.path / STUDY_FILE
        try:
            return path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            raise _not_a_study(self.path, f"its {STUDY_FILE} cannot be read") from None

    def _check_inputs(
        self, manifest: dict, inputs: dict, accept_solver_change: bool, version: str
    ) -> dict | None:
        """CaseError naming what changed since the folder's runs were made; the record of an
        accepted solver change (None when the solver is the same)."""
        old = manifest.get("inputs")
        if not isinstance(old, dict):
            raise CaseError(
                Problem(
                    "output",
                    f"{self.path} does not record the inputs of its runs (base case, options, "
                    "solver), so a resume cannot check that new runs match them: add --restart "
                    "to run the study again from the start",
                )
            )
        changed = []
        if old.get("base_case") != inputs["base_case"]:
            what = _changed_keys(old.get("base_case") or {}, inputs["base_case"])
            changed.append(f"the base case {manifest.get('base', '')!r} changed ({what})")
        if old.get("run") != inputs["run"]:
            what = _changed_keys(old.get("run") or {}, inputs["run"])
            changed.append(f"the run options changed ({what})")
        if changed:
            raise CaseError(
                Problem(
                    "output",
                    f"cannot resume {self.path}: {'; '.join(changed)}. Its finished runs were "
                    "made with the old inputs and would be mixed with new ones: restore the "
                    "inputs, give another --output folder, or add --restart to run every point "
                    "again",
                )
            )
        if old.get("solver_sources") == inputs["solver_sources"]:
            return None
        if not accept_solver_change:
            raise CaseError(
                Problem(
                    "output",
                    f"cannot resume {self.path}: the solver changed since its runs were made "
                    f"(sources hash {old.get('solver_sources')} -> {inputs['solver_sources']}), "
                    "so new runs may not match them. Add --restart to run every point again, or "
                    "--accept-solver-change to keep the finished runs and record the change in "
                    "the study",
                )
            )
        return {
            "from": old.get("solver_sources"),
            "to": inputs["solver_sources"],
            "software_version": version,
            "finished_runs": len(self.finished()),
            "accepted_at": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        }

    def remove_temporary_files(self) -> list[str]:
        """Remove the temporary files that a process killed while writing left behind; return
        their names (relative to the folder)."""
        removed = []
        for folder in (self.path, self.points_dir):
            if not folder.is_dir():
                continue
            for path in sorted(folder.iterdir()):
                if _TEMPORARY.fullmatch(path.name) and path.is_file():
                    path.unlink(missing_ok=True)
                    removed.append(str(path.relative_to(self.path)))
        return removed

    def _clear(self) -> int:
        """Delete every file this module writes in the folder (runs, manifest, Dataset)."""
        count = len(self.remove_temporary_files())
        if self.points_dir.is_dir():
            for path in self.points_dir.iterdir():
                parts = path.name.split(".")
                if (
                    len(parts) == 3
                    and _POINT_NAME.fullmatch(parts[0])
                    and parts[1] in MODEL_NAMES
                    and parts[2] in ("nc", "json")
                    and path.is_file()
                ):
                    path.unlink()
                    count += 1
        for name in (DATASET, MANIFEST, STUDY_FILE):
            path = self.path / name
            if path.is_file():
                path.unlink()
                count += 1
        return count

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
        """The validated manifest (study.json); CaseError "not a study folder: ..." when the
        folder has none or it is not one this module writes."""
        path = self.path / MANIFEST
        if not path.is_file():
            raise _not_a_study(self.path, f"it has no {MANIFEST}")
        data = _read_json(path, MAX_MANIFEST_BYTES, self.path, MANIFEST)
        problem = _manifest_problem(data)
        if problem:
            raise _not_a_study(self.path, problem)
        return data

    def record(self, point: str, model: str) -> dict | None:
        """The validated record of a finished run; None when the run has not finished (no
        record). CaseError when the record is not one this module writes."""
        path = self.record_path(point, model)
        if not os.path.lexists(path):
            return None
        name = f"{POINTS}/{path.name}"
        hint = ": delete it to run that point again with --resume"
        record = _read_json(path, MAX_RECORD_BYTES, self.path, name, hint)
        problem = _record_problem(record)
        if problem:
            raise _not_a_study(self.path, f"{name} {problem}{hint}")
        return record

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
        if (
            not (isinstance(point, str) and _POINT_NAME.fullmatch(point))
            or model not in MODEL_NAMES
        ):
            raise CaseError(Problem("point", f"no run {point!r} {model!r} in {self.path}"))
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


def study_runs(ds: xr.Dataset):
    """The runs a study Dataset holds, in table order (point, then model), leaving out the models a
    point does not run: yields ``(point index, model index, status)`` with status "done",
    "failed" or "pending"."""
    for i in range(ds.sizes["point"]):
        for j in range(ds.sizes["model"]):
            status = str(ds["status"].values[i, j])
            if status != "not run":
                yield i, j, status


def _set_metric_variables(folder: StudyFolder, entries: list, models: list) -> tuple[dict, list]:
    """The bearing-set variables of a study (:data:`SET_STUDY_METRIC_NAMES` per (point, model[,
    bearing]), NaN where a run has none) and its bearings' names in order of first appearance;
    ({}, []) when no run holds them (no point is a bearing set)."""
    found = {}
    bearings: list[str] = []
    for i, entry in enumerate(entries):
        for j, model in enumerate(models):
            if model not in entry["models"]:
                continue
            record = folder.record(entry["name"], model)
            metrics = (record or {}).get("metrics") or {}
            for name in SET_STUDY_METRIC_NAMES:
                value = metrics.get(name)
                if value is None:
                    continue
                found[(i, j, name)] = value
                if isinstance(value, dict):
                    bearings.extend(b for b in value if b not in bearings)
    if not found:
        return {}, []
    variables = {}
    for name, (dims, units, long_name, description) in set_point_metric_table().items():
        shape = (len(entries), len(models), *(len(bearings) for _ in dims))
        data = np.full(shape, np.nan)
        for i in range(len(entries)):
            for j in range(len(models)):
                value = found.get((i, j, name))
                if isinstance(value, dict):
                    for b, v in value.items():
                        data[i, j, bearings.index(b)] = np.nan if v is None else v
                elif value is not None:
                    data[i, j] = value
        attrs = {"units": units, "long_name": long_name, "description": description}
        variables[name] = (("point", "model", *dims), data, attrs)
    return variables, bearings


def study_dataset(folder: StudyFolder) -> xr.Dataset:
    """The study Dataset of a study folder: dimensions ``point``, ``model`` and ``race``.

    Coordinates: ``point`` (p0001...), ``sweep`` and one coordinate per varied key, named by the
    dotted key, holding each point's value of that key (the base case's where a sweep does not
    vary it). Variables: the :data:`~solver.study.metrics.POINT_METRICS` per (point, model[,
    race]) (NaN where the run has not finished or failed, or the point is a bearing set); for a
    study of bearing-set points the set's :data:`~solver.study.metrics.SET_STUDY_METRIC_NAMES`
    per (point, model[, bearing]) with the coordinate ``bearing`` (the bearings' names);
    ``status`` ("done", "failed", "pending" or "not run": the point does not run this model),
    ``message`` and ``wall_time`` [s]. Attributes: ``title``, ``description``, ``base_case``,
    ``software_version``, ``varied_keys`` (JSON), ``study_folder`` (the folder's name, never a
    path of the machine that ran it), ``racetrace_kind`` = "study", ``results_fingerprint`` and
    ``results_version`` (what the points' results depend on: :func:`points_fingerprint`), and
    ``solver_changes`` (JSON) when a resume accepted a change of the solver.
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
    set_variables, bearings = _set_metric_variables(folder, entries, models)
    variables.update(set_variables)
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
    if bearings:
        coords["bearing"] = ("bearing", np.array(bearings), {"long_name": "bearing of the set"})
    for key in manifest["varied_keys"]:
        values = [e["coordinates"].get(key) for e in entries]
        coords[key] = ("point", _coordinate(values), {"long_name": f"case key {key}"})
    attrs = {
        "title": manifest["title"],
        "description": manifest.get("description", ""),
        "base_case": manifest["base"],
        "software_version": manifest.get("software_version", ""),
        "varied_keys": json.dumps(manifest["varied_keys"]),
        "study_folder": folder.path.resolve().name,
        "racetrace_kind": "study",
    }
    if manifest.get("results_fingerprint"):
        attrs["results_fingerprint"] = manifest["results_fingerprint"]
        attrs["results_version"] = manifest.get("results_version", 0)
    if manifest.get("solver_changes"):
        attrs["solver_changes"] = json.dumps(manifest["solver_changes"])
    return xr.Dataset(variables, coords=coords, attrs=attrs)
