"""The Studies chart of a study Dataset, single bearing or bearing set: which metrics it offers and
its figure. A study of bearing-set points (a ``bearing`` dimension) is drawn by
:mod:`app.set_charts` (the set's line and one per bearing), any other by
:func:`app.charts.race_study_figure` (inner and outer race side by side)."""

from __future__ import annotations

from .charts import STUDY_CHART_METRICS, race_study_figure
from .set_charts import SET_STUDY_CHART_METRICS, set_study_figure


def _is_set_study(ds) -> bool:
    return ds is not None and "bearing" in ds.dims


def study_metric_items(ds) -> list[dict]:
    """The metrics the Studies chart offers for the study Dataset ``ds`` (``{"title", "value"}``):
    :data:`app.charts.STUDY_CHART_METRICS`, or for a set study
    :data:`viz.set_study.SET_STUDY_CHART_METRICS`."""
    rows = SET_STUDY_CHART_METRICS if _is_set_study(ds) else STUDY_CHART_METRICS
    return [{"title": row[1], "value": row[0]} for row in rows]


def study_figure(ds, sweep: str | None, metric: str):
    """Plotly figure of ``metric`` against the sweep ``sweep`` of the study Dataset ``ds``."""
    if _is_set_study(ds):
        return set_study_figure(ds, sweep, metric)
    return race_study_figure(ds, sweep, metric)
