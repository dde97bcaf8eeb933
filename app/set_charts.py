"""Figures and tables of a bearing set's result, for the app's set panel (no trame).

Every function reads the set's Dataset only (results-schema.md, "Bearing sets": a ``bearing``
dimension with each bearing's single-bearing variables in its own frame, and the set's variables
in the shaft frame). A dynamic run of a set (a ``time`` dimension, results-schema.md, "Dynamic
results of a bearing set") is drawn at its last stored sample (:func:`set_snapshot`); it has no
stiffness matrices, so its stiffness table is empty. Display units: positions in mm, forces in N,
angles in degrees, translational stiffness in N/µm, tilting stiffness in N m/mrad (the units of
spindle-bearing catalogues).
"""

from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
import xarray as xr

from viz.palette import run_colours
from viz.set_study import SET_STUDY_CHART_METRICS, TILT_UNIT, TRANSLATION_UNIT
from viz.study_axes import key_label

from .charts import LOAD_MIN_SPAN_N, _layout, _pad_y

HELP = {
    "set_layout": (
        "The set along the shaft, cut through its axis: each bearing at the axial position of its "
        "ball-centre plane, its outer ring (grey) in the housing and inner ring (blue) on the "
        "shaft; the dashed line is its contact line at its loaded balls' mean contact angle, "
        "ending on the axis at the bearing's pressure centre (back-to-back: the pressure centres "
        "lie outside the set, wide apart, stiff in tilt; face-to-face: inside). The arrow is the "
        "external load at its point on the shaft. The bearing on show in the 3-D view is drawn "
        "heavier."
    ),
    "set_sharing": (
        "Load sharing: the axial load each bearing carries along its own thrust direction (the "
        "preload included: both bearings of a preloaded pair carry load with no external load) "
        "and the radial load each carries. A bearing whose axial load falls to zero has lost its "
        "preload."
    ),
    "set_spring": (
        "Spring preload: the axial shift of the spring side's floating outer rings over the run "
        "(µm, along those bearings' own thrust direction: their inner rings' approach is this "
        "shift plus the shaft's displacement). The spring pushes them with a constant force; "
        "the dashed line is the shift's mean over the analysed window, which starts at the "
        "dotted line. A shift that drifts or swings means the balls' axial forces do not yet "
        "balance the spring."
    ),
    "set_balls": (
        "Contact load and inner contact angle of every ball versus its azimuth, one line per "
        "bearing of the set (each in its own frame): where each bearing's load zone is and how "
        "the preload and the external load share among its balls."
    ),
}

#: Display units of the stiffness table: (name, scale from SI, unit).


def bearing_names(ds: xr.Dataset) -> list[str]:
    """The names of the set's bearings, in order along the ``bearing`` dimension."""
    return [str(name) for name in ds["bearing"].values]


def bearing_colour(index: int) -> str:
    """The colour of bearing ``index`` in every set chart (the compared runs' palette)."""
    return run_colours(index)["run"]


def set_snapshot(ds: xr.Dataset) -> xr.Dataset:
    """The set at one instant: a quasi-static set's Dataset as it is, a dynamic run's at its last
    stored sample (the loads each bearing carries and its balls where the run ended)."""
    if "time" in ds.dims:
        return ds.isel(time=-1)
    return ds


def _one(ds: xr.Dataset, index: int) -> xr.Dataset:
    """Bearing ``index`` of the set with only its own balls."""
    one = ds.isel(bearing=index)
    return one.isel(ball=slice(0, int(one["ball_count"])))


def _mean_contact_angle(one: xr.Dataset) -> float:
    """The mean inner contact angle (degree) of the loaded balls of one bearing; its free contact
    angle when no ball is loaded."""
    load = one["contact_load"].sel(race="inner").values
    angle = one["contact_angle"].sel(race="inner").values
    loaded = np.isfinite(angle) & (load > 0.0)
    if loaded.any():
        return float(np.mean(angle[loaded]))
    return float(one["free_contact_angle"])


