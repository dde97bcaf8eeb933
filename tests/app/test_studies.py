"""The Studies panel at state level: a small study builds up point by point, charts its metric,
opens a point's run in the result view, and Cancel keeps what is done."""

from __future__ import annotations

import time

import pytest

from app.state import DEFAULT_CASE, RacetraceApp
from solver.study import Study
from tests.app.test_state import _server

pytest.importorskip("distributed")

SMALL = """
title = "app study"
base = "spindle-axial-preload"
[vary]
"operating.radial_load_N" = [0.0, 400.0, 800.0]
"""


@pytest.fixture
def app(tmp_path):
    a = RacetraceApp(_server(), runs_dir=tmp_path / "runs", render=False)
    a.start(DEFAULT_CASE, play=False)
    a.studies.workers = 1
    yield a
    a.shutdown()


def _wait(app, timeout_s=600):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if app.studies.poll():
            return
        time.sleep(0.5)
    raise AssertionError(f"the study did not end: {app.state.study_status}")


def test_shipped_studies_are_offered(app):
    assert {"seed-spindle", "218-radial-load"} <= set(app.state.study_names)
    assert app.state.study_name in app.state.study_names


def test_a_study_builds_up_charts_and_opens_a_point(app):
    app.studies.start(Study.from_text(SMALL), "small")
    assert app.state.study_running
    _wait(app)
    s = app.state
    assert s.study_status == "done" and not s.study_running
    assert [r["point"] for r in s.study_rows] == ["p0001", "p0002", "p0003"]
    assert all(r["status"] == "done" for r in s.study_rows)
    assert s.study_sweep == "sweep 1"
    traces = s.chart_study["data"]
    assert len(traces) == 2  # inner and outer, one model
    outer = next(t for t in traces if t["name"].startswith("outer"))
    assert list(outer["x"]) == [0.0, 400.0, 800.0]
    assert outer["y"][0] < outer["y"][1] < outer["y"][2]
    s.study_metric = "peak_pressure"
    s.flush()
    assert "peak pressure" in str(s.chart_study["layout"])
    serial = int(s.result_serial)
    app.studies.open_point("p0002", "quasistatic")
    assert int(s.result_serial) == serial + 1
    assert "p0002" in s.result_label
    assert app.result.dataset.coords["radial_load"] == pytest.approx(400.0)


def test_cancel_keeps_the_finished_runs(app):
    app.studies.start(Study.from_text(SMALL), "small")
    app.studies.cancel()
    _wait(app)
    assert app.state.study_status.startswith("cancelled")
    assert not app.state.study_running
    assert {r["status"] for r in app.state.study_rows} <= {"done", "pending"}
