"""racetrace solver: case files, Hertz contact, quasi-static and dynamic ball-bearing models.

Public API (everything else is internal):

- ``load_case(path_or_text) -> Case`` and ``Case.to_toml()``
- ``catalogue()``: shipped bearings and example cases
- ``solve_quasistatic(case) -> xarray.Dataset`` (results-schema.md)
- ``CaseError`` (invalid input) and ``NoSolutionError`` (no solution for a valid case)
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("racetrace")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

from .errors import CaseError, NoSolutionError, Problem, SimulationDiverged  # noqa: E402

__all__ = ["CaseError", "NoSolutionError", "Problem", "SimulationDiverged", "__version__"]
