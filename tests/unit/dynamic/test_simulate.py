"""simulate(): Dataset contract (results-schema.md), progress, cancellation and divergence."""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.errors import CaseError, SimulationDiverged
from solver.models.dynamic import SimulationOptions, simulate
from solver.results.io import load_dataset, save_dataset
from solver.results.variables import VARIABLES
from tests.helpers.cases import spindle_inputs
from tests.helpers.results import dynamic_variables_in

SHORT = dict(shaft_revolutions=0.3, samples_per_revolution=40)


@pytest.fixture(scope="module")
def short_run():
    calls = []
    ds = simulate(
        spindle_inputs(radial=300.0),
        progress=lambda *a: calls.append(a),
        options=SimulationOptions(chunk_samples=4, **SHORT),
    )
    return ds, calls


def test_dataset_has_every_dynamic_variable_with_registry_dims_and_no_nan(short_run):
    ds, _ = short_run
    for name, spec in dynamic_variables_in(ds):
        assert ds[name].dims == spec.dims_for("dynamic"), name
        assert ds[name].attrs["units"] == spec.units
        if name == "settling_time":  # 0.3 revolutions cannot settle: NaN by the schema
            assert np.isnan(ds[name].values), name
            continue
        assert np.isfinite(ds[name].values).all(), name  # the test bearing gives both shoulders
    assert ds.attrs["model"] == "dynamic" and ds.attrs["complete"] == 1
    assert ds.attrs["stop_reason"] == "finished"
    assert "along -z" in ds.attrs["gravity"]
    assert "default oil" in ds.attrs["lubricant"]
    assert "skipped" in ds["trajectory_band_width"].attrs["analysed_window"]
    assert int(ds.settled) == 0
    assert any(w.startswith("run too short to settle") for w in ds.racetrace.warnings())


def test_dataset_describes_its_operating_point_and_geometry(short_run):
    """The coordinates hold the inputs (tests.helpers.cases.spindle_inputs: 20 000 rpm,
    500 N axial, 300 N radial, shoulders 49 and 59 mm), not a case text (these have none)."""
    from solver.results.variables import COORDINATES

    ds, _ = short_run
    assert ds.attrs["case"] == ""
    for name in COORDINATES:
        assert name in ds.coords, name
    assert float(ds.inner_ring_speed) == pytest.approx(20000 * math.pi / 30)
    assert float(ds.radial_load) == 300.0 and float(ds.axial_load) == 500.0
    assert np.isnan(float(ds.tilting_moment))
    np.testing.assert_allclose(ds.shoulder_diameter.values, [49.0e-3, 59.0e-3])
    assert int(ds.ball_count) == ds.sizes["ball"] == 18
    assert list(ds.frame.values) == ["inner_ring", "outer_ring"]


def test_time_axis_and_physical_ranges(short_run):
    ds, _ = short_run
    period = 2 * math.pi / (20000 * math.pi / 30)
    np.testing.assert_allclose(np.diff(ds.time.values), period / 40, rtol=1e-12)
    assert ds.sizes["time"] == 13  # t = 0 plus 0.3 rev x 40 samples
    assert ((ds.raceway_azimuth >= 0) & (ds.raceway_azimuth < 360)).all()
    assert (ds.contact_load >= 0).all()
    q = np.linalg.norm(
        ds.ball_orientation.values, axis=ds.ball_orientation.dims.index("quaternion")
    )
    np.testing.assert_allclose(q, 1.0, atol=1e-12)
    # the outer raceway does not turn: its contact azimuth equals the ball azimuth (to the small
    # out-of-plane offset of the contact); the inner one is measured on the turning ring
    outer = ds.raceway_azimuth.sel(race="outer")
    diff = (outer - ds.ball_azimuth + 180) % 360 - 180
    assert float(abs(diff).max()) < 0.5
    inner = ds.raceway_azimuth.sel(race="inner").isel(time=-1)
    ring_turn = math.degrees(ds.time.values[-1] * 20000 * math.pi / 30) % 360
    expected = (ds.ball_azimuth.isel(time=-1) - ring_turn) % 360
    assert float(abs((inner - expected + 180) % 360 - 180).max()) < 0.5


