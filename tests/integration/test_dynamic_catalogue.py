"""Every shipped example case runs through the dynamic model (regression guard, slow)."""

from __future__ import annotations

import numpy as np
import pytest

from solver.catalogue import catalogue, resolve_case
from solver.models.dynamic import SimulationOptions, simulate
from tests.helpers.results import dynamic_variables_in

#: Cases whose operating inputs are time histories run for a duration, not revolutions: the
#: dynamic model follows histories with tsdyn's change (issue 24 §2). A bearing-set case is solved
#: by the quasi-static set model only (the dynamic model runs one bearing and says so:
#: tests/unit/case/test_bearing_set_case.py).
CASES = [
    pytest.param(entry.name, marks=pytest.mark.skip(reason="dynamic history runs: tsdyn"))
    if entry.load().histories
    else entry.name
    for entry in catalogue().cases
    if entry.load().bearing_set is None
]


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
