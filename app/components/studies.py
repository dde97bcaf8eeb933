"""Studies: run a shipped study, or one built from the case in the form, in the background on the
Dask machinery of ``racetrace study``; open the results of a shipped study or of a study run
before; watch a study build up point by point, chart a metric against the varied key and open
any point's run.

State keys: ``study_names`` (shipped studies), ``study_name`` (the one chosen), ``study_running``,
``study_status`` (progress or how it ended), ``study_progress`` (percent done), ``study_rows``
(one row per point and model: values, status, metrics), ``study_sweeps`` / ``study_sweep`` (the
sweep charted), ``study_metric`` / ``study_metric_items`` (the metric charted, one of
:func:`app.study_figures.study_metric_items`: a metric of
:data:`solver.study.metrics.POINT_METRICS`, or
for a study of bearing-set points one of :data:`viz.set_study.SET_STUDY_CHART_METRICS`) and the
chart ``chart_study`` (the metric against the sweep's varied key: inner and outer race side by
side, a line per model; for a set, the set's line and one per bearing). Opening results:
``study_results_items`` / ``study_results`` (shipped study results and the study folders of the
runs folder). Building a study from the current case: ``study_key_items`` (the form's numeric
keys), ``study_key1``/``study_values1`` and ``study_key2``/``study_values2`` (values:
``0, 300, 600`` or ``start:stop:count``), ``study_combine`` (grid | zip), ``study_model``
(quasistatic | dynamic | both), ``study_revolutions`` (run length of the dynamic points).
Controller: ``study_run``, ``study_build``, ``study_cancel``, ``study_open(point, model)``.

The study runs in a thread of this process and keeps its folder under the runs folder
(``.studies/``); the page reads the folder as runs finish. Its points take the solver slots the
runs take (:class:`app.services.pool.SolverPool`, ``racetrace serve --max-runs``, across every
session): the study waits in the same queue for one slot, takes as many more as are free then (up
to ``workers``, default the cap), and runs a local Dask cluster of one single-threaded worker per
slot held, closed at the end, when the slots are given back.
"""

from __future__ import annotations

import json
import math
import secrets
import threading
from pathlib import Path

import numpy as np
from trame.widgets import html
from trame.widgets import vuetify3 as v3

from .. import lazy_charts
from ..case_fields import form_fields
from ..paths import child_path
from ..run_length import has_history
from ..set_charts import TRANSLATION_UNIT
from ..study_building import StudyInputError, build_study_text, parse_values
from ..study_figures import study_figure, study_metric_items
from .base import Component, fig_json, running_loop
from .widgets import button, choices, select

POLL_S = 1.0
SLOT_WAIT_S = 0.5  # a study waiting for a solver slot asks again this often
# Study Datasets of the shipped studies' runs (docs/studies.md); their full runs are not shipped.
SHIPPED_RESULTS = Path(__file__).resolve().parents[2] / "assets" / "studies" / "results"
STUDIES_DIR = ".studies"  # study folders under the runs folder


