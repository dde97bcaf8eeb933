"""``racetrace check`` and ``racetrace solve`` on a bearing-set case: the set described, the
result per bearing (table, JSON, NetCDF) (subprocesses); ``racetrace simulate`` of a set:
test_cli_simulate_set.py."""

import json
import subprocess
import sys

import pytest
import xarray as xr

CASE = "spindle-pair-db-light-preload"


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", *args], capture_output=True, text=True, timeout=600
    )


def test_check_describes_the_set():
    result = run("check", CASE)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "set:       DB of 2 bearing(s), preload force 100 N at assembly" in out
    assert "bearing 2: at 15 mm, carries thrust towards -x" in out
    assert "loads on the shaft at -60 mm: force [100, 200, 0] N" in out
    assert "axial load" not in out  # [operating] gives no load in a set case
    assert "dynamic model:" not in out  # the set's dynamic model runs it (racetrace simulate)


def test_solve_prints_each_bearing_and_writes_the_set_dataset(tmp_path):
    table = run("solve", CASE)
    assert table.returncode == 0, table.stderr
    rows = [
        line.split() for line in table.stdout.splitlines() if line.strip().startswith("bearing")
    ]
    assert [row[3] for row in rows[1:]] == ["+x", "-x"]  # the header row, then one per bearing
    assert "set stiffness at the load point: axial" in table.stdout

    path = tmp_path / "pair.nc"
    result = run("solve", CASE, "--json", "--output", str(path))
    assert result.returncode == 0, result.stderr
    summary = json.loads(result.stdout)
    loads = [b["axial_load_N"] for b in summary["bearings"]]
    assert loads[0] - loads[1] == pytest.approx(100.0, rel=1e-9)
    assert summary["output"] == str(path)
    with xr.open_dataset(path) as ds:
        assert ds.sizes["bearing"] == 2
        assert list(ds["bearing_direction"].values) == ["+x", "-x"]
        assert ds["set_stiffness"].shape == (5, 5)
