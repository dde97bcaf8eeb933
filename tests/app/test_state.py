"""App state and handlers without a browser: form validation, preview, time, runs."""

from __future__ import annotations

import base64
import math
import time

import numpy as np
import pytest

from app import runner as runner_module
from app.charts import NOW_SHAPE, merge_overlay
from app.runner import QUASISTATIC_JOB
from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server
from tests.helpers.processes import wait_until


class CountingView:
    def __init__(self):
        self.renders = 0

    def render(self):
        self.renders += 1


def _length(array) -> int:
    """Length of an array in plotly JSON (a list or a base64 typed array)."""
    if isinstance(array, dict):
        return len(base64.b64decode(array["bdata"])) // np.dtype(array["dtype"]).itemsize
    return len(array)


def _shown(state, name: str) -> dict:
    """The figure the page shows for chart ``name``: its figure and, for a chart that follows
    the time, the marks of the current frame merged in."""
    return merge_overlay(
        state[f"chart_{name}"], state[f"chart_{name}_now"] if f"chart_{name}_now" in state else None
    )


def _set(app, **values):
    with app.state:
        for k, v in values.items():
            app.state[k] = v


def test_opens_on_the_default_case_solved(app):
    s = app.state
    from solver.catalogue import catalogue

    expected = catalogue().get(DEFAULT_CASE).load()
    assert s.case_name == DEFAULT_CASE
    assert s.fv_ball_count == str(expected.bearing.ball_count)
    assert s.status == "preview done"
    assert s.case_valid and not s.run_disabled
    assert s.frame_max > 10
    assert app.result.dataset.attrs["model"] == "quasistatic"
    assert len(s.chart_contact_angle["data"]) >= 2
    # both raceways, the legend of where the balls are now, and a circle at each contact now
    shown = _shown(s, "raceway_map")
    assert [t["name"] for t in shown["data"]] == ["inner raceway", "outer raceway", "contacts now"]
    circles = [c for c in shown["layout"]["shapes"] if c.get("templateitemname") == NOW_SHAPE]
    assert len(circles) > 0
    assert _length(s.chart_raceway_map["data"][0]["x"]) > 0
    # every case-file key has a form field named after its last segment
    assert {f["name"] for f in s.form} >= {
        "ball_count",
        "axial_load_N",
        "inner_groove_radius_ratio",
    }


def test_invalid_field_shows_message_and_disables_run(app):
    s = app.state
    _set(app, fv_inner_groove_radius_ratio="0.49")
    assert "0.49" in s.fe_inner_groove_radius_ratio
    assert "0.5" in s.fe_inner_groove_radius_ratio
    assert s.run_disabled and not s.case_valid
    assert s.fe_ball_count == ""
    _set(app, fv_axial_load_N="lots")
    assert "must be a number" in s.fe_axial_load_N
    _set(app, fv_inner_groove_radius_ratio="0.56", fv_axial_load_N="800")
    assert s.fe_inner_groove_radius_ratio == "" and s.fe_axial_load_N == ""
    assert s.case_valid and not s.run_disabled
    assert app.form.case.operating.axial_load_N == 800.0
    assert app.form.case.bearing.inner_groove_radius_ratio == 0.56


def test_preview_follows_a_valid_edit(app):
    before = float(app.result.dataset["contact_angle"].sel(race="inner").mean())
    load = float(app.state.fv_axial_load_N or 0)
    _set(app, fv_axial_load_N=str(3 * load + 500))
    app.form.preview_now()  # the server does this after a short debounce
    after = float(app.result.dataset["contact_angle"].sel(race="inner").mean())
    assert after > before  # more thrust, larger contact angle


def test_time_controls(app):
    s = app.state
    app.result.step(1)
    assert s.frame == 1
    app.result.step(-2)
    assert s.frame == s.frame_max
    _set(app, frame=5)
    assert s.frame_time.strip().startswith("t =")
    t5 = app.result.source.times[5] * 1e3
    assert f"{t5:8.3f}" in s.frame_time


