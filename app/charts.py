"""Plotly figures of a result, for the app's chart panels (no trame here).

Every figure reads a :class:`viz.frames.FrameSource` (the same per-frame data the 3-D view shows, so
a quasi-static result is charted through its steady kinematics) or the result Dataset itself.
Axes are in display units: time in ms, angles in degrees, lengths in mm, pressures in GPa, speeds
in rev/min. ``HELP`` holds a plain-language explanation of each chart, for teaching.
"""

from __future__ import annotations

import json

import numpy as np
import plotly.graph_objects as go
import xarray as xr

from solver import RPM, loaded_mask
from viz.frames import TWO_PI, FrameSource
from viz.palette import MAX_COMPARED, ball_colours, run_colours, run_style, run_tag
from viz.raceway import INNER, OUTER, RACES

RACE_COLOURS = {INNER: "#1f77b4", OUTER: "#d62728"}

HELP = {
    "contact_angle": (
        "Contact angle: where on the groove a ball touches a ring, measured from the radial plane. "
        "It rises with axial load and changes as a ball passes through the radial load zone; "
        "inner and outer contacts differ at speed because centrifugal force pushes the ball out."
    ),
    "load_azimuth": (
        "Contact load versus azimuth: how the applied loads are shared among the balls. A radial "
        "load concentrates the load on one side (the load zone); pure axial load shares it equally."
    ),
    "raceway_map": (
        "Unrolled raceway map: each raceway cut open and laid flat, circumferential position "
        "(in the ring's own frame) across, contact angle up. Each dot is where a ball touched, "
        "over the whole run; open circles are where the balls touch now. A thin line means "
        "every ball follows the same path; a band means the path wanders. Dashed lines: the "
        "shoulder edges. "
        "Below: the solver's excursion (how far the mean track wanders across the groove) and band "
        "thickness (the spread at one place), each race in its own ring's frame."
    ),
    "ellipse": (
        "Contact ellipse: the flattened patch where ball and raceway touch (Hertz theory). "
        "The long "
        "semi-axis a lies across the groove, the short one b along the rolling direction; the peak "
        "pressure at its centre sets rolling-contact fatigue life."
    ),
    "cage_speed": (
        "Cage speed: how fast the ball set orbits. Kinematics gives a little under half the shaft "
        "speed; sliding or skidding makes it lower."
    ),
    "comparison": (
        "Quasi-static versus dynamic: the quasi-static model assumes steady rolling; the dynamic "
        "model integrates the motion in time. Their contact angles should agree in steady "
        "operation."
    ),
}


# Legends go below the plot, under the x-axis title, so they never cover a curve; each row of
# legend entries takes LEGEND_ROW_PX of the bottom margin. ENTRIES_PER_ROW is what fits in the
# narrowest chart column (~450 px) with names like "quasi-static inner".
LEGEND_ROW_PX = 20
ENTRIES_PER_ROW = 3
_BOTTOM_PX = 58  # x tick labels and title


