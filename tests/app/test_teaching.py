"""Words of the teaching view against hand-worked values."""

from __future__ import annotations

import math

import pytest

from app.teaching import (
    Facts,
    facts_from_result,
    playback_rate,
    revolution_words,
    slow_motion_words,
    what_you_see,
)
from viz.overlay import misalignment_words


def _facts(**kw):
    base = dict(
        model="dynamic",
        inner_ring_speed=2 * math.pi * 100.0,  # 100 rev/s: 10 ms per revolution
        outer_ring_speed=0.0,
        axial_load=500.0,
        radial_load=0.0,
        radial_load_angle=0.0,
        misalignment=0.0,
        misalignment_axis=0.0,
        misalignment_frame="space",
    )
    base.update(kw)
    return Facts(**base)


def test_slow_motion_in_words():
    # 1e-5 s per frame, 2 frames per tick, 15 ticks per second: 0.3 ms per screen second
    rate = playback_rate(1e-5, 2, 15.0)
    assert rate == pytest.approx(3e-4)
    assert slow_motion_words(rate) == "1 s on screen = 300 µs of bearing time"
    assert slow_motion_words(1e-3) == "1 s on screen = 1 ms of bearing time"
    # a rate a rounding error below 1 ms reads as 1 ms, not "1e+03 µs"
    assert slow_motion_words(0.02 / 20) == "1 s on screen = 1 ms of bearing time"
    assert slow_motion_words(0.9999999e-3) == "1 s on screen = 1 ms of bearing time"
    assert slow_motion_words(2.5) == "1 s on screen = 2.5 s of bearing time"
    assert slow_motion_words(0.0) == ""


def test_revolution_counter():
    f = _facts()
    assert revolution_words(0.025, f, 0.06) == "revolution 2.5 of 6"
    assert revolution_words(0.025, f) == "revolution 2.5"
    assert revolution_words(1.0, _facts(inner_ring_speed=0.0)) == "rings at rest"


def test_misalignment_and_note_say_what_is_fixed_where():
    turning = _facts(misalignment=math.radians(0.05), misalignment_frame="ring")
    fixed = _facts(misalignment=math.radians(0.05))
    assert misalignment_words(turning) == "tilt axis, turning with the ring"
    assert misalignment_words(fixed) == "tilt axis, fixed in space"
    assert misalignment_words(_facts()) == ""
    assert "inner track is a thin line" in what_you_see(turning)
    assert "outer track is a thin line" in what_you_see(fixed)
    assert "same circle" in what_you_see(_facts())
    assert "5x larger" in what_you_see(fixed, exaggeration=5.0)
    assert "larger" not in what_you_see(fixed)


def test_facts_come_from_the_result_coordinates(qs_dataset):
    f = facts_from_result(qs_dataset)
    assert f.radial_load == pytest.approx(300.0)
    assert f.inner_ring_speed == pytest.approx(6000.0 * 2 * math.pi / 60)
    assert f.shaft_period == pytest.approx(0.01)
    with pytest.raises(ValueError, match="radial_load"):
        facts_from_result(qs_dataset.drop_vars("radial_load"))
