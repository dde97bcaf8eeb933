"""Background runs under faults: a runs folder that cannot take the job's result (the result goes
to the temporary folder instead, never lost) and a solver process killed from outside."""

from __future__ import annotations

import os
import signal
import time

import pytest
import xarray as xr

from app.runner import SolverRunner
from tests.helpers.faults import read_only_folder

JOBS = """
import time
import numpy as np
import xarray as xr

def ok(case_text, progress, cancel):
    return xr.Dataset({"n": ("x", np.arange(7))}, attrs={"complete": 1, "model": "fake"})

def endless(case_text, progress, cancel):
    k = 0
    while True:
        k += 1
        progress(0.001, 0.0, "")
        time.sleep(0.05)
"""


@pytest.fixture
def jobs(tmp_path, monkeypatch):
    (tmp_path / "fake_jobs_faults.py").write_text(JOBS)
    monkeypatch.syspath_prepend(str(tmp_path))  # spawn children receive the parent's sys.path
    return "fake_jobs_faults"


def _wait(runner, kinds=("done", "error"), timeout=120.0):
    events = []
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        events += runner.poll()
        if events and events[-1].kind in kinds:
            return events
        time.sleep(0.05)
    raise AssertionError(f"no {kinds} event within {timeout} s: {events}")


def test_a_read_only_runs_folder_sends_the_result_to_the_temp_folder(jobs, tmp_path, monkeypatch):
    temp = tmp_path / "tmp"
    temp.mkdir()
    monkeypatch.setenv("TMPDIR", str(temp))  # the child's temporary folder
    with read_only_folder(tmp_path / "runs") as runs:
        runner = SolverRunner()
        runner.start("x", runs / ".job-0123abcd.nc", target=f"{jobs}:ok")
        done = _wait(runner)[-1]
    assert done.kind == "done", done.text
    assert done.path == str(temp / "job-0123abcd.nc")
    with xr.open_dataset(done.path) as ds:
        assert ds.sizes["x"] == 7


def test_a_killed_solver_process_is_reported_and_frees_the_runner(jobs, tmp_path):
    runner = SolverRunner()
    runner.start("x", tmp_path / ".job-x.nc", target=f"{jobs}:endless")
    _wait(runner, kinds=("progress",))
    os.kill(runner._process.pid, signal.SIGKILL)
    last = _wait(runner)[-1]
    assert last.kind == "error" and "stopped unexpectedly" in last.text
    assert str(-signal.SIGKILL) in last.text
    assert not runner.busy
    assert list(tmp_path.glob(".job-x.nc*")) == []
