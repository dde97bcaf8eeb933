"""Page layout (trame + Vuetify 3): widgets bound to the state of :class:`app.state.RacetraceApp`.

Stable element ids used by tests: run-button, cancel-button, progress, status, view-3d, play-button,
time-slider, case-select, chart-contact-angle, chart-raceway-map, field-<name> for every case
input (its validation message is shown inside the same element) and, in the run comparison panel,
compare-select, compare-legend, compare-message, chart-compare-runs, chart-compare-angle,
chart-compare-load and compare-summary; ball-legend over the 3-D view.
"""

from __future__ import annotations

from trame.ui.vuetify3 import SinglePageWithDrawerLayout
from trame.widgets import client, html
from trame.widgets import vuetify3 as v3

from . import lazy_charts
from .charts import HELP, SUMMARY_COLUMNS
from .lessons import widgets as lesson_widgets

_SECTION_TITLES = {
    "bearing": "Bearing",
    "operating": "Speed and loads",
    "lubricant": "Lubricant",
    "cage": "Cage",
    "simulation": "Run length",
    "": "Case",
}


def _field(f) -> None:
    """One case input wrapped in ``div#field-<name>`` with its message inside."""
    tooltip = f.help.replace('"', "'")  # the help text is shown as a tooltip
    with html.Div(id=f"field-{f.name}", classes="mb-1", title=tooltip):
        common = dict(
            label=f.label,
            v_model=(f"fv_{f.name}",),
            density="compact",
            placeholder=(f"placeholders.{f.name}",),  # the default used when left empty
            persistent_placeholder=bool(f.default_text),
        )
        if f.kind in ("choice", "bool", "material"):
            # Vuetify's select fails on error-messages here: the message goes in a div below.
            items = ["true", "false"] if f.kind == "bool" else list(f.choices)
            widget = v3.VCombobox if f.kind == "material" else v3.VSelect
            # a plain list would be read by trame as (state name, default): pass a JS literal
            literal = "[" + ", ".join("'" + str(c).replace("'", "\\'") + "'" for c in items) + "]"
            widget(items=(literal,), hide_details=True, error=(f"!!fe_{f.name}",), **common)
            html.Div(
                f"{{{{ fe_{f.name} }}}}",
                v_if=f"fe_{f.name}",
                classes="text-error text-caption px-3",
            )
        else:
            v3.VTextField(
                error_messages=(f"fe_{f.name} ? [fe_{f.name}] : []",),
                hide_details="auto",
                **common,
            )


def _chart(element_id: str, key: str, help_key: str, height: int = 250) -> None:
    # highlighted when a lesson points at it; the one chart shown in presenter mode
    with html.Div(id=element_id, classes=lesson_widgets.chart_classes(key.removeprefix("chart_"))):
        lazy_charts.ChartFigure(
            key, display_mode_bar=False, style=f"height: {height}px; width: 100%;"
        )
        html.Div(HELP[help_key], classes="text-caption text-medium-emphasis px-2")


