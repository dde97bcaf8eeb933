"""Phases of a dynamic result: the parts of the run between the event times of its operating
history, each an analysed window of its own (results-schema.md, "Phases").

A result computed along a history (issue 24: speeds and loads that change in time) carries the
history's event times inside the run as the attribute ``phase_boundaries_s`` (a sorted array of
times [s] strictly between 0 and the end of the run: the knot times of
:func:`solver.history.event_times`, where a ramp starts or ends or a step occurs) and, optionally,
one label per phase in ``phase_labels`` (:func:`phase_attributes` writes both). The boundaries
e_1 < ... < e_k cut the run into k + 1 phases [0, e_1), [e_1, e_2), ..., [e_k, t_end]: before
and after a step, before, during and after a ramp. Each phase is analysed over every sample it
holds, the transient after its event included (a phase is what the history did, not the part of
it that settled).

A result without the attribute (every steady result) has one phase: its analysed window
(``analysis_start_time`` to the end, :mod:`solver.results.summary`), so that its metrics by phase
are its metrics.

:func:`phase_mask` gives the samples of each phase as a boolean DataArray (``phase``, ``time``)
with the coordinates ``phase_start_time`` and ``phase_end_time`` [s] and ``phase_label``;
:class:`solver.results.metrics.Window` takes it as its time mask, so that every metric of the
table comes out per phase (``ds.racetrace.phase_metrics()``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

#: The attribute holding the event times [s] inside the run.
PHASE_BOUNDARIES_ATTRIBUTE = "phase_boundaries_s"
#: The attribute holding one label per phase (optional).
PHASE_LABELS_ATTRIBUTE = "phase_labels"
#: Coordinates of the ``phase`` dimension.
PHASE_COORDINATES = ("phase_start_time", "phase_end_time", "phase_label")


@dataclass(frozen=True)
class Phase:
    """One phase: from ``start`` to ``end`` [s] (``end`` included for the last phase only) and its
    label."""

    start: float
    end: float
    label: str
    last: bool


def boundaries(ds: xr.Dataset) -> np.ndarray:
    """The event times [s] of the result inside the run (empty for a steady result). ValueError
    naming the attribute when they are not increasing times inside the run."""
    raw = ds.attrs.get(PHASE_BOUNDARIES_ATTRIBUTE)
    if raw is None:
        return np.zeros(0)
    times = np.atleast_1d(np.asarray(raw, dtype=float))
    end = float(ds["time"].values[-1])
    if not (np.all(np.isfinite(times)) and np.all(np.diff(times) > 0.0)):
        raise ValueError(
            f"attribute {PHASE_BOUNDARIES_ATTRIBUTE} = {times.tolist()}: the event times must be "
            "finite and increasing"
        )
    if times.size and not (times[0] > 0.0 and times[-1] < end):
        raise ValueError(
            f"attribute {PHASE_BOUNDARIES_ATTRIBUTE} = {times.tolist()}: the event times must lie "
            f"inside the run (0 s, {end:g} s)"
        )
    return times


def phases(ds: xr.Dataset) -> list[Phase]:
    """The phases of a dynamic result (module docstring)."""
    times = np.asarray(ds["time"].values, dtype=float)
    events = boundaries(ds)
    end = float(times[-1])
    if events.size == 0 and PHASE_BOUNDARIES_ATTRIBUTE not in ds.attrs:
        from .summary import summary

        start = float(summary(ds)["analysis_start_time"])
        return [Phase(start, end, "the analysed window", True)]
    edges = [float(times[0]), *events.tolist(), end]
    labels = ds.attrs.get(PHASE_LABELS_ATTRIBUTE)
    labels = [str(x) for x in np.atleast_1d(labels)] if labels is not None else []
    if labels and len(labels) != len(edges) - 1:
        raise ValueError(
            f"attribute {PHASE_LABELS_ATTRIBUTE} holds {len(labels)} labels for "
            f"{len(edges) - 1} phases"
        )
    return [
        Phase(
            edges[k],
            edges[k + 1],
            labels[k] if labels else f"t from {edges[k]:.6g} s to {edges[k + 1]:.6g} s",
            k == len(edges) - 2,
        )
        for k in range(len(edges) - 1)
    ]


def phase_mask(ds: xr.Dataset) -> xr.DataArray:
    """Samples of each phase: bool (``phase``, ``time``), True where start <= t < end (t <= end
    in the last phase), with the :data:`PHASE_COORDINATES` along ``phase``."""
    times = np.asarray(ds["time"].values, dtype=float)
    found = phases(ds)
    mask = np.array(
        [(times >= p.start) & ((times <= p.end) if p.last else (times < p.end)) for p in found]
    )
    return xr.DataArray(
        mask,
        dims=("phase", "time"),
        coords={
            "phase": np.arange(len(found)),
            "time": ds["time"].values,
            "phase_start_time": ("phase", [p.start for p in found]),
            "phase_end_time": ("phase", [p.end for p in found]),
            "phase_label": ("phase", [p.label for p in found]),
        },
    )


def phase_attributes(record, end: float) -> dict:
    """The attributes :data:`PHASE_BOUNDARIES_ATTRIBUTE` and :data:`PHASE_LABELS_ATTRIBUTE` of a
    run of ``end`` [s] along the history ``record`` (:class:`solver.history.HistoryRecord`); {}
    when no event lies inside the run. A phase's label names the channels that change over it
    and the steps at its start, e.g. "t from 0.05 s to 0.2 s: after the step of radial_load"."""
    from solver.history import CHANNEL_NAMES, N_CHANNELS, channel_value, event_times

    events = event_times(record, 0.0, end)
    if events.size == 0:
        return {}
    edges = [0.0, *events.tolist(), float(end)]
    labels = []
    for k in range(len(edges) - 1):
        start, stop = edges[k], edges[k + 1]
        inside = start + 0.5 * (stop - start)
        words = []
        for c in range(N_CHANNELS):
            knots = record.times[c, : record.counts[c]]
            if k > 0 and np.count_nonzero(knots == start) >= 2:
                words.append(f"after the step of {CHANNEL_NAMES[c]}")
            ahead = channel_value(record, c, start)
            if not math.isclose(ahead, channel_value(record, c, inside), rel_tol=1e-12):
                words.append(f"{CHANNEL_NAMES[c]} changing")
        what = "; ".join(words) if words else "inputs held"
        labels.append(f"t from {start:.6g} s to {stop:.6g} s: {what}")
    return {PHASE_BOUNDARIES_ATTRIBUTE: events, PHASE_LABELS_ATTRIBUTE: labels}


__all__ = [
    "PHASE_BOUNDARIES_ATTRIBUTE",
    "PHASE_COORDINATES",
    "PHASE_LABELS_ATTRIBUTE",
    "Phase",
    "boundaries",
    "phase_attributes",
    "phase_mask",
    "phases",
]
