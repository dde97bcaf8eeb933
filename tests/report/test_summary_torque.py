"""A run report's summary table sets the model's friction torque beside the empirical estimates,
and an estimate the run does not have shows its reason, not a bare '-' or NaN."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")


def test_summary_rows_give_the_torques_and_the_reason_for_a_missing_estimate():
    from report.build import _summary_rows
    from tests.app.conftest import make_dynamic_dataset

    ds = make_dynamic_dataset()
    ds = ds.assign(
        friction_torque=("time", np.full(ds.sizes["time"], 0.25)),
        friction_torque_palmgren=((), 0.125),
    )
    ds.attrs["friction_torque_skf_note"] = "not available: no constants for this series"
    rows = {name: (inner, units) for name, inner, _, units in _summary_rows(ds)}
    assert rows["mean friction torque"] == ("0.25", "N m")
    assert rows["Palmgren friction torque estimate"] == ("0.125", "N m")
    assert rows["SKF-model friction torque estimate"][0] == (
        "not available: no constants for this series"
    )
