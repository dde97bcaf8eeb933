"""What runs on a Dask worker: the numba warm-up plugin and the run of one batch of points.

Imported by solver.study.runner only when a study runs (it imports ``dask.distributed``).
"""

from __future__ import annotations

import os
import time

from distributed import WorkerPlugin

from .store import DONE, FAILED


def warm_up(cases=None) -> str:
    """Load (or compile, the first time on a machine) the numba kernels the runs will use: for
    each ``(model, case)`` of ``cases`` (:func:`warm_up_cases`) solve the case quasi-statically or
    integrate a few hundredths of a revolution of it (so that the traction path of its lubricant,
    slip curve or rheology, is compiled too). Without ``cases``: a catalogue case, both models.
    A case that fails here is left to its run, which reports it."""
    import solver
    from solver.errors import CaseError, NoSolutionError, SimulationDiverged
    from solver.models.dynamic import SimulationOptions

    if cases is None:
        case = solver.catalogue().get("spindle-combined-load").load()
        cases = [("quasistatic", case), ("dynamic", case)]
    for model, case in cases:
        try:
            if model == "quasistatic":  # a bearing set's model for a set case
                solver.solve(case)
            else:
                solver.simulate(case, options=SimulationOptions(shaft_revolutions=0.02))
        except (CaseError, NoSolutionError, SimulationDiverged, ValueError, FloatingPointError):
            continue
    return "warm"


def _traction_path(case) -> str:
    lubricant = getattr(case, "lubricant", None)
    return "dry" if lubricant is None else str(lubricant.traction_model)


def warm_up_cases(points) -> list:
    """``[(model, case)]``: one point's case for each model and lubricant traction path the
    study's points use (the kernels a study compiles are those of its own runs)."""
    chosen: dict[tuple[str, str], object] = {}
    for point in points:
        for model in point.models:
            chosen.setdefault((model, _traction_path(point.case)), point.case)
    return [(model, case) for (model, _path), case in chosen.items()]


class WarmUp(WorkerPlugin):
    """Warms the kernels once when a worker starts, also a worker that Dask restarts after a
    crash, so that no task pays for loading them. ``cases``: as :func:`warm_up` takes them."""

    name = "racetrace-warm-up"
    idempotent = True  # registering again (each study on the same cluster) keeps the warm workers

    def __init__(self, cases=None):
        self.cases = cases

    def setup(self, worker):  # noqa: ARG002 - the plugin interface
        warm_up(self.cases)


def run_one(case, model: str) -> tuple[dict, object]:
    """Run one model on one case: (record, result Dataset or None). A case the model cannot solve
    gives a ``failed`` record with the message, never an exception."""
    import solver
    from solver.errors import CaseError, NoSolutionError, SimulationDiverged

    from .metrics import run_metrics

    start = time.perf_counter()
    ds = None
    try:
        if model == "quasistatic":  # over one revolution for a tilt turning with the ring; the
            ds = solver.solve(case)  # set's model for a bearing set
        else:
            ds = solver.simulate(case)
        record = {"status": DONE, "message": "", "metrics": run_metrics(ds)}
        if "bearing" in ds.dims:
            warnings = solver.set_result_warnings(ds)
        else:
            warnings = ds.racetrace.warnings()
        if warnings:
            record["message"] = " | ".join(warnings)
    except SimulationDiverged as error:
        ds = getattr(error, "dataset", None)
        record = {"status": FAILED, "message": f"diverged: {error}"}
    except (NoSolutionError, CaseError, ValueError, FloatingPointError) as error:
        record = {"status": FAILED, "message": f"{type(error).__name__}: {error}"}
    record["wall_time_s"] = time.perf_counter() - start
    record["worker_pid"] = os.getpid()
    return record, ds


def run_batch(items: list, folder=None) -> list:
    """Run ``[(point name, model, case), ...]`` one after the other (one Dask task):
    ``[(point name, model, record, Dataset or None), ...]``.

    With ``folder`` (the study folder, when the worker shares the client's file system) each run
    is saved there by the worker as soon as it finishes (result, then record) and comes back
    without its Dataset, ``record["saved"]`` True."""
    from .store import StudyFolder

    out = []
    for name, model, case in items:
        record, ds = run_one(case, model)
        if folder is not None:
            record["saved"] = True
            StudyFolder(folder).save_run(name, model, record, ds)
            ds = None
        out.append((name, model, record, ds))
    return out
