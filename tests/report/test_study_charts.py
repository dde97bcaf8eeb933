"""The study report's metric charts hold data: for every sweep of every shipped study, a chart per
metric whose lines pass through every point of the sweep (finite x and y, one line per race and
model), against the key the sweep varies."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("bokeh")
pytest.importorskip("panel")

import solver  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
#: The shipped studies of one bearing (a bearing-set study, spindle-pair-db-speed, keeps the set's
#: loads and stiffness per bearing instead of the per-race metrics these charts draw).
SHIPPED = [
    path
    for path in sorted((ROOT / "assets" / "studies" / "results").glob("*.study.nc"))
    if not path.name.startswith("spindle-pair-")
]


def _finite_points(renderer) -> int:
    data = renderer.data_source.data
    x, y = np.asarray(data["x"], float), np.asarray(data["y"], float)
    return int((np.isfinite(x) & np.isfinite(y)).sum())


def test_the_shipped_studies_are_found():
    assert len(SHIPPED) >= 2


def _charts(ds):
    """[(sweep, metric variable, label, figure)] of the study report's charts, in page order."""
    from report.build import STUDY_CHART_METRICS, study_sections

    sections, _ = study_sections(ds)
    figures = [pane.object for s in sections for pane in getattr(s, "objects", None) or []]
    sweeps = list(dict.fromkeys(np.asarray(ds["sweep"].values).astype(str).tolist()))
    assert len(figures) == len(sweeps) * len(STUDY_CHART_METRICS)
    n = len(STUDY_CHART_METRICS)
    return [(sweeps[k // n], *STUDY_CHART_METRICS[k % n][:2], fig) for k, fig in enumerate(figures)]


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_sweep_is_charted_through_its_points(path):
    ds = solver.load_dataset(path)
    for sweep, var, label, fig in _charts(ds):
        assert fig.title.text == f"{label} ({sweep})"
        rows = np.asarray(ds["sweep"].values).astype(str) == sweep
        expected = []
        for model in ds["model"].values:
            for race in ("inner", "outer"):
                y = ds[var].sel(model=model, race=race).values[rows]
                expected += [int(np.isfinite(y).sum())] * 2  # its line and its markers
        assert min(expected) >= 2, (sweep, var)
        assert [_finite_points(r) for r in fig.renderers] == expected, (sweep, var)


def test_the_x_axis_names_the_varied_key_and_its_unit():
    ds = solver.load_dataset(ROOT / "assets" / "studies" / "results" / "seed-spindle.study.nc")
    labels = {sweep: fig.xaxis[0].axis_label for sweep, _var, _label, fig in _charts(ds)}
    assert labels == {
        "radial load": "Radial load [N]",
        "misalignment fixed in space": "Misalignment [deg]",
        "misalignment turning with the ring": "Misalignment [deg]",
        "speed, 300 N radial": "Inner ring speed [rpm]",
    }
