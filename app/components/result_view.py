"""The result on show (a quasi-static preview or a saved run): its 3-D scene, its charts and the
time controls.

State keys: ``frame``/``frame_max``/``frame_time`` (time and revolution counter)/``playing``/
``speed``, ``slow_motion`` (the playback rate in words), ``scene_note`` (what the view shows),
``result_label``, ``result_serial`` (incremented whenever a new result is shown),
``result_warnings``, ``open_panels`` (chart panels open on the page), scene options
(``show_<layer>``, ``exaggeration``, ``ellipse_scale``, ``track_quantity``, ``track_whole_run``,
``trace_ball``, ``ball_items``, ``camera``), ``ball_legend`` (each ball's colour in the 3-D
view and the raceway map: ``[{"ball": j, "colour": "#..."}]``), ``chart_help``, the chart figures
``chart_<name>`` (plotly JSON) and, for the charts that follow the time (``FOLLOWING_CHARTS``), the
marks of the current frame on them, ``chart_<name>_now`` (an overlay the page merges with the
figure: :func:`app.charts.merge_overlay`).

A bearing set's result (a ``bearing`` dimension) is shown one bearing at a time: the 3-D view,
the time controls and the single-bearing charts show the bearing chosen in the set panel
(:mod:`app.components.set_panel`, ``solver.bearing_result``), the set panel the whole set.
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from typing import NamedTuple

import numpy as np
from trame.widgets import client, html
from trame.widgets import vuetify3 as v3

from viz.frames import FrameSource, frame_source
from viz.layers import LAYERS
from viz.palette import ball_legend

from .. import charts
from ..run_length import has_history
from ..run_store import describe_case
from .base import Component, as_float, as_int, fig_json, running_loop
from .browser_view import DETECT_WEBGL, BrowserView
from .widgets import chart, checkbox, choices, icon_button, own_update, select

log = logging.getLogger("racetrace.app")

PLAY_FPS = 24.0  # animation ticks per second while playing
CHART_FOLLOW_S = 1.0  # while playing, the charts drawn for a frame refresh at most this often
# while playing, the marks of the current frame on the charts that follow the time (the time
# markers, the raceway map's contacts now: small overlays) follow at most this often (s; 0: each
# frame)
MARK_FOLLOW_S = 0.0
CUTAWAY_HALF_WIDTH = math.radians(90.0)  # the outer ring is opened as a half shell on the load side
MAX_EXAGGERATION = 1000.0
MAX_SPEED = 1000  # frames per animation tick
MAX_ELLIPSE_SCALE = 100.0  # largest drawing scale of the contact ellipses the view accepts
MAX_SHOWN_ELLIPSE_SCALE = 10.0  # the slider's end
# Contact ellipses drawn 5x their size: about 4 x 0.8 mm on the default bearing, seen at a glance
# in the whole-bearing views (to scale, 0.8 x 0.15 mm on a 54 mm pitch circle, they are not)
DEFAULT_ELLIPSE_SCALE = 5.0
HIDDEN_LAYERS = ("traces",)  # off until asked for: the painted tracks show where the balls ran
DEFAULT_EXAGGERATION = 5.0  # across-groove deviations drawn 5x: lines and bands tell apart
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
# the charts that follow the time: their figure (state ``chart_<name>``) is sent when the result or
# an option changes, what marks the current frame on it in ``chart_<name>_now`` (an overlay,
# app.charts.merge_overlay) with the frames
FOLLOWING_CHARTS = ("contact_angle", "raceway_map", "cage_speed")


class ShownResult(NamedTuple):
    """The result on show as other components read it: its Dataset, its frames, its title (the
    case and loads), its case as TOML and the id of the saved run (None for a result that is not
    a saved run; all None until a result is shown)."""

    dataset: object
    source: FrameSource | None
    title: str | None
    case_text: str | None
    run_id: str | None


class ResultView(Component):
    """The result on show: ``dataset``, its ``source`` of frames, the quasi-static solution of
    the same case (``quasistatic``, for the comparison chart), the pyvista ``plotter``/``scene``
    (when ``render_enabled``) and the page's ``view`` (set by the UI: an object with render())."""

    PROVIDES = (
        "show_preview",
        "show_unsaved",
        "show_saved_run",
        "shown_result",
        "update_charts",
        "show_set_bearing",
        "push_view",
        "live_scene",
        "show_live_frame",
        "end_live",
        "show_live_inputs",
    )

    def __init__(
        self, session, render: bool = True, window_size=(650, 480), render_mode: str = "browser"
    ):
        super().__init__(session)
        self.render_enabled = render
        self.browser = BrowserView(self, render_mode)  # the view the browser draws
        self.window_size = window_size
        self.plotter = None
        self.scene = None
        self.view = None
        self.dataset = None
        self.set_result = None  # the bearing set's Dataset on show (None: a single bearing)
        self._set_label = ""  # the label the set was shown with
        self.quasistatic = None
        self.source: FrameSource | None = None
        self.facts = None  # app.teaching.Facts of the result on show
        self._chart_keys = {}  # what the figure sent of each chart that follows the time shows
        self._shoulders = None  # (inner, outer) shoulder latitudes (rad) of the result on show
        self._analysis_start = None  # start of the solver's analysed window (s)
        self.shown_case_text = None  # case TOML of the result on show
        self.shown_run_id = None  # id of the saved run on show (None for a preview)
        self.shown_title = ""  # the case and loads of the result on show, in words
        self.animating_export = False  # an animation export is moving the scene's frames
        self._scene_key = None
        self._last_chart_update = 0.0
        self._last_mark_update = 0.0
        self._play_task = None
        self._comparison_serial = -1  # result_serial of the quasi-static vs dynamic chart shown

    # ---- set-up ---------------------------------------------------------------------------------
    def init_state(self) -> None:
        s = self.state
        s.result_warnings = []  # where the result on show leaves the model's validity
        s.frame = 0
        s.frame_max = 0
        s.frame_time = ""
        s.playing = False
        s.speed = 1
        s.result_label = ""
        s.result_serial = 0
        s.open_panels = []
        for layer in LAYERS:
            s[f"show_{layer}"] = layer not in HIDDEN_LAYERS
        s.exaggeration = DEFAULT_EXAGGERATION
        s.ellipse_scale = DEFAULT_ELLIPSE_SCALE  # drawn size of the contact ellipses / true size
        s.track_quantity = "dwell"  # painted tracks coloured by "dwell" or "peak_pressure"
        s.track_whole_run = False  # paint the whole run, not only up to the current frame
        s.slow_motion = ""  # "1 s on screen = ... of bearing time"
        s.map_colour = "race"  # raceway map coloured by "race", "ball" or "load"
        s.map_skip_startup = False  # raceway map leaves out the start-up (solver's window)
        s.raceway_metrics = ""  # excursion and band thickness under the raceway map
        s.closeup_numbers = ""  # the close-up ball's contacts in numbers (camera "close-up")
        s.scene_note = ""  # the "what you see" note beside the view
        s.trace_ball = -1
        s.ball_items = [{"title": "all balls", "value": -1}]
        s.ball_legend = []  # [{"ball": j, "colour": "#..."}]: the balls' colours in the 3-D view
        s.camera = "isometric"
        s.chart_help = dict(charts.HELP)
        self.browser.init_state()
        for name in CHARTS:
            s[f"chart_{name}"] = {"data": [], "layout": {}}
        for name in FOLLOWING_CHARTS:
            s[f"chart_{name}_now"] = charts.empty_overlay()

    def bind(self) -> None:
        self.on_change("frame")(self._on_frame)
        self.on_change("playing")(self._on_playing)
        self.on_change(*[f"show_{n}" for n in LAYERS])(self._on_layers)
        self.on_change("exaggeration", "trace_ball")(self._on_trace_options)
        self.on_change("ellipse_scale", "track_quantity", "track_whole_run")(self._on_track_options)
        self.on_change("speed")(self._on_speed)
        self.on_change("map_colour", "map_skip_startup")(self._on_map_options)
        self.on_change("camera")(self._on_camera)
        self.on_change("browser_webgl")(self._on_browser_webgl)
        self.on_change("open_panels")(self._on_open_panels)
        self.action("step", self.step)
        self.action("set_camera", self.set_camera)

    # ---- what is shown --------------------------------------------------------------------------
    def show_preview(self, ds) -> None:
        """Show a quasi-static preview; the runs list then names no run."""
        self.show_unsaved(ds, "quasi-static preview")

    def show_unsaved(self, ds, label: str) -> None:
        """Show a result that is not a saved run (a preview, a lesson's, a study point's); the
        runs list then names no run."""
        self.state.run_id = None
        self.shown_run_id = None
        self.show_result(ds, label)

    def shown_result(self) -> ShownResult:
        """The result on show, for the views of other components (the comparison)."""
        return ShownResult(
            self.dataset, self.source, self.shown_title, self.shown_case_text, self.shown_run_id
        )

    def show_saved_run(self, ds, run_id: str, label: str) -> None:
        """Show saved run ``run_id``, named in the runs list; a pending preview is dropped."""
        self.ctrl.drop_pending_preview()
        self.show_result(ds, label)
        self.shown_run_id = run_id
        self.state.run_id = run_id

    def show_result(self, ds, label: str) -> None:
        """Show a result Dataset: frame source, scene, charts and the time controls; a bearing
        set's (a ``bearing`` dimension): the bearing chosen in the set panel, and the set in
        it."""
        import solver

        set_warnings = None
        if "bearing" in ds.dims:
            index = self.ctrl.set_bearing_index(ds.sizes["bearing"])
            self.set_result, self._set_label = ds, label
            self.ctrl.show_set(ds, index)
            set_warnings = solver.set_result_warnings(ds)
            label = f"{label}: {ds['bearing'].values[index]} of the set"
            ds = solver.bearing_result(ds, index)
        elif self.set_result is not None:
            self.set_result = None
            self.ctrl.show_set(None)
        self._show_one(ds, label, set_warnings)

    def show_set_bearing(self, index: int) -> None:
        """Show bearing ``index`` of the bearing set on show (nothing without a set)."""
        if self.set_result is not None:
            self.show_result(self.set_result, self._set_label)

    def _show_one(self, ds, label: str, set_warnings=None) -> None:
        """Show a single-bearing result Dataset (``set_warnings``: the warnings of the set it is a
        bearing of, shown instead of its own)."""
        from solver import geometry_from_result, quasistatic_start

        from ..teaching import facts_from_result

        source = frame_source(ds, **self._animation_options(ds))
        answer = ds  # the metrics of a solution over one revolution span its ring angles
        if "ring_angle" in ds.dims:  # a preview over one revolution: the views read its start
            ds = ds.isel(ring_angle=0).drop_vars("ring_angle")
        self.dataset = ds
        self.source = source
        self.facts = facts_from_result(ds)
        self._describe_tracks(answer)
        # the run's own case (its provenance, parsed by the accessor): its case warnings and whether
        # the form already shows it; what the result is, the views read from its Dataset
        case = ds.racetrace.case() if ds.attrs.get("case") else self.ctrl.edited_case()
        self.shown_case_text = case.to_toml() if case is not None else None
        model = "dynamic" if "time" in ds.dims else "quasi-static"
        self.shown_title = f"{describe_case(case)} ({model})" if case is not None else label
        self.ctrl.update_staleness()
        self.state.result_warnings = self._warnings_of(ds, case, set_warnings)
        # the comparison chart's quasi-static solution: the result itself, or the quasi-static
        # start a dynamic result carries (None: the chart says the comparison is not available)
        self.quasistatic = quasistatic_start(ds)
        if self.render_enabled:
            self._ensure_scene(geometry_from_result(ds), self._load_side(ds))
            self.scene.show_source(source, 0)
            self.scene.show_facts(self.facts)
            if self.browser.render_mode == "browser":
                self.browser.show_scene(self.scene)
        self._update_words()
        s = self.state
        s.frame_max = source.n_frames - 1
        s.result_label = label
        s.result_serial = int(s.result_serial) + 1
        self.ctrl.forget_download()
        s.ball_items = [{"title": "all balls", "value": -1}] + [
            {"title": f"ball {j}", "value": j} for j in range(source.ball_count)
        ]
        s.ball_legend = ball_legend(source.ball_count)
        if as_int(s.frame, 0) > s.frame_max:
            s.frame = 0
        self._apply_frame(as_int(s.frame, 0), charts_too=True)  # includes an open comparison

    # ---- live mode (app.components.live) --------------------------------------------------------
    def live_scene(self, ds):
        """Stop the animation and make the scene for the live session's result ``ds`` (a chunk):
        the scene (None without rendering), for the live tracks' grooves and grids."""
        from solver import geometry_from_result

        self.state.playing = False
        if not self.render_enabled:
            return None
        self._ensure_scene(geometry_from_result(ds), self._load_side(ds))
        return self.scene

    def show_live_frame(
        self, source: FrameSource, index: int, tracks, words: str, urgent: bool = False
    ) -> None:
        """Draw frame ``index`` of the live window ``source`` with the live session's painted
        ``tracks`` (:class:`app.live_view.LiveTracks`); ``words``: the time on show;
        ``urgent``: the browser draws it at once (the first frame of a control change)."""
        self.state.frame_time = words
        if self.scene is None:
            return
        scene = self.scene
        scene.source = source  # the window's frames; the references stay the session's
        scene.tracks.painter = tracks
        if self.browser.active:  # the browser draws: send what moved
            if self.browser.scene is None or self.browser.scene.scene is not scene:
                self.browser.show_scene(scene)
            self.browser.show_live_frame(index, urgent)
        else:
            scene.set_frame(index)
            self.push_view()

    def show_live_inputs(self, ds) -> None:
        """While live: the 3-D view's labels (the loads, the speed) and the raceway map's caption
        describe the live session's inputs now, read from its newest chunk ``ds`` (the inputs
        over ``time``; their last values), not the result shown before."""
        from ..teaching import facts_from_result

        facts = facts_from_result(ds)
        speed = facts.inner_ring_speed * 60.0 / (2.0 * math.pi)
        words = (
            f"live session now at radial load {facts.radial_load:.0f} N, axial load "
            f"{facts.axial_load:.0f} N, shaft {speed:.0f} rpm, tilt "
            f"{math.degrees(facts.misalignment):.3g}°; the map is of the result shown before "
            "live mode, the 3-D view's painted tracks are the live session's"
        )
        if words == self.state.raceway_metrics:
            return
        self.state.raceway_metrics = words
        if self.scene is not None:
            self.scene.show_facts(facts)
            if self.browser.active:
                self.browser.show_scene(self.scene)

    def end_live(self) -> None:
        """The live session has ended: show again the result that was on show before it."""
        if self.dataset is None:
            self.state.raceway_metrics = ""
            return
        self.show_result(self.dataset, str(self.state.result_label))

    def _describe_tracks(self, ds) -> None:
        """Shoulder limits, settling window and trajectory metrics of ``ds`` for the map."""
        from solver import geometry_from_result
        from viz.raceway import shoulder_angles

        self._chart_keys.clear()
        self._shoulders = shoulder_angles(geometry_from_result(ds))
        try:
            self.state.raceway_metrics = charts.trajectory_metric_words(ds)
            start = float(ds.racetrace.metric("analysis_start_time"))
            self._analysis_start = start if math.isfinite(start) else None
        except (KeyError, ValueError) as error:  # an older result: the map still shows
            log.warning("no trajectory metrics for the map: %s", error)
            self._analysis_start = None
            self.state.raceway_metrics = ""

    def _closeup_numbers(self, index: int) -> str:
        """The close-up ball's two contacts in numbers at frame ``index``."""
        from viz.raceway import RACES

        j = max(0, self._trace_ball(self.state.trace_ball, self.source.ball_count))
        f = self.source.frame(index)
        c = self.source.contact
        parts = [f"ball {j}"]
        for race in (0, 1):
            if not f.loaded[j, race]:
                parts.append(f"{RACES[race]}: unloaded")
                continue
            text = (
                f"{RACES[race]}: contact angle {math.degrees(f.contact_angle[j, race]):.2f}°, "
                f"load {f.contact_load[j, race]:.0f} N, "
                f"peak pressure {f.max_pressure[j, race] * 1e-9:.2f} GPa"
            )
            if "spin_to_roll" in c:
                text += f", spin-to-roll {c['spin_to_roll'][f.index, j, race]:.3f}"
            parts.append(text)
        if self.source.model == "dynamic" and "ball_latitude" in c:
            parts.append("red: the contact paths on the ball's own surface")
        else:
            parts.append("the contact path on the ball's surface needs a dynamic run")
        return " · ".join(parts)

    def _on_map_options(self, **_):
        self.update_charts()

    def _chart_figures(self, balls, open_panels: set) -> None:
        """Send the figure of each chart that follows the time (those in the collapsible panels
        while open) when what it shows has changed since it was sent: the result, the ball
        (``balls``: a tuple of one, or None for every ball), the raceway map's options. The marks
        of the current frame are not in it (:meth:`_chart_marks`)."""
        s = self.state
        serial = int(s.result_serial)
        skip = bool(s.map_skip_startup) and self._analysis_start is not None
        wanted = {
            "contact_angle": (serial, balls),
            "raceway_map": (serial, balls, str(s.map_colour), skip),
        }
        if "cage_speed" in open_panels:
            wanted["cage_speed"] = (serial,)
        for name, key in wanted.items():
            if self._chart_keys.get(name) == key:
                continue
            if name == "contact_angle":
                figure = fig_json(charts.contact_angle_figure(self.source, balls))
            elif name == "raceway_map":
                figure = charts.raceway_map_base(
                    self.source,
                    balls=balls,
                    colour=str(s.map_colour),
                    start_time=self._analysis_start if skip else None,
                    shoulders=self._shoulders,
                )
            else:
                figure = fig_json(charts.cage_speed_figure(self.source, self.dataset))
            s[f"chart_{name}"] = figure
            self._chart_keys[name] = key

    def _chart_marks(self, index: int, balls, open_panels: set) -> None:
        """The marks of frame ``index`` on the charts that follow the time: the time markers and
        the raceway map's contacts now (small overlays, built without a plotly figure)."""
        s, src = self.state, self.source
        s.chart_contact_angle_now = charts.time_marker_overlay(src, index)
        s.chart_raceway_map_now = charts.current_contact_overlay(src, index, balls)
        if "cage_speed" in open_panels:
            s.chart_cage_speed_now = charts.time_marker_overlay(src, index)
        self._last_mark_update = time.monotonic()

    def _chart_balls(self):
        """The balls the charts show: a tuple of the ball chosen, or None for every ball."""
        ball = self._trace_ball(self.state.trace_ball, self.source.ball_count)
        return (ball,) if ball >= 0 else None

    def _open_panels(self) -> set:
        """The chart panels open on the page (``open_panels``)."""
        panels = self.state.open_panels
        return {p for p in panels if isinstance(p, str)} if isinstance(panels, list) else set()

    @staticmethod
    def _warnings_of(ds, case, set_warnings=None) -> list[str]:
        """Case warnings and :func:`solver.result_warnings` of the result ``ds`` (plain text);
        ``set_warnings``: those of the bearing set ``ds`` is a bearing of, instead."""
        import solver

        found = [str(w) for w in case.warnings()] if case is not None else []
        if set_warnings is not None:
            return found + list(set_warnings)
        try:
            found += solver.result_warnings(ds)
        except (KeyError, ValueError) as error:  # an older result without some variable
            log.warning("result checks skipped: %s", error)
        return found

    @staticmethod
    def _load_side(ds) -> float:
        """Azimuth (rad, from +y towards +z) of the radial load of the result ``ds`` (its
        ``radial_load_angle``, degree: a coordinate, or a data variable over time when it varies
        (a history, a live chunk) and then its value at the end): where the load zone is."""
        angle = ds["radial_load_angle"]
        if "time" in angle.dims:
            angle = angle.isel(time=-1)
        return math.radians(float(angle))

    def _animation_options(self, ds) -> dict:
        """Options of :func:`viz.frames.frame_source`: a quasi-static result is animated for the
        form's ``[simulation] shaft_revolutions`` (the preview shows the case in the form); the
        preview of a case with a time history (its operating point at t = 0) for the revolutions
        the rings make in the case's ``duration_s`` at that point's speeds."""
        case = self.ctrl.edited_case()
        if "time" in ds.dims or case is None:
            return {}
        sim = getattr(case, "simulation", None)
        if has_history(case):
            duration = getattr(sim, "duration_s", None)
            op = case.operating
            relative_rpm = abs(op.inner_ring_speed_rpm - (op.outer_ring_speed_rpm or 0.0))
            if not duration or relative_rpm == 0.0:
                return {}  # rings at rest at t = 0: the default (a static scene)
            return {"revolutions": float(duration) * relative_rpm / 60.0}
        revolutions = getattr(sim, "shaft_revolutions", None)
        return {} if revolutions is None else {"revolutions": float(revolutions)}

    # ---- 3-D scene ------------------------------------------------------------------------------
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

        from viz.scene import BearingScene, SceneOptions

        if self.plotter is None:
            pv.global_theme.multi_samples = 0
            self.plotter = pv.Plotter(off_screen=True, window_size=self.window_size)
        else:  # a new bearing: drop the old scene, its colour bar too (else never redrawn)
            for title in list(self.plotter.scalar_bars.keys()):
                self.plotter.remove_scalar_bar(title)
            self.plotter.clear_actors()
        # the camera stays where the user put it, unless the load zone moved: the view faces the
        # load zone (its outer-ring cutaway too), so it is framed again (e.g. the other bearing
        # of a set, whose radial load is on the other side)
        same_side = self._scene_key is not None and self._scene_key[-1] == load_side
        camera = self.plotter.camera_position if self.scene is not None and same_side else None
        ball = self._trace_ball(self.state.trace_ball, geometry.ball_count)
        options = SceneOptions(
            exaggeration=self._exaggeration(self.state.exaggeration),
            ellipse_scale=self._ellipse_scale(self.state.ellipse_scale),
            track_quantity=self._track_quantity(self.state.track_quantity),
            track_whole_run=bool(self.state.track_whole_run),
            trace_ball=None if ball < 0 else ball,
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
            self.push_view()

    def push_view(self) -> None:
        """Send the current 3-D image to the page (with the browser-drawn view: the parts'
        visibility, the frame and the painted tracks)."""
        if self.browser.active:
            if self.source is not None:
                self.browser.refresh(as_int(self.state.frame, 0, 0, self.source.n_frames - 1))
            return
        if self.view is None:
            return
        if self.scene is not None and not self.scene.framed_for_window():
            # the page resized the view since the preset was applied: frame it again
            self.scene.set_camera(str(self.state.camera))
        self.view.render()

    def _on_layers(self, **_):
        if self.scene is None:
            return
        for layer in self.scene.options.layers:
            self.scene.set_layer(layer, bool(self.state[f"show_{layer}"]))
        self.push_view()

    @staticmethod
    def _trace_ball(value, ball_count: int) -> int:
        """The ball whose traces are drawn (-1: every ball), from the page's ``trace_ball``."""
        return as_int(value, -1, -1, ball_count - 1)

    @staticmethod
    def _exaggeration(value) -> float:
        return as_float(value, DEFAULT_EXAGGERATION, 1.0, MAX_EXAGGERATION)

    @staticmethod
    def _ellipse_scale(value) -> float:
        return as_float(value, DEFAULT_ELLIPSE_SCALE, 1.0, MAX_ELLIPSE_SCALE)

    @staticmethod
    def _track_quantity(value) -> str:
        return str(value) if value in ("dwell", "peak_pressure") else "dwell"

    def _on_trace_options(self, exaggeration=DEFAULT_EXAGGERATION, trace_ball=-1, **_):
        if self.scene is not None:
            ball = self._trace_ball(trace_ball, self.scene.geometry.ball_count)
            self.scene.options.trace_ball = None if ball < 0 else ball
            self.scene.options.closeup_ball = max(0, ball)
            self.scene.set_exaggeration(self._exaggeration(exaggeration))
            self.push_view()
        self._update_words()
        self.update_charts()

    def _on_track_options(self, **_):
        s = self.state
        if self.scene is not None:
            self.scene.set_ellipse_scale(self._ellipse_scale(s.ellipse_scale))
            self.scene.set_track_options(
                self._track_quantity(s.track_quantity), bool(s.track_whole_run)
            )
            self.push_view()
        self._update_words()

    def _on_speed(self, **_):
        self._update_words()

    def _update_words(self) -> None:
        """The slow-motion factor and the "what you see" note for the result on show."""
        from ..teaching import playback_rate, slow_motion_words, what_you_see

        s = self.state
        if self.source is None or self.facts is None:
            s.slow_motion, s.scene_note = "", ""
            return
        step = float(np.median(np.diff(self.source.times))) if self.source.n_frames > 1 else 0.0
        speed = as_int(s.speed, 1, 1, MAX_SPEED)
        s.slow_motion = slow_motion_words(playback_rate(step, speed, PLAY_FPS))
        s.scene_note = what_you_see(
            self.facts, self._exaggeration(s.exaggeration), self._ellipse_scale(s.ellipse_scale)
        )

    def set_camera(self, preset: str) -> None:
        """Apply camera ``preset`` (isometric, axial, radial, inner track, outer track), even if
        it is the current one."""
        if self.state.camera == preset:
            self._on_camera(preset)  # no state change, so no callback: apply it here
        else:
            self.state.camera = preset

    def _on_camera(self, camera="isometric", **_):
        if self.scene is not None:
            self.scene.set_camera(camera)
            self.push_view()
            if self.browser.active:
                self.browser.set_camera(self.plotter)
        if self.source is not None:
            i = as_int(self.state.frame, 0, 0, self.source.n_frames - 1)
            self.state.closeup_numbers = self._closeup_numbers(i) if camera == "close-up" else ""

    # ---- time and charts ------------------------------------------------------------------------
    def _apply_frame(self, index: int, charts_too: bool) -> None:
        if self.source is None:
            return
        index = int(min(max(index, 0), self.source.n_frames - 1))
        if self.scene is not None and not self.animating_export:
            if self.browser.active:  # the browser draws: send what moved
                self.browser.show_frame(index)
            else:
                self.scene.set_frame(index)
                self.push_view()
        from ..teaching import revolution_words

        t = float(self.source.times[index])
        total = float(self.source.times[-1])
        revolutions = revolution_words(t, self.facts, total) if self.facts else ""
        self.state.frame_time = f"t = {t * 1e3:8.3f} ms · {revolutions}"
        self.state.closeup_numbers = (
            self._closeup_numbers(index) if self.state.camera == "close-up" else ""
        )
        if charts_too:
            self.update_charts(index)

    def update_charts(self, index: int | None = None) -> None:
        """Bring the charts up to frame ``index`` (default: the current frame).

        A chart that follows the time gets the marks of the frame (an overlay) and its figure
        only when what the figure shows changed (:meth:`_chart_figures`); a chart drawn for a
        frame (load versus azimuth, the ellipses) is recomputed. The charts in the collapsible
        panels are brought up to date only while their panel is open (``open_panels``), since
        each figure costs 10-30 ms and the preview must stay quick. Opening a panel brings its
        chart up to date.
        """
        if self.source is None:
            return
        src, s = self.source, self.state
        i = as_int(s.frame, 0) if index is None else index
        i = min(max(i, 0), src.n_frames - 1)
        open_panels = self._open_panels()
        balls = self._chart_balls()
        self._chart_figures(balls, open_panels)
        self._chart_marks(i, balls, open_panels)
        if "load_azimuth" in open_panels:
            s.chart_load_azimuth = fig_json(charts.load_azimuth_figure(src, i))
        if "ellipse" in open_panels:
            s.chart_ellipse = fig_json(charts.ellipse_figure(src, i))
        serial = int(s.result_serial)
        if "comparison" in open_panels and self._comparison_serial != serial:
            dyn = self.dataset if "time" in self.dataset.dims else None  # once per result
            s.chart_comparison = fig_json(charts.comparison_figure(self.quasistatic, dyn))
            self._comparison_serial = serial
        if "compare" in open_panels:
            self.ctrl.refresh_comparison()
        self._last_chart_update = time.monotonic()

    def _on_open_panels(self, **_):
        self.update_charts()

    def _on_frame(self, frame=0, **_):
        now = time.monotonic()
        follow = not self.state.playing or now - self._last_chart_update > CHART_FOLLOW_S
        self._apply_frame(as_int(frame, 0), charts_too=follow)
        if not follow and self.source is not None and now - self._last_mark_update >= MARK_FOLLOW_S:
            index = min(max(as_int(frame, 0), 0), self.source.n_frames - 1)
            self._chart_marks(index, self._chart_balls(), self._open_panels())

    def step(self, delta: int = 1) -> None:
        """Move ``delta`` frames (wrapping at the ends)."""
        if self.source is None:
            return
        frame = as_int(self.state.frame, 0) + as_int(delta, 1, -1_000_000, 1_000_000)
        self.state.frame = frame % self.source.n_frames

    def _on_browser_webgl(self, browser_webgl=None, **_):
        """The page said whether it can draw WebGL: pick the view, and bring it up to date."""
        if not self.browser.choose(browser_webgl):
            if self.scene is not None and self.source is not None:
                self.scene.set_frame(as_int(self.state.frame, 0, 0, self.source.n_frames - 1))
            self.push_view()
            return
        self.push_view()
        if self.scene is not None:
            self.browser.set_camera(self.plotter)

    def sync_scene(self) -> None:
        """Bring the server's scene to the frame on show (the browser-drawn view does not move
        it while playing): before an export renders it."""
        if self.scene is not None and self.source is not None:
            self.scene.set_frame(as_int(self.state.frame, 0, 0, self.source.n_frames - 1))

    def _on_playing(self, playing=False, **_):
        if playing and (self._play_task is None or self._play_task.done()):
            loop = running_loop()
            if loop is None:
                return  # started when a browser connects (see RacetraceApp)
            self._play_task = loop.create_task(self._play_loop())
        if not playing:
            self.update_charts()

    async def _play_loop(self) -> None:
        period = 1.0 / PLAY_FPS
        while self.state.playing and self.session.clients > 0 and self.source is not None:
            t0 = time.monotonic()
            try:
                with self.state:  # the frame index and what the frame shows go out in one message
                    step = as_int(self.state.speed, 1, 1, MAX_SPEED)
                    frame = (as_int(self.state.frame, 0) + step) % self.source.n_frames
                    with self.state.suppress_change_listeners("frame"):
                        self.state.frame = frame
                    self._on_frame(frame)
            except Exception:  # a frame that fails to draw must not stop the animation
                log.exception("animation frame failed")
            await asyncio.sleep(max(0.005, period - (time.monotonic() - t0)))

    def shutdown(self) -> None:
        self.state.playing = False

    # ---- page -----------------------------------------------------------------------------------
    def build_toolbar(self) -> None:
        """``#result-label``: what the result on show is."""
        html.Div("{{ result_label }}", id="result-label", classes="text-body-2 mr-4")

    def build_view(self) -> None:
        """``#view-3d`` (the server-rendered scene, with the ball legend over it), the close-up's
        numbers, the "what you see" note and the time controls."""
        from trame_pyvista.rca_view import PyVistaRCAView

        # fills the height the window leaves; the render follows its size, so the picture
        # keeps its aspect ratio at any window size; the browser draws the scene itself where it
        # can (render_mode "browser" and WebGL), else the server's images are shown
        client.Script(DETECT_WEBGL)
        with html.Div(
            id="view-3d",
            style="height: calc(100vh - 330px); min-height: 320px; position: relative;",
        ):
            with html.Template(v_if="view_in_browser"):
                self.browser.build()
            with html.Template(v_else_if="render_mode === 'server' || browser_webgl === false"):
                self.view = PyVistaRCAView(self.plotter, style="width: 100%; height: 100%;")
            _ball_legend()
        with own_update():  # changes with every played frame in the close-up
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

    def build_scene_controls(self) -> None:
        """Camera presets, drawing scales, the ball followed, the tracks' colouring and the
        layers shown."""
        _camera_and_scales(self.ctrl)
        _track_options()
        with v3.VRow(dense=True):
            for layer, label in LAYER_LABELS.items():
                with v3.VCol(cols="auto"):
                    checkbox(label, f"show_{layer}")

    def build_charts(self) -> None:
        """The charts always on the page: contact angle, then the raceway map with its options
        and the excursion and band thickness of each raceway (``#raceway-metrics``)."""
        chart(
            "chart-contact-angle",
            "chart_contact_angle",
            charts.HELP["contact_angle"],
            overlay="chart_contact_angle_now",
        )
        with v3.VRow(dense=True, align="center", classes="mt-1"):
            with v3.VCol(cols=6):
                select(
                    "raceway map coloured by",
                    "map_colour",
                    choices((("race", "raceway"), ("ball", "ball"), ("load", "contact load"))),
                    id="map-colour",
                )
            with v3.VCol():
                checkbox(
                    "skip start-up",
                    "map_skip_startup",
                    id="map-skip-startup",
                    title="Leave out the samples before the solver's analysed window (settling)",
                )
        chart(
            "chart-raceway-map",
            "chart_raceway_map",
            charts.HELP["raceway_map"],
            overlay="chart_raceway_map_now",
        )
        html.Div("{{ raceway_metrics }}", id="raceway-metrics", classes="text-caption px-2 mb-2")

    def build_chart_panels(self) -> None:
        """The collapsible chart panels (values in ``open_panels``; drawn only while open)."""
        for title, key in CHART_PANELS:
            with v3.VExpansionPanel(title=title, value=key), v3.VExpansionPanelText():
                overlay = f"chart_{key}_now" if key in FOLLOWING_CHARTS else None
                chart(
                    f"chart-{key.replace('_', '-')}",
                    f"chart_{key}",
                    charts.HELP[key],
                    overlay=overlay,
                )


LAYER_LABELS = {
    "outer_ring": "outer ring (housing)",
    "inner_ring": "inner ring (shaft)",
    "balls": "balls",
    "cage": "cage",
    "tracks": "painted tracks",
    "edges": "shoulders",
    "ellipses": "ellipses",
    "traces": "traces",
    "labels": "labels",
}
CHART_PANELS = (
    ("Load versus azimuth", "load_azimuth"),
    ("Contact ellipses", "ellipse"),
    ("Cage speed", "cage_speed"),
    ("Quasi-static versus dynamic", "comparison"),
)
CAMERA_BUTTONS = ("isometric", "axial", "radial", "inner track", "outer track", "close-up")


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
        "background: rgba(255, 255, 255, 0.8); color: #000; border-radius: 4px; font-size: 12px; "
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


def _time_controls() -> None:
    """``#time-slider`` on a line of its own (it keeps the width of the view at any window size),
    then play/pause (``#play-button``), frame steps, the time and revolution counter
    (``#frame-time``), the slow-motion factor and the playback speed."""
    with v3.VRow(dense=True, align="center", classes="mt-1"):
        with v3.VCol(cols=12), html.Div(id="time-slider"):
            v3.VSlider(
                v_model=("frame",),
                min=0,
                max=("frame_max",),
                step=1,
                hide_details=True,
                density="compact",
            )
    with v3.VRow(dense=True, align="center", classes="flex-nowrap"):
        with v3.VCol(cols="auto", style="white-space: nowrap;"):
            v3.VBtn(
                icon=("playing ? 'mdi-pause' : 'mdi-play'",),
                id="play-button",
                click="playing = !playing",
                size="small",
            )
            icon_button(
                "mdi-step-backward", "frame = frame > 0 ? frame - 1 : frame_max", "step-back"
            )
            icon_button(
                "mdi-step-forward", "frame = frame < frame_max ? frame + 1 : 0", "step-forward"
            )
        with v3.VCol(style="min-width: 0;"):
            html.Span(
                "{{ frame_time }}",
                classes="text-caption rt-frame-time",
                style="font-family: monospace;",
                id="frame-time",
            )
            html.Div("{{ slow_motion }}", classes="text-caption", id="slow-motion")
        with v3.VCol(cols="auto", style="width: 110px;"):
            select("speed", "speed", "[1, 2, 5, 10, 20]", id="speed-select")


def _camera_and_scales(ctrl) -> None:
    """Camera presets (``#camera-<preset>``, on one line), then ``#exaggeration``,
    ``#ellipse-scale`` (each with its value in words) and the ball followed by the traces, the
    raceway map and the close-up."""
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=12, style="white-space: nowrap; overflow-x: auto;"):
            # plain buttons, not a toggle: pressing the current preset again restores it
            for preset in CAMERA_BUTTONS:
                v3.VBtn(
                    preset,
                    click=(ctrl.set_camera, f"['{preset}']"),
                    size="x-small",
                    variant=(f"camera === '{preset}' ? 'flat' : 'outlined'",),
                    classes="mr-1",
                    id=f"camera-{preset.replace(' ', '-')}",
                )
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=4):
            _slider(
                "exaggeration",
                30,
                "Draw the across-groove deviation of the tracks, traces and ellipse centres "
                "from the run's mean contact angle this many times larger (clipped at the "
                "shoulders)",
            )
            html.Span(
                "deviation × {{ exaggeration }}", classes="text-caption", id="exaggeration-label"
            )
        with v3.VCol(cols=4):
            _slider(
                "ellipse_scale",
                int(MAX_SHOWN_ELLIPSE_SCALE),
                "Draw the contact ellipses this many times their true size (the legend in the "
                "view names the scale)",
            )
            html.Span(
                "ellipses × {{ ellipse_scale }}", classes="text-caption", id="ellipse-scale-label"
            )
        with v3.VCol(cols=4):
            select("ball (traces, map, close-up)", "trace_ball", "ball_items")


def _slider(model: str, largest: int, title: str) -> None:
    """A whole-number slider from 1 to ``largest`` bound to ``model`` (id: ``model`` with
    dashes); its value is written beside it by the caller."""
    v3.VSlider(
        v_model=(model,),
        min=1,
        max=largest,
        step=1,
        thumb_label=True,
        hide_details=True,
        density="compact",
        title=title,
        id=model.replace("_", "-"),
    )


def _track_options() -> None:
    """What the painted tracks show (``#track-quantity``) and over which time
    (``#track-whole-run``)."""
    quantities = (
        ("dwell", "dwell (time under a ball)"),
        ("peak_pressure", "highest peak pressure"),
    )
    with v3.VRow(dense=True, align="center"):
        with v3.VCol(cols=4):
            select("tracks coloured by", "track_quantity", choices(quantities), id="track-quantity")
        with v3.VCol(cols="auto"):
            checkbox(
                "whole run",
                "track_whole_run",
                id="track-whole-run",
                title="Paint the tracks of the whole run, not only up to the current time",
            )
