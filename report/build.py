"""Assemble the review report and save it as one self-contained HTML file.

A run report holds: the case with provenance and the software version, the result warnings, the
summary table with units, the 3-D scene (vtk.js; a PNG of it stands in when printing), the
raceway maps, contact-angle and load charts and the contact-ellipse table. A study report holds
the study's metric charts, its table of points and, for each point, links to nothing external:
the per-point results stay in the study folder. What was decimated is listed on the page.
"""

from __future__ import annotations

import base64
import datetime as _dt
import html
import json
import math
from pathlib import Path

from viz.set_study import SET_STUDY_CHART_METRICS

from .units import hours, number, shown

#: Top-level modules of the ``report`` extra (checked before building).
REPORT_MODULES = ("panel", "bokeh", "nh3", "pyvista", "vtkmodules", "PIL")

PRINT_CSS = """
body { font-family: sans-serif; }
.rt-table { border-collapse: collapse; font-size: 13px; margin: 4px 0 12px 0; }
.rt-table th, .rt-table td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
.rt-table th { background: #f2f2f2; }
.rt-table td.text, .rt-table th.text { text-align: left; }
.rt-points { font-size: 11px; }
.rt-points th, .rt-points td { padding: 1px 3px; white-space: nowrap; }
.rt-points th { white-space: normal; vertical-align: bottom; }
.rt-points tr.rt-sweep td { background: #f7f7f7; font-weight: bold; }
.rt-notes { font-size: 12px; }
.rt-warn { color: #8a4b00; }
pre.rt-case { font-size: 11px; background: #f7f7f7; padding: 6px; white-space: pre-wrap; }
@media print {
  .rt-section, .rt-table, figure, img { break-inside: avoid; page-break-inside: avoid; }
  h2 { break-after: avoid; page-break-after: avoid; }
  .rt-table { font-size: 10px; }
}
"""
#: Panel components live in shadow roots: each gets its own stylesheet for screen and print.
#: The page column hides the vtk.js scene when printing (a still image stands in for it).
PAGE_PRINT_CSS = (
    "@media print { .bk-panel-models-vtk-VTKSynchronizedPlot { display: none !important; } "
    ":host { max-width: none !important; } }"
)
#: A chart is not split across two printed pages.
CHART_PRINT_CSS = "@media print { :host { break-inside: avoid; page-break-inside: avoid; } }"
#: Charts two abreast on screen, one column on paper.
CHART_GRID_CSS = "@media print { :host { grid-template-columns: 1fr !important; } }"
PRINT_ONLY_CSS = ":host { display: none; } @media print { :host { display: block; } }"
#: The live scene's companions, hidden on paper (the printed still carries the scene's own bar).
SCREEN_ONLY_CSS = "@media print { :host { display: none !important; } }"


#: What the report's HTML panes may hold after sanitising (:func:`_html`): the tags and the
#: ``class`` attribute this module writes; anything else (scripts, event handlers, links) is
#: dropped, a second guard behind escaping every value read from a result or a case.
ALLOWED_TAGS = frozenset(
    "div h1 h2 p strong em code ul ol li table thead tbody tr th td pre span br a".split()
)
#: The result's ``model`` attribute as shown; any other value is shown as "unknown".
MODELS = ("quasistatic", "dynamic")


def missing_report_modules() -> list[str]:
    """Modules of the ``report`` extra that are not installed."""
    from .extras import missing_modules

    return missing_modules(REPORT_MODULES)


def _table(headers, rows, text_columns=(0,)) -> str:
    def cell(tag, k, value):
        cls = ' class="text"' if k in text_columns else ""
        return f"<{tag}{cls}>{html.escape(str(value))}</{tag}>"

    head = "".join(cell("th", k, h) for k, h in enumerate(headers))
    body = "".join(
        "<tr>" + "".join(cell("td", k, v) for k, v in enumerate(row)) + "</tr>" for row in rows
    )
    return f'<table class="rt-table"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def sanitized(text: str) -> str:
    """``text`` with only :data:`ALLOWED_TAGS` and their ``class`` attributes kept (nh3)."""
    import nh3

    return nh3.clean(
        text,
        tags=set(ALLOWED_TAGS),
        attributes={"*": {"class"}, "a": {"href"}, "td": {"colspan"}},
        url_schemes=set(),  # relative links only: the point reports beside a study report
        link_rel=None,
    )


def _html(body: str, **options):
    """A Panel HTML pane of ``body`` (built with every outside value escaped), sanitised."""
    import panel as pn

    return pn.pane.HTML(
        body,
        sizing_mode="stretch_width",
        sanitize_html=True,
        sanitize_hook=sanitized,
        **options,
    )


def _text(value, limit: int = 200) -> str:
    """A value read from a result or a case as HTML text: printable, clipped, escaped."""
    from solver import clip, printable

    return html.escape(clip(printable(str(value)), limit))


def _when(value) -> str:
    """A result's ``created`` attribute as the report writes a time (UTC), or "an unknown
    time" when it is not an ISO 8601 time."""
    try:
        when = _dt.datetime.fromisoformat(str(value).replace("Z", "+00:00"))
    except ValueError:
        return "an unknown time"
    if when.tzinfo is not None:
        when = when.astimezone(_dt.UTC)
    return when.strftime("%Y-%m-%d %H:%M UTC")


