"""A bearing set in the app, without a browser: the set's quasi-static solution on show bearing by
bearing, the set panel (the set along the shaft, load sharing, balls, stiffness), the form's
set fields (arrangement and preload) with the case module's messages, and Run of the set's
dynamic model (the run listed, reopened, shown bearing by bearing)."""

from __future__ import annotations

import numpy as np
import pytest

from app import set_charts
from app.state import RacetraceApp
from tests.helpers.app_session import trame_server

PAIR = "spindle-pair-db-light-preload"


def _set(app, **values):
    with app.state:
        for key, value in values.items():
            app.state[key] = value


@pytest.fixture
def pair(tmp_path):
    """A session opened on the shipped DB pair (solved), not playing, without rendering."""
    session = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    session.start(PAIR, play=False)
    yield session
    session.shutdown()


def test_a_bearing_set_opens_solved_with_its_set_panel(pair):
    import solver

    s = pair.state
    assert s.case_name == PAIR and s.status == "preview done"
    assert s.case_is_set and s.set_shown
    assert "bearing set: DB of 2 bearing(s), preload force 100 N" in s.case_notice
    whole = pair.result.set_result
    assert whole.sizes["bearing"] == 2
    assert [item["title"] for item in s.set_bearing_items] == ["bearing 1 (+x)", "bearing 2 (-x)"]
    # the 3-D view and the single-bearing charts show bearing 1 of the set, as its own result
    one = solver.bearing_result(whole, 0)
    np.testing.assert_array_equal(pair.result.dataset["contact_load"], one["contact_load"])
    assert "bearing 1 of the set" in s.result_label
    assert s.frame_max > 10 and len(s.chart_contact_angle["data"]) >= 2
    # load sharing: a bar per bearing, the loads each carries
    axial, radial = s.chart_set_sharing["data"]
    np.testing.assert_allclose(_values(axial["y"]), whole["bearing_axial_load"].values)
    np.testing.assert_allclose(_values(radial["y"]), whole["bearing_radial_load"].values)
    # the balls of both bearings: one line each
    assert len(s.chart_set_load["data"]) == 2 and len(s.chart_set_angle["data"]) == 2
    # stiffness: a row per bearing and the set's, from the 5x5 matrices in N/um and N m/mrad
    rows = s.set_stiffness
    assert [r["name"] for r in rows] == ["bearing 1", "bearing 2", "set (at the load point)"]
    k = whole["bearing_stiffness"].values[1]
    assert float(rows[1]["axial"]) == pytest.approx(k[0, 0] * 1e-6, abs=0.05)
    assert float(rows[1]["radial"]) == pytest.approx(0.5 * (k[1, 1] + k[2, 2]) * 1e-6, abs=0.05)
    assert float(rows[1]["tilt"]) == pytest.approx(0.5 * (k[3, 3] + k[4, 4]) * 1e-3, abs=0.005)
    assert float(rows[2]["axial"]) == pytest.approx(
        float(whole["axial_stiffness"]) * 1e-6, abs=0.05
    )
    # Run runs the set's dynamic model (test_a_set_runs_its_dynamic_model_...)
    assert not s.run_disabled and s.run_reason == ""


def _values(array):
    """Numbers of a plotly JSON array (a list or a base64 typed array)."""
    import base64

    if isinstance(array, dict):
        return np.frombuffer(base64.b64decode(array["bdata"]), dtype=array["dtype"])
    return np.asarray(array, float)


def test_choosing_a_bearing_of_the_set_shows_it(pair):
    import solver

    whole = pair.result.set_result
    _set(pair, set_bearing=1)
    two = solver.bearing_result(whole, 1)
    shown = pair.result.dataset
    np.testing.assert_array_equal(shown["contact_load"], two["contact_load"])
    assert float(shown["axial_load"]) == pytest.approx(float(whole["bearing_axial_load"][1]))
    assert "bearing 2 of the set" in pair.state.result_label
    assert pair.result.set_result is whole  # the set stays on show in its panel
    # the heavier outline in the set along the shaft follows the choice
    widths = {
        t["name"]: t["line"]["width"] for t in pair.state.chart_set_layout["data"] if t.get("name")
    }
    assert widths["bearing 2 (-x)"] > widths["bearing 1 (+x)"]


