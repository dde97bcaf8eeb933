"""The live simulation (issue 24 §3, solver side; docs/live.md): a dynamic run on the shipped
spindle case (7008C-class hybrid, 20 000 rpm, 500 N axial + 300 N radial) advanced in chunks of a
few shaft revolutions, with inputs set while it runs.

Each test runs a few milliseconds of simulated time (a shaft revolution is 3 ms).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver import CaseError, LiveSimulation, parse_case, simulate
from tests.helpers.accuracy import ANGLE_DEG, LOAD_RELATIVE

CASE = "spindle-combined-load"
REVOLUTION = 60.0 / 20000.0  # s


@pytest.fixture(scope="module")
def spindle():
    return solver.resolve_case(CASE)


def _inner(ds, name):
    return ds[name].sel(race="inner").transpose("time", "ball").values


def test_chunks_continue_in_time_with_the_inputs_as_data_variables():
    live = LiveSimulation(CASE)
    rate = live.samples_per_second
    assert rate == pytest.approx(180 / REVOLUTION)  # the case's samples per revolution
    first = live.advance(0.5 * REVOLUTION)
    second = live.advance(0.5 * REVOLUTION)
    t1, t2 = first["time"].values, second["time"].values
    assert t1[0] == pytest.approx(1.0 / rate)
    assert t2[0] == pytest.approx(t1[-1] + 1.0 / rate)
    assert np.allclose(np.diff(np.concatenate([t1, t2])), 1.0 / rate)
    assert live.time == pytest.approx(t2[-1])
    assert set(first.data_vars) == set(second.data_vars)
    for name in live.input_names:
        assert second[name].dims == ("time",), name
    assert np.all(second["radial_load"].values == 300.0)
    assert np.allclose(second["inner_ring_speed"].values, 20000.0 * math.pi / 30.0)
    # the run's per-sample variables, and the ball moves on (no restart at a chunk's start)
    for name in ("contact_load", "contact_angle", "cage_speed", "ball_azimuth"):
        assert name in second
    azimuth = [np.radians(ds["ball_azimuth"].sel(ball=0).values) for ds in (first, second)]
    step = np.diff(np.unwrap(azimuth[1]))
    gap = azimuth[1][0] - azimuth[0][-1]
    assert abs(math.remainder(gap, 2 * math.pi) - np.median(step)) < 0.2 * np.median(step)
    live.close()


def test_a_radial_load_ramp_shows_in_the_chunk_and_loads_the_inner_contacts():
    live = LiveSimulation(CASE)
    before = live.advance(0.5 * REVOLUTION)
    start = live.time
    live.set_input("radial_load", 1500.0, ramp_s=REVOLUTION)
    assert live.inputs_now()["radial_load"] == 300.0
    after = live.advance(2.0 * REVOLUTION)
    t = after["time"].values
    load = after["radial_load"].values
    expected = 300.0 + 1200.0 * np.clip((t - start) / REVOLUTION, 0.0, 1.0)
    assert np.allclose(load, expected, rtol=1e-12, atol=1e-9)
    assert live.inputs_now()["radial_load"] == 1500.0
    # the most loaded inner contact takes most of the added radial load; the contact angles
    # spread round the ring (a radial load lowers the angle in the loaded zone)
    q_before = _inner(before, "contact_load")[-1]
    q_after = _inner(after, "contact_load")[-1]
    assert q_after.max() > q_before.max() + 100.0
    a_before = _inner(before, "contact_angle")[-1]
    a_after = _inner(after, "contact_angle")[-1]
    assert np.ptp(a_after) > np.ptp(a_before) + 1.0
    assert a_after[np.argmax(q_after)] < a_before[np.argmax(q_before)]


def test_reset_starts_again_from_the_quasistatic_state_of_the_inputs_set(spindle):
    live = LiveSimulation(spindle)
    live.advance(0.3 * REVOLUTION)
    live.set_input("axial_load", 800.0, ramp_s=0.1 * REVOLUTION)
    live.advance(0.3 * REVOLUTION)
    live.reset()
    assert live.time == 0.0
    assert live.inputs_now()["axial_load"] == 800.0
    chunk = live.advance(0.3 * REVOLUTION)
    fresh = LiveSimulation(spindle.with_values({"operating.axial_load_N": 800.0}))
    reference = fresh.advance(0.3 * REVOLUTION)
    assert np.array_equal(chunk["time"].values, reference["time"].values)
    assert np.allclose(chunk["contact_load"].values, reference["contact_load"].values, rtol=1e-12)
    assert np.all(chunk["axial_load"].values == 800.0)
    recorded = parse_case(live.recorded_case())  # the history was cleared: nothing set since
    assert recorded.operating.axial_load_N == 800.0
    assert "operating.axial_load_N" not in recorded.histories


def test_an_interrupted_advance_returns_the_samples_done_and_a_change_acts_from_there():
    """``advance(..., interrupt=...)`` asks the callable every INTERRUPT_SAMPLES samples; told
    to stop, it returns the samples done (not the planned duration), and an input set then acts
    from the time reached."""
    from solver.models.dynamic.live import INTERRUPT_SAMPLES

    live = LiveSimulation(CASE)
    live.advance(0.5 * REVOLUTION)
    reached = live.time
    asked = []

    def second_time():
        asked.append(live.time)
        return len(asked) == 2

    chunk = live.advance(0.5 * REVOLUTION, interrupt=second_time)
    planned = round(0.5 * REVOLUTION * live.samples_per_second)
    assert chunk.sizes["time"] == 2 * INTERRUPT_SAMPLES < planned
    timing = live.last_advance
    assert timing.interrupted and timing.planned_samples == planned
    assert live.time == pytest.approx(reached + 2 * INTERRUPT_SAMPLES / live.samples_per_second)
    assert timing.simulated_s == pytest.approx(live.time - reached)
    live.set_input("radial_load", 900.0, ramp_s=0.0)
    after = live.advance(0.1 * REVOLUTION, interrupt=lambda: False)
    step = 1.0 / live.samples_per_second
    assert after["time"].values[0] == pytest.approx(reached + (2 * INTERRUPT_SAMPLES + 1) * step)
    assert np.all(after["radial_load"].values == 900.0)
    assert not live.last_advance.interrupted
    live.close()


def test_a_change_set_between_integrations_acts_before_any_dataset_and_take_joins_them():
    """``integrate`` keeps its samples for ``take`` without building a Dataset, so an input set
    after an interrupted integration acts from the time it reached; ``take`` then gives the
    samples of both integrations as one chunk: the ones up to the change at the old value, the
    ones after it ramping, every variable the same as ``advance`` gives over those samples."""
    from solver.models.dynamic.live import INTERRUPT_SAMPLES

    live, again = LiveSimulation(CASE), LiveSimulation(CASE)
    asked = []
    part = live.integrate(0.5 * REVOLUTION, interrupt=lambda: asked.append(1) or len(asked) == 1)
    assert part.interrupted and part.simulated_s == pytest.approx(
        INTERRUPT_SAMPLES / live.samples_per_second
    )
    assert live.last_advance is None  # nothing taken yet
    changed_at = live.time
    ramp = 4.0 / live.samples_per_second
    live.set_input("radial_load", 900.0, ramp_s=ramp)
    live.integrate(0.05 * REVOLUTION)
    chunk = live.take()
    assert live.take() is None  # taken once
    times, loads = chunk["time"].values, chunk["radial_load"].values
    before = times <= changed_at + 0.5 / live.samples_per_second
    assert before.sum() == INTERRUPT_SAMPLES
    assert np.all(loads[before] == 300.0) and np.all(loads[~before] > 300.0)
    assert loads[-1] == 900.0
    assert np.allclose(np.diff(times), 1.0 / live.samples_per_second)
    timing = live.last_advance
    assert timing.interrupted and timing.simulated_s == pytest.approx(live.time)
    # the same session advanced in whole chunks: the same samples, bit for bit
    first = again.advance(INTERRUPT_SAMPLES / again.samples_per_second)
    again.set_input("radial_load", 900.0, ramp_s=ramp)
    second = again.advance(0.05 * REVOLUTION)
    for name, var in chunk.data_vars.items():
        if "time" not in var.dims or name == "load_work":  # load_work counts from a chunk's start
            continue
        joined = np.concatenate(
            [first[name].values, second[name].values], axis=var.dims.index("time")
        )
        assert np.array_equal(var.values, joined, equal_nan=True), name
    live.close()
    again.close()


def test_the_chunks_hold_the_per_sample_variables_of_the_recorded_run():
    """Every variable over time of the chunks (an interrupted one among them) is the recorded
    run's at the same samples, bit for bit: the chunk's derived data (skidding, the inputs over
    time) is the run's, however it is built. ``load_work`` counts from each chunk's start, the
    inputs a run holds constant are over time in a chunk."""
    live = LiveSimulation(CASE)
    chunks = [live.advance(0.3 * REVOLUTION)]
    live.set_input("radial_load", 900.0, ramp_s=0.2 * REVOLUTION)
    asked = []
    chunks.append(
        live.advance(0.5 * REVOLUTION, interrupt=lambda: len(asked.append(0) or asked) > 2)
    )
    assert live.last_advance.interrupted
    chunks.append(live.advance(0.3 * REVOLUTION))
    recorded = live.recorded_result()
    rate = live.samples_per_second
    compared = set()
    for chunk in chunks:
        first = int(round(float(chunk["time"][0]) * rate))
        run = recorded.isel(time=slice(first, first + chunk.sizes["time"]))
        assert np.array_equal(chunk["time"].values, run["time"].values)
        for name, var in chunk.data_vars.items():
            if "time" not in var.dims or name == "load_work":
                continue
            ours = var.transpose(*run[name].dims).values if "time" in run[name].dims else None
            theirs = run[name].values
            if ours is None:  # constant in the run: the chunk holds it at every sample
                assert np.all(var.values == theirs), name
                continue
            assert np.array_equal(ours, theirs, equal_nan=True), name
            compared.add(name)
    assert {"skidding_ratio", "instantaneous_cage_slip", "radial_load", "contact_load"} <= compared
    live.close()


def test_a_recorded_session_is_a_case_that_simulate_reproduces(tmp_path):
    live = LiveSimulation(CASE)
    live.advance(0.4 * REVOLUTION)
    live.set_input("radial_load", 900.0, ramp_s=0.2 * REVOLUTION)
    live.advance(0.3 * REVOLUTION)
    live.set_input("inner_ring_speed", 18000.0 * math.pi / 30.0, ramp_s=0.2 * REVOLUTION)
    live.advance(0.5 * REVOLUTION)
    text = live.recorded_case()
    case = parse_case(text)
    assert set(case.histories) == {"operating.radial_load_N", "operating.inner_ring_speed_rpm"}
    assert case.simulation.duration_s == pytest.approx(live.time)
    recorded = live.recorded_result()
    assert recorded.attrs["complete"] == 1
    assert recorded.attrs["case"] == text
    reopened = solver.load_result(solver.save_dataset(recorded, tmp_path / "live.nc"))
    assert np.array_equal(reopened["contact_load"].values, recorded["contact_load"].values)
    assert reopened.attrs["complete"] == 1
    run = simulate(case)
    assert np.allclose(run["time"].values, recorded["time"].values, rtol=0, atol=1e-12)
    for name in ("radial_load", "inner_ring_speed"):
        assert np.allclose(run[name].values, recorded[name].values, rtol=1e-12), name
    # the accuracy contract (tests/helpers/accuracy.py): per-contact time means of the contact
    # angle and load (the two integrate the same equations with their step sequences restarted at
    # different chunk boundaries, so they differ at the tolerance's level)
    for name, allowed in (("contact_angle", ANGLE_DEG), ("contact_load", None)):
        ours, theirs = (ds[name].mean("time") for ds in (recorded, run))
        if allowed is None:
            allowed = LOAD_RELATIVE * np.abs(theirs)
        assert np.all(np.abs(ours - theirs) < allowed), name


@pytest.mark.parametrize(
    ("name", "value", "words"),
    [
        ("radial_load", -10.0, "operating.radial_load_N"),
        ("outer_ring_speed", 20000.0 * math.pi / 30.0, "would not turn relative"),
        ("axial_load", math.nan, "finite"),
        ("preload", 100.0, "not an input of this session"),
        ("inner_ring_speed", 1e9, "operating.inner_ring_speed_rpm"),
    ],
)
def test_a_bad_value_is_a_case_error_naming_the_input(spindle, name, value, words):
    live = LiveSimulation(spindle)
    with pytest.raises(CaseError) as error:
        live.set_input(name, value)
    assert words in str(error.value)
    assert f"live input {name}" in str(error.value) or "preload" in str(error.value)
    assert live.inputs_now()["radial_load"] == 300.0  # nothing changed


def test_both_loads_zero_is_refused_and_a_set_case_cannot_run_live(spindle):
    live = LiveSimulation(spindle.with_values({"operating.radial_load_N": 0.0}))
    with pytest.raises(CaseError, match="nothing holds the balls"):
        live.set_input("axial_load", 0.0)
    with pytest.raises(CaseError, match="one bearing"):
        LiveSimulation("spindle-pair-db-light-preload")


def test_divergence_stops_the_session_until_reset_and_close_ends_it(spindle):
    live = LiveSimulation(spindle)
    live.advance(0.1 * REVOLUTION)
    live.set_input("radial_load", 2e5, ramp_s=0.0)  # far beyond the bearing: a ball escapes
    with pytest.raises(solver.SimulationDiverged, match="a ball left the raceways"):
        live.advance(0.3 * REVOLUTION)
    with pytest.raises(solver.SimulationDiverged, match="reset"):
        live.advance(0.1 * REVOLUTION)
    live.set_input("radial_load", 300.0)
    live.reset()
    chunk = live.advance(0.1 * REVOLUTION)
    assert np.all(chunk["radial_load"].values == 300.0)
    live.close()
    with pytest.raises(RuntimeError, match="closed"):
        live.advance(0.1 * REVOLUTION)


def test_a_case_with_histories_starts_from_their_values_at_zero_and_holds_them():
    live = LiveSimulation("spindle-start-up")  # the shaft ramps up from rest over 0.3 s
    assert live.samples_per_second == 20000.0  # the case's simulation.samples_per_second
    chunk = live.advance(0.002)
    assert np.all(chunk["inner_ring_speed"].values == 0.0)  # held at rest, not ramped
    assert np.all(chunk["axial_load"].values == 150.0)
    live.set_input("inner_ring_speed", 100.0, ramp_s=0.001)
    chunk = live.advance(0.002)
    assert chunk["inner_ring_speed"].values[-1] == 100.0
    assert float(chunk["cage_speed"].values[-1]) > 0.0


def test_an_input_changed_more_often_than_a_case_table_holds_is_refused(spindle, monkeypatch):
    import solver.models.dynamic.live as live_module

    monkeypatch.setattr(live_module, "MAX_KNOTS", 5)  # a case's table: at most 100 000 points
    live = LiveSimulation(spindle)
    live.advance(1.0 / live.samples_per_second)
    live.set_input("axial_load", 510.0, ramp_s=0.0)  # 3 points: 0, now, now
    live.advance(1.0 / live.samples_per_second)
    live.set_input("axial_load", 520.0, ramp_s=0.0)  # 5 points
    live.advance(1.0 / live.samples_per_second)
    with pytest.raises(CaseError, match="reset"):
        live.set_input("axial_load", 530.0, ramp_s=0.0)
    assert live.inputs_now()["axial_load"] == 520.0
    assert len(parse_case(live.recorded_case()).histories["operating.axial_load_N"].times) == 5
