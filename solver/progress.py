"""What a run's progress reports tell about the time left (for the command line's progress bar and
the app's status line)."""

from __future__ import annotations

import math

MIN_WAIT_S = 1.0  # the rate is trusted after this long since the first report ...
MIN_PROGRESS = 0.005  # ... and this much progress (a fraction of the run) since it


class TimeLeft:
    """Seconds left of a run, from the rate of its progress since the first report.

    Call it with each report's wall time (s, any monotonic clock) and fraction done (0-1). What
    comes before the first report (process start-up, imports, compiling, the starting point) says
    nothing about the integration speed, so the rate is timed from that report; the answer is NaN
    until at least :data:`MIN_WAIT_S` and :data:`MIN_PROGRESS` have passed since it.
    """

    def __init__(self):
        self._first = None  # (wall time, fraction) of the first report

    def __call__(self, now: float, fraction: float) -> float:
        if self._first is None:
            self._first = (now, fraction)
            return math.nan
        t0, f0 = self._first
        if now - t0 < MIN_WAIT_S or fraction - f0 < MIN_PROGRESS:
            return math.nan
        return (now - t0) / (fraction - f0) * (1.0 - fraction)
