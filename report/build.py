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

import numpy as np

#: Top-level modules of the ``report`` extra (checked before building).
REPORT_MODULES = ("panel", "bokeh", "nh3", "pyvista", "vtkmodules", "PIL")

PRINT_CSS = """
body { font-family: sans-serif; }
.rt-table { border-collapse: collapse; font-size: 13px; margin: 4px 0 12px 0; }
.rt-table th, .rt-table td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
.rt-table th { background: #f2f2f2; }
.rt-table td.text, .rt-table th.text { text-align: left; }
.rt-warn { color: #8a4b00; }
pre.rt-case { font-size: 11px; background: #f7f7f7; padding: 6px; white-space: pre-wrap; }
@media print { .rt-section { break-inside: avoid; page-break-inside: avoid; } }
"""
#: Panel components live in shadow roots: each gets its own stylesheet for screen and print.
#: The page column hides the vtk.js scene when printing (a still image stands in for it).
PAGE_PRINT_CSS = (
    "@media print { .bk-panel-models-vtk-VTKSynchronizedPlot { display: none !important; } }"
)
PRINT_ONLY_CSS = ":host { display: none; } @media print { :host { display: block; } }"


#: What the report's HTML panes may hold after sanitising (:func:`_html`): the tags and the
#: ``class`` attribute this module writes; anything else (scripts, event handlers, links) is
#: dropped, a second guard behind escaping every value read from a result or a case.
ALLOWED_TAGS = frozenset(
    "div h1 h2 p strong em code ul li table thead tbody tr th td pre span br".split()
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

    return nh3.clean(text, tags=set(ALLOWED_TAGS), attributes={"*": {"class"}})


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


def _fmt(value, digits: int = 4) -> str:
    try:
        value = float(value)
    except (TypeError, ValueError):
        return str(value)
    return f"{value:.{digits}g}" if math.isfinite(value) else "-"


def _provenance(ds) -> str:
    """Where the bearing's geometry comes from (the result's ``bearing_provenance``)."""
    from solver import result_description

    return result_description(ds).get("bearing_provenance", "unknown")


# ---- one run --------------------------------------------------------------------------------
def _operating_rows(ds):
    from solver import OPERATING_FIELDS, RPM, variable

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
            rows.append((spec.long_name, _fmt(float(value) / RPM, 6), "rpm"))
        elif value.dtype.kind in "fiu":
            rows.append((spec.long_name, _fmt(value, 6), spec.units))
        else:
            rows.append((spec.long_name, str(value), spec.units))
    return rows


def _summary_rows(ds):
    from solver import (
        METRICS,
        POINT_METRICS,  # the metrics a study keeps, rows of the table
    )

    rows = []
    # a dynamic run also shows the check of its own integration
    checks = ("energy_balance_residual",) if "time" in ds.dims else ()
    for name in (*POINT_METRICS, *checks):
        row, value = METRICS[name], ds.racetrace.metric(name)
        if row.dims:
            inner, outer = (_fmt(float(value.sel(race=race))) for race in ("inner", "outer"))
            rows.append((row.long_name, inner, outer, row.units))
        else:
            rows.append((row.long_name, _fmt(float(value)), "", row.units))
    for name in TORQUE_ROWS:  # the model's friction torque beside the empirical estimates
        row, value = METRICS[name], ds.racetrace.metric(name)
        if name == "mean_friction_torque" and "time" not in ds.dims:
            continue  # a quasi-static result has no friction torque of its own
        number = float(value)
        text = _fmt(number) if math.isfinite(number) else value.attrs.get("note", "-")
        rows.append((row.long_name, text, "", row.units))
    return rows


#: Metrics of the friction-torque rows of a run's summary table.
TORQUE_ROWS = ("mean_friction_torque", "friction_torque_palmgren", "friction_torque_skf")


def _ellipse_rows(ds):
    last = ds.isel(time=-1) if "time" in ds.dims else ds
    rows = []
    for j in range(ds.sizes["ball"]):
        row = [str(j + 1), _fmt(float(last["ball_azimuth"].isel(ball=j)), 4)]
        for race in ("inner", "outer"):
            c = last.isel(ball=j).sel(race=race)
            row += [
                _fmt(float(c["contact_load"]), 4),
                _fmt(float(c["contact_angle"]), 4),
                _fmt(float(c["ellipse_semi_major"]) * 1e3, 4),
                _fmt(float(c["ellipse_semi_minor"]) * 1e3, 4),
                _fmt(float(c["max_pressure"]) * 1e-9, 4),
            ]
        rows.append(row)
    headers = ["ball", "azimuth deg"]
    for race in ("inner", "outer"):
        r = race[0]
        headers += [f"Q_{r} N", f"alpha_{r} deg", f"a_{r} mm", f"b_{r} mm", f"p_{r} GPa"]
    return headers, rows


def run_header(ds, source_name: str) -> str:
    """The HTML header of a run report. A result file is outside input: every value taken from
    it is escaped (:func:`_text`) or written by the report itself (the model, the times)."""
    model = ds.attrs.get("model", "dynamic" if "time" in ds.dims else "quasistatic")
    model = model if model in MODELS else "unknown"
    title = _case_title(ds)
    description = _case_note(ds)
    return (
        f"<h1>racetrace review: {_text(title)}</h1>"
        f"<p><strong>{model} result</strong> <code>{_text(source_name)}</code> · computed with "
        f"{_text(ds.attrs.get('software', 'racetrace'), 80)} on "
        f"{_when(ds.attrs.get('created'))} · report made {_now()} · bearing geometry: "
        f"<strong>{_text(_provenance(ds), 80)}</strong></p>"
        + (f'<p class="rt-case-note">{_text(description, 2000)}</p>' if description else "")
    )


def run_sections(ds, source_name: str):
    """The Panel objects of a run report and the decimation notes."""
    import panel as pn

    from . import charts
    from .scene import bearing_plotter, screenshot_png

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
            _table(("quantity", "value", "units"), _operating_rows(ds)),
        )
    )
    window = answer.racetrace.summary().attrs.get("analysed_window", "the quasi-static snapshot")
    sections.append(
        _section(
            "Summary (each race in its own ring's frame)",
            _table(("metric", "inner", "outer", "units"), _summary_rows(answer))
            + f"<p>Analysed window: {html.escape(window)}.{shown_at}</p>",
        )
    )
    plotter, note = bearing_plotter(ds)
    if note:
        notes.append(note)
    png = base64.b64encode(screenshot_png(plotter)).decode("ascii")
    vtk = pn.pane.VTK(plotter.ren_win, height=520, sizing_mode="stretch_width")
    sections.append(
        pn.pane.Markdown(
            "## 3-D scene (drag to turn, wheel to zoom)\n\nThe bearing at the last sample, with "
            "the contact trajectories of the run on both raceways; ellipses coloured by peak "
            "pressure."
        )
    )
    sections.append(vtk)
    sections.append(
        pn.pane.HTML(  # only the report's own picture: not sanitised (that would drop data: URLs)
            f'<img src="data:image/png;base64,{png}" style="width:100%;max-width:900px" '
            'alt="3-D scene">',
            sizing_mode="stretch_width",
            stylesheets=[PRINT_ONLY_CSS],
        )
    )
    figs = []
    for race in ("inner", "outer"):
        fig, note = charts.raceway_map(ds, race)
        figs.append(fig)
        if note:
            notes.append(note)
    sections.append(pn.pane.Markdown("## Raceway maps"))
    sections.append(pn.Row(*(pn.pane.Bokeh(f, sizing_mode="stretch_width") for f in figs)))
    angle, note_a = charts.contact_series(ds, "contact_angle", "contact angle [deg]")
    load, _ = charts.contact_series(ds, "contact_load", "contact load [N]")
    if note_a:
        notes.append(note_a.replace("contact angle [deg]", "contact-angle and load charts"))
    sections.append(pn.pane.Markdown("## Contact angle and load"))
    sections.append(pn.pane.Bokeh(angle, sizing_mode="stretch_width"))
    sections.append(pn.pane.Bokeh(load, sizing_mode="stretch_width"))
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
    ("mean_contact_angle", "mean contact angle [deg]", 1.0),
    ("peak_pressure", "peak pressure [GPa]", 1e-9),
)


