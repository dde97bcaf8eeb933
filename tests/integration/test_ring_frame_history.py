"""A misalignment history with ``misalignment_frame = "ring"`` (docs/case-format.md, "Time
histories"): the tilt's size follows the history in the inner ring's frame, and its direction
turns with the ring. Checked on a short dynamic run of the shipped spindle-misalignment-ring case
whose 0.05 deg tilt is ramped in from 0 over 0.006 s (two shaft revolutions at 20 000 rpm)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.catalogue import catalogue

RAMP_S = 0.006
TILT_DEG = 0.05
AXIS_DEG = 90.0  # the case's misalignment_axis_deg
RPM = 20000.0


@pytest.fixture(scope="module")
def run():
    case = (
        catalogue()
        .get("spindle-misalignment-ring")
        .load()
        .with_values(
            {
                "operating.misalignment_deg": {
                    "ramp": {"from": 0.0, "to": TILT_DEG, "start_s": 0.0, "duration_s": RAMP_S}
                },
                "simulation.shaft_revolutions": None,
                "simulation.samples_per_revolution": None,
                "simulation.duration_s": 0.009,
                "simulation.samples_per_second": 20000.0,
            }
        )
    )
    assert case.operating.misalignment_frame == "ring" and case.histories
    assert solver.dynamic_problems(case) == []
    return solver.simulate(case)


def test_the_tilt_follows_the_history_and_turns_with_the_ring(run):
    times = run["time"].values
    tilt = run["inner_ring_tilt"].transpose("time", "tilt_axis").values  # degree, space axes
    size = np.hypot(tilt[:, 0], tilt[:, 1])
    expected = TILT_DEG * np.clip(times / RAMP_S, 0.0, 1.0)
    np.testing.assert_allclose(size, expected, atol=1e-4 * TILT_DEG)
    # direction in space: the axis in the ring's frame, turned by the ring's angle
    turning = times > 0.1 * RAMP_S
    direction = np.degrees(np.arctan2(tilt[turning, 1], tilt[turning, 0]))
    ring_angle = np.degrees(2.0 * math.pi * RPM / 60.0 * times[turning])
    offset = (direction - ring_angle - AXIS_DEG + 180.0) % 360.0 - 180.0
    assert np.abs(offset).max() < 0.5
