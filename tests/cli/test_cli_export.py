"""``racetrace export RESULT.nc --csv OUT.csv`` and the trajectory metrics printed by
``racetrace quasistatic`` (subprocesses)."""

import csv
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest


def racetrace(*args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", *args], capture_output=True, text=True, timeout=300
    )


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    path = tmp_path_factory.mktemp("export") / "qs.nc"
    out = racetrace("quasistatic", "spindle-combined-load", "--output", str(path))
    assert out.returncode == 0, out.stderr
    return path, out.stdout


def test_export_writes_the_per_contact_table(result, tmp_path):
    path, _ = result
    target = tmp_path / "contacts.csv"
    out = racetrace("export", str(path), "--csv", str(target))
    assert out.returncode == 0, out.stderr
    rows = list(csv.DictReader(target.open()))
    assert len(rows) == 18 * 2
    assert {"ball", "race", "contact_angle [degree]", "max_pressure [Pa]"} <= set(rows[0])
    assert f"wrote {target}" in out.stderr


@pytest.mark.parametrize(
    "args, words",
    [
        (["--csv", "{tmp}/x.csv"], ["no such results file"]),
        (["{result}"], ["--csv OUT.csv", "use the app"]),
        (["{result}", "--csv", "{tmp}/missing/x.csv"], ["does not exist"]),
        (["{junk}", "--csv", "{tmp}/x.csv"], ["not a readable results NetCDF file"]),
        (["{truncated}", "--csv", "{tmp}/x.csv"], ["not a readable results NetCDF file"]),
        (["{result}", "--csv", "{tmp}"], ["is a folder"]),
        (["{result}", "--csv", "/dev/null"], ["not a regular file"]),
    ],
)
def test_export_refuses_bad_input_with_exit_2(result, tmp_path, args, words):
    junk = tmp_path / "junk.nc"
    junk.write_text("not netcdf")
    truncated = tmp_path / "truncated.nc"
    truncated.write_bytes(Path(result[0]).read_bytes()[:2000])
    names = {"tmp": tmp_path, "result": result[0], "junk": junk, "truncated": truncated}
    given = [a.format(**names) for a in args]
    if given[0].startswith("--"):
        given.insert(0, str(tmp_path / "absent.nc"))
    out = racetrace("export", *given)
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    for word in words:
        assert word in out.stderr
    assert not (tmp_path / "x.csv").exists()


def test_quasistatic_prints_the_trajectory_metrics(result):
    _, stdout = result
    lines = [line for line in stdout.splitlines() if "race: excursion" in line]
    assert len(lines) == 2
    assert "deg" in lines[0] and "um" in lines[0]
    # a load fixed in space: the inner track a band, the outer a line, in steady running
    assert "band thickness n/a" not in stdout
    assert re.search(r"inner race: excursion 0\.0000 deg .*band thickness 0\.9\d+ deg", lines[0])
    assert re.search(r"outer race: excursion 1\.\d+ deg .*band thickness 0\.00\d+ deg", lines[1])
    assert "analysed: steady running" in stdout


def _refuse(constant):
    raise AssertionError(f"{constant} is not JSON")


def test_quasistatic_json_includes_the_metrics():
    out = racetrace("quasistatic", "spindle-combined-load", "--json")
    assert out.returncode == 0, out.stderr
    trajectory = json.loads(out.stdout, parse_constant=_refuse)["trajectory"]
    assert trajectory["outer"]["excursion_deg"] > 0.5
    inner = trajectory["inner"]
    assert inner["band_thickness_deg"] == pytest.approx(inner["band_width_deg"], rel=0.03)
    assert "band_thickness_note" not in trajectory
    assert "steady running" in trajectory["analysed_window"]
    assert trajectory["outer"]["excursion_m"] == pytest.approx(
        trajectory["outer"]["excursion_deg"] * 3.14159265 / 180 * 0.53 * 7.144e-3, rel=1e-6
    )