def _now() -> str:
    return _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")


def _provenance(ds) -> str:
    """Where the bearing's geometry comes from (the result's ``bearing_provenance``)."""
    from solver import result_description

    return result_description(ds).get("bearing_provenance", "unknown")


# ---- one run --------------------------------------------------------------------------------
def _cell(value, units: str) -> str:
    """A table cell: SI ``value`` in ``units`` shown in engineering units (:mod:`report.units`)."""
    return shown(value, units)


def _operating_rows(ds):
    from solver import OPERATING_FIELDS, variable

    rows = []
    for name in (
        *OPERATING_FIELDS,
        "ball_count",
        "ball_diameter",
        "pitch_diameter",
        "free_contact_angle",
    ):
        if name not in ds.coords:
            continue
        spec = variable(name)
        value = ds.coords[name].values
        if name.endswith("_speed"):
            rows.append((spec.long_name, _cell(value, "rad/s")))
        elif value.dtype.kind in "fiu":
            rows.append((spec.long_name, _cell(value, spec.units)))
        else:
            rows.append((spec.long_name, str(value)))
    return rows


def _metric_cells(ds, name: str):
    """(long name, inner cell, outer cell) of a per-race metric, or (long name, value, "")."""
    from solver import METRICS

    row, value = METRICS[name], ds.racetrace.metric(name)
    if row.dims:
        inner, outer = (_cell(float(value.sel(race=race)), row.units) for race in RACES)
        return row.long_name, inner, outer
    number_ = float(value)
    text = _cell(number_, row.units) if math.isfinite(number_) else value.attrs.get("note", "-")
    return row.long_name, text, ""


def _summary_rows(ds):
    from solver import POINT_METRICS  # the metrics a study keeps, rows of the table

    # a dynamic run also shows the check of its own integration
    checks = ("energy_balance_residual",) if "time" in ds.dims else ()
    return [_metric_cells(ds, name) for name in (*POINT_METRICS, *checks)]


#: Metrics of the friction-torque rows of a run's life-and-friction table.
TORQUE_ROWS = ("mean_friction_torque", "friction_torque_palmgren", "friction_torque_skf")
#: (metric, shown as time): the rating lives and their loads, as ``racetrace simulate`` prints
#: them (million revolutions and hours).
LIFE_ROWS = (
    ("basic_rating_life", "revolutions"),
    ("basic_rating_life_time", "hours"),
    ("reference_rating_life", "revolutions"),
    ("reference_rating_life_time", "hours"),
    ("basic_load_rating", ""),
    ("equivalent_load", ""),
)


def _life_rows(ds):
    """Rating lives (L10, L10r), their loads and the friction torques (the model's beside the
    empirical estimates; a left-out estimate with its note) and the energy-balance residual."""
    from solver import METRICS

    rows, notes = [], []
    for name, kind in LIFE_ROWS:
        row, value = METRICS[name], ds.racetrace.metric(name)
        number_ = float(value)
        if kind == "revolutions":
            text = f"{number(number_ / 1e6)} million revolutions"
        elif kind == "hours":
            text = hours(number_)
        else:
            text = _cell(number_, row.units)
        rows.append((row.long_name, text))
        note = value.attrs.get("note")
        if note and note not in notes:
            notes.append(note)
    for name in TORQUE_ROWS:
        if name == "mean_friction_torque" and "time" not in ds.dims:
            continue  # a quasi-static result has no friction torque of its own
        rows.append(_metric_cells(ds, name)[:2])
    if "time" in ds.dims:
        rows.append(_metric_cells(ds, "energy_balance_residual")[:2])
    return rows, notes


def _window_mean(ds, name: str):
    """Variable ``name`` averaged over time in the analysed window (``analysis_start_time``)."""
    start = float(ds.racetrace.metric("analysis_start_time"))
    return ds[name].where(ds["time"] >= start).mean("time")


def _loss_rows(ds):
    """Power loss by source (mean over the analysed window), the total and each race's contact
    heat; None for a quasi-static result (no losses of its own)."""
    if "time" not in ds.dims or "power_loss" not in ds:
        return None
    by_source = _window_mean(ds, "power_loss")
    rows = [
        (f"power loss: {source.replace('_', ' ')}", _cell(float(value), "W"))
        for source, value in zip(by_source["loss_source"].values, by_source.values, strict=True)
    ]
    rows.append(_metric_cells(ds, "mean_total_power_loss")[:2])
    heat = _metric_cells(ds, "mean_contact_heat")
    rows.append((f"{heat[0]}: inner race", heat[1]))
    rows.append((f"{heat[0]}: outer race", heat[2]))
    return rows


#: (upper bound of λ, regime) of the lubrication regimes, in order; above the last: full film.
LAMBDA_REGIMES = ((1.0, "boundary"), (3.0, "mixed"))


def lambda_regime(value: float) -> str:
    """The lubrication regime of film parameter λ: boundary (< 1), mixed (1-3), full film (> 3);
    "-" when λ is not known (NaN)."""
    if not math.isfinite(value):
        return "-"
    for bound, regime in LAMBDA_REGIMES:
        if value < bound:
            return regime
    return "full film"


