"""Sessions at state level: two sessions on shared services, the solver queue, crafted messages."""

from __future__ import annotations

import asyncio
import threading
import time

import pytest

from app import runner as runner_module
from app.components import runs as runs_module
from app.runner import QUASISTATIC_JOB
from app.services import Services
from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server


def _set(app, **values):
    with app.state:
        for k, v in values.items():
            app.state[k] = v


@pytest.fixture
def services(tmp_path):
    s = Services(tmp_path / "runs", slots_dir=tmp_path / "slots", max_runs=1)
    yield s
    s.shutdown()


def _sessions(services, count):
    apps = [RacetraceApp(trame_server(), render=False, services=services) for _ in range(count)]
    for a in apps:
        a.start(DEFAULT_CASE, play=False)
    yield apps
    for a in apps:
        a.shutdown()


@pytest.fixture
def two(services):
    """Two sessions on the same services (the tests of what one session sees of the other)."""
    yield from _sessions(services, 2)


@pytest.fixture
def one(services):
    """One session on the services (the tests of a single session: a session costs about a
    second of CPU to start)."""
    yield from _sessions(services, 1)


def _wait(app, timeout=120.0):
    end = time.monotonic() + timeout
    while not app.runs.poll_runner():
        assert time.monotonic() < end, app.state.status
        time.sleep(0.05)


def test_sessions_keep_their_own_case(two):
    a, b = two
    _set(a, fv_axial_load_N="900")
    assert a.state.fv_axial_load_N == "900" and b.state.fv_axial_load_N != "900"
    assert a.form.case.operating.axial_load_N == 900.0
    assert b.form.case.operating.axial_load_N != 900.0


def test_a_second_run_waits_for_the_slot_with_its_place_shown(two, monkeypatch):
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", QUASISTATIC_JOB)
    a, b = two
    a.runs.run()
    assert a.state.status.startswith("running dynamic")
    b.runs.run()
    assert b.state.busy and b.state.status.startswith("queued: place 1 in the queue")
    assert "at most 1 run at once" in b.state.status
    assert not b.runs.runner.busy
    b.runs.run()  # an extra press says why nothing happens
    assert "already going" in b.state.run_note
    _wait(a)
    assert a.state.status == "done"
    _wait(b)  # it starts once the slot is free
    assert b.state.status == "done" and b.state.run_note == ""
    # each session sees the other's run
    a.runs.refresh()
    assert len(a.state.runs) == len(b.state.runs) == 2


def test_cancelling_a_queued_run_saves_nothing(two, monkeypatch):
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", QUASISTATIC_JOB)
    a, b = two
    a.runs.run()
    b.runs.run()
    b.runs.cancel()
    assert b.state.status == "cancelled" and not b.state.busy and not b.state.run_disabled
    _wait(a)
    assert len(a.state.runs) == 1  # only a's run


def test_a_session_sees_runs_saved_by_another(two, monkeypatch):
    a, b = two
    monkeypatch.setattr(runs_module, "WATCH_S", 0.05)
    saved = a.store.save(a.result.dataset, a.form.case.to_toml(), "from a")

    async def watch():
        b.runs.watch()
        for _ in range(100):
            await asyncio.sleep(0.05)
            if b.state.runs:
                break
        b.runs._watch_task.cancel()

    asyncio.run(watch())
    assert [r["value"] for r in b.state.runs] == [saved.run_id]


@pytest.mark.parametrize(
    "values",
    [
        {"frame": "x"},
        {"frame": 1e300},
        {"speed": None, "frame": float("nan")},
        {"trace_ball": "all"},
        {"trace_ball": 10_000},
        {"exaggeration": "huge"},
        {"open_panels": 5},
        {"open_panels": [{"a": 1}, "comparison"]},
        {"camera": "nowhere"},
        {"run_id": "../../etc"},
        {"run_id": ["x"]},
        {"compare_ids": {"x": 1}},
        {"compare_ids": [{"x": 1}, 5, "../../etc"]},
        {"study_results": {"x": 1}},
        {"study_results": "folder:../../etc"},
        {"uploaded_case": {"name": 5}},
        {"fv_ball_count": ["12"]},
    ],
)
def test_crafted_client_values_never_crash_a_handler(one, values):
    (a,) = one
    label = a.state.result_label
    _set(a, **values)  # must not raise
    assert a.state.result_label == label  # the result on show stays
    # the time controls still work afterwards
    _set(a, frame=3)
    assert a.state.frame_time.strip().startswith("t =")


def test_crafted_values_do_not_stop_the_animation(one):
    (a,) = one
    a.clients = 1  # as if a browser were connected

    async def play():
        _set(a, playing=True)
        await asyncio.sleep(0.2)
        _set(a, speed="fast", frame="nowhere")
        await asyncio.sleep(0.3)
        frame = a.state.frame
        await asyncio.sleep(0.3)
        moved = a.state.frame != frame
        _set(a, playing=False)
        await asyncio.sleep(0.1)
        return moved, a.result._play_task.done()

    moved, stopped = asyncio.run(play())
    assert moved and stopped


def test_case_download_follows_edits(one):
    import urllib.parse

    (a,) = one
    assert "Fr-300-N" in a.state.case_file_name
    original = urllib.parse.unquote(a.state.case_toml_href)
    assert "300 N radial" in original  # the picked case's own title, not edited
    _set(a, fv_radial_load_N="450")
    assert "Fr-450-N" in a.state.case_file_name and "300" not in a.state.case_file_name
    edited = urllib.parse.unquote(a.state.case_toml_href)
    assert "300 N radial" not in edited and "Fr 450 N" in edited
    _set(a, fv_title="my own title")
    assert 'title = "my own title"' in urllib.parse.unquote(a.state.case_toml_href)