def build_ui(app) -> SinglePageWithDrawerLayout:
    """Build the page for ``app`` (a :class:`RacetraceApp` whose scene already exists)."""
    from trame_pyvista.rca_view import PyVistaRCAView

    server = app.server
    ctrl = server.controller
    # The chart library is loaded once the first 3-D frame is on screen (see app.lazy_charts).
    lazy_charts.enable(server)
    with SinglePageWithDrawerLayout(server, full_height=True) as layout:
        client.Script(lazy_charts.LOAD_AFTER_FIRST_FRAME)
        lesson_widgets.page_assets()
        layout.title.set_text("racetrace")
        layout.footer.hide()  # trame's footer covered the chart captions
        with layout.toolbar:
            v3.VSpacer()
            v3.VChip(
                "out of date: the form has changed",
                id="result-stale",
                v_show="result_stale",
                color="warning",
                size="small",
                classes="mr-2",
                title="The result on show is not of the case in the form",
            )
            html.Div("{{ result_label }}", id="result-label", classes="text-body-2 mr-4")
            lesson_widgets.presenter_button()

        with layout.drawer as drawer:
            drawer.width = 380
            with html.Div(classes="pa-3"):
                with v3.VRow(dense=True, align="center"):
                    with v3.VCol():
                        with html.Div(id="case-select"):
                            v3.VSelect(
                                label="Shipped case or catalogue bearing",
                                v_model=("case_name",),
                                items=("case_items",),
                                density="compact",
                                hide_details=True,
                            )
                    with v3.VCol(cols="auto"):
                        v3.VBtn(
                            icon="mdi-restore",
                            click=ctrl.reset_case,
                            size="small",
                            variant="text",
                            id="case-reset",
                            title="Undo the edits: back to the values of the chosen case",
                        )
                with v3.VRow(classes="my-1", dense=True):
                    with v3.VCol():
                        v3.VFileInput(
                            label="Upload a case (.toml)",
                            v_model=("uploaded_case",),
                            accept=".toml",
                            density="compact",
                            hide_details=True,
                            id="case-upload",
                        )
                    with v3.VCol(cols="auto"):
                        # a plain link: Vuetify's button drops the download attribute
                        with html.A(
                            href=("case_valid ? case_toml_href : undefined",),
                            download=("case_file_name",),
                            id="case-download",
                            title="Download the case as a TOML case file",
                            classes=(
                                "case_valid ? 'v-btn v-btn--size-small v-btn--variant-tonal pa-2'"
                                " : 'v-btn v-btn--size-small v-btn--disabled pa-2'",
                            ),
                            style="text-decoration: none;",
                        ):
                            v3.VIcon("mdi-download", size="small")
                            html.Span("TOML")
                html.Div("{{ case_message }}", classes="text-error text-caption", id="case-message")
                section = None
                for f in app.form.fields:
                    if f.section != section:
                        section = f.section
                        html.Div(
                            _SECTION_TITLES.get(section, section.title()),
                            classes="text-subtitle-2 mt-3 mb-1",
                        )
                    _field(f)

        with layout.content:
            with v3.VContainer(
                fluid=True, classes=("presenter ? 'pa-2 rt-presenter' : 'pa-2'",), id="content"
            ):
                with v3.VRow(dense=True):
                    # the 3-D view stays in sight while the chart column scrolls
                    with v3.VCol(
                        cols=12,
                        md=7,
                        style="position: sticky; top: 64px; align-self: flex-start;",
                    ):
                        # fills the height the window leaves; the render follows its size, so
                        # the picture keeps its aspect ratio at any window size
                        with html.Div(
                            id="view-3d",
                            style="height: calc(100vh - 330px); min-height: 320px; "
                            "position: relative;",
                        ):
                            view = PyVistaRCAView(
                                app.result.plotter, style="width: 100%; height: 100%;"
                            )
                            app.result.view = view
                            _ball_legend()
                        html.Div(
                            "{{ closeup_numbers }}",
                            id="closeup-numbers",
                            v_show="closeup_numbers",
                            classes="text-caption px-1",
                        )
                        html.Div(
                            "{{ scene_note }}",
                            id="scene-note",
                            classes="text-caption text-medium-emphasis px-1",
                            title="What you see",
                        )
                        _time_controls()
                        with html.Div(classes=lesson_widgets.HIDE):
                            _scene_controls(ctrl)
                            _export_controls(ctrl)
                    with v3.VCol(cols=12, md=5, classes="rt-side"):
                        lesson_widgets.lessons_panel(ctrl)
                        with html.Div(classes=lesson_widgets.HIDE):
                            _run_panel(ctrl)
                        _chart("chart-contact-angle", "chart_contact_angle", "contact_angle")
                        _raceway_map_controls()
                        _chart("chart-raceway-map", "chart_raceway_map", "raceway_map")
                        html.Div(
                            "{{ raceway_metrics }}",
                            id="raceway-metrics",
                            classes="text-caption px-2 mb-2",
                        )
                        with v3.VExpansionPanels(
                            v_model=("open_panels",), multiple=True, variant="accordion"
                        ):
                            for title, key in (
                                ("Load versus azimuth", "load_azimuth"),
                                ("Contact ellipses", "ellipse"),
                                ("Cage speed", "cage_speed"),
                                ("Quasi-static versus dynamic", "comparison"),
                            ):
                                with v3.VExpansionPanel(title=title, value=key):
                                    with v3.VExpansionPanelText():
                                        help_key = key if key in HELP else "contact_angle"
                                        _chart(
                                            f"chart-{key.replace('_', '-')}",
                                            f"chart_{key}",
                                            help_key,
                                        )
                            with v3.VExpansionPanel(
                                title="Compare runs side by side",
                                value="compare",
                                classes=lesson_widgets.HIDE,
                            ):
                                with v3.VExpansionPanelText():
                                    with html.Div(id="compare-select"):
                                        v3.VSelect(
                                            label="Compare with saved runs (any number)",
                                            v_model=("compare_ids",),
                                            items=("runs",),
                                            density="compact",
                                            multiple=True,
                                            chips=True,
                                            closable_chips=True,
                                            clearable=True,
                                            hide_details=True,
                                        )
                                    _compare_panel()
                            with v3.VExpansionPanel(title="Studies", value="studies"):
                                with v3.VExpansionPanelText():
                                    _studies_panel(ctrl)
    return layout


