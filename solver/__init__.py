"""racetrace solver: case files, Hertz contact, quasi-static and dynamic ball-bearing models.

Public API (everything else is internal):

- ``load_case(path) -> Case`` (a case file), ``parse_case(text, source=...) -> Case`` (TOML text)
  and ``Case.to_toml()``
- ``catalogue()``: shipped bearings and example cases
- ``dynamic_problems(case) -> list[Problem]``: why the dynamic model cannot run a valid case
- ``to_inputs(case) -> Inputs``: the SI inputs both models read
- ``solve_quasistatic(case) -> xarray.Dataset`` (results-schema.md)
- ``solve(case) -> xarray.Dataset``: the quasi-static answer; for a bearing set (a ``[set]`` case)
  the set's Dataset with a ``bearing`` dimension, its stiffness and load sharing
  (``set_result_warnings(ds)``: where a bearing of the set unloads; ``bearing_result(ds, k)``:
  bearing ``k`` of it as a single-bearing result, which the single-bearing views read;
  ``set_spring_preload(ds)``: a spring preload's force and the floating outer rings' shift;
  ``set_stiffness_study(case, preload_forces_N, speeds_rpm)``: the set's stiffness and load
  sharing over preload and speed)
- ``solve_over_revolution(case, angles=None) -> xarray.Dataset``: the quasi-static steady state at
  inner-ring angles over one shaft revolution (dimension ``ring_angle``; None: 36 angles)
- ``quasistatic_answer(case) -> xarray.Dataset``: the quasi-static answer the CLI, studies, app and
  report quote: ``solve_over_revolution`` for a misalignment turning with the inner ring (its
  metrics are taken over the ring angles), else ``solve_quasistatic``
- ``simulate(case, progress=None, cancel=None, options=None) -> xarray.Dataset`` (dynamic model;
  ``SimulationOptions`` overrides the case's ``[simulation]`` values and sets numerical knobs;
  ``INTEGRATION_METHODS``: the names its option ``method`` takes); for a bearing set the set's
  run with a ``bearing`` dimension (``dynamic_ball_count(case)``: the balls a run stores)
- ``LiveSimulation(case, options=None)``: a dynamic run that advances chunk by chunk
  (``advance(duration_s)``) and follows inputs set while it runs (``set_input(name, value,
  ramp_s=LIVE_RAMP)``), recorded as a case and a run (docs/live.md)
- ``result_warnings(ds) -> list[str]``: where a result leaves the model's validity
- ``quasistatic_start(ds) -> xarray.Dataset | None``: the quasi-static solution a dynamic result
  started from (its ``quasistatic_*`` variables), for the views' comparison
- ``result_description(ds) -> dict``: a result's ``title``, ``bearing_provenance`` and
  ``description`` (the case's note of what is known about it)
- ``operating_from_result(ds)`` (its operating point, SI) and ``describe_operating_point(op)``
  (that point as a title names it: ``10 000 rpm, 400 N axial + 0 N radial``)
- the ``racetrace`` accessor on every xarray Dataset, registered by ``import solver``:
  ``ds.racetrace.summary()`` (trajectory metrics, ``trajectory_summary``), ``.warnings()``,
  ``.save(path)`` (NetCDF) and ``.to_csv(path)`` (per-contact table, ``contact_table``)
- ``Study.from_file(path)`` / ``open_study(folder)``: parameter studies run on Dask
  (docs/study-format.md)
- ``CaseError`` (invalid input), ``NoSolutionError`` (no solution for a valid case),
  ``SimulationDiverged`` (the dynamic integration failed), ``ResultWriteError`` (a result file
  could not be written; an OSError naming the file)

The app, the report and the command line import only from this package, never from its
submodules (an import-linter contract in pyproject.toml, checked in CI). For them it also exports
the case schema's table and helpers (``FIELDS``, ``fields_by_key``, ``format_number``, ...), the
message helpers (``clean_message``, ``clip``, ``printable``), ``resolve_case`` (a Case from a
path or a catalogue name: the models take a Case, the functions here resolve names first),
``preload()`` (the imports a forking server shares) and the result and study helpers the views
read (``ring_speeds``, ``geometry_from_result``, ``METRICS``, ``study_dataset``, ...).

The numba kernels are imported on first use; registering the accessor imports xarray.
"""

from importlib import import_module

from ._numba_cache import SOLVER_DIR, configure_numba_cache
from ._version import __version__
from .errors import (
    CaseError,
    NoSolutionError,
    Problem,
    ResultWriteError,
    SimulationDiverged,
    clean_message,
    clip,
    printable,
)

# Before any kernel is defined: compiled kernels are cached per version of the solver sources.
configure_numba_cache(SOLVER_DIR)

