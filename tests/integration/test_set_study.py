"""A study of a bearing set (issue 25 §3, §7): `racetrace study` over the inner-ring speed and the
preload of a DB pair keeps each bearing's axial and radial load and the set's stiffness per point
(solver/study/metrics.py, SET_STUDY_METRIC_NAMES)."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.errors import CaseError
from solver.study import Study

pytest.importorskip("distributed")

STUDY = """
title = "DB pair: speed and preload"
base = "spindle-pair-db-light-preload"
model = "quasistatic"
[[sweep]]
name = "speed"
vary."operating.inner_ring_speed_rpm" = [0.0, 24000.0]
[[sweep]]
name = "spring preload"
vary."set.preload.force_N" = [100.0, 300.0]
set."set.preload.kind" = "spring"
set."set.preload.spring_side" = "-x"
"""


def test_a_set_study_keeps_each_bearings_loads_and_the_set_stiffness(tmp_path):
    study = Study.from_text(STUDY)
    ds = study.run(tmp_path / "study", workers=1)
    assert list(ds["status"].values.ravel()) == ["done"] * 4
    assert list(ds["bearing"].values) == ["bearing 1", "bearing 2"]
    assert ds["bearing_axial_load"].dims == ("point", "model", "bearing")
    assert ds["axial_stiffness"].attrs["units"] == "N/m"
    # the points' values are those of the set solved on its own
    for point in study.points():
        alone = solver.solve(point.case)
        row = ds.sel(point=point.name, model="quasistatic")
        for name in ("bearing_axial_load", "bearing_radial_load"):
            assert np.allclose(row[name].values, alone[name].values, rtol=1e-9), name
        for name in ("axial_stiffness", "radial_stiffness", "tilt_stiffness"):
            assert float(row[name]) == pytest.approx(float(alone[name]), rel=1e-9), name
        # each bearing's stiffness: the diagonal of its own 5x5 matrix (x; mean of y, z; mean
        # of the two tilts), and its mean contact angles, as the set's result has them
        k = alone["bearing_stiffness"].values
        diagonals = {
            "bearing_axial_stiffness": k[:, 0, 0],
            "bearing_radial_stiffness": 0.5 * (k[:, 1, 1] + k[:, 2, 2]),
            "bearing_tilt_stiffness": 0.5 * (k[:, 3, 3] + k[:, 4, 4]),
        }
        for name, expected in diagonals.items():
            assert np.allclose(row[name].values, expected, rtol=1e-9), name
            assert np.allclose(alone[name].values, expected, rtol=1e-12), name
        for race in ("inner", "outer"):
            name = f"bearing_{race}_contact_angle"
            assert np.allclose(row[name].values, alone[name].values, rtol=1e-9), name
            for b in range(2):  # the mean over the bearing's loaded contacts of that race
                one = alone.isel(bearing=b)
                angle = one["contact_angle"].sel(race=race).values
                loaded = one["contact_load"].sel(race=race).values > 0
                assert float(alone[name][b]) == pytest.approx(angle[loaded].mean(), rel=1e-12)
        # the single-bearing metrics have no meaning for a set: NaN, never a number made up
        assert np.isnan(row["peak_pressure"].values).all()
    load = ds["bearing_axial_load"].sel(model="quasistatic")
    # the front bearing takes the 100 N thrust of the nose on top of what the rear one carries
    assert np.allclose(load.sel(bearing="bearing 1") - load.sel(bearing="bearing 2"), 100.0)
    # a fixed-position preload with rigid rings: the balls' centrifugal forces raise it with speed
    speed = ds["operating.inner_ring_speed_rpm"]
    rest, fast = (load.sel(bearing="bearing 2").where(speed == v, drop=True) for v in (0, 24000))
    assert float(fast[0]) > 1.5 * float(rest[0])
    # a fixed-position pair's axial stiffness is its bearings' (the shaft's axial translation
    # moves both inner rings alike); the spring's floating ring makes the set's softer
    fixed = (ds["sweep"] == "speed").values
    axial = ds["bearing_axial_stiffness"].sel(model="quasistatic").sum("bearing").values
    set_axial = ds["axial_stiffness"].sel(model="quasistatic").values
    assert np.allclose(axial[fixed], set_axial[fixed], rtol=1e-9)
    assert np.all(set_axial[~fixed] < axial[~fixed])
    # a spring preload: the rear bearing carries the spring force whatever the speed
    spring = ds["sweep"] == "spring preload"
    assert np.allclose(
        load.sel(bearing="bearing 2").where(spring, drop=True).values, [100.0, 300.0], rtol=1e-6
    )


def test_a_set_study_with_the_dynamic_model_is_refused_naming_the_point():
    with pytest.raises(CaseError) as info:
        Study.from_text(STUDY.replace('model = "quasistatic"', 'model = "dynamic"')).points()
    assert "the dynamic model cannot run it" in str(info.value)
