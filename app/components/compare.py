"""Comparison of the result on show (A) with any number of saved runs (B, C ...).

State keys: ``compare_ids`` (the saved runs chosen, in order: B, C ...), ``compare_legend`` (one
entry per run drawn, A first: ``tag``, ``label`` (the run's full title), ``colour`` (inner race),
``outer_colour``, ``symbol``), ``compare_summary`` (rows of :func:`app.charts.summary_rows`, one
per run and race, with the run's ``label`` and ``colour``), ``compare_chart_px`` (height of the
comparison charts, which grows with the legend), ``compare_message`` (why a chosen run cannot be
compared, "" when fine); the charts ``chart_compare_runs``, ``chart_compare_angle``,
``chart_compare_load`` are set here too (declared by :mod:`app.components.result_view`).
"""

from __future__ import annotations

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from viz.frames import frame_source
from viz.palette import MAX_COMPARED, run_colours, run_style, run_tag

from .. import charts
from .base import Component, fig_json
from .widgets import HIDE, caption, chart, select, swatch

MAX_CACHED = MAX_COMPARED  # loaded runs kept for the next comparison


class Compare(Component):
    PROVIDES = ("refresh_comparison",)

    def __init__(self, session):
        super().__init__(session)
        self._compare_key = None  # (result_serial, run ids) of the comparison shown
        self._loaded = {}  # run id -> (Dataset, FrameSource) of runs compared with

    def init_state(self) -> None:
        s = self.state
        s.compare_ids = []
        s.compare_legend = []
        s.compare_summary = []
        s.compare_message = ""
        s.compare_chart_px = charts.compare_chart_px(2)

    def bind(self) -> None:
        self.on_change("compare_ids")(self._on_compare_ids)

    def chosen(self) -> list:
        """The run ids chosen for comparison (``compare_ids``, as a client sent it), in order,
        without repeats; anything that is not a list of texts counts as nothing chosen."""
        ids = self.state.compare_ids
        if not isinstance(ids, list | tuple):
            return []
        return list(dict.fromkeys(i for i in ids if isinstance(i, str) and i))

    def is_current(self) -> bool:
        """Whether the comparison shown is of the result on show and the chosen runs."""
        return self._compare_key == (int(self.state.result_serial), tuple(self.chosen()))

    def refresh_comparison(self) -> None:
        """Compare again unless the comparison shown is of the result on show and the runs
        chosen (the panel was opened, or the result changed)."""
        if not self.is_current():
            self.update_comparison()

    def _on_compare_ids(self, **_):
        self.update_comparison()

    def update_comparison(self) -> None:
        """Compare the result on show (A) with the saved runs chosen in ``compare_ids`` (B, C ...).

        Sets ``chart_compare_runs`` (raceway maps side by side), ``chart_compare_angle`` and
        ``chart_compare_load`` (overlays versus ball azimuth), ``compare_summary`` (table rows of
        :func:`app.charts.run_summary`) and ``compare_legend``; all are emptied when nothing is
        chosen, and ``compare_message`` says in words why a chosen run is left out (not a saved
        run, cannot be loaded, more than the page can tell apart)."""
        result = self.ctrl.shown_result()
        ids = self.chosen()
        if not ids or result.source is None:
            self._clear_comparison("")
            return
        problems = []
        if len(ids) > MAX_COMPARED - 1:
            problems.append(
                f"at most {MAX_COMPARED - 1} runs are compared with the one on show: "
                f"{len(ids) - MAX_COMPARED + 1} left out"
            )
            ids = ids[: MAX_COMPARED - 1]
        runs = []  # (run id, label, Dataset, FrameSource)
        for run_id in ids:
            if not self.ctrl.is_listed(run_id):
                problems.append(f"cannot compare with {run_id[:80]}: not a saved run")
                continue
            try:
                ds, source = self._load_compare_run(run_id)
            except (OSError, ValueError) as error:
                problems.append(f"cannot compare with {run_id}: {error}")
                continue
            label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
            runs.append((run_id, label, ds, source))
        if not runs:
            self._clear_comparison("; ".join(problems))
            return
        self._compare_key = (int(self.state.result_serial), tuple(self.chosen()))
        label = self.state.result_label or "run on show"
        if result.run_id is None and result.title and result.title not in label:
            # a preview or a lesson's result: its case and loads (a saved run's label has its title)
            label = f"{label}: {result.title}"
        shown = [(None, label, result.dataset, result.source)]
        shown += runs
        sources = [source for _, _, _, source in shown]
        summaries = {run_tag(i): charts.run_summary(ds) for i, (_, _, ds, _) in enumerate(shown)}
        legend = []
        for i, (_, label, _, _) in enumerate(shown):
            colours = run_colours(i)
            legend.append(
                {
                    "tag": run_tag(i),
                    "label": label + (" (on show)" if i == 0 else ""),
                    "colour": colours[0],
                    "outer_colour": colours[1],
                    "symbol": run_style(i)["symbol"],
                }
            )
        by_tag = {e["tag"]: e for e in legend}
        rows = charts.summary_rows(summaries)
        for row in rows:
            row["label"] = by_tag[row["run"]]["label"]
            row["colour"] = by_tag[row["run"]]["colour"]
        with self.state:
            s = self.state
            s.chart_compare_runs = fig_json(charts.side_by_side_raceway_maps(*sources))
            s.chart_compare_angle = fig_json(charts.compare_angle_figure(*sources))
            s.chart_compare_load = fig_json(charts.compare_load_figure(*sources))
            s.compare_chart_px = charts.compare_chart_px(len(sources))
            s.compare_summary = rows
            s.compare_legend = legend
            s.compare_message = "; ".join(problems)

    def _load_compare_run(self, run_id: str):
        """(Dataset, FrameSource) of saved run ``run_id``; the runs last compared are kept."""
        if run_id not in self._loaded:
            ds, _ = self.session.store.load(run_id)
            self._loaded[run_id] = (ds, frame_source(ds))
        keep = set(self.chosen())
        for old in [k for k in self._loaded if k not in keep]:
            if len(self._loaded) > MAX_CACHED:
                del self._loaded[old]
        return self._loaded[run_id]

    def _clear_comparison(self, message: str) -> None:
        """Empty the comparison charts and table; ``message`` says why ("" when not asked for)."""
        with self.state:
            s = self.state
            for name in ("compare_runs", "compare_angle", "compare_load"):
                s[f"chart_{name}"] = {"data": [], "layout": {}}
            s.compare_summary = []
            s.compare_legend = []
            s.compare_message = message
        self._compare_key = None

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """The collapsible panel "Compare runs side by side" (value ``compare``): the saved runs
        to compare with (``#compare-select``), the legend, the three charts and the table."""
        with v3.VExpansionPanel(title="Compare runs side by side", value="compare", classes=HIDE):
            with v3.VExpansionPanelText():
                with html.Div(id="compare-select"):
                    select(
                        "Compare with saved runs (any number)",
                        "compare_ids",
                        "runs",
                        multiple=True,
                        chips=True,
                        closable_chips=True,
                        clearable=True,
                    )
                _legend()
                html.Div(
                    "{{ compare_message }}",
                    v_if="compare_message",
                    id="compare-message",
                    classes="text-error text-caption my-1",
                )
                with html.Div(v_if="compare_legend.length"):  # no empty axes before a choice
                    _charts()
                _summary_table()


