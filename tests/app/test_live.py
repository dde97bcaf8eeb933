"""Live mode, state level (no browser): the pacing of the live solver, the sliding window and the
accumulated tracks read from chunks, and the live controller driving a real
``solver.LiveSimulation`` in its child process (start, pause, resume, reset, record, the solver
slot taken and released, the session stopped when its page closes)."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from app.live_runner import (
    BEHIND_FRACTION,
    CHANGE_CHUNK_FRACTION,
    CHUNK_WALL_S,
    MAX_LEAD_CHUNKS,
    LiveRunner,
    _Pace,
)
from app.live_view import LiveTracks, LiveWindow, band_thickness
from tests.app.conftest import make_dynamic_dataset
from viz.frames import FrameSource

# ---- pacing --------------------------------------------------------------------------------------


def test_pace_keeps_the_asked_rate_while_chunks_are_quick():
    pace = _Pace(0.006)
    for _ in range(5):
        report = pace.after_chunk(0.2 * CHUNK_WALL_S)
    assert pace.rate == pytest.approx(0.006)
    assert not report["behind"]
    assert pace.duration == pytest.approx(0.006 * CHUNK_WALL_S)


def test_pace_slows_to_what_a_slow_solver_achieves_and_stays_there():
    """A solver whose chunks cost a fixed 1.5 s plus 100 s per bearing second: the playback runs
    at about the rate it achieves (behind, said so) and does not spiral down."""
    pace = _Pace(0.006)

    def cost(duration):
        return 1.5 + 100.0 * duration

    asked_chunk = 0.006 * CHUNK_WALL_S
    reports = [pace.after_chunk(cost(pace.duration)) for _ in range(30)]
    # what the solver achieves on chunks of the asked bearing time: the playback keeps it
    assert pace.rate >= 0.99 * BEHIND_FRACTION * asked_chunk / cost(asked_chunk)
    assert all(r["behind"] for r in reports[1:])
    achieved = pace.duration / cost(pace.duration)
    assert BEHIND_FRACTION * achieved <= pace.rate <= achieved
    assert reports[-1]["rate"] == pytest.approx(reports[3]["rate"])  # steady, not shrinking
    assert pace.duration == pytest.approx(0.006 * CHUNK_WALL_S)


def test_pace_climbs_back_when_the_solver_is_quick_again():
    pace = _Pace(0.006)
    pace.after_chunk(0.0)  # the first chunk: not a measure
    pace.after_chunk(10 * CHUNK_WALL_S)
    assert pace.rate < 0.006
    pace.after_chunk(0.1 * CHUNK_WALL_S)
    assert pace.rate == pytest.approx(0.006)
    assert pace.chunk_wall == pytest.approx(CHUNK_WALL_S)


# ---- the lead of the child over the parent -------------------------------------------------------
def _messages_until(runner, condition, timeout_s: float) -> list:
    found, end = [], time.monotonic() + timeout_s
    while time.monotonic() < end:
        found += runner.poll()
        if condition(found):
            return found
        time.sleep(0.01)
    raise AssertionError(f"timed out; messages: {[m[0] for m in found]}")


def test_a_parent_that_falls_behind_gets_a_bounded_lead_and_sees_a_change_promptly():
    """The child runs ahead of the parent by at most MAX_LEAD_CHUNKS chunks, however long the
    parent does not take them (a page busy drawing), so a control change set then shows in one
    of the next MAX_LEAD_CHUNKS + 1 chunks the parent takes, not after a backlog of stale ones."""
    from pathlib import Path

    case_text = (Path(__file__).parents[2] / "assets/cases/spindle-combined-load.toml").read_text()
    runner = LiveRunner()
    runner.start(case_text, rate=0.006, target="tests.app.live_fakes:SlowLive")
    try:
        _messages_until(runner, lambda m: any(k[0] == "chunk" for k in m), 120)
        time.sleep(20 * CHUNK_WALL_S)  # the parent is busy: at the asked rate, 20 chunks are due
        stale = [m for m in runner.poll() if m[0] == "chunk"]
        assert 1 <= len(stale) <= MAX_LEAD_CHUNKS
        runner.send("set", "radial_load", 900.0, 0.0)
        time.sleep(5 * CHUNK_WALL_S)  # still busy
        found = _messages_until(
            runner,
            lambda m: any(k[0] == "chunk" and float(k[1].radial_load[-1]) == 900.0 for k in m),
            30,
        )
        chunks = [m[1] for m in found if m[0] == "chunk"]
        first = next(i for i, c in enumerate(chunks) if float(c.radial_load[-1]) == 900.0)
        assert first <= MAX_LEAD_CHUNKS  # at most the stale lead before it
    finally:
        runner.stop()


def test_a_change_is_computed_at_once_in_a_short_chunk_even_with_the_lead_full():
    """A control change does not wait for the parent to take the chunks ahead of it, nor for the
    rest of the chunk's wall time: the child computes the chunk after it at once, a short one
    (CHANGE_CHUNK_FRACTION of a chunk), and says which sets it carries."""
    from pathlib import Path

    from tests.app.live_fakes import SlowLive

    case_text = (Path(__file__).parents[2] / "assets/cases/spindle-combined-load.toml").read_text()
    runner = LiveRunner()
    rate = 0.006
    runner.start(case_text, rate=rate, target="tests.app.live_fakes:SlowLive")
    try:
        _messages_until(runner, lambda m: any(k[0] == "chunk" for k in m), 120)
        time.sleep(20 * CHUNK_WALL_S)  # the parent is busy: the lead fills up
        runner.send("set", "radial_load", 900.0, 0.0)
        time.sleep(10 * CHUNK_WALL_S)  # still busy
        chunks = [m for m in runner.poll() if m[0] == "chunk"]
        changed = [m for m in chunks if float(m[1].radial_load[-1]) == 900.0]
        assert changed, f"no chunk carries the change: {len(chunks)} chunks taken"
        assert len(chunks) == MAX_LEAD_CHUNKS + 1  # the lead, then the change's chunk alone
        _, chunk, info = changed[0]
        full = round(rate * CHUNK_WALL_S * SlowLive.SAMPLES_PER_SECOND)
        assert chunk.sizes["time"] == round(CHANGE_CHUNK_FRACTION * full)
        assert info["sets"] == 1
        assert info["chunk_wall_s"] == pytest.approx(CHANGE_CHUNK_FRACTION * CHUNK_WALL_S)
        assert all(m[2]["sets"] == 0 for m in chunks[: chunks.index(changed[0])])
    finally:
        runner.stop()


def test_a_change_sent_while_a_chunk_integrates_is_applied_before_the_cut_samples_are_sent():
    """A control that arrives while the child integrates a chunk does not wait for the chunk's
    planned end, nor for a Dataset of the samples done so far: it is applied at once, and those
    samples go to the parent with the change's own short chunk as one chunk, whose
    ``change_from_s`` is the time the change acts from; no chunk of the cut samples alone comes
    first."""
    from pathlib import Path

    from tests.app.live_fakes import InterruptibleLive

    case_text = (Path(__file__).parents[2] / "assets/cases/spindle-combined-load.toml").read_text()
    runner = LiveRunner()
    rate = 0.006
    runner.start(case_text, rate=rate, target="tests.app.live_fakes:InterruptibleLive")
    try:
        found = _messages_until(runner, lambda m: any(k[0] == "chunk" for k in m), 120)
        # a chunk integrates for ADVANCE_S; send the change a quarter into the next one
        time.sleep(0.25 * InterruptibleLive.ADVANCE_S)
        runner.send("set", "radial_load", 900.0, 0.0)
        found += _messages_until(
            runner,
            lambda m: any(k[0] == "chunk" and float(k[1].radial_load[-1]) == 900.0 for k in m),
            60,
        )
        chunks = [m for m in found if m[0] == "chunk"]
        first = next(i for i, m in enumerate(chunks) if float(m[1].radial_load[-1]) == 900.0)
        _, chunk, info = chunks[first]
        assert info["sets"] == 1 and all(m[2]["sets"] == 0 for m in chunks[:first])
        assert all(m[2]["change_from_s"] is None for m in chunks[:first])
        times, loads = chunk["time"].values, chunk["radial_load"].values
        before = times <= info["change_from_s"]
        full = round(rate * CHUNK_WALL_S * InterruptibleLive.SAMPLES_PER_SECOND)
        assert 0 < before.sum() < full  # the cut samples, fewer than planned, come with it
        assert np.all(loads[before] == 300.0) and np.all(loads[~before] == 900.0)
        assert (~before).sum() == round(CHANGE_CHUNK_FRACTION * full)  # the change's short chunk
        assert float(times[before][-1]) == pytest.approx(info["change_from_s"])
        step = 1.0 / InterruptibleLive.SAMPLES_PER_SECOND
        assert np.allclose(np.diff(times), step)
        if first:  # continues the chunk before it
            assert float(times[0]) == pytest.approx(float(chunks[first - 1][1]["time"][-1]) + step)
    finally:
        runner.stop()


def test_a_short_chunk_after_a_change_does_not_change_the_pace():
    pace = _Pace(0.006)
    pace.after_chunk(0.0)  # the first chunk
    duration, wall = pace.next_chunk(short=True)
    assert duration == pytest.approx(CHANGE_CHUNK_FRACTION * 0.006 * CHUNK_WALL_S)
    assert wall == pytest.approx(CHANGE_CHUNK_FRACTION * CHUNK_WALL_S)
    report = pace.after_chunk(2.0 * wall, wall)  # its fixed cost weighs more: no measure
    assert not report["behind"]
    assert pace.chunk_wall == pytest.approx(CHUNK_WALL_S)


# ---- the window and the tracks -------------------------------------------------------------------
def _chunks(ds, size):
    return [ds.isel(time=slice(k, k + size)) for k in range(0, ds.sizes["time"], size)]


def test_window_joins_chunks_into_the_frames_of_the_whole_run():
    ds = make_dynamic_dataset(n_time=120)
    whole = FrameSource.from_dynamic(ds)
    window = LiveWindow(revolutions=100.0)
    inputs = {"inner_ring_speed": float(ds.inner_ring_speed)}
    for chunk in _chunks(ds, 17):
        window.add(chunk, inputs)
    src = window.source
    assert src.n_frames == whole.n_frames
    np.testing.assert_allclose(src.times, whole.times)
    for name in ("ball_azimuth", "raceway_azimuth", "ring_angle", "cage_angle"):
        np.testing.assert_allclose(getattr(src, name), getattr(whole, name), atol=1e-9)
    np.testing.assert_allclose(window.inputs["radial_load"], 300.0)


def test_window_keeps_the_last_revolutions():
    ds = make_dynamic_dataset(n_time=200)  # two shaft revolutions
    omega = float(ds.inner_ring_speed)
    window = LiveWindow(revolutions=0.5)
    for chunk in _chunks(ds, 20):
        window.add(chunk, {"inner_ring_speed": omega})
    span = window.source.times[-1] - window.source.times[0]
    period = 2 * math.pi / omega
    assert 0.45 * period <= span <= 0.5 * period
    assert window.inputs["radial_load"].shape == (window.source.n_frames,)
    assert float(window.chunks[0]["time"][0]) <= window.source.times[0]


def test_the_live_band_is_the_track_summary_of_the_last_two_revolutions():
    """The band joins only the variables the track summary reads, from chunks where the shaft
    speed is a constant and chunks where it is given over time (an input being changed); it is
    the band of the same samples read from the whole Dataset, and NaN while the window holds
    less than the two revolutions."""
    from solver import stretch_track_summary

    ds = make_dynamic_dataset(n_time=200)  # two shaft revolutions
    omega = float(ds.inner_ring_speed)
    inputs = {"inner_ring_speed": omega}
    chunks = _chunks(ds, 20)
    for k in (3, 4):  # the speed over time, as in a chunk whose input is ramping
        n = chunks[k].sizes["time"]
        chunks[k] = (
            chunks[k]
            .drop_vars("inner_ring_speed")
            .assign(inner_ring_speed=("time", np.full(n, omega)))
        )
    window = LiveWindow(revolutions=5.0)
    for chunk in chunks[:6]:
        window.add(chunk, inputs)
    assert math.isnan(band_thickness(window, inputs))  # 0.6 of the two revolutions
    for chunk in chunks[6:]:
        window.add(chunk, inputs)
    band = band_thickness(window, inputs, "inner")
    reference = stretch_track_summary(ds).trajectory_band_thickness
    assert band == pytest.approx(float(reference.sel(race="inner", frame="inner_ring")), rel=1e-12)
    assert band > 0.1
    outer = band_thickness(window, inputs, "outer")
    assert outer == pytest.approx(float(reference.sel(race="outer", frame="outer_ring")), rel=1e-12)


def test_live_tracks_accumulate_as_the_whole_run_paints():
    from solver import geometry_from_result
    from viz.layout import RacewayLayout
    from viz.options import SceneOptions
    from viz.tracks import TrackPainter

    ds = make_dynamic_dataset(n_time=120)
    layout = RacewayLayout(geometry_from_result(ds), SceneOptions())
    whole = FrameSource.from_dynamic(ds)
    reference = [whole.reference_contact_angle(r) for r in (0, 1)]
    painter = TrackPainter(whole, layout.grooves, layout.grids, reference)
    painter.accumulate(whole.n_frames - 1)
    tracks = LiveTracks(layout.grooves, layout.grids, reference, 1.0)
    window = LiveWindow(revolutions=100.0)
    for chunk in _chunks(ds, 25):
        tracks.add(window.add(chunk, {"inner_ring_speed": float(ds.inner_ring_speed)}))
    for race in (0, 1):
        np.testing.assert_allclose(tracks.field(race, "dwell"), painter.field(race, "dwell"))
        np.testing.assert_allclose(
            tracks.field(race, "peak_pressure"), painter.field(race, "peak_pressure")
        )
    assert tracks.value_range("dwell")[1] > 0


# ---- the controller on the real live solver ------------------------------------------------------
def _until(app, condition, timeout_s: float, what: str):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        app.live.tick()
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}: status {app.state.live_status!r}")


@pytest.fixture
def live_app(tmp_path):
    """A session with a pool of one solver slot (so a second live session finds none)."""
    from app.services import Services
    from app.state import DEFAULT_CASE, RacetraceApp
    from tests.helpers.app_session import trame_server

    services = Services(tmp_path / "runs", tmp_path / "slots", max_runs=1)
    session = RacetraceApp(trame_server(), services=services, render=False)
    session.start(DEFAULT_CASE, play=False)
    yield session
    session.shutdown()
    services.shutdown()


@pytest.mark.slow
def test_live_session_start_pause_reset_record_and_stop(live_app):
    app, s = live_app, live_app.state
    pool = app.services.pool
    assert app.live.start()
    assert s.live_on and app.live.ticket.held
    other = pool.enqueue()
    assert not pool.try_acquire(other)  # the live session holds the only slot
    pool.drop(other)
    _until(app, lambda: app.live.window.count >= 3, 600, "three chunks")
    assert s.live_radial_load_N == pytest.approx(300.0)  # the controls show the solver's inputs
    assert s.live_frame["radial_load_N"] == pytest.approx(300.0)

    app.live.pause()
    _until(app, lambda: True, 1, "")
    time.sleep(1.0)
    app.live.tick()
    paused_at = app.live.window.count
    time.sleep(1.5)
    app.live.tick()
    assert app.live.window.count == paused_at  # no chunk while paused
    app.live.resume()
    _until(app, lambda: app.live.window.count > paused_at, 120, "a chunk after resuming")

    s.live_radial_load_N = 900.0
    s.flush()  # the change handler sends set_input to the child
    _until(
        app,
        lambda: app.live.window.inputs["radial_load"][-1] > 301.0,
        120,
        "the radial load to ramp up",
    )
    before_reset = float(app.live.window.source.times[-1])
    app.live.reset()
    _until(
        app,
        lambda: app.live.source is not None and app.live.source.times[-1] < before_reset,
        120,
        "a chunk after the reset",
    )
    assert app.live.window.inputs["radial_load"][0] == pytest.approx(900.0)  # the target holds

    app.live.record()
    _until(app, lambda: s.live_recorded is not None, 120, "the recording")
    assert s.live_recorded in {r["value"] for r in s.runs}
    ds, case_text = app.store.load(s.live_recorded)
    assert "time" in ds.dims and ds.sizes["time"] >= 2
    assert "radial_load" in case_text

    app.live.stop()
    assert not s.live_on and app.live.ticket is None
    again = pool.enqueue()
    assert pool.try_acquire(again)  # the slot is free again
    pool.drop(again)


def test_live_refused_clearly_when_no_slot_is_free(live_app):
    pool = live_app.services.pool
    held = pool.enqueue()
    assert pool.try_acquire(held)
    try:
        assert not live_app.live.start()
        assert "no solver slot is free" in live_app.state.live_status
        assert not live_app.state.live_on
        assert not live_app.live.runner.alive  # no solver process was started
    finally:
        pool.drop(held)


@pytest.mark.slow
def test_live_session_stops_when_its_page_closes(live_app):
    app = live_app
    assert app.live.start()
    process = app.live.runner._process
    app.live.client_count(0)
    assert not app.state.live_on
    assert "page was closed" in app.state.live_status
    assert app.live.ticket is None
    assert not process.is_alive()


def test_the_load_side_is_read_from_a_radial_load_angle_that_varies_in_time():
    """A live chunk (or a run along a history) carries the load direction over time: the view's
    load side is its value at the end (a coordinate for a steady result)."""
    from app.components.result_view import ResultView

    ds = make_dynamic_dataset(n_time=10)
    assert "radial_load_angle" in ds.coords
    assert ResultView._load_side(ds) == pytest.approx(math.radians(float(ds.radial_load_angle)))
    angles = np.linspace(0.0, 90.0, ds.sizes["time"])
    varying = ds.drop_vars("radial_load_angle").assign(radial_load_angle=("time", angles))
    assert ResultView._load_side(varying) == pytest.approx(math.pi / 2)


def test_while_live_the_map_caption_and_labels_describe_the_live_inputs(live_app):
    """The raceway map's caption (and the 3-D view's labels, from the same facts) say the live
    session's inputs from its newest chunk, not the result shown before; ending live mode
    shows that result's words again."""
    app, s = live_app, live_app.state
    before = s.raceway_metrics
    ds = make_dynamic_dataset(n_time=10)
    chunk = ds.drop_vars("radial_load").assign(radial_load=("time", np.full(10, 1234.0)))
    app.ctrl.show_live_inputs(chunk)
    assert "radial load 1234 N" in s.raceway_metrics
    assert s.raceway_metrics != before
    s.live_on = True
    app.live.ticket = None
    app.live.stop()
    assert s.raceway_metrics == before


