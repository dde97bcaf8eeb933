"""Stand-ins for :class:`solver.LiveSimulation` in the live child process (tests swap the class
the child runs: ``LiveRunner.start(..., target="tests.app.live_fakes:SlowLive")``)."""

from __future__ import annotations

import time

import numpy as np
import xarray as xr


class SlowLive:
    """A live simulation whose every ``integrate`` takes :attr:`ADVANCE_S` of wall time; ``take``
    returns the samples integrated since the last one: ``time`` and the ``radial_load`` over it
    (a change set is a step)."""

    ADVANCE_S = 0.01
    SAMPLES_PER_SECOND = 60_000.0

    def __init__(self, case):
        self.time = 0.0
        self._load = 300.0
        self._pending = []  # (times, loads) integrated, not yet taken

    def inputs_now(self) -> dict:
        return {"radial_load": self._load}

    def set_input(self, name: str, value: float, ramp_s: float = 0.0) -> None:
        self._load = float(value)

    def advance(self, duration_s: float, interrupt=None) -> xr.Dataset:
        self.integrate(duration_s, interrupt)
        return self.take()

    def integrate(self, duration_s: float, interrupt=None):
        from solver.models.dynamic.live import AdvanceTiming

        time.sleep(self.ADVANCE_S)
        count = max(1, round(duration_s * self.SAMPLES_PER_SECOND))
        self._add(count)
        return AdvanceTiming(count / self.SAMPLES_PER_SECOND, 0.0, 0.0, 0.0, 0.0, False, count)

    def _add(self, count: int) -> None:
        """``count`` samples from the current time on, at the load now, waiting for take()."""
        first = round(self.time * self.SAMPLES_PER_SECOND) + 1
        times = np.arange(first, first + count) / self.SAMPLES_PER_SECOND
        if count:
            self.time = float(times[-1])
        self._pending.append((times, np.full(count, self._load)))

    def take(self) -> xr.Dataset:
        times = np.concatenate([t for t, _ in self._pending])
        loads = np.concatenate([v for _, v in self._pending])
        self._pending = []
        return xr.Dataset({"radial_load": ("time", loads)}, coords={"time": times})

    def reset(self) -> None:
        self.time = 0.0
        self._pending = []

    def close(self) -> None:
        pass


class InterruptibleLive(SlowLive):
    """:class:`SlowLive` whose ``integrate`` runs in :attr:`STEPS` equal steps of
    :attr:`ADVANCE_S` / :attr:`STEPS` wall time each and asks ``interrupt`` between them, as
    ``solver.LiveSimulation.integrate`` does: it keeps the samples of the steps done when told
    to stop."""

    ADVANCE_S = 0.8
    STEPS = 8

    def __init__(self, case):
        super().__init__(case)
        self.last_advance = None

    def integrate(self, duration_s: float, interrupt=None):
        from solver.models.dynamic.live import AdvanceTiming

        count = max(1, round(duration_s * self.SAMPLES_PER_SECOND))
        done, interrupted = 0, False
        for step in range(self.STEPS):
            if done and interrupt is not None and interrupt():
                interrupted = True
                break
            time.sleep(self.ADVANCE_S / self.STEPS)
            done = round(count * (step + 1) / self.STEPS)
        self._add(done)
        simulated = done / self.SAMPLES_PER_SECOND
        return AdvanceTiming(simulated, 0.0, 0.0, 0.0, 0.0, interrupted, count)