class Studies(Component):
    def __init__(self, session, workers: int | None = None):
        super().__init__(session)
        self.workers = workers
        self.folder = None  # solver.study.StudyFolder of the study on show
        self._shipped = None  # the study Dataset of shipped results on show (no folder)
        self.study_text = ""  # the study file of the last study built from the form's case
        self.study = None
        self._thread = None
        self._stop = threading.Event()
        self._progress = None
        self._error = ""
        self._queued = 0  # place in the queue for a solver slot while waiting (0: not waiting)
        self._poll_task = None
        self._rows = []  # the table's rows as this server made them (study_rows is the page's)

    def init_state(self) -> None:
        from solver import shipped_studies

        s = self.state
        names = list(shipped_studies())
        s.study_names = names
        s.study_name = names[0] if names else None
        s.study_running = False
        s.study_progress = 0  # percent of the running study's runs finished
        s.study_status = ""
        s.study_rows = []
        s.study_table_heads = [head for head, _figure in RACE_TABLE_FIGURES]
        s.study_sweeps = []
        s.study_sweep = None
        s.study_metric = "excursion"
        s.study_metric_items = study_metric_items(None)
        s.chart_study = {"data": [], "layout": {}}
        s.study_results_items = []
        s.study_results = None
        fields = [f for f in form_fields() if f.kind in ("int", "float")]
        s.study_key_items = [{"title": f"{f.key} ({f.label})", "value": f.key} for f in fields]
        keys = self.numeric_keys()
        s.study_key1 = "operating.radial_load_N" if "operating.radial_load_N" in keys else None
        s.study_values1 = "0, 500, 1000"
        s.study_key2 = None
        s.study_values2 = ""
        s.study_combine = "grid"
        s.study_model = "quasistatic"
        s.study_revolutions = "2"
        self.list_results()

    def numeric_keys(self) -> list[str]:
        """The case keys a study built in the page may vary: the form's numeric fields."""
        return [f.key for f in form_fields() if f.kind in ("int", "float")]

    def bind(self) -> None:
        self.ctrl.study_run = self.run
        self.ctrl.study_cancel = self.cancel
        self.ctrl.study_open = self.open_point
        self.action("study_build", self.build)
        self.state.change("study_sweep", "study_metric")(self._on_chart_choice)
        self.on_change("study_results")(self._on_results)

    # ---- running --------------------------------------------------------------------------------
    @property
    def busy(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def run(self) -> None:
        """Start the chosen shipped study (``study_name``, one of :func:`shipped_studies`) in the
        background."""
        from solver import CaseError, Study, shipped_studies

        if self.busy or not self.state.study_name:
            return
        name = self.state.study_name
        shipped = shipped_studies()  # the names offered, listed again here: never a path
        if not isinstance(name, str) or name not in shipped:
            self.state.study_status = (
                f"error: no shipped study {str(name)[:80]!r}: choose one from the list"
            )
            return
        try:
            text = shipped[name].read_text(encoding="utf-8")
            study = Study.from_text(text, f"shipped study {name}")
        except (CaseError, OSError) as error:
            self.state.study_status = f"error: {error}"
            return
        self.start(study, name)

    def new_folder(self, name: str) -> Path:
        """A new study folder ``.studies/<name>-<random>`` of the runs folder (not created)."""
        root = self.session.store.root / STUDIES_DIR
        root.mkdir(parents=True, exist_ok=True)
        safe = "".join(c if c.isalnum() or c in "-_" else "-" for c in name)[:40] or "study"
        return root / f"{safe}-{secrets.token_hex(3)}"

    def start(self, study, name: str, path: Path | None = None) -> None:
        """Run ``study`` (a :class:`solver.study.Study`) in the background, in the study folder
        ``path`` (default: a new one, :meth:`new_folder`)."""
        from solver import StudyFolder

        if self.busy:
            return
        self.study = study
        path = path if path is not None else self.new_folder(name)
        self.folder = StudyFolder(path)
        self._shipped = None
        self._rows = []
        self.state.study_results = None  # the panel now shows the study started here
        self._stop.clear()
        self._progress, self._error, self._queued = None, "", 0
        self._thread = threading.Thread(target=self._work, name="racetrace-study", daemon=True)
        self._thread.start()
        with self.state:
            self.state.study_running = True
            self.state.study_progress = 0
            self.state.study_status = f"starting {self.study.title} ..."
        loop = running_loop()
        if loop is not None:  # without one, tests call poll() themselves
            self._poll_task = loop.create_task(self.poll_until_done(self.poll, POLL_S))

    def _take_slots(self) -> list:
        """Solver slots (:class:`app.services.pool.SolverPool`, shared with the runs of every
        session) for the study's workers: waits in the queue for one, then takes more that are
        free now, without passing runs queued before, up to ``workers`` (default: the pool's
        cap). Returns the held tickets ([] when cancelled while waiting)."""
        pool = self.session.services.pool
        first = pool.enqueue()
        try:
            while not pool.try_acquire(first):
                self._queued = first.place + 1
                if self._stop.wait(SLOT_WAIT_S):
                    pool.drop(first)
                    return []
        except BaseException:
            pool.drop(first)
            raise
        self._queued = 0
        held = [first]
        wanted = min(self.workers or pool.max_runs, pool.max_runs)
        while len(held) < wanted:
            ticket = pool.enqueue()
            if not pool.try_acquire(ticket):
                pool.drop(ticket)
                break
            held.append(ticket)
        return held

    def _work(self) -> None:
        held = []
        try:
            held = self._take_slots()
            if held:  # one single-threaded Dask worker per slot held
                self.study.run(
                    self.folder.path,
                    workers=len(held),
                    progress=self._on_progress,
                    cancel=self._stop,
                )
        except Exception as error:  # noqa: BLE001 - shown on the page, the session goes on
            self._error = f"{type(error).__name__}: {error}"
        finally:
            for ticket in held:
                self.session.services.pool.drop(ticket)

    def _on_progress(self, progress) -> None:
        self._progress = progress

    def build(self) -> None:
        """Build a study from the case in the form (its base, written as ``<folder>.base.toml``
        beside the study folder) with the keys and values chosen and run it (the study runner
        writes its study file into the folder)."""
        from solver import CaseError, Study

        if self.busy:
            self.state.study_status = "a study is running: cancel it or wait for it to end"
            return
        s = self.state
        case = self.ctrl.edited_case()
        if case is None:
            s.study_status = "error: the case in the form is not valid: fix the fields in red first"
            return
        keys = set(self.numeric_keys())  # the keys offered, from the form: never the client's list
        varied = []
        try:
            for n in (1, 2):
                key = s[f"study_key{n}"]
                if not key:
                    if n == 1:
                        raise StudyInputError("choose the key to vary (first key)")
                    continue
                if not isinstance(key, str) or key not in keys:
                    raise StudyInputError(f"{str(key)[:80]!r} is not a numeric key of the case")
                varied.append((key, parse_values(s[f"study_values{n}"], f"values of {key}")))
            varied_words = " and ".join(k.rsplit(".", 1)[-1] for k, _ in varied)
            title = f"{case.bearing.designation or 'bearing'}: {varied_words} (built in the app)"
            text = build_study_text(
                title,
                varied,
                str(s.study_combine),
                str(s.study_model),
                s.study_revolutions,
                duration_s=case.simulation.duration_s if has_history(case) else None,
            )
        except StudyInputError as error:
            s.study_status = f"error: {error}"
            return
        path = self.new_folder("built-" + varied[0][0].rsplit(".", 1)[-1])
        # the base case beside the study folder (a study runs only into an empty folder); the
        # study file names it relative to itself, so a resume finds it
        base = path.parent / f"{path.name}.base.toml"
        base.write_text(case.to_toml(), encoding="utf-8")
        path.mkdir()
        text = text.replace('base = "base.toml"', f"base = {json.dumps('../' + base.name)}")
        try:
            study = Study.from_text(text, "the study built here", folder=path)
        except CaseError as error:
            path.rmdir()
            base.unlink()
            s.study_status = f"error: {error}"
            return
        self.study_text = text
        self.start(study, path.name, path)

    def cancel(self) -> None:
        """Stop the study: the runs finished so far are kept."""
        if self.busy:
            self._stop.set()
            self.state.study_status = "cancelling (finished runs are kept) ..."

    def poll(self) -> bool:
        """Read the study folder into the table and chart; True once the study has ended."""
        running = self.busy
        self.refresh()
        s = self.state
        p = self._progress
        if running:
            if self._queued:
                cap = self.session.services.pool.max_runs
                s.study_status = (
                    f"queued: place {self._queued} in the queue for a solver (at most {cap} "
                    f"run{'s' * (cap != 1)} at once, study points included)"
                )
            elif p is not None:
                eta = f", about {p.eta_s:.0f} s left" if math.isfinite(p.eta_s) else ""
                s.study_progress = round(100 * p.done / p.total) if p.total else 0
                s.study_status = f"{p.done}/{p.total} runs done, {p.running} running{eta}" + (
                    f", {p.failed} failed" if p.failed else ""
                )
            return False
        s.study_running = False
        if self._error:
            s.study_status = f"error: {self._error}"
        elif self._stop.is_set():
            s.study_status = "cancelled: the finished runs are kept"
        else:
            s.study_status = "done"
            s.study_progress = 100
        self.list_results()
        return True

    # ---- showing --------------------------------------------------------------------------------
    def dataset(self):
        from solver import study_dataset

        if self._shipped is not None:
            return self._shipped
        if self.folder is None or not self.folder.exists():
            return None
        return study_dataset(self.folder)

    def refresh(self) -> None:
        """Table rows and chart from the study folder."""
        from solver import study_runs, sweep_varied_keys

        ds = self.dataset()
        if ds is None:
            return
        shown = sweep_varied_keys(ds)
        rows = []
        for i, j, status in study_runs(ds):
            point, model = str(ds["point"].values[i]), str(ds["model"].values[j])
            values = ", ".join(
                f"{k.rsplit('.', 1)[-1]} = {_text(ds[k].values[i])}"
                for k in shown[str(ds["sweep"].values[i])]
            )
            row = {
                "key": f"{point}-{model}",
                "point": point,
                "model": model,
                "sweep": str(ds["sweep"].values[i]),
                "values": values,
                "status": status,
                "openable": status == "done" and self._shipped is None,
            }
            row["figures"] = [
                " / ".join(_text(value, 4) for value in figure(ds, i, j))
                for _head, figure in table_figures(ds)
            ]
            rows.append(row)
        sweeps = list(dict.fromkeys(str(v) for v in ds["sweep"].values))
        self._rows = rows
        s = self.state
        s.study_rows = rows
        heads = [head for head, _figure in table_figures(ds)]
        if s.study_table_heads != heads:
            s.study_table_heads = heads
        if s.study_sweeps != sweeps:
            s.study_sweeps = sweeps
        if s.study_sweep not in sweeps:
            s.study_sweep = sweeps[0] if sweeps else None
        items = study_metric_items(ds)
        if s.study_metric_items != items:  # a set study offers the set's metrics
            s.study_metric_items = items
        metric = self._metric(ds)
        if s.study_metric != metric:
            s.study_metric = metric
        s.chart_study = fig_json(study_figure(ds, s.study_sweep, metric))

    def _metric(self, ds) -> str:
        """The metric charted: ``study_metric`` when it is one the chart offers for ``ds``
        (:func:`app.study_figures.study_metric_items`), else the first of them."""
        metric = self.state.study_metric
        names = [item["value"] for item in study_metric_items(ds)]
        return metric if isinstance(metric, str) and metric in names else names[0]

    def _on_chart_choice(self, **_):
        ds = self.dataset()
        if ds is not None:
            self.state.chart_study = fig_json(
                study_figure(ds, self.state.study_sweep, self._metric(ds))
            )

    def open_point(self, point: str, model: str) -> None:
        """Show one point's run in the 3-D view, the raceway map and the charts."""
        from solver import CaseError

        if self._shipped is not None:
            self.state.study_status = (
                "the full runs of a shipped study are not shipped: run the study to open a point"
            )
            return
        if self.folder is None:
            return
        shown = {(r["point"], r["model"]) for r in self._rows if r["openable"]}
        if not (isinstance(point, str) and isinstance(model, str) and (point, model) in shown):
            self.state.study_status = (
                f"error: no point {str(point)[:40]!r} {str(model)[:40]!r} in the study on show"
            )
            return
        try:
            child_path(self.folder.points_dir, f"{point}.{model}.nc", "point")
            ds = self.folder.load_point(point, model)
        except (CaseError, OSError, ValueError) as error:
            self.state.study_status = f"cannot open {point} {model}: {error}"
            return
        title = self.study.title if self.study is not None else self.folder.path.name
        values = next(
            (r["values"] for r in self._rows if r["point"] == point), ""
        )  # what the point changes, e.g. "radial_load_N = 300"
        self.ctrl.show_unsaved(ds, f"{title}: {point} ({values}) {model}")

    # ---- results of studies run before ----------------------------------------------------------
    def results_items(self) -> list[dict]:
        """The shipped studies' results and the study folders of the runs folder (newest
        first), as offered in ``study_results_items``: listed again by the server at each use."""
        items = [
            {"title": f"shipped: {p.name.removesuffix('.study.nc')}", "value": f"shipped:{p.name}"}
            for p in sorted(SHIPPED_RESULTS.glob("*.study.nc"))
        ]
        root = self.session.store.root / STUDIES_DIR
        if root.is_dir():
            folders = [
                p for p in root.iterdir() if not p.is_symlink() and (p / "study.json").is_file()
            ]
            for p in sorted(folders, key=lambda p: p.stat().st_mtime, reverse=True):
                items.append({"title": f"run here: {p.name}", "value": f"folder:{p.name}"})
        return items

    def list_results(self) -> None:
        """``study_results_items``: :meth:`results_items`."""
        items = self.results_items()
        if items != self.state.study_results_items:
            self.state.study_results_items = items

    def _on_results(self, study_results=None, **_):
        if study_results:
            self.open_results(study_results)

    def open_results(self, value: str) -> None:
        """Show the results ``value`` of :meth:`list_results` in the table and the chart."""
        import xarray as xr

        from solver import CaseError, open_study

        if self.busy:
            self.state.study_status = "a study is running: cancel it before opening other results"
            return
        known = {item["value"] for item in self.results_items()}  # never the client's list
        if not isinstance(value, str) or value not in known:
            self.state.study_status = f"error: no such study results {str(value)[:80]!r}"
            self.state.study_results = None
            return
        kind, name = value.split(":", 1)
        try:
            if kind == "shipped":
                path = child_path(SHIPPED_RESULTS, name, "study results")
                with xr.open_dataset(path) as ds:
                    self._shipped = ds.load()
                self.folder, self.study = None, None
                title = self._shipped.attrs.get("title", name)
                note = " (the study Dataset only: run the study to open its points)"
            else:
                root = self.session.store.root / STUDIES_DIR
                folder = open_study(child_path(root, name, "study folder"))
                self.folder, self._shipped, self.study = folder, None, None
                title = folder.manifest().get("title", name)
                note = ""
        except (CaseError, OSError, ValueError) as error:
            self.state.study_status = f"error: cannot open {name}: {error}"
            return
        self.state.study_status = f"showing {title}{note}"
        self.refresh()

    def shutdown(self) -> None:
        self._stop.set()

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """The collapsible panel "Studies" (value ``studies``, ``#studies``): open earlier
        results, run a shipped study or one built from the current case, chart a metric and
        open any point."""
        ctrl = self.ctrl
        with v3.VExpansionPanel(title="Studies", value="studies"):
            with v3.VExpansionPanelText(), html.Div(id="studies", classes="mb-2"):
                with html.Div(id="study-results"):
                    select(
                        "Open study results",
                        "study_results",
                        "study_results_items",
                        disabled=("study_running",),
                        no_data_text="no study results yet",
                        classes="mb-2",
                    )
                _shipped_study(ctrl)
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
                _study_chart(ctrl)
                _study_table(ctrl)


def _shipped_study(ctrl) -> None:
    """A shipped study to run (``#study-run``) and ``#study-cancel``."""
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=6):
            select("Shipped study", "study_name", "study_names", disabled=("study_running",))
        with v3.VCol(cols="auto"):
            button("Run study", "study-run", ctrl.study_run, "study_running", color="primary")
        with v3.VCol(cols="auto"):
            button("Cancel", "study-cancel", ctrl.study_cancel, "!study_running")


