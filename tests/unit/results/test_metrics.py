"""The metrics table (solver.results.metrics): its values against numbers computed here from the
Dataset, the one loaded-contact mask, the dimensions it keeps, the accessor's cache, and that the
table, docs/results-schema.md ("Metrics") and the views agree."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import solver
from solver.results import metrics as table
from solver.results.accessor import RacetraceAccessor
from solver.results.metrics import METRICS, loaded_mask

ROOT = Path(__file__).resolve().parents[3]
SCHEMA = ROOT / "docs" / "results-schema.md"
LESSON_RESULTS = ROOT / "assets" / "lessons" / "results"


@pytest.fixture(scope="module")
def quasistatic():
    return solver.load_dataset(LESSON_RESULTS / "02-speed--speed.nc")


@pytest.fixture(scope="module")
def dynamic():
    return solver.load_dataset(LESSON_RESULTS / "03-radial-load--radial.nc")


def _window(ds):
    start = float(ds["analysis_start_time"])
    return ds.sel(time=ds["time"] >= start)


# ---- the loaded-contact mask ---------------------------------------------------------------------
def test_a_loaded_contact_carries_load_and_has_a_contact_angle():
    load = np.array([100.0, 0.0, np.nan, 50.0, -1.0, np.inf])
    angle = np.array([20.0, 20.0, 20.0, np.nan, 20.0, 15.0])
    np.testing.assert_array_equal(
        loaded_mask(load, angle), [True, False, False, False, False, True]
    )
    da = loaded_mask(xr.DataArray(load, dims="ball"), xr.DataArray(angle, dims="ball"))
    assert da.dims == ("ball",) and int(da.sum()) == 2
    assert solver.loaded_mask is loaded_mask


# ---- values against the Dataset ----------------------------------------------------------------
def test_quasistatic_statistics_are_over_the_loaded_balls(quasistatic):
    ds = quasistatic.copy(deep=True)
    ds["contact_load"][0, 0] = 0.0  # ball 0 unloaded on the inner race
    m = ds.racetrace
    angle = ds["contact_angle"].sel(race="inner").values[1:]
    assert float(m.metric("mean_contact_angle").sel(race="inner")) == angle.mean()
    assert float(m.metric("min_contact_angle").sel(race="inner")) == angle.min()
    assert float(m.metric("smallest_load").sel(race="inner")) == 0.0
    assert float(m.metric("loaded_balls").sel(race="inner")) == ds.sizes["ball"] - 1
    pressure = ds["max_pressure"].sel(race="outer").values
    assert float(m.metric("peak_pressure").sel(race="outer")) == pressure.max()
    assert float(m.metric("mean_cage_speed")) == float(ds["cage_speed"])
    assert math.isnan(float(m.metric("shaft_revolutions")))
    assert math.isnan(float(m.metric("settled")))


def test_dynamic_statistics_are_over_the_analysed_window(dynamic):
    window = _window(dynamic)
    assert 0 < window.sizes["time"] < dynamic.sizes["time"]
    metric = dynamic.racetrace.metric
    for race in ("inner", "outer"):
        w = window.sel(race=race)
        loaded = (w["contact_load"].values > 0) & np.isfinite(w["contact_angle"].values)
        angle = np.asarray(w["contact_angle"].values, float)[loaded]
        assert float(metric("mean_contact_angle").sel(race=race)) == angle.mean()
        assert float(metric("max_contact_angle").sel(race=race)) == angle.max()
        load = np.asarray(w["contact_load"].values, float)
        assert float(metric("largest_load").sel(race=race)) == load.max()
        pressure = np.asarray(w["max_pressure"].values, float)[loaded]
        assert float(metric("peak_pressure").sel(race=race)) == pressure.max()
        summary = dynamic.racetrace.summary()
        own = {"race": race, "frame": f"{race}_ring"}
        assert float(metric("excursion").sel(race=race)) == float(
            summary["trajectory_excursion"].sel(own)
        )
    # cage slip by hand: the epicyclic speed at the free contact angle, outer ring at rest
    omega = float(dynamic.coords["inner_ring_speed"])
    gamma = (
        float(dynamic.coords["ball_diameter"])
        * math.cos(math.radians(float(dynamic.coords["free_contact_angle"])))
        / float(dynamic.coords["pitch_diameter"])
    )
    cage = np.asarray(window["cage_speed"].values, float).mean()
    assert float(metric("cage_slip")) == pytest.approx(1 - cage / (0.5 * (1 - gamma) * omega))
    assert float(metric("settled")) == 1.0
    period = 2 * math.pi / omega
    assert float(metric("shaft_revolutions")) == pytest.approx(float(dynamic["time"][-1]) / period)


def test_every_metric_has_its_declared_dims_and_units(quasistatic, dynamic):
    for ds in (quasistatic, dynamic):
        values = ds.racetrace.metrics()
        assert list(values.data_vars) == list(METRICS)
        for name, row in METRICS.items():
            assert values[name].dims == row.dims, name
            assert values[name].attrs["units"] == row.units, name
            assert values[name].attrs["description"] == row.meaning, name


def test_stacking_dimensions_are_kept(dynamic):
    """Two results along a new dimension (a set of bearings, a sweep): one value per element,
    each that element's own (its own analysed window)."""
    late = dynamic.copy(deep=True)
    late["analysis_start_time"] = late["time"][-40]  # a shorter window for the second element
    stacked = xr.concat([dynamic, late], dim="bearing")
    for name in ("mean_contact_angle", "peak_pressure", "mean_cage_speed", "excursion"):
        both = stacked.racetrace.metric(name)
        assert "bearing" in both.dims, name
        for k, element in enumerate((dynamic, late)):
            expected = table.metrics_table(element)[name]
            xr.testing.assert_identical(
                both.isel(bearing=k, drop=True).transpose(*expected.dims), expected
            )
    angle = stacked.racetrace.metric("mean_contact_angle")
    assert float(angle.isel(bearing=0, race=0)) != float(angle.isel(bearing=1, race=0))


