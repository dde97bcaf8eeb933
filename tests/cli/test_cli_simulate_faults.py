"""``racetrace simulate`` loses no result: the output is checked before the run, the run length and
size are bounded before it starts, SIGTERM and SIGHUP keep the partial result like Ctrl-C (a signal
while the run starts stops it with nothing written; signals while the result is written wait for
it), and a result that cannot be written where asked goes to the temporary folder."""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
import time

import pytest

from racetrace.cli import main
from racetrace.commands import _output
from racetrace.commands import simulate as command
from solver.results.io import load_dataset
from tests.helpers.faults import read_only_folder, small_file_system
from tests.helpers.processes import signal_when

SHORT = ["--revolutions", "0.1", "--samples-per-revolution", "40", "--quiet"]


@pytest.fixture
def no_run(monkeypatch):
    """Fail the test if the model is started (the checks must come first)."""
    import solver.models.dynamic as dynamic

    def refuse(*args, **kwargs):
        raise AssertionError("the run started before the check")

    monkeypatch.setattr(dynamic, "simulate", refuse)


def _simulate(out, *extra):
    return main(["simulate", "spindle", "--output", str(out), *extra])


# ---- before the run ------------------------------------------------------------------------------
def test_missing_folder_exits_2_before_the_run(fake_case, no_run, tmp_path, capsys):
    assert _simulate(tmp_path / "missing" / "run.nc", *SHORT) == 2
    err = capsys.readouterr().err
    assert "does not exist" in err and "missing" in err and "Traceback" not in err


def test_folder_as_output_exits_2_before_the_run(fake_case, no_run, tmp_path, capsys):
    assert _simulate(tmp_path, *SHORT) == 2
    assert "is a folder: give a file name" in capsys.readouterr().err


def test_device_as_output_exits_2_and_is_left_alone(fake_case, no_run, capsys):
    assert _simulate("/dev/null", *SHORT) == 2
    assert "not a regular file" in capsys.readouterr().err
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")


def test_read_only_folder_exits_2_before_the_run(fake_case, no_run, tmp_path, capsys):
    with read_only_folder(tmp_path / "ro") as folder:
        assert _simulate(folder / "run.nc", *SHORT) == 2
        err = capsys.readouterr().err
        assert f"cannot write in folder '{folder}'" in err


@pytest.mark.parametrize(
    ("revolutions", "words"),
    [
        ("1e9", "must be at most 1000"),
        ("1e-9", "before its first output sample"),
        ("0", "must be greater than 0"),
        ("-1", "must be greater than 0"),
        ("nan", "shaft_revolutions"),
        ("inf", "shaft_revolutions"),
    ],
)
def test_revolutions_have_the_case_bounds(fake_case, no_run, tmp_path, capsys, revolutions, words):
    assert _simulate(tmp_path / "r.nc", "--revolutions", revolutions, "-q") == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err
    assert not (tmp_path / "r.nc").exists()


def test_overrides_together_are_bounded_by_the_memory_rule(fake_case, no_run, tmp_path, capsys):
    args = ["--revolutions", "1000", "--samples-per-revolution", "3600", "-q"]
    assert _simulate(tmp_path / "r.nc", *args) == 2
    assert "ball-samples a run can keep in memory" in capsys.readouterr().err


def test_a_run_larger_than_the_free_memory_is_refused(
    fake_case, no_run, tmp_path, capsys, monkeypatch
):
    monkeypatch.setattr(_output, "free_memory_bytes", lambda: 10_000)
    assert _simulate(tmp_path / "r.nc", *SHORT) == 2
    assert "of memory and 10 kB are available" in capsys.readouterr().err


def test_size_problems_compare_the_estimate_with_what_is_free(tmp_path):
    big = dict(free_memory=10_000, free_disk=10_000, file_limit=None)
    errors, warnings = _output.size_problems(20_000, 20_000, tmp_path, **big)
    assert len(errors) == 2 and not warnings
    errors, warnings = _output.size_problems(6_000, 6_000, tmp_path, **big)
    assert not errors and len(warnings) == 2
    assert _output.size_problems(1_000, 1_000, tmp_path, **big) == ([], [])
    errors, _ = _output.size_problems(1_000, 5_000, tmp_path, None, None, file_limit=4_096)
    assert any("ulimit -f" in e for e in errors)


