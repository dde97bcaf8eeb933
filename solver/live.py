"""The public door of the live simulation (docs/live.md): :class:`LiveSimulation` of a case by any
name (a :class:`~solver.case.Case`, a case-file path or a catalogue name)."""

from __future__ import annotations

from solver.catalogue import resolve_case
from solver.models.dynamic.live import LIVE_RAMP, AdvanceTiming
from solver.models.dynamic.live import LiveSimulation as _ModelSession
from solver.models.dynamic.options import SimulationOptions


class LiveSimulation(_ModelSession):
    """A dynamic run that advances chunk by chunk and follows inputs set while it runs
    (:class:`solver.models.dynamic.live.LiveSimulation`); ``case`` by any name."""

    def __init__(self, case, options: SimulationOptions | None = None):
        super().__init__(resolve_case(case), options)


__all__ = ["LIVE_RAMP", "AdvanceTiming", "LiveSimulation"]
