"""A small study on a LocalCluster of 2 workers: a few quasi-static points and two short dynamic
points; a worker killed mid-study; resume; the study Dataset through NetCDF."""

from __future__ import annotations

import os
import signal
import threading

import numpy as np
import pytest
import xarray as xr

from solver.errors import CaseError
from solver.study import Study, open_study, study_dataset
from tests.helpers.processes import signal_when

pytest.importorskip("distributed")

STUDY = """
title = "small test study"
base = "spindle-axial-preload"
[run]
shaft_revolutions = 1.0
samples_per_revolution = 40
[[sweep]]
name = "radial"
vary."operating.radial_load_N" = [0.0, 300.0, 600.0]
[[sweep]]
name = "tilt"
model = "dynamic"
vary."operating.misalignment_deg" = [0.05, 0.1]
set."operating.misalignment_frame" = "ring"
"""


@pytest.fixture(scope="module")
def client():
    from solver.study.runner import start_local_cluster

    cluster, client = start_local_cluster(2)
    yield client
    client.close()
    cluster.close()


def test_a_killed_worker_loses_nothing_and_the_dataset_round_trips(client, tmp_path):
    study = Study.from_text(STUDY)
    killed = []

    def progress(p):
        # once the quasi-static batch is in, the two dynamic runs are on the workers: kill one
        if p.done >= 3 and not killed:
            pids = client.run(os.getpid)
            victim = sorted(pids.values())[0]
            os.kill(victim, signal.SIGKILL)
            killed.append(victim)

    ds = study.run(tmp_path / "out", client=client, progress=progress)
    assert killed
    assert list(ds["point"].values) == ["p0001", "p0002", "p0003", "p0004", "p0005"]
    status = ds["status"].to_pandas()
    assert (status.loc[["p0001", "p0002", "p0003"], "quasistatic"] == "done").all()
    assert (status.loc[["p0004", "p0005"], "dynamic"] == "done").all()
    assert (status.loc[["p0004", "p0005"], "quasistatic"] == "not run").all()
    # metrics: the outer race's excursion grows with the radial load (quasi-static)
    exc = ds["excursion"].sel(model="quasistatic", race="outer").values[:3]
    assert exc[0] < exc[1] < exc[2]
    assert np.isfinite(ds["band_thickness"].sel(model="dynamic").values[3:]).all()
    assert ds["operating.radial_load_N"].values[:3].tolist() == [0.0, 300.0, 600.0]
    assert ds["operating.misalignment_frame"].values.tolist()[3:] == ["ring", "ring"]
    # every run's full result is on disk and loadable by point
    folder = open_study(tmp_path / "out")
    run = folder.load_point("p0005", "dynamic")
    assert "time" in run.dims and float(run.coords["misalignment"]) == pytest.approx(0.1)
    with pytest.raises(CaseError, match="it has not run"):
        folder.load_point("p0001", "dynamic")
    # the study Dataset through NetCDF
    path = tmp_path / "out" / "study.nc"
    with xr.open_dataset(path) as back:
        back = back.load()
    xr.testing.assert_identical(back.drop_attrs(), ds.drop_attrs())
    assert back.attrs["title"] == "small test study"
    xr.testing.assert_identical(study_dataset(folder), ds)


def test_resume_skips_finished_runs_and_redoes_a_missing_one(client, tmp_path):
    study = Study.from_text(STUDY.replace('model = "dynamic"', 'model = "quasistatic"'))
    out = tmp_path / "out"
    study.run(out, client=client)
    with pytest.raises(CaseError, match="--resume"):
        study.run(out, client=client)
    kept = out / "points" / "p0004.quasistatic.json"
    before = kept.stat().st_mtime_ns
    (out / "points" / "p0002.quasistatic.json").unlink()
    lines = []
    ds = study.run(out, client=client, resume=True, log=lines.append)
    assert any("4 run(s) already finished" in line for line in lines), lines
    assert kept.stat().st_mtime_ns == before
    assert (ds["status"].sel(model="quasistatic") == "done").all()
    other = Study.from_text(STUDY.replace("600.0", "700.0"))
    with pytest.raises(CaseError, match="another study"):
        other.run(out, client=client, resume=True)