def _film_rows(ds):
    """(quantity, inner, outer) of the smallest film thickness, λ and its regime."""
    lam = ds.racetrace.metric("min_film_parameter")
    values = [float(lam.sel(race=r)) for r in RACES]
    return [
        _metric_cells(ds, "min_film_thickness"),
        (lam.attrs["long_name"], *(number(v, 3) for v in values)),
        ("lubrication regime", *(lambda_regime(v) for v in values)),
    ]


def _film_note(ds) -> str:
    """What λ is computed from: the roughnesses of the case (or why λ is not known)."""
    case = ds.racetrace.case()
    if case is None:
        return str(ds.racetrace.metric("min_film_parameter").attrs.get("note", ""))
    return (
        "λ = h / √(Rq_ball² + Rq_raceway²): the smallest central film thickness of a loaded "
        f"contact over the composite roughness, with Rq_ball = "
        f"{_cell(case.bearing.ball_roughness_um * 1e-6, 'm')} and Rq_raceway = "
        f"{_cell(case.bearing.raceway_roughness_um * 1e-6, 'm')} (bearing.ball_roughness_um and "
        "bearing.raceway_roughness_um; when the case does not give them, estimates of typical "
        "finishes). λ < 1: boundary lubrication, 1-3: mixed, > 3: full film."
    )


def _lambda_margin_row(ds):
    """The margin row of λ against the full-film limit 3."""
    lam = ds.racetrace.metric("min_film_parameter")
    values = [float(lam.sel(race=r)) for r in RACES]
    return (
        "smallest film parameter λ",
        *(number(v, 3) for v in values),
        f"> {number(LAMBDA_REGIMES[-1][0])} full film",
        "; ".join(f"{r} {lambda_regime(v)}" for r, v in zip(RACES, values, strict=True)),
    )


def _margin_rows(ds):
    """(quantity, inner, outer, limit, margin or ratio) of each check against a limit."""
    from solver import STATIC_PRESSURE_LIMIT

    peak = ds.racetrace.metric("peak_pressure")
    rows = [
        (
            "peak contact pressure",
            *(_cell(float(peak.sel(race=r)), "Pa") for r in RACES),
            f"{_cell(STATIC_PRESSURE_LIMIT, 'Pa')} (ISO 76)",
            "; ".join(
                f"{r} {_cell(STATIC_PRESSURE_LIMIT - float(peak.sel(race=r)), 'Pa')} below"
                for r in RACES
            ),
        )
    ]
    margin = ds.racetrace.metric("min_truncation_margin")
    rows.append(
        (
            "smallest truncation margin (ellipse to shoulder)",
            *(_cell(float(margin.sel(race=r)), "degree") for r in RACES),
            "> 0 deg",
            "; ".join(
                f"{r} {'clear' if float(margin.sel(race=r)) > 0 else 'over the shoulder'}"
                if math.isfinite(float(margin.sel(race=r)))
                else f"{r}: no shoulder given"
                for r in RACES
            ),
        )
    )
    rows.append(_lambda_margin_row(ds))
    spin = ds.racetrace.metric("mean_spin_to_roll")
    rows.append(
        ("mean spin-to-roll ratio", *(number(float(spin.sel(race=r))) for r in RACES), "", "")
    )
    slip = float(ds.racetrace.metric("cage_slip"))
    rows.append(("cage slip (1 - cage speed / epicyclic)", number(slip), "", "", ""))
    if "time" in ds.dims:
        residual = float(ds.racetrace.metric("energy_balance_residual"))
        rows.append(("energy-balance residual", number(residual), "", "", ""))
        model = float(ds.racetrace.metric("mean_friction_torque"))
        for name in ("friction_torque_palmgren", "friction_torque_skf"):
            estimate = ds.racetrace.metric(name)
            value = float(estimate)
            ratio = (
                f"model / estimate = {number(model / value, 3)}"
                if math.isfinite(value) and value
                else estimate.attrs.get("note", "-")
            )
            rows.append((estimate.attrs["long_name"], _cell(value, "N m"), "", "", ratio))
    return rows


def _stiffness_rows(ds):
    return [_metric_cells(ds, name)[:2] for name in STIFFNESS_ROWS]


#: Metrics of the ring displacement and stiffness table.
STIFFNESS_ROWS = (
    "axial_displacement",
    "radial_displacement",
    "axial_stiffness",
    "radial_stiffness",
)