def describe_set(ds: xr.Dataset) -> list[str]:
    """The set in words: its description, then one line per bearing (position, direction, loads)."""
    lines = [
        str(ds.attrs.get("bearing_set", "bearing set")),
        "The 3-D view and the charts below show the bearing chosen here in its own frame (the "
        "thrust it carries along the view's axis); the set along the shaft shows which way each "
        "bearing faces.",
    ]
    if "time" in ds.dims:
        lines.append(
            f"Dynamic run of the set: the loads, the set along the shaft and the balls below are "
            f"those of its last stored sample, t = {float(ds['time'][-1]) * 1e3:.4g} ms."
        )
    spring = spring_line(ds)  # a run's over its analysed window, not at the snapshot
    ds = set_snapshot(ds)
    for index, name in enumerate(bearing_names(ds)):
        one = ds.isel(bearing=index)
        lines.append(
            f"{name}: at {float(one['bearing_position']) * 1e3:g} mm, carries thrust towards "
            f"{one['bearing_direction'].item()}; axial load {float(one['bearing_axial_load']):.0f} "
            f"N, radial load {float(one['bearing_radial_load']):.0f} N, "
            f"{int((one['contact_load'].sel(race='inner').values > 0).sum())} of "
            f"{int(one['ball_count'])} balls loaded"
        )
    if spring is not None:
        lines.append(spring)
    return lines


def spring_line(ds: xr.Dataset) -> str | None:
    """The spring preload in words (:func:`solver.set_spring_preload`), None without one: a
    dynamic run's spring force and the floating outer rings' shift over its analysed window, a
    quasi-static result's solved shift."""
    from solver import set_spring_preload

    spring = set_spring_preload(ds)
    if spring is None:
        return None
    if "spring_force_N" not in spring:
        return (
            f"Spring preload: the spring side's floating outer rings are shifted by "
            f"{spring['spring_shift_m'] * 1e6:.3f} µm along their thrust direction (the spring "
            "force is the set's preload above)."
        )
    return (
        f"Spring preload: {spring['spring_force_N']:g} N on the spring side's floating outer "
        f"rings; their shift {spring['spring_shift_m'] * 1e6:.3f} µm (mean over the analysed "
        f"window), {spring['spring_shift_span_m'] * 1e6:.3f} µm peak to peak."
    )


def spring_figure(ds: xr.Dataset) -> go.Figure | None:
    """The spring side's outer rings' shift (µm) over time (ms) of a dynamic run with a spring
    preload, with its mean over the analysed window (dashed, from its start, dotted); None for a
    result without one (a quasi-static set has one shift, given in words)."""
    from solver import set_spring_preload

    spring = set_spring_preload(ds)
    if spring is None or "spring_force_N" not in spring:
        return None
    times = ds["time"].values * 1e3
    start = float(ds["analysis_start_time"].max()) * 1e3
    mean = spring["spring_shift_m"] * 1e6
    fig = go.Figure()
    fig.add_trace(
        go.Scatter(
            x=times,
            y=ds["spring_shift"].values * 1e6,
            mode="lines",
            name="shift",
            line={"color": "#1f77b4"},
        )
    )
    fig.add_trace(
        go.Scatter(
            x=[start, float(times[-1])],
            y=[mean, mean],
            mode="lines",
            name=f"mean {mean:.3f} µm",
            line={"color": "#222", "dash": "dash", "width": 1},
        )
    )
    fig.add_vline(x=start, line={"color": "#888", "dash": "dot", "width": 1})
    _layout(
        fig,
        f"Spring side outer rings' shift (spring force {spring['spring_force_N']:g} N)",
        "time, ms",
        "shift, µm",
    )
    _pad_y(fig, 0.01)
    return fig


