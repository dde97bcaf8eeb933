"""The shared results builder: describing coordinates (operating point and geometry), their NetCDF
round trip, concatenation of results along a new dimension, and reading them back."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from solver.catalogue import resolve_case
from solver.models.quasistatic import solve_quasistatic
from solver.results.dataset import (
    build_result,
    geometry_from_result,
    operating_from_result,
    result_description,
    ring_speeds,
    with_data_variables,
)
from solver.results.io import load_dataset, save_dataset
from solver.results.variables import COORDINATES
from tests.helpers.dataset_checks import assert_public_constructor_makes

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def combined():
    """The shipped combined-load case: 20 000 rpm, 500 N axial + 300 N radial at 0 deg."""
    return solve_quasistatic(resolve_case("spindle-combined-load"))


@pytest.fixture(scope="module")
def tilted():
    """The same bearing at 12 000 rpm with a radial load at 90 deg and a given tilting moment."""
    case = resolve_case("spindle-combined-load").with_values(
        {
            "operating.inner_ring_speed_rpm": 12000.0,
            "operating.radial_load_angle_deg": 90.0,
            "operating.tilting_moment_Nm": 0.5,
            "operating.moment_axis_deg": 45.0,
        }
    )
    return solve_quasistatic(case)


def test_every_coordinate_is_written_with_its_registered_units(combined):
    for name, spec in COORDINATES.items():
        assert name in combined.coords, name
        assert combined[name].dims == spec.dims, name
        assert combined[name].attrs["units"] == spec.units, name
        assert combined[name].attrs["long_name"] == spec.long_name, name


def test_coordinates_hold_the_case_values_in_si_and_degree(combined, tilted):
    """Values against the case file (mm, rpm, degree): spindle-combined-load.toml."""
    c = combined
    assert float(c.inner_ring_speed) == pytest.approx(20000.0 * RPM)
    assert float(c.outer_ring_speed) == 0.0
    assert float(c.axial_load) == 500.0 and float(c.radial_load) == 300.0
    assert float(c.radial_load_angle) == 0.0
    assert str(c.misalignment_frame.values) == "space"
    assert np.isnan(float(c.tilting_moment))  # tilt imposed (0 deg): no moment given
    assert int(c.ball_count) == 18 and c.ball_count.dtype.kind == "i"
    assert float(c.ball_diameter) == pytest.approx(7.144e-3)
    assert float(c.pitch_diameter) == pytest.approx(54.0e-3)
    assert float(c.free_contact_angle) == pytest.approx(15.0)
    np.testing.assert_allclose(c.groove_radius.values, [0.54 * 7.144e-3, 0.53 * 7.144e-3])
    np.testing.assert_allclose(c.shoulder_diameter.values, [49.1e-3, 58.9e-3])
    # groove bottom: pitch diameter -+ ball diameter, each groove deeper by the radial clearance
    # share (f - 0.5) D (1 - cos alpha0) of its race (just-touching state at alpha0 = 15 deg)
    deeper = np.array([0.04, 0.03]) * 7.144e-3 * (1 - math.cos(math.radians(15.0)))
    np.testing.assert_allclose(
        c.groove_bottom_diameter.values,
        [54.0e-3 - 7.144e-3 - 2 * deeper[0], 54.0e-3 + 7.144e-3 + 2 * deeper[1]],
        rtol=1e-12,
    )
    assert list(c.material.values) == ["silicon_nitride", "bearing_steel"]
    t = tilted
    assert float(t.inner_ring_speed) == pytest.approx(12000.0 * RPM)
    assert float(t.radial_load_angle) == pytest.approx(90.0)
    assert float(t.tilting_moment) == pytest.approx(0.5)
    assert float(t.moment_axis) == pytest.approx(45.0)


def test_netcdf_round_trip_keeps_strings_nan_and_integers(combined, tmp_path):
    back = load_dataset(save_dataset(combined, tmp_path / "qs.nc"))
    xr.testing.assert_identical(back, combined)
    assert str(back.misalignment_frame.values) == "space"
    assert np.isnan(float(back.tilting_moment))
    assert back.ball_count.dtype.kind == "i" and int(back.ball_count) == 18
    assert list(back.material.values) == ["silicon_nitride", "bearing_steel"]
    for name in COORDINATES:
        assert back[name].attrs["units"] == COORDINATES[name].units, name


def test_concat_along_case_keeps_each_elements_operating_point(combined, tilted, tmp_path):
    study = xr.concat([combined, tilted], dim="case", coords="different", compat="equals")
    np.testing.assert_allclose(study.inner_ring_speed.values, [20000.0 * RPM, 12000.0 * RPM])
    np.testing.assert_allclose(study.radial_load_angle.values, [0.0, 90.0])
    assert np.isnan(study.tilting_moment.values[0]) and study.tilting_moment.values[1] == 0.5
    assert study.inner_ring_speed.dims == ("case",)
    assert study.ball_diameter.dims == ()  # the same bearing: not stacked
    for i, alone in enumerate((combined, tilted)):
        element = study.isel(case=i)
        assert ring_speeds(element) == pytest.approx(ring_speeds(alone))
    back = load_dataset(save_dataset(study, tmp_path / "study.nc"))
    np.testing.assert_allclose(back.inner_ring_speed.values, study.inner_ring_speed.values)
    with pytest.raises(ValueError, match="several cases"):
        ring_speeds(study)


def test_geometry_is_rebuilt_from_the_coordinates(combined):
    case = resolve_case("spindle-combined-load")
    expected = case.geometry()
    got = geometry_from_result(combined.assign_attrs(case=""))  # no case text needed
    for name in (
        "ball_count",
        "ball_diameter",
        "pitch_diameter",
        "inner_conformity",
        "outer_conformity",
        "free_contact_angle",
        "inner_shoulder_diameter",
        "outer_shoulder_diameter",
        "inner_curvature_center_radius",
        "effective_modulus",
        "ball_mass",
    ):
        assert getattr(got, name) == pytest.approx(getattr(expected, name), rel=1e-12), name
    assert got.ball_material == expected.ball_material


def test_operating_point_is_rebuilt_from_the_coordinates(tilted):
    case = resolve_case("spindle-combined-load").with_values(
        {
            "operating.inner_ring_speed_rpm": 12000.0,
            "operating.radial_load_angle_deg": 90.0,
            "operating.tilting_moment_Nm": 0.5,
            "operating.moment_axis_deg": 45.0,
        }
    )
    from solver.inputs import to_inputs

    expected = to_inputs(case).operating
    got = operating_from_result(tilted.assign_attrs(case=""))
    for name, value in vars(expected).items():
        if isinstance(value, str):
            assert getattr(got, name) == value, name
        else:
            assert getattr(got, name) == pytest.approx(value, rel=1e-12, abs=1e-15), name
    imposed = operating_from_result(resolve_result_without_tilting_moment())
    assert imposed.tilting_moment is None and not imposed.tilt_is_free


def resolve_result_without_tilting_moment():
    return solve_quasistatic(resolve_case("spindle-misalignment-space"))


def test_result_names_its_title_and_provenance_without_its_case_text(combined):
    """The title, the geometry's provenance and the case's description are attributes of the
    result (the views never parse the case text); a result written before they were stored has
    them read from its case here."""
    case = resolve_case("spindle-combined-load")
    named = {
        "title": case.title,
        "bearing_provenance": case.bearing.provenance,
        "description": case.description,
    }
    assert {k: combined.attrs[k] for k in named} == named
    assert result_description(combined.assign_attrs(case="")) == named
    older = combined.copy()
    for name in named:
        del older.attrs[name]
    assert result_description(older) == named
    assert result_description(older.assign_attrs(case="[bearing")) == {}  # not TOML: unknown


def test_a_result_without_coordinates_is_refused_with_a_reason(combined):
    bare = combined.drop_vars(["inner_ring_speed", "groove_radius"])
    with pytest.raises(ValueError, match="inner_ring_speed.*run the case again"):
        ring_speeds(bare)
    with pytest.raises(ValueError, match="groove_radius"):
        geometry_from_result(bare)


def test_builder_refuses_dimensions_that_differ_from_the_registry():
    geometry = resolve_case("spindle-combined-load").geometry()
    from tests.helpers.cases import operating_point

    with pytest.raises(RuntimeError, match="contact_load"):
        build_result(
            "quasistatic",
            {"contact_load": (("ball",), np.zeros(18))},
            geometry,
            operating_point(1.0),
        )


def test_builder_gives_the_dataset_of_xarrays_public_constructor(combined):
    """The builder assembles a result from its finished Variables with xarray's own direct
    constructor (solver.results.dataset.direct_dataset): the result is the Dataset that the public
    ``xr.Dataset(data_vars, coords)`` makes of the same variables, attributes, order and indexes
    included (kept here in case a new xarray changes what the direct constructor does)."""
    public = assert_public_constructor_makes(combined)
    assert set(public.xindexes) == {"ball", *combined.xindexes}


def test_builder_still_refuses_variables_whose_sizes_differ():
    """Sizes are checked without xarray's merge too: a variable whose ball count differs from the
    geometry's is a ValueError naming the dimension."""
    geometry = resolve_case("spindle-combined-load").geometry()
    from tests.helpers.cases import operating_point

    with pytest.raises(ValueError, match="ball"):
        build_result(
            "quasistatic",
            {"contact_load": (("ball", "race"), np.zeros((geometry.ball_count + 1, 2)))},
            geometry,
            operating_point(1.0),
        )