def _input_rows(ds):
    """The inputs a reviewer checks: materials, groove curvatures, shoulder diameters (the
    result's coordinates), clearance or preload and the lubricant (its case, parsed by the solver:
    ``ds.racetrace.case()``)."""
    from solver import variable

    rows = []
    for k, body in enumerate(ds["body"].values):
        rows.append(
            (
                f"{body} material",
                f"{ds['material'].values[k]}: E {_cell(ds['youngs_modulus'].values[k], 'Pa')}, "
                f"ν {number(ds['poisson_ratio'].values[k])}, "
                f"ρ {_cell(ds['density'].values[k], 'kg m-3')}",
            )
        )
    diameter = float(ds["ball_diameter"])
    for k, race in enumerate(RACES):
        radius = float(ds["groove_radius"].values[k])
        rows.append(
            (
                f"{race} groove curvature f = r / D",
                f"{number(radius / diameter)} (r = {_cell(radius, 'm')})",
            )
        )
    for k, race in enumerate(RACES):
        shoulder = float(ds["shoulder_diameter"].values[k])
        rows.append(
            (
                f"{race} shoulder diameter",
                _cell(shoulder, "m") if math.isfinite(shoulder) else "not given",
            )
        )
    case = ds.racetrace.case()
    clearance = None if case is None else case.bearing.diametral_clearance_mm
    free_angle = _cell(float(ds["free_contact_angle"]), "degree")
    if clearance is not None:
        rows.append(("diametral clearance", f"{_cell(clearance * 1e-3, 'm')} (α0 {free_angle})"))
    else:
        rows.append(
            (
                "clearance or preload",
                f"free contact angle α0 {free_angle} given; preload: the axial load "
                f"{_cell(float(ds['axial_load']), variable('axial_load').units)}",
            )
        )
    lubricant = None if case is None else case.lubricant
    if lubricant is None:
        rows.append(("lubricant", "none (or the result holds no readable case)"))
    else:
        name = lubricant.oil or "given in the case"
        rows.append(
            (
                "lubricant",
                f"{name}: viscosity {_cell(lubricant.viscosity_Pas, 'Pa s')}, pressure-viscosity "
                f"{number(lubricant.pressure_viscosity_per_GPa)} 1/GPa, inlet "
                f"{number(lubricant.inlet_temperature_C)} °C, traction model "
                f"{lubricant.traction_model}",
            )
        )
    return rows


#: (variable, units, statistics, column) of the per-ball ranges over the analysed window.
BALL_RANGES = (
    ("contact_load", "N", ("min", "max"), "Q"),
    ("contact_angle", "degree", ("min", "max"), "α"),
    ("max_pressure", "Pa", ("max",), "p"),
    ("truncation_margin", "degree", ("min",), "margin"),
)


def _ball_range_rows(ds):
    """Each ball's min and max of the contact variables over the analysed window (dynamic) or
    the ring angles (a solution over one revolution); the values of a snapshot otherwise."""
    headers, columns = ["ball"], []
    spans = "time" in ds.dims
    window = ds
    if spans:
        start = float(ds.racetrace.metric("analysis_start_time"))
        window = ds.where(ds["time"] >= start)
    over = [d for d in ("time", "ring_angle") if d in ds.dims]
    for race in RACES:
        for name, units, stats, short in BALL_RANGES:
            if name not in ds:
                continue
            values = window[name].sel(race=race)
            for how in stats if over else stats[:1]:  # a snapshot: one value per quantity
                reduced = getattr(values, how)(over) if over else values
                columns.append((reduced, units))
                label = f"{short} {race} {how}" if over else f"{short} {race}"
                headers.append(label)
    rows = []
    for j in range(ds.sizes["ball"]):
        rows.append(
            [str(j + 1)] + [_cell(float(values.isel(ball=j)), units) for values, units in columns]
        )
    return headers, rows


RACES = ("inner", "outer")


def _ellipse_rows(ds):
    last = ds.isel(time=-1) if "time" in ds.dims else ds
    rows = []
    for j in range(ds.sizes["ball"]):
        row = [str(j + 1), _cell(float(last["ball_azimuth"].isel(ball=j)), "degree")]
        for race in RACES:
            c = last.isel(ball=j).sel(race=race)
            row += [
                _cell(float(c["contact_load"]), "N"),
                _cell(float(c["contact_angle"]), "degree"),
                _cell(float(c["ellipse_semi_major"]), "m"),
                _cell(float(c["ellipse_semi_minor"]), "m"),
                _cell(float(c["max_pressure"]), "Pa"),
            ]
        rows.append(row)
    headers = ["ball", "azimuth"]
    for race in RACES:
        r = race[0]
        headers += [f"Q_{r}", f"α_{r}", f"a_{r}", f"b_{r}", f"p_{r}"]
    return headers, rows


def operating_heading(ds) -> str:
    """The result's own operating point as the page heads it (from its coordinates)."""
    from solver import describe_operating_point, operating_from_result

    try:
        return describe_operating_point(operating_from_result(ds))
    except ValueError:  # a result without its operating coordinates: its case title only
        return _case_title(ds)


def run_header(ds, source_name: str) -> str:
    """The HTML header of a run report, headed by the result's own operating point (its
    coordinates), then its case title. A result file is outside input: every value taken from
    it is escaped (:func:`_text`) or written by the report itself (the model, the times)."""
    model = ds.attrs.get("model", "dynamic" if "time" in ds.dims else "quasistatic")
    model = model if model in MODELS else "unknown"
    description = _case_note(ds)
    return (
        f"<h1>racetrace review: {_text(operating_heading(ds))}</h1>"
        f"<p>case: <strong>{_text(_case_title(ds))}</strong></p>"
        f"<p><strong>{model} result</strong> <code>{_text(source_name)}</code> · computed with "
        f"{_text(ds.attrs.get('software', 'racetrace'), 80)} on "
        f"{_when(ds.attrs.get('created'))} · report made {_now()} · bearing geometry: "
        f"<strong>{_text(_provenance(ds), 80)}</strong></p>"
        + (f'<p class="rt-case-note">{_text(description, 2000)}</p>' if description else "")
    )


