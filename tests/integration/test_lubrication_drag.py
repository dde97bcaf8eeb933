"""A dynamic run follows the lubrication method: the spindle fed by an oil jet loses more power to
drag (balls and cage) than the same spindle on oil-air, whose mixture is air in effect, and its
cage land (flooded against starved) dissipates more."""

from __future__ import annotations

import pytest

from solver.catalogue import resolve_case
from solver.models.dynamic import simulate

pytestmark = pytest.mark.slow


def _losses(lubricant: dict) -> dict:
    case = resolve_case("spindle-axial-preload").with_values(
        {
            "lubricant.oil_flow_mm3_h": None,
            "simulation.shaft_revolutions": 1.0,
            "simulation.samples_per_revolution": 60,
        }
        | lubricant
    )
    ds = simulate(case)
    late = ds["time"] >= 0.5 * float(ds["time"][-1])  # the second half of the run
    losses = ds["power_loss"].where(late, drop=True).mean("time")
    return {str(s): float(losses.sel(loss_source=s)) for s in ds["loss_source"].values}


def test_oil_jet_drags_more_than_oil_air():
    air = _losses({"lubricant.method": "oil_air", "lubricant.oil_flow_mm3_h": 60.0})
    jet = _losses({"lubricant.method": "oil_jet", "lubricant.jet_flow_l_min": 1.0})
    assert jet["drag"] > 5.0 * air["drag"] > 0.0
    assert jet["cage_drag"] > 5.0 * air["cage_drag"] > 0.0
    assert jet["cage_land"] > air["cage_land"]