def test_scene_follows_frames_and_options(tmp_path):
    a = RacetraceApp(trame_server(), runs_dir=tmp_path, render=True, window_size=(200, 150))
    view = CountingView()
    a.result.view = view
    a.start(DEFAULT_CASE, play=False)
    try:
        _set(a, frame=7)
        assert a.result.scene.frame_index == 7
        assert view.renders >= 1
        _set(a, show_cage=False)
        assert not a.result.scene.actors["cage"][0].visibility
        _set(a, exaggeration=8)
        assert a.result.scene.options.exaggeration == 8
        # the view faces the load zone: a radial load towards +z (90 deg) turns it there
        assert a.result.scene.options.view_azimuth == pytest.approx(0.0)
        _set(a, fv_radial_load_angle_deg="90")
        a.form.preview_now()
        assert a.result.scene.options.view_azimuth == pytest.approx(math.pi / 2)
        lo, hi = a.result.scene.options.outer_cutaway
        assert (lo + hi) / 2 == pytest.approx(math.pi / 2)
        # another bearing and back: the pressure colour bar is drawn each time
        for case_name in ("209-deep-groove", DEFAULT_CASE):
            _set(a, case_name=case_name)
            props = a.result.plotter.renderer.GetViewProps()
            props = [props.GetItemAsObject(i) for i in range(props.GetNumberOfItems())]
            bars = [x for x in props if x.IsA("vtkScalarBarActor")]
            assert len(bars) == 1 and bars[0].GetVisibility(), case_name
        # a resized view is framed again before the next frame is sent
        a.result.plotter.window_size = (150, 150)
        assert not a.result.scene.framed_for_window()
        _set(a, frame=3)
        assert a.result.scene.framed_for_window()
    finally:
        a.shutdown()


def _wait_run(app, timeout=180.0):
    wait_until(
        app.runs.poll_runner,
        timeout,
        0.1,
        lambda: f"run did not finish in {timeout} s; status {app.state.status!r}",
    )


def test_run_saves_and_reload_keeps_the_run_list(app, tmp_path, monkeypatch):
    # a fast run: the quasi-static job in place of the dynamic one
    monkeypatch.setattr(runner_module, "DYNAMIC_JOB", QUASISTATIC_JOB)
    app.runs.run()
    assert app.state.busy and app.state.run_disabled
    assert app.state.status.startswith("running")
    _wait_run(app)
    assert app.state.status == "done", app.state.status
    assert not app.state.busy and not app.state.run_disabled
    assert len(app.state.runs) == 1
    # a new app on the same runs folder (server restart or reload) lists the same run
    again = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    assert again.state.runs == app.state.runs
    again.start(DEFAULT_CASE, play=False)
    _set(again, run_id=app.state.runs[0]["value"])
    assert again.state.result_label == app.state.runs[0]["title"]
    assert again.result.dataset.attrs["case"] == app.result.dataset.attrs["case"]
    # compare the preview with the saved run side by side
    _set(again, compare_ids=[app.state.runs[0]["value"]])
    assert len(again.state.chart_compare_runs["data"]) == 4
    again.shutdown()


def test_run_refused_while_invalid(app):
    _set(app, fv_ball_count="0")
    assert app.state.run_disabled
    app.runs.run()
    assert not app.runs.runner.busy and not app.state.busy


def test_exports_from_the_app(app):
    path = app.exports.export("csv")
    assert path.is_file() and path.parent == app.exports_dir
    assert (
        app.state.export_href.startswith("racetrace-exports/")
        and app.state.export_name == path.name
    )
    assert app.exports.export("netcdf").suffix == ".nc"
    assert app.exports.export("png") is None  # render=False: no 3-D view
    assert "not available" in app.state.export_message
    with pytest.raises(ValueError, match="netcdf, csv"):
        app.exports.export("xls")


def test_uploaded_case_fills_the_form(app, fixture_model):
    _set(app, uploaded_case={"name": "mine.toml", "content": fixture_model.FIXTURE_CASE.encode()})
    assert app.state.fv_ball_count == "12"
    assert app.state.fv_title == "app test fixture"
    assert app.state.case_valid
    bad = fixture_model.FIXTURE_CASE.replace("ball_count = 12", "ball_count = 1")
    _set(app, uploaded_case=[{"name": "bad.toml", "content": bad.encode()}])
    assert app.state.case_message.startswith("bad.toml: bearing.ball_count = 1")
    assert app.state.fv_ball_count == "12"  # the form keeps the last valid case
    # the case list no longer names the shipped case, so picking it again reloads it
    assert app.state.case_name is None
    assert app.state.uploaded_case is None  # the file box is emptied: the same file can be resent
    _set(app, case_name=DEFAULT_CASE)
    assert app.state.fv_title != "app test fixture"


