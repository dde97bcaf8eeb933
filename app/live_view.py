"""What the page shows of a live session, built from the chunk Datasets the live solver sends:
the sliding window of the last :data:`WINDOW_REVOLUTIONS` shaft revolutions (3-D view frames and
time charts), the painted tracks accumulated over the whole session, and the inner track's band
thickness over the last :data:`BAND_REVOLUTIONS` revolutions.

Everything here reads Datasets (results-schema.md) only; no rendering.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from viz.frames import FrameSource

#: The charts and the 3-D view's frames cover the last this many shaft revolutions.
WINDOW_REVOLUTIONS = 5.0
#: The live band thickness is measured over the last this many shaft revolutions.
BAND_REVOLUTIONS = 2.0
#: With the rings at rest (no revolution to count) the window keeps this much bearing time (s).
AT_REST_WINDOW_S = 0.05


def shaft_period(inputs: dict) -> float:
    """Period of one revolution of the inner ring relative to the outer one (s) from the inputs
    now (``inner_ring_speed``, ``outer_ring_speed`` in rad/s); inf with the rings at rest."""
    inner = float(inputs.get("inner_ring_speed", 0.0))
    relative = abs(inner - float(inputs.get("outer_ring_speed", 0.0)))
    return 2.0 * math.pi / relative if relative > 0.0 else math.inf


def _with_time(ds: xr.Dataset, names) -> xr.Dataset:
    """``ds`` with each variable of ``names`` as a data variable over ``time`` (a constant one
    broadcast), so that chunks where an input is constant and chunks where it varies join."""
    for name in names:
        if name not in ds.variables or "time" in ds[name].dims:
            continue
        if name in ds.coords:
            ds = ds.reset_coords(name)
        ds[name] = ds[name].expand_dims(time=ds["time"]).copy()
    return ds


def join_chunks(chunks: list[xr.Dataset]) -> xr.Dataset:
    """The chunks of a session, in time order, joined along ``time`` in one concatenation (a
    sample an earlier chunk holds is kept once). Concatenating them pairwise would copy the
    growing result at every step: about ten times the cost for the ten chunks of two
    revolutions."""
    parts, t_end = [], -math.inf
    for chunk in chunks:
        times = np.asarray(chunk["time"].values, float)
        if times.size and times[0] <= t_end:
            chunk = chunk.isel(time=times > t_end)
        if chunk.sizes.get("time", 0) == 0:
            continue
        parts.append(chunk)
        t_end = float(chunk["time"][-1])
    if len(parts) <= 1:
        return parts[0] if parts else chunks[-1]
    timed = {n for ds in parts for n, v in ds.variables.items() if "time" in v.dims and n != "time"}
    return xr.concat(
        [_with_time(ds, timed) for ds in parts],
        dim="time",
        data_vars="minimal",
        coords="minimal",
        compat="override",
        join="override",
        combine_attrs="override",
    )


def last_stretch(ds: xr.Dataset, duration_s: float) -> xr.Dataset:
    """The samples of ``ds`` in its last ``duration_s`` seconds (all when inf)."""
    if not math.isfinite(duration_s):
        return ds
    t = np.asarray(ds["time"].values, float)
    return ds.isel(time=slice(int(np.searchsorted(t, t[-1] - duration_s)), None))


#: Inputs the window keeps per sample (SI), for the words and data of the frame on show.
FRAME_INPUTS = ("inner_ring_speed", "outer_ring_speed", "radial_load", "axial_load", "misalignment")


def input_values(ds: xr.Dataset, name: str) -> np.ndarray:
    """Input ``name`` of ``ds`` at each of its time samples (a variable over ``time``, or a
    constant repeated); NaN when ``ds`` has none."""
    n = ds.sizes["time"]
    if name not in ds.variables:
        return np.full(n, np.nan)
    var = ds.variables[name]  # a bare Variable: no coordinates attached
    if "time" in var.dims:
        return np.asarray(var.transpose("time", ...).values, float).reshape(n)
    return np.full(n, float(var))


def _concat(a: FrameSource, b: FrameSource) -> FrameSource:
    """The frames of ``a`` then those of ``b`` (whose angles already continue ``a``'s)."""

    def cat(x, y):
        return np.concatenate([x, y])

    return FrameSource(
        "dynamic",
        cat(a.times, b.times),
        cat(a.ball_center, b.ball_center),
        cat(a.ball_rotation, b.ball_rotation),
        cat(a.ball_azimuth, b.ball_azimuth),
        cat(a.ring_angle, b.ring_angle),
        cat(a.cage_angle, b.cage_angle),
        {k: cat(v, b.contact[k]) for k, v in a.contact.items() if k in b.contact},
        cat(a.raceway_azimuth, b.raceway_azimuth),
    )


def continue_source(old: FrameSource, new: FrameSource) -> FrameSource:
    """``new`` (the frames of the next chunk, read alone) with its accumulated angles continuing
    ``old``'s: the unwrapped azimuths (balls, raceway contacts) by whole turns to the nearest of
    ``old``'s last, the ring and cage turns (counted from the chunk's first sample) from ``old``'s
    last turned on at ``old``'s last rate over the time between the two samples."""
    two_pi = 2.0 * math.pi
    dt = float(new.times[0] - old.times[-1])
    step = float(old.times[-1] - old.times[-2]) if old.n_frames > 1 else 0.0

    def whole_turns(a, b):
        return b + two_pi * np.round((a[-1] - b[0]) / two_pi)

    def turned_on(a, b):
        rate = (a[-1] - a[-2]) / step if step > 0 else 0.0 * a[-1]
        return b - b[0] + a[-1] + rate * dt

    return FrameSource(
        "dynamic",
        new.times,
        new.ball_center,
        new.ball_rotation,
        whole_turns(old.ball_azimuth, new.ball_azimuth),
        turned_on(old.ring_angle, new.ring_angle),
        turned_on(old.cage_angle, new.cage_angle),
        new.contact,
        whole_turns(old.raceway_azimuth, new.raceway_azimuth),
    )


def source_since(src: FrameSource, first: int) -> FrameSource:
    """The frames of ``src`` from index ``first`` on."""
    if first <= 0:
        return src
    return FrameSource(
        src.model,
        src.times[first:],
        src.ball_center[first:],
        src.ball_rotation[first:],
        src.ball_azimuth[first:],
        src.ring_angle[first:],
        src.cage_angle[first:],
        {k: v[first:] for k, v in src.contact.items()},
        src.raceway_azimuth[first:],
    )


class LiveWindow:
    """The sliding window of a live session: the frames (``source``), the inputs at each frame
    (``inputs``, SI) and the chunk Datasets (``chunks``) of the last ``revolutions`` shaft
    revolutions. Each chunk is read into frames once (:meth:`add` returns the frames of the new
    samples, with the sample before them, for the painted tracks)."""

    def __init__(self, revolutions: float = WINDOW_REVOLUTIONS):
        self.revolutions = float(revolutions)
        self.clear()

    def clear(self) -> None:
        self.source: FrameSource | None = None
        self.inputs: dict[str, np.ndarray] = {}
        self.chunks: list[xr.Dataset] = []
        self.count = 0  # chunks received since the start or the last reset

    def add(self, chunk: xr.Dataset, inputs_now: dict) -> FrameSource:
        """Append ``chunk`` and drop what is older than the window (by the shaft period of the
        inputs now, ``inputs_now``); the frames of the new samples (see the class docstring)."""
        if self.source is not None:  # a sample the window holds is not taken again
            new_times = np.asarray(chunk["time"].values, float)
            chunk = chunk.isel(time=np.flatnonzero(new_times > self.source.times[-1]))
        if chunk.sizes["time"] == 0:
            return source_since(self.source, self.source.n_frames - 1)
        new = FrameSource.from_dynamic(chunk)
        values = {name: input_values(chunk, name) for name in FRAME_INPUTS}
        if self.source is None:
            self.source, self.inputs, painted = new, values, new
        else:
            new = continue_source(self.source, new)
            painted = _concat(source_since(self.source, self.source.n_frames - 1), new)
            self.source = _concat(self.source, new)
            self.inputs = {k: np.concatenate([v, values[k]]) for k, v in self.inputs.items()}
        self.chunks.append(chunk)
        self.count += 1
        period = shaft_period(inputs_now)
        keep = self.revolutions * period if math.isfinite(period) else AT_REST_WINDOW_S
        times = self.source.times
        first = int(np.searchsorted(times, times[-1] - keep))
        self.source = source_since(self.source, first)
        self.inputs = {k: v[first:] for k, v in self.inputs.items()}
        while len(self.chunks) > 1 and float(self.chunks[1]["time"][0]) <= self.source.times[0]:
            self.chunks.pop(0)
        return painted

    def dataset(self, duration_s: float = math.inf, names=None) -> xr.Dataset | None:
        """The chunks of the last ``duration_s`` seconds joined into one Dataset (None: none);
        ``names``: only these variables (those a chunk has) and their coordinates, which joins
        in a fraction of the time of every variable."""
        if not self.chunks:
            return None
        end = float(self.chunks[-1]["time"][-1])
        first = len(self.chunks) - 1
        while first > 0 and float(self.chunks[first]["time"][0]) > end - duration_s:
            first -= 1
        chunks = self.chunks[first:]
        if names is not None:
            chunks = [chunk[[n for n in names if n in chunk.variables]] for chunk in chunks]
        return last_stretch(join_chunks(chunks), duration_s)


def band_thickness(window: LiveWindow, inputs: dict, race: str = "inner") -> float:
    """Band thickness (degree) of ``race``'s track in its own ring's frame over the last
    :data:`BAND_REVOLUTIONS` of ``window`` (``solver.stretch_track_summary``: the whole stretch
    analysed, only the variables it reads joined); NaN while the stretch is too short to give
    one."""
    from solver import STRETCH_VARIABLES, stretch_track_summary

    period = shaft_period(inputs)
    if not math.isfinite(period) or not window.chunks:
        return math.nan
    stretch = window.dataset(BAND_REVOLUTIONS * period, names=STRETCH_VARIABLES)
    if stretch.sizes["time"] < 3:
        return math.nan
    span = float(stretch["time"][-1] - stretch["time"][0])
    if span < 0.9 * BAND_REVOLUTIONS * period:
        return math.nan
    metrics = stretch_track_summary(stretch)
    value = metrics["trajectory_band_thickness"].sel(race=race, frame=f"{race}_ring")
    return float(value)


class LiveTracks:
    """The painted tracks of a live session: dwell (summed) and peak pressure (highest) of every
    chunk, accumulated over the session. It offers what :class:`viz.painted.PaintedRaceways`
    reads of a :class:`viz.tracks.TrackPainter` (``accumulate``, ``field``, ``painted``,
    ``value_range``), so the scene paints it like a run's tracks."""

    def __init__(self, grooves, grids, references, exaggeration: float):
        self.grooves, self.grids = grooves, tuple(grids)
        self.references = tuple(references)
        self.exaggeration = float(exaggeration)
        self.reset()

    def reset(self) -> None:
        self._dwell = [np.zeros((g.n_phi, g.n_alpha)) for g in self.grids]
        self._peak = [np.zeros((g.n_phi, g.n_alpha)) for g in self.grids]
        self.stop = 0  # samples painted so far (what a TrackPainter calls its stop)

    def add(self, source) -> None:
        """Paint every sample of ``source`` (:class:`viz.frames.FrameSource` of the new samples
        and the one before them, which carries each ellipse's sweep to the first new one)."""
        from viz.tracks import TrackPainter

        painter = TrackPainter(
            source, self.grooves, self.grids, self.references, exaggeration=self.exaggeration
        )
        painter.accumulate(source.n_frames - 1)  # the last sample sweeps on with the next chunk
        self.stop += source.n_frames - 1
        for race in (0, 1):
            self._dwell[race] += painter.field(race, "dwell")
            np.maximum(self._peak[race], painter.field(race, "peak_pressure"), out=self._peak[race])

    # the TrackPainter interface read by viz.painted.PaintedRaceways
    def accumulate(self, stop: int) -> None:
        """Nothing to do: the fields grow as chunks arrive (:meth:`add`)."""

    def field(self, race: int, quantity: str) -> np.ndarray:
        if quantity not in ("dwell", "peak_pressure"):
            raise ValueError(f"unknown track quantity {quantity!r}; use dwell or peak_pressure")
        return (self._dwell if quantity == "dwell" else self._peak)[race]

    def painted(self, race: int) -> np.ndarray:
        return self._dwell[race] > 0.0

    def value_range(self, quantity: str) -> tuple[float, float]:
        values = np.concatenate([self.field(r, quantity)[self.painted(r)] for r in (0, 1)])
        if values.size == 0:
            return 0.0, 0.0
        return float(values.min()), float(values.max())