def study_header(ds) -> str:
    """The HTML header of a study report, every value from the study escaped."""
    return (
        f"<h1>racetrace study review: {_text(ds.attrs.get('title', ''))}</h1>"
        f"<p>Base case <code>{_text(ds.attrs.get('base_case', ''))}</code> · "
        f"{ds.sizes['point']} points · {_text(ds.attrs.get('software_version', ''), 80)} · "
        f"report made {_now()}</p>"
        f"<p>{_text(ds.attrs.get('description', ''), 2000)}</p>"
    )


def study_sections(ds):
    import panel as pn

    from solver import study_runs

    from . import charts

    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    sections = [_html(study_header(ds), stylesheets=[PRINT_CSS])]
    for sweep in dict.fromkeys(str(s) for s in ds["sweep"].values):
        select = np.asarray(ds["sweep"].values) == sweep
        varied = [k for k in keys if len(set(np.asarray(ds[k].values)[select].tolist())) > 1]
        if not varied:
            continue
        figs = charts.study_metric_charts(ds, sweep, varied[0], STUDY_CHART_METRICS)
        if figs:
            sections.append(_html(f"<h2>{_text(sweep)}</h2>", stylesheets=[PRINT_CSS]))
            sections.append(
                pn.GridBox(
                    *(pn.pane.Bokeh(f, sizing_mode="stretch_width") for f in figs),
                    ncols=2,
                    sizing_mode="stretch_width",
                )
            )
    headers = ["point", "sweep", "model", *(k.rsplit(".", 1)[-1] for k in keys), "status"]
    columns = (
        ("excursion", "exc", "deg", 1.0),
        ("band_thickness", "band", "deg", 1.0),
        ("mean_contact_angle", "alpha", "deg", 1.0),
        ("peak_pressure", "p", "GPa", 1e-9),
        ("largest_load", "Q", "N", 1.0),
    )
    for _v, short, unit, _s in columns:
        headers += [f"{short}_i {unit}", f"{short}_o {unit}"]
    headers += ["cage slip", "message"]
    rows = []
    for i, j, status in study_runs(ds):
        row = [str(ds["point"].values[i]), str(ds["sweep"].values[i]), str(ds["model"].values[j])]
        row += [_fmt(ds[k].values[i], 5) for k in keys]
        row.append(status)
        for var, _short, _unit, scale in columns:
            for k in range(2):  # inner, outer
                row.append(_fmt(float(ds[var].values[i, j, k]) * scale))
        row.append(_fmt(float(ds["cage_slip"].values[i, j])))
        row.append(str(ds["message"].values[i, j])[:200])
        rows.append(row)
    sections.append(
        _section(
            "Points (each race in its own ring's frame)",
            _table(headers, rows, text_columns=(0, 1, 2, len(headers) - 1)),
        )
    )
    return sections, []