def _legend_rows(fig: go.Figure) -> int:
    """Rows the legend needs below a narrow chart (0 without a legend)."""
    shown = [t for t in fig.data if t.showlegend is not False]
    if fig.layout.showlegend is False or len(shown) < 2 and fig.layout.showlegend is not True:
        return 0
    return -(-len(shown) // ENTRIES_PER_ROW)


def _layout(fig: go.Figure, title: str, xtitle: str, ytitle: str) -> go.Figure:
    rows = _legend_rows(fig)
    fig.update_layout(
        title={"text": title, "font": {"size": 14}, "x": 0.02, "xanchor": "left"},
        xaxis_title=xtitle,
        yaxis_title=ytitle,
        margin={"l": 55, "r": 10, "t": 35, "b": _BOTTOM_PX + LEGEND_ROW_PX * rows},
        showlegend=rows > 0,
        legend={
            "orientation": "h",
            "x": 0.0,
            "xanchor": "left",
            "yref": "container",
            "y": 0.0,
            "yanchor": "bottom",
            "font": {"size": 11},
        },
        template="none",  # built-in templates cost ~60 ms per figure (deep copies)
        plot_bgcolor="white",
        paper_bgcolor="white",
        uirevision="keep",
    )
    fig.update_xaxes(gridcolor="#e5e5e5", zeroline=False, automargin=True)
    fig.update_yaxes(gridcolor="#e5e5e5", zeroline=False, automargin=True)
    return fig


# ---- what follows the time: overlays -----------------------------------------------------------
# A chart that follows the time is sent as two parts: its figure without the current frame (the
# base, sent again only when the result or an option changes) and a small overlay of what marks
# the current frame (``{"data": [traces], "shapes": [shapes]}``, plain JSON), sent with the frames.
# The page shows ``merge_overlay(base, overlay)`` (the same merge: ``static/racetrace-charts.js``).


def empty_overlay() -> dict:
    """An overlay that marks nothing."""
    return {"data": [], "shapes": []}


def merge_overlay(base: dict, overlay: dict | None) -> dict:
    """The figure the page shows (plotly JSON): ``base``'s traces then the ``overlay``'s, and
    ``base``'s layout with the overlay's shapes after its own."""
    overlay = overlay or empty_overlay()
    layout = dict(base.get("layout", {}))
    if overlay.get("shapes"):
        layout["shapes"] = [*layout.get("shapes", []), *overlay["shapes"]]
    return {**base, "data": [*base.get("data", []), *overlay.get("data", [])], "layout": layout}


def time_marker_shape(x_ms: float) -> dict:
    """The dotted vertical line at time ``x_ms`` (ms) of a chart against time (plotly JSON)."""
    return {
        "line": {"color": "#444", "dash": "dot", "width": 1},
        "type": "line",
        "x0": x_ms,
        "x1": x_ms,
        "xref": "x",
        "y0": 0,
        "y1": 1,
        "yref": "y domain",
    }


def time_marker_overlay(source: FrameSource, current: int) -> dict:
    """The overlay of a chart against time at frame ``current`` of ``source``: its time marker."""
    t_ms = float(source.times[min(max(int(current), 0), source.n_frames - 1)] * 1e3)
    return {"data": [], "shapes": [time_marker_shape(t_ms)]}


def _time_marker(fig: go.Figure, x: float) -> None:
    fig.add_shape(time_marker_shape(x))


def padded_range(values, min_span: float, pad: float = 0.08) -> list[float] | None:
    """Axis range [low, high] around the finite ``values`` with room above and below.

    The span is widened by ``pad`` of itself at each end and to at least ``min_span`` (same unit
    as the values) around its middle, so that a curve never runs along the frame and a nearly
    constant one does not get tick labels like 89.2885. None when no value is finite.
    """
    finite = np.asarray(values, float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return None
    low, high = float(finite.min()), float(finite.max())
    span = max(high - low, min_span / (1.0 + 2.0 * pad))
    middle = 0.5 * (low + high)
    half = 0.5 * span * (1.0 + 2.0 * pad)
    return [middle - half, middle + half]


def _pad_y(fig: go.Figure, min_span: float, axis: str = "y", low_zero: bool = False) -> None:
    """Set the range of y axis ``axis`` ("y" or "y2") from the data of the traces on it."""
    values = [
        np.asarray(t.y, float) for t in fig.data if (t.yaxis or "y") == axis and t.y is not None
    ]
    if not values:
        return
    yrange = padded_range(np.concatenate([v.ravel() for v in values]), min_span)
    if yrange is None:
        return
    if low_zero:  # a non-negative quantity (loads, sizes): the axis starts at 0
        yrange[0] = 0.0
    fig.update_layout({"yaxis" if axis == "y" else "yaxis2": {"range": yrange}})


ANGLE_MIN_SPAN_DEG = 1.0  # contact-angle axes span at least this much (degree)
LOAD_MIN_SPAN_N = 1.0  # contact-load axes span at least this much (N)
# points in all of a contact-angle chart of every ball: ~330 per line, more than the chart is
# wide in pixels; drawn as SVG and rebuilt once a second while playing (40 000 added ~0.05 s per
# refresh in a software-rendering browser). One ball alone gets the full `max_points`.
ALL_BALLS_MAX_POINTS = 12_000


def contact_angle_figure(
    source: FrameSource, balls=(0,), current: int | None = None, max_points: int = 4000
) -> go.Figure:
    """Contact angle (degree) versus time (ms), inner and outer contacts of the chosen balls.

    ``balls``: ball indices, one line per (ball, race) in the race's colour; or None for every
    ball, drawn as ONE trace per race ("inner, all balls") whose balls are separated by gaps
    (NaN), sharing :data:`ALL_BALLS_MAX_POINTS` points: 36 separate traces made the chart slow
    to build, send and draw while playing. Hovering names the ball. Long results are decimated
    to at most ``max_points`` samples per line.
    """
    every_ball = balls is None
    if every_ball:
        balls = range(source.ball_count)
        max_points = min(max_points, ALL_BALLS_MAX_POINTS // (2 * max(1, source.ball_count)) - 1)
    balls = [int(j) for j in balls]
    for j in balls:
        if not 0 <= j < source.ball_count:
            raise ValueError(
                f"balls: ball {j} does not exist; balls are 0 to {source.ball_count - 1}"
            )
    fig = go.Figure()
    step = max(1, int(np.ceil(source.n_frames / max_points)))
    t_ms = source.times[::step] * 1e3
    alpha = np.degrees(source.contact["contact_angle"][::step])
    load = source.contact["contact_load"][::step]
    angle = np.where(loaded_mask(load, alpha), alpha, np.nan)  # (frame, ball, race); gaps: open
    for race in (INNER, OUTER):
        if every_ball:
            gap = np.full((len(balls), 1), np.nan)
            x = np.hstack([np.tile(t_ms, (len(balls), 1)), gap]).ravel()
            y = np.hstack([angle[:, balls, race].T, gap]).ravel()
            ball_of_point = np.repeat(balls, len(t_ms) + 1)
            fig.add_trace(
                go.Scatter(
                    x=x,
                    y=y,
                    customdata=ball_of_point,
                    mode="lines",
                    name=f"{RACES[race]}, all balls",
                    line={"color": RACE_COLOURS[race], "width": 1},
                    hovertemplate=(
                        f"ball %{{customdata}} {RACES[race]}: %{{y:.3f}} degree<extra></extra>"
                    ),
                )
            )
            continue
        for j in balls:
            fig.add_trace(
                go.Scatter(
                    x=t_ms,
                    y=angle[:, j, race],
                    mode="lines",
                    name=f"ball {j} {RACES[race]}",
                    line={"color": RACE_COLOURS[race], "width": 2},
                    hovertemplate=f"ball {j} {RACES[race]}: %{{y:.3f}} degree<extra></extra>",
                )
            )
    if current is not None:
        _time_marker(fig, float(source.times[min(current, source.n_frames - 1)] * 1e3))
    fig = _layout(fig, "Contact angle", "time, ms", "contact angle, degree")
    _pad_y(fig, ANGLE_MIN_SPAN_DEG)
    return fig


def _frame_by_azimuth(source: FrameSource, current: int):
    """Frame ``current`` of ``source``, its balls' azimuths (degree, in [0, 360)) and the order
    that sorts the balls by azimuth."""
    f = source.frame(current)
    psi = np.mod(np.degrees(f.ball_azimuth), 360.0)
    return f, psi, np.argsort(psi)


def load_azimuth_figure(source: FrameSource, current: int = 0) -> go.Figure:
    """Contact load (N) of every ball versus its azimuth (degree) at frame ``current``."""
    f, psi, order = _frame_by_azimuth(source, current)
    fig = go.Figure()
    for race in (INNER, OUTER):
        fig.add_trace(
            go.Scatter(
                x=psi[order],
                y=np.nan_to_num(f.contact_load[order, race]),
                mode="lines+markers",
                name=RACES[race],
                line={"color": RACE_COLOURS[race]},
            )
        )
    fig.update_xaxes(range=[0, 360])
    _layout(
        fig, f"Contact load at t = {f.time * 1e3:.2f} ms", "ball azimuth, degree", "contact load, N"
    )
    _pad_y(fig, LOAD_MIN_SPAN_N, low_zero=True)
    return fig


MAP_COLOURINGS = ("race", "ball", "load")


def raceway_map_figure(
    source: FrameSource,
    stop: int | None = None,
    max_points: int = 20000,
    *,
    current: int | None = None,
    balls=None,
    colour: str = "race",
    start_time: float | None = None,
    shoulders: tuple[float, float] | None = None,
) -> go.Figure:
    """Unrolled raceway maps: raceway azimuth (ring frame) x contact angle, both races.

    ``stop``: frames ``[0, stop)`` (default: the whole run); ``current``: frame marked with open
    circles (where the contacts are now); ``balls``: ball indices drawn (default all);
    ``colour``: "race" (one colour per raceway), "ball" (one per ball) or "load" (contact load,
    N, colour bar); ``start_time`` (s): leave out the samples before it (the start-up transient,
    e.g. the solver's ``analysis_start_time``); ``shoulders``: (inner, outer) groove latitude of
    the shoulder edges (rad), drawn as dashed lines at +-theta. The first two traces are the
    inner and outer samples; hovering one gives ball, azimuth and contact angle.
    """
    if colour not in MAP_COLOURINGS:
        raise ValueError(f"unknown colouring {colour!r}; use one of {', '.join(MAP_COLOURINGS)}")
    fig = go.Figure()
    first = 0
    if start_time is not None and source.n_frames > 1:
        first = int(np.searchsorted(source.times, float(start_time)))
        first = min(first, source.n_frames - 2)
    chosen = None if balls is None else np.asarray(list(balls), int)
    for race in (INNER, OUTER):
        phi, alpha, loaded = source.trace(race, stop)
        load = source.contact["contact_load"][: phi.shape[1], :, race].T
        loaded = loaded.copy()
        loaded[:, :first] = False
        if chosen is not None:
            keep = np.zeros(loaded.shape[0], bool)
            keep[chosen[(chosen >= 0) & (chosen < loaded.shape[0])]] = True
            loaded &= keep[:, None]
        ball = np.broadcast_to(np.arange(loaded.shape[0])[:, None], loaded.shape)[loaded]
        step = max(1, int(np.ceil(loaded.sum() / max_points)))
        x = np.mod(np.degrees(phi[loaded]), 360.0)[::step]
        y = np.degrees(alpha[loaded])[::step]
        ball = ball[::step]
        q = load[loaded][::step]
        marker = {"size": 3, "color": RACE_COLOURS[race]}
        if colour == "ball":
            palette = ball_colours(source.ball_count)  # the 3-D view's ball colours
            marker["color"] = [palette[j] for j in ball]
        elif colour == "load":
            marker.update(
                color=q,
                colorscale="Viridis",
                cmin=0.0,
                showscale=race == INNER,
                colorbar={"title": {"text": "load, N"}, "thickness": 10, "len": 0.8},
            )
        fig.add_trace(
            go.Scattergl(
                x=x,
                y=y,
                mode="markers",
                name=f"{RACES[race]} raceway",
                marker=marker,
                customdata=np.column_stack([ball, q]),
                hovertemplate=(
                    f"{RACES[race]} raceway<br>ball %{{customdata[0]}}<br>"
                    "azimuth %{x:.1f}°<br>contact angle %{y:.3f}°<br>"
                    "load %{customdata[1]:.0f} N<extra></extra>"
                ),
            )
        )
    if current is not None:
        fig.add_traces(current_contact_traces(source, current, balls))
    if colour == "ball":  # the legend of the per-ball colours (legend entries only)
        shown = range(source.ball_count) if chosen is None else chosen
        for j in shown:
            fig.add_trace(
                go.Scatter(
                    x=[None],
                    y=[None],
                    mode="markers",
                    name=f"ball {j}",
                    marker={"size": 8, "color": ball_colours(source.ball_count)[j]},
                )
            )
    fig.update_xaxes(range=[0, 360])
    _layout(
        fig, "Unrolled raceways", "raceway azimuth (ring frame), degree", "contact angle, degree"
    )
    _pad_y(fig, ANGLE_MIN_SPAN_DEG)
    if shoulders is not None:
        _shoulder_lines(fig, shoulders)
    return fig


SHOULDER_MARGIN_DEG = 2.0  # the raceway map's axis reaches this far past a shoulder line


def _shoulder_lines(fig: go.Figure, shoulders) -> None:
    """Dashed lines at the shoulder edge of each raceway on the side of its track (the sign of its
    mean contact angle; the land the contact runs towards), named in the title; the axis is
    widened to hold them (``shoulders``: (inner, outer) groove latitude of the edges, rad)."""
    lo, hi = fig.layout.yaxis.range or (0.0, 0.0)
    words = []
    for race, theta in zip((INNER, OUTER), shoulders, strict=True):
        samples = np.asarray(fig.data[race].y, float)  # the first two traces: inner, outer
        mean = np.nanmean(samples) if samples.size else 1.0
        edge = float(np.degrees(theta)) * (1.0 if not mean < 0 else -1.0)
        words.append(f"{RACES[race]} {edge:+.0f}°")
        fig.add_hline(y=edge, line={"dash": "dash", "color": RACE_COLOURS[race], "width": 1})
        lo = min(lo, edge - SHOULDER_MARGIN_DEG)
        hi = max(hi, edge + SHOULDER_MARGIN_DEG)
    fig.update_layout(
        title_text="Unrolled raceways; shoulders at " + ", ".join(words) + " (dashed)",
        yaxis={"range": [lo, hi]},
    )


# the raceway map's open circles at the contacts now (a plotly marker: its size is a diameter, px)
NOW_MARKER = {"color": "#000000", "line": {"width": 2}, "size": 9, "symbol": "circle-open"}


def _contacts_now(source: FrameSource, current: int, balls=None) -> list[tuple]:
    """Raceway azimuth (degree, in [0, 360)) and contact angle (degree) of the loaded contacts of
    frame ``current`` (of ``balls``, default all): an (x, y) pair of arrays per race."""
    f = source.frame(current)
    chosen = None if balls is None else np.asarray(list(balls), int)
    out = []
    for race in (INNER, OUTER):
        ok = f.loaded[:, race].copy()
        if chosen is not None:
            ok &= np.isin(np.arange(ok.size), chosen)
        out.append(
            (
                np.mod(np.degrees(f.raceway_azimuth[ok, race]), 360.0),
                np.degrees(f.contact_angle[ok, race]),
            )
        )
    return out


def current_contact_traces(source: FrameSource, current: int, balls=None) -> list:
    """Open circles at the contacts of frame ``current`` (of ``balls``, default all), one trace
    per race, for the raceway map."""
    traces = []
    for race, (x, y) in zip((INNER, OUTER), _contacts_now(source, current, balls), strict=True):
        traces.append(
            go.Scatter(
                x=x,
                y=y,
                mode="markers",
                name="contacts now" if race == INNER else f"{RACES[race]} now",
                marker=NOW_MARKER,
                hoverinfo="skip",
                showlegend=race == INNER,
            )
        )
    return traces


def contacts_now_legend() -> dict:
    """The raceway map's legend entry of the contacts now (plotly JSON: a trace with no points;
    :func:`current_contact_overlay` draws the circles)."""
    return {
        "hoverinfo": "skip",
        "marker": NOW_MARKER,
        "mode": "markers",
        "name": "contacts now",
        "showlegend": True,
        "x": [None],
        "y": [None],
        "type": "scatter",
    }


NOW_SHAPE = "contact now"  # the name of the raceway map's template shape of a contact now


def contacts_now_shape() -> dict:
    """The raceway map's template shape of a contact now (plotly JSON, in its layout's template,
    sent with the figure): an open circle of :data:`NOW_MARKER`'s size in pixels, colour and line.
    Hidden until a shape of the overlay names it (``templateitemname``) and places it."""
    radius = NOW_MARKER["size"] / 2.0
    return {
        "name": NOW_SHAPE,
        "type": "circle",
        "xref": "x",
        "yref": "y",
        "xsizemode": "pixel",
        "ysizemode": "pixel",
        "x0": -radius,
        "x1": radius,
        "y0": -radius,
        "y1": radius,
        "line": {"color": NOW_MARKER["color"], "width": NOW_MARKER["line"]["width"]},
        "visible": False,
    }


def current_contact_overlay(source: FrameSource, current: int, balls=None) -> dict:
    """The raceway map's overlay at frame ``current`` (of ``balls``, default all): an open circle
    at each contact now, a shape that places the map's template shape
    (:func:`contacts_now_shape`) there (plain JSON, no plotly figure). Shapes, not a trace: moving
    them redraws the shapes only, where a trace's new points make plotly redraw every trace of
    the map (the WebGL samples)."""
    return {
        "data": [],
        "shapes": [
            {"templateitemname": NOW_SHAPE, "visible": True, "xanchor": xk, "yanchor": yk}
            for x, y in _contacts_now(source, current, balls)
            for xk, yk in zip(x.tolist(), y.tolist(), strict=True)
        ],
    }


def raceway_map_base(source: FrameSource, **options) -> dict:
    """The raceway map that follows the time as the app sends it (plotly JSON):
    :func:`raceway_map_figure` of ``options`` without the current frame, the legend entry of the
    contacts now and the template shape of their circles, which :func:`current_contact_overlay`
    places."""
    base = json.loads(raceway_map_figure(source, **options).to_json())
    base["data"].append(contacts_now_legend())
    template = base["layout"].setdefault("template", {}).setdefault("layout", {})
    template["shapes"] = [contacts_now_shape()]
    return base


def trajectory_metric_words(ds: xr.Dataset) -> str:
    """Excursion and band thickness of each race in its own ring's frame (the metrics
    ``excursion``, ``excursion_arc``, ``band_thickness``, ``band_thickness_arc``), in degree and
    micrometres, and the ``energy_balance_residual`` of a dynamic run with losses, in %."""
    metric = ds.racetrace.metric
    parts = []
    for race in RACES:
        exc = float(metric("excursion").sel(race=race))
        exc_arc = float(metric("excursion_arc").sel(race=race)) * 1e6
        thick = float(metric("band_thickness").sel(race=race))
        if np.isfinite(thick):
            thick_arc = float(metric("band_thickness_arc").sel(race=race)) * 1e6
            band = f"band thickness {thick:.3f}° ({thick_arc:.0f} µm)"
        else:
            band = "band thickness needs a dynamic run"
        parts.append(f"{race} raceway: excursion {exc:.3f}° ({exc_arc:.0f} µm), {band}")
    residual = float(metric("energy_balance_residual"))
    if np.isfinite(residual):  # a dynamic run with losses checks its energy balance
        parts.append(f"energy balance residual {100.0 * residual:+.2f} % of the losses")
    return "; ".join(parts)


def ellipse_figure(source: FrameSource, current: int = 0) -> go.Figure:
    """Ellipse semi-axes a, b (mm) and peak pressure (GPa, right axis) versus ball azimuth."""
    f, psi, order = _frame_by_azimuth(source, current)
    fig = go.Figure()
    for race in (INNER, OUTER):
        ok = f.loaded[order, race]
        x = psi[order]
        a = np.where(ok, f.semi_major[order, race] * 1e3, np.nan)
        b = np.where(ok, f.semi_minor[order, race] * 1e3, np.nan)
        p = np.where(ok, f.max_pressure[order, race] * 1e-9, np.nan)
        c = RACE_COLOURS[race]
        fig.add_trace(go.Scatter(x=x, y=a, name=f"a {RACES[race]}", line={"color": c}))
        fig.add_trace(
            go.Scatter(x=x, y=b, name=f"b {RACES[race]}", line={"color": c, "dash": "dot"})
        )
        fig.add_trace(
            go.Scatter(
                x=x, y=p, name=f"p max {RACES[race]}", yaxis="y2", line={"color": c, "dash": "dash"}
            )
        )
    fig.update_xaxes(range=[0, 360])
    _layout(fig, "Contact ellipses", "ball azimuth, degree", "semi-axis, mm")
    fig.update_layout(
        # the right margin holds the pressure axis's tick labels and title
        margin={"r": 65},
        yaxis2={
            "title": {"text": "peak pressure, GPa"},
            "overlaying": "y",
            "side": "right",
            "showgrid": False,
            "zeroline": False,
            "automargin": True,
            "tickformat": ".2f",
            "tickmode": "auto",
            "nticks": 5,
        },
    )
    _pad_y(fig, 0.01, low_zero=True)
    _pad_y(fig, 0.1, axis="y2", low_zero=True)
    return fig


def cage_speed_figure(source: FrameSource, ds: xr.Dataset, current: int | None = None) -> go.Figure:
    """Cage speed (rev/min) versus time (ms); a quasi-static result gives a constant line."""
    t_ms = source.times * 1e3
    speed = np.asarray(ds["cage_speed"].values, float) / RPM
    if speed.ndim == 0:
        speed = np.full_like(t_ms, float(speed))
    step = max(1, int(np.ceil(len(t_ms) / 4000)))
    fig = go.Figure(go.Scatter(x=t_ms[::step], y=speed[::step], mode="lines", name="cage"))
    if current is not None:
        _time_marker(fig, float(t_ms[min(current, len(t_ms) - 1)]))
    _layout(fig, "Cage speed", "time, ms", "cage speed, rev/min")
    finite = speed[np.isfinite(speed)]
    _pad_y(fig, max(1.0, 0.01 * float(np.abs(finite).mean())) if finite.size else 1.0)
    return fig


def comparison_figure(quasistatic: xr.Dataset | None, dynamic: xr.Dataset | None) -> go.Figure:
    """Contact angle versus ball azimuth: quasi-static (lines) and dynamic samples (dots). Without
    a quasi-static solution (``solver.quasistatic_start`` found none) the chart says so."""
    fig = go.Figure()
    if quasistatic is None:
        _layout(fig, COMPARISON_UNAVAILABLE, "ball azimuth, degree", "contact angle, degree")
        return fig
    psi = np.mod(quasistatic["ball_azimuth"].values, 360.0)
    order = np.argsort(psi)
    for race in (INNER, OUTER):
        alpha = quasistatic["contact_angle"].isel(race=race).values
        fig.add_trace(
            go.Scatter(
                x=psi[order],
                y=alpha[order],
                mode="lines+markers",
                name=f"quasi-static {RACES[race]}",
                line={"color": RACE_COLOURS[race]},
            )
        )
        if dynamic is not None and "time" in dynamic.dims:
            d_psi = np.mod(dynamic["ball_azimuth"].values, 360.0)
            d_alpha = (
                dynamic["contact_angle"].isel(race=race).transpose(*dynamic["ball_azimuth"].dims)
            )
            fig.add_trace(
                go.Scattergl(
                    x=d_psi.ravel()[::7],
                    y=d_alpha.values.ravel()[::7],
                    mode="markers",
                    name=f"dynamic {RACES[race]}",
                    marker={"size": 3, "color": RACE_COLOURS[race], "opacity": 0.4},
                )
            )
    fig.update_xaxes(range=[0, 360])
    _layout(fig, "Quasi-static versus dynamic", "ball azimuth, degree", "contact angle, degree")
    _pad_y(fig, ANGLE_MIN_SPAN_DEG)
    return fig


COMPARISON_UNAVAILABLE = (
    "Quasi-static versus dynamic: not available (no quasi-static equilibrium at this operating "
    "point)"
)
MAP_COLUMNS = 3  # raceway maps per row when several runs are compared


def side_by_side_raceway_maps(*sources: FrameSource, max_points: int = 10000) -> go.Figure:
    """Runs compared: unrolled raceway maps of each run (A = the run on show, then B, C ...),
    side by side (at most :data:`MAP_COLUMNS` per row), same contact-angle axis, each run in its
    own colour (:func:`viz.palette.run_colours`; inner race its colour, outer race a darker shade).
    The runs' full names are too long for the narrow column: the page lists them above the chart."""
    from plotly.subplots import make_subplots

    n = len(sources)
    cols = max(1, min(n, MAP_COLUMNS))
    rows = max(1, -(-n // cols))
    titles = [f"{run_tag(i)} (run on show)" if i == 0 else run_tag(i) for i in range(n)]
    fig = make_subplots(
        rows=rows,
        cols=cols,
        shared_yaxes="all",
        horizontal_spacing=0.04,
        vertical_spacing=0.12 if rows > 1 else 0.0,
        subplot_titles=titles,  # full names: listed above the chart
    )
    per_panel = max(1, max_points // max(1, n))
    for i, source in enumerate(sources):
        row, col = i // cols + 1, i % cols + 1
        colours = run_colours(i)
        for race in (INNER, OUTER):
            phi, alpha, loaded = source.trace(race)
            step = max(1, int(np.ceil(loaded.sum() / per_panel)))
            fig.add_trace(
                go.Scattergl(
                    x=np.mod(np.degrees(phi[loaded]), 360.0)[::step],
                    y=np.degrees(alpha[loaded])[::step],
                    mode="markers",
                    marker={"size": 3, "color": colours[race]},
                    name=f"{run_tag(i)} {RACES[race]} raceway",
                ),
                row=row,
                col=col,
            )
        fig.update_xaxes(range=[0, 360], row=row, col=col)
    fig.update_xaxes(title_text="raceway azimuth, degree", row=rows)
    fig.update_yaxes(title_text="contact angle, degree", col=1)
    _layout(fig, "", "", "")
    fig.update_layout(
        xaxis_title="raceway azimuth, degree",
        yaxis_title="contact angle, degree",
        margin={"t": 30},  # the run names stand above the maps; the legend is below
    )
    ys = [np.asarray(t.y, float) for t in fig.data]
    yrange = padded_range(np.concatenate(ys), 1.0) if ys else None
    if yrange is not None:
        fig.update_yaxes(range=yrange)
    return fig


def compare_chart_px(n_runs: int, base_px: int = 280) -> int:
    """Height (pixels) of a comparison chart of ``n_runs`` runs: room for its legend rows (two
    entries per run) and, for the raceway maps, a row of maps per :data:`MAP_COLUMNS` runs."""
    legend_rows = -(-2 * n_runs // ENTRIES_PER_ROW)
    return base_px + LEGEND_ROW_PX * max(0, legend_rows - 2)


HELP["compare_runs"] = (
    "Runs side by side: the contact tracks on both raceways of the run on show (A) and of each "
    "run chosen for comparison (B, C ...; named in full above), e.g. without and with radial "
    "load, on the same contact-angle axis."
)


# Compared runs (A = the run on show, then B, C ...): each its own colour (the inner race in it,
# the outer race in a darker shade), marker and line dash (viz.palette).
RUN_STYLES = {run_tag(i): run_style(i) for i in range(MAX_COMPARED)}
RUN_COLOURS = {run_tag(i): run_colours(i) for i in range(MAX_COMPARED)}

HELP["compare_angle"] = (
    "Contact angle versus ball azimuth, the runs overlaid (A: blue circles on a solid line, B: "
    "orange crosses on a dashed line, C: green diamonds ...; the outer race in a darker shade of "
    "the run's colour; a dynamic run is a cloud of its samples). Under pure axial "
    "load every ball has the same contact angles, so each race is a flat line; a radial load "
    "spreads them: balls in the load zone press deeper into the groove than the others."
)
HELP["compare_load"] = (
    "Contact load versus ball azimuth, the runs overlaid (A: blue circles on a solid line, B: "
    "orange crosses on a dashed line, C: green diamonds ...; the outer race in a darker shade of "
    "the run's colour; a dynamic run is a cloud of its samples). Pure axial "
    "load shares the load equally (a flat line); with a radial load the loads concentrate in "
    "a load zone around the load direction and the balls opposite it carry less, or nothing."
)
HELP["compare_summary"] = (
    "Summary per run and race, every number taken after a dynamic run has settled (its "
    "analysed window; see docs/results-schema.md). Contact angle min/max tell where the contact "
    "sits in the groove; the excursion (how far the mean track wanders across the groove going "
    "round the raceway) and the band thickness (the spread at one raceway azimuth, across passes "
    "and balls: 0 for a thin line; '-' for a quasi-static result, which has one pass) are "
    "measured in each race's own ring frame; the largest contact load and peak pressure tell how "
    "hard the most loaded ball is pressed (fatigue life); the cage speed shows whether the ball "
    "set orbits as kinematics predicts. The friction torque of a dynamic run stands beside two "
    "empirical estimates of the same bearing (Palmgren, SKF model: catalogue formulas, oil-air "
    "lubrication); '-' where a run has no torque of its own (quasi-static) or an estimate cannot "
    "be made (the CLI summary and the report say why); the energy balance residual (drive "
    "power minus losses minus the change of kinetic energy, as a share of the losses) checks a "
    "dynamic run's integration: beyond 1 % its torque and losses are not to be trusted."
)


def azimuth_samples(source: FrameSource) -> dict[str, np.ndarray]:
    """Contact samples of a run against ball azimuth, flattened over balls (and time).

    A quasi-static result gives its per-ball values (the source's first frame, where every ball
    sits at its solved azimuth); a dynamic run gives every (time, ball) sample. SI/rad: key
    ``ball_azimuth`` holds (n,) rad in [0, 2 pi); every contact quantity of
    :attr:`FrameSource.contact` (``contact_angle`` rad, ``contact_load`` N, ``max_pressure`` Pa,
    ...) an (n, 2) array with columns [inner, outer].
    """
    frames = slice(0, 1) if source.model == "quasistatic" else slice(None)
    samples = {"ball_azimuth": np.mod(source.ball_azimuth[frames].reshape(-1), TWO_PI)}
    for name, values in source.contact.items():
        samples[name] = values[frames].reshape(-1, 2)
    return samples


def run_summary(ds: xr.Dataset) -> dict:
    """Summary numbers of one run for the run comparison, in display units: metrics of the
    metrics table (``ds.racetrace.metric``; loaded contacts, over the analysed window of a dynamic
    run), converted here only. Returns ``{"inner": {...}, "outer": {...}, "cage_speed_rpm":
    float}``, each race holding

    * ``contact_angle_min_deg``, ``contact_angle_max_deg``: ``min_contact_angle`` and
      ``max_contact_angle`` (degree);
    * ``excursion_deg``, ``band_thickness_deg``: ``excursion`` and ``band_thickness``, the race in
      its own ring's frame (degree; NaN thickness for a quasi-static result);
    * ``contact_load_max_N``: ``largest_load`` (N);
    * ``max_pressure_max_GPa``: ``peak_pressure`` (GPa).

    ``cage_speed_rpm`` is ``mean_cage_speed`` (rev/min); ``friction_torque_Nmm``,
    ``palmgren_torque_Nmm`` and ``skf_torque_Nmm`` are ``mean_friction_torque`` and the empirical
    estimates ``friction_torque_palmgren`` / ``friction_torque_skf`` (N mm; NaN when not available).
    ``model`` names the model whose metrics they are ("quasi-static", "quasi-static, over one
    revolution" or "dynamic"): the table puts both models' excursions in one column.
    ``energy_residual_pct`` is the ``energy_balance_residual`` (%, NaN for a quasi-static result).
    """
    columns = (
        ("contact_angle_min_deg", "min_contact_angle", 1.0),
        ("contact_angle_max_deg", "max_contact_angle", 1.0),
        ("excursion_deg", "excursion", 1.0),
        ("band_thickness_deg", "band_thickness", 1.0),
        ("contact_load_max_N", "largest_load", 1.0),
        ("max_pressure_max_GPa", "peak_pressure", 1e-9),
    )
    metric = ds.racetrace.metric
    summary = {
        race: {key: float(metric(name).sel(race=race)) * scale for key, name, scale in columns}
        for race in RACES
    }
    summary["cage_speed_rpm"] = float(metric("mean_cage_speed")) / RPM
    for key, name in TORQUE_COLUMNS:
        summary[key] = float(metric(name)) * 1e3
    if "time" in ds.dims:
        summary["model"] = "dynamic"
    elif "ring_angle" in ds.dims:
        summary["model"] = "quasi-static, over one revolution"
    else:
        summary["model"] = "quasi-static"
    summary["energy_residual_pct"] = 100.0 * float(metric("energy_balance_residual"))
    return summary


#: Bearing-level friction torques of the comparison table: (row key, metric), in N mm.
TORQUE_COLUMNS = (
    ("friction_torque_Nmm", "mean_friction_torque"),
    ("palmgren_torque_Nmm", "friction_torque_palmgren"),
    ("skf_torque_Nmm", "friction_torque_skf"),
)


# Columns of the comparison table: (row key, header, number format); the first two are text.
SUMMARY_COLUMNS = (
    ("run", "run", None),
    ("race", "race", None),
    ("model", "model", None),
    ("contact_angle_min_deg", "contact angle min, degree", ".2f"),
    ("contact_angle_max_deg", "contact angle max, degree", ".2f"),
    ("excursion_deg", "excursion (own ring frame), degree", ".3f"),
    ("band_thickness_deg", "band thickness (own ring frame), degree", ".3f"),
    ("contact_load_max_N", "contact load max, N", ".1f"),
    ("max_pressure_max_GPa", "peak pressure max, GPa", ".3f"),
    ("cage_speed_rpm", "mean cage speed, rev/min", ".0f"),
    ("friction_torque_Nmm", "friction torque (model), N mm", ".4g"),
    ("palmgren_torque_Nmm", "Palmgren estimate, N mm", ".4g"),
    ("skf_torque_Nmm", "SKF-model estimate, N mm", ".4g"),
    ("energy_residual_pct", "energy balance residual, %", "+.2f"),
)


def summary_rows(runs: dict[str, dict]) -> list[dict]:
    """Table rows (plain JSON, numbers as text) of summaries ``{run tag: run_summary(...)}``.

    One row per run and race, keyed ``"<tag>-<race>"``; a NaN is shown as "-".
    """
    rows = []
    for tag, summary in runs.items():
        for race in RACES:
            bearing = ("cage_speed_rpm", "energy_residual_pct", *(key for key, _ in TORQUE_COLUMNS))
            values = {**summary[race], **{key: summary.get(key, np.nan) for key in bearing}}
            row = {"key": f"{tag}-{race}", "run": tag, "race": race}
            row["model"] = summary.get("model", "-")
            for key, _, fmt in SUMMARY_COLUMNS[3:]:
                value = values[key]
                row[key] = "-" if not np.isfinite(value) else format(value, fmt)
            rows.append(row)
    return rows


def _azimuth_trace(
    source: FrameSource, tag: str, race: int, quantity: str, max_points: int
) -> go.Scatter | go.Scattergl:
    """One run's ``quantity`` (degree or N) on ``race`` versus ball azimuth (degree)."""
    samples = azimuth_samples(source)
    psi = np.degrees(samples["ball_azimuth"])
    alpha = samples["contact_angle"][:, race]
    load = samples["contact_load"][:, race]
    if quantity == "contact_angle":
        y = np.where(loaded_mask(load, alpha), np.degrees(alpha), np.nan)
    else:
        y = np.nan_to_num(load)
    style = RUN_STYLES[tag]
    colour = RUN_COLOURS[tag][race]
    name = f"{tag} {RACES[race]}"
    if source.model == "quasistatic":  # one value per ball: a line through the balls
        order = np.argsort(psi)
        return go.Scatter(
            x=psi[order],
            y=y[order],
            mode="lines+markers",
            name=name,
            line={"color": colour, "dash": style["dash"]},
            marker={"symbol": style["symbol"], "size": style["size"], "color": colour},
        )
    keep = np.isfinite(y)
    step = max(1, int(np.ceil(keep.sum() / max_points)))
    return go.Scattergl(
        x=psi[keep][::step],
        y=y[keep][::step],
        mode="markers",
        name=name,
        marker={"symbol": style["symbol"], "size": 4, "color": colour, "opacity": 0.5},
    )


def _compare_azimuth_figure(
    sources, quantity: str, title: str, ytitle: str, max_points: int
) -> go.Figure:
    fig = go.Figure()
    for i, source in enumerate(sources):
        tag = run_tag(i)
        for race in (INNER, OUTER):
            fig.add_trace(_azimuth_trace(source, tag, race, quantity, max_points))
    fig.update_xaxes(range=[0, 360])
    _layout(fig, title, "ball azimuth, degree", ytitle)
    if quantity == "contact_angle":
        _pad_y(fig, ANGLE_MIN_SPAN_DEG)
    else:
        _pad_y(fig, LOAD_MIN_SPAN_N, low_zero=True)
    return fig


def compare_angle_figure(*sources: FrameSource, max_points: int = 5000) -> go.Figure:
    """Contact angle (degree) versus ball azimuth (degree) of the runs ``sources`` (A, B, C ...),
    both races.

    Traces "A inner", "A outer", "B inner", "B outer" ...; a quasi-static run is a line through
    its balls, a dynamic run a cloud of all its samples (at most ``max_points`` per trace).
    """
    return _compare_azimuth_figure(
        sources,
        "contact_angle",
        "Contact angle versus ball azimuth",
        "contact angle, degree",
        max_points,
    )


def compare_load_figure(*sources: FrameSource, max_points: int = 5000) -> go.Figure:
    """Contact load (N) versus ball azimuth (degree) of the runs ``sources`` (A, B, C ...), both
    races.

    Same traces and conventions as :func:`compare_angle_figure`; unloaded contacts show 0 N.
    """
    return _compare_azimuth_figure(
        sources,
        "contact_load",
        "Contact load versus ball azimuth",
        "contact load, N",
        max_points,
    )


# ---- studies ----------------------------------------------------------------------------------
#: Metrics of a study Dataset the page charts: (name, axis title, scale to the axis unit).
STUDY_CHART_METRICS = (
    ("excursion", "excursion [deg]", 1.0),
    ("band_thickness", "band thickness [deg]", 1.0),
    ("band_width", "track width across the groove [deg]", 1.0),
    ("mean_contact_angle", "mean contact angle [deg]", 1.0),
    ("peak_pressure", "peak pressure [GPa]", 1e-9),
    ("largest_load", "largest contact load [N]", 1.0),
)


def race_study_figure(ds, sweep: str | None, metric: str):
    """Plotly figure of a single-bearing study: ``metric`` against the key ``sweep`` is charted
    against (:func:`solver.sweep_axis_key`), inner and outer race side by side, a line per model
    (:func:`app.study_figures.study_figure` picks it or the set's)."""
    from plotly.subplots import make_subplots

    from solver import sweep_axis_key

    label, scale = next(
        ((lab, sc) for n, lab, sc in STUDY_CHART_METRICS if n == metric), (metric, 1.0)
    )
    fig = make_subplots(
        rows=1, cols=2, subplot_titles=("inner race", "outer race"), shared_yaxes=True
    )
    select = np.asarray(ds["sweep"].values).astype(str) == sweep
    key = sweep_axis_key(ds, sweep) if sweep is not None and select.any() else None
    if key is not None:
        x = np.asarray(ds[key].values, float)[select]
        order = np.argsort(x)
        order = order[np.isfinite(x[order])]
        for col, (race, index) in enumerate((("inner", INNER), ("outer", OUTER)), start=1):
            for model in ds["model"].values:
                y = np.asarray(ds[metric].sel(model=model, race=race).values, float)[select]
                fig.add_trace(
                    go.Scatter(
                        x=x[order].tolist(),
                        y=(y[order] * scale).tolist(),
                        mode="lines+markers",
                        name=f"{race}, {model}",
                        line={
                            "color": RACE_COLOURS[index],
                            "dash": "dash" if model == "quasistatic" else "solid",
                        },
                        # (point, model) of each marker: a click opens that run
                        customdata=[
                            [str(pt), str(model)]
                            for pt in np.asarray(ds["point"].values)[select][order]
                        ],
                    ),
                    row=1,
                    col=col,
                )
        fig.update_xaxes(title_text=key.rsplit(".", 1)[-1])
    fig.update_yaxes(title_text=label, col=1)
    fig.update_layout(
        margin={"l": 50, "r": 10, "t": 30, "b": 90},
        legend={"orientation": "h", "yref": "container", "y": 0.0, "yanchor": "bottom"},
    )
    return fig
