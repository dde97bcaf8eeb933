"""The report of a bearing set's result (the shipped DB pair solved by ``racetrace solve``): the
set (arrangement, positions, directions), the load sharing and the stiffness of every bearing and
of the set, each 5 x 5 matrix as a table with its units, every value read from the result."""

from __future__ import annotations

import html
import re

import numpy as np
import pytest

pytest.importorskip("panel")

PAIR = "spindle-pair-db-light-preload"


@pytest.fixture(scope="module")
def pair_file(tmp_path_factory):
    """The DB pair's quasi-static set result, written by ``racetrace solve --output``."""
    from racetrace.cli import main

    path = tmp_path_factory.mktemp("set") / "pair.nc"
    assert main(["solve", PAIR, "--output", str(path)]) == 0
    return path


def _page_text(path) -> str:
    """The page's text with the markup of its embedded panes unescaped (JSON's \\u escapes, then
    HTML twice: the panes' HTML sits in the document's JSON as escaped text)."""
    text = path.read_text(encoding="utf-8").replace("\\n", " ").replace('\\"', '"')
    text = re.sub(r"\\u([0-9a-fA-F]{4})", lambda m: chr(int(m.group(1), 16)), text)
    return html.unescape(html.unescape(text))


def test_a_set_report_shows_the_set_its_load_sharing_and_stiffness(pair_file, tmp_path):
    import solver
    from report import build_report
    from report.units import number

    ds = solver.load_result(pair_file)
    info = build_report(pair_file, tmp_path / "pair.html")
    assert info["kind"] == "set" and info["unresolved"] == []
    text = _page_text(tmp_path / "pair.html")
    for heading in ("The bearing set", "Load sharing", "Stiffness", "5 × 5 stiffness, set"):
        assert heading in text, heading
    assert "DB of 2 bearing(s), preload force 100 N at assembly" in text
    # each bearing's row: its position and direction; its axial and radial load
    for index in range(2):
        one = ds.isel(bearing=index)
        position = number(float(one["bearing_position"]) * 1e3)
        direction = one["bearing_direction"].item()
        assert re.search(
            rf"<td[^>]*>bearing {index + 1}</td><td>{position}</td>"
            rf"<td>{re.escape(direction)}</td>",
            text,
        ), (index, position)
        assert f"<td>{number(float(one['bearing_axial_load']))}</td>" in text
        assert f"<td>{number(float(one['bearing_radial_load']))}</td>" in text
    # the set's 5 x 5: every entry with its unit, the x-x entry in N/um, tilt-tilt in N m/mrad
    k = ds["set_stiffness"].values
    assert f"<td>{number(k[0, 0] * 1e-6)} N/µm</td>" in text
    assert f"<td>{number(k[3, 3] * 1e-3)} N m/mrad</td>" in text
    assert f"<td>{number(k[1, 4] * 1e-3)} N/mrad</td>" in text
    assert f"<td>{number(k[4, 1] * 1e-6)} N m/µm</td>" in text
    # each bearing's matrix too, and the summary row of the set
    for index in range(2):
        kb = ds["bearing_stiffness"].values[index]
        assert f"5 × 5 stiffness, bearing {index + 1}" in text
        assert f"<td>{number(kb[2, 2] * 1e-6)} N/µm</td>" in text
    radial = number(0.5 * (k[1, 1] + k[2, 2]) * 1e-6)
    assert re.search(rf"set \(at the load point\)</td><td>[^<]+</td><td>{radial}</td>", text)
    # both bearings' contact charts
    assert text.count(": contact angle and load per ball") == 2
    assert np.isfinite(ds["axial_stiffness"].values)


def test_the_matrix_units_follow_the_blocks():
    from report.bearing_set import matrix_unit

    assert matrix_unit("x", "y") == ("N/µm", 1e-6)
    assert matrix_unit("y", "tilt_z") == ("N/mrad", 1e-3)
    assert matrix_unit("tilt_y", "z") == ("N m/µm", 1e-6)
    assert matrix_unit("tilt_z", "tilt_z") == ("N m/mrad", 1e-3)


def _row(name: str, value: str) -> str:
    """A row of the set's "shaft and preload" table (both cells text)."""
    return f'<td class="text">{name}</td><td class="text">{value}</td>'


def _spring_case():
    """The shipped DB pair with a spring on its -x bearing's outer ring instead of its
    fixed-position preload (the same 100 N)."""
    import solver

    return solver.resolve_case(PAIR).with_values(
        {"set.preload.kind": "spring", "set.preload.spring_side": "-x"}
    )


def test_a_set_report_shows_the_spring_preload(tmp_path):
    """A spring-preloaded pair's reports: the quasi-static set's gives the floating outer rings'
    solved shift; a dynamic run's gives the spring force, the shift's mean and peak to peak over
    the run's analysed window and a chart of the shift over time, the tables at the run's last
    sample and no stiffness (a run has none). A fixed-position pair's report has no spring
    rows."""
    import solver
    from report import build_report
    from report.units import number
    from solver.models.dynamic import SimulationOptions

    case = _spring_case()
    qs = solver.solve(case)
    solver.save_dataset(qs, tmp_path / "qs.nc")
    build_report(tmp_path / "qs.nc", tmp_path / "qs.html")
    text = _page_text(tmp_path / "qs.html")
    shift = float(qs["spring_shift"])
    assert shift != 0.0
    assert _row("spring side shift", f"{number(shift * 1e6)} µm") in text
    assert "5 × 5 stiffness, set" in text

    run = solver.simulate(
        case,
        options=SimulationOptions(
            shaft_revolutions=0.1, samples_per_revolution=200, method="dopri5"
        ),
    )
    solver.save_dataset(run, tmp_path / "run.nc")
    info = build_report(tmp_path / "run.nc", tmp_path / "run.html")
    assert info["kind"] == "set"
    text = _page_text(tmp_path / "run.html")
    window = run["spring_shift"].sel(time=slice(float(run["analysis_start_time"].max()), None))
    force = number(float(run["spring_force"]))
    for row in (
        _row("spring force on the spring side's outer rings", f"{force} N"),
        _row(
            "spring side shift (mean over the analysed window)",
            f"{number(float(window.mean()) * 1e6)} µm",
        ),
        _row(
            "spring side shift, peak to peak over the analysed window",
            f"{number(float(np.ptp(window.values)) * 1e6)} µm",
        ),
    ):
        assert row in text, row
    assert f"Spring side outer rings' shift (spring force {force} N)" in text  # the chart
    last = run.isel(time=-1)
    assert f"last stored sample, t = {number(float(last['time']) * 1e3)} ms" in text
    assert f"<td>{number(float(last['bearing_axial_load'][0]))}</td>" in text
    assert "5 × 5 stiffness" not in text
    assert text.count(": contact angle and load over time") == 2


def test_a_fixed_position_pair_report_has_no_spring_rows(pair_file, tmp_path):
    from report import build_report

    build_report(pair_file, tmp_path / "pair.html")
    text = _page_text(tmp_path / "pair.html")
    assert "spring side shift" not in text and "Spring preload" not in text