# ---- signals (a real process) --------------------------------------------------------------------
def _start(tmp_path, *args, preexec_fn=None):
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    return subprocess.Popen(
        [sys.executable, "-m", "racetrace", "simulate", "spindle-combined-load", *args],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        preexec_fn=preexec_fn,
    )


def _wait_for_progress(process, timeout=300.0) -> bytes:
    """Read stderr until the first progress update (the run is then integrating)."""
    seen = b""
    deadline = time.monotonic() + timeout
    while b"%" not in seen:
        if time.monotonic() > deadline or process.poll() is not None:
            break
        seen += os.read(process.stderr.fileno(), 256)
    return seen


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_signals_keep_the_partial_result(tmp_path, signum):
    out = tmp_path / "run.nc"
    process = _start(tmp_path, "--output", str(out), "--revolutions", "200")
    try:
        seen = _wait_for_progress(process)
        assert b"%" in seen, seen.decode(errors="replace")
        process.send_signal(signum)
        _, rest = process.communicate(timeout=300)
    finally:
        if process.poll() is None:
            process.kill()
    err = (seen + rest).decode(errors="replace")
    assert process.returncode == 128 + signum, err
    assert f"stopped by {signal.Signals(signum).name}" in err and "Traceback" not in err
    ds = load_dataset(out)
    assert ds.attrs["complete"] == 0 and ds.attrs["stop_reason"] == "cancelled"
    assert ds.sizes["time"] > 1
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]  # no temporary file left


def test_hangup_with_the_terminal_gone_still_saves(tmp_path):
    """After a hang-up, writing to the terminal fails: the progress bar and the messages must not
    stop the command before the partial result is saved (here both pipes are closed)."""
    out = tmp_path / "run.nc"
    process = _start(tmp_path, "--output", str(out), "--revolutions", "200", "--json")
    try:
        assert b"%" in _wait_for_progress(process)
        process.stdout.close()
        process.stderr.close()
        process.send_signal(signal.SIGHUP)
        process.wait(timeout=300)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 128 + signal.SIGHUP
    assert load_dataset(out).attrs["complete"] == 0


def _handles(pid: int, signum: int) -> bool:
    """Whether process ``pid`` has installed a handler for ``signum`` (Linux: SigCgt in
    /proc/PID/status)."""
    try:
        with open(f"/proc/{pid}/status", encoding="ascii") as handle:
            for line in handle:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (signum - 1) & 1)
    except OSError:
        return False
    return False


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_while_the_run_starts_stops_it_with_nothing_written(tmp_path, signum):
    """Sent as soon as the command handles SIGTERM (it then loads the case, loads or compiles the
    model and finds the quasi-static start): the command stops at once, exits 128 + the signal
    and writes nothing."""
    process = _start(tmp_path, "--output", "run.nc", "--revolutions", "200")
    _, err = signal_when(
        process,
        lambda: _handles(process.pid, signal.SIGTERM),
        signum,
        120,
        "the command never handled SIGTERM",
        0.005,
    )
    err = err.decode(errors="replace")
    assert process.returncode == 128 + signum, err
    assert "before the run started" in err and "Traceback" not in err, err
    assert "%" not in err  # stopped before the first chunk
    assert list(tmp_path.iterdir()) == []  # nothing written, no temporary file