#: What the 3-D scene shows (on screen under its heading, on paper beside the still).
SCENE_TEXT = (
    "The bearing at the last sample, with its contact ellipses and the contact trajectories of "
    "the run; each raceway is painted where the ellipses ran, by the peak contact pressure there "
    "(the colour scale with the view). The outer ring is drawn apart from the balls and opened "
    "(a sector cut away) so that its raceway and the outer track can be seen: the bearing is not "
    "exploded."
)
SCENE_CAPTION = f"## 3-D scene (drag to turn, wheel to zoom)\n\n{SCENE_TEXT}"


#: The scene's pane: a size from the start; vtk.js's camera-info toggle ("...", a live view's)
#: hidden.
VTK_PANE_CSS = (
    ":host { min-height: 520px; min-width: 300px; } .vtk_info { display: none !important; }"
)


def _vtk_pane(plotter):
    """The vtk.js scene with :data:`VTK_PANE_CSS` in its own shadow root (Panel's VTK pane does
    not pass a pane's ``stylesheets`` on to its model, so they are added to the model here)."""
    from panel.pane.vtk.vtk import VTKRenderWindowSynchronized

    class ReportScene(VTKRenderWindowSynchronized):
        def _get_model(self, doc, root=None, parent=None, comm=None):
            model = super()._get_model(doc, root, parent, comm)
            model.stylesheets = [*model.stylesheets, VTK_PANE_CSS]
            return model

    return ReportScene(plotter.ren_win, height=520, min_width=300, sizing_mode="stretch_width")


def run_sections(ds, source_name: str):
    """The Panel objects of a run report and the decimation notes."""
    import panel as pn

    from . import charts
    from .scene import bearing_plotter, pressure_scale_html, screenshot_png

    notes = []
    sections = [_html(run_header(ds, source_name), stylesheets=[PRINT_CSS])]
    answer = ds  # the metrics of a solution over one revolution span its ring angles
    shown_at = ""
    if "ring_angle" in ds.dims:  # the scene, charts and tables show ring angle 0
        ds = ds.isel(ring_angle=0, drop=True)
        shown_at = " The scene, the charts and the ellipse table below show ring angle 0."
    warnings = answer.racetrace.warnings()
    warn_html = (
        "<ul>" + "".join(f'<li class="rt-warn">{html.escape(w)}</li>' for w in warnings) + "</ul>"
        if warnings
        else "<p>none: the result stays within the model's validity checks</p>"
    )
    sections.append(_section("Result warnings", warn_html))
    sections.append(
        _section(
            "Operating point and bearing",
            _table(("quantity", "value"), _operating_rows(ds)),
        )
    )
    sections.append(_section("Inputs", _table(("input", "value"), _input_rows(answer), (0, 1))))
    window = answer.racetrace.summary().attrs.get("analysed_window", "the quasi-static snapshot")
    life, life_notes = _life_rows(answer)
    sections.append(
        _section(
            "Rating life and friction torque",
            _table(("quantity", "value"), life)
            + "".join(f"<p>{html.escape(n)}</p>" for n in life_notes),
        )
    )
    losses = _loss_rows(answer)
    sections.append(
        _section(
            "Power loss and heat (mean over the analysed window)",
            _table(("source", "power"), losses)
            if losses
            else "<p>A quasi-static result has no power loss of its own: run the dynamic model "
            "(racetrace simulate) for the losses by source and the contact heat.</p>",
        )
    )
    sections.append(
        _section(
            "Film thickness and λ",
            _table(("quantity", "inner", "outer"), _film_rows(answer))
            + f"<p>{html.escape(_film_note(answer))}</p>",
        )
    )
    sections.append(
        _section(
            "Margins against limits",
            _table(("check", "inner", "outer", "limit", "margin"), _margin_rows(answer)),
        )
    )
    sections.append(
        _section(
            "Ring displacement and stiffness",
            _table(("quantity", "value"), _stiffness_rows(answer))
            + "<p>Inner ring relative to the outer ring from the just-touching position, mean "
            "over the analysed window; stiffness = applied load / displacement (secant).</p>",
        )
    )
    sections.append(
        _section(
            "Summary (each race in its own ring's frame)",
            _table(("metric", "inner", "outer"), _summary_rows(answer))
            + f"<p>Analysed window: {html.escape(window)}.{shown_at}</p>",
        )
    )
    headers, rows = _ball_range_rows(answer)
    where = (
        "over the analysed window"
        if "time" in answer.dims
        else "over the ring angles"
        if "ring_angle" in answer.dims
        else "(one snapshot)"
    )
    sections.append(_section(f"Per ball {where}", _table(headers, rows, text_columns=())))
    plotter, note, scale = bearing_plotter(ds)
    if note:
        notes.append(note)
    png = base64.b64encode(screenshot_png(plotter)).decode("ascii")
    # on screen: the live view and its colour scale; on paper: a still of it (with the scene's
    # own colour bar) under one heading, kept on one page
    sections.append(pn.pane.Markdown(SCENE_CAPTION, stylesheets=[PRINT_CSS, SCREEN_ONLY_CSS]))
    sections.append(_vtk_pane(plotter))
    sections.append(  # the report's own markup (numbers and fixed text): not sanitised
        pn.pane.HTML(pressure_scale_html(scale), stylesheets=[SCREEN_ONLY_CSS])
    )
    sections.append(
        pn.pane.HTML(  # only the report's own picture: not sanitised (that would drop data: URLs)
            '<div class="rt-section rt-still"><h2>3-D scene (a still of the interactive view)</h2>'
            f"<p>{html.escape(SCENE_TEXT)}</p>"
            f'<img src="data:image/png;base64,{png}" style="width:100%;max-width:900px" '
            'alt="3-D scene"></div>',
            sizing_mode="stretch_width",
            stylesheets=[PRINT_CSS, PRINT_ONLY_CSS],
        )
    )
    figs = []
    for race in RACES:
        fig, note = charts.raceway_map(ds, race)
        figs.append(fig)
        if note:
            notes.append(note)
    sections.append(pn.pane.Markdown("## Raceway maps", stylesheets=[PRINT_CSS]))
    sections.append(
        pn.GridBox(
            *(
                pn.pane.Bokeh(f, sizing_mode="stretch_width", stylesheets=[CHART_PRINT_CSS])
                for f in figs
            ),
            ncols=2,
            sizing_mode="stretch_width",
            stylesheets=[CHART_GRID_CSS],
        )
    )
    angle, note_a = charts.contact_series(ds, "contact_angle", "contact angle [deg]")
    load, _ = charts.contact_series(ds, "contact_load", "contact load [N]")
    if note_a:
        notes.append(note_a.replace("contact angle [deg]", "contact-angle and load charts"))
    sections.append(pn.pane.Markdown("## Contact angle and load", stylesheets=[PRINT_CSS]))
    for chart in (angle, load):
        sections.append(
            pn.pane.Bokeh(chart, sizing_mode="stretch_width", stylesheets=[CHART_PRINT_CSS])
        )
    headers, rows = _ellipse_rows(ds)
    when = "at the last sample" if "time" in ds.dims else ""
    sections.append(
        _section(f"Contact ellipses {when}".strip(), _table(headers, rows, text_columns=()))
    )
    sections.append(
        _section(
            "Case (as run)",
            f'<pre class="rt-case">{html.escape(ds.attrs.get("case", ""))}</pre>',
        )
    )
    return sections, notes


