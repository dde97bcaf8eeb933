"""What each sweep of a study Dataset varies: a key no point of a sweep sets (NaN at each point) is
not a key the sweep varies, and a sweep's metrics are charted against a numeric key with at least
two finite values."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import solver
from solver.study import sweep_axis_key, sweep_varied_keys

SHIPPED = sorted((Path(__file__).resolve().parents[3] / "assets/studies/results").glob("*.nc"))
NAN = float("nan")


def study(sweeps, columns) -> xr.Dataset:
    """A study Dataset of points in ``sweeps`` with varied-key coordinates ``columns``."""
    coords = {"point": [f"p{k + 1:04d}" for k in range(len(sweeps))], "sweep": ("point", sweeps)}
    coords |= {key: ("point", np.asarray(values)) for key, values in columns.items()}
    return xr.Dataset(coords=coords, attrs={"varied_keys": json.dumps(list(columns))})


def test_a_key_no_point_of_a_sweep_sets_is_not_varied():
    ds = study(
        ["speed"] * 3 + ["tilt"] * 2,
        {
            "operating.misalignment_deg": [NAN, NAN, NAN, 0.1, 0.2],
            "operating.misalignment_frame": ["space"] * 5,
            "operating.inner_ring_speed_rpm": [5e3, 1e4, 2e4, 2e4, 2e4],
        },
    )
    assert sweep_varied_keys(ds) == {
        "speed": ["operating.inner_ring_speed_rpm"],
        "tilt": ["operating.misalignment_deg"],
    }
    assert sweep_axis_key(ds, "speed") == "operating.inner_ring_speed_rpm"
    assert sweep_axis_key(ds, "tilt") == "operating.misalignment_deg"


def test_the_chart_key_is_a_number_with_two_finite_values():
    ds = study(
        ["frame"] * 2 + ["one"] + ["partly"] * 3,
        {
            "operating.misalignment_frame": ["space", "ring", "space", "space", "space", "space"],
            "operating.misalignment_deg": [0.1, 0.1, 0.1, NAN, NAN, 0.2],
            "operating.radial_load_N": [0.0, 0.0, 0.0, 100.0, 200.0, 300.0],
        },
    )
    assert sweep_varied_keys(ds)["frame"] == ["operating.misalignment_frame"]
    assert sweep_axis_key(ds, "frame") is None  # only a text key changes
    assert sweep_varied_keys(ds)["one"] == list(json.loads(ds.attrs["varied_keys"]))
    assert sweep_axis_key(ds, "one") is None  # one point: nothing to chart against
    # misalignment changes (NaN, NaN, 0.2) but takes one finite value: load is charted
    assert sweep_axis_key(ds, "partly") == "operating.radial_load_N"
    assert sweep_axis_key(ds, "no such sweep") is None


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_sweep_of_a_shipped_study_has_a_chart_key(path):
    ds = solver.load_dataset(path)
    rows = np.asarray(ds["sweep"].values).astype(str)
    for sweep, keys in sweep_varied_keys(ds).items():
        key = sweep_axis_key(ds, sweep)
        assert key in keys, (sweep, keys)
        values = np.asarray(ds[key].values, float)[rows == sweep]
        assert np.isfinite(values).all() and np.unique(values).size == values.size, (sweep, key)


def test_the_shipped_studies_are_found():
    assert len(SHIPPED) >= 2
