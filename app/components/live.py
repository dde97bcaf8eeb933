"""Live mode: the case in the form runs continuously in a live solver process
(:mod:`app.live_runner`, a :class:`solver.LiveSimulation`) that takes a solver slot like any run;
the 3-D view, the painted tracks and the time charts follow the chunks it sends, and the live
controls (radial and axial load, shaft speed, tilt) change the running simulation, each change a
ramp of :data:`RAMP_REVOLUTIONS` shaft revolutions of bearing time.

State keys: ``live_on`` (a live session runs), ``live_paused``, ``live_status`` (what it does, in
words), ``live_behind`` (set while the solver cannot keep up with the playback: the playback is
slowed, and this says by how much), ``live_rate`` (the playback in words), ``live_band_inner``
(the inner track's band thickness in degree over the last
:data:`app.live_view.BAND_REVOLUTIONS` revolutions, None until known), ``live_frame`` (the frame
on show: ``{"serial", "time_s", "radial_load_N", "axial_load_N", "speed_rpm", "tilt_deg",
"band_inner_deg", "sent_at_s"}``: ``sent_at_s`` the server's wall clock when it was drawn, s
since the epoch; also written as ``data-*`` attributes of ``#live-data``), and the controls
``live_radial_load_N``, ``live_axial_load_N``, ``live_speed_rpm``, ``live_tilt_deg``.
"""

from __future__ import annotations

import asyncio
import math
import secrets
import tempfile
import time
from pathlib import Path

import numpy as np
from trame.widgets import client, html
from trame.widgets import vuetify3 as v3

from viz.frames import FrameSource

from .. import charts
from .. import live_runner as live_runner_module
from ..live_runner import LiveRunner
from ..live_view import WINDOW_REVOLUTIONS, LiveTracks, LiveWindow, band_thickness, shaft_period
from .base import Component, as_float, fig_json, log, running_loop

#: Playback while live: shaft revolutions of bearing time per wall second (the solver is asked
#: for this; it slows down when it cannot keep up).
REVOLUTIONS_PER_S = 2.0
#: A live control change is a ramp over this many shaft revolutions of bearing time (at the speed
#: then), so nothing jumps.
RAMP_REVOLUTIONS = 0.25
#: Frames drawn per wall second while live (each a render of the 3-D view).
LIVE_FPS = 12.0
#: The charts and the band thickness are brought up to date at most this often (s).
CHART_PERIOD_S = 1.0
#: ... and take at most this share of the page's wall time: after an update that took ``w``
#: seconds the next waits ``max(CHART_PERIOD_S, w / CHART_SHARE)``, so that on a loaded machine
#: the frames and the solver's chunks keep flowing between chart updates.
CHART_SHARE = 0.25
#: From a live control change until the first chunk that carries it is drawn, the charts are not
#: updated (an update takes a few tenths of a second of the page's loop on a loaded machine and
#: would hold back the frame that shows the change); at most this long (s), in case the chunk
#: never comes.
CHANGE_HOLDS_CHARTS_S = 2.0
#: ... and meanwhile the page's loop reads the solver's messages this often (s), so that the chunk
#: with the change is drawn as it arrives, not at the next of the :data:`LIVE_FPS` frames.
CHANGE_POLL_S = 0.02
RPM = 60.0 / (2.0 * math.pi)  # rev/min per rad/s

#: The live controls: state key -> (solver input, page unit per SI unit, lowest, highest, step).
CONTROLS = {
    "live_radial_load_N": ("radial_load", 1.0, 0.0, 3000.0, 50.0),
    "live_axial_load_N": ("axial_load", 1.0, 0.0, 3000.0, 50.0),
    "live_speed_rpm": ("inner_ring_speed", RPM, 0.0, 40000.0, 500.0),
    "live_tilt_deg": ("misalignment", math.degrees(1.0), -0.2, 0.2, 0.01),
}
CONTROL_IDS = {
    "live_radial_load_N": "live-radial-load",
    "live_axial_load_N": "live-axial-load",
    "live_speed_rpm": "live-speed",
    "live_tilt_deg": "live-tilt",
}
CONTROL_LABELS = {
    "live_radial_load_N": "radial load, N",
    "live_axial_load_N": "axial load, N",
    "live_speed_rpm": "shaft speed, rpm",
    "live_tilt_deg": "tilt, degree",
}


