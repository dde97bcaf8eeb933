"""The results a lesson shows: shipped with racetrace, else computed once and cached.

Each :class:`~app.lessons.format.ResultSpec` has a fingerprint (a hash of its case's values, the
model, the run length and the solver's results version: ``solver.result_fingerprint``).
:func:`lesson_result` looks, in this order, for

1. the shipped file ``assets/lessons/results/<lesson>--<result>.nc`` (written by
   ``tools/make_lesson_results.py``) whose ``lesson_fingerprint`` attribute matches;
2. ``<cache>/<fingerprint>.nc`` in the user cache folder (``lesson_cache_dir``);
3. otherwise it solves the case (quasi-static: milliseconds; dynamic: seconds) and keeps the
   result in the cache, so a lesson a teacher adds is solved once, on first use.

Files are compressed NetCDF (zlib; time histories in single precision), written atomically.
"""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from .format import Lesson, ResultSpec

FINGERPRINT_ATTR = "lesson_fingerprint"
RESULTS_VERSION_ATTR = "results_version"
_COMPRESSION = {"zlib": True, "complevel": 6, "shuffle": True}


def fingerprint(spec: ResultSpec) -> str:
    """Hash of what the result depends on (``solver.result_fingerprint``): the case's values, the
    model, the run length of a dynamic run and the solver's results version."""
    import solver

    case = spec.case()
    options = (
        {
            "shaft_revolutions": spec.shaft_revolutions,
            "samples_per_revolution": spec.samples_per_revolution,
        }
        if spec.model == "dynamic" and not case.histories
        else {}
    )
    return solver.result_fingerprint(case, spec.model, options)


def shipped_results_dir():
    """The folder of the shipped lesson results (``assets/lessons/results``)."""
    from .format import shipped_lessons_dir

    return shipped_lessons_dir() / "results"


def shipped_name(lesson: Lesson, spec: ResultSpec) -> str:
    return f"{lesson.id}--{spec.name}.nc"


def lesson_cache_dir(environ: dict | None = None) -> Path:
    """``$RACETRACE_LESSON_CACHE`` if set, else ``<user cache dir>/racetrace/lessons``."""
    environ = os.environ if environ is None else environ
    if environ.get("RACETRACE_LESSON_CACHE"):
        return Path(environ["RACETRACE_LESSON_CACHE"])
    import platformdirs

    return Path(platformdirs.user_cache_dir("racetrace", appauthor=False)) / "lessons"


def compute(spec: ResultSpec) -> xr.Dataset:
    """Solve the spec's case with its model (the dynamic run with its own length; a case with a
    time history runs for its own simulation.duration_s)."""
    import solver

    case = spec.case()
    if spec.model == "quasistatic":
        ds = solver.solve_quasistatic(case)
    elif case.histories:
        ds = solver.simulate(case)
    else:
        options = solver.SimulationOptions(
            shaft_revolutions=spec.shaft_revolutions,
            samples_per_revolution=spec.samples_per_revolution,
        )
        ds = solver.simulate(case, options=options)
    ds.attrs[FINGERPRINT_ATTR] = fingerprint(spec)
    ds.attrs[RESULTS_VERSION_ATTR] = solver.RESULTS_VERSION
    return ds


def save_compressed(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` as zlib-compressed NetCDF, atomically. The time histories of a dynamic run
    (floating-point data variables along ``time``) are stored in single precision, 7 significant
    digits: far finer than any figure a lesson quotes; coordinates and the stored summary metrics
    keep double precision."""
    from solver import ENGINE, atomic_write

    encoding = {}
    for name, var in ds.variables.items():
        if var.dtype.kind not in "fiu" or var.ndim == 0:
            continue
        encoding[name] = dict(_COMPRESSION)
        if name in ds.data_vars and var.dtype.kind == "f" and "time" in var.dims:
            encoding[name]["dtype"] = "float32"
    return atomic_write(path, lambda tmp: ds.to_netcdf(tmp, engine=ENGINE, encoding=encoding))


def _read_matching(path, wanted: str) -> xr.Dataset | None:
    from solver import load_dataset

    try:
        if not path.is_file():
            return None
        ds = load_dataset(path)
    except (OSError, ValueError):
        return None  # unreadable: solve again
    return ds if ds.attrs.get(FINGERPRINT_ATTR) == wanted else None


def lesson_result(
    lesson: Lesson, spec: ResultSpec, cache_dir: Path | None = None
) -> tuple[xr.Dataset, str]:
    """(result, where it came from: "shipped", "cache" or "computed") of one result of a lesson."""
    wanted = fingerprint(spec)
    ds = _read_matching(shipped_results_dir() / shipped_name(lesson, spec), wanted)
    if ds is not None:
        return ds, "shipped"
    cache = lesson_cache_dir() if cache_dir is None else Path(cache_dir)
    cached = cache / f"{wanted}.nc"
    ds = _read_matching(cached, wanted)
    if ds is not None:
        return ds, "cache"
    ds = compute(spec)
    try:
        cache.mkdir(parents=True, exist_ok=True)
        save_compressed(ds, cached)
    except OSError:
        pass  # no writable cache: the result is still shown, and solved again next time
    return ds, "computed"


__all__ = [
    "FINGERPRINT_ATTR",
    "RESULTS_VERSION_ATTR",
    "compute",
    "fingerprint",
    "lesson_cache_dir",
    "lesson_result",
    "save_compressed",
    "shipped_name",
    "shipped_results_dir",
]