def layout_figure(ds: xr.Dataset, selected: int = 0) -> go.Figure:
    """The set along the shaft, cut through its axis (x: axial position, mm; y: radius, mm):
    each bearing's rings, its ball, its contact line through the ball centre at its mean contact
    angle down to the pressure centre on the axis, mirrored below the axis; the external load as
    an arrow at its point. Bearing ``selected`` is drawn heavier."""
    ds = set_snapshot(ds)
    fig = go.Figure()
    reach = []
    for index, name in enumerate(bearing_names(ds)):
        one = ds.isel(bearing=index)
        x = float(one["bearing_position"]) * 1e3
        pitch_r = 0.5 * float(one["pitch_diameter"]) * 1e3
        ball_d = float(one["ball_diameter"]) * 1e3
        sign = 1.0 if one["bearing_direction"].item() == "+x" else -1.0
        alpha = math.radians(_mean_contact_angle(_one(ds, index)))
        colour = bearing_colour(index)
        width = 3 if index == selected else 1
        half = 0.5 * 1.9 * ball_d  # ring half-width: a little wider than the ball
        for side in (1.0, -1.0):  # the section above the axis, and its mirror below
            for low, high, fill in (
                (pitch_r + 0.25 * ball_d, pitch_r + 1.0 * ball_d, "#b0b0b0"),  # outer ring
                (pitch_r - 1.0 * ball_d, pitch_r - 0.25 * ball_d, "#9ec5e8"),  # inner ring
            ):
                fig.add_trace(
                    go.Scatter(
                        x=[x - half, x + half, x + half, x - half, x - half],
                        y=[side * low, side * low, side * high, side * high, side * low],
                        fill="toself",
                        fillcolor=fill,
                        line={"color": colour, "width": width},
                        mode="lines",
                        hoverinfo="skip",
                        showlegend=False,
                    )
                )
            theta = np.linspace(0.0, 2.0 * math.pi, 40)
            fig.add_trace(
                go.Scatter(
                    x=x + 0.5 * ball_d * np.cos(theta),
                    y=side * pitch_r + 0.5 * ball_d * np.sin(theta),
                    fill="toself",
                    fillcolor=colour,
                    line={"color": colour, "width": 1},
                    mode="lines",
                    hoverinfo="skip",
                    showlegend=False,
                )
            )
            # the contact line: from the axis outwards it runs towards the bearing's direction
            centre_x = x - sign * pitch_r * math.tan(alpha)
            outer_x = x + sign * 1.0 * ball_d * math.tan(alpha)
            fig.add_trace(
                go.Scatter(
                    x=[centre_x, outer_x],
                    y=[0.0, side * (pitch_r + 1.0 * ball_d)],
                    mode="lines",
                    line={"color": colour, "width": width, "dash": "dash"},
                    name=f"{name} ({one['bearing_direction'].item()})",
                    showlegend=side > 0,
                    hovertemplate=(
                        f"{name}: at {x:g} mm, thrust towards {one['bearing_direction'].item()}, "
                        f"contact angle {math.degrees(alpha):.1f}°, pressure centre at "
                        f"{centre_x:.1f} mm<extra></extra>"
                    ),
                )
            )
            reach += [centre_x, x - half, x + half]
        fig.add_annotation(
            x=x, y=pitch_r + 1.6 * ball_d, text=name, showarrow=False, font={"color": colour}
        )
    load_x = float(ds["load_position"]) * 1e3
    # the external force balances the bearings' forces on the shaft
    force = ", ".join(f"{round(-v):d}" for v in ds["bearing_force"].values.sum(axis=0))
    reach.append(load_x)
    top = float(np.max(0.5 * ds["pitch_diameter"].values * 1e3 + 2.0 * ds["ball_diameter"].values))
    fig.add_trace(
        go.Scatter(
            x=[min(reach) - 5.0, max(reach) + 5.0],
            y=[0.0, 0.0],
            mode="lines",
            line={"color": "#555", "width": 1, "dash": "dashdot"},
            name="shaft axis",
            hoverinfo="skip",
        )
    )
    fig.add_annotation(
        x=load_x,
        y=0.0,
        ax=load_x,
        ay=0.55 * top,
        xref="x",
        yref="y",
        axref="x",
        ayref="y",
        showarrow=True,
        arrowhead=2,
        arrowwidth=2,
        arrowcolor="#222",
        text="load",
        hovertext=f"external force [{force}] N at {load_x:g} mm",
    )
    fig.update_yaxes(scaleanchor="x", scaleratio=1.0, range=[-top, top])
    _layout(fig, "The set along the shaft", "axial position, mm", "radius, mm")
    return fig


def sharing_figure(ds: xr.Dataset) -> go.Figure:
    """Axial and radial load (N) each bearing carries, as grouped bars."""
    ds = set_snapshot(ds)
    names = bearing_names(ds)
    fig = go.Figure()
    fig.add_trace(
        go.Bar(
            x=names,
            y=ds["bearing_axial_load"].values,
            name="axial (own direction)",
            marker_color="#1f77b4",
        )
    )
    fig.add_trace(
        go.Bar(x=names, y=ds["bearing_radial_load"].values, name="radial", marker_color="#ff7f0e")
    )
    fig.update_layout(barmode="group")
    _layout(fig, "Load sharing", "", "load carried, N")
    return fig


def ball_figure(ds: xr.Dataset, quantity: str) -> go.Figure:
    """Inner ``quantity`` ("contact_load", N, or "contact_angle", degree) of every ball versus its
    azimuth (degree), one line per bearing."""
    ds = set_snapshot(ds)
    fig = go.Figure()
    for index, name in enumerate(bearing_names(ds)):
        one = _one(ds, index)
        psi = np.mod(one["ball_azimuth"].values, 360.0)
        order = np.argsort(psi)
        values = one[quantity].sel(race="inner").values[order]
        if quantity == "contact_load":
            values = np.nan_to_num(values)
        fig.add_trace(
            go.Scatter(
                x=psi[order],
                y=values,
                mode="lines+markers",
                name=name,
                line={"color": bearing_colour(index)},
            )
        )
    fig.update_xaxes(range=[0, 360])
    if quantity == "contact_load":
        _layout(fig, "Inner contact load per ball", "ball azimuth, degree", "contact load, N")
        _pad_y(fig, LOAD_MIN_SPAN_N, low_zero=True)
    else:
        _layout(fig, "Inner contact angle per ball", "ball azimuth, degree", "contact angle, °")
        _pad_y(fig, 1.0)
    return fig