@pytest.mark.parametrize("text", ["/proc/self/environ", "/dev/zero", "/dev/stdin"])
def test_uploaded_one_line_text_is_case_text_never_a_path(app, text, monkeypatch):
    """An upload holds case text: a one-line text naming a server file is invalid TOML, and no
    file is read (the message shows neither the environment nor device data; it returns at
    once)."""
    import os

    from solver.case import io as case_io

    def no_file_reading(*args, **kwargs):
        raise AssertionError("an uploaded text was read as a path")

    monkeypatch.setattr(case_io, "read_case_bytes", no_file_reading)
    monkeypatch.setenv("RACETRACE_UPLOAD_SECRET", "do-not-show-this-value")
    before = app.state.fv_title
    start = time.perf_counter()
    _set(app, uploaded_case={"name": "evil.toml", "content": text.encode()})
    assert time.perf_counter() - start < 5.0
    message = app.state.case_message
    assert message.startswith("evil.toml: uploaded file evil.toml is not valid TOML"), message
    assert text in message
    assert "do-not-show-this-value" not in message and os.environ["PATH"] not in message
    assert app.state.fv_title == before  # the form keeps its case


def test_uploaded_file_that_is_not_utf8_is_reported(app):
    _set(app, uploaded_case={"name": "bin.toml", "content": b"\xff\xfe\x00garbage"})
    assert "not a text file" in app.state.case_message


def test_a_case_the_dynamic_model_cannot_run_disables_run_with_the_reason(app):
    s = app.state
    speed = s.fv_inner_ring_speed_rpm
    _set(app, fv_outer_ring_speed_rpm=speed)
    assert s.case_valid and s.run_disabled  # valid: the quasi-static preview still works
    assert s.run_reason.startswith("dynamic model: ")
    assert "turn relative to each other" in s.run_reason
    app.runs.run()
    assert not app.runs.runner.busy and not app.state.busy
    _set(app, fv_outer_ring_speed_rpm="0")
    assert s.case_valid and not s.run_disabled and s.run_reason == ""


def test_reset_undoes_the_edits(app):
    s = app.state
    original = s.fv_ball_diameter_mm
    _set(app, fv_ball_diameter_mm="", fv_axial_load_N="650")
    assert not s.case_valid
    app.form.reset_case()
    assert s.fv_ball_diameter_mm == original and s.fv_axial_load_N in ("500", "500.0")
    assert s.case_valid


def test_a_reopened_run_stays_on_show(app):
    s = app.state
    _set(app, fv_radial_load_N="0")
    app.form.preview_now()
    saved = app.store.save(app.result.dataset, app.form.case.to_toml(), "pure axial")
    _set(app, fv_radial_load_N="300")  # a different case on show
    app.form.preview_now()
    app.runs.refresh()
    _set(app, run_id=saved.run_id)
    assert s.result_label == saved.label and s.fv_radial_load_N in ("0", "0.0")
    # the form's change callbacks arrive after the run is on show: no preview may replace it
    app.form._on_field()
    assert s.result_label == saved.label
    assert s.status == "saved run opened: done"
    # an edit does replace it, and the runs list then names no run
    _set(app, fv_radial_load_N="100")
    assert s.result_label == "quasi-static preview" and s.run_id is None


def test_run_title_says_what_was_run(app):
    _set(app, fv_radial_load_N="0", fv_axial_load_N="650", fv_shaft_revolutions="0.2")
    _set(app, playing=True)
    app.runs.run()
    try:
        title = app.runs.run_info["title"]
        assert "Fa 650 N" in title and "Fr" not in title and "0.2 rev" in title
        assert app.state.playing is False  # the animation pauses while the solver runs
    finally:
        app.runs.cancel()
        app.runs.runner.shutdown()


def test_export_in_the_background(app):
    import asyncio

    async def export_csv():
        app.exports.request_export("csv")
        assert app.exports.task is not None
        await app.exports.task

    asyncio.run(export_csv())
    assert app.state.exporting is False
    assert app.state.export_name.endswith(".csv")
    assert (app.exports_dir / app.state.export_name).is_file()