def test_the_form_edits_the_arrangement_and_the_preload_with_the_case_messages(pair):
    s = pair.state
    assert (s.fv_set_arrangement, s.fv_preload_kind, s.fv_preload_force_N) == (
        "DB",
        "force",
        "100.0",
    )
    _set(pair, fv_preload_kind="offset")  # an offset preload reads offset_um, not force_N
    assert not s.case_valid and s.run_blocked
    assert (
        "set.preload.force_N is not read with set.preload.kind = 'offset'" in s.fe_preload_force_N
    )
    assert "set.preload.offset_um is missing" in s.fe_preload_offset_um
    _set(pair, fv_preload_force_N="", fv_preload_offset_um="12")
    assert s.case_valid and s.fe_preload_offset_um == ""
    assert pair.form.case.bearing_set.preload_kind == "offset"
    assert pair.form.case.bearing_set.preload_offset_um == 12.0
    _set(pair, fv_set_arrangement="QBC")  # four bearings on the case's [bearing]
    assert s.case_valid
    assert pair.form.case.bearing_set.directions == ("+x", "+x", "-x", "-x")
    assert 'arrangement = "QBC"' in pair.form.case_text  # the downloaded case has it
    pair.form.preview_now()
    assert pair.result.set_result.sizes["bearing"] == 4
    assert len(s.set_bearing_items) == 4 and len(s.set_stiffness) == 5
    _set(pair, fv_preload_offset_um="many")
    assert s.fe_preload_offset_um == "set.preload.offset_um = 'many': must be a number"


def test_a_single_bearing_after_a_set_hides_the_set(pair):
    _set(pair, case_name="spindle-combined-load")
    s = pair.state
    assert s.status == "preview done"
    assert not s.set_shown and not s.case_is_set and s.case_notice == ""
    assert pair.result.set_result is None and "of the set" not in s.result_label


def test_an_uploaded_set_opens(tmp_path):
    from pathlib import Path

    session = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    try:
        session.start("spindle-combined-load", play=False)
        text = (Path("assets/cases") / f"{PAIR}.toml").read_text("utf-8")
        _set(session, uploaded_case={"name": "pair.toml", "content": text.encode()})
        session.form.preview_now()
        assert session.state.case_is_set and session.state.set_shown
        assert session.result.set_result.sizes["bearing"] == 2
    finally:
        session.shutdown()


def test_the_set_along_the_shaft_puts_the_pressure_centres_by_arrangement(pair):
    """Back-to-back: each contact line meets the axis outside the pair; face-to-face (the same
    bearings turned round): inside."""
    whole = pair.result.set_result

    def centres(ds):
        fig = set_charts.layout_figure(ds)
        lines = [t for t in fig.data if t.showlegend and (t.name or "").startswith("bearing")]
        return [float(t.x[0]) for t in lines]  # each contact line starts on the axis

    first, second = centres(whole)
    assert first < 0.0 and second > 15.0  # outside the ball-centre planes at 0 and 15 mm
    turned = whole.assign_coords(bearing_direction=("bearing", ["-x", "+x"]))
    first, second = centres(turned)
    assert 0.0 < first and second < 15.0


def _wait_run(session, timeout=600.0):
    from tests.helpers.processes import wait_until

    wait_until(
        session.runs.poll_runner,
        timeout,
        0.1,
        lambda: f"run did not finish in {timeout} s; status {session.state.status!r}",
    )


