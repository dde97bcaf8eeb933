"""The runs folder: every finished or cancelled run saved (NetCDF + case TOML), listed, reopened.

Layout: ``<runs_dir>/<run_id>/`` holding ``result.nc`` (the result Dataset), ``case.toml`` (the case
as run) and ``run.json`` (title, model, status, creation time). A run is first written into a hidden
``.tmp-<run_id>`` folder and renamed into place, so a crash never leaves a half-written run listed.

Nothing in the folder stops the store: a run folder that cannot be used (``run.json`` missing,
unreadable or with wrong types, the result or the case missing, a result that is not NetCDF) is
listed as ``broken`` with the reason. When the folder is read-only or full, a finished run is kept
in memory instead (listed, reopened and exported as any other, with ``saved = False`` and the
reason) until the process ends. :meth:`RunStore.recover` tidies the folder when a server starts.

The folder is, in order: the ``runs_dir`` argument (``racetrace serve --runs-dir``), the environment
variable ``RACETRACE_RUNS_DIR``, or ``<user data dir>/racetrace/runs`` (platformdirs).
"""

from __future__ import annotations

import json
import os
import re
import secrets
import shutil
import tempfile
import time
from dataclasses import asdict, dataclass, replace
from datetime import UTC, datetime
from pathlib import Path

import xarray as xr

from .paths import UnsafeNameError, child_path, name_problem

ENV_VAR = "RACETRACE_RUNS_DIR"
RESULT_FILE, CASE_FILE, META_FILE = "result.nc", "case.toml", "run.json"


def default_runs_dir(environ: dict | None = None) -> Path:
    """``$RACETRACE_RUNS_DIR`` or the user's data directory for racetrace, plus ``runs``."""
    env = os.environ if environ is None else environ
    if env.get(ENV_VAR):
        return Path(env[ENV_VAR]).expanduser()
    import platformdirs

    return Path(platformdirs.user_data_dir("racetrace", appauthor=False)) / "runs"


#: Statuses of a usable run: finished, or stopped early with the part computed so far.
STATUSES = ("done", "cancelled")
#: Hidden files a run or a job leaves behind when its process dies: a job's result (``.job-*``),
#: a run being saved (``.tmp-*``) and atomic writes (``.<name>.*.tmp``).
_ORPHAN_PATTERNS = (".job-*", ".tmp-*", ".*.tmp")
#: First bytes of a NetCDF file: HDF5 (netCDF-4) or classic / 64-bit offset / CDF-5.
_NETCDF_SIGNATURES = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02", b"CDF\x05")
#: A run id is the name of a folder made by :meth:`RunStore.save`: no separators, no dots.
_RUN_ID = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]{0,127}$")


class UnknownRunError(FileNotFoundError):
    """A run id that is not one of the listed runs (including any id naming a path)."""


class RunNotSavedError(OSError):
    """A run could not be written to the runs folder; the message names the folder and why."""


@dataclass(frozen=True)
class RunInfo:
    """One run. ``status`` is ``done``, ``cancelled`` or ``broken`` (unusable: ``problem`` says
    why); ``created`` is ISO 8601 (UTC). ``saved`` is False for a run kept only in memory because
    the runs folder could not take it (``problem`` then says why)."""

    run_id: str
    title: str
    model: str
    status: str
    created: str
    problem: str = ""
    saved: bool = True

    @property
    def broken(self) -> bool:
        return self.status == "broken"

    @property
    def label(self) -> str:
        when = self.created.replace("T", " ")[:19]
        if self.broken:
            return f"{when}  {self.title} (broken: {self.problem})"
        note = "" if self.saved else ", not saved: download it to keep it"
        return f"{when}  {self.title} ({self.model}, {self.status}{note})"


