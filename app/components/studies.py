"""Studies: run a shipped study in the background on the Dask machinery of ``racetrace study``,
watch it build up point by point, chart a metric against the varied key and open any point's run.

State keys: ``study_names`` (shipped studies), ``study_name`` (the one chosen), ``study_running``,
``study_status`` (progress or how it ended), ``study_rows`` (one row per point and model: values,
status, metrics), ``study_sweeps`` / ``study_sweep`` (the sweep charted), ``study_metric`` (the
metric charted, a name of :data:`solver.study.metrics.POINT_METRICS`) and the chart
``chart_study`` (the metric against the sweep's varied key, inner and outer race side by side, a
line per model). Controller: ``study_run``, ``study_cancel``, ``study_open(point, model)``.

The study runs in a thread of this process (a local Dask cluster of one single-threaded worker
per core, closed at the end) and keeps its folder under the runs folder (``.studies/``); the page
reads the folder as runs finish.
"""

from __future__ import annotations

import asyncio
import json
import math
import secrets
import threading

import numpy as np

from .base import Component, fig_json

POLL_S = 1.0
CHART_METRICS = (
    ("excursion", "excursion [deg]", 1.0),
    ("band_thickness", "band thickness [deg]", 1.0),
    ("band_width", "track width across the groove [deg]", 1.0),
    ("mean_contact_angle", "mean contact angle [deg]", 1.0),
    ("peak_pressure", "peak pressure [GPa]", 1e-9),
    ("largest_load", "largest contact load [N]", 1.0),
)
RACE_COLOURS = {"inner": "#1f77b4", "outer": "#d62728"}


