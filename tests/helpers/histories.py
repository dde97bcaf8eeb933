"""Dynamic-model inputs with an operating history, built in Python from steady inputs (the case
keys that give histories in a case file build the same record: solver.history)."""

from __future__ import annotations

from dataclasses import replace

from solver.history import FRAME_SPACE, N_CHANNELS, history_record, steady_history
from solver.inputs import Inputs


def with_history(
    inputs: Inputs,
    channels: dict,
    duration: float,
    samples_per_second: float,
    radial_load_frame: int = FRAME_SPACE,
) -> Inputs:
    """``inputs`` driven by ``channels`` (channel constant -> solver.history.ChannelHistory; every
    other input constant at its steady value) for ``duration`` [s], sampled
    ``samples_per_second`` times per second."""
    steady = steady_history(inputs.operating)
    base = {c: float(steady.values[c, 0]) for c in range(N_CHANNELS)}
    record = history_record(channels, base, radial_load_frame, bool(steady.tilt_free))
    simulation = replace(
        inputs.simulation, duration=float(duration), samples_per_second=float(samples_per_second)
    )
    return replace(inputs, history=record, simulation=simulation)
