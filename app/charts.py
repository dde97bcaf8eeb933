"""Plotly figures of a result, for the app's chart panels (no trame here).

Every figure reads a :class:`app.frames.FrameSource` (the same per-frame data the 3-D view shows, so
a quasi-static result is charted through its steady kinematics) or the result Dataset itself.
Axes are in display units: time in ms, angles in degrees, lengths in mm, pressures in GPa, speeds
in rev/min. ``HELP`` holds a plain-language explanation of each chart, for teaching.
"""

from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
import xarray as xr

from .frames import RPM, FrameSource
from .raceway import INNER, OUTER, RACES

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
        "(in the ring's own frame) across, contact angle up. Each dot is where a ball touched. A "
        "thin line means every ball follows the same path; a band means the path wanders."
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


def _layout(fig: go.Figure, title: str, xtitle: str, ytitle: str) -> go.Figure:
    fig.update_layout(
        title={"text": title, "font": {"size": 14}, "x": 0.02, "xanchor": "left"},
        xaxis_title=xtitle,
        yaxis_title=ytitle,
        margin={"l": 55, "r": 10, "t": 35, "b": 40},
        legend={"orientation": "h", "x": 1.0, "xanchor": "right", "y": 1.0, "yanchor": "bottom"},
        template="none",  # built-in templates cost ~60 ms per figure (deep copies)
        plot_bgcolor="white",
        paper_bgcolor="white",
        uirevision="keep",
    )
    fig.update_xaxes(gridcolor="#e5e5e5", zeroline=False)
    fig.update_yaxes(gridcolor="#e5e5e5", zeroline=False)
    return fig


def _time_marker(fig: go.Figure, x: float) -> None:
    fig.add_vline(x=x, line_width=1, line_dash="dot", line_color="#444")


def contact_angle_figure(
    source: FrameSource, balls=(0,), current: int | None = None, max_points: int = 4000
) -> go.Figure:
    """Contact angle (degree) versus time (ms), inner and outer contacts of the chosen balls.

    Long results are decimated to at most ``max_points`` samples per line.
    """
    fig = go.Figure()
    step = max(1, int(np.ceil(source.n_frames / max_points)))
    t_ms = source.times[::step] * 1e3
    alpha = np.degrees(source.contact["contact_angle"][::step])
    load = np.nan_to_num(source.contact["contact_load"][::step])
    for race in (INNER, OUTER):
        for j in balls:
            y = np.where(load[:, j, race] > 0, alpha[:, j, race], np.nan)
            fig.add_trace(
                go.Scatter(
                    x=t_ms,
                    y=y,
                    mode="lines",
                    name=f"ball {j} {RACES[race]}",
                    line={"color": RACE_COLOURS[race]},
                )
            )
    if current is not None:
        _time_marker(fig, float(source.times[min(current, source.n_frames - 1)] * 1e3))
    return _layout(fig, "Contact angle", "time, ms", "contact angle, degree")


def load_azimuth_figure(source: FrameSource, current: int = 0) -> go.Figure:
    """Contact load (N) of every ball versus its azimuth (degree) at frame ``current``."""
    f = source.frame(current)
    psi = np.mod(np.degrees(f.ball_azimuth), 360.0)
    order = np.argsort(psi)
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
    return _layout(
        fig, f"Contact load at t = {f.time * 1e3:.2f} ms", "ball azimuth, degree", "contact load, N"
    )


def raceway_map_figure(
    source: FrameSource, stop: int | None = None, max_points: int = 20000
) -> go.Figure:
    """Unrolled raceway maps: raceway azimuth (ring frame) x contact angle, both races."""
    fig = go.Figure()
    for race in (INNER, OUTER):
        phi, alpha, loaded = source.trace(race, stop)
        step = max(1, int(np.ceil(loaded.sum() / max_points)))
        x = np.mod(np.degrees(phi[loaded]), 360.0)[::step]
        y = np.degrees(alpha[loaded])[::step]
        fig.add_trace(
            go.Scattergl(
                x=x,
                y=y,
                mode="markers",
                name=f"{RACES[race]} raceway",
                marker={"size": 3, "color": RACE_COLOURS[race]},
            )
        )
    fig.update_xaxes(range=[0, 360])
    return _layout(
        fig,
        "Unrolled raceways",
        "raceway azimuth (ring frame), degree",
        "contact angle, degree",
    )


def ellipse_figure(source: FrameSource, current: int = 0) -> go.Figure:
    """Ellipse semi-axes a, b (mm) and peak pressure (GPa, right axis) versus ball azimuth."""
    f = source.frame(current)
    psi = np.mod(np.degrees(f.ball_azimuth), 360.0)
    order = np.argsort(psi)
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
    fig.update_layout(yaxis2={"title": "peak pressure, GPa", "overlaying": "y", "side": "right"})
    fig.update_xaxes(range=[0, 360])
    return _layout(fig, "Contact ellipses", "ball azimuth, degree", "semi-axis, mm")


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
    return _layout(fig, "Cage speed", "time, ms", "cage speed, rev/min")


def comparison_figure(quasistatic: xr.Dataset, dynamic: xr.Dataset | None) -> go.Figure:
    """Contact angle versus ball azimuth: quasi-static (lines) and dynamic samples (dots)."""
    fig = go.Figure()
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
    return _layout(
        fig, "Quasi-static versus dynamic", "ball azimuth, degree", "contact angle, degree"
    )


def side_by_side_raceway_maps(
    a: FrameSource, b: FrameSource, title_a: str, title_b: str, max_points: int = 10000
) -> go.Figure:
    """Two runs compared: unrolled raceway maps next to each other, same contact-angle axis."""
    from plotly.subplots import make_subplots

    fig = make_subplots(
        rows=1,
        cols=2,
        shared_yaxes=True,
        horizontal_spacing=0.04,
        subplot_titles=(title_a[:60], title_b[:60]),
    )
    for col, source in ((1, a), (2, b)):
        for race in (INNER, OUTER):
            phi, alpha, loaded = source.trace(race)
            step = max(1, int(np.ceil(loaded.sum() / max_points)))
            fig.add_trace(
                go.Scattergl(
                    x=np.mod(np.degrees(phi[loaded]), 360.0)[::step],
                    y=np.degrees(alpha[loaded])[::step],
                    mode="markers",
                    marker={"size": 3, "color": RACE_COLOURS[race]},
                    name=f"{RACES[race]} raceway",
                    showlegend=col == 1,
                ),
                row=1,
                col=col,
            )
        fig.update_xaxes(range=[0, 360], title_text="raceway azimuth, degree", row=1, col=col)
    fig.update_yaxes(title_text="contact angle, degree", row=1, col=1)
    _layout(fig, "", "", "")
    fig.update_layout(xaxis_title="raceway azimuth, degree", yaxis_title="contact angle, degree")
    return fig


HELP["compare_runs"] = (
    "Two runs side by side: the contact tracks on both raceways of the run on show (left) and of "
    "the run chosen for comparison (right), e.g. without and with radial load."
)