def test_dynamic_run_reports_progress_and_shows_its_result(app):
    _set(app, fv_shaft_revolutions="0.3", open_panels=["comparison"])
    assert app.state.case_valid
    app.runs.run()
    progress = []
    end = time.monotonic() + 300
    while not app.runs.poll_runner():
        progress.append(app.state.progress)
        assert time.monotonic() < end, app.state.status
        time.sleep(0.05)
    assert app.state.status == "done", app.state.status
    assert app.state.progress == 100
    assert "time" in app.result.dataset.dims and app.result.source.model == "dynamic"
    omega = app.form.case.operating.inner_ring_speed_rpm * 2 * np.pi / 60
    assert float(app.result.dataset.time[-1]) == pytest.approx(0.3 * 2 * np.pi / omega, rel=0.02)
    x = app.state.chart_contact_angle["data"][0]["x"]  # plotly JSON: base64 typed array
    # "all balls": every ball's samples on one line per race, a gap after each ball
    assert _length(x) == app.result.source.ball_count * (app.result.source.n_frames + 1)
    # quasi-static versus dynamic: both models of the same case
    names = [t["name"] for t in app.state.chart_comparison["data"]]
    assert names == ["quasi-static inner", "dynamic inner", "quasi-static outer", "dynamic outer"]
    # ... the quasi-static one being the start the run carries
    start = app.result.dataset["quasistatic_contact_angle"]
    np.testing.assert_array_equal(app.result.quasistatic["contact_angle"], start)
    assert app.state.frame_max == app.result.dataset.sizes["time"] - 1


def _with_start(ds):
    """The fixture run carrying a quasi-static start that differs from every solution of a case
    (so that a re-solved comparison cannot pass for it)."""
    z = ds.sizes["ball"]
    azimuth = 360.0 * np.arange(z) / z
    angle = np.stack([30.0 + 0.1 * np.arange(z), 20.0 - 0.1 * np.arange(z)], axis=1)
    return ds.assign(
        quasistatic_ball_azimuth=("ball", azimuth),
        quasistatic_contact_angle=(("ball", "race"), angle),
        quasistatic_contact_load=(("ball", "race"), np.full((z, 2), 100.0)),
        quasistatic_cage_speed=((), 1000.0),
    )


def test_comparison_chart_reads_the_quasistatic_start_without_the_case(app, dynamic_dataset):
    """The quasi-static versus dynamic chart shows the start the dynamic result carries; the case
    text is neither parsed nor solved (a result without attrs["case"] gives the same chart)."""
    ds = _with_start(dynamic_dataset)
    del ds.attrs["case"]
    _set(app, open_panels=["comparison"])
    app.result.show_result(ds, "fixture without its case")
    traces = app.state.chart_comparison["data"]
    names = [t["name"] for t in traces]
    assert names == ["quasi-static inner", "dynamic inner", "quasi-static outer", "dynamic outer"]
    for trace, race in ((traces[0], 0), (traces[2], 1)):
        np.testing.assert_array_equal(
            _decode(trace["y"]), ds["quasistatic_contact_angle"].isel(race=race).values
        )
        np.testing.assert_array_equal(_decode(trace["x"]), ds["quasistatic_ball_azimuth"].values)


def test_comparison_chart_says_when_a_result_has_no_quasistatic_start(app, dynamic_dataset):
    """A dynamic result without its start and without the operating point to solve one for (its
    moment_axis coordinate is missing): the chart says the comparison is not available (no
    traceback, no stale chart)."""
    from app.charts import COMPARISON_UNAVAILABLE

    ds = dynamic_dataset.drop_vars("moment_axis")
    _set(app, open_panels=["comparison"])
    app.result.show_result(ds, "fixture without a start")
    assert app.state.chart_comparison["data"] == []
    assert app.state.chart_comparison["layout"]["title"]["text"] == COMPARISON_UNAVAILABLE


def test_panel_charts_are_computed_only_while_their_panel_is_open(app):
    s = app.state
    empty = {"data": [], "layout": {}}
    # nothing open: only the two charts always on the page were drawn
    assert s.chart_contact_angle["data"] and s.chart_raceway_map["data"]
    for name in ("load_azimuth", "ellipse", "cage_speed", "comparison"):
        assert s[f"chart_{name}"] == empty, name
    _set(app, open_panels=["load_azimuth", "comparison"])
    assert len(s.chart_load_azimuth["data"]) == 2  # inner and outer
    assert s.chart_comparison["data"]
    assert s.chart_ellipse == empty and s.chart_cage_speed == empty
    # an open panel follows the time: a later frame changes the load chart's title
    title = s.chart_load_azimuth["layout"]["title"]["text"]
    _set(app, frame=5)
    assert s.chart_load_azimuth["layout"]["title"]["text"] != title