#: ``racetrace simulate`` in a process whose result writer first says SAVING on stderr and takes
#: two seconds, so that signals can be sent while it writes.
_SLOW_WRITER = """
import sys, time
import solver.results.io as io
original = io.atomic_write
def slow(path, write):
    def slow_write(tmp):
        sys.stderr.write("SAVING\\n")
        sys.stderr.flush()
        time.sleep(2.0)
        return write(tmp)
    return original(path, slow_write)
io.atomic_write = slow
from racetrace.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_signals_during_the_save_wait_for_the_partial_result(tmp_path):
    """Ctrl-C stops the run; a second Ctrl-C and a SIGTERM while the partial result is written
    must not lose it: they wait, and the command exits with the first signal's code."""
    process = subprocess.Popen(
        [sys.executable, "-c", _SLOW_WRITER, "simulate", "spindle-combined-load"]
        + ["--output", "run.nc", "--revolutions", "200"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    try:
        seen = _wait_for_progress(process)
        assert b"%" in seen, seen.decode(errors="replace")
        process.send_signal(signal.SIGINT)
        deadline = time.monotonic() + 120
        while b"SAVING" not in seen and process.poll() is None:
            assert time.monotonic() < deadline, seen.decode(errors="replace")
            seen += os.read(process.stderr.fileno(), 256)
        process.send_signal(signal.SIGINT)
        time.sleep(0.2)
        process.send_signal(signal.SIGTERM)
        _, rest = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
    err = (seen + rest).decode(errors="replace")
    assert process.returncode == 128 + signal.SIGINT, err
    assert "saving the result first" in err and "Traceback" not in err, err
    ds = load_dataset(tmp_path / "run.nc")
    assert ds.attrs["complete"] == 0 and ds.sizes["time"] > 1
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]  # no temporary file left


# ---- write failures ------------------------------------------------------------------------------
def test_file_size_limit_is_refused_before_the_run(tmp_path):
    def limit():
        resource.setrlimit(
            resource.RLIMIT_FSIZE, (100_000, resource.getrlimit(resource.RLIMIT_FSIZE)[1])
        )

    process = _start(tmp_path, "--output", "run.nc", *SHORT, preexec_fn=limit)
    _, err = process.communicate(timeout=300)
    err = err.decode()
    assert process.returncode == 2, err
    assert "ulimit -f" in err and "Traceback" not in err


def test_a_full_disk_after_the_run_saves_to_the_temp_folder(
    fake_case, tmp_path, capsys, monkeypatch
):
    monkeypatch.setattr(command, "size_problems", lambda *a, **k: ([], []))  # the estimate misses
    monkeypatch.setattr(_output.tempfile, "tempdir", str(tmp_path))
    with small_file_system(tmp_path / "full", size="64k") as folder:
        code = _simulate(
            folder / "run.nc", "--revolutions", "0.5", "--samples-per-revolution", "40", "-q"
        )
        err = capsys.readouterr().err
        assert list(folder.iterdir()) == []  # no partial file, no temporary file
    assert code == command.EXIT_NOT_WRITTEN, err
    (saved,) = tmp_path.glob("racetrace-run-*.nc")
    assert f"the result was saved to {saved} instead" in err and str(folder / "run.nc") in err
    assert load_dataset(saved).attrs["complete"] == 1


def _netcdf_fails_in(folder, monkeypatch):
    """Make ``folder`` and let every NetCDF write into it fail as a full disk's HDF error does."""
    import xarray as xr

    real = xr.Dataset.to_netcdf
    folder.mkdir()

    def failing(self, path, *args, **kwargs):
        if str(path).startswith(str(folder)):
            raise RuntimeError("NetCDF: HDF error")
        return real(self, path, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", failing)


def test_a_netcdf_runtime_error_names_the_file_and_falls_back(
    fake_case, tmp_path, capsys, monkeypatch
):
    monkeypatch.setattr(_output.tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    target = tmp_path / "out" / "run.nc"
    _netcdf_fails_in(target.parent, monkeypatch)
    assert _simulate(target, *SHORT) == command.EXIT_NOT_WRITTEN
    err = capsys.readouterr().err
    assert f"could not write {target}: NetCDF: HDF error" in err
    assert list(target.parent.iterdir()) == []
    (saved,) = (tmp_path / "tmp").glob("racetrace-run-*.nc")
    assert load_dataset(saved).sizes["time"] == 5


def test_nothing_writable_says_the_result_is_lost(fake_case, tmp_path, capsys, monkeypatch):
    import xarray as xr

    def failing(self, path, *args, **kwargs):
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", failing)
    monkeypatch.setattr(_output.tempfile, "tempdir", str(tmp_path))
    assert _simulate(tmp_path / "run.nc", *SHORT) == command.EXIT_NOT_WRITTEN
    err = capsys.readouterr().err
    assert "the result could not be saved" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_quasistatic_output_is_checked_first_and_falls_back(tmp_path, capsys, monkeypatch):
    assert main(["quasistatic", "spindle-combined-load", "--output", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err
    target = tmp_path / "out" / "qs.nc"
    _netcdf_fails_in(target.parent, monkeypatch)
    monkeypatch.setattr(_output.tempfile, "tempdir", str(tmp_path))
    code = main(["quasistatic", "spindle-combined-load", "--output", str(target), "--json"])
    captured = capsys.readouterr()
    assert code == 5, captured.err
    (saved,) = tmp_path.glob("racetrace-qs-*.nc")
    assert f"could not write {target}" in captured.err and str(saved) in captured.err
    import json

    assert json.loads(captured.out)["output"] == str(saved)