def test_a_set_runs_its_dynamic_model_and_reopens_bearing_by_bearing(pair, tmp_path):
    import solver

    s = pair.state
    assert not s.run_disabled and s.run_reason == ""
    assert "Run runs the set's dynamic model" in s.case_notice
    _set(pair, fv_shaft_revolutions="0.5", fv_samples_per_revolution="40")
    assert "dynamic run: 0.5 shaft revolutions" in s.run_size
    pair.runs.run()
    _wait_run(pair)
    assert s.status == "done", s.status
    whole = pair.result.set_result
    assert whole.sizes["bearing"] == 2 and whole.sizes["time"] == 21
    assert s.set_shown and s.set_stiffness == []  # a dynamic run has no stiffness matrices
    assert any("last stored sample" in line for line in s.set_lines)
    # load sharing: the bars are each bearing's loads at the run's last sample
    axial, _radial = s.chart_set_sharing["data"]
    np.testing.assert_allclose(
        _values(axial["y"]), whole["bearing_axial_load"].isel(time=-1).values
    )
    # the run is listed under a title that says it is the set's, and a new session on the same
    # runs folder reopens it as a set
    assert (
        "DB of 2 bearing(s), preload force 100 N at assembly: 12000 rpm, load [100, 200, 0] N"
        in (s.runs[0]["title"])
    )
    again = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    try:
        again.start(PAIR, play=False)
        _set(again, run_id=s.runs[0]["value"])
        reopened = again.result.set_result
        assert reopened is not None and reopened.sizes["bearing"] == 2
        assert "time" in again.result.dataset.dims and "bearing 1 of the set" in (
            again.state.result_label
        )
        first = again.result.dataset
        np.testing.assert_array_equal(
            first["contact_load"], solver.bearing_result(reopened, 0)["contact_load"]
        )
        # the selector switches the bearing the view and the charts read
        _set(again, set_bearing=1)
        second = again.result.dataset
        np.testing.assert_array_equal(
            second["contact_load"], solver.bearing_result(reopened, 1)["contact_load"]
        )
        assert not np.array_equal(first["contact_load"].values, second["contact_load"].values)
        assert "bearing 2 of the set" in again.state.result_label
        assert again.state.frame_max == reopened.sizes["time"] - 1
    finally:
        again.shutdown()


def test_the_set_panel_shows_a_spring_preload(pair):
    """A spring-preloaded pair (the shipped pair with a spring on its -x bearing's outer ring):
    the quasi-static set's lines give the floating outer rings' solved shift; a dynamic run's
    give the spring force and the shift over its analysed window (mean, peak to peak), and its
    chart draws the shift over time with that mean, all read from the result. A set without a
    spring shows neither."""
    import solver
    from solver.models.dynamic import SimulationOptions

    s = pair.state
    assert not s.set_shown or not any(line.startswith("Spring") for line in s.set_lines)
    assert not s.set_spring_shown
    case = solver.resolve_case(PAIR).with_values(
        {"set.preload.kind": "spring", "set.preload.spring_side": "-x"}
    )
    qs = solver.solve(case)
    pair.set_panel.show_set(qs)
    shift = float(qs["spring_shift"])
    assert shift != 0.0
    assert [line for line in s.set_lines if line.startswith("Spring preload")] == [
        f"Spring preload: the spring side's floating outer rings are shifted by "
        f"{shift * 1e6:.3f} µm along their thrust direction (the spring force is the set's "
        "preload above)."
    ]
    assert not s.set_spring_shown  # one shift: no chart over time

    run = solver.simulate(
        case,
        options=SimulationOptions(
            shaft_revolutions=0.1, samples_per_revolution=200, method="dopri5"
        ),
    )
    pair.set_panel.show_set(run)
    w = run["spring_shift"]
    window = w.sel(time=slice(float(run["analysis_start_time"].max()), None)).values
    assert 0 < window.size < w.size  # the mean is over the analysed window, not the whole run
    line = [line for line in s.set_lines if line.startswith("Spring preload")]
    assert line == [
        f"Spring preload: {float(run['spring_force']):g} N on the spring side's floating outer "
        f"rings; their shift {window.mean() * 1e6:.3f} µm (mean over the analysed window), "
        f"{np.ptp(window) * 1e6:.3f} µm peak to peak."
    ]
    assert s.set_spring_shown
    shift_trace, mean_trace = s.chart_set_spring["data"]
    np.testing.assert_allclose(_values(shift_trace["x"]), run["time"].values * 1e3)
    np.testing.assert_allclose(_values(shift_trace["y"]), w.values * 1e6)
    np.testing.assert_allclose(_values(mean_trace["y"]), [window.mean() * 1e6] * 2)
    assert (
        f"spring force {float(run['spring_force']):g} N"
        in (s.chart_set_spring["layout"]["title"]["text"])
    )

    pair.set_panel.show_set(pair.result.set_result)  # the pair's own fixed-position preload
    assert not s.set_spring_shown
    assert not any(line.startswith("Spring preload") for line in s.set_lines)