def _case_title(ds) -> str:
    """The title of the result's case (its ``title``), "result" when it has none."""
    from solver import result_description

    return result_description(ds).get("title") or "result"


def _case_note(ds) -> str:
    """The case's note of what is known about it (its ``description``), "" when it has none."""
    from solver import result_description

    return result_description(ds).get("description", "")


def _section(title: str, body_html: str):
    return _html(
        f'<div class="rt-section"><h2>{html.escape(title)}</h2>{body_html}</div>',
        stylesheets=[PRINT_CSS],
    )


# ---- a study --------------------------------------------------------------------------------
STUDY_CHART_METRICS = (
    ("excursion", "excursion [deg]", 1.0),
    ("band_thickness", "band thickness [deg]", 1.0),
    ("band_width", "band width [deg]", 1.0),
    ("mean_contact_angle", "mean contact angle [deg]", 1.0),
    ("peak_pressure", "peak pressure [GPa]", 1e-9),
)
#: Columns of the study's points table: (variable, short header, scale from SI, unit shown),
#: inner and outer; one unit per column (in the header), so that the column reads down.
STUDY_TABLE_METRICS = (
    ("excursion", "exc", 1.0, "deg"),
    ("band_thickness", "band", 1.0, "deg"),
    ("band_width", "width", 1.0, "deg"),
    ("mean_contact_angle", "α", 1.0, "deg"),
    ("peak_pressure", "p", 1e-9, "GPa"),
    ("largest_load", "Q", 1.0, "N"),
)
#: A metric smaller than this in its table unit is a zero's rounding noise (the excursion of a
#: quasi-static point without radial load, 4e-14 deg) and is shown as 0.
ZERO_NOISE = 1e-9


def _metric_cell(value: float) -> str:
    """A study table cell: ``value`` (in its column's unit) to 4 digits, 0 for rounding noise."""
    return number(0.0 if abs(value) < ZERO_NOISE else value)


#: Where a study report's per-point run reports go: ``<report stem>.points/<point>.<model>.html``.
POINT_REPORTS_SUFFIX = ".points"


def point_report_path(output, point: str, model: str) -> Path:
    """The run report of one study point, next to the study report ``output``."""
    output = Path(output)
    return output.with_name(output.stem + POINT_REPORTS_SUFFIX) / f"{point}.{model}.html"


def study_header(ds) -> str:
    """The HTML header of a study report, every value from the study escaped."""
    return (
        f"<h1>racetrace study review: {_text(ds.attrs.get('title', ''))}</h1>"
        f"<p>Base case <code>{_text(ds.attrs.get('base_case', ''))}</code> · "
        f"{ds.sizes['point']} points · {_text(ds.attrs.get('software_version', ''), 80)} · "
        f"report made {_now()}</p>"
        f"<p>{_text(ds.attrs.get('description', ''), 2000)}</p>"
    )


def _message_kind(message: str) -> str:
    """The short flag of a run's message: its first clause (before the first colon), clipped."""
    first = message.split(" | ")[0].split(":")[0].strip()
    return first if len(first) <= 40 else first[:39] + "…"


TEXT_CLASS = ' class="text"'
#: How the points table writes a model (its legend is below the table).
MODEL_SHORT = {"quasistatic": "qs", "dynamic": "dyn"}


