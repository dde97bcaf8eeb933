"""The run report's header names the result from its attributes and coordinates, not from its
case text: headed by its own operating point, then its case title."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")


def test_the_run_header_names_the_case_and_provenance_without_the_case_text():
    import solver
    from report.build import run_header

    case = solver.catalogue().get("spindle-combined-load").load()
    ds = solver.solve_quasistatic(case).assign_attrs(case="")
    header = run_header(ds, "run.nc")
    assert "racetrace review: 20 000 rpm, 500 N axial + 300 N radial</h1>" in header
    assert f"case: <strong>{case.title}</strong>" in header
    assert f"bearing geometry: <strong>{case.bearing.provenance}</strong>" in header