def _decode(array) -> np.ndarray:
    """Values of an array in plotly JSON (a list or a base64 typed array) as floats."""
    if isinstance(array, dict):
        return np.frombuffer(base64.b64decode(array["bdata"]), dtype=array["dtype"]).astype(float)
    return np.asarray(array, float)


def _trace(figure: dict, name: str) -> dict:
    return next(t for t in figure["data"] if t["name"] == name)


def test_compare_with_a_saved_run_fills_charts_and_summary(app):
    s = app.state
    radial = s.fv_radial_load_N
    assert float(radial) > 0  # the default case is a combined load
    # save a pure-axial run of the same bearing, then go back to the combined load (run A)
    _set(app, fv_radial_load_N="0")
    app.form.preview_now()
    axial = app.store.save(app.result.dataset, app.form.case.to_toml(), "pure axial")
    _set(app, fv_radial_load_N=radial)
    app.form.preview_now()
    combined = app.store.save(app.result.dataset, app.form.case.to_toml(), "combined load")
    app.runs.refresh()

    _set(app, compare_ids=[axial.run_id])
    assert s.compare_message == ""
    assert [e["tag"] for e in s.compare_legend] == ["A", "B"]
    assert s.compare_legend[1]["label"] == axial.label
    assert len(s.chart_compare_runs["data"]) == 4
    names = ["A inner", "A outer", "B inner", "B outer"]
    for key in ("chart_compare_angle", "chart_compare_load"):
        assert [t["name"] for t in s[key]["data"]] == names
    balls = app.result.source.ball_count
    # pure axial load: every ball carries the same load; the combined load has a load zone
    axial_load = _decode(_trace(s.chart_compare_load, "B inner")["y"])
    combined_load = _decode(_trace(s.chart_compare_load, "A inner")["y"])
    assert len(axial_load) == len(combined_load) == balls
    assert np.ptp(axial_load) < 1e-6 * axial_load.max()
    assert np.ptp(combined_load) > 0.2 * combined_load.max()
    # the table: A then B, inner then outer; the axial run's contact angles form no band; the
    # combined load (fixed in space) draws the outer line and the inner band
    rows = {r["key"]: r for r in s.compare_summary}
    assert list(rows) == ["A-inner", "A-outer", "B-inner", "B-outer"]
    assert float(rows["B-inner"]["excursion_deg"]) == pytest.approx(0.0, abs=1e-3)
    assert float(rows["B-inner"]["band_thickness_deg"]) == pytest.approx(0.0, abs=1e-3)
    assert float(rows["A-outer"]["excursion_deg"]) > 0.1
    assert float(rows["A-inner"]["band_thickness_deg"]) > 0.1
    assert float(rows["A-inner"]["excursion_deg"]) == pytest.approx(0.0, abs=1e-3)
    assert {rows[key]["model"] for key in rows} == {"quasi-static"}  # each row names its model
    assert float(rows["A-inner"]["contact_load_max_N"]) == pytest.approx(
        combined_load.max(), abs=0.05
    )
    assert float(rows["B-outer"]["cage_speed_rpm"]) > 0

    # the same combined run saved and compared with itself: identical numbers
    _set(app, compare_ids=[combined.run_id])
    rows = {r["key"]: r for r in s.compare_summary}
    assert {
        k: v for k, v in rows["A-inner"].items() if k not in ("key", "run", "label", "colour")
    } == {k: v for k, v in rows["B-inner"].items() if k not in ("key", "run", "label", "colour")}

    # a run that cannot be loaded says so in words and empties the comparison
    _set(app, compare_ids=["no-such-run"])
    assert "no-such-run" in s.compare_message
    assert s.chart_compare_load["data"] == [] and s.compare_summary == []

    _set(app, compare_ids=[axial.run_id])
    assert len(s.compare_summary) == 4 and s.compare_message == ""
    _set(app, compare_ids=None)
    for key in ("chart_compare_runs", "chart_compare_angle", "chart_compare_load"):
        assert s[key]["data"] == []
    assert s.compare_summary == [] and s.compare_legend == [] and s.compare_message == ""


def test_a_result_outside_the_models_validity_is_flagged(app):
    s = app.state
    assert s.result_warnings == []  # the shipped default case is within the model's validity
    _set(app, fv_axial_load_N="1e9")  # absurd: ~100 GPa, contacts wider than the groove allows
    assert s.status == "preview done"
    joined = " ".join(s.result_warnings)
    assert "4.2 GPa" in joined and "inner race" in joined and "outer race" in joined
    _set(app, fv_axial_load_N="500")
    assert s.result_warnings == []


