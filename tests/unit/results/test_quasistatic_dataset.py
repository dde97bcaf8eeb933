"""The quasi-static Dataset: schema completeness, units, NaN-free values, and geometric consistency
checked against independent references (exact Hertz, groove geometry, Kingsbury latitudes)."""

import math
import warnings

import numpy as np
import pytest

from solver.case import parse_case
from solver.models.quasistatic import quasistatic_speed_sweep, solve_quasistatic
from solver.physics.hertz import race_contact
from tests.helpers import cases

SCHEMA_QS = {
    "contact_load": "N",
    "contact_angle": "degree",
    "contact_deflection": "m",
    "ellipse_semi_major": "m",
    "ellipse_semi_minor": "m",
    "max_pressure": "Pa",
    "raceway_azimuth": "degree",
    "raceway_contact_point": "m",
    "ball_latitude": "degree",
    "ball_longitude": "degree",
    "spin_to_roll": "1",
    "sliding_speed": "m/s",
    "truncation_margin": "degree",
    "ball_azimuth": "degree",
    "orbital_speed": "rad/s",
    "ball_center": "m",
    "ball_angular_velocity": "rad/s",
    "attitude_angle": "degree",
    "centrifugal_force": "N",
    "gyroscopic_moment": "N m",
    "inner_ring_offset": "m",
    "inner_ring_tilt": "degree",
    "cage_speed": "rad/s",
}


@pytest.fixture(scope="module")
def spindle_case():
    return parse_case(cases.SPINDLE)


@pytest.fixture(scope="module")
def spindle_ds(spindle_case):
    return solve_quasistatic(spindle_case)


def test_schema_variables_units_and_attributes(spindle_ds, spindle_case):
    ds = spindle_ds
    for name, units in SCHEMA_QS.items():
        assert name in ds, name
        assert ds[name].attrs["units"] == units, name
        assert ds[name].attrs["long_name"]
    assert list(ds.race.values) == ["inner", "outer"]
    assert list(ds.axis.values) == ["x", "y", "z"]
    assert list(ds.tilt_axis.values) == ["y", "z"]
    assert ds.contact_load.dims == ("ball", "race")
    assert ds.raceway_contact_point.dims == ("ball", "race", "axis")
    # the catalogue default takes the ball speeds from the traction balance
    assert ds.attrs["kinematics"] == "traction"
    assert set(ds.race_control.values) == {"traction"}
    assert "film_thickness" not in ds  # no lubricant in the case
    assert ds.attrs["model"] == "quasistatic" and ds.attrs["complete"] == 1
    assert ds.attrs["software"].startswith("racetrace ")
    assert parse_case(ds.attrs["case"]) == spindle_case
    from datetime import datetime

    datetime.fromisoformat(ds.attrs["created"])
    for name in ds.data_vars:
        if ds[name].dtype.kind == "f":
            assert np.all(np.isfinite(ds[name].values)), name


def test_hertz_results_match_the_exact_solution(spindle_ds, spindle_case):
    ds = spindle_ds
    geometry = spindle_case.geometry()
    for k, race in enumerate(("inner", "outer")):
        alpha = np.radians(ds.contact_angle.values[:, k])
        exact = race_contact(geometry, alpha, ds.contact_load.values[:, k], race)
        np.testing.assert_allclose(ds.ellipse_semi_major.values[:, k], exact.semi_major, rtol=1e-8)
        np.testing.assert_allclose(ds.ellipse_semi_minor.values[:, k], exact.semi_minor, rtol=1e-8)
        np.testing.assert_allclose(ds.max_pressure.values[:, k], exact.max_pressure, rtol=1e-8)
        np.testing.assert_allclose(ds.contact_deflection.values[:, k], exact.approach, rtol=1e-7)


def test_contact_points_lie_on_the_grooves(spindle_ds, spindle_case):
    """Outer point at r_o + delta/2 from the outer groove centre; inner point (ring frame) at
    r_i + delta/2 from the inner groove centre of the undisplaced ring; azimuths agree."""
    ds = spindle_ds
    g = spindle_case.geometry()
    p = ds.raceway_contact_point.values
    delta = ds.contact_deflection.values
    psi = np.radians(ds.ball_azimuth.values)
    for k, (xc, rc, r) in enumerate(
        (
            (
                g.inner_curvature_center_axial,
                g.inner_curvature_center_radius,
                g.inner_groove_radius,
            ),
            (
                g.outer_curvature_center_axial,
                g.outer_curvature_center_radius,
                g.outer_groove_radius,
            ),
        )
    ):
        radial = np.hypot(p[:, k, 1], p[:, k, 2])
        dist = np.hypot(p[:, k, 0] - xc, radial - rc)
        np.testing.assert_allclose(dist, r + 0.5 * delta[:, k], rtol=0, atol=2e-9)
    np.testing.assert_allclose(ds.raceway_azimuth.values[:, 1], np.degrees(psi) % 360, atol=1e-9)
    assert np.all((ds.raceway_azimuth.values >= 0) & (ds.raceway_azimuth.values < 360))
    # the outer contact sits on the +x side of the ball centre, the inner one on the -x side
    assert np.all(p[:, 1, 0] > ds.ball_center.values[:, 0])
    assert np.all(p[:, 0, 0] < ds.ball_center.values[:, 0] + ds.inner_ring_offset.values[0])