def test_the_chunk_with_a_change_is_drawn_at_once_and_the_charts_wait_for_it(live_app, monkeypatch):
    """From a control change until the first chunk that carries it is drawn, the charts (a few
    tenths of a second of the page's loop on a loaded machine) are not brought up to date; that
    chunk is drawn as soon as the page reads it, even between two of the LIVE_FPS frames, and
    the charts follow at the next tick."""
    from tests.app.conftest import SHAFT_RPM

    live, s = live_app.live, live_app.state
    parts = _chunks(make_dynamic_dataset(n_time=60), 20)
    omega = SHAFT_RPM * math.pi / 30.0
    info = {"rate": 1e-3, "playback_rate": 1e-3, "asked_rate": 1e-3, "sets": 0}
    info["change_from_s"] = None
    info["inputs"] = {"radial_load": 300.0, "inner_ring_speed": omega}
    inbox, sent, charts = [], [], []
    monkeypatch.setattr(live.runner, "poll", lambda: [inbox.pop(0)] if inbox else [])
    monkeypatch.setattr(live.runner, "send", lambda *control: sent.append(control))
    monkeypatch.setattr(live, "_update_charts", lambda index: charts.append(index))
    s.live_on = True
    inbox.append(("chunk", parts[0], info))
    assert live.tick()
    assert len(charts) == 1  # due at the start
    assert not live.tick(frame_due=False)  # between frames, nothing new: nothing drawn

    s.live_radial_load_N = 900.0
    s.flush()  # the control's handler sends the change to the child
    assert [c[0] for c in sent] == ["set"]
    live._charts_due = 0.0  # the charts are due again
    assert live.tick()
    assert len(charts) == 1  # held while the change is on its way
    inbox.append(("chunk", parts[1], {**info, "sets": 1}))
    serial = live._serial
    assert live.tick(frame_due=False)  # drawn as it arrives
    assert live._serial == serial + 1 and len(charts) == 1  # the frame goes first
    assert live.tick()
    assert len(charts) == 2  # then the charts


