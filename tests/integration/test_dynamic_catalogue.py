"""Every shipped example case runs through the dynamic model (regression guard, slow)."""

from __future__ import annotations

import numpy as np
import pytest

from solver.catalogue import catalogue, resolve_case
from solver.models.dynamic import SimulationOptions, simulate
from tests.helpers.results import dynamic_variables_in

#: Steady cases run two revolutions; a case whose operating inputs are time histories runs for a
#: duration (``HISTORY_CASES``: its first milliseconds). A bearing-set case runs the set's
#: dynamic model (tests/integration/test_dynamic_set.py, tests/cli/test_cli_simulate_set.py),
#: not this single-bearing one.
CASES = [
    entry.name
    for entry in catalogue().cases
    if entry.load().bearing_set is None and not entry.load().histories
]
HISTORY_CASES = [entry.name for entry in catalogue().cases if entry.load().histories]


@pytest.mark.slow
@pytest.mark.parametrize("name", CASES)
def test_catalogue_case_runs_two_revolutions(name):
    ds = simulate(
        resolve_case(name),
        options=SimulationOptions(shaft_revolutions=2.0, samples_per_revolution=60),
    )
    assert ds.attrs["complete"] == 1
    for var, _spec in dynamic_variables_in(ds):
        values = ds[var].values
        if var == "truncation_margin":  # NaN where the case gives no shoulder (results-schema.md)
            continue
        if var == "settling_time":  # NaN when the run does not settle (results-schema.md)
            assert np.isnan(values) == (int(ds.settled) == 0), var
            continue
        assert np.isfinite(values).all(), var
    # the cage turns between the speeds of its two rings (epicyclic drive)
    case = resolve_case(name)
    rpm = np.pi / 30.0
    speeds = sorted(
        [
            case.operating.inner_ring_speed_rpm * rpm,
            (case.operating.outer_ring_speed_rpm or 0.0) * rpm,
        ]
    )
    cage = ds.cage_speed.isel(time=slice(ds.sizes["time"] // 2, None)).values
    assert np.all((cage > speeds[0]) & (cage < speeds[1]))


@pytest.mark.slow
@pytest.mark.parametrize("name", HISTORY_CASES)
def test_history_case_runs_and_stores_its_varying_inputs_over_time(name):
    """The start of each shipped history case runs to the end with finite outputs, and each input
    that the case varies is a data variable over ``time`` that changes: 25 ms (past the radial
    step at 20 ms and into the load spectrum's first cut), and the spindle start-up's first 5 ms
    (from rest through low speed, the entrainment floor)."""
    case = resolve_case(name)
    duration = 0.005 if "operating.inner_ring_speed_rpm" in case.histories else 0.025
    short = case.with_values({"simulation.duration_s": duration})
    ds = simulate(short)
    assert ds.attrs["complete"] == 1
    turning = np.asarray(ds["inner_ring_speed"] != ds["outer_ring_speed"])
    for var, _spec in dynamic_variables_in(ds):
        if var in ("truncation_margin", "settling_time"):
            continue
        values = ds[var].values
        if var in ("skidding_ratio", "instantaneous_cage_slip"):  # NaN while the rings are still
            values = values[np.broadcast_to(turning, values.shape)]
        assert np.isfinite(values).all(), var
    varying = {
        "operating.inner_ring_speed_rpm": "inner_ring_speed",
        "operating.outer_ring_speed_rpm": "outer_ring_speed",
        "operating.axial_load_N": "axial_load",
        "operating.radial_load_N": "radial_load",
        "operating.radial_load_angle_deg": "radial_load_angle",
    }
    for key, var in varying.items():
        if key in case.histories:
            assert var in ds.data_vars and ds[var].dims == ("time",), var
            assert np.ptp(ds[var].values) > 0.0, var
