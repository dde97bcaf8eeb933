"""Chart figures carry the result's data in display units."""

from __future__ import annotations

import numpy as np
import pytest

from app import charts
from app.frames import frame_source


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
    fig = charts.side_by_side_raceway_maps(a, b, "quasi-static", "dynamic")
    assert len(fig.data) == 4
    assert [t.xaxis for t in fig.data] == ["x", "x", "x2", "x2"]
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
    summary = charts.run_summary(frame_source(qs_dataset), qs_dataset)
    for race in ("inner", "outer"):
        alpha = _loaded_values(qs_dataset, "contact_angle", race)  # degree, per ball
        assert len(alpha) == 9  # three balls opposite the load zone are unloaded
        s = summary[race]
        assert s["contact_angle_min_deg"] == pytest.approx(alpha.min())
        assert s["contact_angle_max_deg"] == pytest.approx(alpha.max())
        assert s["band_width_deg"] == pytest.approx(np.ptp(alpha))
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
    summary = charts.run_summary(frame_source(axial), axial)
    assert summary["inner"]["band_width_deg"] == pytest.approx(0.0, abs=1e-12)
    assert summary["outer"]["contact_angle_min_deg"] == pytest.approx(18.0)
    assert summary["outer"]["contact_load_max_N"] == pytest.approx(150.0)


def test_run_summary_of_a_dynamic_run_uses_every_sample(dynamic_dataset, fixture_model):
    summary = charts.run_summary(frame_source(dynamic_dataset), dynamic_dataset)
    for race in ("inner", "outer"):
        alpha = _loaded_values(dynamic_dataset, "contact_angle", race)
        assert alpha.size > dynamic_dataset.sizes["ball"] * 10
        assert summary[race]["band_width_deg"] == pytest.approx(np.ptp(alpha))
        assert summary[race]["contact_angle_min_deg"] == pytest.approx(alpha.min())
        assert summary[race]["max_pressure_max_GPa"] == pytest.approx(1.0)
    expected_rpm = fixture_model.CAGE_RATIO * fixture_model.SHAFT_RPM
    assert summary["cage_speed_rpm"] == pytest.approx(expected_rpm)


def test_summary_rows_are_text_per_run_and_race(qs_dataset):
    summary = charts.run_summary(frame_source(qs_dataset), qs_dataset)
    empty = {race: dict.fromkeys(summary["inner"], float("nan")) for race in ("inner", "outer")}
    rows = charts.summary_rows({"A": summary, "B": {**empty, "cage_speed_rpm": float("nan")}})
    assert [r["key"] for r in rows] == ["A-inner", "A-outer", "B-inner", "B-outer"]
    assert rows[0]["contact_load_max_N"] == "250.0"
    assert rows[0]["contact_angle_max_deg"] == "23.00"
    assert rows[3]["band_width_deg"] == "-"
    assert set(rows[0]) == {"key"} | {key for key, _, _ in charts.SUMMARY_COLUMNS}


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
