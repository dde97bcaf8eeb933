"""Cases with time histories on the command line: ``racetrace check`` prints each history, its
events and the run length; ``racetrace solve --at-time`` and ``--along-history`` (subprocesses)."""

import json
import subprocess
import sys


def racetrace(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_check_prints_each_history_in_engineering_units():
    result = racetrace("check", "spindle-load-spectrum")
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "axial_load_N: file spindle-load-spectrum.csv, table of 7 points (linear)" in out
    assert "0 to 900 N, 2 steps" in out
    assert "events (steps and segment ends) at 0.02 s, 0.025 s, 0.08 s, 0.12 s" in out
    assert "run:       0.15 s, 12000 samples per second" in out
    start = racetrace("check", "spindle-start-up").stdout
    assert "inner_ring_speed_rpm: smooth ramp from 0 to 20000 rpm, 0 s to 0.3 s" in start


def test_solve_at_a_time_solves_that_times_operating_point():
    result = racetrace("solve", "spindle-radial-step", "--at-time", "0.05")
    assert result.returncode == 0, result.stderr
    assert "loads:   axial 500 N, radial 800 N at 0 deg" in result.stdout
    assert "time:    t = 0.05 s along the case's history" in result.stdout
    before = json.loads(
        racetrace("solve", "spindle-radial-step", "--at-time", "0.01", "--json").stdout
    )
    after = json.loads(
        racetrace("solve", "spindle-radial-step", "--at-time", "0.05", "--json").stdout
    )
    assert before["time_s"] == 0.01 and after["time_s"] == 0.05
    # 500 N preload alone, then with 800 N radial: the largest inner contact load grows
    assert after["max_contact_load_N"]["inner"] > 2 * before["max_contact_load_N"]["inner"]


def test_solve_along_the_history_prints_one_row_per_time(tmp_path):
    output = tmp_path / "along.nc"
    result = racetrace(
        "solve", "spindle-radial-step", "--along-history", "3", "--json", "--output", str(output)
    )
    assert result.returncode == 0, result.stderr
    rows = json.loads(result.stdout)["along_history"]
    assert [row["time_s"] for row in rows] == [0.0, 0.05, 0.1]
    assert [row["radial_load_N"] for row in rows] == [0.0, 800.0, 800.0]
    import xarray as xr

    with xr.open_dataset(output) as ds:
        assert ds.sizes["time"] == 3 and ds.radial_load.dims == ("time",)
    table = racetrace("solve", "spindle-radial-step", "--along-history", "2").stdout
    assert "quasi-static solutions at 2 times from 0 s to 0.1 s" in table


def test_history_options_on_a_steady_case_are_refused():
    result = racetrace("solve", "spindle-combined-load", "--at-time", "0.1")
    assert result.returncode == 2
    assert "needs a case with a time history" in result.stderr
    result = racetrace("solve", "spindle-radial-step", "--along-history", "1")
    assert result.returncode == 2 and "at least 2 times" in result.stderr


def test_simulate_refuses_revolution_options_for_a_history_case(tmp_path):
    result = racetrace(
        "simulate", "spindle-radial-step", "--revolutions", "2", "-o", str(tmp_path / "r.nc")
    )
    assert result.returncode == 2, result.stderr
    assert "--revolutions 2: this case has a time history" in result.stderr
    assert "simulation.duration_s" in result.stderr and "Traceback" not in result.stderr
