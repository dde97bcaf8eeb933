"""The ``racetrace`` accessor on xarray Datasets: the one export door for scripts, the CLI and the
app.

``import solver`` registers it, so every results Dataset offers (results-schema.md)::

    ds.racetrace.summary()    # trajectory metrics (solver.results.summary), with units
    ds.racetrace.metrics()    # the metrics table (solver.results.metrics), with units
    ds.racetrace.metric(name) # one metric of the table (a DataArray)
    ds.racetrace.phase_metrics() # the metrics table per phase of a history (solver.results.phases)
    ds.racetrace.phase_metric(name) # one metric per phase
    ds.racetrace.phases()     # the phases: start and end time [s], label
    ds.racetrace.skid_extent() # when and how much the cage lagged (solver.results.skidding)
    ds.racetrace.warnings()   # list[str]: where the result leaves the model's validity
    ds.racetrace.save(path)   # NetCDF, written atomically
    ds.racetrace.to_csv(path) # per-contact table: one row per (time,) ball and race

PNG images and MP4 animations of the 3-D view need the app's renderer: the app exports them.
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from . import checks, io, phases, skidding, summary
from .metrics import METRICS, Window, compute_metric, metrics_table

ACCESSOR_NAME = "racetrace"


#: The case of a result not parsed yet (None is a result without a readable case).
_UNREAD = object()


class RacetraceAccessor:
    """Methods of ``ds.racetrace`` (see the module docstring)."""

    def __init__(self, ds: xr.Dataset):
        self._ds = ds
        self._window: Window | None = None
        self._metrics: dict[str, xr.DataArray] = {}
        self._case = _UNREAD

    def metric(self, name: str) -> xr.DataArray:
        """Metric ``name`` of the metrics table (:data:`solver.results.metrics.METRICS`), with
        ``units``, ``long_name`` and ``description``; computed once per Dataset (xarray keeps one
        accessor per Dataset object: a Dataset changed in place after the first call keeps the
        metrics of its earlier values). KeyError naming the known metrics for another name."""
        if name not in self._metrics:
            if self._window is None:
                self._window = Window(self._ds)
            self._metrics[name] = compute_metric(self._window, name)
        return self._metrics[name]

    def metrics(self) -> xr.Dataset:
        """Every metric of the table as one Dataset (cached like :meth:`metric`)."""
        return xr.Dataset({name: self.metric(name) for name in METRICS})

    def phase_metrics(self) -> xr.Dataset:
        """Every metric of the table per phase of the result (:mod:`solver.results.phases`), a
        ``phase`` dimension with ``phase_start_time``, ``phase_end_time`` and ``phase_label``;
        a steady result has one phase, its analysed window. Computed at each call."""
        return metrics_table(self._ds, by_phase=True)

    def phase_metric(self, name: str) -> xr.DataArray:
        """Metric ``name`` per phase of the result (a ``phase`` dimension, as
        :meth:`phase_metrics`), computed at each call."""
        return compute_metric(Window(self._ds, by_phase=True), name)

    def phases(self) -> list:
        """The result's phases (:func:`solver.results.phases.phases`): start and end time [s]
        and label of each; a steady result has one phase, its analysed window."""
        return phases.phases(self._ds)

    def skid_extent(self, within=None):
        """When and how much the cage lagged its rolling speed
        (:func:`solver.results.skidding.skid_extent`); None when it never lagged by more than the
        skidding threshold or the result is not dynamic."""
        return skidding.skid_extent(self._ds, within)

    def summary(self) -> xr.Dataset:
        """The trajectory metrics: those stored in the result (a dynamic run), otherwise computed
        from its data by :func:`solver.results.summary.trajectory_summary`. Each variable has
        ``units``, ``long_name`` and ``description``."""
        return summary.summary(self._ds)

    def warnings(self) -> list[str]:
        """:func:`solver.results.checks.result_warnings` of the result (plain-text messages)."""
        return checks.result_warnings(self._ds)

    def case(self):
        """The case the result was solved from (its provenance attribute ``case``, parsed once and
        kept), or None when the result holds no case text or one that no longer parses (a case
        file format of another version). For re-opening a run's case in an editor and for its
        case warnings; what the result *is* is read from its coordinates and variables."""
        if self._case is _UNREAD:
            from solver.case import parse_case
            from solver.errors import CaseError

            text = str(self._ds.attrs.get("case", ""))
            try:
                self._case = parse_case(text, "the result's case") if text else None
            except CaseError:
                self._case = None
        return self._case

    def save(self, path) -> Path:
        """Write the result as NetCDF to ``path`` atomically (the temporary file is removed if
        writing fails); returns the path."""
        return io.save_dataset(self._ds, path)

    def to_csv(self, path) -> Path:
        """Write the per-contact table (:func:`solver.results.io.contact_table`) as CSV to
        ``path`` atomically; returns the path."""
        return io.save_csv(self._ds, path)


def register() -> None:
    """Register the accessor as ``racetrace`` on xarray Datasets (once per process)."""
    if ACCESSOR_NAME not in xr.Dataset.__dict__:
        xr.register_dataset_accessor(ACCESSOR_NAME)(RacetraceAccessor)


register()

__all__ = ["ACCESSOR_NAME", "RacetraceAccessor", "register"]