@dataclass(frozen=True)
class Recovery:
    """What :meth:`RunStore.recover` found: files removed, job results saved as runs, runs that
    stopped early (``cancelled``), broken runs, and the folder's problem ("" when writable)."""

    removed: tuple[str, ...] = ()
    recovered: tuple[RunInfo, ...] = ()
    incomplete: tuple[RunInfo, ...] = ()
    broken: tuple[RunInfo, ...] = ()
    folder_problem: str = ""

    def messages(self) -> list[str]:
        """One line per finding, for the server's start-up report."""
        lines = []
        if self.folder_problem:
            lines.append(self.folder_problem)
        if self.removed:
            lines.append(f"removed {len(self.removed)} leftover temporary file(s) of stopped runs")
        for info in self.recovered:
            lines.append(f"recovered the result of a stopped server as run {info.run_id}")
        if self.incomplete:
            lines.append(
                f"{len(self.incomplete)} run(s) stopped early (partial results): "
                + ", ".join(r.run_id for r in self.incomplete)
            )
        for info in self.broken:
            lines.append(f"broken run {info.run_id}: {info.problem}")
        return lines


def save_netcdf(ds: xr.Dataset, path: Path) -> None:
    from solver import save_dataset

    save_dataset(ds, path)


def load_netcdf(path: Path) -> xr.Dataset:
    from solver import load_dataset

    return load_dataset(path)


def open_netcdf(path: Path) -> xr.Dataset:
    """A saved result opened lazily: the file stays open and a variable is read from it each time
    a view uses it (not kept: the views keep what they need in their own form). A session so
    holds none of the 140 MB of a 100-revolution run's variables, only the frames made of some.
    Saved runs are never rewritten, so the file stays what was opened."""
    from solver import ENGINE

    return xr.open_dataset(path, engine=ENGINE, cache=False)


def _meta_problem(meta) -> str:
    """Why a parsed ``run.json`` cannot describe a run ("" when it can)."""
    if not isinstance(meta, dict):
        return f"{META_FILE} holds {type(meta).__name__}, not an object of run fields"
    for name in ("title", "model", "status", "created"):
        if name not in meta:
            return f"{META_FILE} has no {name!r}"
        if not isinstance(meta[name], str):
            return f"{META_FILE}: {name!r} is {json.dumps(meta[name])[:40]}, not text"
    if meta["status"] not in STATUSES:
        return f"{META_FILE}: status {meta['status'][:40]!r} is not one of {', '.join(STATUSES)}"
    try:
        datetime.fromisoformat(meta["created"])
    except ValueError:
        return f"{META_FILE}: created {meta['created'][:40]!r} is not an ISO 8601 time"
    return ""


