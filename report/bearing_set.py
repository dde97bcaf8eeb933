"""The report of a bearing set's result (a Dataset with a ``bearing`` dimension,
results-schema.md, "Bearing sets"): the set (arrangement, positions, directions), the load sharing,
the stiffness of every bearing and of the set (each 5 x 5 matrix as a table with its units), a
spring preload's force and the floating outer rings' shift, and each bearing's contact angle and
load per ball. A dynamic run of a set is shown at its last stored sample (it has no stiffness),
its spring shift charted over time and each bearing's contacts over time.

Every value is read from the Dataset; every text taken from it is escaped (the tables escape
their cells, :func:`report.build._text` the rest).
"""

from __future__ import annotations

import html

import numpy as np

from .units import number

#: The rows (generalised forces) and columns (displacements) of a 5 x 5 stiffness, as the
#: Dataset's ``dof`` coordinate orders them, with the unit each is shown in and its scale from SI.
FORCE_UNITS = {"x": "N", "y": "N", "z": "N", "tilt_y": "N m", "tilt_z": "N m"}
DISPLACEMENT_UNITS = {"x": ("µm", 1e-6), "y": ("µm", 1e-6), "z": ("µm", 1e-6)}
TILT_UNIT = ("mrad", 1e-3)
FORCE_NAMES = {"x": "Fx", "y": "Fy", "z": "Fz", "tilt_y": "My", "tilt_z": "Mz"}
DISPLACEMENT_NAMES = {"x": "x", "y": "y", "z": "z", "tilt_y": "tilt y", "tilt_z": "tilt z"}


def _displacement_unit(dof: str) -> tuple[str, float]:
    return DISPLACEMENT_UNITS.get(dof, TILT_UNIT)


def matrix_unit(row: str, column: str) -> tuple[str, float]:
    """(unit text, scale from SI) of the stiffness entry K[row, column]: the row's force or
    moment per the column's displacement or tilt (N/µm, N/mrad, N m/µm, N m/mrad)."""
    unit, per = _displacement_unit(column)
    return f"{FORCE_UNITS[row]}/{unit}", per


def matrix_rows(k: np.ndarray, dofs) -> tuple[list[str], list[list[str]]]:
    """(headers, rows) of the 5 x 5 stiffness ``k`` (SI) as a table: a row per generalised force,
    a column per displacement, every entry with its unit."""
    dofs = [str(d) for d in dofs]
    headers = ["K", *(DISPLACEMENT_NAMES.get(d, d) for d in dofs)]
    rows = []
    for i, row in enumerate(dofs):
        cells = [FORCE_NAMES.get(row, row)]
        for j, column in enumerate(dofs):
            unit, scale = matrix_unit(row, column)
            cells.append(f"{number(k[i, j] * scale)} {unit}")
        rows.append(cells)
    return headers, rows


def _mean_inner_angle(one) -> float:
    load = one["contact_load"].sel(race="inner").values
    angle = one["contact_angle"].sel(race="inner").values
    loaded = np.isfinite(angle) & (load > 0.0)
    return float(np.mean(angle[loaded])) if loaded.any() else float("nan")


def set_rows(ds) -> list[list[str]]:
    """The set's bearings: name, position (mm), direction, balls and their size, pitch diameter,
    free and mean loaded inner contact angle."""
    rows = []
    for index, name in enumerate(ds["bearing"].values):
        one = ds.isel(bearing=index)
        count = int(one["ball_count"])
        rows.append(
            [
                str(name),
                number(float(one["bearing_position"]) * 1e3),
                str(one["bearing_direction"].item()),
                str(count),
                number(float(one["ball_diameter"]) * 1e3),
                number(float(one["pitch_diameter"]) * 1e3),
                number(float(one["free_contact_angle"])),
                number(_mean_inner_angle(one.isel(ball=slice(0, count)))),
            ]
        )
    return rows


SET_HEADERS = (
    "bearing",
    "position [mm]",
    "thrust towards",
    "balls",
    "ball diameter [mm]",
    "pitch diameter [mm]",
    "free contact angle [deg]",
    "mean loaded inner contact angle [deg]",
)


def sharing_rows(ds) -> tuple[list[str], list[list[str]]]:
    """(headers, rows) of the load sharing: each bearing's axial load (its own direction) and
    radial load, its shares of the external loads (when there are such loads), its largest
    contact load, its loaded balls and its peak pressure."""
    headers = ["bearing", "axial load [N]", "radial load [N]"]
    shares = [name for name in ("axial_load_share", "radial_load_share") if name in ds]
    headers += [f"{name.split('_')[0]} share" for name in shares]
    headers += ["largest contact load [N]", "loaded balls", "peak pressure [GPa]"]
    rows = []
    for index, name in enumerate(ds["bearing"].values):
        one = ds.isel(bearing=index)
        count = int(one["ball_count"])
        load = one["contact_load"].values[:count]
        row = [
            str(name),
            number(float(one["bearing_axial_load"])),
            number(float(one["bearing_radial_load"])),
        ]
        row += [number(float(one[share])) for share in shares]
        row += [
            number(float(np.nanmax(load))),
            f"{int((load[:, 0] > 0.0).sum())} of {count}",
            number(float(np.nanmax(one["max_pressure"].values[:count])) * 1e-9),
        ]
        rows.append(row)
    return headers, rows


