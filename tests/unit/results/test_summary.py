"""Trajectory metrics and settling (solver.results.summary) on synthetic data whose answers are
known in closed form: a line alpha0 + A cos(phi) has an excursion 2 A cos(5 deg) (bin medians at
the 10-degree bin centres) and no thickness; a band of uniform width w independent of the azimuth
has a thickness 0.95 w (central 95 % of a uniform law) and no excursion; a track fixed in space is
a line in the stationary ring's frame and a band in the turning ring's frame."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.catalogue import resolve_case
from solver.results import summary
from solver.results.dataset import build_result
from tests.helpers.cases import operating_point

OMEGA = 2 * math.pi * 100.0  # inner ring, rad/s: one shaft revolution = 10 ms
PERIOD = 2 * math.pi / OMEGA
CAGE = 0.4 * OMEGA
Z = 18
PER_REV = 180
ALPHA0, AMPLITUDE = 18.0, 0.5  # degree


# ---- track_metrics on plain arrays ---------------------------------------------------------------
def test_a_pure_line_has_excursion_2a_and_no_thickness():
    phi = np.linspace(0.0, 360.0, 72_000, endpoint=False)
    alpha = ALPHA0 + AMPLITUDE * np.cos(np.radians(phi))
    excursion, thickness = summary.track_metrics(phi, alpha)
    assert excursion == pytest.approx(2 * AMPLITUDE * math.cos(math.radians(5.0)), rel=1e-4)
    assert thickness < 0.01 * AMPLITUDE  # the mean track follows the line between bin centres


def test_a_band_has_thickness_095_w_and_no_excursion():
    rng = np.random.default_rng(7)
    width = 0.8
    phi = rng.uniform(0.0, 360.0, 400_000)
    alpha = ALPHA0 + rng.uniform(-width / 2, width / 2, phi.size)
    excursion, thickness = summary.track_metrics(phi, alpha)
    assert thickness == pytest.approx(0.95 * width, rel=0.01)
    assert excursion < 0.03 * width  # only the scatter of 36 bin medians of ~11 000 samples


def test_a_line_plus_a_band_gives_both():
    rng = np.random.default_rng(8)
    width = 0.2
    phi = rng.uniform(0.0, 360.0, 400_000)
    alpha = ALPHA0 + AMPLITUDE * np.cos(np.radians(phi)) + rng.uniform(-width / 2, width / 2)
    alpha = alpha + rng.uniform(-width / 2, width / 2, phi.size)
    excursion, thickness = summary.track_metrics(phi, alpha)
    assert excursion == pytest.approx(2 * AMPLITUDE * math.cos(math.radians(5.0)), abs=0.02)
    assert thickness == pytest.approx(0.95 * width, rel=0.03)


def test_bins_with_too_few_samples_are_ignored():
    phi = np.linspace(0.0, 180.0, 18_000, endpoint=False)  # half the raceway: the load zone
    alpha = np.full(phi.size, ALPHA0)
    stray_phi = np.array([270.0, 271.0, 272.0, 273.0])  # 4 samples < 5 in one bin: ignored
    stray = np.full(4, ALPHA0 + 3.0)
    excursion, thickness = summary.track_metrics(
        np.concatenate([phi, stray_phi]), np.concatenate([alpha, stray])
    )
    assert excursion == pytest.approx(0.0, abs=1e-12)
    assert thickness == pytest.approx(0.0, abs=1e-12)
    one_more = summary.track_metrics(
        np.concatenate([phi, stray_phi, [274.0]]), np.concatenate([alpha, stray, [ALPHA0 + 3.0]])
    )
    assert one_more[0] == pytest.approx(3.0)  # a 5-sample bin counts
    assert np.isnan(summary.track_metrics([10.0], [ALPHA0])[0])


def test_azimuths_are_taken_modulo_360():
    phi = np.linspace(0.0, 360.0, 36_000, endpoint=False)
    alpha = ALPHA0 + AMPLITUDE * np.cos(np.radians(phi))
    assert summary.track_metrics(phi + 720.0, alpha) == pytest.approx(
        summary.track_metrics(phi - 360.0, alpha)
    )


# ---- synthetic dynamic results -------------------------------------------------------------------
def dynamic_result(revolutions: float, spin_to_roll=None, angle_offset=None, misaligned=False):
    """A dynamic-shaped result: Z balls orbiting at the cage speed, the inner ring turning at OMEGA,
    the outer ring fixed. The contact angle of both races is ALPHA0 + AMPLITUDE cos(psi) with psi
    the ball's inertial azimuth (a disturbance fixed in space), or, with ``misaligned``, of its
    azimuth on the inner ring (a disturbance turning with the inner ring).
    ``spin_to_roll(revolution)`` and ``angle_offset(revolution)`` [degree] set per-revolution
    values (default: constant 0.07 and 0)."""
    times = np.arange(int(round(revolutions * PER_REV)) + 1) * (PERIOD / PER_REV)
    psi = 2 * np.pi * np.arange(Z)[None, :] / Z + CAGE * times[:, None]  # (time, ball)
    on_inner = psi - OMEGA * times[:, None]
    revolution = np.floor(times / PERIOD + 1e-9).astype(int)
    track = np.degrees(np.cos(on_inner if misaligned else psi)) * math.radians(AMPLITUDE)
    offset = np.array([angle_offset(k) if angle_offset else 0.0 for k in revolution])
    alpha = ALPHA0 + track + offset[:, None]
    ratio = np.array([spin_to_roll(k) if spin_to_roll else 0.07 for k in revolution])
    both = np.stack([alpha, alpha], axis=-1)  # (time, ball, race)
    azimuth = np.stack([np.degrees(on_inner), np.degrees(psi)], axis=-1) % 360.0
    dims = ("time", "ball", "race")
    data = {
        "contact_angle": (dims, both),
        "contact_load": (dims, np.full(both.shape, 100.0)),
        "raceway_azimuth": (dims, azimuth),
        "ellipse_semi_major": (dims, np.full(both.shape, 4e-4)),
        "max_pressure": (dims, np.full(both.shape, 1e9)),
        "spin_to_roll": (dims, np.broadcast_to(ratio[:, None, None], both.shape)),
    }
    geometry = resolve_case("spindle-combined-load").geometry()
    return build_result("dynamic", data, geometry, operating_point(OMEGA), times=times)


def test_a_track_fixed_in_space_is_a_line_on_the_outer_and_a_band_on_the_inner_ring():
    ds = dynamic_result(5.0)  # 4 revolutions after the ring-down
    m = summary.trajectory_summary(ds)
    line = 2 * AMPLITUDE * math.cos(math.radians(5.0))
    for race in ("inner", "outer"):
        outer_frame = {"race": race, "frame": "outer_ring"}
        inner_frame = {"race": race, "frame": "inner_ring"}
        assert float(m.trajectory_excursion.sel(outer_frame)) == pytest.approx(line, rel=2e-3)
        assert float(m.trajectory_band_thickness.sel(outer_frame)) < 0.01 * AMPLITUDE
        # on the turning ring every azimuth sees every phase of the track: A cos of a uniform
        # phase, whose central 95 % spans 2 A cos(0.025 pi)
        band = 2 * AMPLITUDE * math.cos(0.025 * math.pi)
        assert float(m.trajectory_band_thickness.sel(inner_frame)) == pytest.approx(band, rel=0.02)
        # no mean variation on the inner ring: only the scatter of the bin medians of a finite run
        thickness = float(m.trajectory_band_thickness.sel(inner_frame))
        assert float(m.trajectory_excursion.sel(inner_frame)) < 0.1 * thickness
    groove = ds.groove_radius.values
    np.testing.assert_allclose(
        m.trajectory_band_thickness_arc.sel(frame="inner_ring").values,
        groove * np.radians(m.trajectory_band_thickness.sel(frame="inner_ring").values),
    )
    np.testing.assert_allclose(m.ellipse_semi_major_mean.values, 4e-4)
    np.testing.assert_allclose(m.trajectory_band_width.values, 2 * AMPLITUDE, rtol=1e-3)
    assert m.trajectory_excursion.attrs["units"] == "degree"


def test_a_track_turning_with_the_inner_ring_swaps_line_and_band():
    m = summary.trajectory_summary(dynamic_result(4.0, misaligned=True))
    inner_own = {"race": "inner", "frame": "inner_ring"}
    outer_own = {"race": "outer", "frame": "outer_ring"}
    assert float(m.trajectory_band_thickness.sel(inner_own)) < 0.01 * AMPLITUDE
    assert float(m.trajectory_band_thickness.sel(outer_own)) > 1.5 * AMPLITUDE


def test_settling_found_where_the_spin_to_roll_ratio_comes_within_1_percent():
    """0.07 plus per-revolution departures 0.05, 0.02, 0.008, 0.003, 0.0004, 0: the tolerance is
    1 % of 0.07 = 0.0007 (above the 0.0005 floor), first met in revolution 4 (0-based)."""
    steps = [0.05, 0.02, 0.008, 0.003, 0.0004]
    ds = dynamic_result(8.0, spin_to_roll=lambda k: 0.07 + (steps[k] if k < len(steps) else 0.0))
    state = summary.settling(ds)
    assert state.settled and state.revolutions == 8
    assert state.settling_time == pytest.approx(4 * PERIOD)
    m = summary.trajectory_summary(ds)
    assert int(m.settled) == 1
    assert float(m.settling_time) == pytest.approx(4 * PERIOD)
    assert float(m.analysis_start_time) == pytest.approx(4 * PERIOD)
    assert "from the settling time on" in m.attrs["analysed_window"]


def test_settling_waits_for_the_contact_angle_too():
    ds = dynamic_result(6.0, angle_offset=lambda k: 0.02 if k == 2 else 0.005 if k == 3 else 0.0)
    assert summary.settling(ds).settling_time == pytest.approx(3 * PERIOD)  # 0.005 < 0.01 deg


def test_a_run_too_short_to_settle_is_analysed_after_30_percent_and_says_so():
    steps = [0.05, 0.02, 0.008, 0.003, 0.0004]
    ds = dynamic_result(5.0, spin_to_roll=lambda k: 0.07 + steps[min(k, 4)])
    state = summary.settling(ds)
    assert not state.settled and np.isnan(state.settling_time)
    m = summary.trajectory_summary(ds)
    assert int(m.settled) == 0 and np.isnan(float(m.settling_time))
    times = ds.time.values
    assert float(m.analysis_start_time) == times[int(0.3 * (times.size - 1))]
    message = summary.unsettled_message(ds, state, float(m.analysis_start_time))
    assert message.startswith("run too short to settle")
    assert "revolution 4 of 5" in message and "spin-to-roll of the inner race" in message
    assert "10 shaft revolutions suggested" in message
    from solver.results.checks import result_warnings

    stored = ds.assign(m.data_vars)
    assert any(w.startswith("run too short to settle") for w in result_warnings(stored))
    settled = dynamic_result(4.0)
    assert not any(
        "settle" in w
        for w in result_warnings(settled.assign(summary.trajectory_summary(settled).data_vars))
    )


def test_a_stretch_is_analysed_whole_where_the_summary_analyses_its_settled_window():
    """stretch_track_summary reads every sample it is given: on the samples from the settling
    time on it gives what trajectory_summary gives for the whole run, whose window starts there;
    on the whole run (transient included) it differs."""
    steps = [0.05, 0.02, 0.008, 0.003, 0.0004]
    offsets = [0.6, 0.3, 0.1, 0.0]
    ds = dynamic_result(
        8.0,
        spin_to_roll=lambda k: 0.07 + (steps[k] if k < len(steps) else 0.0),
        angle_offset=lambda k: offsets[k] if k < len(offsets) else 0.0,
    )
    m = summary.trajectory_summary(ds)
    first = int(np.searchsorted(ds.time.values, float(m.analysis_start_time)))
    assert first > 0
    stretch = summary.stretch_track_summary(ds.isel(time=slice(first, None)))
    assert set(stretch.data_vars) == set(summary.TRACK_METRICS)
    for name in summary.TRACK_METRICS:
        np.testing.assert_allclose(stretch[name].values, m[name].values, rtol=1e-12)
    whole = summary.stretch_track_summary(ds)
    own = {"race": "outer", "frame": "outer_ring"}  # a line whose offset the transient moved
    assert float(whole.trajectory_band_thickness.sel(own)) > 0.1 + float(
        m.trajectory_band_thickness.sel(own)
    )
    with pytest.raises(ValueError, match="needs a dynamic result"):
        summary.stretch_track_summary(ds.isel(time=0))


def test_less_than_two_revolutions_cannot_settle():
    ds = dynamic_result(1.5)
    state = summary.settling(ds)
    assert not state.settled and state.revolutions == 1
    message = summary.unsettled_message(ds, state, 0.0)
    assert "fewer than the 2 full revolutions" in message


# ---- quasi-static results and stacked results ----------------------------------------------------
def test_a_radial_load_fixed_in_space_gives_a_band_inside_and_a_line_outside():
    """A quasi-static solution of a load fixed in space: the stationary outer ring meets the field
    at the same place (a line: excursion about the band width, thickness near 0); the turning inner
    ring meets the whole field at every azimuth (a band: thickness about the band width, no mean
    variation), as the dynamic model draws them."""
    from solver import solve_quasistatic

    ds = solve_quasistatic("spindle-combined-load")
    m = summary.trajectory_summary(ds)
    for race in ("inner", "outer"):
        alpha = ds.contact_angle.sel(race=race).values[ds.contact_load.sel(race=race).values > 0]
        width = np.ptp(alpha)
        assert float(m.trajectory_band_width.sel(race=race)) == pytest.approx(width, rel=1e-12)
        in_outer = "outer_ring"
        excursion = float(m.trajectory_excursion.sel(race=race, frame=in_outer))
        thickness = float(m.trajectory_band_thickness.sel(race=race, frame=in_outer))
        assert excursion == pytest.approx(width, rel=0.02)  # the line
        assert thickness < 0.02 * width
        excursion = float(m.trajectory_excursion.sel(race=race, frame="inner_ring"))
        thickness = float(m.trajectory_band_thickness.sel(race=race, frame="inner_ring"))
        assert thickness == pytest.approx(width, rel=0.03)  # the band
        assert excursion < 0.02 * width
    assert "note" not in m.trajectory_band_thickness.attrs
    assert "steady running" in m.trajectory_excursion.attrs["analysed_window"]
    assert "settled" not in m


def test_a_tilt_turning_with_the_ring_alone_gives_the_lines_and_bands_of_its_revolution():
    """The field of a tilt turning with the inner ring (no radial load) is stationary in the inner
    ring's frame: one solution gives the tracks the solutions over one revolution give."""
    from solver import solve_over_revolution, solve_quasistatic

    case = "spindle-misalignment-ring"
    snapshot = summary.trajectory_summary(solve_quasistatic(case))
    revolution = summary.trajectory_summary(solve_over_revolution(case, angles=12))
    for race in ("inner", "outer"):
        width = float(revolution.trajectory_band_width.sel(race=race))
        line = snapshot.trajectory_excursion.sel(race=race, frame="inner_ring")
        band = snapshot.trajectory_band_thickness.sel(race=race, frame="outer_ring")
        expected_line = revolution.trajectory_excursion.sel(race=race, frame="inner_ring")
        expected_band = revolution.trajectory_band_thickness.sel(race=race, frame="outer_ring")
        assert float(line) == pytest.approx(float(expected_line), rel=0.01)
        assert float(band) == pytest.approx(width, rel=0.01)
        assert float(expected_band) > 0.9 * width  # the revolution's band, from fewer samples
        assert float(snapshot.trajectory_band_thickness.sel(race=race, frame="inner_ring")) < (
            0.01 * width
        )
        assert float(snapshot.trajectory_excursion.sel(race=race, frame="outer_ring")) < (
            0.01 * width
        )