def test_cancel_keeps_what_is_done_and_resume_finishes(client, tmp_path):
    study = Study.from_text(STUDY)
    stop = threading.Event()
    stop.set()
    ds = study.run(tmp_path / "out", client=client, cancel=stop)
    assert set(np.unique(ds["status"].values)) <= {"pending", "not run", "done"}
    assert (ds["status"] == "pending").any()
    ds = study.run(tmp_path / "out", client=client, resume=True)
    assert not (ds["status"] == "pending").any()


def test_connect_scheduler_reaches_a_real_scheduler(client):
    from solver.study.runner import connect_scheduler

    other = connect_scheduler(client.scheduler.address, timeout_s=20)
    try:
        assert other.scheduler_info()["workers"]
    finally:
        other.close()


def test_two_local_clusters_at_once_listen_on_loopback_without_a_port_warning(caplog):
    """The dashboard Dask always starts is on a free loopback port, never on 8787: a second
    cluster on the machine gives no "port already in use" warning."""
    import logging
    import warnings

    from solver.study.runner import start_local_cluster

    started = []
    with warnings.catch_warnings(record=True) as caught, caplog.at_level(logging.WARNING):
        warnings.simplefilter("always")
        try:
            for _ in range(2):
                started.append(start_local_cluster(1))
        finally:
            for cluster, client in started:
                client.close()
                cluster.close()
    texts = [str(w.message) for w in caught] + [r.getMessage() for r in caplog.records]
    assert not [t for t in texts if "already in use" in t or "8787" in t], texts
    for cluster, _client in started:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        assert cluster.dashboard_link.startswith("http://127.0.0.1:")
        assert ":8787/" not in cluster.dashboard_link


SIGNAL_STUDY = """
title = "signals"
base = "spindle-axial-preload"
[vary]
"operating.radial_load_N" = [{loads}]
"""


@pytest.mark.parametrize(
    "name",
    # each starts a cluster and warms a worker (a minute on a busy machine): SIGTERM in the
    # normal suite, the others (the same handler) with -m slow
    [
        "SIGTERM",
        pytest.param("SIGHUP", marks=pytest.mark.slow),
        pytest.param("SIGINT", marks=pytest.mark.slow),
    ],
)
def test_a_stop_signal_keeps_the_finished_runs_and_writes_the_study(tmp_path, name):
    """A real ``racetrace study`` process, sent the signal once runs have finished: it stops,
    shuts its cluster down without a traceback, writes study.nc, prints the resume command and
    exits with 128 + the signal's number."""
    import subprocess
    import sys
    from pathlib import Path

    signum = getattr(signal, name)
    study = tmp_path / "s.toml"
    study.write_text(SIGNAL_STUDY.format(loads=", ".join(f"{x}.0" for x in range(0, 2000, 5))))
    out = tmp_path / "out"
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    process = subprocess.Popen(
        [sys.executable, "-m", "racetrace", "study", str(study), "-o", str(out), "--workers", "1"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        text=True,
    )
    # the first run on a machine compiles the kernels: up to 600 s
    stdout, stderr = signal_when(
        process, lambda: bool(list(out.glob("points/*.json"))), signum, 600, "no run finished", 0.2
    )
    assert process.returncode == 128 + signum, stderr
    assert "Traceback" not in stderr and "ERROR" not in stderr, stderr
    assert f"{name} received" in stderr and "--resume" in stderr
    ds = xr.load_dataset(out / "study.nc")
    status = ds["status"].values
    assert (status == "done").any() and (status == "pending").any()
    assert "p0001" in stdout
