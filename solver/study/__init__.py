"""Studies: many cases around one base case, run on Dask, kept in a study folder.

Public: :class:`Study` (``Study.from_file(path)``, ``.points()``, ``.run(output, ...)``),
:func:`open_study` (a study folder: its Dataset and each point's full result), and the file
format in docs/study-format.md (solver.study.spec). Modules: ``spec`` (the study file), ``points``
(one validated case per point), ``metrics`` (what is kept per point), ``store`` (the study folder),
``sweeps`` (what each sweep of a study Dataset varies), ``runner`` (Dask execution, resume).
"""

from __future__ import annotations

from pathlib import Path

from .metrics import POINT_METRICS, point_metrics
from .points import StudyPoint, base_case, study_points
from .runner import Progress, run_study
from .spec import StudySpec, load_study, parse_study, resolve_study, shipped_studies
from .store import StudyFolder, points_fingerprint, study_dataset, study_inputs, study_runs
from .sweeps import sweep_axis_key, sweep_varied_keys


class Study:
    """A parsed and validated study: ``Study.from_file("seed.toml")`` or ``Study.from_text(...)``.

    ``points()`` lists its points (each with a validated case); ``run(output, ...)`` runs them and
    returns the study Dataset (:func:`solver.study.store.study_dataset`).
    """

    def __init__(self, spec: StudySpec):
        self.spec = spec
        self.base = base_case(spec)
        self._points = study_points(spec, self.base)

    @classmethod
    def from_file(cls, path) -> Study:
        """The study of a study file (or a shipped study's name: ``seed-spindle``); CaseError
        naming each wrong key or point."""
        return cls(resolve_study(path))

    @classmethod
    def from_text(cls, text: str, source: str = "study", folder=None) -> Study:
        return cls(parse_study(text, source, Path(folder) if folder is not None else None))

    @property
    def title(self) -> str:
        return self.spec.title

    def points(self) -> list[StudyPoint]:
        return list(self._points)

    def fingerprint(self) -> str:
        """What the study's results depend on (the points' cases and models and the results
        version); its study Dataset carries it as ``results_fingerprint``."""
        return points_fingerprint(self._points)

    def run(
        self,
        output,
        client=None,
        workers: int | None = None,
        resume: bool = False,
        progress=None,
        cancel=None,
        log=None,
        shared_folder: bool | None = None,
        restart: bool = False,
        accept_solver_change: bool = False,
    ):
        """Run the points not yet finished in the study folder ``output`` and return the study
        Dataset. ``client``: a ``dask.distributed.Client`` (default: a LocalCluster of
        ``workers`` single-threaded processes, closed at the end). ``progress``: callable with a
        :class:`Progress`; ``cancel``: a ``threading.Event`` that stops the study, keeping what is
        done. ``resume``: allowed to continue a folder that holds this study made from the same
        inputs (base case, run options, solver sources; CaseError naming what changed otherwise).
        ``restart``: delete the runs of the study folder ``output`` and run every point again.
        ``accept_solver_change``: on resume, keep the runs made by another solver and record the
        change in the study. ``shared_folder``: the workers write each run into ``output``
        themselves (default: only with the local cluster started here; give True for a
        ``client`` whose workers share this file system)."""
        import solver
        from solver._numba_cache import SOLVER_DIR, source_fingerprint

        folder = run_study(
            self.spec,
            self._points,
            output,
            client=client,
            workers=workers,
            resume=resume,
            progress=progress,
            cancel=cancel,
            version=solver.__version__,
            log=log,
            shared_folder=shared_folder,
            inputs=study_inputs(self.spec, self.base, source_fingerprint(SOLVER_DIR)),
            restart=restart,
            accept_solver_change=accept_solver_change,
        )
        return study_dataset(folder)


def open_study(path) -> StudyFolder:
    """A study folder written by :meth:`Study.run`: ``.manifest()``, ``.load_point(name, model)``
    and :func:`study_dataset` of it."""
    folder = StudyFolder(path)
    folder.finished()  # CaseError when the manifest or a run record is not one a study writes
    return folder


__all__ = [
    "POINT_METRICS",
    "Progress",
    "Study",
    "StudyFolder",
    "StudyPoint",
    "StudySpec",
    "base_case",
    "load_study",
    "open_study",
    "parse_study",
    "point_metrics",
    "points_fingerprint",
    "resolve_study",
    "run_study",
    "shipped_studies",
    "study_dataset",
    "study_points",
    "study_runs",
    "sweep_axis_key",
    "sweep_varied_keys",
]