def _ball_legend() -> None:
    """``div#ball-legend`` over the top of the 3-D view: each ball's number in the colour of its
    marking (and of its trace and its raceway-map samples), state ``ball_legend``."""
    with html.Div(
        id="ball-legend",
        v_show="ball_legend.length && (show_balls || show_traces)",
        title="Ball colours: the marking on each ball, its trace and its samples in the raceway "
        "map coloured by ball",
        style="position: absolute; top: 4px; left: 4px; right: 18%; display: flex; "
        "flex-wrap: wrap; align-items: center; gap: 2px 6px; padding: 2px 6px; "
        "background: rgba(255, 255, 255, 0.8); border-radius: 4px; font-size: 12px; "
        "line-height: 16px; pointer-events: none; z-index: 2;",
    ):
        html.Span("balls", classes="font-weight-medium mr-1")
        with html.Span(
            v_for="item in ball_legend",
            key="item.ball",
            classes="rt-ball-entry",
            style="white-space: nowrap;",
        ):
            html.Span(
                style=(
                    "{display: 'inline-block', width: '10px', height: '10px', "
                    "borderRadius: '50%', marginRight: '2px', verticalAlign: 'middle', "
                    "background: item.colour}",
                ),
            )
            html.Span("{{ item.ball }}")


def _study_builder(ctrl) -> None:
    """``div#study-build``: a study built from the case in the form (app.components.studies)."""
    with html.Div(id="study-build", classes="mt-2 pa-2", style="border: 1px solid #ddd;"):
        html.Div("Build a study from the current case", classes="text-subtitle-2")
        for n in (1, 2):
            with v3.VRow(dense=True, align="center"):
                with v3.VCol(cols=7), html.Div(id=f"study-key{n}"):
                    v3.VAutocomplete(
                        label="key to vary" if n == 1 else "second key (optional)",
                        v_model=(f"study_key{n}",),
                        items=("study_key_items",),
                        density="compact",
                        hide_details=True,
                        clearable=n == 2,
                        disabled=("study_running",),
                    )
                with v3.VCol(cols=5), html.Div(id=f"study-values{n}"):
                    v3.VTextField(
                        label="values",
                        v_model=(f"study_values{n}",),
                        placeholder="0, 300, 600 or 0:1500:6",
                        persistent_placeholder=True,
                        density="compact",
                        hide_details=True,
                        title="A list (0, 300, 600) or start:stop:count (0:1500:6)",
                        disabled=("study_running",),
                    )
        with v3.VRow(dense=True, align="center"):
            with v3.VCol(cols=4), html.Div(id="study-combine"):
                v3.VSelect(
                    label="two keys",
                    v_model=("study_combine",),
                    items=(
                        "[{title: 'grid (every pair)', value: 'grid'}, "
                        "{title: 'zipped (side by side)', value: 'zip'}]",
                    ),
                    density="compact",
                    hide_details=True,
                )
            with v3.VCol(cols=4), html.Div(id="study-model"):
                v3.VSelect(
                    label="model",
                    v_model=("study_model",),
                    items=(
                        "[{title: 'quasi-static', value: 'quasistatic'}, "
                        "{title: 'dynamic', value: 'dynamic'}, {title: 'both', value: 'both'}]",
                    ),
                    density="compact",
                    hide_details=True,
                )
            with v3.VCol(cols=4), html.Div(id="study-revolutions"):
                v3.VTextField(
                    label="revolutions (dynamic)",
                    v_model=("study_revolutions",),
                    density="compact",
                    hide_details=True,
                    disabled=("study_model === 'quasistatic'",),
                )
        v3.VBtn(
            "Build and run",
            id="study-build-run",
            click=ctrl.study_build,
            disabled=("study_running || !case_valid",),
            color="primary",
            size="small",
            classes="mt-1",
            title="Write a study file with the case in the form as its base and run it",
        )