def _study_builder(ctrl) -> None:
    """``#study-build``: a study built from the case in the form (:meth:`Studies.build`)."""
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
        _study_options()
        button(
            "Build and run",
            "study-build-run",
            ctrl.study_build,
            "study_running || !case_valid",
            color="primary",
            classes="mt-1",
            title="Write a study file with the case in the form as its base and run it",
        )


def _study_options() -> None:
    """How two keys combine, the model and the dynamic run length of a built study."""
    combine = (("grid", "grid (every pair)"), ("zip", "zipped (side by side)"))
    models = (("quasistatic", "quasi-static"), ("dynamic", "dynamic"), ("both", "both"))
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=4), html.Div(id="study-combine"):
            select("two keys", "study_combine", choices(combine))
        with v3.VCol(cols=4), html.Div(id="study-model"):
            select("model", "study_model", choices(models))
        with v3.VCol(cols=4), html.Div(id="study-revolutions"):
            v3.VTextField(
                label="revolutions (dynamic)",
                v_model=("study_revolutions",),
                density="compact",
                hide_details=True,
                disabled=("study_model === 'quasistatic'",),
            )


def _study_chart(ctrl) -> None:
    """The sweep and metric to chart, and ``#chart-study`` (a click on a point opens its run:
    its (point, model) is the customdata)."""
    with v3.VRow(dense=True):
        with v3.VCol(cols=6):
            select("Sweep", "study_sweep", "study_sweeps")
        with v3.VCol(cols=6):
            select("Metric", "study_metric", "study_metric_items")
    with html.Div(id="chart-study", classes="mb-2"):
        lazy_charts.ChartFigure(
            "chart_study",
            display_mode_bar=False,
            style="height: 280px; width: 100%;",
            click=(
                ctrl.study_open,
                "[$event.points[0].customdata[0], $event.points[0].customdata[1]]",
            ),
        )


