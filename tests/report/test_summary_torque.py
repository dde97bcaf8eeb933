"""A run report's life-and-friction table sets the model's friction torque beside the empirical
estimates, and an estimate the run does not have shows its reason, not a bare '-' or NaN."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("panel")


def test_life_rows_give_the_torques_and_the_reason_for_a_missing_estimate():
    from report.build import _life_rows
    from tests.app.conftest import make_dynamic_dataset

    ds = make_dynamic_dataset()
    ds = ds.assign(
        friction_torque=("time", np.full(ds.sizes["time"], 0.25)),
        friction_torque_palmgren=((), 0.125),
    )
    ds.attrs["friction_torque_skf_note"] = "not available: no constants for this series"
    rows = dict(_life_rows(ds)[0])
    assert rows["mean friction torque"] == "250 N·mm"
    assert rows["Palmgren friction torque estimate"] == "125 N·mm"
    assert rows["SKF-model friction torque estimate"] == (
        "not available: no constants for this series"
    )