def test_a_chunk_with_samples_from_before_its_change_is_played_from_the_change(
    live_app, monkeypatch
):
    """A chunk that holds the samples a change cut short and the change's own (``change_from_s``:
    the time the change acts from) is drawn as it arrives from its first sample after the
    change: the frame shows the change, not the cut samples before it."""
    live, s = live_app.live, live_app.state
    parts = _chunks(make_dynamic_dataset(n_time=60), 20)
    # a slow playback, so that the frame due when it is drawn is within a sample of its start
    info = {"rate": 1e-6, "playback_rate": 1e-6, "asked_rate": 1e-6, "sets": 0}
    info |= {"change_from_s": None, "inputs": {"radial_load": 300.0}}
    inbox = []
    monkeypatch.setattr(live.runner, "poll", lambda: [inbox.pop(0)] if inbox else [])
    monkeypatch.setattr(live.runner, "send", lambda *control: None)
    monkeypatch.setattr(live, "_update_charts", lambda index: None)
    s.live_on = True
    inbox.append(("chunk", parts[0], info))
    assert live.tick()
    times = parts[1]["time"].values
    loads = np.where(np.arange(times.size) < 12, 300.0, 900.0)  # the change acts after sample 11
    merged = parts[1].drop_vars("radial_load", errors="ignore").assign(radial_load=("time", loads))
    inbox.append(("chunk", merged, {**info, "sets": 1, "change_from_s": float(times[11])}))
    assert live.tick(frame_due=False)  # drawn as it arrives
    # the frame due a moment after it arrived: its first sample after the change, or the next
    assert float(times[11]) < s.live_frame["time_s"] <= float(times[13])
    assert s.live_frame["radial_load_N"] == 900.0


