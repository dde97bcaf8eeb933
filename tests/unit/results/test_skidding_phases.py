"""Skidding against time (solver.results.skidding) and metrics by phase (solver.results.phases) on
synthetic dynamic results whose answers are known in closed form: a cage running at a stated
fraction of its rolling speed, a cage speed and a friction torque that step at an event time, a
contact angle that wanders in one phase and holds in the next."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from solver.catalogue import resolve_case
from solver.history import (
    CH_INNER_SPEED,
    CH_RADIAL_LOAD,
    CHANNEL_NAMES,
    ChannelHistory,
    history_record,
)
from solver.results import checks, phases, skidding
from solver.results.dataset import build_result
from solver.results.metrics import Window, compute_metric
from solver.results.summary import phase_summary, trajectory_summary
from tests.helpers.cases import operating_point

OMEGA = 2 * math.pi * 100.0  # inner ring [rad/s]: a shaft revolution is 10 ms
SAMPLES = 2001  # over 0.2 s: 20 revolutions, 100 samples each
END = 0.2
EVENT = 0.08  # s: the cage speed, the torque and the contact angle change here
ALPHA_INNER, ALPHA_OUTER = 20.0, 12.0  # degree
GEOMETRY = resolve_case("spindle-combined-load").geometry()
D, DM = GEOMETRY.ball_diameter, GEOMETRY.pitch_diameter
Z = int(GEOMETRY.ball_count)


def rolling_speed(alpha_inner, alpha_outer, inner=OMEGA, outer=0.0):
    """omega_roll of the module docstring, written out: both raceways pass the cage at one
    surface speed, (inner - w) r_i = (w - outer) r_o."""
    r_i = 0.5 * (DM - D * math.cos(math.radians(alpha_inner)))
    r_o = 0.5 * (DM + D * math.cos(math.radians(alpha_outer)))
    return (inner * r_i + outer * r_o) / (r_i + r_o)


def result(lag_before=0.03, lag_after=0.0, inner=OMEGA, load=100.0, events=None):
    """Z balls orbiting at the cage speed; the cage lags its rolling speed by ``lag_before`` until
    EVENT and by ``lag_after`` from then on; the friction torque is 10 mN m before and 4 mN m
    after; the inner contact angle wanders by +-0.2 degree with the ball's azimuth before EVENT
    and holds at ALPHA_INNER + 1 after. ``events``: the phase_boundaries_s attribute (None: a
    steady result without it)."""
    times = np.linspace(0.0, END, SAMPLES)
    after = times >= EVENT
    roll = np.where(
        after,
        rolling_speed(ALPHA_INNER + 1.0, ALPHA_OUTER),
        rolling_speed(ALPHA_INNER, ALPHA_OUTER),
    )
    roll = roll * inner / OMEGA
    cage = roll * np.where(after, 1.0 - lag_after, 1.0 - lag_before)
    psi = 2 * np.pi * np.arange(Z)[None, :] / Z + (np.cumsum(cage) * (times[1] - times[0]))[:, None]
    inner_angle = np.where(
        after[:, None], ALPHA_INNER + 1.0, ALPHA_INNER + 0.2 * np.sin(psi - inner * times[:, None])
    )
    angle = np.stack([inner_angle, np.full(inner_angle.shape, ALPHA_OUTER)], axis=-1)
    azimuth = np.stack([np.degrees(psi - inner * times[:, None]), np.degrees(psi)], axis=-1)
    dims = ("time", "ball", "race")
    data = {
        "contact_angle": (dims, angle),
        "contact_load": (dims, np.full(angle.shape, load)),
        "raceway_azimuth": (dims, azimuth % 360.0),
        "ellipse_semi_major": (dims, np.full(angle.shape, 4e-4)),
        "max_pressure": (dims, np.full(angle.shape, 1e9)),
        "cage_speed": (("time",), cage),
        "friction_torque": (("time",), np.where(after, 0.004, 0.010)),
    }
    ds = build_result("dynamic", data, GEOMETRY, operating_point(inner), times=times)
    if events is not None:
        ds.attrs[phases.PHASE_BOUNDARIES_ATTRIBUTE] = np.asarray(events, dtype=float)
    return ds


# ---- skidding against time ----------------------------------------------------------------------
def test_the_skidding_ratio_is_the_cage_speed_over_its_rolling_speed_at_the_actual_angles():
    ds = result(lag_before=0.03, lag_after=0.01)
    ratio = skidding.skidding_ratio(ds)
    assert ratio.dims == ("time",)
    before = ds["time"] < EVENT
    # the mean of the wandering inner angle over the balls is ALPHA_INNER to ~1e-16 (Z equal
    # spacings of a sine), so the closed form holds sample by sample
    np.testing.assert_allclose(ratio.where(before, drop=True), 0.97, rtol=1e-6)
    np.testing.assert_allclose(ratio.where(~before, drop=True), 0.99, rtol=1e-12)
    slip = skidding.skidding_variables(ds)["instantaneous_cage_slip"]
    np.testing.assert_allclose(slip.where(~before, drop=True), 0.01, rtol=1e-9)
    assert slip.attrs["units"] == "1"


def test_with_equal_contact_angles_the_rolling_speed_is_the_epicyclic_speed():
    alpha = math.radians(15.0)
    g = D * math.cos(alpha) / DM
    epicyclic = 0.5 * (1.0 - g) * OMEGA
    assert rolling_speed(15.0, 15.0) == pytest.approx(epicyclic, rel=1e-14)
    # and the outer ring turning alone: ((1 + g) omega_o) / 2
    assert rolling_speed(15.0, 15.0, inner=0.0, outer=OMEGA) == pytest.approx(
        0.5 * (1.0 + g) * OMEGA, rel=1e-14
    )


def test_rings_at_rest_or_unloaded_races_give_no_ratio_and_no_infinity():
    at_rest = result(inner=0.0)
    assert np.isnan(skidding.skidding_ratio(at_rest).values).all()
    unloaded = result(load=0.0)
    assert np.isnan(skidding.skidding_ratio(unloaded).values).all()


# ---- phases ------------------------------------------------------------------------------------
def test_a_cage_speed_that_steps_gives_the_slip_of_each_phase():
    ds = result(lag_before=0.03, lag_after=0.0, events=[EVENT])
    window = Window(ds, by_phase=True)
    slip = compute_metric(window, "mean_instantaneous_cage_slip")
    assert slip.dims == ("phase",)
    np.testing.assert_allclose(slip.values, [0.03, 0.0], atol=1e-6)
    np.testing.assert_array_equal(compute_metric(window, "cage_skids").values, [1.0, 0.0])
    torque = compute_metric(window, "mean_friction_torque")
    np.testing.assert_allclose(torque.values, [0.010, 0.004], rtol=1e-12)
    np.testing.assert_allclose(torque["phase_start_time"].values, [0.0, EVENT])
    np.testing.assert_allclose(torque["phase_end_time"].values, [EVENT, END])


def test_the_band_width_of_each_phase_is_its_own():
    ds = result(events=[EVENT])
    width = compute_metric(Window(ds, by_phase=True), "band_width").sel(race="inner")
    assert width.values[0] == pytest.approx(0.4, abs=2e-3)  # ALPHA_INNER +- 0.2
    assert width.values[1] == pytest.approx(0.0, abs=1e-12)  # held at ALPHA_INNER + 1
    summary = phase_summary(ds)
    assert summary["analysis_start_time"].values.tolist() == [0.0, EVENT]
    assert np.isnan(summary["settling_time"].values).all()


def test_the_cage_skids_warning_names_the_phase():
    ds = result(lag_before=0.03, lag_after=0.0, events=[EVENT])
    found = [w for w in checks.result_warnings(ds) if w.startswith("the cage skids")]
    assert len(found) == 1
    assert f"t from 0 s to {EVENT:g} s" in found[0] and "3 % slower" in found[0]
    calm = result(lag_before=0.005, lag_after=0.0, events=[EVENT])
    assert not [w for w in checks.result_warnings(calm) if "skids" in w]


def test_the_cage_skids_warning_says_when_and_how_much_the_cage_lagged():
    """A dip of the cage speed before the event: 6 % behind its rolling speed at t = 0.05 s,
    lag(t) = 0.06 exp(-((t - 0.05) / 0.01)^2), so more than 1 % behind while |t - 0.05| <
    0.01 sqrt(ln 6) = 0.0134 s; the phase's mean slip 0.06 * 0.01 sqrt(pi) / 0.08 = 1.33 %."""
    ds = result(lag_before=0.0, lag_after=0.0, events=[EVENT])
    times = ds["time"].values
    lag = np.where(times < EVENT, 0.06 * np.exp(-(((times - 0.05) / 0.01) ** 2)), 0.0)
    ds["cage_speed"] = ds["cage_speed"] * (1.0 - lag)
    extent = skidding.skid_extent(ds, times < EVENT)
    assert extent.peak == pytest.approx(0.06, rel=1e-6)
    assert extent.peak_time == pytest.approx(0.05, abs=1e-12)
    half = 0.01 * math.sqrt(math.log(6.0))
    step = times[1] - times[0]
    assert extent.start == pytest.approx(0.05 - half, abs=step)
    assert extent.end == pytest.approx(0.05 + half, abs=step)
    found = [w for w in checks.result_warnings(ds) if w.startswith("the cage skids")]
    assert len(found) == 1
    assert "1.33 % slower" in found[0]
    assert "lags most, 6 % (skidding_ratio 0.94), at t = 0.05 s" in found[0]
    assert f"from t = {extent.start:.4g} s to {extent.end:.4g} s" in found[0]
    # samples near rest (rolling speed under a tenth of the run's largest) are not counted
    slow = result(lag_before=0.0, lag_after=0.0, events=[EVENT])
    slow["inner_ring_speed"] = xr.DataArray(np.where(times < 0.01, 0.05, 1.0) * OMEGA, dims="time")
    slow["cage_speed"] = slow["cage_speed"] * np.where(times < 0.01, 0.05 * 0.5, 1.0)
    assert skidding.skid_extent(slow).peak == pytest.approx(0.0, abs=1e-9)


