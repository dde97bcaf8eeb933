"""The quasi-static model along a case's time history (solver.quasistatic_along_history and
solver.solve_quasistatic(at_time=...)): one Dataset over ``time`` whose elements are the
quasi-static solutions of the steady cases written with each time's values; and every shipped case
with a history validates and is solved along it."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver import CaseError
from solver.catalogue import catalogue, resolve_case

STEADY_RUN = {"simulation.duration_s": None, "simulation.samples_per_second": None}


def steady(case, **values):
    """``case`` written as a steady case with the given operating values (case units)."""
    changes = dict(STEADY_RUN)
    changes.update({f"operating.{k}": v for k, v in values.items()})
    out = case.with_values(changes)
    assert not out.histories
    return out


@pytest.fixture(scope="module")
def step_case():
    return resolve_case("spindle-radial-step")  # radial 0 -> 800 N at 0.02 s


@pytest.fixture(scope="module")
def along(step_case):
    return solver.quasistatic_along_history(step_case, times=[0.0, 0.01, 0.05])


def test_along_history_dataset_has_a_time_dimension(along):
    assert along.sizes["time"] == 3
    np.testing.assert_array_equal(along.time.values, [0.0, 0.01, 0.05])
    assert along.time.attrs["units"] == "s"
    # the varying input is a data variable over time; the constant ones stay scalar coordinates
    assert "radial_load" in along.data_vars and along.radial_load.dims == ("time",)
    np.testing.assert_array_equal(along.radial_load.values, [0.0, 0.0, 800.0])
    assert "axial_load" in along.coords and along.axial_load.ndim == 0
    assert along.contact_load.dims == ("time", "ball", "race")
    assert along.cage_speed.dims == ("time",)
    assert "radial_load" in along.attrs["along_history"]


def test_constant_part_equals_the_steady_solution(step_case, along):
    reference = solver.solve_quasistatic(steady(step_case, radial_load_N=0.0))
    for name in ("contact_load", "contact_angle", "cage_speed", "inner_ring_offset"):
        # t = 0 is solved from scratch like the steady case: the same numbers exactly
        np.testing.assert_array_equal(along[name].isel(time=0).values, reference[name].values)
        # t = 0.01 s, started from the solution at 0: the same equilibrium
        np.testing.assert_allclose(
            along[name].isel(time=1).values, reference[name].values, rtol=1e-9, atol=1e-12
        )


def test_solve_at_a_time_equals_the_steady_case_of_that_time(step_case, along):
    at = solver.solve_quasistatic(step_case, at_time=0.05)
    reference = solver.solve_quasistatic(steady(step_case, radial_load_N=800.0))
    assert at.attrs["history_time"] == 0.05
    assert float(at.radial_load) == 800.0
    for name in ("contact_load", "contact_angle", "cage_speed", "max_pressure"):
        np.testing.assert_array_equal(at[name].values, reference[name].values)
        np.testing.assert_allclose(
            along[name].isel(time=2).values, reference[name].values, rtol=1e-9, atol=1e-12
        )


def test_at_time_and_along_history_of_a_steady_case_are_refused():
    case = resolve_case("spindle-combined-load")
    with pytest.raises(CaseError, match="needs a case with a time history"):
        solver.solve_quasistatic(case, at_time=0.1)
    with pytest.raises(CaseError, match="needs a case with a time history"):
        solver.quasistatic_along_history(case)


def test_default_times_hold_every_knot(step_case):
    from solver.inputs import to_inputs
    from solver.models.quasistatic import ALONG_HISTORY_TIMES, along_history_times

    grid = along_history_times(to_inputs(step_case))
    assert 0.02 in grid and grid[0] == 0.0 and grid[-1] == 0.1
    assert grid.size == ALONG_HISTORY_TIMES  # 0.02 s is on the 41-point grid already
    with pytest.raises(CaseError, match="at least 2 times"):
        solver.quasistatic_along_history(step_case, times=1)


HISTORY_CASES = [e.name for e in catalogue().cases if e.load().histories]


def test_the_four_transient_cases_are_shipped():
    assert {
        "spindle-start-up",
        "spindle-radial-step",
        "spindle-unbalance",
        "spindle-load-spectrum",
    } <= set(HISTORY_CASES)
    for name in HISTORY_CASES:
        assert resolve_case(name).description, name


@pytest.mark.parametrize("name", HISTORY_CASES)
def test_shipped_history_case_is_solved_along_its_history(name):
    case = resolve_case(name)
    assert case.simulation.duration_s > 0 and case.simulation.shaft_revolutions is None
    ds = solver.quasistatic_along_history(case, times=3)
    assert ds.sizes["time"] == 3
    assert np.isfinite(ds.contact_load.values).all()
    varying = [
        n
        for n in ("inner_ring_speed", "axial_load", "radial_load", "radial_load_angle")
        if n in ds.data_vars
    ]
    assert varying, "a history case varies an input along its history"