def _legend() -> None:
    """``#compare-legend``: the run on show (A) and the runs chosen (B, C ...), each in its
    colours, named in full (wrapped, never cut: it says what differs between the runs)."""
    with html.Div(id="compare-legend", v_if="compare_legend.length", classes="my-1"):
        with html.Div(
            v_for="entry in compare_legend",
            key="entry.tag",
            classes="rt-compare-entry text-caption d-flex align-start mb-1",
            title=("entry.label",),
        ):
            with html.Span(classes="mr-1 mt-1", style="white-space: nowrap;"):
                swatch("entry.colour")
                swatch("entry.outer_colour")
            html.B("{{ entry.tag }}", classes="mr-1")
            html.Span("{{ entry.label }}", style="overflow-wrap: anywhere;")
        html.Div(
            "Each run in its colour: the inner race in the lighter shade, the outer race in the "
            "darker one.",
            classes="text-caption text-medium-emphasis",
        )


def _charts() -> None:
    """The raceway maps (three a row: taller with more runs), contact angle and load."""
    rows = "20 + 220 * (Math.ceil(compare_legend.length / 3) - 1)"
    chart(
        "chart-compare-runs",
        "chart_compare_runs",
        charts.HELP["compare_runs"],
        (f"compare_chart_px + {rows}",),
    )
    chart(
        "chart-compare-angle",
        "chart_compare_angle",
        charts.HELP["compare_angle"],
        ("compare_chart_px",),
    )
    chart(
        "chart-compare-load",
        "chart_compare_load",
        charts.HELP["compare_load"],
        ("compare_chart_px",),
    )


def _summary_table() -> None:
    """``#compare-summary``: the table of :func:`app.charts.run_summary`, one row per run and
    race (state ``compare_summary``)."""
    columns = charts.SUMMARY_COLUMNS
    with html.Div(id="compare-summary", classes="mb-2"):
        with v3.VTable(density="compact", classes="text-caption"):
            with html.Thead(), html.Tr():
                for _, header, _ in columns:
                    html.Th(header, classes="text-caption px-1")
            with html.Tbody():
                with html.Tr(v_for="row in compare_summary", key="row.key"):
                    for key, _, fmt in columns:
                        if key == "run":  # the run's colour and tag; its full name on hover
                            with html.Td(
                                classes="px-1", title=("row.label",), style="white-space: nowrap;"
                            ):
                                swatch("row.colour")
                                html.Span(" {{ row.run }}")
                            continue
                        html.Td(
                            f"{{{{ row.{key} }}}}",
                            classes="px-1" + (" text-right" if fmt else ""),
                        )
                with html.Tr(v_if="!compare_summary.length"):
                    html.Td(
                        "choose a saved run to compare with",
                        colspan=len(columns),
                        classes="text-medium-emphasis px-1",
                    )
        caption(charts.HELP["compare_summary"])