STUDY_TABLE_HEADS = ("point", "model", "values", "status")  # then the figures' heads, and open
STUDY_TABLE_WIDTHS = ("12%", "14%", "20%", "18%", "13%", "13%", "10%")  # of the side column


def _per_race(name: str, scale: float = 1.0):
    return lambda ds, i, j: [scale * float(ds[name].values[i, j, k]) for k in range(2)]


def _set_value(name: str, scale: float):
    return lambda ds, i, j: [scale * float(ds[name].values[i, j])]


#: The two figure columns of a single-bearing study's table: (head, figures of row i, model j)
RACE_TABLE_FIGURES = (
    ("exc i/o deg", _per_race("excursion")),
    ("band i/o deg", _per_race("band_thickness")),
)
#: ... and of a bearing-set study's (the set's stiffness, in the set charts' unit)
SET_TABLE_FIGURES = (
    (f"axial {TRANSLATION_UNIT[0]}", _set_value("axial_stiffness", TRANSLATION_UNIT[1])),
    (f"radial {TRANSLATION_UNIT[0]}", _set_value("radial_stiffness", TRANSLATION_UNIT[1])),
)


def table_figures(ds) -> tuple:
    """The figure columns of the study table for the study Dataset ``ds``: the set's stiffness
    for a study of bearing-set points (a ``bearing`` dimension), else the races' excursion and
    band thickness."""
    return SET_TABLE_FIGURES if "bearing" in ds.dims else RACE_TABLE_FIGURES