def slowdown_words(playback_rate: float, asked_rate: float) -> str:
    """What ``#live-behind`` says of a playback at ``playback_rate`` when ``asked_rate`` was
    asked (bearing s per wall s): how far it is slowed, in whole percent of the asked rate; empty
    when it is not below the asked rate by at least half a percent (nothing to say)."""
    if not (asked_rate > 0.0 and math.isfinite(playback_rate)):
        return ""
    percent = 100.0 * playback_rate / asked_rate
    if round(percent) >= 100:
        return ""
    return f"the solver cannot keep up: playback slowed to {percent:.0f} % of the asked rate"


def _played_from(chunk, change_from_s) -> float:
    """The bearing time [s] from which a chunk is played: its first sample, or, for a chunk that
    holds samples from before a change (``change_from_s``: where the change begins, s), the first
    sample after the change, so that the change is the first thing shown."""
    times = np.asarray(chunk["time"].values, float)
    if change_from_s is None:
        return float(times[0])
    return float(times[min(np.searchsorted(times, change_from_s, side="right"), times.size - 1)])


def _simulation() -> str:
    """The live simulation class the child runs (looked up at each start, so that tests can swap
    it)."""
    return live_runner_module.LIVE_SIMULATION


class Live(Component):
    """The live session of this page (at most one)."""

    def __init__(self, session):
        super().__init__(session)
        self.pool = session.services.pool
        self.runner = LiveRunner()
        self.ticket = None  # the solver slot held while live
        self.window = LiveWindow()
        self.tracks: LiveTracks | None = None
        self.source: FrameSource | None = None
        self.inputs: dict = {}  # the solver's inputs now (SI), as the last chunk said
        self.rate = 0.0  # bearing s per wall s of the chunk playing
        self._chunk_start = (0.0, 0.0)  # (bearing time the newest chunk plays from, its arrival)
        self._charts_due = 0.0  # monotonic time of the next chart update
        self._task = None
        self._record_out = None
        self._frames_drawn = 0  # frames drawn since the start (benchmarks read it)
        self._serial = 0
        self._case_text = None
        self._sets_sent = 0  # "set" controls sent to the child since the start
        self._sets_taken = 0  # ... and carried by the chunks taken (the chunks' info["sets"])
        self._set_sent_at = -math.inf  # monotonic time of the last one sent
        self._change_to_draw = False  # the newest chunk is the first to carry a change

    # ---- state ----------------------------------------------------------------------------------
    def init_state(self) -> None:
        s = self.state
        s.live_on = False
        s.live_paused = False
        s.live_status = ""
        s.live_behind = ""
        s.live_rate = ""
        s.live_band_inner = None
        s.live_frame = {}
        s.live_recorded = None  # the run id of the last recording
        s.live_radial_load_N = 0.0
        s.live_axial_load_N = 0.0
        s.live_speed_rpm = 0.0
        s.live_tilt_deg = 0.0

    def bind(self) -> None:
        self.action("live_start", self.start)
        self.action("live_stop", self.stop)
        self.action("live_pause", self.pause)
        self.action("live_resume", self.resume)
        self.action("live_reset", self.reset)
        self.action("live_record", self.record)
        for key in CONTROLS:
            self.on_change(key)(self._control_handler(key))

    # ---- the session ----------------------------------------------------------------------------
    def start(self) -> bool:
        """Start live mode on the case in the form, if a solver slot is free (else say why)."""
        s = self.state
        if self.ticket is not None:
            s.live_status = "live: already running (Stop ends it)"
            return False
        case = self.ctrl.edited_case() if self.ctrl.validate_case() is not None else None
        if case is None:
            s.live_status = "live: the case in the form is not valid; " + str(s.run_blocked or "")
            return False
        ticket = self.pool.enqueue()
        if not self.pool.try_acquire(ticket):
            self.pool.drop(ticket)
            cap = self.pool.max_runs
            s.live_status = (
                f"live: no solver slot is free (at most {cap} run{'s' * (cap != 1)} at once): "
                "wait for a run or live session to end, then press Live again"
            )
            return False
        self.ticket = ticket
        self._case_text = case.to_toml()
        period = 2.0 * math.pi / max(abs(case.operating.inner_ring_speed_rpm) / RPM, 1e-9)
        rate = REVOLUTIONS_PER_S * period if case.operating.inner_ring_speed_rpm else 0.01
        self.window.clear()
        self.tracks = None
        self.source = None
        self._frames_drawn = 0
        self._sets_sent = self._sets_taken = 0
        self._change_to_draw = False
        try:
            self.runner.start(self._case_text, rate, target=_simulation())
        except Exception:
            self._release()
            raise
        s.live_on = True
        s.live_paused = False
        s.live_behind = ""
        s.live_band_inner = None
        s.live_status = "live: starting the solver process"
        loop = running_loop()
        if loop is not None:  # without one, tests call tick() themselves
            self._task = loop.create_task(self._loop())
        return True

    def stop(self, reason: str = "live: stopped") -> None:
        """End the live session (its solver process and slot); the result shown before it is
        shown again. Nothing of an unrecorded session is kept."""
        if self.ticket is None and not self.state.live_on:
            return
        self.runner.stop()
        self._release()
        if self._task is not None and self._task is not asyncio.current_task():
            self._task.cancel()
        self._task = None
        s = self.state
        s.live_on = False
        s.live_paused = False
        s.live_behind = ""
        s.live_status = reason
        self.ctrl.end_live()

    def _release(self) -> None:
        self.pool.drop(self.ticket)
        self.ticket = None

    def pause(self) -> None:
        if self.state.live_on:
            self.runner.send("pause")
            self.state.live_paused = True
            self.state.live_status = "live: paused"

    def resume(self) -> None:
        if self.state.live_on:
            self.runner.send("resume")
            self.state.live_paused = False
            self.state.live_status = "live: running"

    def reset(self) -> None:
        """Back to the quasi-static state: the solver starts again, the window and the tracks are
        emptied."""
        if self.state.live_on:
            self.runner.send("reset")
            self.state.live_status = "live: resetting to the quasi-static state"

    def record(self) -> None:
        """Save the session so far as a run (its case with the time histories of what the user
        did); it then appears in the runs list."""
        if not self.state.live_on:
            return
        store = self.session.store
        folder = Path(tempfile.gettempdir()) if store.folder_problem() else store.root
        self._record_out = folder / f".job-{secrets.token_hex(4)}.nc"
        self.runner.send("record", str(self._record_out))
        self.state.live_status = "live: recording the session as a run"

    def _control_handler(self, key: str):
        channel, per_si, lo, hi, _ = CONTROLS[key]

        def on_control(**changes):
            if not self.state.live_on:
                return
            value = as_float(changes.get(key), math.nan, lo, hi)
            if not math.isfinite(value):
                self.state.live_status = f"live: {CONTROL_LABELS[key]} must be a number"
                return
            now = float(self.inputs.get(channel, math.nan)) * per_si
            if math.isclose(value, now, rel_tol=1e-6, abs_tol=1e-9):
                return  # the control shows the input the solver has (set from it)
            ramp = RAMP_REVOLUTIONS * shaft_period(self.inputs)
            ramp = ramp if math.isfinite(ramp) else RAMP_REVOLUTIONS * 0.01
            self.runner.send("set", channel, value / per_si, ramp)
            self._sets_sent += 1
            self._set_sent_at = time.monotonic()
            if channel == "inner_ring_speed" and value > 0:  # the same revolutions per second
                self.runner.send("rate", REVOLUTIONS_PER_S * 2.0 * math.pi * RPM / value)

        return on_control

    # ---- the loop -------------------------------------------------------------------------------
    async def _loop(self) -> None:
        period = 1.0 / LIVE_FPS
        next_frame = time.monotonic()
        while self.state.live_on:
            t0 = time.monotonic()
            due = t0 >= next_frame
            try:
                with self.state:
                    if self.tick(frame_due=due) or due:  # drawn, or nothing to draw yet
                        next_frame = t0 + period
            except Exception as error:  # a failing frame must not end the session's loop
                log.exception("live frame failed")
                next_frame = t0 + period
                with self.state:
                    self.state.live_status = f"live: error: {type(error).__name__}: {error}"[:300]
            wait = next_frame - time.monotonic()
            if self._change_awaited(time.monotonic()):
                wait = min(wait, CHANGE_POLL_S)
            await asyncio.sleep(max(0.005, wait))

    def tick(self, frame_due: bool = True) -> bool:
        """Apply the solver's messages and draw the frame due now (one animation tick); with
        ``frame_due`` false only a chunk that is the first to carry a change is drawn. Whether a
        frame was drawn."""
        for message in self.runner.poll():
            self._handle(message)
            if not self.state.live_on:
                return False
        if self.source is None or self.state.live_paused:
            return False
        if frame_due or self._change_to_draw:
            self._draw(time.monotonic())
            return True
        return False

    def _handle(self, message) -> None:
        kind, s = message[0], self.state
        if kind == "preparing":
            s.live_status = "live: " + message[1]
        elif kind == "ready":
            self._take_inputs(message[2])
            self.window.clear()
            if self.tracks is not None:
                self.tracks.reset()
            self.source = None
            s.live_band_inner = None
            s.live_status = "live: running"
        elif kind == "chunk":
            self._take_chunk(message[1], message[2])
        elif kind == "recorded":
            self._save_recording(message[1], message[2])
        elif kind == "refused":
            s.live_status = f"live: {message[1]}"
        elif kind == "error":
            self.stop(f"live: error: {message[1]}")
        elif kind == "stopped" and s.live_on:
            self.stop("live: the solver stopped")

    def _take_inputs(self, inputs: dict) -> None:
        """The solver's inputs now (SI): the live controls show them."""
        self.inputs = dict(inputs)
        for key, (channel, per_si, *_) in CONTROLS.items():
            if channel in self.inputs:
                self.state[key] = round(float(self.inputs[channel]) * per_si, 6)

    def _take_chunk(self, chunk, info: dict) -> None:
        s = self.state
        self.inputs = dict(info.get("inputs", {}))
        self.rate = float(info["rate"])
        sets = int(info.get("sets", 0))
        if sets > self._sets_taken:
            self._sets_taken = sets
            self._change_to_draw = True
        if self.tracks is None:
            self._start_view(chunk)
        new = self.window.add(chunk, self.inputs)
        if new.n_frames >= 2:
            self.tracks.add(new)
        self.source = self.window.source
        self._chunk_start = (_played_from(chunk, info["change_from_s"]), time.monotonic())
        s.live_behind = slowdown_words(float(info["playback_rate"]), float(info["asked_rate"]))
        period = shaft_period(self.inputs)
        if math.isfinite(period):
            s.live_rate = (
                f"playing {self.rate / period:.2g} shaft revolutions per second "
                f"(1 s on screen = {self.rate * 1e3:.3g} ms of bearing time); charts: the last "
                f"{WINDOW_REVOLUTIONS:g} revolutions"
            )
        else:
            s.live_rate = (
                f"1 s on screen = {self.rate * 1e3:.3g} ms of bearing time (rings at rest)"
            )

    def _start_view(self, chunk) -> None:
        """The scene and the session's painted tracks, from the first chunk. The tracks' across-
        groove exaggeration acts about the mean contact angles of the result on show before
        (the scene's), or of the first chunk without a scene."""
        scene = self.ctrl.live_scene(chunk)
        if scene is None:  # no rendering (state tests): a layout of the scene's own making
            from solver import geometry_from_result
            from viz.layout import RacewayLayout
            from viz.options import SceneOptions

            layout = RacewayLayout(geometry_from_result(chunk), SceneOptions())
            source = FrameSource.from_dynamic(chunk)
            layout.reference = [source.reference_contact_angle(r) for r in (0, 1)]
            exaggeration = as_float(self.state.exaggeration, 1.0, 1.0)
        else:
            layout, exaggeration = scene.layout, scene.options.exaggeration
        self.tracks = LiveTracks(layout.grooves, layout.grids, layout.reference, exaggeration)

    def _change_awaited(self, now: float) -> bool:
        """A change was sent and no chunk taken carries it yet (for at most
        :data:`CHANGE_HOLDS_CHARTS_S`)."""
        waiting = self._sets_taken < self._sets_sent
        return waiting and now - self._set_sent_at < CHANGE_HOLDS_CHARTS_S

    def _charts_held(self, now: float) -> bool:
        """Whether the charts wait: a change is awaited (:meth:`_change_awaited`), or this frame
        is the first to show it (the charts follow at the next tick, after the frame has gone to
        the page)."""
        return self._change_to_draw or self._change_awaited(now)

    def _draw(self, now: float) -> None:
        """Draw the frame of the bearing time due at ``now``: the newest chunk plays over the wall
        time it took to make, from its arrival on. The charts are brought up to date when due
        unless a change is on its way to the picture (:meth:`_charts_held`)."""
        src = self.source
        t0, arrived = self._chunk_start
        due = t0 + self.rate * (now - arrived)
        index = int(min(np.searchsorted(src.times, due), src.n_frames - 1))
        inputs = {name: float(v[index]) for name, v in self.window.inputs.items()}
        speed = inputs["inner_ring_speed"] * RPM
        frame = {
            "serial": self._serial,
            "time_s": float(src.times[index]),
            "radial_load_N": inputs["radial_load"],
            "axial_load_N": inputs["axial_load"],
            "speed_rpm": speed,
            "tilt_deg": math.degrees(inputs["misalignment"]),
            "band_inner_deg": self.state.live_band_inner,
            "sent_at_s": time.time(),  # wall clock (s since the epoch): the page's latency
        }
        words = (
            f"live · t = {frame['time_s'] * 1e3:8.3f} ms · Fr {frame['radial_load_N']:.0f} N · "
            f"Fa {frame['axial_load_N']:.0f} N · {speed:.0f} rpm"
        )
        self.ctrl.show_live_frame(src, index, self.tracks, words, urgent=self._change_to_draw)
        if now >= self._charts_due and not self._charts_held(now):
            self._update_charts(index)
            frame["band_inner_deg"] = self.state.live_band_inner
            took = time.monotonic() - now
            self._charts_due = time.monotonic() + max(CHART_PERIOD_S, took / CHART_SHARE)
        self._change_to_draw = False
        self._serial += 1
        self._frames_drawn += 1
        self.state.live_frame = {
            k: (None if isinstance(v, float) and not math.isfinite(v) else v)
            for k, v in frame.items()
        }

    def _update_charts(self, index: int) -> None:
        """The contact-angle chart, the band thickness, and the words of the 3-D view's labels
        and the raceway map's caption: the live inputs (of the newest chunk)."""
        s = self.state
        self.ctrl.show_live_inputs(self.window.chunks[-1])
        # the window slides with each chunk: the figure is sent again, and the time marker with it
        s.chart_contact_angle = fig_json(charts.contact_angle_figure(self.source, None))
        s.chart_contact_angle_now = charts.time_marker_overlay(self.source, index)
        band = band_thickness(self.window, self.inputs, "inner")
        s.live_band_inner = round(band, 5) if math.isfinite(band) else None

    def _save_recording(self, path: str, case_text: str) -> None:
        from solver import parse_case

        from ..run_store import describe_case, load_netcdf

        out = Path(path)
        try:
            ds = load_netcdf(out)
            title = f"live session: {describe_case(parse_case(case_text, 'the recorded case'))}"
            info = self.session.store.save(ds, case_text, title)
        except Exception as error:
            self.state.live_status = f"live: error: the session could not be saved ({error})"
            return
        finally:
            out.unlink(missing_ok=True)
        self.ctrl.refresh_runs()
        where = "" if info.saved else f" (kept in memory: {info.problem})"
        self.state.live_status = f"live: recorded as run {info.run_id}{where}"
        self.state.live_recorded = info.run_id

    def client_count(self, clients: int) -> None:
        """The page's browsers changed: the last one gone ends the live session."""
        if clients == 0 and self.state.live_on:
            self.stop("live: stopped (the page was closed)")

    def shutdown(self) -> None:
        self.stop("live: stopped with the server")

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """The live card: Live/Stop, pause/resume, reset, record, the status and the controls."""
        ctrl = self.ctrl
        with v3.VCard(variant="outlined", classes="mb-2 pa-2", id="live-card"):
            with v3.VRow(dense=True, align="center"):
                with v3.VCol(cols="auto", style="white-space: nowrap;"):
                    v3.VBtn(
                        "Live",
                        id="live-button",
                        click=ctrl.live_start,
                        v_if="!live_on",
                        color="secondary",
                        prepend_icon="mdi-motion-play",
                        size="small",
                        title="Run the case continuously; the controls below change it as it runs",
                    )
                    v3.VBtn(
                        "Stop",
                        id="live-stop",
                        click=ctrl.live_stop,
                        v_if="live_on",
                        size="small",
                        prepend_icon="mdi-stop",
                    )
                    v3.VBtn(
                        icon=("live_paused ? 'mdi-play' : 'mdi-pause'",),
                        id="live-pause",
                        click="live_paused ? trigger('live_resume') : trigger('live_pause')",
                        disabled=("!live_on",),
                        size="small",
                        variant="text",
                    )
                    v3.VBtn(
                        "reset",
                        id="live-reset",
                        click=ctrl.live_reset,
                        disabled=("!live_on",),
                        size="small",
                        variant="text",
                        title="Back to the quasi-static state",
                    )
                    v3.VBtn(
                        "record",
                        id="live-record",
                        click=ctrl.live_record,
                        disabled=("!live_on",),
                        size="small",
                        variant="text",
                        prepend_icon="mdi-record-circle",
                        title="Save the session so far as a run (with the histories of your "
                        "changes)",
                    )
                with v3.VCol():
                    html.Div("{{ live_status }}", id="live-status", classes="text-body-2")
            html.Div("{{ live_behind }}", id="live-behind", v_show="live_behind",
                     classes="text-caption text-warning")  # fmt: skip
            html.Div("{{ live_rate }}", id="live-rate", v_show="live_on", classes="text-caption")
            html.Div(
                "inner track band {{ live_band_inner === null ? '…' : "
                "live_band_inner.toFixed(4) + '°' }}",
                id="live-data",
                v_show="live_on",
                classes="text-caption",
                # html elements keep only the attributes they know: data-* go in as written
                raw_attrs=[
                    ':data-band-inner="live_band_inner"',
                    ':data-radial-load="live_frame.radial_load_N"',
                    ':data-frame-serial="live_frame.serial"',
                ],
            )
            for key in CONTROLS:  # the 3-D view waits for the change's frame (browser_view)
                client.ClientStateChange(
                    value=key, change="utils.rt3d && utils.rt3d.expectChange()"
                )
            with v3.VRow(dense=True):
                for key, (_, _, lo, hi, step) in CONTROLS.items():
                    with v3.VCol(cols=6):
                        v3.VSlider(
                            v_model=(key,),
                            min=lo,
                            max=hi,
                            step=step,
                            label=CONTROL_LABELS[key],
                            thumb_label=True,
                            hide_details=True,
                            density="compact",
                            disabled=("!live_on",),
                            id=CONTROL_IDS[key],
                        )