def test_a_snapshot_no_frame_holds_still_is_the_snapshot_alone():
    """A tilt turning with the ring and a radial load fixed in space: no frame holds the field
    still, so the snapshot gives its spread over the balls in both frames and no thickness."""
    from solver import resolve_case, solve_quasistatic

    case = resolve_case("spindle-misalignment-ring").with_values({"operating.radial_load_N": 300.0})
    ds = solve_quasistatic(case)
    m = summary.trajectory_summary(ds)
    for race in ("inner", "outer"):
        alpha = ds.contact_angle.sel(race=race).values[ds.contact_load.sel(race=race).values > 0]
        np.testing.assert_allclose(
            m.trajectory_excursion.sel(race=race).values, np.ptp(alpha), rtol=1e-12
        )
    assert np.isnan(m.trajectory_band_thickness.values).all()
    assert "over one revolution" in m.trajectory_band_thickness.attrs["note"]


def test_a_sweep_gives_the_metrics_of_every_element():
    from solver import quasistatic_speed_sweep, solve_quasistatic

    ds = quasistatic_speed_sweep("spindle-combined-load", [5000.0, 20000.0])
    m = summary.trajectory_summary(ds)
    assert m.trajectory_excursion.dims == ("inner_ring_speed", "race", "frame")
    alone = summary.trajectory_summary(solve_quasistatic("spindle-combined-load"))
    np.testing.assert_allclose(
        m.trajectory_excursion.isel(inner_ring_speed=1).values,
        alone.trajectory_excursion.values,
        rtol=1e-6,
    )
