"""The SI inputs of a real case (solver.inputs.to_inputs), as the dynamic model reads them."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import solver
from solver.case.io import parse_case
from solver.case.schema import field
from solver.catalogue import resolve_case
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions

CASES = Path(__file__).resolve().parents[3] / "assets" / "cases"


def test_spindle_case_is_converted_to_si():
    case = resolve_case("spindle-combined-load")
    inp = to_inputs(case)
    op = inp.operating
    assert op.inner_ring_speed == pytest.approx(20000.0 * 2.0 * math.pi / 60.0, rel=1e-15)
    assert op.axial_load == 500.0 and op.radial_load == 300.0
    assert op.misalignment_axis == pytest.approx(math.pi / 2, rel=1e-15)
    assert inp.geometry.ball_count == 18
    assert inp.geometry.ball_diameter == pytest.approx(7.144e-3, rel=1e-15)
    assert inp.lubricant.given is True
    assert inp.lubricant.viscosity == case.lubricant.viscosity_Pas
    assert inp.lubricant.pressure_viscosity == pytest.approx(
        case.lubricant.pressure_viscosity_per_GPa / 1e9, rel=1e-15
    )
    assert inp.cage.pocket_clearance == pytest.approx(
        case.cage.pocket_diametral_clearance_mm / 1000.0, rel=1e-15
    )
    assert inp.cage.mass == pytest.approx(case.cage.mass_g / 1000.0, rel=1e-15)
    assert op.tilting_moment is None and op.misalignment == 0.0
    assert solver.parse_case(inp.case_text) == case


def test_case_without_lubricant_uses_the_schema_oil_and_says_so():
    text = (CASES / "218-heavy-combined.toml").read_text()
    without = text[: text.index("[lubricant]")]  # the case's last section
    inp = to_inputs(parse_case(without))
    assert inp.lubricant.given is False
    assert inp.lubricant.viscosity == field("lubricant.viscosity_Pas").default
    curve = inp.lubricant.traction
    assert (curve.mu_zero, curve.mu_max, curve.slip_at_max, curve.mu_infinity) == tuple(
        field(f"lubricant.traction.{name}").default
        for name in ("mu_zero", "mu_max", "slip_at_max_m_s", "mu_infinity")
    )
    assert "no [lubricant] in the case" in inp.lubricant.description
    assert "viscosity 0.01 Pa s" in inp.lubricant.description


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


@pytest.mark.parametrize(
    ("law", "rule", "rows"), [("slip_curve", "product", 2 * 8), ("rheology", "split", 3)]
)
def test_default_quadrature_follows_the_traction_law(law, rule, rows):
    """The product rule with two points along the rolling direction for the slip curve, the split
    rule with 3 x 3 for the rheology law (docs/numerics.md); explicit options win."""
    from dataclasses import replace

    from solver.models.dynamic.params import build_params, build_quadrature
    from solver.physics import traction as tr

    inp = to_inputs(resolve_case("spindle-combined-load"))
    inp = replace(inp, lubricant=replace(inp.lubricant, traction_model=law))
    options = SimulationOptions()
    par = build_params(inp, options)
    quad = build_quadrature(options, par)
    assert quad.shape == (rows, tr.NODE_COLUMNS if rule == "product" else tr.SPLIT_COLUMNS)
    if rule == "product":
        assert sum(quad[:, tr.NODE_LOAD]) == pytest.approx(1.0, rel=1e-12)
    else:
        assert tuple(quad[:2, tr.SPLIT_COUNTS]) == (3, 3)
    split = build_quadrature(SimulationOptions(ellipse_rule="split", quadrature=(2, 4)), par)
    assert split.shape == (4, tr.SPLIT_COLUMNS)
    assert build_quadrature(SimulationOptions(quadrature=(3, 5)), par).shape[0] == 15