def _study_table(ctrl) -> None:
    """``#study-table``: a row per point and model (state ``study_rows``) with its **open**. It
    keeps to the side column's width (about 500 px on a 1600 px window): the values and the status
    wrap anywhere rather than widen the table."""
    wrap = "overflow-wrap: anywhere; white-space: normal;"
    with v3.VTable(
        density="compact",
        id="study-table",
        style="table-layout: fixed; width: 100%; font-size: 12px;",
    ):
        with html.Thead(), html.Tr():
            for head, width in zip(STUDY_TABLE_HEADS, STUDY_TABLE_WIDTHS, strict=False):
                html.Th(head, style=f"width: {width}; {wrap} padding: 0 4px;")
            for k, width in enumerate(STUDY_TABLE_WIDTHS[len(STUDY_TABLE_HEADS) : -1]):
                html.Th(
                    f"{{{{ study_table_heads[{k}] }}}}",
                    style=f"width: {width}; {wrap} padding: 0 4px;",
                )
            html.Th("", style=f"width: {STUDY_TABLE_WIDTHS[-1]}; {wrap} padding: 0 4px;")
        with html.Tbody(), html.Tr(v_for="row in study_rows", key="row.key"):
            for cell in ("point", "model", "values", "status"):
                html.Td(f"{{{{ row.{cell} }}}}", style=f"{wrap} padding: 0 4px;")
            for k in range(len(RACE_TABLE_FIGURES)):
                html.Td(f"{{{{ row.figures[{k}] }}}}", style=f"{wrap} padding: 0 4px;")
            with html.Td(style="padding: 0 2px;"):
                v3.VBtn(
                    "open",
                    size="x-small",
                    variant="text",
                    disabled=("!row.openable",),
                    click=(ctrl.study_open, "[row.point, row.model]"),
                )


def _text(value, digits: int = 5) -> str:
    """A table cell: a number to ``digits`` significant figures ("0" below 1e-9: rounding noise
    of a zero), "-" for NaN."""
    if isinstance(value, float | np.floating):
        if not math.isfinite(value):
            return "-"
        return "0" if abs(value) < 1e-9 else f"{float(value):.{digits}g}"
    return str(value)