def test_the_page_loop_ticks_at_the_frame_rate_while_there_is_nothing_to_draw(live_app):
    """Before the first chunk (the solver compiling) and while paused, the page's loop ticks at
    LIVE_FPS, not as fast as it can; it polls faster only while a change is on its way."""
    import asyncio

    from app.components.live import LIVE_FPS

    live = live_app.live
    ticks = []

    def tick(frame_due=True):
        ticks.append(frame_due)
        return False  # nothing to draw

    live.tick = tick
    live_app.state.live_on = True

    async def run():
        try:
            await asyncio.wait_for(live._loop(), 1.0)
        except TimeoutError:
            pass

    asyncio.run(run())
    assert 0.5 * LIVE_FPS <= len(ticks) <= 1.5 * LIVE_FPS


def test_the_slowdown_is_said_with_the_rate_the_playback_keeps(live_app, monkeypatch):
    """#live-behind says the playback is slowed only while it runs below the asked rate, with the
    rate it runs at from then on: not the rate of the chunk that took too long (made for the
    asked rate, which read "slowed to 100 % of the asked rate")."""
    from tests.app.conftest import SHAFT_RPM

    live, s = live_app.live, live_app.state
    parts = _chunks(make_dynamic_dataset(n_time=60), 20)
    inputs = {"radial_load": 300.0, "inner_ring_speed": SHAFT_RPM * math.pi / 30.0}
    inbox = []
    monkeypatch.setattr(live.runner, "poll", lambda: [inbox.pop(0)] if inbox else [])
    s.live_on = True
    asked = 1e-3
    pace = _Pace(asked)

    def chunk_that_took(part, took_s):
        info = {**pace.after_chunk(took_s), "inputs": inputs, "sets": 0, "change_from_s": None}
        inbox.append(("chunk", part, info))
        live.tick()

    chunk_that_took(parts[0], 0.0)  # the first chunk: no measure
    assert s.live_behind == ""
    chunk_that_took(parts[1], 3.0 * CHUNK_WALL_S)  # the solver could not keep up
    slowed = 100.0 * pace.rate / asked
    assert slowed < 50.0
    assert s.live_behind.endswith(f"slowed to {slowed:.0f} % of the asked rate")
    assert "100 %" not in s.live_behind
    chunk_that_took(parts[2], 0.1 * CHUNK_WALL_S)  # quick again: the asked rate is back
    assert pace.rate == pytest.approx(asked)
    assert s.live_behind == ""


def test_a_slowdown_too_small_to_show_in_whole_percent_is_not_said():
    from app.components.live import slowdown_words

    assert slowdown_words(1e-3, 1e-3) == ""
    assert slowdown_words(0.996e-3, 1e-3) == ""  # would read "slowed to 100 %"
    assert slowdown_words(2e-3, 1e-3) == ""  # faster than asked: not slowed
    assert slowdown_words(0.994e-3, 1e-3).endswith("slowed to 99 % of the asked rate")
    assert slowdown_words(0.25e-3, 1e-3).endswith("slowed to 25 % of the asked rate")
