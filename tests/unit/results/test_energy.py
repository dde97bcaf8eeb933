"""The energy-balance residual of a dynamic result, on hand-built Datasets with known powers and
kinetic energy: its value, the metric, and the result warning just past 1 % and not below it.

Expected values are worked out here by hand: drive power 100 W + a 5 W ripple of whole periods over
the window, losses 90 W, and a kinetic energy growing at 10 W close the balance exactly; without
the growth the residual is (100 - 90) / 90.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

import solver  # noqa: F401  (registers ds.racetrace)
from solver.results.checks import result_warnings
from solver.results.energy import energy_balance

PERIOD = 0.1  # s, the ripple's period
TIMES = np.linspace(0.0, 1.0, 401)  # s; the window from 0.5 s holds five whole ripple periods
WINDOW_START = 0.5  # s


def dynamic_result(kinetic_rate: float, loss: float = 90.0, stored: bool = False) -> xr.Dataset:
    """A dynamic-shaped result of 3 balls (benign contacts) with drive power 100 W plus ripple,
    constant losses ``loss`` [W] and a kinetic energy growing at ``kinetic_rate`` [W] from 2 J,
    analysed from :data:`WINDOW_START`."""
    n = TIMES.size
    ripple = 5.0 * np.sin(2.0 * math.pi * TIMES / PERIOD)
    tc = ("ball", "race", "time")
    data = {
        "contact_load": (tc, np.full((3, 2, n), 100.0)),
        "contact_angle": (tc, np.full((3, 2, n), 10.0)),
        "ellipse_semi_major": (tc, np.full((3, 2, n), 0.5e-3)),
        "max_pressure": (tc, np.full((3, 2, n), 1.0e9)),
        "truncation_margin": (tc, np.full((3, 2, n), math.nan)),
        "drive_power": (("time",), 100.0 + ripple),
        "total_power_loss": (("time",), np.full(n, loss)),
        "kinetic_energy": (("time",), 2.0 + kinetic_rate * TIMES),
        "analysis_start_time": ((), WINDOW_START),
        "settled": ((), np.int8(1)),
    }
    ds = xr.Dataset(
        data,
        coords={"ball": [0, 1, 2], "race": ["inner", "outer"], "time": TIMES},
        attrs={"model": "dynamic", "complete": 1, "integrator": "test, tolerance 0.001"},
    )
    if stored:
        ds["energy_balance_residual"] = ((), -0.5)  # a stored value wins over a recomputation
    return ds


def test_the_balance_closes_with_the_kinetic_energy_change():
    balance = energy_balance(dynamic_result(kinetic_rate=10.0), WINDOW_START)
    assert balance.start == pytest.approx(WINDOW_START)
    assert balance.end == pytest.approx(1.0)
    assert balance.drive == pytest.approx(100.0, abs=1e-9)  # whole ripple periods
    assert balance.loss == pytest.approx(90.0)
    assert balance.kinetic_rate == pytest.approx(10.0)
    assert balance.residual == pytest.approx(0.0, abs=1e-9)


def test_the_residual_is_the_unbalanced_power_over_the_losses():
    balance = energy_balance(dynamic_result(kinetic_rate=0.0), WINDOW_START)
    assert balance.residual == pytest.approx(10.0 / 90.0)
    # only the window counts: a kinetic energy jump before it changes nothing
    ds = dynamic_result(kinetic_rate=0.0)
    ds["kinetic_energy"][:10] = 1e3
    assert energy_balance(ds, WINDOW_START).residual == pytest.approx(10.0 / 90.0)


def test_the_first_shaft_revolution_is_left_out_of_a_longer_run():
    ds = dynamic_result(kinetic_rate=10.0)
    ds["kinetic_energy"][TIMES < 0.3] = -100.0  # a start-up the balance does not hold for
    ds.attrs["shaft_period_s"] = 0.3  # 3.3 revolutions: balanced from 0.3 s (7 ripple periods)
    balance = energy_balance(ds, 0.0)
    assert balance.start == pytest.approx(0.3)
    assert balance.kinetic_rate == pytest.approx(10.0)
    assert balance.residual == pytest.approx(0.0, abs=1e-9)
    assert energy_balance(ds, WINDOW_START).start == pytest.approx(WINDOW_START)  # later: kept
    ds.attrs["shaft_period_s"] = 0.6  # fewer than two revolutions: the window as given
    assert energy_balance(ds, 0.0).start == 0.0


def test_the_metric_reads_the_stored_value_else_computes_it():
    assert float(dynamic_result(0.0).racetrace.metric("energy_balance_residual")) == (
        pytest.approx(10.0 / 90.0)
    )
    stored = dynamic_result(0.0, stored=True)
    assert float(stored.racetrace.metric("energy_balance_residual")) == -0.5


def test_no_losses_gives_nan_and_no_warning():
    ds = dynamic_result(kinetic_rate=0.0, loss=0.0)
    assert math.isnan(energy_balance(ds, WINDOW_START).residual)
    assert not [w for w in result_warnings(ds) if "energy balance" in w]


def test_a_result_without_the_kinetic_energy_has_no_balance():
    ds = dynamic_result(kinetic_rate=0.0).drop_vars("kinetic_energy")
    assert energy_balance(ds, WINDOW_START) is None
    assert math.isnan(float(ds.racetrace.metric("energy_balance_residual")))


@pytest.mark.parametrize(
    ("kinetic_rate", "warns"),
    [(10.0, False), (10.0 - 0.0099 * 90.0, False), (10.0 - 0.0101 * 90.0, True), (20.0, True)],
)
def test_the_warning_fires_beyond_one_percent_of_the_losses(kinetic_rate, warns):
    found = [w for w in result_warnings(dynamic_result(kinetic_rate)) if "energy balance" in w]
    assert bool(found) == warns
    if warns:
        (message,) = found
        assert "tolerance" in message and "shaft_revolutions" in message
        assert "drive power 100 W" in message and "losses 90 W" in message
