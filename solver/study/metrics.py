"""The metrics a study keeps per point and model: rows of the metrics table.

:data:`POINT_METRICS` names them; their dimensions, units, long names and meanings are those of
:data:`solver.results.metrics.METRICS`, and :func:`point_metrics` reads their values from
``ds.racetrace.metric(name)`` (each race in its own ring's frame; over the analysed window of a
dynamic result, the whole snapshot of a quasi-static one, or its solutions over one revolution for
a misalignment turning with the inner ring: :func:`solver.quasistatic_answer`).

A point of a bearing-set case (quasi-static model only) keeps instead the set's values of
:data:`SET_STUDY_METRIC_NAMES` (:func:`set_point_metrics`): the set's stiffness and each bearing's
loads, whose dimensions, units and meanings are those of the set's Dataset
(:data:`solver.models.quasistatic.set_result.SET_VARIABLES`, results-schema.md, "Bearing sets").
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


#: The set's variables a study keeps for a bearing-set point, in the order of its file.
SET_STUDY_METRIC_NAMES = (
    "bearing_axial_load",
    "bearing_radial_load",
    "axial_stiffness",
    "radial_stiffness",
    "tilt_stiffness",
    "bearing_axial_stiffness",
    "bearing_radial_stiffness",
    "bearing_tilt_stiffness",
    "bearing_inner_contact_angle",
    "bearing_outer_contact_angle",
)


def set_point_metric_table() -> dict[str, tuple[tuple[str, ...], str, str, str]]:
    """name -> (dims beyond point/model: () or ("bearing",), units, long name, description) of
    :data:`SET_STUDY_METRIC_NAMES`, from the set's variables (imported when a study reads them)."""
    from solver.models.quasistatic.set_result import SET_VARIABLES

    table = {}
    for name in SET_STUDY_METRIC_NAMES:
        spec = SET_VARIABLES[name]
        table[name] = (spec.dims, spec.units, spec.long_name, spec.description)
    return table


def set_point_metrics(ds: xr.Dataset) -> dict[str, object]:
    """The :data:`SET_STUDY_METRIC_NAMES` of a bearing set's Dataset: ``{name: float or
    {bearing name: float}}``."""
    out: dict[str, object] = {}
    names = [str(b) for b in ds["bearing"].values]
    for name in SET_STUDY_METRIC_NAMES:
        values = ds[name].values
        if ds[name].dims == ("bearing",):
            out[name] = {b: float(v) for b, v in zip(names, values, strict=True)}
        else:
            out[name] = float(values)
    return out


def run_metrics(ds: xr.Dataset) -> dict[str, object]:
    """The metrics a study keeps of one result: :func:`set_point_metrics` for a bearing set's
    Dataset (it has a ``bearing`` dimension), else :func:`point_metrics`."""
    if "bearing" in ds.dims:
        return set_point_metrics(ds)
    return point_metrics(ds)


__all__ = [
    "POINT_METRICS",
    "SET_STUDY_METRIC_NAMES",
    "STUDY_METRIC_NAMES",
    "point_metrics",
    "run_metrics",
    "set_point_metric_table",
    "set_point_metrics",
]
