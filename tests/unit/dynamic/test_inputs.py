"""Reading a real case (solver.case / catalogue) into the dynamic model's SI inputs."""

from __future__ import annotations

import math

import numpy as np
import pytest

import solver
from solver.catalogue import resolve_case
from solver.models.dynamic import SimulationOptions, inputs_from_case
from solver.models.dynamic.inputs import DEFAULT_OIL


def test_spindle_case_is_converted_to_si():
    case = resolve_case("spindle-combined-load")
    inp = inputs_from_case(case)
    assert inp.inner_speed == pytest.approx(20000.0 * math.pi / 30.0)
    assert inp.axial_load == 500.0 and inp.radial_load == 300.0
    assert inp.geometry.ball_count == 18
    assert inp.default_lubricant is False
    assert inp.viscosity == pytest.approx(case.lubricant.viscosity_Pas)
    assert inp.pressure_viscosity == pytest.approx(case.lubricant.pressure_viscosity_per_GPa * 1e-9)
    assert inp.pocket_clearance == pytest.approx(case.cage.pocket_diametral_clearance_mm * 1e-3)
    assert inp.cage_mass == pytest.approx(case.cage.mass_g * 1e-3)
    assert inp.tilting_moment is None and inp.misalignment == 0.0
    assert "[bearing]" in inp.case_text


def test_case_without_lubricant_uses_the_documented_default_oil():
    inp = inputs_from_case(resolve_case("218-heavy-combined"))
    assert inp.default_lubricant is True
    assert inp.viscosity == DEFAULT_OIL["viscosity"]
    assert inp.traction_curve == DEFAULT_OIL["traction"]


def test_public_api_runs_a_catalogue_case():
    ds = solver.simulate(
        resolve_case("spindle-misalignment-ring"),
        options=SimulationOptions(shaft_revolutions=0.1, samples_per_revolution=60),
    )
    assert ds.attrs["model"] == "dynamic" and ds.attrs["complete"] == 1
    assert ds.attrs["case"].startswith("title") or "[bearing]" in ds.attrs["case"]
    assert "quasi-static" in ds.attrs["initial_state"]
    # the ring-fixed misalignment is imposed: its size is the case's, its axis turns with the ring
    tilt = ds.inner_ring_tilt.transpose("time", "tilt_axis").values
    misalignment = resolve_case("spindle-misalignment-ring").operating.misalignment_deg
    np.testing.assert_allclose(np.hypot(tilt[:, 0], tilt[:, 1]), misalignment, rtol=1e-9)
    axis = np.degrees(np.unwrap(np.arctan2(tilt[:, 1], tilt[:, 0])))
    turned = math.degrees(float(ds.time[-1]) * 20000.0 * math.pi / 30.0)
    assert axis[-1] - axis[0] == pytest.approx(turned, rel=1e-6)
