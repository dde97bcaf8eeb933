"""The runs folder: every finished or cancelled run saved (NetCDF + case TOML), listed, reopened.

Layout: ``<runs_dir>/<run_id>/`` holding ``result.nc`` (the result Dataset), ``case.toml`` (the case
as run) and ``run.json`` (title, model, status, creation time). A run is first written into a hidden
``.tmp-<run_id>`` folder and renamed into place, so a crash never leaves a half-written run listed.

The folder is, in order: the ``runs_dir`` argument (``racetrace serve --runs-dir``), the environment
variable ``RACETRACE_RUNS_DIR``, or ``<user data dir>/racetrace/runs`` (platformdirs).
"""

from __future__ import annotations

import json
import os
import re
import secrets
import shutil
from dataclasses import asdict, dataclass
from datetime import UTC, datetime
from pathlib import Path

import xarray as xr

ENV_VAR = "RACETRACE_RUNS_DIR"
RESULT_FILE, CASE_FILE, META_FILE = "result.nc", "case.toml", "run.json"


def default_runs_dir(environ: dict | None = None) -> Path:
    """``$RACETRACE_RUNS_DIR`` or the user's data directory for racetrace, plus ``runs``."""
    env = os.environ if environ is None else environ
    if env.get(ENV_VAR):
        return Path(env[ENV_VAR]).expanduser()
    import platformdirs

    return Path(platformdirs.user_data_dir("racetrace", appauthor=False)) / "runs"


@dataclass(frozen=True)
class RunInfo:
    """One saved run. ``status`` is ``done`` or ``cancelled``; ``created`` is ISO 8601 (UTC)."""

    run_id: str
    title: str
    model: str
    status: str
    created: str

    @property
    def label(self) -> str:
        when = self.created.replace("T", " ")[:19]
        return f"{when}  {self.title} ({self.model}, {self.status})"


def save_netcdf(ds: xr.Dataset, path: Path) -> None:
    from solver.results.io import save_dataset

    save_dataset(ds, path)


def load_netcdf(path: Path) -> xr.Dataset:
    from solver.results.io import load_dataset

    return load_dataset(path)


class RunStore:
    """Runs saved under one folder (created on first save)."""

    def __init__(self, root: str | Path):
        self.root = Path(root)

    def save(
        self, ds: xr.Dataset, case_text: str, title: str, status: str | None = None
    ) -> RunInfo:
        """Save a run atomically and return its :class:`RunInfo`.

        ``status`` defaults to ``done`` when the Dataset's ``complete`` attribute is 1 (or
        absent) and ``cancelled`` otherwise.
        """
        if status is None:
            status = "done" if int(ds.attrs.get("complete", 1)) == 1 else "cancelled"
        now = datetime.now(UTC)
        slug = re.sub(r"[^A-Za-z0-9]+", "-", title).strip("-")[:40] or "run"
        run_id = f"{now:%Y%m%d-%H%M%S}-{slug}-{secrets.token_hex(2)}"
        info = RunInfo(
            run_id,
            title,
            str(ds.attrs.get("model", "unknown")),
            status,
            now.isoformat(timespec="seconds"),
        )
        self.root.mkdir(parents=True, exist_ok=True)
        tmp = self.root / f".tmp-{run_id}"
        tmp.mkdir()
        try:
            save_netcdf(ds, tmp / RESULT_FILE)
            (tmp / CASE_FILE).write_text(case_text, encoding="utf-8")
            (tmp / META_FILE).write_text(json.dumps(asdict(info), indent=1), encoding="utf-8")
            os.replace(tmp, self.root / run_id)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
        return info

    def list(self) -> list[RunInfo]:
        """Saved runs, newest first (folders without a readable ``run.json`` are skipped)."""
        if not self.root.is_dir():
            return []
        runs = []
        for folder in self.root.iterdir():
            if folder.name.startswith(".") or not (folder / META_FILE).is_file():
                continue
            try:
                meta = json.loads((folder / META_FILE).read_text(encoding="utf-8"))
                runs.append(RunInfo(**{k: meta[k] for k in RunInfo.__dataclass_fields__}))
            except (ValueError, KeyError, TypeError):
                continue
        return sorted(runs, key=lambda r: (r.created, r.run_id), reverse=True)

    def load(self, run_id: str) -> tuple[xr.Dataset, str]:
        """(result Dataset, case TOML text) of a saved run. ValueError (naming the run) when the
        result does not describe itself: the views need its geometry and operating point
        coordinates (results-schema.md), which results of older versions lack."""
        from solver.results.dataset import geometry_from_result, ring_speeds

        folder = self.root / run_id
        if not (folder / RESULT_FILE).is_file():
            known = ", ".join(r.run_id for r in self.list()[:5]) or "none"
            raise FileNotFoundError(f"no saved run {run_id!r} in {self.root} (latest: {known})")
        ds = load_netcdf(folder / RESULT_FILE)
        try:
            ring_speeds(ds)
            geometry_from_result(ds)
        except ValueError as error:
            raise ValueError(f"saved run {run_id}: {error}") from None
        return ds, (folder / CASE_FILE).read_text(encoding="utf-8")

    def path(self, run_id: str) -> Path:
        """Folder of a saved run (for export)."""
        return self.root / run_id


def describe_case(case) -> str:
    """A one-line run title from the values actually run (the case's own title may be stale).

    e.g. ``7008C-class hybrid: 20000 rpm, Fa 500 N, Fr 300 N at 0 deg, 10 rev``; loads in N,
    speeds in rev/min, angles in degree as in the case file. Zero loads and tilts are left out.
    """
    op = case.operating
    name = case.bearing.designation or case.title or "bearing"
    parts = [f"{op.inner_ring_speed_rpm:g} rpm"]
    if op.outer_ring_speed_rpm:
        parts.append(f"outer ring {op.outer_ring_speed_rpm:g} rpm")
    parts.append(f"Fa {op.axial_load_N:g} N")
    if op.radial_load_N:
        parts.append(f"Fr {op.radial_load_N:g} N at {op.radial_load_angle_deg or 0:g} deg")
    if op.tilting_moment_Nm:
        parts.append(f"M {op.tilting_moment_Nm:g} N m")
    if op.misalignment_deg:
        parts.append(f"tilt {op.misalignment_deg:g} deg ({op.misalignment_frame or 'space'})")
    revolutions = getattr(getattr(case, "simulation", None), "shaft_revolutions", None)
    if revolutions:
        parts.append(f"{revolutions:g} rev")
    return f"{name}: " + ", ".join(parts)