def test_kingsbury_latitudes_and_outer_control_spin(spindle_case, spindle_ds):
    race = spindle_case.with_values({"simulation.quasistatic_ball_speeds": "race_control"})
    ds = solve_quasistatic(race)
    beta = ds.attitude_angle.values
    np.testing.assert_allclose(
        ds.ball_latitude.values[:, 1], ds.contact_angle.values[:, 1] - beta, atol=1e-9
    )
    np.testing.assert_allclose(
        ds.ball_latitude.values[:, 0], -(ds.contact_angle.values[:, 0] - beta), atol=1e-9
    )
    outer = ds.race_control.values == "outer"
    assert outer.any()
    np.testing.assert_allclose(ds.spin_to_roll.values[outer, 1], 0.0, atol=1e-12)
    assert np.all(np.abs(ds.spin_to_roll.values[outer, 0]) > 1e-3)
    np.testing.assert_allclose(ds.sliding_speed.values, 0.0)
    # the traction balance (the default) spins the ball at both contacts, with the signs of the
    # dynamic model's steady means (0.07 inner, -0.047 outer, results-schema.md)
    assert np.all(spindle_ds.spin_to_roll.values[:, 0] > 0.02)
    assert np.all(spindle_ds.spin_to_roll.values[:, 1] < -0.02)


def test_film_thickness_is_zero_at_open_contacts():
    ds = solve_quasistatic(parse_case(cases.DEEP_GROOVE_RADIAL + cases.LUBRICANT))
    open_inner = ds.contact_load.values[:, 0] == 0.0
    assert open_inner.any()
    assert np.all(ds.film_thickness.values[open_inner, 0] == 0.0)
    assert np.all(ds.film_thickness.values[~open_inner, 0] > 0.0)


def test_film_thickness_only_with_a_lubricant():
    ds = solve_quasistatic(parse_case(cases.SPINDLE + cases.LUBRICANT))
    h = ds.film_thickness.values
    assert ds.film_thickness.attrs["units"] == "m"
    assert np.all(np.isfinite(h)) and np.all(h > 1e-8) and np.all(h < 1e-5)


def test_unloaded_balls_in_the_dataset_are_zero_not_nan():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = solve_quasistatic(parse_case(cases.DEEP_GROOVE_RADIAL))
    open_inner = ds.contact_load.values[:, 0] == 0.0
    assert open_inner.sum() >= 3
    for name in ("ellipse_semi_major", "ellipse_semi_minor", "max_pressure", "contact_deflection"):
        assert np.all(ds[name].values[open_inner, 0] == 0.0), name
    for name in ds.data_vars:
        if ds[name].dtype.kind == "f" and name != "truncation_margin":
            assert np.all(np.isfinite(ds[name].values)), name
    assert np.all(np.isnan(ds.truncation_margin.values))  # no shoulders given: NaN by the schema


def test_speed_sweep_stacks_on_the_inner_ring_speed(spindle_case):
    speeds = [0.0, 10000.0, 20000.0, 30000.0]
    ds = quasistatic_speed_sweep(spindle_case, speeds)
    assert ds.contact_load.dims == ("inner_ring_speed", "ball", "race")
    np.testing.assert_allclose(ds.inner_ring_speed.values, np.array(speeds) * math.pi / 30)
    alone = solve_quasistatic(spindle_case)  # 20 000 rpm
    np.testing.assert_allclose(
        ds.contact_load.isel(inner_ring_speed=2).values, alone.contact_load.values, rtol=1e-7
    )
    assert ds.ball_center.dims == ("inner_ring_speed", "ball", "axis")
    assert float(ds.axial_load) == float(alone.axial_load)  # the same in every element


def test_speed_sweep_elements_each_report_their_own_speed():
    """On the 20 000 rpm shipped case, a sweep over 5000 and 10 000 rpm: nothing in element 0
    claims another speed than 5000 rpm."""
    from solver.catalogue import resolve_case

    case = resolve_case("spindle-combined-load")
    assert case.operating.inner_ring_speed_rpm == 20000.0
    ds = quasistatic_speed_sweep(case, [5000.0, 10000.0])
    rpm = ds.inner_ring_speed.values * 30 / math.pi
    np.testing.assert_allclose(rpm, [5000.0, 10000.0])
    first = ds.isel(inner_ring_speed=0)
    assert float(first.inner_ring_speed) * 30 / math.pi == pytest.approx(5000.0)
    # no per-element attribute left that would give one element's solver statistics to all
    assert "solver_iterations" not in ds.attrs and "solver_residual" not in ds.attrs
    assert not any("speed" in key for key in ds.attrs)
    # the provenance text says that the speed varies and lists the swept speeds
    assert ds.attrs["case"].startswith("# speed sweep: operating.inner_ring_speed_rpm varies")
    assert "5000, 10000 rpm" in ds.attrs["case"].splitlines()[0]
    # the cage turns slower at 5000 rpm: each element holds its own solution
    assert float(first.cage_speed) < float(ds.cage_speed.isel(inner_ring_speed=1))
    alone = solve_quasistatic(case.with_values({"operating.inner_ring_speed_rpm": 5000.0}))
    np.testing.assert_allclose(first.contact_load.values, alone.contact_load.values, rtol=1e-6)
    with pytest.raises(ValueError, match="repeat"):
        quasistatic_speed_sweep(case, [5000.0, 5000.0])


def test_public_door_resolves_a_catalogue_name_the_model_does_not():
    import solver
    from solver.catalogue import resolve_case

    by_name = solver.solve_quasistatic("209-radial")
    by_case = solve_quasistatic(resolve_case("209-radial"))
    np.testing.assert_array_equal(by_name.contact_load.values, by_case.contact_load.values)
    with pytest.raises(TypeError, match="solver.solve_quasistatic resolves"):
        solve_quasistatic("209-radial")
