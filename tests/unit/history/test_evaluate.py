"""The history record's evaluation against closed forms: constants, ramps (linear and smooth),
steps (right-continuous), sines, rates, the drive's forces and tilt, and the event times."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.history import (
    CH_AXIAL_LOAD,
    CH_INNER_SPEED,
    CH_MISALIGNMENT,
    CH_MISALIGNMENT_AXIS,
    CH_RADIAL_LOAD,
    CH_RADIAL_LOAD_ANGLE,
    FRAME_INNER_RING,
    N_CHANNELS,
    SEGMENT_SMOOTH,
    ChannelHistory,
    channel_rate,
    channel_value,
    drive_at,
    event_times,
    history_record,
)

BASE = {c: 0.0 for c in range(N_CHANNELS)}


def record(channel, history, **kw):
    return history_record({channel: history}, BASE, **kw)


def test_linear_ramp_value_and_rate_inside_and_outside():
    rec = record(CH_INNER_SPEED, ChannelHistory((0.1, 0.3), (100.0, 500.0)))
    assert channel_value(rec, CH_INNER_SPEED, 0.0) == 100.0
    assert channel_value(rec, CH_INNER_SPEED, 0.2) == pytest.approx(300.0, rel=1e-15)
    assert channel_value(rec, CH_INNER_SPEED, 1.0) == 500.0
    assert channel_rate(rec, CH_INNER_SPEED, 0.2) == pytest.approx(2000.0, rel=1e-12)
    assert channel_rate(rec, CH_INNER_SPEED, 0.05) == 0.0
    assert channel_rate(rec, CH_INNER_SPEED, 0.4) == 0.0


def test_smooth_ramp_is_the_c1_step_and_its_rate_is_its_derivative():
    rec = record(
        CH_AXIAL_LOAD, ChannelHistory((0.0, 2.0), (10.0, 30.0), segments=(SEGMENT_SMOOTH, 0))
    )
    for t in (0.0, 0.3, 1.0, 1.7, 2.0):
        s = t / 2.0
        assert channel_value(rec, CH_AXIAL_LOAD, t) == pytest.approx(
            10.0 + 20.0 * (3 * s * s - 2 * s**3), rel=1e-14
        )
        h = 1e-6
        if 0.0 < t < 2.0:
            numeric = (
                channel_value(rec, CH_AXIAL_LOAD, t + h) - channel_value(rec, CH_AXIAL_LOAD, t - h)
            ) / (2 * h)
            assert channel_rate(rec, CH_AXIAL_LOAD, t) == pytest.approx(numeric, rel=1e-7)
    assert channel_rate(rec, CH_AXIAL_LOAD, 0.0) == 0.0  # C1 at both ends


def test_step_is_right_continuous_and_has_no_rate():
    rec = record(CH_RADIAL_LOAD, ChannelHistory((0.0, 0.5, 0.5, 1.0), (100.0, 100.0, 900.0, 900.0)))
    assert channel_value(rec, CH_RADIAL_LOAD, 0.5 - 1e-12) == 100.0
    assert channel_value(rec, CH_RADIAL_LOAD, 0.5) == 900.0
    assert channel_rate(rec, CH_RADIAL_LOAD, 0.5) == 0.0
    last = record(CH_RADIAL_LOAD, ChannelHistory((0.0, 0.5, 0.5), (100.0, 100.0, 900.0)))
    assert channel_value(last, CH_RADIAL_LOAD, 0.5) == 900.0


def test_sine_and_rate_terms_add_to_the_table():
    rec = record(
        CH_RADIAL_LOAD_ANGLE,
        ChannelHistory((0.0,), (0.2,), amplitude=0.1, frequency=5.0, phase=0.3, rate=7.0),
    )
    t = 0.123
    w = 2 * math.pi * 5.0
    assert channel_value(rec, CH_RADIAL_LOAD_ANGLE, t) == pytest.approx(
        0.2 + 0.1 * math.sin(w * t + 0.3) + 7.0 * t, rel=1e-14
    )
    assert channel_rate(rec, CH_RADIAL_LOAD_ANGLE, t) == pytest.approx(
        0.1 * w * math.cos(w * t + 0.3) + 7.0, rel=1e-14
    )


def test_drive_turns_a_radial_load_with_the_inner_ring_and_resolves_the_tilt():
    base = dict(BASE)
    base[CH_RADIAL_LOAD] = 200.0
    base[CH_RADIAL_LOAD_ANGLE] = 0.5
    base[CH_MISALIGNMENT_AXIS] = 0.25
    tilt = ChannelHistory((0.0, 1.0), (0.0, 1e-3))
    space = history_record({CH_MISALIGNMENT: tilt}, base)
    ring = history_record({CH_MISALIGNMENT: tilt}, base, radial_load_frame=FRAME_INNER_RING)
    d_space = drive_at(space, 0.5, 1.0)
    d_ring = drive_at(ring, 0.5, 1.0)
    assert (d_space.force_y, d_space.force_z) == pytest.approx(
        (200.0 * math.cos(0.5), 200.0 * math.sin(0.5)), rel=1e-14
    )
    assert (d_ring.force_y, d_ring.force_z) == pytest.approx(
        (200.0 * math.cos(1.5), 200.0 * math.sin(1.5)), rel=1e-14
    )
    assert (d_space.tilt_y, d_space.tilt_z) == pytest.approx(
        (5e-4 * math.cos(0.25), 5e-4 * math.sin(0.25)), rel=1e-14
    )
    assert (d_space.tilt_rate_y, d_space.tilt_rate_z) == pytest.approx(
        (1e-3 * math.cos(0.25), 1e-3 * math.sin(0.25)), rel=1e-14
    )
    assert d_space.moment_y == 0.0 and d_space.inner_acceleration == 0.0


def test_free_tilt_takes_the_moment_channels_and_imposes_no_tilt():
    base = dict(BASE)
    base[CH_MISALIGNMENT] = 1e-3
    base[7] = 4.0  # CH_TILTING_MOMENT
    base[8] = math.pi / 2  # CH_MOMENT_AXIS
    d = drive_at(history_record({}, base, tilt_free=True), 0.0, 0.0)
    assert d.tilt_y == 0.0 and d.tilt_z == 0.0
    assert d.moment_y == pytest.approx(0.0, abs=1e-15) and d.moment_z == pytest.approx(4.0)


def test_event_times_are_the_knots_inside_the_run_once_each():
    channels = {
        CH_INNER_SPEED: ChannelHistory((0.0, 0.2), (0.0, 100.0)),
        CH_RADIAL_LOAD: ChannelHistory((0.0, 0.2, 0.2, 5.0), (1.0, 1.0, 2.0, 2.0)),
    }
    rec = history_record(channels, BASE)
    np.testing.assert_array_equal(event_times(rec, 0.0, 1.0), [0.2])
    np.testing.assert_array_equal(event_times(rec, 0.0, 6.0), [0.2, 5.0])


def test_channel_history_refuses_decreasing_times_and_mismatched_lengths():
    with pytest.raises(ValueError, match="must not decrease"):
        ChannelHistory((0.0, 1.0, 0.5), (1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="as many times as values"):
        ChannelHistory((0.0, 1.0), (1.0,))
