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
