"""The ``ds.racetrace`` accessor: registered by ``import solver``; summary, warnings, atomic NetCDF
and the per-contact CSV table."""

from __future__ import annotations

import csv
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import solver
from solver.results.io import contact_table
from tests.helpers.faults import check_failed_write_keeps_the_old_file


@pytest.fixture(scope="module")
def qs():
    return solver.solve_quasistatic("spindle-combined-load")


def test_import_solver_registers_the_accessor_in_a_fresh_interpreter(tmp_path):
    """Only ``import solver``: a Dataset opened with xarray itself has ``.racetrace``."""
    path = tmp_path / "r.nc"
    solver.solve_quasistatic("209-radial").racetrace.save(path)
    code = (
        "import solver, xarray as xr\n"
        f"ds = xr.open_dataset({str(path)!r})\n"
        "print(type(ds.racetrace).__name__, len(ds.racetrace.summary().data_vars))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    # 7 trajectory metrics + 9 rating-life metrics
    assert out.stdout.split() == ["RacetraceAccessor", "16"]


def test_summary_and_warnings_are_the_solver_definitions(qs):
    from solver.results.checks import result_warnings
    from solver.results.summary import trajectory_summary

    xr.testing.assert_identical(qs.racetrace.summary(), trajectory_summary(qs))
    assert qs.racetrace.warnings() == result_warnings(qs) == []
    heavy = qs.copy(deep=True)
    heavy["max_pressure"][:] = 5e9
    assert any("4.2 GPa" in w for w in heavy.racetrace.warnings())


def test_summary_prefers_the_stored_metrics(qs):
    from solver.results.summary import trajectory_summary

    stored = qs.assign(trajectory_summary(qs).data_vars)
    stored["trajectory_excursion"][:] = 42.0  # a marker: the stored values are returned as they are
    assert float(stored.racetrace.summary().trajectory_excursion.max()) == 42.0


def test_save_round_trips_and_leaves_no_temporary_file_on_failure(qs, tmp_path, monkeypatch):
    target = qs.racetrace.save(tmp_path / "qs.nc")
    xr.testing.assert_identical(solver.load_dataset(target), qs)
    assert solver.load_dataset(target).racetrace.summary() is not None
    check_failed_write_keeps_the_old_file(target, lambda: qs.racetrace.save(target), monkeypatch)


def test_csv_has_one_row_per_ball_and_race_with_units_in_the_headers(qs, tmp_path):
    path = qs.racetrace.to_csv(tmp_path / "qs.csv")
    rows = list(csv.DictReader(path.open()))
    assert len(rows) == qs.sizes["ball"] * 2
    header = list(rows[0])
    assert header[:2] == ["ball", "race"]
    assert "contact_angle [degree]" in header and "contact_load [N]" in header
    assert not any(h.startswith(("inner_ring_speed", "groove_radius")) for h in header)
    row = next(r for r in rows if r["ball"] == "4" and r["race"] == "outer")
    expected = float(qs.contact_angle.sel(ball=4, race="outer"))
    assert float(row["contact_angle [degree]"]) == pytest.approx(expected, rel=1e-12)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["qs.csv"]


def test_csv_of_a_dynamic_result_has_time_first():
    times = np.array([0.0, 1e-3, 2e-3])
    ds = xr.Dataset(
        {
            "contact_load": (
                ("ball", "race", "time"),
                np.arange(12.0).reshape(2, 2, 3),
                {"units": "N"},
            )
        },
        coords={"ball": [0, 1], "race": ["inner", "outer"], "time": times},
    )
    table = contact_table(ds)
    assert list(table.columns) == ["time", "ball", "race", "contact_load [N]"]
    assert len(table) == 12
    first = table.iloc[:4]
    assert (first["time"] == 0.0).all()
    assert list(first["contact_load [N]"]) == [0.0, 3.0, 6.0, 9.0]


def test_csv_refuses_a_stack_of_results_and_a_result_without_contacts(qs, tmp_path):
    stack = xr.concat([qs, qs], dim="case")
    with pytest.raises(ValueError, match="select one element"):
        stack.racetrace.to_csv(tmp_path / "s.csv")
    with pytest.raises(ValueError, match="no per-contact variables"):
        qs[["cage_speed"]].racetrace.to_csv(tmp_path / "c.csv")
    assert list(tmp_path.iterdir()) == []


def test_case_is_the_one_the_result_was_solved_from_or_none(qs):
    case = qs.racetrace.case()
    assert case is not None and case.to_toml() == qs.attrs["case"]
    assert qs.racetrace.case() is case  # parsed once
    assert qs.copy().assign_attrs(case="").racetrace.case() is None
    broken = qs.copy().assign_attrs(case="[bearing]\nball_count = 'many'\n")
    assert broken.racetrace.case() is None
