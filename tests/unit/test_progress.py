"""The time left of a run from its progress reports (solver.TimeLeft: the app's status line and
the command line's progress bar)."""

import math

import pytest

from solver import TimeLeft


def test_time_left_from_the_progress_rate_after_the_first_report():
    time_left = TimeLeft()
    # the first report only starts the clock (start-up and compiling are not integration)
    assert math.isnan(time_left(100.0, 0.10))
    assert math.isnan(time_left(100.5, 0.20))  # less than 1 s since the first report
    assert math.isnan(time_left(102.0, 0.102))  # less than 0.5 % of the run since it
    # 0.2 of the run in 2 s since the first report: 0.7 left takes 7 s
    assert time_left(102.0, 0.30) == pytest.approx(7.0)
    assert time_left(110.0, 1.0) == pytest.approx(0.0)


def test_probe_write_says_when_a_folder_cannot_take_a_file(tmp_path):
    from solver import probe_write

    probe_write(tmp_path, ".probe-")
    assert list(tmp_path.iterdir()) == []  # nothing left behind
    with pytest.raises(OSError):
        probe_write(tmp_path / "missing", ".probe-")