#: Columns of the points table of a bearing-set study: (variable, short header, scale from SI,
#: unit shown); a variable with a ``bearing`` dimension takes a column per bearing.
SET_STUDY_TABLE_METRICS = (
    ("bearing_axial_load", "Fa", 1.0, "N"),
    ("axial_stiffness", "k_ax", 1e-6, "N/µm"),
    ("radial_stiffness", "k_rad", 1e-6, "N/µm"),
    ("tilt_stiffness", "k_tilt", 1e-3, "N m/mrad"),
)


def _study_table_columns(ds) -> list:
    """[(header, cell(i, j) -> value in the header's unit)] of the points table: each metric of
    :data:`STUDY_TABLE_METRICS` inner and outer and the cage slip; for a bearing-set study (a
    ``bearing`` dimension) :data:`SET_STUDY_TABLE_METRICS`, per bearing where they have one."""

    def cell(var, scale, *index):
        values = ds[var].values
        return lambda i, j: float(values[(i, j, *index)]) * scale

    columns = []
    if "bearing" in ds.dims:
        for var, short, scale, unit in SET_STUDY_TABLE_METRICS:
            if "bearing" in ds[var].dims:
                columns += [
                    (f"{short} {name} {unit}", cell(var, scale, b))
                    for b, name in enumerate(str(n) for n in ds["bearing"].values)
                ]
            else:
                columns.append((f"{short} {unit}", cell(var, scale)))
        return columns
    for var, short, scale, unit in STUDY_TABLE_METRICS:
        columns += [
            (f"{short}_i {unit}", cell(var, scale, 0)),
            (f"{short}_o {unit}", cell(var, scale, 1)),
        ]
    columns.append(("cage slip", cell("cage_slip", 1.0)))
    return columns


def _study_table(ds, links: dict):
    """(table HTML, notes HTML) of a study's points, laid out to fit a 1300-px page: one row per
    run under a row naming its sweep, a note number per kind of message (its first clause) and
    each message's full text once below the table. ``links``: {(point, model): relative URL} of
    the point reports that exist."""
    from solver import study_runs

    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    headers = ["point", "model", *(k.rsplit(".", 1)[-1].replace("_", " ") for k in keys)]
    headers.append("status")
    columns = _study_table_columns(ds)
    headers += [header for header, _cell in columns]
    headers.append("note")
    kinds: dict[str, int] = {}  # kind of message -> note number
    notes: dict[str, dict[str, list[str]]] = {}  # kind -> full message -> runs
    body, sweep = [], None
    for i, j, status in study_runs(ds):
        point, model = str(ds["point"].values[i]), str(ds["model"].values[j])
        if str(ds["sweep"].values[i]) != sweep:
            sweep = str(ds["sweep"].values[i])
            body.append(
                f'<tr class="rt-sweep"><td class="text" colspan="{len(headers)}">'
                f"{_text(sweep, 120)}</td></tr>"
            )
        url = links.get((point, model))
        name = (
            f'<a href="{html.escape(url, quote=True)}">{html.escape(point)}</a>'
            if url
            else html.escape(point)
        )
        row = [name, html.escape(MODEL_SHORT.get(model, model))]
        row += [html.escape(number(ds[k].values[i], 5)) for k in keys]
        row.append(html.escape(status))
        row += [html.escape(_metric_cell(cell(i, j))) for _header, cell in columns]
        message = str(ds["message"].values[i, j])
        flag = ""
        if message:
            kind = _message_kind(message)
            flag = f"[{kinds.setdefault(kind, len(kinds) + 1)}]"
            notes.setdefault(kind, {}).setdefault(message, []).append(f"{point} {model}")
        row.append(flag)
        text = (0, 1, len(headers) - 1)
        cells = (f"<td{TEXT_CLASS if k in text else ''}>{v}</td>" for k, v in enumerate(row))
        body.append("<tr>" + "".join(cells) + "</tr>")
    head = "".join(f"<th>{html.escape(h)}</th>" for h in headers)
    table = (
        f'<table class="rt-table rt-points"><thead><tr>{head}</tr></thead>'
        f"<tbody>{''.join(body)}</tbody></table>"
    )
    listed = "".join(
        f"<li>[{kinds[kind]}] <strong>{html.escape(kind)}</strong><ul>"
        + "".join(
            f"<li>{html.escape(', '.join(runs))}: {_text(message, 2000)}</li>"
            for message, runs in messages.items()
        )
        + "</ul></li>"
        for kind, messages in notes.items()
    )
    notes_html = f'<ul class="rt-notes">{listed}</ul>' if listed else ""
    return table, notes_html