def shaft_rows(ds, whole=None) -> list[list[str]]:
    """The shaft at the load point, the preload offset (a quasi-static set) and a spring
    preload (:func:`solver.set_spring_preload`): its force (a dynamic run) and the floating outer
    rings' shift (a dynamic run: mean and peak to peak over the analysed window). ``ds``: a
    quasi-static set, or a dynamic run's set at one sample (its shaft then) with ``whole``, the
    run (its spring preload)."""
    from solver import set_spring_preload

    offset = ", ".join(number(v * 1e6) for v in ds["shaft_offset"].values)
    tilt = ", ".join(number(v) for v in ds["shaft_tilt"].values)
    rows = [
        ["load point on the shaft", f"{number(float(ds['load_position']) * 1e3)} mm"],
        ["shaft displacement at the load point (x, y, z)", f"{offset} µm"],
        ["shaft tilt (y, z)", f"{tilt} deg"],
    ]
    if "preload_offset" in ds:
        rows.append(["preload offset", f"{number(float(ds['preload_offset']) * 1e6)} µm"])
    return rows + spring_rows(set_spring_preload(ds if whole is None else whole))


def spring_rows(spring: dict | None) -> list[list[str]]:
    """The rows of a spring preload (:func:`solver.set_spring_preload`; none without one)."""
    if spring is None:
        return []
    if "spring_force_N" not in spring:
        return [["spring side shift", f"{number(spring['spring_shift_m'] * 1e6)} µm"]]
    return [
        ["spring force on the spring side's outer rings", f"{number(spring['spring_force_N'])} N"],
        [
            "spring side shift (mean over the analysed window)",
            f"{number(spring['spring_shift_m'] * 1e6)} µm",
        ],
        [
            "spring side shift, peak to peak over the analysed window",
            f"{number(spring['spring_shift_span_m'] * 1e6)} µm",
        ],
    ]


def spring_chart(ds):
    """The spring side's outer rings' shift [µm] over time [ms] of a dynamic run with a spring
    preload, with its mean over the analysed window (dashed, from the window's start); None
    without one."""
    from solver import set_spring_preload

    from .charts import MAX_TIME_POINTS, _figure, _legend_outside, _stride

    spring = set_spring_preload(ds)
    if spring is None or "spring_force_N" not in spring:
        return None
    t = np.asarray(ds["time"].values, float) * 1e3
    w = np.asarray(ds["spring_shift"].values, float) * 1e6
    step = _stride(t.size, MAX_TIME_POINTS)
    start = float(ds["analysis_start_time"].max()) * 1e3
    mean = spring["spring_shift_m"] * 1e6
    fig = _figure(
        f"Spring side outer rings' shift (spring force {number(spring['spring_force_N'])} N)",
        "time [ms]",
        "shift [µm]",
    )
    fig.line(t[::step], w[::step], color="#1f77b4", legend_label="shift")
    fig.line(
        [start, float(t[-1])],
        [mean, mean],
        color="#222222",
        line_dash="dashed",
        legend_label=f"mean over the analysed window, {number(mean)} µm",
    )
    _legend_outside(fig)
    return fig


def stiffness_rows(ds) -> list[list[str]]:
    """Axial, radial (mean of y and z) and tilting (mean of the two tilts) stiffness of every
    bearing (about its ball-centre plane) and of the set (at the load point)."""

    def cells(name, k):
        return [
            name,
            number(k[0, 0] * 1e-6),
            number(0.5 * (k[1, 1] + k[2, 2]) * 1e-6),
            number(0.5 * (k[3, 3] + k[4, 4]) * 1e-3),
        ]

    rows = [
        cells(str(name), ds["bearing_stiffness"].values[index])
        for index, name in enumerate(ds["bearing"].values)
    ]
    rows.append(cells("set (at the load point)", ds["set_stiffness"].values))
    return rows