def test_the_accessor_computes_each_metric_once(quasistatic, monkeypatch):
    calls = []
    compute = table.compute_metric

    def counted(window, name):
        calls.append(name)
        return compute(window, name)

    monkeypatch.setattr("solver.results.accessor.compute_metric", counted)
    ds = quasistatic.copy()
    first = ds.racetrace.metric("peak_pressure")
    assert ds.racetrace.metric("peak_pressure") is first
    ds.racetrace.metrics()
    ds.racetrace.metrics()
    assert sorted(calls) == sorted(METRICS)
    with pytest.raises(KeyError, match="known metrics"):
        ds.racetrace.metric("peak_presure")


# ---- the table, the docs and the views agree --------------------------------------------------
def _documented_rows() -> dict[str, tuple[str, str, str]]:
    text = SCHEMA.read_text(encoding="utf-8")
    section = text.split("\n## Metrics\n", 1)[1].split("\n## ", 1)[0]
    rows = {}
    for line in section.splitlines():
        match = re.fullmatch(r"\| `([a-z_0-9]+)` \| \(([a-z_, ]*)\) \| ([^|]+) \| (.+) \|", line)
        if match:
            name, dims, units, meaning = match.groups()
            rows[name] = (dims, units.strip(), meaning.strip())
    return rows


def test_the_schema_document_lists_the_metrics_table():
    documented = _documented_rows()
    declared = {n: (", ".join(r.dims), r.units, r.meaning) for n, r in METRICS.items()}
    assert list(documented) == list(declared), (
        "docs/results-schema.md, section Metrics, lists other metrics than the table; "
        "its rows are solver.results.metrics.markdown_table():\n" + table.markdown_table()
    )
    for name, (dims, units, meaning) in declared.items():
        assert documented[name][1] == units, f"{name}: units {documented[name][1]} in the docs"
        assert documented[name] == (dims, units, meaning), name


def _asked_for(monkeypatch) -> set[str]:
    asked: set[str] = set()
    metric = RacetraceAccessor.metric

    def spy(self, name):
        asked.add(name)
        return metric(self, name)

    monkeypatch.setattr(RacetraceAccessor, "metric", spy)
    return asked


def test_every_metric_a_view_asks_for_is_in_the_table(quasistatic, dynamic, monkeypatch):
    pytest.importorskip("plotly")
    from app.charts import run_summary
    from app.lessons.values import lesson_values
    from racetrace import metrics as cli
    from racetrace.commands.quasistatic import summary as quasistatic_json
    from report.build import STUDY_CHART_METRICS, _summary_rows
    from solver.study.metrics import POINT_METRICS, point_metrics

    asked = _asked_for(monkeypatch)
    for ds in (quasistatic.copy(), dynamic.copy()):
        lesson_values(ds)
        run_summary(ds)
        point_metrics(ds)
        _summary_rows(ds)
        cli.metrics_json(ds), cli.metrics_text(ds), cli.life_json(ds), cli.life_text(ds)
    quasistatic_json(quasistatic.copy())
    unknown = sorted(asked - set(METRICS))
    assert not unknown, f"views ask for metrics the table does not have: {unknown}"
    # the views' own lists of names
    declared = {name for _, name in cli.RACE_METRICS} | {n for _, n, _ in cli.LIFE_VALUES}
    declared |= set(POINT_METRICS) | {name for name, _, _ in STUDY_CHART_METRICS}
    assert declared <= set(METRICS), sorted(declared - set(METRICS))
    assert {"mean_contact_angle", "peak_pressure", "excursion", "cage_slip"} <= asked
