"""How the quasi-static bearing set's Dataset is assembled (quasistatic/set_result.py): from
the bearings' single-bearing Datasets and the set's own variables, without xarray's merge."""

from __future__ import annotations

import pytest
import xarray as xr

from solver.catalogue import resolve_case
from solver.models.quasistatic.bearing_set import bearing_datasets, set_inputs, solve_set_state
from solver.models.quasistatic.set_result import set_dataset
from tests.helpers.dataset_checks import assert_public_constructor_makes

PAIR = "spindle-pair-db-light-preload"


@pytest.fixture(scope="module")
def parts():
    """(case, state, the bearings' Datasets, the external loads, the case text) of the DB pair."""
    case = resolve_case(PAIR)
    given = set_inputs(case)
    state = solve_set_state(given)
    text = given.inputs.case_text
    datasets = bearing_datasets(state, text)
    return case, state, datasets, given.applied, text


def test_set_dataset_makes_each_variable_once(parts, monkeypatch):
    """The set's Dataset is assembled from the Variables made for it, as they are: none is copied
    or rebuilt by xarray's merge (which copied all of the about 130 variables of a pair's result,
    the dearest step of its build). So the Variables made are at most one per variable of the
    result and one more per dimension coordinate (its index's variable)."""
    case, state, datasets, applied, text = parts
    made = []
    original = xr.Variable.__init__

    def counting(self, *args, **kwargs):
        made.append(type(self).__name__)
        original(self, *args, **kwargs)

    monkeypatch.setattr(xr.Variable, "__init__", counting)
    ds = set_dataset(case.bearing_set, state, datasets, applied, text)
    monkeypatch.undo()
    assert len(made) <= len(ds.variables) + len(ds.xindexes), (len(made), len(ds.variables))


def test_set_dataset_is_the_dataset_of_xarrays_public_constructor(parts):
    """The set's Dataset is the one the public ``xr.Dataset(data_vars, coords)`` makes of the
    same variables: attributes, order, sizes and indexes included (kept in case a new xarray
    changes what its direct constructor does)."""
    case, state, datasets, applied, text = parts
    ds = set_dataset(case.bearing_set, state, datasets, applied, text)
    public = assert_public_constructor_makes(ds)
    assert {"bearing", "ball", "dof", "dof_"} <= set(ds.xindexes)
    for name in ds.xindexes:
        assert ds.xindexes[name].equals(public.xindexes[name]), name