def study_sections(ds, links=None):
    import panel as pn

    from . import charts

    sections = [_html(study_header(ds), stylesheets=[PRINT_CSS])]
    for sweep in dict.fromkeys(str(s) for s in ds["sweep"].values):
        if "bearing" in ds.dims:  # a study of bearing-set points
            figs = charts.set_study_charts(ds, sweep, SET_STUDY_CHART_METRICS)
        else:
            figs = charts.study_metric_charts(ds, sweep, STUDY_CHART_METRICS)
        if figs:
            sections.append(_html(f"<h2>{_text(sweep)}</h2>", stylesheets=[PRINT_CSS]))
            sections.append(
                pn.GridBox(
                    *(pn.pane.Bokeh(f, sizing_mode="stretch_width") for f in figs),
                    ncols=2,
                    sizing_mode="stretch_width",
                    stylesheets=[CHART_GRID_CSS],
                )
            )
    table, notes_html = _study_table(ds, links or {})
    point_note = (
        "<p>Each point name links to its own run report.</p>"
        if links
        else "<p>Run reports of the points: <code>racetrace report STUDY_DIR --points</code> "
        "writes them beside this page and links them here.</p>"
    )
    if "bearing" in ds.dims:
        title = "Points (each bearing's loads in its own direction, the set's stiffness)"
        legend = (
            "qs = quasi-static; Fa = axial load each bearing carries in its own direction (the "
            "preload included), k_ax, k_rad, k_tilt = the set's axial, radial and tilting "
            "stiffness at the load point; note [n]: the run's message, in full below."
        )
    else:
        title = "Points (each race in its own ring's frame)"
        legend = (
            "qs = quasi-static, dyn = dynamic; exc = trajectory excursion, band = band "
            "thickness, width = band width, α = mean contact angle, p = peak pressure, Q = largest "
            "contact load; note [n]: the run's message, in full below."
        )
    sections.append(_section(title, table + f"<p>{legend}</p>" + notes_html + point_note))
    return sections, []


# ---- the page -------------------------------------------------------------------------------
def _load(source):
    """('run', Dataset, name), ('set', Dataset, name) (a bearing set's result) or ('study',
    Dataset, name) for a result file or study folder."""
    from solver import CaseError, Problem, load_result, open_study, study_dataset

    path = Path(source)
    if path.is_dir():
        return "study", study_dataset(open_study(path)), path.name
    if not path.is_file():
        raise CaseError(Problem("report", f"{source}: no such result file or study folder"))
    ds = load_result(path, str(source))  # CaseError naming what the file lacks
    if ds.attrs.get("racetrace_kind") == "study":
        return "study", ds, path.name
    if "bearing" in ds.dims:  # a bearing set's result (quasi-static, or a dynamic run)
        return "set", ds, path.name
    return "run", ds, path.name


def _point_links(source, ds, output, point_reports: bool, log=None) -> dict:
    """{(point, model): URL relative to ``output``} of the study's point reports that exist
    beside it (:func:`point_report_path`); with ``point_reports`` those missing are built first
    from the study folder's point results."""
    from solver import StudyFolder, study_runs

    folder = Path(source) if Path(source).is_dir() else Path(ds.attrs.get("study_folder", ""))
    links = {}
    for i, j, status in study_runs(ds):
        point, model = str(ds["point"].values[i]), str(ds["model"].values[j])
        target = point_report_path(output, point, model)
        result = StudyFolder(folder).result_path(point, model)
        if point_reports and status == "done" and result.is_file() and not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            if log is not None:
                log(f"point report {target.name}")
            build_report(result, target)
        if target.is_file():
            links[(point, model)] = f"{target.parent.name}/{target.name}"
    return links


def build_report(source, output, point_reports: bool = False, log=None) -> dict:
    """Write the report of ``source`` (a result NetCDF file or a study folder) to ``output``.

    For a study, each point name links to the point's run report when it exists beside the page
    (``<output stem>.points/<point>.<model>.html``); ``point_reports`` builds those missing from
    the study folder's results first (``log``: callable(str) told of each).

    Returns ``{"path", "bytes", "kind", "notes", "unresolved"}``: the decimation notes shown on the
    page and any external URL that could not be inlined (empty when the page is standalone)."""
    import panel as pn
    from bokeh.resources import INLINE

    import solver  # noqa: F401  (registers ds.racetrace)
    from solver import atomic_write

    from .deferred_render import with_deferred_render
    from .offline import external_urls, inline_cdn_links

    kind, ds, name = _load(source)
    pn.config.inline = True
    if kind == "set":
        from .bearing_set import set_sections

        sections, notes = set_sections(ds, name)
    elif kind == "run":
        sections, notes = run_sections(ds, name)
    else:
        links = _point_links(source, ds, output, point_reports, log)
        sections, notes = study_sections(ds, links)
    if notes:
        sections.append(
            _section(
                "Decimated for this page",
                "<ul>" + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>"
                "<p>The full result keeps every sample.</p>",
            )
        )
    page = pn.Column(
        *sections,
        sizing_mode="stretch_width",
        styles={"max-width": "1200px", "margin": "0 auto"},
        stylesheets=[PAGE_PRINT_CSS],
    )
    output = Path(output)

    def write(tmp):
        raw = Path(tmp).with_suffix(".raw.html")
        try:
            page.save(str(raw), embed=True, resources=INLINE, title=f"racetrace review: {name}")
            text, _missing = inline_cdn_links(raw.read_text(encoding="utf-8"))
            if kind == "run":  # the 3-D scene: no drawing into a canvas without a size
                text = with_deferred_render(text)
        finally:
            raw.unlink(missing_ok=True)
        Path(tmp).write_text(text, encoding="utf-8")

    atomic_write(output, write)
    text = output.read_text(encoding="utf-8")
    return {
        "path": output,
        "bytes": output.stat().st_size,
        "kind": kind,
        "notes": notes,
        "unresolved": external_urls(text),
    }
