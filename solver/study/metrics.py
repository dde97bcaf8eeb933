"""The metrics a study keeps per point and model: rows of the metrics table.

:data:`POINT_METRICS` names them; their dimensions, units, long names and meanings are those of
:data:`solver.results.metrics.METRICS`, and :func:`point_metrics` reads their values from
``ds.racetrace.metric(name)`` (each race in its own ring's frame; over the analysed window of a
dynamic result, the whole snapshot of a quasi-static one, or its solutions over one revolution for
a misalignment turning with the inner ring: :func:`solver.quasistatic_answer`).
"""

from __future__ import annotations

import xarray as xr

from solver.results.metrics import RACES, metric_row

#: The table's metrics a study keeps, in the order of its table and file.
STUDY_METRIC_NAMES = (
    "excursion",
    "excursion_arc",
    "band_thickness",
    "band_thickness_arc",
    "band_width",
    "mean_contact_angle",
    "peak_pressure",
    "largest_load",
    "cage_slip",
    "settling_time",
    "settled",
)

#: name -> (dims beyond point/model, units, long name, description), from the metrics table.
POINT_METRICS: dict[str, tuple[tuple[str, ...], str, str, str]] = {
    name: (row.dims, row.units, row.long_name, row.meaning)
    for name, row in ((name, metric_row(name)) for name in STUDY_METRIC_NAMES)
}


def point_metrics(ds: xr.Dataset) -> dict[str, object]:
    """The :data:`POINT_METRICS` of one result: ``{name: float or {race: float}}``."""
    out: dict[str, object] = {}
    for name, (dims, *_rest) in POINT_METRICS.items():
        value = ds.racetrace.metric(name)
        if dims:
            out[name] = {race: float(value.sel(race=race)) for race in RACES}
        else:
            out[name] = float(value)
    return out


__all__ = ["POINT_METRICS", "STUDY_METRIC_NAMES", "point_metrics"]
