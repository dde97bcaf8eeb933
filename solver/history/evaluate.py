"""A history's channels at a time, and the drive record the dynamic model's right-hand side reads.

:func:`channel_value` and :func:`channel_rate` evaluate one channel of a
:class:`~.record.HistoryRecord` (formula in :mod:`.record`); :func:`drive_at` turns all channels
into what the equations of motion need (forces and moments on the inner ring, imposed ring speeds
and accelerations, imposed tilt and its rate), in the inertial frame of case-format.md (x = bearing
axis).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from numba import njit

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
    FRAME_INNER_RING,
    SEGMENT_SMOOTH,
)


class Drive(NamedTuple):
    """The imposed inputs at one time (SI, inertial frame; loads act on the inner ring)."""

    inner_speed: float  # rad/s about +x
    outer_speed: float  # rad/s about +x
    inner_acceleration: float  # rad/s^2, d(inner_speed)/dt
    outer_acceleration: float  # rad/s^2
    force_x: float  # N
    force_y: float  # N
    force_z: float  # N
    moment_y: float  # N m (free tilt only; zero otherwise)
    moment_z: float  # N m
    tilt_y: float  # rad, imposed tilt vector (zero under free tilt)
    tilt_z: float  # rad
    tilt_rate_y: float  # rad/s
    tilt_rate_z: float  # rad/s


@njit(cache=True)
def _segment(record, channel, t):
    """(k, s, width): the table segment [t_k, t_k+1) holding t, its local coordinate s in [0, 1]
    and its width [s]; k = -1 before the first knot and k = count - 1 from the last one on."""
    n = record.counts[channel]
    times = record.times[channel]
    if t < times[0]:
        return -1, 0.0, 0.0
    if t >= times[n - 1]:
        return n - 1, 0.0, 0.0
    lo, hi = 0, n - 1  # times[lo] <= t < times[hi]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if times[mid] <= t:
            lo = mid
        else:
            hi = mid
    width = times[hi] - times[lo]
    return lo, (t - times[lo]) / width, width


@njit(cache=True)
def channel_value(record, channel, t):
    """Value of ``channel`` at time ``t`` [s] (SI units of the channel)."""
    k, s, width = _segment(record, channel, t)
    values = record.values[channel]
    if k < 0:
        v = values[0]
    elif width == 0.0:
        v = values[k]
    else:
        if record.segments[channel, k] == SEGMENT_SMOOTH:
            s = s * s * (3.0 - 2.0 * s)
        v = values[k] + (values[k + 1] - values[k]) * s
    f = record.frequency[channel]
    a = record.amplitude[channel]
    if a != 0.0:
        v += a * math.sin(2.0 * math.pi * f * t + record.phase[channel])
    return v + record.rate[channel] * t


@njit(cache=True)
def channel_rate(record, channel, t):
    """Time derivative of ``channel`` at ``t`` [SI/s] (right derivative at a knot; a step's jump
    itself has no rate)."""
    k, s, width = _segment(record, channel, t)
    r = 0.0
    if k >= 0 and width > 0.0:
        values = record.values[channel]
        slope = (values[k + 1] - values[k]) / width
        if record.segments[channel, k] == SEGMENT_SMOOTH:
            slope *= 6.0 * s * (1.0 - s)
        r = slope
    a = record.amplitude[channel]
    if a != 0.0:
        w = 2.0 * math.pi * record.frequency[channel]
        r += a * w * math.cos(w * t + record.phase[channel])
    return r + record.rate[channel]


@njit(cache=True)
def drive_at(record, t, inner_angle):
    """The :class:`Drive` at time ``t`` [s]; ``inner_angle`` [rad] is the inner ring's spin angle
    (the state's), which a radial load in the inner ring's frame turns with."""
    wi = channel_value(record, CH_INNER_SPEED, t)
    wo = channel_value(record, CH_OUTER_SPEED, t)
    radial = channel_value(record, CH_RADIAL_LOAD, t)
    psi = channel_value(record, CH_RADIAL_LOAD_ANGLE, t)
    if record.radial_load_frame == FRAME_INNER_RING:
        psi += inner_angle
    if record.tilt_free:
        moment = channel_value(record, CH_TILTING_MOMENT, t)
        axis = channel_value(record, CH_MOMENT_AXIS, t)
        my, mz = moment * math.cos(axis), moment * math.sin(axis)
        ty = tz = ty_rate = tz_rate = 0.0
    else:
        my = mz = 0.0
        m = channel_value(record, CH_MISALIGNMENT, t)
        axis = channel_value(record, CH_MISALIGNMENT_AXIS, t)
        m_rate = channel_rate(record, CH_MISALIGNMENT, t)
        axis_rate = channel_rate(record, CH_MISALIGNMENT_AXIS, t)
        ca, sa = math.cos(axis), math.sin(axis)
        ty, tz = m * ca, m * sa
        ty_rate = m_rate * ca - m * sa * axis_rate
        tz_rate = m_rate * sa + m * ca * axis_rate
    return Drive(
        wi,
        wo,
        channel_rate(record, CH_INNER_SPEED, t),
        channel_rate(record, CH_OUTER_SPEED, t),
        channel_value(record, CH_AXIAL_LOAD, t),
        radial * math.cos(psi),
        radial * math.sin(psi),
        my,
        mz,
        ty,
        tz,
        ty_rate,
        tz_rate,
    )
