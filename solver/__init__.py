"""racetrace solver: case files, Hertz contact, quasi-static and dynamic ball-bearing models.

Public API (everything else is internal):

- ``load_case(path) -> Case`` (a case file), ``parse_case(text, source=...) -> Case`` (TOML text)
  and ``Case.to_toml()``
- ``catalogue()``: shipped bearings and example cases
- ``dynamic_problems(case) -> list[Problem]``: why the dynamic model cannot run a valid case
- ``to_inputs(case) -> Inputs``: the SI inputs both models read
- ``solve_quasistatic(case) -> xarray.Dataset`` (results-schema.md)
- ``solve_over_revolution(case, angles=36) -> xarray.Dataset``: the quasi-static steady state at
  inner-ring angles over one shaft revolution (dimension ``ring_angle``)
- ``simulate(case, progress=None, cancel=None, options=None) -> xarray.Dataset`` (dynamic model;
  ``SimulationOptions`` overrides the case's ``[simulation]`` values and sets numerical knobs;
  ``INTEGRATION_METHODS``: the names its option ``method`` takes)
- ``result_warnings(ds) -> list[str]``: where a result leaves the model's validity
- the ``racetrace`` accessor on every xarray Dataset, registered by ``import solver``:
  ``ds.racetrace.summary()`` (trajectory metrics, ``trajectory_summary``), ``.warnings()``,
  ``.save(path)`` (NetCDF) and ``.to_csv(path)`` (per-contact table, ``contact_table``)
- ``Study.from_file(path)`` / ``open_study(folder)``: parameter studies run on Dask
  (docs/study-format.md)
- ``CaseError`` (invalid input), ``NoSolutionError`` (no solution for a valid case),
  ``SimulationDiverged`` (the dynamic integration failed), ``ResultWriteError`` (a result file
  could not be written; an OSError naming the file)

The numba kernels are imported on first use; registering the accessor imports xarray.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

from ._numba_cache import SOLVER_DIR, configure_numba_cache
from .errors import CaseError, NoSolutionError, Problem, ResultWriteError, SimulationDiverged

# Before any kernel is defined: compiled kernels are cached per version of the solver sources.
configure_numba_cache(SOLVER_DIR)

try:
    __version__ = version("racetrace")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

# public name -> module that defines it
_LAZY = {
    "Case": "solver.case",
    "load_case": "solver.case",
    "parse_case": "solver.case",
    "dynamic_problems": "solver.case",
    "Inputs": "solver.inputs",
    "to_inputs": "solver.inputs",
    "SimulationOptions": "solver.models.dynamic",
    "BearingGeometry": "solver.geometry",
    "solve_quasistatic": "solver.models.quasistatic",
    "solve_over_revolution": "solver.models.quasistatic",
    "simulate": "solver.models.dynamic",
    "INTEGRATION_METHODS": "solver.models.dynamic.options",
    "save_dataset": "solver.results.io",
    "load_dataset": "solver.results.io",
    "result_warnings": "solver.results.checks",
    "trajectory_summary": "solver.results.summary",
    "Study": "solver.study",
    "open_study": "solver.study",
    "contact_table": "solver.results.io",
    "RacetraceAccessor": "solver.results.accessor",
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
    *_LAZY,
]


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'solver' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
