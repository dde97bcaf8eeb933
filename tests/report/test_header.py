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


def test_the_run_header_shows_the_case_description_from_the_result():
    import solver
    from report.build import run_header

    case = solver.catalogue().get("spindle-combined-load").load()
    note = "Known: the cage runs 4 % below race control's speed <at 20 000 rpm>."
    described = case.with_values({"description": note})
    ds = solver.solve_quasistatic(described)
    assert ds.attrs["description"] == note
    header = run_header(ds.assign_attrs(case=""), "run.nc")
    escaped = "Known: the cage runs 4 % below race control&#x27;s speed &lt;at 20 000 rpm&gt;."
    assert f'<p class="rt-case-note">{escaped}</p>' in header
    plain = run_header(solver.solve_quasistatic(case).assign_attrs(case=""), "run.nc")
    assert "rt-case-note" not in plain