def _netcdf_problem(path: Path) -> str:
    """Why ``path`` is not a NetCDF file, from its first bytes ("" when it looks like one)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(8)
    except OSError as error:
        return f"{path.name} cannot be read ({error.strerror})"
    if not head:
        return f"{path.name} is empty"
    if not head.startswith(_NETCDF_SIGNATURES):
        return f"{path.name} is not a NetCDF file"
    return ""


def _clean_text(text: str, limit: int = 200) -> str:
    from solver import clip, printable

    return clip(printable(text), limit)


class RunStore:
    """Runs saved under one folder (created on first save), plus runs kept in memory when the
    folder cannot take them."""

    def __init__(self, root: str | Path):
        self.root = Path(root)
        # runs that could not be saved: run_id -> (RunInfo, Dataset, case text)
        self._memory: dict[str, tuple[RunInfo, xr.Dataset, str]] = {}

    # ---- saving ----------------------------------------------------------------------------------
    def save(
        self,
        ds: xr.Dataset,
        case_text: str,
        title: str,
        status: str | None = None,
        keep_in_memory: bool = True,
    ) -> RunInfo:
        """Save a run atomically and return its :class:`RunInfo`.

        ``status`` defaults to ``done`` when the Dataset's ``complete`` attribute is 1 (or
        absent) and ``cancelled`` otherwise. When the folder cannot take the run (read-only, full,
        a file-size limit: OSError, or netCDF4's RuntimeError) nothing is left in the folder and the
        run is kept in memory instead: its RunInfo has ``saved = False`` and the reason, naming the
        folder. With ``keep_in_memory=False`` :class:`RunNotSavedError` says so instead.
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
        try:
            self._write(info, ds, case_text)
        except (OSError, RuntimeError) as error:
            reason = _clean_text(getattr(error, "strerror", None) or str(error))
            message = f"the run could not be saved in {self.root} ({reason})"
            if not keep_in_memory:
                raise RunNotSavedError(message) from error
            info = replace(info, saved=False, problem=message)
            self._memory[run_id] = (info, ds, case_text)
        return info

    def _write(self, info: RunInfo, ds: xr.Dataset, case_text: str) -> None:
        self.root.mkdir(parents=True, exist_ok=True)
        tmp = self.root / f".tmp-{info.run_id}"
        tmp.mkdir()
        try:
            save_netcdf(ds, tmp / RESULT_FILE)
            (tmp / CASE_FILE).write_text(case_text, encoding="utf-8")
            meta = {k: v for k, v in asdict(info).items() if k not in ("problem", "saved")}
            (tmp / META_FILE).write_text(json.dumps(meta, indent=1), encoding="utf-8")
            os.replace(tmp, self.root / info.run_id)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise

    def folder_problem(self) -> str:
        """Why runs cannot be saved in the folder now ("" when a test file can be written there):
        a folder that cannot be created, is not a folder, is read-only or is full."""
        try:
            self.root.mkdir(parents=True, exist_ok=True)
            from solver import probe_write

            probe_write(self.root, ".tmp-probe-")
        except OSError as error:
            reason = error.strerror or str(error)
            return (
                f"runs folder {self.root} cannot take new runs ({reason}); finished runs are "
                "kept in memory until the server stops: download them to keep them, or start "
                "with --runs-dir on a writable folder"
            )
        return ""

    def job_path(self) -> Path:
        """A new file for a background job's result: a hidden ``.job-*.nc`` in the runs folder, or
        in the temporary folder when the runs folder cannot take files (:meth:`folder_problem`).
        :meth:`recover` collects job files left in the runs folder by a stopped server."""
        name = f".job-{secrets.token_hex(4)}.nc"
        if self.folder_problem():
            return Path(tempfile.gettempdir()) / name
        return self.root / name

    # ---- listing and loading ---------------------------------------------------------------------
    def _folders(self) -> list[Path]:
        """Run folders: the visible sub-folders of the root (not symbolic links)."""
        try:
            entries = list(self.root.iterdir())
        except OSError:
            return []
        return [
            e for e in entries if not e.name.startswith(".") and e.is_dir() and not e.is_symlink()
        ]

    def _describe(self, folder: Path) -> RunInfo:
        """The RunInfo of a run folder; ``broken`` with the reason when it cannot be used."""
        run_id = folder.name
        try:
            created = datetime.fromtimestamp(folder.stat().st_mtime, UTC)
            fallback = created.isoformat(timespec="seconds")
        except OSError:
            fallback = ""
        title = _clean_text(run_id, 80)

        def broken(problem: str) -> RunInfo:
            return RunInfo(run_id, title, "unknown", "broken", fallback, problem=problem)

        if not _RUN_ID.match(run_id):
            return broken("the folder name is not a run id")
        try:
            meta = json.loads((folder / META_FILE).read_text(encoding="utf-8"))
        except FileNotFoundError:
            return broken(f"no {META_FILE}")
        except (OSError, UnicodeDecodeError, ValueError, RecursionError) as error:
            reason = getattr(error, "strerror", None) or str(error)
            return broken(f"{META_FILE} cannot be read ({_clean_text(reason, 120)})")
        problem = _meta_problem(meta)
        if problem:
            return broken(_clean_text(problem))
        title = _clean_text(meta["title"], 200)
        for name in (RESULT_FILE, CASE_FILE):
            if not (folder / name).is_file():
                return broken(f"no {name}")
        problem = _netcdf_problem(folder / RESULT_FILE)
        if problem:
            return broken(problem)
        return RunInfo(
            run_id,
            title,
            _clean_text(meta["model"], 40),
            meta["status"],
            meta["created"],
        )

    def list(self, include_broken: bool = True) -> list[RunInfo]:
        """Runs, newest first: saved runs, runs kept in memory and (unless ``include_broken`` is
        False) broken run folders, each with its reason. Never raises for the folder's content."""
        runs = [self._describe(folder) for folder in self._folders()]
        runs += [info for info, _, _ in self._memory.values()]
        if not include_broken:
            runs = [r for r in runs if not r.broken]
        return sorted(runs, key=lambda r: (r.created, r.run_id), reverse=True)

    def info(self, run_id) -> RunInfo:
        """The RunInfo of a listed run; :class:`UnknownRunError` for any other id (an id that is
        not text, names a path, or is not listed)."""
        if isinstance(run_id, str) and run_id in self._memory:
            return self._memory[run_id][0]
        if not isinstance(run_id, str) or not _RUN_ID.match(run_id) or name_problem(run_id):
            shown = _clean_text(repr(run_id), 80)
            raise UnknownRunError(f"{shown} is not a run id: choose a run from the list")
        folder = self.root / run_id
        if folder not in self._folders():
            known = ", ".join(r.run_id for r in self.list(include_broken=False)[:5]) or "none"
            raise UnknownRunError(f"no saved run {run_id!r} in {self.root} (latest: {known})")
        return self._describe(folder)

    def load(self, run_id: str) -> tuple[xr.Dataset, str]:
        """(result Dataset, case TOML text) of a listed run.

        :class:`UnknownRunError` (a FileNotFoundError) for an id that is not a listed run;
        ValueError naming the run when it is broken, its result cannot be read, or the result is
        not a racetrace result with what the views read (solver.results.validate: its variables,
        its geometry and operating point coordinates, results-schema.md, which results of older
        versions lack)."""
        from solver import CaseError, check_result, geometry_from_result, ring_speeds

        info = self.info(run_id)
        if run_id in self._memory:
            _, ds, case_text = self._memory[run_id]
            return ds, case_text
        if info.broken:
            raise ValueError(f"saved run {run_id} is broken: {info.problem}")
        folder = self._run_folder(run_id)
        try:
            ds = open_netcdf(folder / RESULT_FILE)  # runs are never rewritten: read on demand
            case_text = (folder / CASE_FILE).read_text(encoding="utf-8")
        except (OSError, RuntimeError, ValueError, UnicodeDecodeError) as error:
            reason = _clean_text(getattr(error, "strerror", None) or str(error))
            raise ValueError(f"saved run {run_id} cannot be read ({reason})") from None
        try:
            check_result(ds, f"saved run {run_id}")  # CaseError (a ValueError) naming what it lacks
            ring_speeds(ds)
            geometry_from_result(ds)
        except CaseError as error:
            ds.close()
            raise ValueError(str(error)) from None
        except ValueError as error:
            ds.close()
            raise ValueError(f"saved run {run_id}: {error}") from None
        return ds, case_text

    def path(self, run_id: str) -> Path:
        """Folder of a saved run (for export); UnknownRunError for an id that is not listed, or a
        run kept only in memory."""
        info = self.info(run_id)
        if not info.saved:
            raise UnknownRunError(f"run {run_id} is kept in memory only: {info.problem}")
        return self._run_folder(run_id)

    def _run_folder(self, run_id: str) -> Path:
        """The folder of listed run ``run_id``, checked to stay under the root
        (:func:`app.paths.child_path`); UnknownRunError otherwise."""
        try:
            return child_path(self.root, run_id, "run")
        except UnsafeNameError as error:
            raise UnknownRunError(str(error)) from None

    # ---- start-up --------------------------------------------------------------------------------
    def recover(self, min_age_s: float = 60.0) -> Recovery:
        """Tidy the folder when a server starts, and report what it holds.

        A job result a stopped server left (``.job-*.nc``) that reads as a result with its case is
        saved as a run (its ``complete`` attribute gives done or cancelled), other leftovers
        (unreadable job results, half-saved runs ``.tmp-*``, temporary files of atomic writes)
        are removed. Files changed in the last ``min_age_s`` seconds are left alone: another
        server may be writing them. Never raises for the folder's content.
        """
        removed, recovered = [], []
        folder_problem = self.folder_problem()
        now = time.time()
        seen = set()
        for pattern in _ORPHAN_PATTERNS:
            try:
                candidates = sorted(self.root.glob(pattern))
            except OSError:
                candidates = []
            for path in candidates:
                if path in seen or path.name.startswith(".exports"):
                    continue
                seen.add(path)
                try:
                    if now - path.lstat().st_mtime < min_age_s:
                        continue
                except OSError:
                    continue
                if pattern == ".job-*" and path.is_file() and not folder_problem:
                    try:
                        info = self._recover_job(path)
                    except RunNotSavedError:
                        continue  # kept for the next start
                    if info is not None:
                        recovered.append(info)
                if folder_problem:
                    continue  # nothing can be removed from a read-only folder
                try:
                    if path.is_dir() and not path.is_symlink():
                        shutil.rmtree(path)
                    else:
                        path.unlink()
                    removed.append(path.name)
                except OSError:
                    pass
        runs = self.list()
        return Recovery(
            removed=tuple(removed),
            recovered=tuple(recovered),
            incomplete=tuple(r for r in runs if r.status == "cancelled"),
            broken=tuple(r for r in runs if r.broken),
            folder_problem=folder_problem,
        )

    def _recover_job(self, path: Path) -> RunInfo | None:
        """Save the job result at ``path`` as a run; None when it is not a readable result."""
        if _netcdf_problem(path):
            return None
        try:
            ds = load_netcdf(path)
            case_text = str(ds.attrs.get("case", ""))
        except (OSError, RuntimeError, ValueError, TypeError, KeyError):
            return None
        from solver import CaseError, parse_case

        try:
            title = "recovered: " + describe_case(parse_case(case_text, "the job's case"))
        except CaseError:
            title = "recovered run"
        info = self.save(ds, case_text, title, keep_in_memory=False)
        return info


def describe_case(case) -> str:
    """A one-line run title from the values actually run (the case's own title may be stale).

    e.g. ``7008C-class hybrid: 20000 rpm, Fa 500 N, Fr 300 N at 0 deg, 10 rev``; loads in N,
    speeds in rev/min, angles in degree as in the case file. Zero loads and tilts are left out.
    A key given as a time history is named with the history in words, and the run length of such
    a case is its duration (``... inner ring speed smooth ramp from 0 to 20000 rpm, 0 s to 0.3 s,
    Fa 500 N, 0.4 s``). A bearing set says so, with its loads on the shaft (``7008C-class
    hybrid DB of 2 bearing(s), preload force 100 N at assembly: 12000 rpm, load [100, 200, 0] N,
    10 rev``).
    """
    from .case_fields import history_texts
    from .run_length import run_length_words

    op = case.operating
    histories = {key.split(".", 1)[1]: text for key, text in history_texts(case).items()}
    name = case.bearing.designation or case.title or "bearing"

    def said(key: str, steady: str, words: str) -> str:
        return f"{words} {histories[key]}" if key in histories else steady

    bearing_set = getattr(case, "bearing_set", None)
    if bearing_set is not None:  # a set's loads are on the shaft, not in [operating]
        force = ", ".join(f"{v:g}" for v in bearing_set.load_force_N)
        parts = [f"{op.inner_ring_speed_rpm:g} rpm", f"load [{force}] N"]
        if any(bearing_set.load_moment_Nm):
            parts.append(f"moment [{', '.join(f'{v:g}' for v in bearing_set.load_moment_Nm)}] N m")
        if length := run_length_words(case):
            parts.append(length)
        return f"{name} {bearing_set.describe()}: " + ", ".join(parts)
    parts = [said("inner_ring_speed_rpm", f"{op.inner_ring_speed_rpm:g} rpm", "inner ring speed")]
    if op.outer_ring_speed_rpm or "outer_ring_speed_rpm" in histories:
        parts.append(
            said(
                "outer_ring_speed_rpm", f"outer ring {op.outer_ring_speed_rpm:g} rpm", "outer ring"
            )
        )
    parts.append(said("axial_load_N", f"Fa {op.axial_load_N:g} N", "Fa"))
    if op.radial_load_N or "radial_load_N" in histories:
        radial = said("radial_load_N", f"Fr {op.radial_load_N:g} N", "Fr")
        angle = said("radial_load_angle_deg", f"{op.radial_load_angle_deg or 0:g} deg", "angle")
        parts.append(f"{radial} at {angle}")
    if op.tilting_moment_Nm or "tilting_moment_Nm" in histories:
        parts.append(said("tilting_moment_Nm", f"M {op.tilting_moment_Nm:g} N m", "M"))
    if op.misalignment_deg or "misalignment_deg" in histories:
        tilt = said("misalignment_deg", f"tilt {op.misalignment_deg:g} deg", "tilt")
        parts.append(f"{tilt} ({op.misalignment_frame or 'space'})")
    if length := run_length_words(case):
        parts.append(length)
    return f"{name}: " + ", ".join(parts)