def _stiffness_cells(k: np.ndarray) -> dict:
    """Axial, radial (mean of y and z) and tilting (mean of the two tilts) stiffness of the 5x5
    ``k`` in the table's units, as text."""
    t_unit, t_scale = TRANSLATION_UNIT
    r_unit, r_scale = TILT_UNIT
    return {
        "axial": f"{k[0, 0] * t_scale:.1f}",
        "radial": f"{0.5 * (k[1, 1] + k[2, 2]) * t_scale:.1f}",
        "tilt": f"{0.5 * (k[3, 3] + k[4, 4]) * r_scale:.2f}",
    }


def stiffness_rows(ds: xr.Dataset) -> list[dict]:
    """The stiffness table: a row per bearing (its 5x5 about its ball-centre plane) and one for
    the set (at the load point): ``{"name", "axial", "radial", "tilt"}`` in N/µm and N m/mrad;
    none for a result without stiffness matrices (a dynamic run)."""
    if "bearing_stiffness" not in ds or "set_stiffness" not in ds:
        return []
    rows = [
        {"name": name, **_stiffness_cells(ds["bearing_stiffness"].values[index])}
        for index, name in enumerate(bearing_names(ds))
    ]
    rows.append({"name": "set (at the load point)", **_stiffness_cells(ds["set_stiffness"].values)})
    return rows


# ---- a study of bearing-set points ------------------------------------------------------------
#: The set's line in a set study chart (the bearings take the runs' palette): wide and
#: translucent, under the bearings' lines, so that both show where they coincide (the axial
#: stiffness of a spring-preloaded pair is its fixed bearing's).
SET_LINE_COLOUR = "rgba(34, 34, 34, 0.45)"
SET_LINE_WIDTH = 6


def set_study_figure(ds: xr.Dataset, sweep: str | None, metric: str) -> go.Figure:
    """Plotly figure of a bearing-set study: ``metric`` (a name of
    :data:`SET_STUDY_CHART_METRICS`) against the key ``sweep`` is charted against
    (:func:`solver.sweep_axis_key`): the set's line (black, "set") and one line per bearing in
    its colour, named by the bearing, through the points where both are finite. The markers'
    customdata is (point, model): a click opens that run."""
    from solver import sweep_axis_key

    _name, label, scale, variables = next(
        (row for row in SET_STUDY_CHART_METRICS if row[0] == metric), SET_STUDY_CHART_METRICS[0]
    )
    fig = go.Figure()
    select = np.asarray(ds["sweep"].values).astype(str) == sweep
    key = sweep_axis_key(ds, sweep) if sweep is not None and select.any() else None
    if key is not None:
        x = np.asarray(ds[key].values, float)[select]
        points = np.asarray(ds["point"].values)[select]
        models = [str(m) for m in ds["model"].values]
        names = bearing_names(ds)
        for model in models:
            suffix = f", {model}" if len(models) > 1 else ""
            for variable, tag, dashed in variables:
                if variable not in ds:
                    continue
                values = ds[variable].sel(model=model)
                lines = (
                    [(f"set{suffix}", values.values, SET_LINE_COLOUR, SET_LINE_WIDTH)]
                    if "bearing" not in values.dims
                    else [
                        (
                            f"{name}{', ' + tag if tag else ''}{suffix}",
                            values.sel(bearing=name).values,
                            bearing_colour(index),
                            2,
                        )
                        for index, name in enumerate(names)
                    ]
                )
                for trace_name, y_all, colour, width in lines:
                    y = np.asarray(y_all, float)[select] * scale
                    order = np.argsort(x)
                    shown = order[np.isfinite(x[order]) & np.isfinite(y[order])]
                    fig.add_trace(
                        go.Scatter(
                            x=x[shown].tolist(),
                            y=y[shown].tolist(),
                            mode="lines+markers",
                            name=trace_name,
                            line={
                                "color": colour,
                                "width": width,
                                "dash": "dash" if dashed else "solid",
                            },
                            customdata=[[str(p), model] for p in points[shown]],
                        )
                    )
        fig.update_xaxes(title_text=key_label(key))
    fig.update_yaxes(title_text=label)
    fig.update_layout(
        margin={"l": 50, "r": 10, "t": 30, "b": 90},
        legend={"orientation": "h", "yref": "container", "y": 0.0, "yanchor": "bottom"},
    )
    return fig