def _studies_panel(ctrl) -> None:
    """Run a shipped study or one built from the current case (app.components.studies), open
    earlier results, chart a metric and open any point."""
    with html.Div(id="studies", classes="mb-2"):
        with html.Div(id="study-results"):
            v3.VSelect(
                label="Open study results",
                v_model=("study_results",),
                items=("study_results_items",),
                density="compact",
                hide_details=True,
                disabled=("study_running",),
                no_data_text="no study results yet",
                classes="mb-2",
            )
        with v3.VRow(dense=True, align="center"):
            with v3.VCol(cols=6):
                v3.VSelect(
                    label="Shipped study",
                    v_model=("study_name",),
                    items=("study_names",),
                    density="compact",
                    hide_details=True,
                    disabled=("study_running",),
                )
            with v3.VCol(cols="auto"):
                v3.VBtn(
                    "Run study",
                    id="study-run",
                    click=ctrl.study_run,
                    disabled=("study_running",),
                    color="primary",
                    size="small",
                )
            with v3.VCol(cols="auto"):
                v3.VBtn(
                    "Cancel",
                    id="study-cancel",
                    click=ctrl.study_cancel,
                    disabled=("!study_running",),
                    size="small",
                )
        _study_builder(ctrl)
        v3.VProgressLinear(
            id="study-progress",
            model_value=("study_progress",),
            v_show="study_running",
            height=6,
            color="primary",
            classes="mt-2",
        )
        html.Div(
            "{{ study_status }}",
            id="study-status",
            classes=(
                "study_status.startsWith('error') ? 'text-caption my-1 text-error' : "
                "'text-caption my-1'",
            ),
        )
        with v3.VRow(dense=True):
            with v3.VCol(cols=6):
                v3.VSelect(
                    label="Sweep",
                    v_model=("study_sweep",),
                    items=("study_sweeps",),
                    density="compact",
                    hide_details=True,
                )
            with v3.VCol(cols=6):
                v3.VSelect(
                    label="Metric",
                    v_model=("study_metric",),
                    items=("study_metric_items",),
                    density="compact",
                    hide_details=True,
                )
        with html.Div(id="chart-study", classes="mb-2"):
            # a click on a point opens that point's run (its (point, model) is the customdata)
            lazy_charts.ChartFigure(
                "chart_study",
                display_mode_bar=False,
                style="height: 280px; width: 100%;",
                click=(
                    ctrl.study_open,
                    "[$event.points[0].customdata[0], $event.points[0].customdata[1]]",
                ),
            )
        with v3.VTable(density="compact", id="study-table"):
            with html.Thead():
                with html.Tr():
                    for head in (
                        "point",
                        "model",
                        "values",
                        "status",
                        "exc i/o deg",
                        "band i/o deg",
                        "",
                    ):
                        html.Th(head)
            with html.Tbody():
                with html.Tr(v_for="row in study_rows", key="row.key"):
                    html.Td("{{ row.point }}")
                    html.Td("{{ row.model }}")
                    html.Td("{{ row.values }}")
                    html.Td("{{ row.status }}")
                    html.Td("{{ row.excursion_inner }} / {{ row.excursion_outer }}")
                    html.Td("{{ row.band_thickness_inner }} / {{ row.band_thickness_outer }}")
                    with html.Td():
                        v3.VBtn(
                            "open",
                            size="x-small",
                            variant="text",
                            disabled=("!row.openable",),
                            click=(ctrl.study_open, "[row.point, row.model]"),
                        )