def test_invalid_form_says_why_run_is_off_and_marks_the_result_out_of_date(one):
    (a,) = one
    assert a.state.run_blocked == "" and a.state.result_stale is False
    _set(a, fv_ball_count="0")
    assert a.state.run_disabled
    assert a.state.run_blocked.startswith("Run is off until the form is fixed: ")
    assert "all" in a.state.run_blocked.lower() or "ball" in a.state.run_blocked.lower()
    assert a.state.result_stale is True
    a.runs.run()
    assert a.state.run_note == a.state.run_blocked and not a.state.busy


def test_run_on_a_result_outside_the_model_asks_first(one, monkeypatch):
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", QUASISTATIC_JOB)
    (a,) = one
    _set(a, fv_axial_load_N="1e9")
    a.form.preview_now()
    assert a.state.result_warnings and not a.state.result_stale
    a.runs.run()
    assert a.state.run_confirm is True and not a.state.busy  # asked, not started
    a.runs.run_anyway()
    assert a.state.run_confirm is False and a.state.busy
    a.runs.cancel()
    _wait(a)


def test_upload_errors_show_in_the_status(one):
    (a,) = one
    _set(a, uploaded_case={"name": "big.toml", "content": b"#" * (1024 * 1024 + 1)})
    assert a.state.status == "error: upload refused: big.toml is too large"
    _set(a, uploaded_case={"name": "bad.toml", "content": b"ball_count = ="})
    assert a.state.status.startswith("error: upload bad.toml is not a valid case")


def test_opening_a_corrupt_run_says_so_in_the_status(one):
    (a,) = one
    saved = a.store.save(a.result.dataset, a.form.case.to_toml(), "to be damaged")
    (a.store.path(saved.run_id) / "result.nc").write_bytes(b"not a netcdf file")
    a.runs.refresh()
    _set(a, run_id=saved.run_id)
    assert a.state.status.startswith("error: ")
    assert a.state.result_label == "quasi-static preview"  # the result on show stays


def test_cancel_right_after_run_saves_nothing(one):
    (a,) = one
    _set(a, fv_shaft_revolutions="0.3")
    a.runs.run()
    a.runs.cancel()
    _wait(a, timeout=300)
    assert a.state.status == "nothing computed yet, so nothing saved: cancelled", a.state.status
    assert a.store.list() == [] and a.state.runs == []


def test_a_preview_still_on_its_way_does_not_overwrite_a_run(one, monkeypatch):
    """An edit schedules a preview; Run is pressed and cancelled before that preview arrives: the
    late preview is dropped and does not replace the run's final status."""
    from app.components import case_form

    (a,) = one
    _set(a, fv_shaft_revolutions="0.3")
    slow = case_form.solve_preview

    def late_preview(case):  # arrives only after the run has ended (a loaded machine)
        end = time.monotonic() + 300
        while not ran.is_set() or a.runs.ticket is not None:
            assert time.monotonic() < end
            time.sleep(0.05)
        try:
            return slow(case)
        finally:
            previewed.set()

    ran, previewed = threading.Event(), threading.Event()

    monkeypatch.setattr(case_form, "solve_preview", late_preview)

    async def scenario():
        a.form.schedule_preview()  # what an edit does, with the page's event loop running
        await asyncio.sleep(0.3)  # the preview is being computed
        a.runs.run()
        ran.set()
        a.runs.cancel()
        end = time.monotonic() + 300
        while a.runs.ticket is not None:
            assert time.monotonic() < end, a.state.status
            await asyncio.sleep(0.1)
        while not previewed.is_set():  # the late preview arrives ...
            assert time.monotonic() < end
            await asyncio.sleep(0.1)
        await asyncio.sleep(0.5)  # ... and its task has had its turn

    asyncio.run(scenario())
    assert a.state.status.endswith("cancelled"), a.state.status


def test_server_stop_mid_run_saves_the_partial_run_marked_incomplete(one):
    (a,) = one
    _set(a, fv_shaft_revolutions="100")
    a.runs.run()
    end = time.monotonic() + 300
    while a.state.progress <= 0:  # wait for the first steps
        assert not a.runs.poll_runner() and time.monotonic() < end, a.state.status
        time.sleep(0.1)
    process = a.runs.runner._process
    a.shutdown()  # what the session process does on SIGTERM
    assert not process.is_alive()
    (saved,) = a.store.list()
    assert saved.status == "cancelled" and saved.title.endswith("(server stopped)")
    assert " of 100 rev" in saved.title  # the revolutions reached, not those asked for
    ds, _ = a.store.load(saved.run_id)
    assert ds.attrs["complete"] == 0 and ds.sizes["time"] >= 2


def test_a_read_only_runs_folder_still_gives_a_session(tmp_path, monkeypatch):
    """The session starts and exports into a temporary folder (runs are kept in memory by the
    run store, which says so)."""
    from tests.helpers.faults import read_only_folder

    with read_only_folder(tmp_path / "ro") as runs:
        app = RacetraceApp(trame_server(), runs_dir=runs, render=False)
        app.start(DEFAULT_CASE, play=False)
        path = app.exports.export("csv")
        assert path is not None and path.is_file() and runs not in path.parents
        # a run still runs; its result is kept in memory and the page says so
        monkeypatch.setattr(runner_module, "DYNAMIC_JOB", QUASISTATIC_JOB)
        app.runs.run()
        _wait(app)
        assert app.state.status == "done", app.state.status
        assert "could not be saved" in app.state.run_note
        assert len(app.state.runs) == 1
        app.shutdown()