def test_empty_fields_show_the_default_used(app):
    p = app.state.placeholders
    assert p["viscosity_Pas"].endswith("Pa s")
    # an estimated default shows this bearing's value and its rule
    assert p["pocket_diametral_clearance_mm"].startswith("0.2 mm (estimated")
    assert p["ball_count"] == ""  # required: no default


def test_a_misalignment_turning_with_the_ring_is_previewed_over_a_revolution(app):
    """The t = 0 snapshot would draw a band on the inner race where the run draws a line."""
    _set(app, case_name="spindle-misalignment-ring")
    app.form.preview_now()
    src = app.result.source
    spreads = []
    for race in (0, 1):
        phi, alpha, ok = src.trace(race)
        bins = (np.mod(phi[ok], 2 * np.pi) / (2 * np.pi) * 36).astype(int)
        alpha = np.degrees(alpha[ok])
        spreads.append(np.median([np.ptp(alpha[bins == b]) for b in range(36)]))
    assert spreads[0] < 0.25 * spreads[1], spreads  # a line inside, a band outside
    assert "ring_angle" not in app.result.dataset.dims  # the views read one element
    # the metrics by the raceway map span the revolution: the turning tilt's bands have thicknesses
    assert "needs a dynamic run" not in app.state.raceway_metrics
    assert "turning with the ring" in app.state.scene_note or "turns with" in app.state.scene_note


def test_time_words_name_the_revolution_and_the_slow_motion(app):
    s = app.state
    _set(app, frame=int(s.frame_max))
    assert "revolution" in s.frame_time and " of " in s.frame_time
    assert s.slow_motion.startswith("1 s on screen = ")
    before = s.slow_motion
    _set(app, speed=10)
    assert s.slow_motion != before
    assert "painted" in s.scene_note


def test_raceway_map_follows_the_ball_and_its_options(app):
    s = app.state
    _set(app, frame=3)
    data = _shown(s, "raceway_map")["data"]
    assert [t["name"] for t in data[:3]] == ["inner raceway", "outer raceway", "contacts now"]
    assert "shoulders at" in s.chart_raceway_map["layout"]["title"]["text"]
    assert "excursion" in s.raceway_metrics and "band thickness" in s.raceway_metrics
    assert "needs a dynamic run" not in s.raceway_metrics  # steady running from one solution
    _set(app, trace_ball=2)
    balls = {int(b) for b in _decode_custom(s.chart_raceway_map["data"][0])}
    assert balls == {2}
    _set(app, map_colour="load")
    assert "colorscale" in s.chart_raceway_map["data"][0]["marker"]


def _decode_custom(trace):
    custom = trace["customdata"]
    if isinstance(custom, dict):
        values = np.frombuffer(base64.b64decode(custom["bdata"]), dtype=np.dtype(custom["dtype"]))
        return values.reshape(-1, 2)[:, 0]
    return [row[0] for row in custom]


def test_ball_legend_gives_each_ball_of_the_result_its_colour(app, dynamic_dataset):
    from viz.palette import ball_colours

    s = app.state
    z = app.result.source.ball_count
    assert [e["ball"] for e in s.ball_legend] == list(range(z))
    assert [e["colour"] for e in s.ball_legend] == ball_colours(z)
    app.result.show_result(dynamic_dataset, "fixture")  # 12 balls
    assert len(s.ball_legend) == 12


def test_compare_legend_names_a_saved_run_on_show_once(app):
    s = app.state
    saved = []
    for radial in ("0", "600"):
        _set(app, fv_radial_load_N=radial)
        app.form.preview_now()
        saved.append(app.store.save(app.result.dataset, app.form.case.to_toml(), f"r{radial}"))
    app.runs.refresh()
    _set(app, run_id=saved[0].run_id)
    _set(app, open_panels=["compare"], compare_ids=[saved[1].run_id])
    assert s.compare_legend[0]["label"] == f"{saved[0].label} (on show)"
    assert s.compare_legend[1]["label"] == saved[1].label


