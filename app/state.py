"""The app: one class holding the trame state and its handlers (testable without a browser).

:class:`RacetraceApp` owns the case being edited, the result on show (a quasi-static preview or a
saved run), the 3-D scene, the charts, the background runner and the runs folder. The page layout
(:mod:`app.ui`) only binds widgets to the state keys and controller actions defined here.

State keys the page binds to (all plain JSON values):
``case_items``/``case_name`` (shipped cases), ``form`` (field descriptors), ``fv_<name>`` (field
text), ``fe_<name>`` (field message, "" when valid), ``case_message``, ``run_disabled``,
``run_reason`` (why the dynamic model cannot run a valid case, "" when it can), ``busy``,
``status`` (ends in ``done``, ``cancelled`` or ``error: ...``), ``progress`` (0-100), ``eta``,
``frame``/``frame_max``/``playing``/``speed``, ``result_label``, ``runs``/``run_id``, scene
options (``show_<layer>``, ``exaggeration``, ``trace_ball``, ``camera``) and the chart figures
``chart_<name>`` (plotly JSON).
"""

from __future__ import annotations

import asyncio
import json
import logging
import math
import secrets
import time
import urllib.parse
from pathlib import Path

import numpy as np

from . import charts
from .caseform import apply_form, case_form_values, form_fields, form_text
from .frames import FrameSource, frame_source
from .lessons.panel import LessonController
from .runner import DYNAMIC_JOB, SolverRunner
from .runs import RunStore, default_runs_dir, describe_case, load_netcdf

log = logging.getLogger("racetrace.app")

DEFAULT_CASE = "spindle-combined-load"
PLAY_FPS = 15.0  # animation ticks per second while playing
CHART_FOLLOW_S = 1.0  # while playing, time-following charts refresh at most this often
POLL_S = 0.2  # runner polling period
PREVIEW_DEBOUNCE_S = 0.1
CUTAWAY_HALF_WIDTH = math.radians(70.0)  # the outer ring is cut away +-70 deg about the load side
_SELECT_KINDS = ("choice", "bool", "material")  # form fields shown as selects (empty = None)
CHARTS = (
    "contact_angle",
    "raceway_map",
    "load_azimuth",
    "ellipse",
    "cage_speed",
    "comparison",
    "compare_runs",
    "compare_angle",
    "compare_load",
)


def _fig_json(fig) -> dict:
    return json.loads(fig.to_json())


