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