def test_progress_reports_increasing_fractions(short_run):
    _, calls = short_run
    fractions = [c[0] for c in calls]
    assert fractions == sorted(fractions) and fractions[-1] == pytest.approx(1.0)
    assert len(calls) == 3  # 12 samples in chunks of 4
    assert all(isinstance(c[2], str) for c in calls)


def test_cancel_returns_partial_result():
    state = {"n": 0}

    def cancel():
        state["n"] += 1
        return state["n"] > 2  # cancel before the third chunk

    ds = simulate(
        spindle_inputs(radial=300.0),
        cancel=cancel,
        options=SimulationOptions(chunk_samples=3, **SHORT),
    )
    assert ds.attrs["complete"] == 0 and ds.attrs["stop_reason"] == "cancelled"
    assert ds.sizes["time"] == 7
    assert np.isfinite(ds.contact_load.values).all()


def test_divergence_raises_with_partial_dataset_and_cause():
    with pytest.raises(SimulationDiverged, match="step budget") as info:
        simulate(spindle_inputs(), options=SimulationOptions(max_steps_per_chunk=5, **SHORT))
    ds = info.value.dataset
    assert ds.attrs["complete"] == 0
    assert ds.sizes["time"] >= 1
    assert "step budget" in ds.attrs["stop_reason"]


def test_netcdf_round_trip(short_run, tmp_path):
    ds, _ = short_run
    path = save_dataset(ds, tmp_path / "run.nc")
    back = load_dataset(path)
    np.testing.assert_allclose(back.contact_angle.values, ds.contact_angle.values)
    assert back.attrs["complete"] == 1


def test_first_sample_reproduces_the_quasistatic_dataset():
    """At t = 0 the run sits at the project's quasi-static solution, so its outputs must equal the
    quasi-static Dataset (solver.models.quasistatic.result, written independently of this model's
    output code) for every geometric and kinematic variable both define."""
    from solver.models.dynamic.initial import quasistatic_solution
    from solver.models.quasistatic.result import solution_to_dataset

    inp = spindle_inputs(radial=300.0)
    qs = solution_to_dataset(quasistatic_solution(inp), inp.geometry, None, None)
    ds = simulate(inp, options=SimulationOptions(shaft_revolutions=0.05, samples_per_revolution=60))
    first = ds.isel(time=0)
    for name, atol in (
        ("contact_angle", 1e-4),  # degree
        # N (loads 60-140 N): the quasi-static ring geometry is linear in the ring offset, the
        # dynamic one exact; the second-order difference (offset^2 / radius) is ~2e-4 of the load
        ("contact_load", 0.05),
        ("ball_latitude", 1e-4),
        ("raceway_azimuth", 2e-3),  # the offset inner ring: azimuth of P about the ring centre
        ("spin_to_roll", 1e-5),
        ("orbital_speed", 1e-6),
        ("ball_azimuth", 1e-9),
        ("attitude_angle", 1e-9),
        # m: identical at psi = 0; on the offset inner ring the two codes differ by <= 0.2 um
        ("raceway_contact_point", 5e-7),
        ("ellipse_semi_major", 1e-7),  # m (a ~ 0.8 mm; follows the load difference above)
        ("max_pressure", 5e5),  # Pa (p_max ~ 2 GPa)
    ):
        a, b = xr_align(first[name], qs[name])
        diff = a - b
        if name in ("raceway_azimuth",):
            diff = (diff + 180.0) % 360.0 - 180.0
        assert float(np.abs(diff).max()) < atol, name
    lon = (first.ball_longitude - qs.ball_longitude + 180.0) % 360.0 - 180.0
    # the offset inner ring tilts the inner normal out of the ball's meridian plane by ~offset /
    # radius (0.003 deg here), which the exact dynamic geometry keeps
    assert float(np.abs(lon).max()) < 1e-2