def test_a_steady_result_has_one_phase_its_analysed_window():
    ds = result(lag_before=0.0, lag_after=0.0)
    mask = phases.phase_mask(ds)
    assert mask.sizes["phase"] == 1
    start = float(trajectory_summary(ds)["analysis_start_time"])
    assert float(mask["phase_start_time"][0]) == start
    np.testing.assert_array_equal(mask.values[0], ds["time"].values >= start)
    for name in ("mean_friction_torque", "band_thickness", "band_width", "loaded_balls"):
        by_phase = compute_metric(Window(ds, by_phase=True), name).isel(phase=0, drop=True)
        plain = compute_metric(Window(ds), name)
        np.testing.assert_array_equal(by_phase.values, plain.values)


def test_phase_boundaries_must_be_increasing_times_inside_the_run():
    for bad in ([0.1, 0.05], [0.0, 0.1], [0.1, END], [math.nan]):
        with pytest.raises(ValueError, match="phase_boundaries_s"):
            phases.phase_mask(result(events=bad))


def test_phase_attributes_of_a_history_name_the_ramp_and_the_step():
    base = {c: 0.0 for c in range(len(CHANNEL_NAMES))}
    record = history_record(
        {
            CH_INNER_SPEED: ChannelHistory((0.02, 0.06), (0.0, OMEGA)),
            CH_RADIAL_LOAD: ChannelHistory((0.12, 0.12), (0.0, 300.0)),
        },
        base,
    )
    attrs = phases.phase_attributes(record, END)
    np.testing.assert_allclose(attrs[phases.PHASE_BOUNDARIES_ATTRIBUTE], [0.02, 0.06, 0.12])
    labels = attrs[phases.PHASE_LABELS_ATTRIBUTE]
    assert labels[0] == "t from 0 s to 0.02 s: inputs held"
    assert labels[1] == "t from 0.02 s to 0.06 s: inner_ring_speed changing"
    assert labels[2] == "t from 0.06 s to 0.12 s: inputs held"
    assert labels[3] == "t from 0.12 s to 0.2 s: after the step of radial_load"
    assert phases.phase_attributes(record, 0.01) == {}  # no event inside the run
    ds = result(events=attrs[phases.PHASE_BOUNDARIES_ATTRIBUTE])
    ds.attrs[phases.PHASE_LABELS_ATTRIBUTE] = labels
    assert phases.phase_mask(ds)["phase_label"].values.tolist() == labels