class Studies(Component):
    def __init__(self, session, workers: int | None = None):
        super().__init__(session)
        self.workers = workers
        self.folder = None  # solver.study.StudyFolder of the study on show
        self.study = None
        self._thread = None
        self._stop = threading.Event()
        self._progress = None
        self._error = ""
        self._poll_task = None

    def init_state(self) -> None:
        from solver.study import shipped_studies

        s = self.state
        names = list(shipped_studies())
        s.study_names = names
        s.study_name = names[0] if names else None
        s.study_running = False
        s.study_status = ""
        s.study_rows = []
        s.study_sweeps = []
        s.study_sweep = None
        s.study_metric = "excursion"
        s.study_metric_items = [{"title": label, "value": name} for name, label, _ in CHART_METRICS]
        s.chart_study = {"data": [], "layout": {}}

    def bind(self) -> None:
        self.ctrl.study_run = self.run
        self.ctrl.study_cancel = self.cancel
        self.ctrl.study_open = self.open_point
        self.state.change("study_sweep", "study_metric")(self._on_chart_choice)

    # ---- running --------------------------------------------------------------------------------
    @property
    def busy(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def run(self) -> None:
        """Start the chosen shipped study in the background."""
        from solver.errors import CaseError
        from solver.study import Study

        if self.busy or not self.state.study_name:
            return
        try:
            study = Study.from_file(self.state.study_name)
        except CaseError as error:
            self.state.study_status = f"error: {error}"
            return
        self.start(study, self.state.study_name)

    def start(self, study, name: str) -> None:
        """Run ``study`` (a :class:`solver.study.Study`) in the background, in a new folder
        ``.studies/<name>-<random>`` of the runs folder."""
        from solver.study import StudyFolder

        if self.busy:
            return
        self.study = study
        root = self.session.store.root / ".studies"
        root.mkdir(parents=True, exist_ok=True)
        path = root / f"{name}-{secrets.token_hex(3)}"
        self.folder = StudyFolder(path)
        self._stop.clear()
        self._progress, self._error = None, ""
        self._thread = threading.Thread(target=self._work, name="racetrace-study", daemon=True)
        self._thread.start()
        with self.state:
            self.state.study_running = True
            self.state.study_status = f"starting {self.study.title} ..."
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            return  # tests call poll() themselves
        self._poll_task = loop.create_task(self._poll_loop())

    def _work(self) -> None:
        try:
            self.study.run(
                self.folder.path,
                workers=self.workers,
                progress=self._on_progress,
                cancel=self._stop,
            )
        except Exception as error:  # noqa: BLE001 - shown on the page, the session goes on
            self._error = f"{type(error).__name__}: {error}"

    def _on_progress(self, progress) -> None:
        self._progress = progress

    def cancel(self) -> None:
        """Stop the study: the runs finished so far are kept."""
        if self.busy:
            self._stop.set()
            self.state.study_status = "cancelling (finished runs are kept) ..."

    async def _poll_loop(self) -> None:
        while True:
            with self.state:
                finished = self.poll()
            if finished:
                return
            await asyncio.sleep(POLL_S)

    def poll(self) -> bool:
        """Read the study folder into the table and chart; True once the study has ended."""
        running = self.busy
        self.refresh()
        s = self.state
        p = self._progress
        if running:
            if p is not None:
                eta = f", about {p.eta_s:.0f} s left" if math.isfinite(p.eta_s) else ""
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
        return True

    # ---- showing --------------------------------------------------------------------------------
    def dataset(self):
        from solver.study import study_dataset

        if self.folder is None or not self.folder.exists():
            return None
        return study_dataset(self.folder)

    def refresh(self) -> None:
        """Table rows and chart from the study folder."""
        ds = self.dataset()
        if ds is None:
            return
        keys = json.loads(ds.attrs.get("varied_keys", "[]"))
        rows = []
        for i, point in enumerate(ds["point"].values):
            for j, model in enumerate(ds["model"].values):
                status = str(ds["status"].values[i, j])
                if status == "not run":
                    continue
                values = ", ".join(
                    f"{k.rsplit('.', 1)[-1]} = {_text(ds[k].values[i])}" for k in keys
                )
                row = {
                    "key": f"{point}-{model}",
                    "point": str(point),
                    "model": str(model),
                    "sweep": str(ds["sweep"].values[i]),
                    "values": values,
                    "status": status,
                }
                for name in ("excursion", "band_thickness"):
                    for k, race in enumerate(("inner", "outer")):
                        row[f"{name}_{race}"] = _text(ds[name].values[i, j, k], 4)
                rows.append(row)
        sweeps = list(dict.fromkeys(str(v) for v in ds["sweep"].values))
        s = self.state
        s.study_rows = rows
        if s.study_sweeps != sweeps:
            s.study_sweeps = sweeps
        if s.study_sweep not in sweeps:
            s.study_sweep = sweeps[0] if sweeps else None
        s.chart_study = fig_json(study_figure(ds, s.study_sweep, s.study_metric))

    def _on_chart_choice(self, **_):
        ds = self.dataset()
        if ds is not None:
            self.state.chart_study = fig_json(
                study_figure(ds, self.state.study_sweep, self.state.study_metric)
            )

    def open_point(self, point: str, model: str) -> None:
        """Show one point's run in the 3-D view, the raceway map and the charts."""
        from solver.errors import CaseError

        if self.folder is None:
            return
        try:
            ds = self.folder.load_point(point, model)
        except (CaseError, OSError, ValueError) as error:
            self.state.study_status = f"cannot open {point} {model}: {error}"
            return
        self.state.run_id = None
        self.session.result.shown_run_id = None
        self.session.result.show_result(ds, f"{self.study.title}: {point} {model}")

    def shutdown(self) -> None:
        self._stop.set()


def _text(value, digits: int = 5) -> str:
    if isinstance(value, float | np.floating):
        return f"{float(value):.{digits}g}" if math.isfinite(value) else "-"
    return str(value)


def study_figure(ds, sweep: str | None, metric: str):
    """Plotly figure: ``metric`` against the first key ``sweep`` varies, inner and outer race side
    by side, a line per model."""
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    label, scale = next(((lab, sc) for n, lab, sc in CHART_METRICS if n == metric), (metric, 1.0))
    fig = make_subplots(
        rows=1, cols=2, subplot_titles=("inner race", "outer race"), shared_yaxes=True
    )
    select = np.asarray(ds["sweep"].values) == sweep
    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    varied = [k for k in keys if len(set(np.asarray(ds[k].values)[select].tolist())) > 1]
    if select.any() and varied and np.asarray(ds[varied[0]].values).dtype.kind in "fi":
        key = varied[0]
        x = np.asarray(ds[key].values, float)[select]
        order = np.argsort(x)
        for col, race in enumerate(("inner", "outer"), start=1):
            for model in ds["model"].values:
                y = np.asarray(ds[metric].sel(model=model, race=race).values, float)[select]
                fig.add_trace(
                    go.Scatter(
                        x=x[order].tolist(),
                        y=(y[order] * scale).tolist(),
                        mode="lines+markers",
                        name=f"{race}, {model}",
                        line={
                            "color": RACE_COLOURS[race],
                            "dash": "dash" if model == "quasistatic" else "solid",
                        },
                        customdata=np.asarray(ds["point"].values)[select][order].tolist(),
                    ),
                    row=1,
                    col=col,
                )
        fig.update_xaxes(title_text=key.rsplit(".", 1)[-1])
    fig.update_yaxes(title_text=label, col=1)
    fig.update_layout(margin={"l": 50, "r": 10, "t": 30, "b": 40}, legend={"orientation": "h"})
    return fig
