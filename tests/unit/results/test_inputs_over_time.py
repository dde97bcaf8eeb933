"""A result whose ring speed varies in time (a run along a history: the speed a data variable over
``time``) is read like any other: it loads, ``ring_speeds`` gives the speed at the end of the run
(the final phase), the metrics read a varying input as its mean over the analysed window, the
skidding ratio is taken at each sample's speed, and the 3-D view turns the ring by the integral of
its speed."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.results.io import save_dataset
from solver.results.skidding import skidding_variables
from viz.frames import FrameSource

LESSON = "assets/lessons/results/01-axial-load--axial.nc"


@pytest.fixture(scope="module")
def ramped():
    """The lesson's steady result with its inner ring speed made a linear ramp from half the
    speed to the speed over the run (the sampled states are the steady run's: only the readers
    are under test)."""
    ds = solver.load_result(LESSON).load()
    speed = float(ds["inner_ring_speed"])
    t = ds["time"].values
    ramp = speed * (0.5 + 0.5 * t / t[-1])
    attrs = ds["inner_ring_speed"].attrs
    ds = ds.drop_vars("inner_ring_speed")
    ds["inner_ring_speed"] = (("time",), ramp, attrs)
    for var in ds.variables.values():  # the file's encoding lists the speed among coordinates
        var.encoding = {}
    return ds, speed


def test_a_result_with_a_speed_over_time_saves_and_loads(ramped, tmp_path):
    ds, _ = ramped
    path = save_dataset(ds, tmp_path / "ramp.nc")
    loaded = solver.load_result(path)
    assert loaded["inner_ring_speed"].dims == ("time",)


def test_ring_speeds_are_those_at_the_end_of_the_run(ramped):
    ds, speed = ramped
    inner, outer = solver.ring_speeds(ds)
    assert inner == pytest.approx(speed, rel=1e-12) and outer == 0.0


def test_the_shaft_period_metric_reads_the_speed_over_the_analysed_window(ramped):
    ds, speed = ramped
    t = ds["time"].values
    start = float(ds["analysis_start_time"])
    window = t >= start
    mean = np.mean(speed * (0.5 + 0.5 * t[window] / t[-1]))
    period = float(ds.racetrace.metric("shaft_period"))
    assert period == pytest.approx(2.0 * np.pi / mean, rel=1e-12)


def test_the_skidding_ratio_follows_each_samples_speed(ramped):
    ds, _ = ramped
    ratio = skidding_variables(ds)["skidding_ratio"].values
    steady = skidding_variables(solver.load_result(LESSON))["skidding_ratio"].values
    t = ds["time"].values
    scale = 0.5 + 0.5 * t / t[-1]
    # the cage speed is the steady run's; the epicyclic speed grows with the inner ring's
    ok = np.isfinite(ratio) & np.isfinite(steady)
    assert ok.sum() > 0.9 * t.size
    np.testing.assert_allclose(ratio[ok], steady[ok] / scale[ok], rtol=1e-9)


def test_the_3d_view_turns_the_ring_by_the_integral_of_its_speed(ramped):
    ds, speed = ramped
    t = ds["time"].values
    frames = FrameSource.from_dynamic(ds)
    turn = speed * (0.5 * (t - t[0]) + 0.25 * (t**2 - t[0] ** 2) / t[-1])  # trapezoid is exact
    np.testing.assert_allclose(frames.ring_angle[:, 0], turn, rtol=1e-12, atol=1e-12)