def _swatch(colour_expr: str, symbol: str = "") -> None:
    html.Span(
        symbol,
        style=(
            "{display: 'inline-block', width: '12px', height: '12px', borderRadius: '2px', "
            f"verticalAlign: 'middle', background: {colour_expr}}}",
        ),
    )


def _compare_panel() -> None:
    """Inside the comparison panel: the run on show (A) versus the saved runs chosen
    (``compare_ids``: B, C ...), each in its own colour, named in full in the legend."""
    with html.Div(id="compare-legend", v_if="compare_legend.length", classes="my-1"):
        with html.Div(
            v_for="entry in compare_legend",
            key="entry.tag",
            classes="rt-compare-entry text-caption d-flex align-start mb-1",
            title=("entry.label",),
        ):
            with html.Span(classes="mr-1 mt-1", style="white-space: nowrap;"):
                _swatch("entry.colour")
                _swatch("entry.outer_colour")
            html.B("{{ entry.tag }}", classes="mr-1")
            # the full name, wrapped (never cut): it says what differs between the runs
            html.Span("{{ entry.label }}", style="overflow-wrap: anywhere;")
        html.Div(
            "Each run in its colour: the inner race in the lighter shade, the outer race in the "
            "darker one.",
            classes="text-caption text-medium-emphasis",
        )
    html.Div(
        "{{ compare_message }}",
        v_if="compare_message",
        id="compare-message",
        classes="text-error text-caption my-1",
    )
    with html.Div(v_if="compare_legend.length"):  # no empty axes before a run is chosen
        for element_id, key, help_key, extra in (
            ("chart-compare-runs", "chart_compare_runs", "compare_runs", 20),
            ("chart-compare-angle", "chart_compare_angle", "compare_angle", 0),
            ("chart-compare-load", "chart_compare_load", "compare_load", 0),
        ):
            with html.Div(
                id=element_id, classes=lesson_widgets.chart_classes(key.removeprefix("chart_"))
            ):
                height = (
                    f"compare_chart_px + {extra}"
                    if key != "chart_compare_runs"
                    else "compare_chart_px + 20 + 220 * (Math.ceil(compare_legend.length / 3) - 1)"
                )
                lazy_charts.ChartFigure(
                    key,
                    display_mode_bar=False,
                    style=(f"`height: ${{{height}}}px; width: 100%;`",),
                )
                html.Div(HELP[help_key], classes="text-caption text-medium-emphasis px-2")
    _summary_table()


def _summary_table() -> None:
    """``div#compare-summary``: the table of :func:`app.charts.run_summary`, one row per run and
    race (state ``compare_summary``)."""
    with html.Div(id="compare-summary", classes="mb-2"):
        with v3.VTable(density="compact", classes="text-caption"):
            with html.Thead():
                with html.Tr():
                    for _, header, _ in SUMMARY_COLUMNS:
                        html.Th(header, classes="text-caption px-1")
            with html.Tbody():
                with html.Tr(v_for="row in compare_summary", key="row.key"):
                    for key, _, fmt in SUMMARY_COLUMNS:
                        if key == "run":  # the run's colour and tag; its full name on hover
                            with html.Td(
                                classes="px-1", title=("row.label",), style="white-space: nowrap;"
                            ):
                                _swatch("row.colour")
                                html.Span(" {{ row.run }}")
                            continue
                        html.Td(
                            f"{{{{ row.{key} }}}}",
                            classes="px-1" + (" text-right" if fmt else ""),
                        )
                with html.Tr(v_if="!compare_summary.length"):
                    html.Td(
                        "choose a saved run to compare with",
                        colspan=len(SUMMARY_COLUMNS),
                        classes="text-medium-emphasis px-1",
                    )
        html.Div(HELP["compare_summary"], classes="text-caption text-medium-emphasis px-2")


