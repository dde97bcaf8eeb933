"""The numba record of an operating history, and its builders.

Channels (one per operating input, SI units, the signs of :class:`solver.inputs.OperatingPoint`):
``CH_INNER_SPEED``/``CH_OUTER_SPEED`` [rad/s], ``CH_AXIAL_LOAD``/``CH_RADIAL_LOAD`` [N],
``CH_RADIAL_LOAD_ANGLE`` [rad] (azimuth of the radial load, in space or in the inner ring's frame:
``radial_load_frame``), ``CH_MISALIGNMENT``/``CH_MISALIGNMENT_AXIS`` [rad] (imposed tilt and the
azimuth of its axis), ``CH_TILTING_MOMENT`` [N m] and ``CH_MOMENT_AXIS`` [rad] (free tilt).

A channel's value at time t [s]::

    v(t) = table(t) + amplitude * sin(2 pi frequency t + phase) + rate * t

``table(t)``: the knots (t_k, v_k), k < count, times non-decreasing; constant before the first
knot and after the last; between two knots linear (``SEGMENT_LINEAR``) or the C1 smooth step
v_k + (v_k+1 - v_k) (3 s^2 - 2 s^3), s = (t - t_k)/(t_k+1 - t_k) (``SEGMENT_SMOOTH``; the segment
kind is that of its first knot). Two knots at one time are a step: the value jumps there and is the
later knot's from that time on (right-continuous). A rotating load is a radial-load angle with a
``rate`` (in space) or a constant angle in the inner ring's frame (``FRAME_INNER_RING``: turning
with the shaft whatever its speed).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

CH_INNER_SPEED = 0
CH_OUTER_SPEED = 1
CH_AXIAL_LOAD = 2
CH_RADIAL_LOAD = 3
CH_RADIAL_LOAD_ANGLE = 4
CH_MISALIGNMENT = 5
CH_MISALIGNMENT_AXIS = 6
CH_TILTING_MOMENT = 7
CH_MOMENT_AXIS = 8
N_CHANNELS = 9
CHANNEL_NAMES = (
    "inner_ring_speed",
    "outer_ring_speed",
    "axial_load",
    "radial_load",
    "radial_load_angle",
    "misalignment",
    "misalignment_axis",
    "tilting_moment",
    "moment_axis",
)  # index = channel constant; the OperatingPoint field each channel varies

SEGMENT_LINEAR = 0
SEGMENT_SMOOTH = 1

FRAME_SPACE = 0  # the radial load's angle is an azimuth fixed in space
FRAME_INNER_RING = 1  # ... measured in the inner ring's frame (turns with the shaft)


class HistoryRecord(NamedTuple):
    """All channels of one history, padded to the longest table (numba reads it as one record).

    ``times``, ``values``, ``segments``: (N_CHANNELS, K) knots [s], values [SI], segment kinds;
    ``counts``: (N_CHANNELS,) knots used per channel (>= 1); ``amplitude``, ``frequency`` [Hz],
    ``phase`` [rad], ``rate`` [SI/s]: (N_CHANNELS,) the sine and the rate;
    ``radial_load_frame``: FRAME_SPACE or FRAME_INNER_RING; ``tilt_free``: the tilt is solved
    under the moment channels (else imposed by the misalignment channels).
    """

    times: np.ndarray
    values: np.ndarray
    segments: np.ndarray
    counts: np.ndarray
    amplitude: np.ndarray
    frequency: np.ndarray
    phase: np.ndarray
    rate: np.ndarray
    radial_load_frame: int
    tilt_free: bool


@dataclass(frozen=True)
class ChannelHistory:
    """One channel's history (SI units): knots, segment kinds (one per knot, the kind of the
    segment that starts there; default linear), and the sine and rate terms."""

    times: tuple[float, ...]
    values: tuple[float, ...]
    segments: tuple[int, ...] = ()
    amplitude: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    rate: float = 0.0

    @staticmethod
    def constant(value: float) -> ChannelHistory:
        return ChannelHistory((0.0,), (float(value),))

    def __post_init__(self):
        if len(self.times) != len(self.values) or not self.times:
            raise ValueError("a channel history needs as many times as values, at least one")
        if np.any(np.diff(np.asarray(self.times, float)) < 0.0):
            raise ValueError("a channel history's times must not decrease")
        if self.segments and len(self.segments) != len(self.times):
            raise ValueError("a channel history gives one segment kind per knot, or none")
        if not np.all(np.isfinite(self.times)) or not np.all(np.isfinite(self.values)):
            raise ValueError("a channel history's times and values must be finite")

    @property
    def is_constant(self) -> bool:
        v = self.values
        return all(x == v[0] for x in v) and self.amplitude == 0.0 and self.rate == 0.0


def history_record(
    channels: dict[int, ChannelHistory],
    base: dict[int, float],
    radial_load_frame: int = FRAME_SPACE,
    tilt_free: bool = False,
) -> HistoryRecord:
    """The record of ``channels`` (channel constant -> history); every other channel is constant
    at its value in ``base`` (channel constant -> value, all N_CHANNELS given)."""
    missing = [CHANNEL_NAMES[c] for c in range(N_CHANNELS) if c not in base and c not in channels]
    if missing:
        raise ValueError(f"history_record: no value for {', '.join(missing)}")
    full = {c: channels.get(c) or ChannelHistory.constant(base[c]) for c in range(N_CHANNELS)}
    k = max(len(h.times) for h in full.values())
    times = np.zeros((N_CHANNELS, k))
    values = np.zeros((N_CHANNELS, k))
    segments = np.zeros((N_CHANNELS, k), dtype=np.int64)
    counts = np.zeros(N_CHANNELS, dtype=np.int64)
    amplitude, frequency, phase, rate = (np.zeros(N_CHANNELS) for _ in range(4))
    for c, h in full.items():
        n = len(h.times)
        counts[c] = n
        times[c, :n] = h.times
        times[c, n:] = h.times[-1]
        values[c, :n] = h.values
        values[c, n:] = h.values[-1]
        if h.segments:
            segments[c, :n] = h.segments
        amplitude[c], frequency[c], phase[c], rate[c] = h.amplitude, h.frequency, h.phase, h.rate
    return HistoryRecord(
        times,
        values,
        segments,
        counts,
        amplitude,
        frequency,
        phase,
        rate,
        int(radial_load_frame),
        bool(tilt_free),
    )


def operating_values(operating) -> dict[int, float]:
    """Every channel's value (channel constant -> SI value) at a
    :class:`solver.inputs.OperatingPoint`: the fields named by :data:`CHANNEL_NAMES`, a moment of
    None (imposed tilt) as 0."""
    values = {c: getattr(operating, name) for c, name in enumerate(CHANNEL_NAMES)}
    if values[CH_TILTING_MOMENT] is None:
        values[CH_TILTING_MOMENT] = 0.0
    return values


def steady_history(operating) -> HistoryRecord:
    """The constant history of a :class:`solver.inputs.OperatingPoint`."""
    return history_record(
        {}, operating_values(operating), FRAME_SPACE, operating.tilting_moment is not None
    )


def event_times(record: HistoryRecord, start: float, end: float) -> np.ndarray:
    """Sorted distinct knot times strictly inside (start, end) [s]: where a channel's value or its
    rate may jump, so an integrator ends a step there rather than stepping over it."""
    inside = []
    for c in range(N_CHANNELS):
        t = record.times[c, : record.counts[c]]
        inside.extend(float(x) for x in t if start < x < end)
    return np.unique(np.asarray(inside, dtype=float))
