"""Bokeh charts of the report: raceway maps, contact angle and load, study metrics.

Each chart embeds its data in the page, so long runs are decimated: at most
:data:`MAX_MAP_POINTS` contact samples per raceway map and :data:`MAX_TIME_POINTS` samples per
time series (an even stride; the caption says so).
"""

from __future__ import annotations

import math

import numpy as np

from solver import loaded_mask
from viz.study_axes import key_label

from .units import ordinal

MAX_MAP_POINTS = 20_000
MAX_TIME_POINTS = 2_000
#: At most this many samples on a raceway map are drawn as large markers (fine dots above).
FEW_MAP_POINTS = 500
RACE_COLOURS = {"inner": "#1f77b4", "outer": "#d62728"}
MODEL_DASH = {"quasistatic": "dashed", "dynamic": "solid"}
PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")


def _figure(title: str, x_label: str, y_label: str, **kwargs):
    from bokeh.plotting import figure

    fig = figure(
        title=title,
        x_axis_label=x_label,
        y_axis_label=y_label,
        height=kwargs.pop("height", 300),
        sizing_mode="stretch_width",
        tools="pan,wheel_zoom,box_zoom,reset,hover,save",
        **kwargs,
    )
    fig.toolbar.logo = None
    return fig


def _stride(n: int, limit: int) -> int:
    return max(1, math.ceil(n / limit))


def raceway_map(ds, race: str):
    """Contact angle against raceway azimuth in the race's own ring frame (every loaded contact
    sample of the run, decimated), with the ellipse's edges across the groove (contact angle
    ± the ellipse's angular half-width a / r) and the shoulder's groove angle, so that how close
    the track runs to the land can be read off; and a note on decimation."""
    from solver import geometry_from_result, shoulder_angle

    angle = np.asarray(ds["contact_angle"].sel(race=race).values, float).ravel()
    azimuth = np.asarray(ds["raceway_azimuth"].sel(race=race).values, float).ravel()
    load = np.asarray(ds["contact_load"].sel(race=race).values, float).ravel()
    semi_major = np.asarray(ds["ellipse_semi_major"].sel(race=race).values, float).ravel()
    groove_radius = float(ds["groove_radius"].sel(race=race))
    ok = loaded_mask(load, angle) & np.isfinite(azimuth)
    angle, azimuth, semi_major = angle[ok], azimuth[ok], semi_major[ok]
    half_width = np.degrees(semi_major / groove_radius)
    step = _stride(angle.size, MAX_MAP_POINTS)
    # a few samples (a quasi-static snapshot: one per ball) as markers that can be seen; many (a
    # dynamic run) as fine, translucent dots, so that the track's density shows
    few = angle[::step].size <= FEW_MAP_POINTS
    centre_size, centre_alpha = (7, 0.9) if few else (2, 0.4)
    edge_size, edge_alpha = (4, 0.6) if few else (1, 0.25)
    shoulder = math.degrees(shoulder_angle(geometry_from_result(ds), race))
    title = f"{race} raceway map (own ring frame)"
    if math.isfinite(shoulder):
        title += f": shoulder at {shoulder:.1f} deg"
    fig = _figure(title, f"{race} raceway azimuth, own ring frame [deg]", "contact angle [deg]")
    for sign, label in ((1.0, "ellipse edges (α ± a/r)"), (-1.0, "ellipse edges (α ± a/r)")):
        fig.scatter(
            azimuth[::step],
            angle[::step] + sign * half_width[::step],
            size=edge_size,
            alpha=edge_alpha,
            color="#7f7f7f",
            legend_label=label,
        )
    fig.scatter(
        azimuth[::step],
        angle[::step],
        size=centre_size,
        alpha=centre_alpha,
        color=RACE_COLOURS[race],
        legend_label=f"{race} contacts (ellipse centre)",
    )
    if math.isfinite(shoulder):  # a line (not a span): the axis range takes it in
        fig.line(
            [0.0, 360.0],
            [shoulder, shoulder],
            color="black",
            line_dash="dashed",
            legend_label=f"shoulder ({shoulder:.1f} deg)",
        )
    fig.x_range.start, fig.x_range.end = 0.0, 360.0
    _legend_outside(fig)
    note = (
        f"{race} raceway map: {angle.size} loaded contact samples, every {ordinal(step)} shown"
        if step > 1
        else ""
    )
    return fig, note


def _legend_outside(fig) -> None:
    """Move the figure's legend below the plot area, so that it covers no data."""
    legend = fig.legend[0]
    fig.legend.location = "center"
    fig.legend.orientation = "horizontal"
    fig.legend.click_policy = "hide"
    fig.legend.label_text_font_size = "10px"
    fig.legend.spacing = 14  # px between items: a line sample is not read as the last label's
    fig.add_layout(legend, "below")