STIFFNESS_HEADERS = ("", "axial [N/µm]", "radial [N/µm]", "tilting [N m/mrad]")
SPRING_NOTE = (
    "The spring pushes the floating outer rings of its side onto their balls with a constant "
    "force; their axial shift (along those bearings' own thrust direction) settles where their "
    "balls' axial forces balance the spring. A shift that still drifts or swings at the end of "
    "the run has not settled: run longer ([simulation] shaft_revolutions)."
)
MATRIX_NOTE = (
    "Rows: the generalised forces on the shaft (Fx, Fy, Fz, My, Mz); columns: the displacements "
    "(x, y, z, tilt y, tilt z); K[i, j] = -d(force i)/d(displacement j), ball speeds held at "
    "their solved values, shaft frame (x along the shaft)."
)


def _stiffness_body(ds) -> str:
    """The stiffness section's HTML: the summary table, then the set's and every bearing's
    5 x 5 matrix with its units."""
    from .build import _table, _text

    matrices = [("set (at the load point)", ds["set_stiffness"].values)] + [
        (str(name), ds["bearing_stiffness"].values[index])
        for index, name in enumerate(ds["bearing"].values)
    ]
    body = _table(STIFFNESS_HEADERS, stiffness_rows(ds))
    for name, k in matrices:
        m_headers, m_rows = matrix_rows(k, ds["dof"].values)
        body += f"<p><strong>5 × 5 stiffness, {html.escape(name)}</strong></p>"
        body += _table(m_headers, m_rows)
    body += f"<p>{html.escape(MATRIX_NOTE)}</p>"
    symmetry = ds.attrs.get("stiffness_symmetry")
    if symmetry:
        body += f"<p>{_text(symmetry, 600)}</p>"
    return body


def set_sections(ds, source_name: str):
    """The Panel objects of a bearing set's report and its notes (none: nothing is decimated)."""
    import panel as pn

    import solver

    from . import charts
    from .build import CHART_PRINT_CSS, PRINT_CSS, _html, _section, _table, _text, run_header

    sections = [_html(run_header(ds, source_name), stylesheets=[PRINT_CSS])]
    warnings = solver.set_result_warnings(ds)
    whole = ds
    moment = ""
    if "time" in ds.dims:  # a dynamic run of the set: its loads and balls at the last sample
        ds = ds.isel(time=-1)
        moment = (
            "<p>A dynamic run of the set: the shaft, the loads and the balls in these tables are "
            f"those of its last stored sample, t = {number(float(ds['time']) * 1e3)} ms; the "
            "spring preload's shift, when there is one, over its analysed window.</p>"
        )
    sections.append(
        _section(
            "Result warnings",
            "<ul>"
            + "".join(f'<li class="rt-warn">{html.escape(w)}</li>' for w in warnings)
            + "</ul>"
            if warnings
            else "<p>none: every bearing of the set stays within the model's validity checks</p>",
        )
    )
    described = _text(ds.attrs.get("bearing_set", ""), 400)
    sections.append(
        _section(
            "The bearing set",
            f"<p>{described}</p>"
            + moment
            + _table(SET_HEADERS, set_rows(ds))
            + "<p>Positions are those of each bearing's ball-centre plane along the shaft; a "
            "bearing carries shaft thrust towards its direction (back-to-back, DB: the contact "
            "lines diverge towards the axis).</p>"
            + _table(("shaft and preload", "value"), shaft_rows(ds, whole), (0, 1)),
        )
    )
    spring = spring_chart(whole)
    if spring is not None:
        sections.append(_section("Spring preload", f"<p>{html.escape(SPRING_NOTE)}</p>"))
        sections.append(
            pn.pane.Bokeh(spring, sizing_mode="stretch_width", stylesheets=[CHART_PRINT_CSS])
        )
    headers, rows = sharing_rows(ds)
    sections.append(
        _section(
            "Load sharing",
            _table(headers, rows)
            + "<p>Axial load: along the bearing's own thrust direction, the preload included. "
            "Shares: each bearing's force on the shaft over the external load, summing to 1 "
            "(with preload, a share above 1 and a negative one).</p>",
        )
    )
    if "set_stiffness" in ds:  # a quasi-static set (a dynamic run has no stiffness matrices)
        sections.append(_section("Stiffness", _stiffness_body(ds)))
    over = "over time" if "time" in whole.dims else "per ball"
    for index, name in enumerate(whole["bearing"].values):
        one = solver.bearing_result(whole, index)
        sections.append(
            pn.pane.Markdown(
                f"## {html.escape(str(name))}: contact angle and load {over}",
                stylesheets=[PRINT_CSS],
            )
        )
        for variable, label in (
            ("contact_angle", "contact angle [deg]"),
            ("contact_load", "contact load [N]"),
        ):
            chart, _ = charts.contact_series(one, variable, label)
            sections.append(
                pn.pane.Bokeh(chart, sizing_mode="stretch_width", stylesheets=[CHART_PRINT_CSS])
            )
    sections.append(
        _section(
            "Case (as run)",
            f'<pre class="rt-case">{html.escape(ds.attrs.get("case", ""))}</pre>',
        )
    )
    return sections, []
