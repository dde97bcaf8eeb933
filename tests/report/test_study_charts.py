"""The study report's metric charts hold data: for every sweep of every shipped study, a chart per
metric whose lines pass through every point of the sweep (finite x and y, one line per race and
model; for a bearing-set study the set's line and one per bearing), against the key the sweep
varies."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("bokeh")
pytest.importorskip("panel")

import solver  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
#: Every shipped study's results: of one bearing (per-race metric charts) and of a bearing set
#: (spindle-pair-db-speed: the set's and each bearing's loads and stiffness).
SHIPPED = sorted((ROOT / "assets" / "studies" / "results").glob("*.study.nc"))
SET_STUDY = ROOT / "assets" / "studies" / "results" / "spindle-pair-db-speed.study.nc"


def _finite_points(renderer) -> int:
    data = renderer.data_source.data
    x, y = np.asarray(data["x"], float), np.asarray(data["y"], float)
    return int((np.isfinite(x) & np.isfinite(y)).sum())


def test_the_shipped_studies_are_found():
    assert len(SHIPPED) >= 3 and SET_STUDY in SHIPPED


def _chart_metrics(ds):
    from report.build import SET_STUDY_CHART_METRICS, STUDY_CHART_METRICS

    return SET_STUDY_CHART_METRICS if "bearing" in ds.dims else STUDY_CHART_METRICS


def _charts(ds):
    """[(sweep, metric row, figure)] of the study report's charts, in page order."""
    from report.build import study_sections

    metrics = _chart_metrics(ds)
    sections, _ = study_sections(ds)
    figures = [pane.object for s in sections for pane in getattr(s, "objects", None) or []]
    sweeps = list(dict.fromkeys(np.asarray(ds["sweep"].values).astype(str).tolist()))
    assert len(figures) == len(sweeps) * len(metrics)
    n = len(metrics)
    return [(sweeps[k // n], metrics[k % n], fig) for k, fig in enumerate(figures)]


def _expected_lines(ds, row, rows):
    """Finite points of each renderer (a line and its markers) of the chart of metric ``row``:
    per model and race the metric's; for a set study per model and variable of the row, the
    set's or each bearing's."""
    expected = []
    for model in ds["model"].values:
        if "bearing" in ds.dims:
            for variable, *_ in row[3]:
                values = ds[variable].sel(model=model)
                per_line = (
                    [values.sel(bearing=b).values for b in ds["bearing"].values]
                    if "bearing" in values.dims
                    else [values.values]
                )
                for y in per_line:
                    expected += [int(np.isfinite(np.asarray(y, float)[rows]).sum())] * 2
        else:
            for race in ("inner", "outer"):
                y = ds[row[0]].sel(model=model, race=race).values[rows]
                expected += [int(np.isfinite(y).sum())] * 2  # its line and its markers
    return expected


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_sweep_is_charted_through_its_points(path):
    ds = solver.load_dataset(path)
    for sweep, row, fig in _charts(ds):
        assert fig.title.text == f"{row[1]} ({sweep})"
        rows = np.asarray(ds["sweep"].values).astype(str) == sweep
        expected = _expected_lines(ds, row, rows)
        assert min(expected) >= 2, (sweep, row[0])
        assert [_finite_points(r) for r in fig.renderers] == expected, (sweep, row[0])


def test_set_study_charts_a_line_per_bearing_and_the_sets_in_display_units():
    """The set study's report charts: the set's line and a line per bearing, in the legend by
    name, stiffness in N/µm and N m/mrad; against the preload force every stiffness rises, and
    against speed the spring-preloaded set softens while its rear bearing keeps 100 N."""
    ds = solver.load_dataset(SET_STUDY)
    bearings = [str(b) for b in ds["bearing"].values]
    charts = {(sweep, row[0]): fig for sweep, row, fig in _charts(ds)}

    def lines(fig):
        """{legend label: y of its line}."""
        out = {}
        for item in fig.legend[0].items:
            renderer = item.renderers[0]
            out[item.label["value"]] = np.asarray(renderer.data_source.data["y"], float)
        return out

    for sweep in ("fixed-position preload at rest", "fixed-position preload at 24 000 rpm"):
        for metric, unit, names in (
            ("axial_stiffness", "N/µm", ["set", *bearings]),
            ("radial_stiffness", "N/µm", ["set", *bearings]),
            ("tilt_stiffness", "N m/mrad", ["set"]),
            ("bearing_tilt_stiffness", "N m/mrad", bearings),
        ):
            fig = charts[(sweep, metric)]
            assert fig.xaxis[0].axis_label == "preload force [N]"
            assert fig.yaxis[0].axis_label.endswith(f"[{unit}]")
            drawn = lines(fig)
            assert list(drawn) == names
            for name, y in drawn.items():
                assert y.size == 5 and np.all(np.diff(y) > 0.0), (sweep, metric, name)
    spring = "spring preload 100 N on the rear outer ring"
    load = lines(charts[(spring, "bearing_load")])
    assert list(load) == [f"{b}, {kind}" for kind in ("axial", "radial") for b in bearings]
    np.testing.assert_allclose(load[f"{bearings[1]}, axial"], 100.0, rtol=1e-6)
    k_set = lines(charts[(spring, "axial_stiffness")])["set"]
    assert np.all(np.diff(k_set) < 0.0) and 5.0 < k_set[0] < 100.0  # N/µm


def test_the_x_axis_names_the_varied_key_and_its_unit():
    ds = solver.load_dataset(ROOT / "assets" / "studies" / "results" / "seed-spindle.study.nc")
    labels = {sweep: fig.xaxis[0].axis_label for sweep, _row, fig in _charts(ds)}
    assert labels == {
        "radial load": "Radial load [N]",
        "misalignment fixed in space": "Misalignment [deg]",
        "misalignment turning with the ring": "Misalignment [deg]",
        "speed, 300 N radial": "Inner ring speed [rpm]",
    }