class RacetraceApp:
    """State and handlers of the racetrace page.

    ``server``: a trame server (``trame.app.get_server``); ``runs_dir``: runs folder (default
    :func:`app.runs.default_runs_dir`); ``render``: build the pyvista scene (False in pure state
    tests); ``window_size``: 3-D view size in pixels.
    """

    def __init__(
        self,
        server,
        runs_dir: str | Path | None = None,
        render: bool = True,
        window_size=(650, 480),
    ):
        self.server = server
        self.state, self.ctrl = server.state, server.controller
        self.store = RunStore(runs_dir if runs_dir is not None else default_runs_dir())
        self.runner = SolverRunner()
        self.fields = form_fields()
        self._field_by_name = {f.name: f for f in self.fields}
        self.render_enabled = render
        self.window_size = window_size
        self.plotter = None
        self.scene = None
        self.view = None  # set by the UI: an object with render() that pushes a frame
        self.base_case = None  # the case the form edits (from the case list, a file or a run)
        self.case = None  # the valid edited case, or None while the form is invalid
        self.dataset = None  # result on show
        self.quasistatic = None  # latest quasi-static result (for comparison)
        self.source: FrameSource | None = None
        self._scene_key = None
        self._preview_generation = 0
        self._last_chart_update = 0.0
        self._play_task = None
        self._poll_task = None
        self._run_info = {}
        self._cancel_requested = False
        self._filling = False
        self._client_ids = set()
        self._case_text = None  # case TOML of the valid edited case
        self._shown_case_text = None  # case TOML of the result on show
        self._shown_run_id = None  # id of the saved run on show (None for a preview)
        self._animating_export = False  # an animation export is moving the scene's frames
        self._export_task = None
        self._comparison_serial = -1  # result_serial of the quasi-static vs dynamic chart shown
        self._compare_key = None  # (result_serial, compare_id) of the comparison shown
        self._compare_run = None  # (run_id, Dataset, FrameSource) of the last run compared with
        self.clients = 0  # connected browsers
        self._init_state()
        self._bind()
        self.lessons = LessonController(self)  # the Lessons panel and presenter mode

    # ---- set-up ---------------------------------------------------------------------------------
    def _init_state(self) -> None:
        s = self.state
        from solver.catalogue import catalogue

        entries = list(catalogue())
        s.case_items = [{"title": f"{e.title} ({e.kind})", "value": e.name} for e in entries]
        self._catalogue = {e.name: e for e in entries}
        s.case_name = None
        s.form = [
            {
                "name": f.name,
                "key": f.key,
                "label": f.label,
                "kind": f.kind,
                "unit": f.unit,
                "help": f.help,
                "choices": list(f.choices),
                "section": f.section,
            }
            for f in self.fields
        ]
        for f in self.fields:
            s[f"fv_{f.name}"] = ""
            s[f"fe_{f.name}"] = ""
        # what an empty field means: the default the solver uses (estimated ones per case)
        s.placeholders = {f.name: f.default_text for f in self.fields}
        s.result_warnings = []  # where the result on show leaves the model's validity
        s.case_message = ""
        s.case_valid = False
        s.case_toml_href = ""
        s.case_file_name = "case.toml"
        s.busy = False
        s.run_disabled = True
        s.run_reason = ""  # why the dynamic model cannot run the case in the form ("" if it can)
        s.status = "starting"
        s.progress = 0
        s.eta = ""
        s.frame = 0
        s.frame_max = 0
        s.frame_time = ""
        s.playing = False
        s.speed = 1
        s.result_label = ""
        s.result_serial = 0  # incremented whenever a new result is shown (tests, benchmarks)
        s.runs = []
        s.run_id = None
        s.compare_id = None
        s.open_panels = []  # collapsible chart panels open on the page (their keys)
        s.compare_label = ""  # label of the run compared with (B)
        s.compare_summary = []  # rows of charts.summary_rows (plain JSON)
        s.compare_message = ""  # why the chosen run cannot be compared ("" when fine)
        for layer in ("inner_ring", "outer_ring", "balls", "cage", "ellipses", "traces"):
            s[f"show_{layer}"] = True
        s.exaggeration = 1.0
        s.trace_ball = -1
        s.ball_items = [{"title": "all balls", "value": -1}]
        s.camera = "isometric"
        s.chart_help = dict(charts.HELP)
        for name in CHARTS:
            s[f"chart_{name}"] = {"data": [], "layout": {}}
        s.uploaded_case = None
        s.export_href = ""
        s.export_name = ""
        s.export_message = ""
        s.exporting = False
        self._refresh_runs()

    def _bind(self) -> None:
        s, c = self.state, self.ctrl
        s.change("case_name")(self._on_case_name)
        s.change(*[f"fv_{f.name}" for f in self.fields])(self._on_field)
        s.change("frame")(self._on_frame)
        s.change("playing")(self._on_playing)
        s.change(
            *[
                f"show_{n}"
                for n in ("inner_ring", "outer_ring", "balls", "cage", "ellipses", "traces")
            ]
        )(self._on_layers)
        s.change("exaggeration", "trace_ball")(self._on_trace_options)
        s.change("camera")(self._on_camera)
        s.change("run_id")(self._on_run_id)
        s.change("compare_id")(self._on_compare_id)
        s.change("open_panels")(self._on_open_panels)
        s.change("uploaded_case")(self._on_upload)
        c.run = self.run
        c.cancel = self.cancel
        c.step = self.step
        c.set_camera = self.set_camera
        c.reset_case = self.reset_case
        c.refresh_runs = self._refresh_runs
        c.export = self.request_export
        # Count browser connections at the websocket level: the page's own "exited" signal is not
        # sent when a browser is killed, and a play loop without viewers floods the log.
        self.server.add_protocol_to_configure(self._configure_protocol)

    def start(self, case_name: str = DEFAULT_CASE, play: bool = True) -> None:
        """Open ``case_name`` solved (quasi-static) before the first page is served."""
        if case_name not in self._catalogue:
            case_name = next(iter(self._catalogue))
        self.state.case_name = case_name
        self._on_case_name(case_name, synchronous=True)
        self.state.playing = play

    # ---- case and form --------------------------------------------------------------------------
    def _on_case_name(self, case_name=None, synchronous=False, **_):
        entry = self._catalogue.get(case_name)
        if entry is None:
            return
        self.set_base_case(entry.load(), synchronous=synchronous)

    def set_base_case(self, case, synchronous: bool = False) -> None:
        """Put ``case`` in the form and preview it."""
        self._take_case(case)
        if synchronous:
            self.preview_now()
        else:
            self.schedule_preview()

    def _take_case(self, case) -> None:
        """Make ``case`` the one the form edits: its values, placeholders and messages."""
        self.base_case = case
        self._fill_form(case)
        self._update_placeholders(case)
        self.validate()

    def _fill_form(self, case) -> None:
        """Put the values of ``case`` in the form without triggering a preview per field."""
        values = case_form_values(case, self.fields)
        self._filling = True
        try:
            with self.state:
                for name, value in values.items():
                    empty = None if self._field_by_name[name].kind in _SELECT_KINDS else ""
                    self.state[f"fv_{name}"] = empty if value is None else form_text(value)
                    self.state[f"fe_{name}"] = ""
        finally:
            self._filling = False

    def _update_placeholders(self, case) -> None:
        from .caseform import estimated_default_texts

        placeholders = {f.name: f.default_text for f in self.fields}
        try:
            placeholders.update(estimated_default_texts(case, self.fields))
        except (ValueError, ArithmeticError) as error:  # a doubtful case keeps the rules
            log.warning("no estimated defaults for this case: %s", error)
        self.state.placeholders = placeholders

    def _on_upload(self, uploaded_case=None, **_):
        if not uploaded_case:
            return
        from solver import CaseError, parse_case
        from solver.case.io import decode_case_bytes

        item = uploaded_case[0] if isinstance(uploaded_case, list) else uploaded_case
        self.state.uploaded_case = None  # empty the file box, so the same file can be sent again
        name = str(item.get("name", "file"))
        content = item.get("content", b"")
        try:
            # the upload is case text, never a path on the server
            text = decode_case_bytes(content, name) if isinstance(content, bytes) else str(content)
            case = parse_case(text, source=f"uploaded file {name}")
        except CaseError as error:
            self.state.case_message = f"{name}: {error}"
            return
        self.state.case_name = None  # picking a shipped case afterwards (even the same) reloads it
        self.set_base_case(case)

    def reset_case(self) -> None:
        """Undo the edits: the form gets the values of the case last picked, uploaded or opened."""
        entry = self._catalogue.get(self.state.case_name)
        case = entry.load() if entry is not None else self.base_case
        if case is not None:
            self.set_base_case(case)

    def form_values(self) -> dict:
        return {f.name: self.state[f"fv_{f.name}"] for f in self.fields}

    def validate(self):
        """Check the form; set field messages, ``case_valid``, ``run_disabled``; return result."""
        if self.base_case is None:
            return None
        result = apply_form(self.base_case, self.fields, self.form_values())
        with self.state:
            for f in self.fields:
                self.state[f"fe_{f.name}"] = result.errors.get(f.name, "")
            self.state.case_message = "\n".join(result.general)
            self.state.case_valid = result.valid
            self.state.run_reason = self._run_reason(result.case) if result.valid else ""
            self.state.run_disabled = (
                not result.valid or bool(self.state.run_reason) or self.state.busy
            )
        self.case = result.case if result.valid else None
        self._case_text = self.case.to_toml() if self.case is not None else None
        if self.case is not None:
            text = self._case_text
            self.state.case_toml_href = "data:application/toml;charset=utf-8," + urllib.parse.quote(
                text
            )
            name = self.state.case_name or self.case.bearing.designation or "case"
            self.state.case_file_name = "".join(c if c.isalnum() else "-" for c in name) + ".toml"
        return result

    @staticmethod
    def _run_reason(case) -> str:
        """Why the dynamic model cannot run the valid ``case`` ("" when it can)."""
        from solver import dynamic_problems

        return "\n".join(f"dynamic model: {p.message}" for p in dynamic_problems(case))

    def _on_field(self, **_):
        if self._filling:
            return
        if self.validate() is not None and self.case is not None:
            if self._case_text == self._shown_case_text:
                return  # the result on show is already this case (e.g. a reopened run)
            self.schedule_preview()

    # ---- quasi-static preview -------------------------------------------------------------------
    def schedule_preview(self) -> None:
        """Recompute the quasi-static preview soon (debounced) without blocking the page."""
        self._preview_generation += 1
        generation = self._preview_generation
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            self.preview_now()
            return
        if not self.state.busy:
            self.state.status = "updating preview"
        loop.create_task(self._preview_async(generation))

    async def _preview_async(self, generation: int) -> None:
        await asyncio.sleep(PREVIEW_DEBOUNCE_S)
        if generation != self._preview_generation or self.case is None:
            return
        case = self.case
        try:
            ds = await asyncio.to_thread(self._solve_quasistatic, case)
        except Exception as error:  # shown in words in the status line
            if not self.state.busy:
                with self.state:
                    self.state.status = f"error: {error}"
            return
        if generation == self._preview_generation:
            with self.state:
                self._show_preview(ds)
                if not self.state.busy:  # a run's status stays until it ends
                    self.state.status = "preview done"

    def preview_now(self) -> None:
        """Solve the quasi-static model for the current case now and show it."""
        if self.case is None:
            return
        try:
            ds = self._solve_quasistatic(self.case)
        except Exception as error:
            self.state.status = f"error: {error}"
            return
        self._show_preview(ds)
        self.state.status = "preview done"

    def _show_preview(self, ds) -> None:
        """Show a quasi-static preview; the runs list then names no run."""
        self.state.run_id = None
        self._shown_run_id = None
        self.show_result(ds, "quasi-static preview")

    def show_lesson_result(self, case, ds, label: str) -> None:
        """Put ``case`` in the form and show ``ds``, a result of that case (a lesson's), without
        solving a preview; the runs list then names no run."""
        self._preview_generation += 1  # a preview still on its way must not replace it
        self.state.case_name = None  # picking a shipped case afterwards (even the same) reloads it
        self._take_case(case)
        self.state.run_id = None
        self._shown_run_id = None
        self.show_result(ds, label)

    def _show_saved_run(self, ds, run_id: str, label: str) -> None:
        """Show saved run ``run_id``, named in the runs list; a pending preview is dropped."""
        self._preview_generation += 1  # a preview still on its way must not replace the run
        self.show_result(ds, label)
        self._shown_run_id = run_id
        self.state.run_id = run_id

    @staticmethod
    def _solve_quasistatic(case):
        import solver

        return solver.solve_quasistatic(case)

    # ---- showing a result -----------------------------------------------------------------------
    def show_result(self, ds, label: str) -> None:
        """Show a result Dataset: frame source, scene, charts and the time controls."""
        from solver import parse_case
        from solver.results.dataset import geometry_from_result

        source = frame_source(ds, **self._animation_options(ds))
        self.dataset = ds
        self.source = source
        # the run's own case (provenance): its case warnings, whether the form already shows it, and
        # the quasi-static comparison solved for it; the views read the result's coordinates
        case = parse_case(ds.attrs["case"], "the run's case") if ds.attrs.get("case") else self.case
        self._shown_case_text = case.to_toml() if case is not None else None
        self.state.result_warnings = self._warnings_of(ds, case)
        if "time" not in ds.dims:
            self.quasistatic = ds
        else:  # the quasi-static solution of the same case, for the comparison chart
            try:
                self.quasistatic = self._solve_quasistatic(case)
            except Exception as error:  # the comparison is then left out, with the reason logged
                log.warning("no quasi-static comparison for this run: %s", error)
                self.quasistatic = None
        if self.render_enabled:
            self._ensure_scene(geometry_from_result(ds), self._load_side(ds))
            self.scene.show_source(source, 0)
        s = self.state
        s.frame_max = source.n_frames - 1
        s.result_label = label
        s.result_serial = int(s.result_serial) + 1
        s.export_href, s.export_name, s.export_message = "", "", ""
        s.ball_items = [{"title": "all balls", "value": -1}] + [
            {"title": f"ball {j}", "value": j} for j in range(source.ball_count)
        ]
        if s.frame > s.frame_max:
            s.frame = 0
        self._apply_frame(int(s.frame), charts_too=True)  # includes an open comparison

    @staticmethod
    def _warnings_of(ds, case) -> list[str]:
        """Case warnings and :func:`solver.result_warnings` of the result ``ds`` (plain text)."""
        import solver

        found = [str(w) for w in case.warnings()] if case is not None else []
        try:
            found += solver.result_warnings(ds)
        except (KeyError, ValueError) as error:  # an older result without some variable
            log.warning("result checks skipped: %s", error)
        return found

    @staticmethod
    def _load_side(ds) -> float:
        """Azimuth (rad, from +y towards +z) of the radial load of the result ``ds`` (its
        ``radial_load_angle`` coordinate, degree): where the load zone is."""
        return math.radians(float(ds.coords["radial_load_angle"]))

    def _animation_options(self, ds) -> dict:
        """Options of :func:`app.frames.frame_source`: a quasi-static result is animated for the
        form's ``[simulation] shaft_revolutions`` (the preview shows the case in the form)."""
        if "time" in ds.dims or self.case is None:
            return {}
        revolutions = getattr(getattr(self.case, "simulation", None), "shaft_revolutions", None)
        return {} if revolutions is None else {"revolutions": float(revolutions)}

    def _ensure_scene(self, geometry, load_side: float) -> None:
        key = (
            geometry.ball_count,
            geometry.ball_diameter,
            geometry.pitch_diameter,
            geometry.inner_conformity,
            geometry.outer_conformity,
            geometry.free_contact_angle,
            geometry.inner_shoulder_diameter,
            geometry.outer_shoulder_diameter,
            geometry.ball_material.name,
            load_side,
        )
        if self.scene is not None and key == self._scene_key:
            return
        import pyvista as pv

        from .scene import BearingScene, SceneOptions

        if self.plotter is None:
            pv.global_theme.multi_samples = 0
            self.plotter = pv.Plotter(off_screen=True, window_size=self.window_size)
        else:  # a new bearing: drop the old scene, its colour bar too (else never redrawn)
            for title in list(self.plotter.scalar_bars.keys()):
                self.plotter.remove_scalar_bar(title)
            self.plotter.clear_actors()
        camera = self.plotter.camera_position if self.scene is not None else None
        options = SceneOptions(
            exaggeration=float(self.state.exaggeration),
            trace_ball=None if int(self.state.trace_ball) < 0 else int(self.state.trace_ball),
            # face the load zone and cut the outer ring away there
            view_azimuth=load_side,
            outer_cutaway=(load_side - CUTAWAY_HALF_WIDTH, load_side + CUTAWAY_HALF_WIDTH),
        )
        dark = geometry.ball_material.density < 5000.0  # ceramic balls drawn dark
        self.scene = BearingScene(self.plotter, geometry, options, dark_balls=dark)
        for layer in options.layers:
            self.scene.set_layer(layer, bool(self.state[f"show_{layer}"]))
        if camera is not None:
            self.plotter.camera_position = camera
        self._scene_key = key
        if camera is None:  # a new scene: frame it with the chosen preset
            self.scene.set_camera(str(self.state.camera))
            self._push_view()

    def _push_view(self) -> None:
        if self.view is None:
            return
        if self.scene is not None and not self.scene.framed_for_window():
            # the page resized the view since the preset was applied: frame it again
            self.scene.set_camera(str(self.state.camera))
        self.view.render()

    def _apply_frame(self, index: int, charts_too: bool) -> None:
        if self.source is None:
            return
        index = int(min(max(index, 0), self.source.n_frames - 1))
        if self.scene is not None and not self._animating_export:
            self.scene.set_frame(index)
            self._push_view()
        self.state.frame_time = f"t = {self.source.times[index] * 1e3:8.3f} ms"
        if charts_too:
            self.update_charts(index)

    def update_charts(self, index: int | None = None) -> None:
        """Recompute the chart figures for frame ``index`` (default: the current frame).

        The two charts always on the page are recomputed every time; those in the collapsible
        panels only while their panel is open (``open_panels``), since each figure costs 10-30 ms
        and the preview must stay quick. Opening a panel brings its chart up to date.
        """
        if self.source is None:
            return
        i = int(self.state.frame) if index is None else index
        src, s = self.source, self.state
        open_panels = set(s.open_panels or ())
        ball = int(s.trace_ball)
        balls = (ball,) if ball >= 0 else None  # None: every ball
        s.chart_contact_angle = _fig_json(charts.contact_angle_figure(src, balls, current=i))
        s.chart_raceway_map = _fig_json(charts.raceway_map_figure(src, stop=i + 1))
        if "load_azimuth" in open_panels:
            s.chart_load_azimuth = _fig_json(charts.load_azimuth_figure(src, i))
        if "ellipse" in open_panels:
            s.chart_ellipse = _fig_json(charts.ellipse_figure(src, i))
        if "cage_speed" in open_panels:
            s.chart_cage_speed = _fig_json(charts.cage_speed_figure(src, self.dataset, current=i))
        serial = int(s.result_serial)
        if "comparison" in open_panels and self._comparison_serial != serial:
            if self.quasistatic is not None:  # does not follow time: once per result
                dyn = self.dataset if "time" in self.dataset.dims else None
                s.chart_comparison = _fig_json(charts.comparison_figure(self.quasistatic, dyn))
            self._comparison_serial = serial
        if "compare" in open_panels and self._compare_key != (serial, s.compare_id):
            self.update_comparison()
        self._last_chart_update = time.monotonic()

    def _on_open_panels(self, **_):
        self.update_charts()

    # ---- time -----------------------------------------------------------------------------------
    def _on_frame(self, frame=0, **_):
        follow = (
            not self.state.playing or time.monotonic() - self._last_chart_update > CHART_FOLLOW_S
        )
        self._apply_frame(int(frame), charts_too=follow)

    def step(self, delta: int = 1) -> None:
        """Move ``delta`` frames (wrapping at the ends)."""
        if self.source is None:
            return
        self.state.frame = int((int(self.state.frame) + int(delta)) % self.source.n_frames)

    def _on_playing(self, playing=False, **_):
        if playing and (self._play_task is None or self._play_task.done()):
            try:
                loop = asyncio.get_running_loop()
            except RuntimeError:
                return  # started when a browser connects (see _configure_protocol)
            self._play_task = loop.create_task(self._play_loop())
        if not playing:
            self.update_charts()

    async def _play_loop(self) -> None:
        period = 1.0 / PLAY_FPS
        while self.state.playing and self.clients > 0 and self.source is not None:
            t0 = time.monotonic()
            with self.state:
                step = max(1, int(self.state.speed))
                self.state.frame = (int(self.state.frame) + step) % self.source.n_frames
            await asyncio.sleep(max(0.005, period - (time.monotonic() - t0)))

    def _configure_protocol(self, protocol) -> None:
        connect, close = protocol.onConnect, protocol.onClose

        def on_connect(request, client_id):
            connect(request, client_id)
            self._client_ids.add(client_id)
            self.clients = len(self._client_ids)
            self._on_playing(self.state.playing)

        def on_close(client_id):
            close(client_id)
            self._client_ids.discard(client_id)
            self.clients = len(self._client_ids)

        protocol.onConnect, protocol.onClose = on_connect, on_close

    # ---- scene options --------------------------------------------------------------------------
    def _on_layers(self, **_):
        if self.scene is None:
            return
        for layer in self.scene.options.layers:
            self.scene.set_layer(layer, bool(self.state[f"show_{layer}"]))
        self._push_view()

    def _on_trace_options(self, exaggeration=1.0, trace_ball=-1, **_):
        if self.scene is not None:
            self.scene.options.trace_ball = None if int(trace_ball) < 0 else int(trace_ball)
            self.scene.set_exaggeration(float(exaggeration))
            self._push_view()
        self.update_charts()

    def set_camera(self, preset: str) -> None:
        """Apply camera ``preset`` (isometric, axial, radial), even if it is the current one."""
        if self.state.camera == preset:
            self._on_camera(preset)  # no state change, so no callback: apply it here
        else:
            self.state.camera = preset

    def _on_camera(self, camera="isometric", **_):
        if self.scene is not None:
            self.scene.set_camera(camera)
            self._push_view()

    # ---- runs -----------------------------------------------------------------------------------
    def _refresh_runs(self) -> None:
        self.state.runs = [{"title": r.label, "value": r.run_id} for r in self.store.list()]

    def _on_run_id(self, run_id=None, **_):
        if not run_id or run_id == self._shown_run_id:
            return
        try:
            ds, case_text = self.store.load(run_id)
        except (OSError, ValueError) as error:
            self.state.status = f"error: {error}"
            return
        from solver import parse_case

        self._take_case(parse_case(case_text, "the saved run's case"))
        label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
        with self.state:
            self._show_saved_run(ds, run_id, label)
            if not self.state.busy:
                self.state.status = "saved run opened: done"  # at rest the status ends in done

    def _on_compare_id(self, compare_id=None, **_):
        self.update_comparison()

    def update_comparison(self) -> None:
        """Compare the result on show (A) with the saved run chosen in ``compare_id`` (B).

        Sets ``chart_compare_runs`` (side-by-side raceway maps), ``chart_compare_angle`` and
        ``chart_compare_load`` (overlays versus ball azimuth), ``compare_summary`` (table rows of
        :func:`app.charts.run_summary`) and ``compare_label``; all are emptied when nothing is
        chosen or the run cannot be loaded, and ``compare_message`` then says why in words.
        """
        run_id = self.state.compare_id
        if not run_id or self.source is None:
            self._clear_comparison("")
            return
        try:
            ds, other = self._load_compare_run(run_id)
        except (OSError, ValueError) as error:
            self._clear_comparison(f"cannot compare with {run_id}: {error}")
            return
        self._compare_key = (int(self.state.result_serial), run_id)
        label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
        summaries = {
            "A": charts.run_summary(self.source, self.dataset),
            "B": charts.run_summary(other, ds),
        }
        with self.state:
            s = self.state
            s.chart_compare_runs = _fig_json(charts.side_by_side_raceway_maps(self.source, other))
            s.chart_compare_angle = _fig_json(charts.compare_angle_figure(self.source, other))
            s.chart_compare_load = _fig_json(charts.compare_load_figure(self.source, other))
            s.compare_summary = charts.summary_rows(summaries)
            s.compare_label = label
            s.compare_message = ""

    def _load_compare_run(self, run_id: str):
        """(Dataset, FrameSource) of saved run ``run_id``; the last one is kept for reuse."""
        if self._compare_run is None or self._compare_run[0] != run_id:
            ds, _ = self.store.load(run_id)
            self._compare_run = (run_id, ds, frame_source(ds))
        return self._compare_run[1], self._compare_run[2]

    def _clear_comparison(self, message: str) -> None:
        """Empty the comparison charts and table; ``message`` says why ("" when not asked for)."""
        with self.state:
            s = self.state
            for name in ("compare_runs", "compare_angle", "compare_load"):
                s[f"chart_{name}"] = {"data": [], "layout": {}}
            s.compare_summary = []
            s.compare_label = ""
            s.compare_message = message
        self._compare_key = None

    def run(self) -> None:
        """Start the dynamic model on the current case in the background."""
        if self.runner.busy or self.validate() is None or self.case is None:
            return
        if self.state.run_reason:  # the form says why
            return
        self.store.root.mkdir(parents=True, exist_ok=True)
        out = self.store.root / f".job-{secrets.token_hex(4)}.nc"
        case_text = self.case.to_toml()
        title = describe_case(self.case)
        self._run_info = {"case_text": case_text, "title": title, "out": out}
        self._cancel_requested = False
        self.runner.start(case_text, out, target=DYNAMIC_JOB)
        with self.state:
            # the animation would take processor time from the solver (2 cores here): pause it
            self.state.playing = False
            self.state.busy = True
            self.state.run_disabled = True
            self.state.progress = 0
            self.state.eta = ""
            self.state.status = "running dynamic"
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            return  # tests drive poll_runner() themselves
        self._poll_task = loop.create_task(self._poll_loop())

    def cancel(self) -> None:
        """Stop the run; the part computed so far is kept and saved."""
        if not self.runner.busy:
            return
        self._cancel_requested = True
        self.state.status = "cancelling"
        self.runner.cancel()

    async def _poll_loop(self) -> None:
        while self.runner.busy or self.state.busy:
            with self.state:
                finished = self.poll_runner()
            if finished:
                return
            await asyncio.sleep(POLL_S)

    def poll_runner(self) -> bool:
        """Apply runner events to the state; True once the run has finished."""
        events = self.runner.poll()
        if not events and not self.runner.busy and self.state.busy:
            # the runner was shut down before its last event (SolverRunner.shutdown)
            self._end_run("cancelled" if self._cancel_requested else "error: the run stopped")
            return True
        for event in events:
            if event.kind == "progress":
                self.state.progress = round(100 * event.fraction, 1)
                if np.isfinite(event.eta_s):
                    self.state.eta = f"about {event.eta_s:.0f} s left"
            elif event.kind == "done":
                self._finish_run(event)
                return True
            elif event.kind == "error":
                status = "cancelled" if self._cancel_requested else f"error: {event.text}"
                self._end_run(status)
                return True
        return False

    def _finish_run(self, event) -> None:
        out = Path(event.path)
        try:
            ds = load_netcdf(out)
            info = self.store.save(ds, self._run_info["case_text"], self._run_info["title"])
        except Exception as error:
            self._end_run(f"error: the result could not be saved ({error})")
            return
        finally:
            out.unlink(missing_ok=True)
        self._refresh_runs()
        self._show_saved_run(ds, info.run_id, info.label)
        self._end_run("cancelled" if info.status == "cancelled" else "done")

    def _end_run(self, status: str) -> None:
        s = self.state
        s.busy = False
        s.run_disabled = not s.case_valid or bool(s.run_reason)
        s.eta = ""
        if status == "done":
            s.progress = 100
        s.status = status
        out = self._run_info.get("out")
        if out is not None:
            Path(out).unlink(missing_ok=True)

    # ---- export ---------------------------------------------------------------------------------
    EXPORT_URL = "racetrace-exports"
    MAX_ANIMATION_FRAMES = 120

    @property
    def exports_dir(self) -> Path:
        """Where exported files are written (served under ``/racetrace-exports/``)."""
        return self.store.root / ".exports"

    EXPORT_EXTENSIONS = {"netcdf": "nc", "csv": "csv", "png": "png", "gif": "gif", "mp4": "mp4"}

    def _export_path(self, kind: str) -> Path:
        """Target file of an export of ``kind``, named after the result on show."""
        ext = self.EXPORT_EXTENSIONS.get(kind)
        if ext is None:
            raise ValueError(f"unknown export {kind!r}; use netcdf, csv, png, gif or mp4")
        label = str(self.state.result_label)
        stem = "".join(c if c.isalnum() else "-" for c in label)[:60].strip("-") or "racetrace"
        return self.exports_dir / f"{stem}.{ext}"

    def _export_problem(self, kind: str) -> str:
        """Why ``kind`` cannot be exported now ("" if it can)."""
        if self.dataset is None:
            return "nothing to export yet"
        if kind in ("png", "gif", "mp4") and self.scene is None:
            return "export failed: the 3-D view is not available"
        return ""

    def _animation_step(self) -> int:
        return max(1, -(-self.source.n_frames // self.MAX_ANIMATION_FRAMES))

    def _offer_download(self, path: Path) -> None:
        self.state.export_name = path.name
        self.state.export_href = (
            f"{self.EXPORT_URL}/{urllib.parse.quote(path.name)}?t={time.time():.0f}"
        )
        self.state.export_message = ""

    def export(self, kind: str) -> Path | None:
        """Write the shown result or view as ``kind`` (netcdf, csv, png, gif, mp4) now.

        Returns the file (offered for download in ``export_href``), or None with the reason in
        ``export_message``. For callers without a running event loop (scripts, tests); the page
        uses :meth:`request_export`, which keeps it responsive.
        """
        return asyncio.run(self._export_async(kind))

    def request_export(self, kind: str) -> None:
        """Export from the page: in the background, with progress in ``export_message``.

        NetCDF and CSV are written in a worker thread; an animation is rendered frame by frame
        on the event loop (VTK renders in the thread that owns its window), pausing the animation
        while it runs. Returns nothing (the page cannot receive a path).
        """
        if self.state.exporting:
            return
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            self.export(kind)
            return
        self._export_task = loop.create_task(self._export_async(kind))

    async def _export_async(self, kind: str) -> Path | None:
        """The export itself (see :meth:`request_export`); returns the file or None."""
        from . import export as ex

        path = self._export_path(kind)
        problem = self._export_problem(kind)
        if problem:
            self.state.export_message = problem
            self.state.flush()
            return None
        with self.state:
            self.state.exporting = True
            self.state.export_href = ""
            self.state.export_message = f"writing {path.name} ..."
        await asyncio.sleep(0)
        dataset, label = self.dataset, self.state.result_label
        try:
            if kind == "netcdf":
                await asyncio.to_thread(ex.export_netcdf, dataset, path)
            elif kind == "csv":
                await asyncio.to_thread(ex.export_csv, dataset, path)
            elif kind == "png":
                ex.export_png(self.plotter, path)
            else:
                await self._export_animation(ex, path)
        except (OSError, ValueError) as error:
            with self.state:
                self.state.export_message = f"export failed: {error}"
            return None
        finally:
            self._animating_export = False
            with self.state:
                self.state.exporting = False
        with self.state:
            if self.state.result_label == label:  # still the same result on show
                self._offer_download(path)
            else:
                self.state.export_message = ""
        self._push_view()
        return path

    async def _export_animation(self, ex, path: Path) -> None:
        with self.state:
            self.state.playing = False
        self._animating_export = True  # frame changes from the page wait until it is written
        frames = ex.iter_export_animation(self.scene, path, step=self._animation_step())
        for fraction in frames:
            with self.state:
                self.state.export_message = f"writing {path.name}: {100 * fraction:.0f} %"
            await asyncio.sleep(0)

    def shutdown(self) -> None:
        """Stop the background run and the animation."""
        self.state.playing = False
        self.runner.shutdown()