def _raceway_map_controls() -> None:
    """Options of the raceway map: colouring and the start-up left out (it follows the ball
    chosen for the traces)."""
    with v3.VRow(dense=True, align="center", classes="mt-1"):
        with v3.VCol(cols=6):
            v3.VSelect(
                label="raceway map coloured by",
                v_model=("map_colour",),
                items=(
                    "[{title: 'raceway', value: 'race'}, {title: 'ball', value: 'ball'}, "
                    "{title: 'contact load', value: 'load'}]",
                ),
                density="compact",
                hide_details=True,
                id="map-colour",
            )
        with v3.VCol():
            v3.VCheckbox(
                label="skip start-up",
                v_model=("map_skip_startup",),
                density="compact",
                hide_details=True,
                id="map-skip-startup",
                title="Leave out the samples before the solver's analysed window (settling)",
            )


def _time_controls() -> None:
    with v3.VRow(dense=True, align="center", classes="mt-1"):
        with v3.VCol(cols="auto"):
            v3.VBtn(
                icon=("playing ? 'mdi-pause' : 'mdi-play'",),
                id="play-button",
                click="playing = !playing",
                size="small",
            )
            v3.VBtn(
                icon="mdi-step-backward",
                click="frame = frame > 0 ? frame - 1 : frame_max",
                size="small",
                variant="text",
                id="step-back",
            )
            v3.VBtn(
                icon="mdi-step-forward",
                click="frame = frame < frame_max ? frame + 1 : 0",
                size="small",
                variant="text",
                id="step-forward",
            )
        with v3.VCol():
            with html.Div(id="time-slider"):
                v3.VSlider(
                    v_model=("frame",),
                    min=0,
                    max=("frame_max",),
                    step=1,
                    hide_details=True,
                    density="compact",
                )
        with v3.VCol(cols="auto"):
            html.Span(
                "{{ frame_time }}",
                classes="text-caption rt-frame-time",
                style="font-family: monospace;",
                id="frame-time",
            )
            html.Div("{{ slow_motion }}", classes="text-caption", id="slow-motion")
        with v3.VCol(cols=2):
            v3.VSelect(
                label="speed",
                v_model=("speed",),
                items=([1, 2, 5, 10, 20],),
                density="compact",
                hide_details=True,
                id="speed-select",
            )


def _scene_controls(ctrl) -> None:
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols="auto"):
            # plain buttons, not a toggle: pressing the current preset again restores it
            for preset in (
                "isometric",
                "axial",
                "radial",
                "inner track",
                "outer track",
                "close-up",
            ):
                v3.VBtn(
                    preset,
                    click=(ctrl.set_camera, f"['{preset}']"),
                    size="small",
                    variant=(f"camera === '{preset}' ? 'flat' : 'outlined'",),
                    classes="mr-1",
                    id=f"camera-{preset.replace(' ', '-')}",
                )
        with v3.VCol():
            v3.VSlider(
                label="exaggeration",
                v_model=("exaggeration",),
                min=1,
                max=30,
                step=1,
                thumb_label=True,
                hide_details=True,
                density="compact",
                title="Draw the across-groove deviation of the tracks, traces and ellipse centres "
                "from the run's mean contact angle this many times larger (clipped at the "
                "shoulders)",
                id="exaggeration",
            )
            html.Span("deviation × {{ exaggeration }}", classes="text-caption")
        with v3.VCol(cols=2):
            v3.VSlider(
                label="ellipses ×",
                v_model=("ellipse_scale",),
                min=1,
                max=10,
                step=1,
                thumb_label=True,
                hide_details=True,
                density="compact",
                title="Draw the contact ellipses this many times their true size",
                id="ellipse-scale",
            )
        with v3.VCol(cols=3):
            v3.VSelect(
                label="ball (traces, map, close-up)",
                v_model=("trace_ball",),
                items=("ball_items",),
                density="compact",
                hide_details=True,
            )
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=4):
            v3.VSelect(
                label="tracks coloured by",
                v_model=("track_quantity",),
                items=(
                    "[{title: 'dwell (time under a ball)', value: 'dwell'}, "
                    "{title: 'highest peak pressure', value: 'peak_pressure'}]",
                ),
                density="compact",
                hide_details=True,
                id="track-quantity",
            )
        with v3.VCol(cols="auto"):
            v3.VCheckbox(
                label="whole run",
                v_model=("track_whole_run",),
                density="compact",
                hide_details=True,
                id="track-whole-run",
                title="Paint the tracks of the whole run, not only up to the current time",
            )
    with v3.VRow(dense=True):
        for layer, label in (
            ("outer_ring", "outer ring"),
            ("inner_ring", "inner ring"),
            ("balls", "balls"),
            ("cage", "cage"),
            ("tracks", "painted tracks"),
            ("edges", "shoulders"),
            ("ellipses", "ellipses"),
            ("traces", "traces"),
            ("labels", "labels"),
        ):
            with v3.VCol(cols="auto"):
                v3.VCheckbox(
                    label=label, v_model=(f"show_{layer}",), density="compact", hide_details=True
                )


