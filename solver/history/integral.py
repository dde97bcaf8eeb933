"""The integral over time of a history's channel, in closed form: the angle a ring has turned
under a speed history (a radial load turning with the shaft is at that angle in space)."""

from __future__ import annotations

import math

from .record import SEGMENT_SMOOTH, HistoryRecord


def _table_integral(times, values, segments, count: int, t: float) -> float:
    """Integral over [0, t] of the knot table (constant before the first knot and after the
    last; a linear segment integrates to the mean of its ends, a smooth one s^3 - s^4/2)."""
    total = values[0] * min(t, times[0])
    for k in range(count - 1):
        t0, t1 = times[k], times[k + 1]
        if t <= t0:
            break
        width = t1 - t0
        if width == 0.0:
            continue
        x = (min(t, t1) - t0) / width
        dv = values[k + 1] - values[k]
        shape = x**3 - 0.5 * x**4 if segments[k] == SEGMENT_SMOOTH else 0.5 * x * x
        total += width * (values[k] * x + dv * shape)
    last = times[count - 1]
    if t > last:
        total += values[count - 1] * (t - last)
    return float(total)


def channel_integral(record: HistoryRecord, channel: int, t: float) -> float:
    """Integral of ``channel`` over [0, ``t``] (``t`` >= 0 [s]; SI unit of the channel times s):
    the table, plus the sine's (a / (2 pi f)) (cos(phase) - cos(2 pi f t + phase)), plus the rate's
    r t^2 / 2."""
    n = int(record.counts[channel])
    total = _table_integral(
        record.times[channel], record.values[channel], record.segments[channel], n, t
    )
    a, f = float(record.amplitude[channel]), float(record.frequency[channel])
    if a != 0.0 and f != 0.0:
        phase = float(record.phase[channel])
        w = 2.0 * math.pi * f
        total += a / w * (math.cos(phase) - math.cos(w * t + phase))
    return total + 0.5 * float(record.rate[channel]) * t * t


__all__ = ["channel_integral"]