def contact_series(ds, name: str, label: str, scale: float = 1.0):
    """A contact variable per race: against time for a dynamic result (mean over the loaded
    balls, and ball 1; loaded as :func:`solver.loaded_mask` defines it), against ball azimuth for
    a quasi-static one."""
    if "time" in ds.dims:
        t = np.asarray(ds["time"].values, float) * 1e3
        step = _stride(t.size, MAX_TIME_POINTS)
        fig = _figure(f"{label} against time", "time [ms]", label)
        for race in ("inner", "outer"):
            values, load, angle = (
                np.asarray(ds[v].sel(race=race).transpose("time", "ball").values, float)
                for v in (name, "contact_load", "contact_angle")
            )
            masked = np.where(loaded_mask(load, angle), values, np.nan) * scale
            with np.errstate(all="ignore"):
                mean = np.nanmean(masked, axis=1)
            fig.line(
                t[::step], mean[::step], color=RACE_COLOURS[race], legend_label=f"{race}, mean"
            )
            fig.line(
                t[::step],
                masked[::step, 0],
                color=RACE_COLOURS[race],
                alpha=0.5,
                line_dash="dotted",
                legend_label=f"{race}, ball 1",
            )
        note = f"{label}: {t.size} time samples, every {ordinal(step)} shown" if step > 1 else ""
    else:
        psi = np.asarray(ds["ball_azimuth"].values, float)
        order = np.argsort(psi)
        fig = _figure(f"{label} around the bearing", "ball azimuth [deg]", label)
        for race in ("inner", "outer"):
            values = np.asarray(ds[name].sel(race=race).values, float) * scale
            fig.line(psi[order], values[order], color=RACE_COLOURS[race], legend_label=race)
            fig.scatter(psi[order], values[order], color=RACE_COLOURS[race], size=6)
        note = ""
    _legend_outside(fig)
    return fig, note


def study_metric_charts(ds, sweep: str, metrics):
    """Charts of ``metrics`` [(variable, label, scale)] against the key the points of ``sweep``
    are charted against (:func:`solver.sweep_axis_key`): one line per race and model through the
    points where both the key and the metric are finite. No charts when the sweep has no such key
    or a metric has no finite value."""
    from solver import sweep_axis_key

    key = sweep_axis_key(ds, sweep)
    if key is None:
        return []
    select = np.asarray(ds["sweep"].values).astype(str) == sweep
    x = np.asarray(ds[key].values, float)[select]
    order = np.argsort(x)
    figures = []
    for var, label, scale in metrics:
        fig = _figure(f"{label} ({sweep})", key_label(key), label, height=320)
        drawn = False
        for model in ds["model"].values:
            for race in ("inner", "outer"):
                y = np.asarray(ds[var].sel(model=model, race=race).values, float)[select] * scale
                shown = order[np.isfinite(x[order]) & np.isfinite(y[order])]
                if shown.size == 0:
                    continue
                drawn = True
                fig.line(
                    x[shown],
                    y[shown],
                    color=RACE_COLOURS[race],
                    line_dash=MODEL_DASH.get(str(model), "solid"),
                    legend_label=f"{race}, {model}",
                )
                fig.scatter(x[shown], y[shown], color=RACE_COLOURS[race], size=6)
        if drawn:
            _legend_outside(fig)
            figures.append(fig)
    return figures


#: The set's line in a set study chart (the bearings take :data:`PALETTE`): wide and
#: translucent, under the bearings' lines, so that both show where they coincide (the axial
#: stiffness of a spring-preloaded pair is its fixed bearing's).
SET_LINE_COLOUR = "#222222"
SET_LINE_WIDTH = 6
SET_LINE_ALPHA = 0.45


def set_study_charts(ds, sweep: str, metrics):
    """Charts of a bearing-set study (a ``bearing`` dimension): for each row (name, label, scale,
    ((variable, tag, dashed), ...)) of ``metrics``, the variables against the key the points of
    ``sweep`` are charted against (:func:`solver.sweep_axis_key`): a variable without a
    ``bearing`` dimension draws the set's line (black, "set"), one with it a line per bearing in
    the bearing's colour, named by the bearing and the tag, through the points
    where both the key and the value are finite. No charts when the sweep has no such key; no
    chart for a row without a finite value."""
    from solver import sweep_axis_key

    key = sweep_axis_key(ds, sweep)
    if key is None:
        return []
    select = np.asarray(ds["sweep"].values).astype(str) == sweep
    x = np.asarray(ds[key].values, float)[select]
    order = np.argsort(x)
    names = [str(b) for b in ds["bearing"].values]
    models = [str(m) for m in ds["model"].values]
    figures = []
    for _name, label, scale, variables in metrics:
        fig = _figure(f"{label} ({sweep})", key_label(key), label, height=320)
        drawn = False
        for model in models:
            suffix = f", {model}" if len(models) > 1 else ""
            for variable, tag, dashed in variables:
                if variable not in ds:
                    continue
                values = ds[variable].sel(model=model)
                if "bearing" in values.dims:
                    lines = [
                        (
                            f"{name}{', ' + tag if tag else ''}{suffix}",
                            values.sel(bearing=name).values,
                            PALETTE[index % len(PALETTE)],
                            2,
                        )
                        for index, name in enumerate(names)
                    ]
                else:  # wide and translucent: a bearing's line on top of it stays visible
                    lines = [(f"set{suffix}", values.values, SET_LINE_COLOUR, SET_LINE_WIDTH)]
                for legend, y_all, colour, width in lines:
                    y = np.asarray(y_all, float)[select] * scale
                    shown = order[np.isfinite(x[order]) & np.isfinite(y[order])]
                    if shown.size == 0:
                        continue
                    drawn = True
                    fig.line(
                        x[shown],
                        y[shown],
                        color=colour,
                        line_width=width,
                        line_alpha=SET_LINE_ALPHA if colour == SET_LINE_COLOUR else 1.0,
                        line_dash="dashed" if dashed else "solid",
                        legend_label=legend,
                    )
                    fig.scatter(x[shown], y[shown], color=colour, size=6)
        if drawn:
            _legend_outside(fig)
            figures.append(fig)
    return figures