def _export_controls(ctrl) -> None:
    with v3.VRow(dense=True, align="center", id="export"):
        with v3.VCol(cols="auto"):
            html.Span("Export:", classes="text-body-2 mr-1")
            for kind, label in (
                ("netcdf", "NetCDF"),
                ("csv", "CSV"),
                ("png", "PNG"),
                ("gif", "GIF"),
                ("mp4", "MP4"),
            ):
                v3.VBtn(
                    label,
                    click=(ctrl.export, f"['{kind}']"),
                    size="small",
                    variant="tonal",
                    disabled=("exporting",),
                    classes="mr-1",
                    id=f"export-{kind}",
                )
        with v3.VCol():
            html.A(
                "download {{ export_name }}",
                href=("export_href",),
                download=("export_name",),
                v_show="export_href",
                id="export-link",
                target="_blank",
            )
            html.Span("{{ export_message }}", classes="text-error text-caption")


def _run_panel(ctrl) -> None:
    with v3.VCard(variant="outlined", classes="mb-2 pa-2"):
        with v3.VRow(dense=True, align="center"):
            with v3.VCol(cols="auto"):
                v3.VBtn(
                    "Run",
                    id="run-button",
                    color="primary",
                    click=ctrl.run,
                    disabled=("run_disabled",),
                    prepend_icon="mdi-play-circle",
                )
                v3.VBtn(
                    "Cancel",
                    id="cancel-button",
                    click=ctrl.cancel,
                    disabled=("!busy",),
                    classes="ml-2",
                    prepend_icon="mdi-stop-circle",
                )
            with v3.VCol():
                html.Div("{{ status }}", id="status", classes="text-body-2")
                html.Div("{{ eta }}", classes="text-caption")
        html.Div(
            "{{ run_blocked }}",
            id="run-blocked",
            v_show="run_blocked",
            classes="text-caption text-error",
        )
        html.Div(
            "{{ run_note }}", id="run-note", v_show="run_note", classes="text-caption text-warning"
        )
        with v3.VAlert(
            id="run-confirm",
            v_if="run_confirm",
            type="warning",
            density="compact",
            variant="tonal",
            classes="my-1 text-caption",
        ):
            html.Div(
                "The result of this case leaves the model's validity (see the warnings below). "
                "Run the dynamic model anyway?"
            )
            v3.VBtn(
                "Run anyway",
                id="run-anyway",
                click=ctrl.run_anyway,
                size="small",
                color="warning",
                classes="mt-1 mr-2",
            )
            v3.VBtn(
                "Back",
                id="run-back",
                click="run_confirm = false",
                size="small",
                variant="text",
                classes="mt-1",
            )
        html.Div(
            "{{ run_reason }}",
            id="run-reason",
            v_show="run_reason",
            classes="text-caption text-error",
            style="white-space: pre-line",
        )
        with html.Div(id="result-warnings", v_if="result_warnings.length"):
            v3.VAlert(
                "{{ warning }}",
                v_for="warning in result_warnings",
                key="warning",
                type="warning",
                density="compact",
                variant="tonal",
                classes="my-1 text-caption",
            )
        v3.VProgressLinear(
            id="progress", model_value=("progress",), height=8, color="primary", classes="my-1"
        )
        with html.Div(id="runs-select"):
            v3.VSelect(
                label="Saved runs",
                v_model=("run_id",),
                items=("runs",),
                density="compact",
                hide_details=True,
                no_data_text="no saved runs yet",
            )
