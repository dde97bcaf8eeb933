"""``racetrace simulate``: output file, progress on stderr, Ctrl-C writes the partial result."""

from __future__ import annotations

import argparse
import signal

import pytest

from racetrace.commands import simulate as command
from solver.results.io import load_dataset


def _parse(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    command.register(sub)
    return parser.parse_args(argv)


def test_simulate_writes_netcdf_and_reports_progress(fake_case, tmp_path, capsys):
    out = tmp_path / "run.nc"
    args = _parse(
        [
            "simulate",
            "spindle",
            "--output",
            str(out),
            "--revolutions",
            "0.2",
            "--samples-per-revolution",
            "40",
        ]
    )
    assert args.func(args) == 0
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 1 and ds.sizes["time"] == 9
    err = capsys.readouterr().err
    assert "100.0%" in err and "ETA" in err and "t = " in err and "wrote" in err


def test_ctrl_c_writes_partial_result_and_exits_130(
    fake_case, tmp_path, capsys, ctrl_c_at_first_progress
):
    before = signal.getsignal(signal.SIGINT)  # SIG_IGN when the tests run in a background job
    out = tmp_path / "partial.nc"
    args = _parse(
        [
            "simulate",
            "spindle",
            "-o",
            str(out),
            "--revolutions",
            "1",
            "--samples-per-revolution",
            "200",
        ]
    )  # 200 samples: 4 chunks of 60
    assert args.func(args) == command.EXIT_INTERRUPTED
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 0 and ds.attrs["stop_reason"] == "cancelled"
    assert ds.sizes["time"] == 61  # t = 0 and the first chunk
    assert "partial result" in capsys.readouterr().err
    assert signal.getsignal(signal.SIGINT) is before  # the command's handler is removed again


def test_divergence_exits_4_with_partial_file(fake_case, tmp_path, capsys, monkeypatch):
    from solver.models import dynamic

    real = dynamic.SimulationOptions

    def tiny_budget(**kw):
        return real(max_steps_per_chunk=3, **kw)

    monkeypatch.setattr(dynamic, "SimulationOptions", tiny_budget)
    out = tmp_path / "bad.nc"
    args = _parse(["simulate", "spindle", "-o", str(out), "--revolutions", "0.2", "-q"])
    assert args.func(args) == command.EXIT_DIVERGED
    assert load_dataset(out).attrs["complete"] == 0
    assert "diverged" in capsys.readouterr().err


def test_simulate_prints_the_metrics_and_json_on_request(fake_case, tmp_path, capsys):
    import json

    out = tmp_path / "run.nc"
    common = ["simulate", "spindle", "--output", str(out), "--revolutions", "1.0", "--quiet"]
    args = _parse([*common, "--samples-per-revolution", "40"])
    assert args.func(args) == 0
    text = capsys.readouterr().out
    assert "inner race: excursion" in text and "band thickness" in text
    assert "settling: NOT settled" in text
    assert "energy balance: residual " in text and "% of the losses" in text
    args = _parse([*common, "--samples-per-revolution", "40", "--json"])
    assert args.func(args) == 0
    report = json.loads(capsys.readouterr().out)
    stored = load_dataset(out)
    assert report["output"] == str(out)
    trajectory = report["trajectory"]
    assert trajectory["settled"] is False and trajectory["settling_time_s"] is None
    assert trajectory["inner"]["band_thickness_deg"] > 0.1  # a band on the turning ring
    assert trajectory["inner"]["band_thickness_deg"] == pytest.approx(
        float(stored.trajectory_band_thickness.sel(race="inner", frame="inner_ring"))
    )
    assert trajectory["analysis_start_time_s"] == pytest.approx(float(stored.analysis_start_time))
    assert trajectory["energy_balance_residual"] == float(stored.energy_balance_residual)


def test_method_choices_are_the_solver_methods():
    """The command line's --method choices are the steppers' registry, in its order, looked up
    when used; the default is the solver's."""
    from solver.models.dynamic.integrate.registry import REGISTRY
    from solver.models.dynamic.options import METHODS, SimulationOptions

    assert tuple(command.METHODS) == tuple(REGISTRY) == METHODS
    assert SimulationOptions().method in command.METHODS
    assert "rosenbrock" not in command.METHODS


def test_building_the_parser_does_not_import_the_dynamic_model():
    """The --method choices are looked up when used: building the parser leaves the dynamic
    model (and its numba kernels) unimported, and a wrong method is refused with the list."""
    import subprocess
    import sys

    script = (
        "import sys\n"
        "from racetrace.cli import build_parser\n"
        "parser = build_parser()\n"
        "assert 'solver.models.dynamic' not in sys.modules, 'imported by the parser'\n"
        "parser.parse_args(['simulate', 'x', '--method', 'rosenbrock'])\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert "imported by the parser" not in done.stderr, done.stderr
    assert done.returncode == 2, done.stderr  # argparse's usage error
    assert "invalid choice: 'rosenbrock'" in done.stderr
    assert "'auto', 'dopri5', 'imex'" in done.stderr