# public name -> module that defines it (imported on first use)
_LAZY = {
    # the time left of a run, from its progress reports
    "TimeLeft": "solver.progress",
    # case files and their schema (docs/case-format.md)
    "Case": "solver.case",
    "load_case": "solver.case",
    "parse_case": "solver.case",
    "decode_case_bytes": "solver.case.io",
    "dynamic_problems": "solver.case",
    "run_length_problems": "solver.case.validate",
    "dynamic_run_size": "solver.case.validate",
    "dynamic_ball_count": "solver.case.validate",
    "history_run_length_problems": "solver.case.validate",
    "FIELDS": "solver.case.schema",
    "REQUIRED": "solver.case.schema",
    "OPTIONAL": "solver.case.schema",
    "Estimated": "solver.case.schema",
    "fields_by_key": "solver.case.schema",
    "format_number": "solver.case.schema",
    "BUILTIN_MATERIALS": "solver.materials",
    "resolve_case": "solver.catalogue",
    # inputs and geometry
    "Inputs": "solver.inputs",
    "to_inputs": "solver.inputs",
    "describe_operating_point": "solver.inputs",
    "BearingGeometry": "solver.geometry",
    # the models, through the facade (a case by any name)
    "solve": "solver.facade",
    # bearing sets: the [set] table's choices (docs/case-format.md)
    "ARRANGEMENTS": "solver.case.bearing_set",
    "DIRECTIONS": "solver.case.bearing_set",
    "PRELOAD_KINDS": "solver.case.bearing_set",
    "DEFAULT_PRELOAD_KIND": "solver.case.bearing_set",
    "set_result_warnings": "solver.models.quasistatic.set_warnings",
    "bearing_result": "solver.models.quasistatic.set_warnings",
    "set_spring_preload": "solver.models.quasistatic.set_warnings",
    "set_stiffness_study": "solver.models.quasistatic.bearing_set",
    "solve_quasistatic": "solver.facade",
    "solve_over_revolution": "solver.facade",
    "quasistatic_answer": "solver.facade",
    "quasistatic_speed_sweep": "solver.facade",
    "quasistatic_along_history": "solver.facade",
    "operating_at": "solver.inputs",
    "simulate": "solver.facade",
    "LiveSimulation": "solver.live",
    "LIVE_RAMP": "solver.live",
    "preload": "solver.facade",
    "SimulationOptions": "solver.models.dynamic",
    "INTEGRATION_METHODS": "solver.models.dynamic.options",
    "dynamic_model_compiled": "solver.compiled",
    # results (docs/results-schema.md)
    "save_dataset": "solver.results.io",
    "load_dataset": "solver.results.io",
    "load_result": "solver.results.io",
    "check_result": "solver.results.validate",
    "available_memory_bytes": "solver.results.io",
    "atomic_write": "solver.results.io",
    "probe_write": "solver.results.io",
    "ENGINE": "solver.results.io",
    "contact_table": "solver.results.io",
    "variable": "solver.results.variables",
    "result_warnings": "solver.results.checks",
    "STATIC_PRESSURE_LIMIT": "solver.results.checks",
    "ring_speeds": "solver.results.dataset",
    "OPERATING_FIELDS": "solver.results.dataset",
    "geometry_from_result": "solver.results.dataset",
    "operating_from_result": "solver.results.dataset",
    "shoulder_angle": "solver.physics.hertz",
    "quasistatic_start": "solver.models.quasistatic.result",
    "result_description": "solver.results.dataset",
    "trajectory_summary": "solver.results.summary",
    "stretch_track_summary": "solver.results.summary",
    "STRETCH_VARIABLES": "solver.results.summary",
    "QUASISTATIC_THICKNESS_NOTE": "solver.results.summary",
    "RacetraceAccessor": "solver.results.accessor",
    "METRICS": "solver.results.metrics",
    "loaded_mask": "solver.results.loaded",
    "RPM": "solver.units",
    "RESULTS_VERSION": "solver.results.provenance",
    "result_fingerprint": "solver.results.provenance",
    # studies (docs/study-format.md)
    "Study": "solver.study",
    "StudyFolder": "solver.study",
    "open_study": "solver.study",
    "study_dataset": "solver.study",
    "study_runs": "solver.study",
    "sweep_varied_keys": "solver.study.sweeps",
    "sweep_axis_key": "solver.study.sweeps",
    "shipped_studies": "solver.study",
    "scheduler_address": "solver.study.runner",
    "connect_scheduler": "solver.study.runner",
    "POINT_METRICS": "solver.study.metrics",
    "point_metrics": "solver.study.metrics",
    # the compiled-kernel cache (racetrace cache)
    "active_folder": "solver._numba_cache",
    "cache_folders": "solver._numba_cache",
    "remove_folders": "solver._numba_cache",
}

# ``catalogue`` is both a submodule and the function it defines: import it eagerly (it is light), so
# that ``solver.catalogue`` stays the function even after ``import solver.catalogue``.
from .catalogue import catalogue  # noqa: E402
from .results import accessor as _accessor  # noqa: E402, F401  (registers ds.racetrace)

__all__ = [
    "CaseError",
    "NoSolutionError",
    "Problem",
    "ResultWriteError",
    "SimulationDiverged",
    "__version__",
    "catalogue",
    "clean_message",
    "clip",
    "printable",
    *_LAZY,
]


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'solver' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