def test_a_start_from_rest_weighs_its_first_samples_by_the_rolling_speed():
    """Ring speed ramping linearly from rest (a data variable over time, the form a history
    result has), an event halfway; the cage stands still for the first 5 % of the run, then runs
    at 98 % of its rolling speed. In the first phase, weighted by the rolling speed (which grows
    as t), the standing start (a tenth of the phase) counts 0.1^2 of the phase: slip
    1 - 0.98 (1 - 0.01) = 0.0298; the plain mean of the samples' slips counts it a tenth:
    0.1 + 0.9 x 0.02 = 0.118."""
    ds = result(lag_before=0.0, lag_after=0.0, events=[0.5 * END])
    times = ds["time"].values
    ramp = OMEGA * times / END
    ds = ds.drop_vars("inner_ring_speed").assign(inner_ring_speed=("time", ramp))
    rolling = skidding.rolling_cage_speed(ds)
    ds["cage_speed"] = xr.where(ds["time"] < 0.05 * END, 0.0, 0.98 * rolling)
    slip = skidding.skidding_variables(ds)["instantaneous_cage_slip"]
    assert np.isnan(slip.values[0])  # at rest: no rolling speed
    weighted = compute_metric(Window(ds, by_phase=True), "mean_instantaneous_cage_slip")
    np.testing.assert_allclose(weighted.values, [1.0 - 0.98 * 0.99, 0.02], atol=3e-4)
    first = slip.where(ds["time"] < 0.5 * END, drop=True)
    assert float(first[1:].mean()) == pytest.approx(0.118, abs=2e-3)