def test_builder_makes_each_variable_once(monkeypatch):
    """A result's Variables are made once and handed to the Dataset as they are: no xarray
    Variable is copied or rebuilt on the way (each copy of the about 65 variables of a
    quasi-static result cost about 1.5 ms per Dataset), so the Variables made are one per
    variable of the result, and one more per dimension coordinate (pandas index and its
    variable)."""
    case = resolve_case("spindle-combined-load")
    solve_quasistatic(case)  # compiled and cached before counting
    made = []
    original = xr.Variable.__init__

    def counting(self, *args, **kwargs):
        made.append(type(self).__name__)
        original(self, *args, **kwargs)

    monkeypatch.setattr(xr.Variable, "__init__", counting)
    ds = solve_quasistatic(case)
    monkeypatch.undo()
    assert len(made) <= len(ds.variables) + len(ds.xindexes), made


def test_adding_data_variables_gives_what_xarrays_drop_and_assign_give(combined):
    """with_data_variables (the live chunk's inputs over time and skidding, without a merge over
    every variable) makes the Dataset that ``drop_vars(...).assign(...)`` makes: a coordinate
    replaced by a data variable of the same name, a new one added, order and indexes included."""
    balls = combined.sizes["ball"]
    added = {
        "radial_load": xr.Variable(("ball",), np.arange(balls, dtype=float), {"units": "N"}),
        "extra": xr.DataArray(np.ones((balls, 2)), dims=("ball", "race")),
    }
    ours = with_data_variables(combined, added, dropped=["radial_load"])
    theirs = combined.drop_vars(["radial_load"]).assign(added)
    xr.testing.assert_identical(ours, theirs)
    assert list(ours.variables) == list(theirs.variables)
    assert list(ours.coords) == list(theirs.coords)
    assert set(ours.xindexes) == set(theirs.xindexes)
    assert "radial_load" in ours.data_vars and "radial_load" in combined.coords
    assert_public_constructor_makes(ours)
    with pytest.raises(ValueError, match="ball"):
        with_data_variables(combined, {"extra": xr.Variable(("ball",), np.ones(balls + 1))})
