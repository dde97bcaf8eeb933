"""A bearing set's result as a file and as single-bearing results: ``solver.load_result`` reads the
set's file (as ``racetrace solve --output`` or ``racetrace simulate`` writes it) after checking
it, and ``solver.bearing_result`` gives each bearing as a valid single-bearing result, which the
app's views and the report read."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.errors import CaseError
from solver.results.validate import check_result

PAIR = "spindle-pair-db-light-preload"


@pytest.fixture(scope="module")
def pair():
    return solver.solve(solver.resolve_case(PAIR))


def test_each_bearing_of_a_set_is_a_valid_single_bearing_result(pair):
    for index in range(pair.sizes["bearing"]):
        one = solver.bearing_result(pair, index)
        check_result(one, f"bearing {index + 1}", values=True)  # raises when it is not
        assert int(one["ball_count"]) == one.sizes["ball"] == 18
        assert "bearing" not in one.dims and "set_stiffness" not in one
        np.testing.assert_array_equal(
            one["contact_load"].values, pair["contact_load"].values[index]
        )


def test_a_set_file_is_read_back_and_a_broken_one_is_named(pair, tmp_path):
    path = solver.save_dataset(pair, tmp_path / "pair.nc")
    again = solver.load_result(path)
    assert again.sizes["bearing"] == 2
    np.testing.assert_allclose(again["set_stiffness"].values, pair["set_stiffness"].values)
    broken = solver.save_dataset(pair.drop_vars("set_stiffness"), tmp_path / "broken.nc")
    with pytest.raises(CaseError, match="a bearing set without 'set_stiffness'"):
        solver.load_result(broken)
    no_angle = pair.drop_vars("contact_angle")
    with pytest.raises(CaseError, match="bearing 1: .*contact_angle"):
        check_result(no_angle, "pair")


def test_a_dynamic_set_file_is_read_back_without_stiffness_and_a_broken_one_is_named(tmp_path):
    from solver.models.dynamic import SimulationOptions

    options = SimulationOptions(shaft_revolutions=0.1, samples_per_revolution=40)
    run = solver.simulate(solver.resolve_case(PAIR), options=options)
    assert "set_stiffness" not in run  # a dynamic run has no stiffness matrices
    again = solver.load_result(solver.save_dataset(run, tmp_path / "run.nc"))
    assert again.sizes["bearing"] == 2 and again.sizes["time"] == run.sizes["time"]
    broken = solver.save_dataset(run.drop_vars("energy_balance_residual"), tmp_path / "b.nc")
    with pytest.raises(CaseError, match="a bearing set without 'energy_balance_residual'"):
        solver.load_result(broken)
