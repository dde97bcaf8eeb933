"""Background runs in a spawn process: progress, result file, cancel, user errors, crashes."""

from __future__ import annotations

import math
import sys
import time

import pytest
import xarray as xr

from app.runner import SolverRunner

JOBS = """
import os, signal, time
import numpy as np
import xarray as xr
from solver import CaseError

def ok(case_text, progress, cancel):
    progress(0.5, 0.01, "half way")
    attrs = {"complete": 1, "model": "fake"}
    return xr.Dataset({"n": ("x", np.arange(len(case_text)))}, attrs=attrs)

def slow(case_text, progress, cancel):
    k = 0
    while not cancel.is_set():
        k += 1
        progress(min(0.9, 0.01 * k), 0.001 * k, "")
        time.sleep(0.02)
    return xr.Dataset({"n": ("x", np.arange(k))}, attrs={"complete": 0, "model": "fake"})

def bad(case_text, progress, cancel):
    raise CaseError("bearing.ball_count = 0: must be at least 3")

def crash(case_text, progress, cancel):
    os.kill(os.getpid(), signal.SIGSEGV)
"""


@pytest.fixture
def jobs(tmp_path, monkeypatch):
    (tmp_path / "fake_jobs_e.py").write_text(JOBS)
    monkeypatch.syspath_prepend(str(tmp_path))  # spawn children receive the parent's sys.path
    return "fake_jobs_e"


def _wait(runner, timeout=60.0):
    events = []
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        events += runner.poll()
        if events and events[-1].kind in ("done", "error"):
            return events
        time.sleep(0.05)
    raise AssertionError(f"no end event within {timeout} s: {events}")


def test_run_reports_progress_and_result(jobs, tmp_path):
    r = SolverRunner()
    out = tmp_path / "out.nc"
    r.start("abcdef", out, target=f"{jobs}:ok")
    assert r.busy
    events = _wait(r)
    assert [e.kind for e in events] == ["progress", "done"]
    assert events[0].fraction == 0.5 and events[0].text == "half way"
    assert math.isnan(events[0].eta_s)  # one message gives no rate yet
    assert events[-1].complete == 1
    with xr.open_dataset(events[-1].path) as ds:
        assert ds.sizes["x"] == 6
    assert not r.busy


def test_cancel_keeps_partial_result(jobs, tmp_path):
    r = SolverRunner()
    r.start("x", tmp_path / "out.nc", target=f"{jobs}:slow")
    seen = []
    end = time.monotonic() + 60
    while not any(e.kind == "progress" for e in seen) and time.monotonic() < end:
        seen += r.poll()
        time.sleep(0.05)
    r.cancel()
    events = _wait(r)
    assert events[-1].kind == "done" and events[-1].complete == 0
    with pytest.raises(RuntimeError, match="already"):
        r._finished = False
        r.start("x", tmp_path / "b.nc", target=f"{jobs}:ok")


def test_user_error_and_crash_are_words(jobs, tmp_path):
    r = SolverRunner()
    r.start("x", tmp_path / "o.nc", target=f"{jobs}:bad")
    events = _wait(r)
    assert events[-1].kind == "error"
    assert events[-1].text == "bearing.ball_count = 0: must be at least 3"
    r.start("x", tmp_path / "o.nc", target=f"{jobs}:crash")
    events = _wait(r)
    assert events[-1].kind == "error"
    assert "stopped unexpectedly" in events[-1].text and "-11" in events[-1].text
    assert "Traceback" not in events[-1].text
    assert sys.modules.get("fake_jobs_e") is None  # the job ran only in the child