def test_compare_any_number_of_runs_each_in_its_own_colour(app):
    from viz.palette import run_colours

    s = app.state
    saved = []
    for radial in ("0", "400", "800", "1200"):
        _set(app, fv_radial_load_N=radial)
        app.form.preview_now()
        title = f"spindle, a title long enough to be cut in a narrow column, radial {radial} N"
        saved.append(app.store.save(app.result.dataset, app.form.case.to_toml(), title))
    app.runs.refresh()
    _set(app, compare_ids=[r.run_id for r in saved] + ["no-such-run"])
    # A (on show) and four saved runs: each its own tag, full name and colour
    tags = ["A", "B", "C", "D", "E"]
    assert [e["tag"] for e in s.compare_legend] == tags
    assert [e["label"] for e in s.compare_legend[1:]] == [r.label for r in saved]
    assert "radial 1200 N" in s.compare_legend[4]["label"]  # never truncated
    colours = [e["colour"] for e in s.compare_legend]
    assert len(set(colours)) == 5
    assert "no-such-run" in s.compare_message  # the others are still compared
    # every chart holds every run, in its colour; the table has a row per run and race
    maps = s.chart_compare_runs["data"]
    assert [t["name"].split()[0] for t in maps] == [t for t in tags for _ in (0, 1)]
    for i, tag in enumerate(tags):
        for key in ("chart_compare_angle", "chart_compare_load"):
            inner = _trace(s[key], f"{tag} inner")
            outer = _trace(s[key], f"{tag} outer")
            assert inner["marker"]["color"] == run_colours(i)[0]
            assert outer["marker"]["color"] == run_colours(i)[1]
    assert [r["key"] for r in s.compare_summary] == [
        f"{t}-{race}" for t in tags for race in ("inner", "outer")
    ]
    assert [r["colour"] for r in s.compare_summary[::2]] == colours
    # the radial loads differ run by run: so does the largest contact load in the table
    loads = [float(r["contact_load_max_N"]) for r in s.compare_summary[2::2]]
    assert loads == sorted(loads) and loads[0] < loads[-1]
    assert s.compare_chart_px > charts_height_for_two()


def charts_height_for_two() -> int:
    from app import charts

    return charts.compare_chart_px(2)


def test_every_shipped_case_opens_and_a_bearing_set_opens_as_a_set(app):
    from solver.catalogue import catalogue

    names = [e.name for e in catalogue() if e.kind == "case"]
    sets = [n for n in names if catalogue().get(n).load().bearing_set is not None]
    assert sets  # the shipped DB pair
    for name in names:
        _set(app, case_name=name)
        s = app.state
        assert s.status == "preview done", (name, s.status)
        assert s.case_valid and app.result.dataset is not None
        assert s.set_shown == s.case_is_set == (name in sets), name
        if name in sets:
            assert s.case_notice.startswith("bearing set: ")
            assert not s.run_disabled and s.run_reason == ""  # Run runs the set's dynamic model
            assert "bearing 1 of the set" in app.result.shown_title + s.result_label
            continue
        assert s.case_notice == ""
        for f in app.form.fields:  # a history key shows its history, never an empty field
            history = app.form.base_case.histories.get(f.key)
            if history is not None:
                assert s[f"fv_{f.name}"] == s[f"fh_{f.name}"] != ""
        assert "None" not in s.run_size and "None" not in app.result.shown_title


def test_a_bearing_set_asked_for_at_start_opens_it(tmp_path):
    session = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    try:
        session.start("spindle-pair-db-light-preload", play=False)
        assert session.form.base_case.bearing_set is not None
        assert session.state.set_shown and session.state.status == "preview done"
    finally:
        session.shutdown()


def test_a_history_case_in_the_form_keeps_its_history_and_says_its_run_in_seconds(app):
    _set(app, case_name="spindle-start-up")
    s = app.state
    assert s.fv_inner_ring_speed_rpm == "smooth ramp from 0 to 20000 rpm, 0 s to 0.3 s"
    assert s.run_size.startswith("dynamic run: 0.4 s at 20 000 samples per second")
    _set(app, fv_axial_load_N="200")
    assert s.case_valid and s.fe_inner_ring_speed_rpm == ""
    assert app.form.case.operating.axial_load_N == 200.0
    assert "operating.inner_ring_speed_rpm" in app.form.case.histories
    assert "ramp" in app.form.case_text


def test_the_preview_of_a_history_case_plays_for_its_duration(app):
    _set(app, case_name="spindle-unbalance")  # 0.05 s at 20 000 rpm: 16.7 revolutions
    assert app.state.frame_time.endswith("revolution 0.0 of 16.7")
