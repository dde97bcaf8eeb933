"""The run report's header names the result from its attributes, not from its case text."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")


def test_the_run_header_names_the_case_and_provenance_without_the_case_text():
    import solver
    from report.build import run_header

    case = solver.catalogue().get("spindle-combined-load").load()
    ds = solver.solve_quasistatic(case).assign_attrs(case="")
    header = run_header(ds, "run.nc")
    assert f"racetrace review: {case.title}</h1>" in header
    assert f"bearing geometry: <strong>{case.bearing.provenance}</strong>" in header
