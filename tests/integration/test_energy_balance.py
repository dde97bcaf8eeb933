"""Every dynamic result checks its energy balance (solver/results/energy.py): a short run at the
default settings closes it within 1 % and says so; a deliberately loose run warns."""

from __future__ import annotations

import math

from racetrace.metrics import metrics_text
from solver import SimulationOptions, result_warnings, simulate


def _energy_warnings(ds) -> list[str]:
    return [w for w in result_warnings(ds) if "energy balance" in w]


def test_short_default_run_carries_a_closed_energy_balance():
    ds = simulate("spindle-combined-load", options=SimulationOptions(shaft_revolutions=2.0))
    residual = float(ds["energy_balance_residual"])
    assert math.isfinite(residual) and abs(residual) <= 0.01, residual
    assert ds["kinetic_energy"].dims == ("time",) and bool((ds["kinetic_energy"] > 0.0).all())
    assert float(ds.racetrace.metric("energy_balance_residual")) == residual
    assert not _energy_warnings(ds)
    assert f"energy balance: residual {100.0 * residual:+.2f} % of the losses" in metrics_text(ds)


def test_loose_run_raises_the_energy_warning():
    # the 209's step sits at a stability limit: a loose tolerance dissipates energy numerically,
    # which the drive power supplies (docs/numerics.md, "Default tolerance")
    ds = simulate("209-radial", options=SimulationOptions(shaft_revolutions=2.0, tolerance=1e-2))
    assert float(ds["energy_balance_residual"]) > 0.01
    (message,) = _energy_warnings(ds)
    assert "Tighten [simulation] tolerance" in message and "tolerance 0.01" in message
