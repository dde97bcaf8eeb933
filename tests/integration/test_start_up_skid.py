"""The shipped start-up that skids (assets/cases/spindle-start-up-skid.toml: 80 N preload, VG 68
oil jets, 0 to 20 000 rpm in 0.05 s): during the ramp the cage falls behind its rolling speed and
the result warns, naming when and how much; once the speed holds the cage catches up."""

from __future__ import annotations

import re

import numpy as np
import pytest

import solver
from solver.catalogue import resolve_case
from solver.results.skidding import CAGE_SKID_THRESHOLD, skid_extent

RAMP_END = 0.05  # s, the case's ramp


@pytest.fixture(scope="module")
def run():
    return solver.simulate(resolve_case("spindle-start-up-skid"))


@pytest.mark.slow
def test_the_start_up_skids_during_the_ramp_and_warns(run):
    times = run["time"].values
    ramp = times < RAMP_END
    extent = skid_extent(run, ramp)
    # the cage lags by 6.3 % at most near the end of the ramp (skidding ratio 0.937 at 0.046 s)
    assert 0.04 < extent.peak < 0.10
    assert 0.6 * RAMP_END < extent.peak_time < RAMP_END
    assert extent.end >= 0.95 * RAMP_END and extent.share > 0.8
    slip = run.racetrace.phase_metrics()["mean_instantaneous_cage_slip"].values
    assert slip[0] > 2.5 * CAGE_SKID_THRESHOLD  # 4.0 % over the ramp
    assert slip[-1] < CAGE_SKID_THRESHOLD  # 0.64 % once the speed holds: it catches up
    (warning,) = [w for w in run.racetrace.warnings() if w.startswith("the cage skids")]
    assert "t from 0 s to 0.05 s" in warning
    quoted = re.search(
        r"lags most, ([0-9.]+) % \(skidding_ratio ([0-9.]+)\), at t = ([0-9.]+)", warning
    )
    assert float(quoted.group(1)) == pytest.approx(100.0 * extent.peak, rel=2e-3)
    assert float(quoted.group(3)) == pytest.approx(extent.peak_time, abs=1e-4)
    ratio = run["skidding_ratio"].values
    assert np.nanmin(ratio[(times > 0.02) & ramp]) < 0.95