def test_dynamic_result_carries_its_quasistatic_start(short_run):
    """The run stores the quasi-static solution it started from (quasistatic_* variables, the
    values a quasi-static Dataset holds); solver.quasistatic_start serves them under the
    quasi-static names, and derives them from the coordinates for a result without them."""
    from solver import quasistatic_start
    from solver.models.dynamic.initial import quasistatic_solution

    ds, _ = short_run
    qs = quasistatic_solution(spindle_inputs(radial=300.0))
    np.testing.assert_array_equal(ds.quasistatic_ball_azimuth, np.degrees(qs.ball_azimuth))
    np.testing.assert_array_equal(ds.quasistatic_contact_angle, np.degrees(qs.contact_angle))
    np.testing.assert_array_equal(ds.quasistatic_contact_load, qs.contact_load)
    assert float(ds.quasistatic_cage_speed) == qs.cage_speed
    start = quasistatic_start(ds)
    assert set(start.data_vars) == {"ball_azimuth", "contact_angle", "contact_load", "cage_speed"}
    np.testing.assert_array_equal(start.contact_angle, ds.quasistatic_contact_angle)
    older = ds.drop_vars([name for name in ds.data_vars if name.startswith("quasistatic_")])
    older.attrs["case"] = "not a case: never read"
    derived = quasistatic_start(older)
    for name in start.data_vars:
        np.testing.assert_allclose(derived[name], start[name], rtol=1e-9, atol=1e-9)
        assert derived[name].attrs["units"] == VARIABLES[name].units


def xr_align(a, b):
    return a.transpose(*b.dims).values, b.values


def test_simulation_keys_of_a_case_set_the_switches_and_options_override_them():
    from solver.catalogue import resolve_case
    from solver.inputs import to_inputs

    case = resolve_case("spindle-combined-load").with_values(
        {"simulation.ball_race_traction": False, "simulation.gravity_m_s2": 0.0}
    )
    sim = to_inputs(case).simulation
    assert sim.traction is False and sim.gravity == 0.0
    resolved = SimulationOptions().resolved(sim)
    assert resolved.traction is False and resolved.gravity == 0.0
    assert resolved.tolerance == sim.tolerance == 1e-4  # not given: the schema default
    overridden = SimulationOptions(traction=True, tolerance=1e-3).resolved(sim)
    assert overridden.traction is True and overridden.tolerance == 1e-3
    assert overridden.gravity == 0.0


def test_options_are_checked_against_the_case_key_bounds():
    with pytest.raises(CaseError) as info:
        SimulationOptions(tolerance=0.1, damping_ratio=-1.0).validated()
    text = str(info.value)
    assert "simulation option tolerance = 0.1: must be at most 0.01" in text
    assert "simulation option damping_ratio = -1: must be at least 0" in text


def test_unknown_ellipse_rule_is_refused():
    with pytest.raises(CaseError) as info:
        SimulationOptions(ellipse_rule="gauss").validated()
    assert "simulation option ellipse_rule = 'gauss': must be one of 'product', 'split'" in str(
        info.value
    )
    assert SimulationOptions(ellipse_rule="split").validated().ellipse_rule == "split"


def test_equal_ring_speeds_are_refused_by_the_validator_rule():
    from solver.case import dynamic_problems
    from solver.catalogue import resolve_case

    case = resolve_case("spindle-combined-load").with_values(
        {"operating.outer_ring_speed_rpm": 20000.0}
    )
    with pytest.raises(CaseError) as info:
        simulate(case)
    assert info.value.problems == dynamic_problems(case)
    assert info.value.for_key("operating.outer_ring_speed_rpm")
