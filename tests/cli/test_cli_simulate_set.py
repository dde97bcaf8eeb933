"""``racetrace simulate`` on a bearing-set case: the set's dynamic model runs, the result keeps
its ``bearing`` dimension, the summary is per bearing, Ctrl-C keeps what was computed, and a spring
preload runs with its floating outer ring."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import pytest

from racetrace.commands import simulate as command
from racetrace.commands.bearing_set import dynamic_set_text
from solver.results.io import load_dataset

PAIR = "spindle-pair-db-light-preload"  # 100 N preload, external load 100 N axial (+x), 200 N
SHORT = ["--revolutions", "0.5", "--samples-per-revolution", "40"]


def _parse(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    command.register(sub)
    return parser.parse_args(argv)


def test_a_db_pair_runs_and_reports_each_bearing(tmp_path, capsys):
    out = tmp_path / "pair.nc"
    args = _parse(["simulate", PAIR, "--output", str(out), *SHORT, "--json"])
    assert args.func(args) == 0
    captured = capsys.readouterr()
    assert "100.0%" in captured.err and "wrote" in captured.err  # progress, as for one bearing
    report = json.loads(captured.out)
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 1 and ds.sizes["time"] == 21
    assert list(ds["bearing_direction"].values) == ["+x", "-x"]
    assert ds["contact_load"].dims == ("bearing", "ball", "race", "time")
    assert report["output"] == str(out)
    assert "DB of 2 bearing(s)" in report["bearing_set"]
    first, second = report["bearings"]
    assert (first["name"], first["direction"]) == ("bearing 1", "+x")
    assert (second["name"], second["direction"]) == ("bearing 2", "-x")
    # the shaft carries the external axial load: the +x bearing takes it over the preload,
    # the -x bearing is relieved by it (within the shaft's inertia over half a revolution)
    assert first["axial_load_N"] - second["axial_load_N"] == pytest.approx(100.0, rel=0.05)
    assert second["axial_load_N"] > 0.0  # the preload keeps it loaded
    for bearing in (first, second):
        assert bearing["trajectory"]["inner"]["excursion_deg"] > 0.0
        assert bearing["mean_total_power_loss_W"] > 0.0
        assert bearing["cage_slip"] is not None and abs(bearing["cage_slip"]) < 0.5
        assert bearing["mean_friction_torque_N_m"] > 0.0
        assert bearing["life"]["L10r_hours"] > 0.0
        assert "L10_hours" not in bearing["life"]  # ISO 281 reads applied loads: none here
    # each bearing's loads are its own, not the set's stacked twice
    assert first["mean_total_power_loss_W"] != second["mean_total_power_loss_W"]
    assert report["energy_balance_residual"] is not None


def test_the_text_summary_names_each_bearing_and_the_set_balance(tmp_path, capsys):
    out = tmp_path / "pair.nc"
    args = _parse(["simulate", PAIR, "--output", str(out), *SHORT, "--quiet"])
    assert args.func(args) == 0
    text = capsys.readouterr().out
    assert "bearing 1 (at 0 mm, carries thrust towards +x): axial load" in text
    assert "bearing 2 (at 15 mm, carries thrust towards -x): axial load" in text
    assert text.count("inner race: excursion") == 2
    assert text.count("cage slip: ") == 2 and text.count("power loss: ") == 2
    assert text.count("L10r (ISO/TS 16281") == 2 and "L10  (ISO 281" not in text
    assert text.count("energy balance:") == 1 and "the set: energy balance" in text


def test_ctrl_c_keeps_the_sets_partial_result(tmp_path, capsys, ctrl_c_at_first_progress):
    out = tmp_path / "partial.nc"
    args = _parse(
        ["simulate", PAIR, "-o", str(out), "--revolutions", "1", "--samples-per-revolution", "80"]
    )  # 80 samples: chunks of 60
    assert args.func(args) == command.EXIT_INTERRUPTED
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 0 and ds.attrs["stop_reason"] == "cancelled"
    assert ds.sizes["time"] == 61 and ds.sizes["bearing"] == 2
    assert np.isfinite(ds["bearing_axial_load"].values).all()
    assert "partial result" in capsys.readouterr().err


def _case_file(tmp_path: Path, old: str, new: str) -> Path:
    text = (Path("assets/cases") / f"{PAIR}.toml").read_text("utf-8")
    assert old in text
    path = tmp_path / "set.toml"
    path.write_text(text.replace(old, new), "utf-8")
    return path


def test_a_spring_preload_runs_with_its_floating_outer_ring(tmp_path, capsys):
    """The shipped pair with its 100 N preload given as a spring on the -x bearing's outer ring:
    the run writes a result that reads back, with the floating ring's shift over time and the
    spring force; the -x bearing carries the spring force, the +x one the 100 N axial load too."""
    case = _case_file(tmp_path, 'kind = "force"', 'kind = "spring"\nspring_side = "-x"')
    out = tmp_path / "spring.nc"
    short = ["--revolutions", "0.1", "--samples-per-revolution", "40"]
    args = _parse(["simulate", str(case), "--output", str(out), *short, "--json"])
    assert args.func(args) == 0
    summary = json.loads(capsys.readouterr().out)
    first, second = summary["bearings"]
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 1
    assert ds["spring_shift"].dims == ("time",) and float(ds["spring_force"]) == 100.0
    # the summary gives the spring and the floating rings' shift over the analysed window
    assert summary["spring_force_N"] == 100.0
    shift = ds["spring_shift"].values
    assert shift.min() <= summary["spring_shift_m"] <= shift.max()
    assert 0.0 <= summary["spring_shift_span_m"] <= shift.max() - shift.min()
    assert dynamic_set_text(ds).count("spring preload: 100 N") == 1
    assert (first["direction"], second["direction"]) == ("+x", "-x")
    assert second["axial_load_N"] == pytest.approx(100.0, rel=0.02)
    assert first["axial_load_N"] == pytest.approx(200.0, rel=0.02)