# ---- the page -------------------------------------------------------------------------------
def _load(source):
    """('run', Dataset, name) or ('study', Dataset, name) for a result file or study folder."""
    from solver import CaseError, Problem, load_result, open_study, study_dataset

    path = Path(source)
    if path.is_dir():
        return "study", study_dataset(open_study(path)), path.name
    if not path.is_file():
        raise CaseError(Problem("report", f"{source}: no such result file or study folder"))
    ds = load_result(path, str(source))  # CaseError naming what the file lacks
    if ds.attrs.get("racetrace_kind") == "study":
        return "study", ds, path.name
    return "run", ds, path.name


def build_report(source, output) -> dict:
    """Write the report of ``source`` (a result NetCDF file or a study folder) to ``output``.

    Returns ``{"path", "bytes", "kind", "notes", "unresolved"}``: the decimation notes shown on the
    page and any external URL that could not be inlined (empty when the page is standalone)."""
    import panel as pn
    from bokeh.resources import INLINE

    import solver  # noqa: F401  (registers ds.racetrace)
    from solver import atomic_write

    from .offline import external_urls, inline_cdn_links

    kind, ds, name = _load(source)
    pn.config.inline = True
    if kind == "run":
        sections, notes = run_sections(ds, name)
    else:
        sections, notes = study_sections(ds)
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
