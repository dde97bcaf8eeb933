"""Chart figures carry the result's data in display units."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from app import charts, study_figures
from viz.frames import frame_source
from viz.palette import ball_colours


def test_contact_angle_chart(qs_dataset):
    src = frame_source(qs_dataset)
    fig = charts.contact_angle_figure(src, balls=(0, 2), current=10)
    assert len(fig.data) == 4  # 2 balls x 2 races
    inner0 = fig.data[0]
    np.testing.assert_allclose(inner0.x, src.times * 1e3)
    alpha = np.degrees(src.contact["contact_angle"][:, 0, 0])
    ok = np.isfinite(np.asarray(inner0.y, float))
    assert ok.sum() > 10
    np.testing.assert_allclose(np.asarray(inner0.y, float)[ok], alpha[ok])
    assert fig.layout.shapes[0].x0 == pytest.approx(src.times[10] * 1e3)


def test_load_chart_sorted_by_azimuth(qs_dataset, fixture_model):
    src = frame_source(qs_dataset)
    fig = charts.load_azimuth_figure(src, current=0)
    x = np.asarray(fig.data[0].x, float)
    assert np.all(np.diff(x) > 0)
    np.testing.assert_allclose(fig.data[0].y, fixture_model.load_of_psi(np.radians(x)), rtol=1e-9)


def test_raceway_map_outer_line_inner_band(qs_dataset, fixture_model):
    fm = fixture_model
    src = frame_source(qs_dataset)
    fig = charts.raceway_map_figure(src)
    inner, outer = fig.data
    # outer ring stationary: every ball draws the same curve alpha_o(psi)
    x, y = np.asarray(outer.x, float), np.asarray(outer.y, float)
    assert len(x) > 100
    h = 2 * np.pi / qs_dataset.sizes["ball"]
    np.testing.assert_allclose(
        y, fm.alpha_of_psi(np.radians(x), "outer"), atol=fm.ALPHA_AMPL["outer"] * h * h / 8 + 1e-9
    )
    # inner ring turns: at a fixed raceway azimuth, several contact angles (a band)
    xi, yi = np.asarray(inner.x, float), np.asarray(inner.y, float)
    sector = (xi > 100) & (xi < 140)
    assert np.ptp(yi[sector]) > 1.0


def test_ellipse_and_cage_charts(qs_dataset, fixture_model):
    src = frame_source(qs_dataset)
    fig = charts.ellipse_figure(src, 0)
    assert len(fig.data) == 6
    a_inner = np.asarray(fig.data[0].y, float)
    assert np.nanmax(a_inner) == pytest.approx(
        qs_dataset["ellipse_semi_major"].isel(race=0).values.max() * 1e3
    )
    cage = charts.cage_speed_figure(src, qs_dataset)
    np.testing.assert_allclose(cage.data[0].y, fixture_model.CAGE_RATIO * fixture_model.SHAFT_RPM)


def test_comparison_chart(qs_dataset, dynamic_dataset):
    fig = charts.comparison_figure(qs_dataset, dynamic_dataset)
    names = [t.name for t in fig.data]
    assert names == ["quasi-static inner", "dynamic inner", "quasi-static outer", "dynamic outer"]
    assert len(fig.data[1].x) > 10
    assert len(charts.comparison_figure(qs_dataset, None).data) == 2
    assert set(charts.HELP) >= {"contact_angle", "raceway_map", "ellipse", "cage_speed"}


def test_long_results_are_decimated(qs_dataset):
    src = frame_source(qs_dataset, revolutions=20, samples_per_revolution=500)  # 10 001 frames
    fig = charts.contact_angle_figure(src, balls=(0,), current=src.n_frames - 1, max_points=1000)
    assert 900 <= len(fig.data[0].x) <= 1000
    assert fig.layout.shapes[0].x0 == pytest.approx(src.times[-1] * 1e3)


def test_side_by_side_maps(qs_dataset, dynamic_dataset):
    a, b = frame_source(qs_dataset), frame_source(dynamic_dataset)
    fig = charts.side_by_side_raceway_maps(a, b)
    assert len(fig.data) == 4
    assert [t.xaxis for t in fig.data] == ["x", "x", "x2", "x2"]
    assert [a.text for a in fig.layout.annotations] == ["A (run on show)", "B"]
    # the right panel shows run b: its outer-race contact angles
    np.testing.assert_allclose(
        sorted(fig.data[3].y), sorted(np.degrees(b.trace(1)[1][b.trace(1)[2]])), rtol=1e-12
    )


# ---- comparing two runs -------------------------------------------------------------------------
def _loaded_values(ds, name, race):
    """Values of ``name`` on ``race`` where the contact carries load, straight from the Dataset."""
    values = ds[name].sel(race=race).values
    load = ds["contact_load"].sel(race=race).values
    return values[(load > 0) & np.isfinite(ds["contact_angle"].sel(race=race).values)]


def test_run_summary_of_a_quasistatic_result(qs_dataset, fixture_model):
    summary = charts.run_summary(qs_dataset)
    for race in ("inner", "outer"):
        alpha = _loaded_values(qs_dataset, "contact_angle", race)  # degree, per ball
        assert len(alpha) == 9  # three balls opposite the load zone are unloaded
        s = summary[race]
        assert s["contact_angle_min_deg"] == pytest.approx(alpha.min())
        assert s["contact_angle_max_deg"] == pytest.approx(alpha.max())
        # a load fixed in space: the turning inner ring's track is a band, the stationary outer
        # ring's a line (steady running from the one solution)
        spread = np.ptp(alpha)
        if race == "inner":
            assert s["band_thickness_deg"] == pytest.approx(spread, rel=0.05)
            assert s["excursion_deg"] < 0.01 * spread
        else:
            assert s["excursion_deg"] == pytest.approx(spread, rel=0.02)
            assert s["band_thickness_deg"] < 0.05 * spread
        assert s["contact_load_max_N"] == pytest.approx(
            float(qs_dataset["contact_load"].sel(race=race).max())
        )
        assert s["max_pressure_max_GPa"] == pytest.approx(
            float(qs_dataset["max_pressure"].sel(race=race).max()) * 1e-9
        )
    # the fixture's analytic numbers: alpha = mean + ampl cos(psi) reaches mean + ampl at psi = 0
    assert summary["inner"]["contact_angle_max_deg"] == pytest.approx(23.0)
    assert summary["inner"]["contact_load_max_N"] == pytest.approx(250.0)
    assert summary["outer"]["contact_load_max_N"] == pytest.approx(255.0)
    expected_rpm = fixture_model.CAGE_RATIO * fixture_model.SHAFT_RPM
    assert summary["cage_speed_rpm"] == pytest.approx(expected_rpm)


def test_run_summary_of_pure_axial_load_has_no_band(qs_dataset):
    axial = qs_dataset.copy(deep=True)
    axial["contact_angle"][:] = [[21.0, 18.0]] * axial.sizes["ball"]
    axial["contact_load"][:] = [[140.0, 150.0]] * axial.sizes["ball"]
    summary = charts.run_summary(axial)
    assert summary["inner"]["excursion_deg"] == pytest.approx(0.0, abs=1e-12)
    assert summary["outer"]["contact_angle_min_deg"] == pytest.approx(18.0)
    assert summary["outer"]["contact_load_max_N"] == pytest.approx(150.0)


def test_run_summary_of_a_dynamic_run_uses_the_analysed_window(dynamic_dataset, fixture_model):
    """The same samples as the study table, the lessons and the CLI: the analysed window."""
    summary = charts.run_summary(dynamic_dataset)
    start = float(dynamic_dataset.racetrace.summary()["analysis_start_time"])
    window = dynamic_dataset.sel(time=dynamic_dataset["time"] >= start)
    assert 0 < window.sizes["time"] < dynamic_dataset.sizes["time"]
    for race in ("inner", "outer"):
        alpha = _loaded_values(window, "contact_angle", race)
        assert alpha.size > dynamic_dataset.sizes["ball"] * 10
        assert summary[race]["contact_angle_min_deg"] == alpha.min()
        assert summary[race]["contact_angle_max_deg"] == alpha.max()
        assert summary[race]["max_pressure_max_GPa"] == pytest.approx(1.0)
    expected_rpm = fixture_model.CAGE_RATIO * fixture_model.SHAFT_RPM
    assert summary["cage_speed_rpm"] == pytest.approx(expected_rpm)


def test_run_summary_takes_the_trajectory_metrics_from_the_solver(dynamic_dataset):
    """The table's excursion and thickness are the solver's own-frame values (one definition):
    the fixture's contact angle is fixed in space, so the outer race (stationary ring) draws a
    line and the inner race, seen on its turning ring, a band."""
    summary = charts.run_summary(dynamic_dataset)
    metrics = dynamic_dataset.racetrace.summary()
    for race in ("inner", "outer"):
        own = {"race": race, "frame": f"{race}_ring"}
        assert summary[race]["excursion_deg"] == float(metrics.trajectory_excursion.sel(own))
        assert summary[race]["band_thickness_deg"] == float(
            metrics.trajectory_band_thickness.sel(own)
        )
    assert summary["outer"]["band_thickness_deg"] < 0.1 * summary["inner"]["band_thickness_deg"]


def test_summary_rows_are_text_per_run_and_race(qs_dataset):
    summary = charts.run_summary(qs_dataset)
    empty = {race: dict.fromkeys(summary["inner"], float("nan")) for race in ("inner", "outer")}
    rows = charts.summary_rows({"A": summary, "B": {**empty, "cage_speed_rpm": float("nan")}})
    assert [r["key"] for r in rows] == ["A-inner", "A-outer", "B-inner", "B-outer"]
    assert rows[0]["contact_load_max_N"] == "250.0"
    assert rows[0]["contact_angle_max_deg"] == "23.00"
    assert rows[3]["excursion_deg"] == "-"
    assert rows[0]["band_thickness_deg"] == f"{summary['inner']['band_thickness_deg']:.3f}"
    assert rows[3]["band_thickness_deg"] == "-"
    assert rows[0]["energy_residual_pct"] == "-"  # nor an energy balance
    assert set(rows[0]) == {"key"} | {key for key, _, _ in charts.SUMMARY_COLUMNS}
    # both models' excursions share a column: each row names its model
    assert rows[0]["model"] == "quasi-static"
    assert rows[3]["model"] == "-"


def test_compare_overlays_have_both_runs_and_races(qs_dataset, dynamic_dataset, fixture_model):
    a, b = frame_source(qs_dataset), frame_source(dynamic_dataset)
    names = ["A inner", "A outer", "B inner", "B outer"]
    load = charts.compare_load_figure(a, b, max_points=200)
    angle = charts.compare_angle_figure(a, b)
    assert [t.name for t in load.data] == names
    assert [t.name for t in angle.data] == names
    # run A (quasi-static): one point per ball, sorted by azimuth, solid; run B dashed markers
    x = np.asarray(load.data[0].x, float)
    assert len(x) == qs_dataset.sizes["ball"] and np.all(np.diff(x) > 0)
    np.testing.assert_allclose(load.data[0].y, fixture_model.load_of_psi(np.radians(x)))
    assert load.data[0].line.dash == "solid" and load.data[2].marker.symbol == "x"
    # run B (dynamic): a decimated cloud of all its samples
    assert 100 <= len(load.data[2].x) <= 200
    psi_b = np.radians(np.asarray(angle.data[3].x, float))
    np.testing.assert_allclose(
        angle.data[3].y, fixture_model.alpha_of_psi(psi_b, "outer"), rtol=1e-9
    )
    # unloaded contacts have no contact angle but a zero load
    assert np.isnan(np.asarray(angle.data[0].y, float)).sum() == 3
    assert (np.asarray(load.data[0].y, float) == 0).sum() == 3
    assert {"compare_angle", "compare_load", "compare_summary"} <= set(charts.HELP)


# ---- layout in the narrow chart column ----------------------------------------------------------
def _figures(qs_dataset, dynamic_dataset):
    q, d = frame_source(qs_dataset), frame_source(dynamic_dataset)
    return {
        "contact_angle": charts.contact_angle_figure(q, (0, 2), current=3),
        "load_azimuth": charts.load_azimuth_figure(q, 0),
        "raceway_map": charts.raceway_map_figure(q),
        "ellipse": charts.ellipse_figure(q, 0),
        "comparison": charts.comparison_figure(qs_dataset, dynamic_dataset),
        "compare_runs": charts.side_by_side_raceway_maps(q, d),
        "compare_angle": charts.compare_angle_figure(q, d),
        "compare_load": charts.compare_load_figure(q, d),
    }


def test_legends_stand_below_the_plot_with_room_for_them(qs_dataset, dynamic_dataset):
    for name, fig in _figures(qs_dataset, dynamic_dataset).items():
        legend = fig.layout.legend
        # at the foot of the figure (container y = 0), under the x-axis title: never on a curve
        assert (legend.yref, legend.y, legend.yanchor) == ("container", 0.0, "bottom"), name
        rows = -(-sum(t.showlegend is not False for t in fig.data) // charts.ENTRIES_PER_ROW)
        assert fig.layout.margin.b >= charts._BOTTOM_PX + charts.LEGEND_ROW_PX * rows, name


def test_y_ranges_leave_room_above_and_below_the_curves(qs_dataset, dynamic_dataset):
    for name, fig in _figures(qs_dataset, dynamic_dataset).items():
        low, high = fig.layout.yaxis.range
        ys = np.concatenate([np.asarray(t.y, float) for t in fig.data if (t.yaxis or "y") == "y"])
        ys = ys[np.isfinite(ys)]
        room = 0.05 * (high - low)
        assert ys.max() <= high - room, name
        assert ys.min() >= low + room or (low == 0.0 and ys.min() >= 0.0), name


def test_a_nearly_constant_angle_gets_a_readable_axis():
    # 89.2885 degree +- 1e-4: plotly would zoom to ticks like 89.2885; at least 1 degree is shown
    low, high = charts.padded_range([89.2884, 89.2885, 89.2886], min_span=1.0)
    assert high - low == pytest.approx(1.0)
    assert (low + high) / 2 == pytest.approx(89.2885)
    assert charts.padded_range([np.nan], 1.0) is None


def test_ellipse_chart_pressure_axis_has_room_for_its_labels(qs_dataset):
    fig = charts.ellipse_figure(frame_source(qs_dataset), 0)
    assert fig.layout.yaxis2.side == "right" and fig.layout.margin.r >= 50
    assert fig.layout.yaxis2.range[1] > 1e-9 * float(qs_dataset["max_pressure"].max())


def test_compare_help_describes_the_drawing():
    for key in ("compare_angle", "compare_load"):
        assert "B: orange crosses" in charts.HELP[key] and "B dashed" not in charts.HELP[key]
    assert charts.RUN_STYLES["B"]["symbol"] == "x"


def test_compared_runs_have_distinct_colours(qs_dataset, dynamic_dataset):
    a, b = frame_source(qs_dataset), frame_source(dynamic_dataset)
    for fig in (charts.side_by_side_raceway_maps(a, b), charts.compare_angle_figure(a, b)):
        colours = {}
        for trace in fig.data:
            colours.setdefault(trace.name.split()[0], set()).add(trace.marker.color)
        assert set(colours) == {"A", "B"}
        assert not colours["A"] & colours["B"]


def test_raceway_map_marks_now_follows_balls_and_names_samples_on_hover(dynamic_dataset):
    src = frame_source(dynamic_dataset)
    whole = charts.raceway_map_figure(src, current=5)
    inner, outer, now_inner, now_outer = whole.data[:4]
    # the whole run by default, the contacts of frame 5 marked apart
    assert len(inner.x) == int(src.trace(0)[2].sum())
    f = src.frame(5)
    np.testing.assert_allclose(
        np.sort(now_inner.y), np.sort(np.degrees(f.contact_angle[f.loaded[:, 0], 0]))
    )
    assert "ball %{customdata[0]}" in inner.hovertemplate and "°" in inner.hovertemplate
    # one ball: only its samples
    one = charts.raceway_map_figure(src, balls=(3,))
    assert set(np.asarray(one.data[0].customdata)[:, 0].astype(int)) == {3}
    # coloured by ball: as many colours as balls; by load: the load values
    by_ball = charts.raceway_map_figure(src, colour="ball")
    assert len(set(by_ball.data[0].marker.color)) == src.ball_count
    # with its legend: one entry per ball in that ball's colour
    legend = by_ball.data[2:]
    assert [t.name for t in legend] == [f"ball {j}" for j in range(src.ball_count)]
    assert [t.marker.color for t in legend] == ball_colours(src.ball_count)
    by_load = charts.raceway_map_figure(src, colour="load")
    assert np.max(by_load.data[0].marker.color) > 0
    # leaving out the start-up: only samples from that time on
    late = charts.raceway_map_figure(src, start_time=float(src.times[src.n_frames // 2]))
    assert 0 < len(late.data[0].x) < 0.6 * len(inner.x)
    with pytest.raises(ValueError, match="colouring"):
        charts.raceway_map_figure(src, colour="rainbow")


def test_raceway_map_draws_the_shoulders_it_names_inside_its_range(qs_dataset):
    fig = charts.raceway_map_figure(frame_source(qs_dataset), shoulders=(0.9, 0.8))
    # the shoulder on the side of each track (positive contact angles here)
    lines = sorted(round(shape.y0, 3) for shape in fig.layout.shapes)
    assert lines == sorted(round(v, 3) for v in np.degrees([0.9, 0.8]))
    assert "inner +52°" in fig.layout.title.text and "outer +46°" in fig.layout.title.text
    lo, hi = fig.layout.yaxis.range
    assert all(lo < y < hi for y in lines)
    # and the tracks too
    for trace in fig.data[:2]:
        y = np.asarray(trace.y, float)
        assert lo <= np.nanmin(y) and np.nanmax(y) <= hi


def test_contact_angle_of_all_balls(dynamic_dataset):
    src = frame_source(dynamic_dataset)
    z = src.ball_count
    fig = charts.contact_angle_figure(src, balls=None, current=5)
    # one trace per race holding every ball, the balls separated by a gap
    assert [t.name for t in fig.data] == ["inner, all balls", "outer, all balls"]
    assert fig.data[0].line.color == charts.RACE_COLOURS[0]
    n = src.n_frames  # short fixture: not decimated
    for race, trace in enumerate(fig.data):
        y = np.asarray(trace.y, float).reshape(z, n + 1)
        assert np.isnan(y[:, -1]).all()  # the gap after each ball
        for j in range(z):
            alpha = np.degrees(src.contact["contact_angle"][:, j, race])
            ok = np.isfinite(y[j, :n])
            np.testing.assert_allclose(y[j, :n][ok], alpha[ok])
        assert list(np.asarray(trace.customdata).reshape(z, n + 1)[:, 0]) == list(range(z))


def test_all_balls_chart_stays_light(qs_dataset):
    src = frame_source(qs_dataset, revolutions=20, samples_per_revolution=500)  # 10 001 frames
    fig = charts.contact_angle_figure(src, balls=None)
    total = sum(len(t.x) for t in fig.data)
    assert total <= charts.ALL_BALLS_MAX_POINTS
    assert total > 0.5 * charts.ALL_BALLS_MAX_POINTS  # decimated, not thrown away
    with pytest.raises(ValueError, match="balls are 0 to 11"):
        charts.contact_angle_figure(src, balls=(12,))


def test_many_runs_compared_each_in_its_colour(qs_dataset, dynamic_dataset):
    q, d = frame_source(qs_dataset), frame_source(dynamic_dataset)
    runs = (q, d, q, d, q)
    maps = charts.side_by_side_raceway_maps(*runs)
    assert len(maps.data) == 10
    assert [a.text for a in maps.layout.annotations] == ["A (run on show)", "B", "C", "D", "E"]
    # three maps a row: the fourth and fifth runs on a second row, the same angle axis
    assert maps.data[6].xaxis == "x4" and maps.data[6].yaxis == "y4"
    assert maps.layout.yaxis4.range == maps.layout.yaxis.range
    angle = charts.compare_angle_figure(*runs)
    by_run = {}
    for trace in angle.data:
        by_run.setdefault(trace.name.split()[0], set()).add(trace.marker.color)
    assert list(by_run) == ["A", "B", "C", "D", "E"]
    seen = set()
    for colours in by_run.values():
        assert len(colours) == 2 and not colours & seen  # two shades, no run shares one
        seen |= colours
    assert charts.compare_chart_px(5) > charts.compare_chart_px(2)


def test_run_summary_sets_the_model_torque_beside_the_estimates(dynamic_dataset):
    """The comparison table's torque columns are the metrics (N mm); an estimate the run does not
    have is '-' (the CLI and the report say why)."""
    torque = np.full(dynamic_dataset.sizes["time"], 0.25)  # N m, constant over the run
    ds = dynamic_dataset.assign(
        friction_torque=("time", torque), friction_torque_palmgren=((), 0.125)
    )
    summary = charts.run_summary(ds)
    assert summary["friction_torque_Nmm"] == pytest.approx(250.0)
    assert summary["palmgren_torque_Nmm"] == pytest.approx(125.0)
    assert np.isnan(summary["skf_torque_Nmm"])
    (row, _) = charts.summary_rows({"A": summary})
    assert (row["friction_torque_Nmm"], row["palmgren_torque_Nmm"]) == ("250", "125")
    assert row["skf_torque_Nmm"] == "-"
    headers = [header for _, header, _ in charts.SUMMARY_COLUMNS]
    assert "friction torque (model), N mm" in headers and "Palmgren estimate, N mm" in headers


#: Every shipped study's results: of one bearing (per-race metrics) and of a bearing set
#: (spindle-pair-db-speed: the set's and each bearing's loads and stiffness).
SHIPPED_STUDIES = sorted(
    (Path(__file__).resolve().parents[2] / "assets" / "studies" / "results").glob("*.study.nc")
)
SET_STUDY = next(p for p in SHIPPED_STUDIES if p.name == "spindle-pair-db-speed.study.nc")


def _expected_traces(ds, metric: str) -> int:
    """The traces of the Studies chart of ``metric``: inner and outer race per model; for a set
    study, per variable of the metric's chart the set's line or one per bearing, per model."""
    if "bearing" not in ds.dims:
        return 2 * ds.sizes["model"]
    from app.set_charts import SET_STUDY_CHART_METRICS

    variables = next(row[3] for row in SET_STUDY_CHART_METRICS if row[0] == metric)
    lines = sum(ds.sizes["bearing"] if "bearing" in ds[v].dims else 1 for v, *_ in variables)
    return lines * ds.sizes["model"]


@pytest.mark.parametrize("study", SHIPPED_STUDIES, ids=lambda p: p.name.split(".")[0])
def test_study_chart_of_every_shipped_sweep_holds_its_points(study):
    """The Studies chart draws each sweep through its points: a trace per race and model (a set
    study: the set's and each bearing's), as many finite points as the sweep has, against the
    key the sweep varies (never a key the sweep leaves unset, all NaN), for every metric the
    chart offers."""
    import solver

    ds = solver.load_dataset(study)
    sweeps = np.asarray(ds["sweep"].values).astype(str)
    metrics = [item["value"] for item in study_figures.study_metric_items(ds)]
    if "bearing" not in ds.dims:
        metrics = ["band_width"]
    for sweep in dict.fromkeys(sweeps.tolist()):
        for metric in metrics:
            fig = study_figures.study_figure(ds, sweep, metric)
            assert len(fig.data) == _expected_traces(ds, metric), (sweep, metric)
            for trace in fig.data:
                x, y = np.asarray(trace.x, float), np.asarray(trace.y, float)
                finite = (np.isfinite(x) & np.isfinite(y)).sum()
                assert finite == (sweeps == sweep).sum(), (sweep, metric, trace.name)


def _trace(fig, name: str):
    return next(trace for trace in fig.data if trace.name == name)


def test_set_study_charts_one_line_per_bearing_and_the_set_as_the_physics_says():
    """The set study's charts: a line per bearing, named by it, and the set's line, in display
    units (N/µm, N m/mrad; the set's tilting stiffness apart from the bearings' own, a hundred
    times smaller); against speed the spring-preloaded pair keeps its rear bearing's
    100 N and softens, the fixed-position pair's bearings both carry more (rigid rings: the
    centrifugal forces raise the preload), the front one 100 N (the thrust) more than the rear;
    against the preload force the set and each bearing stiffen and each carries more; the
    outer contact angles fall below the inner ones at speed."""
    import solver

    ds = solver.load_dataset(SET_STUDY)
    bearings = [str(b) for b in ds["bearing"].values]
    assert [item["value"] for item in study_figures.study_metric_items(ds)] == [
        "axial_stiffness",
        "radial_stiffness",
        "tilt_stiffness",
        "bearing_tilt_stiffness",
        "bearing_load",
        "contact_angle",
    ]

    def y(fig, name):
        return np.asarray(_trace(fig, name).y, float)

    spring = "spring preload 100 N on the rear outer ring"
    fig = study_figures.study_figure(ds, spring, "bearing_load")
    axial = [f"{b}, axial" for b in bearings]
    assert [trace.name for trace in fig.data] == [*axial, *(f"{b}, radial" for b in bearings)]
    assert [trace.line.dash for trace in fig.data] == ["solid", "solid", "dash", "dash"]
    assert fig.layout.xaxis.title.text == "Inner ring speed [rpm]"
    assert list(_trace(fig, axial[0]).x) == [0.0, 6000.0, 12000.0, 18000.0, 24000.0, 30000.0]
    np.testing.assert_allclose(y(fig, axial[1]), 100.0, rtol=1e-6)
    np.testing.assert_allclose(y(fig, axial[0]) - y(fig, axial[1]), 100.0, rtol=1e-6)
    fig = study_figures.study_figure(ds, spring, "axial_stiffness")
    assert [trace.name for trace in fig.data] == ["set", *bearings]
    assert fig.layout.yaxis.title.text == "axial stiffness [N/µm]"
    k_set = y(fig, "set")
    assert np.all(np.diff(k_set) < 0.0), k_set  # the spring-preloaded set softens with speed
    assert 5.0 < k_set[0] < 100.0  # N/µm, not N/m

    for preload in ("light preload 100 N", "medium preload 300 N", "heavy preload 600 N"):
        fig = study_figures.study_figure(ds, f"fixed position, {preload}", "bearing_load")
        front, rear = y(fig, axial[0]), y(fig, axial[1])
        assert np.all(np.diff(rear) > 0.0) and np.all(np.diff(front) > 0.0), preload
        np.testing.assert_allclose(front - rear, 100.0, rtol=1e-6)
        fig = study_figures.study_figure(ds, f"fixed position, {preload}", "contact_angle")
        assert [trace.name for trace in fig.data] == [
            *(f"{b}, inner" for b in bearings),
            *(f"{b}, outer" for b in bearings),
        ]
        for b in bearings:  # at speed the outer contact angle falls below the inner one
            inner, outer = y(fig, f"{b}, inner"), y(fig, f"{b}, outer")
            assert outer[-1] < inner[-1] - 1.0 and np.all(np.diff(outer) < 0.0), (preload, b)

    for sweep in ("fixed-position preload at rest", "fixed-position preload at 24 000 rpm"):
        for metric, lines in (
            ("axial_stiffness", ["set", *bearings]),
            ("radial_stiffness", ["set", *bearings]),
            ("tilt_stiffness", ["set"]),
            ("bearing_tilt_stiffness", bearings),
        ):
            fig = study_figures.study_figure(ds, sweep, metric)
            assert fig.layout.xaxis.title.text == "preload force [N]"
            assert [trace.name for trace in fig.data] == lines
            assert list(fig.data[0].x) == [100.0, 200.0, 300.0, 450.0, 600.0]
            for name in lines:  # stiffer with every step of preload
                assert np.all(np.diff(y(fig, name)) > 0.0), (sweep, metric, name)
        fig = study_figures.study_figure(ds, sweep, "tilt_stiffness")
        assert fig.layout.yaxis.title.text == "set tilt stiffness [N m/mrad]"
        assert 200.0 < y(fig, "set")[0] < 5000.0  # N m/mrad, not N m/rad
        fig = study_figures.study_figure(ds, sweep, "bearing_load")
        for name in axial:
            assert np.all(np.diff(y(fig, name)) > 0.0), (sweep, name)


def _json(fig) -> dict:
    return json.loads(fig.to_json())


def test_a_following_chart_and_its_overlay_show_what_the_whole_figure_showed(dynamic_dataset):
    src = frame_source(dynamic_dataset)
    for i in (0, 7, src.n_frames - 1):
        # the charts against time: the figure without the current frame, the marker apart
        angle = charts.merge_overlay(
            _json(charts.contact_angle_figure(src, None)), charts.time_marker_overlay(src, i)
        )
        assert angle == _json(charts.contact_angle_figure(src, None, current=i))
        cage = charts.merge_overlay(
            _json(charts.cage_speed_figure(src, dynamic_dataset)),
            charts.time_marker_overlay(src, i),
        )
        assert cage == _json(charts.cage_speed_figure(src, dynamic_dataset, current=i))
        # the raceway map: the samples and the legend as before, the contacts now as circles of
        # the markers' size and colour at the markers' points
        for balls in (None, (1,)):
            options = {"balls": balls, "colour": "ball", "shoulders": (0.9, 0.8)}
            base = charts.raceway_map_figure(src, **options)
            shown = charts.merge_overlay(
                charts.raceway_map_base(src, **options),
                charts.current_contact_overlay(src, i, balls),
            )
            assert shown["data"][:-1] == _json(base)["data"]
            assert shown["layout"]["shapes"][: len(base.layout.shapes)] == [
                s.to_plotly_json() for s in base.layout.shapes
            ]
            legend = shown["data"][-1]
            assert (legend["name"], legend["showlegend"]) == ("contacts now", True)
            assert legend["marker"] == charts.NOW_MARKER and legend["x"] == [None]
            circles = shown["layout"]["shapes"][len(base.layout.shapes) :]
            now = charts.current_contact_traces(src, i, balls)
            points = [(x, y) for t in now for x, y in zip(t.x, t.y, strict=True)]
            assert len(circles) == len(points) > 0
            for circle, (x, y) in zip(circles, points, strict=True):
                assert circle["xanchor"] == pytest.approx(x) and circle["yanchor"] == pytest.approx(
                    y
                )
                assert circle["templateitemname"] == charts.NOW_SHAPE and circle["visible"]
            # each places the figure's template shape: an open circle of the marker's size in
            # pixels, colour and line
            (shape,) = shown["layout"]["template"]["layout"]["shapes"]
            assert (shape["name"], shape["type"], shape["visible"]) == (
                charts.NOW_SHAPE,
                "circle",
                False,
            )
            assert (shape["xsizemode"], shape["ysizemode"]) == ("pixel", "pixel")
            assert shape["x1"] - shape["x0"] == now[0].marker.size  # the marker's diameter
            assert shape["y1"] - shape["y0"] == now[0].marker.size
            assert shape["line"] == {
                "color": now[0].marker.color,
                "width": now[0].marker.line.width,
            }
