"""Operating inputs as functions of time (issue 24): the numba record of a case's time histories
(:mod:`.record`) and its evaluation at a time (:mod:`.evaluate`).

A history is given per *channel* — one operating input of :class:`solver.inputs.OperatingPoint` —
as a piecewise table of (time, value) knots (linear or smooth segments; a step is two knots at one
time), plus a sine and a constant rate. Every case form (constant, ramp, step, sine, rotating load,
table) compiles to this one record, so the models read one thing.
"""

from .evaluate import Drive, channel_rate, channel_value, drive_at
from .record import (
    CH_AXIAL_LOAD,
    CH_INNER_SPEED,
    CH_MISALIGNMENT,
    CH_MISALIGNMENT_AXIS,
    CH_MOMENT_AXIS,
    CH_OUTER_SPEED,
    CH_RADIAL_LOAD,
    CH_RADIAL_LOAD_ANGLE,
    CH_TILTING_MOMENT,
    CHANNEL_NAMES,
    FRAME_INNER_RING,
    FRAME_SPACE,
    N_CHANNELS,
    SEGMENT_LINEAR,
    SEGMENT_SMOOTH,
    ChannelHistory,
    HistoryRecord,
    event_times,
    history_record,
    operating_values,
    steady_history,
)

__all__ = [
    "CHANNEL_NAMES",
    "CH_AXIAL_LOAD",
    "CH_INNER_SPEED",
    "CH_MISALIGNMENT",
    "CH_MISALIGNMENT_AXIS",
    "CH_MOMENT_AXIS",
    "CH_OUTER_SPEED",
    "CH_RADIAL_LOAD",
    "CH_RADIAL_LOAD_ANGLE",
    "CH_TILTING_MOMENT",
    "FRAME_INNER_RING",
    "FRAME_SPACE",
    "N_CHANNELS",
    "SEGMENT_LINEAR",
    "SEGMENT_SMOOTH",
    "ChannelHistory",
    "Drive",
    "HistoryRecord",
    "channel_rate",
    "channel_value",
    "drive_at",
    "event_times",
    "history_record",
    "operating_values",
    "steady_history",
]
