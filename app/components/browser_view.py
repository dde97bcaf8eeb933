"""The 3-D view drawn by the browser (vtk.js through trame-vtk's declarative components).

The server keeps its pyvista scene (:class:`viz.scene.BearingScene`: the exports render it off
screen, and it holds the layers, the camera presets and the painted-track fields); the browser
gets the scene's meshes once per result (:class:`viz.browser_scene.BrowserScene`) and, for a
played frame, only the moving parts' matrices, the contact ellipses of the frame and how many
quads of each painted track are shown. The painted tracks' quads come once per result and
painting options, in the order the run paints them, with their colours over the whole run (drawn
while playing); a frame chosen by hand gets the colours painted up to it. The camera lives in the
browser (a preset is sent once when chosen). The words of the server view's 2-D overlay (labels,
legend, colour bar) are shown over the canvas as HTML.

Which view a page shows: ``render_mode`` (``racetrace serve --render browser|server``) and
``browser_webgl`` (set by the page itself: whether the browser can draw WebGL); the browser view
when both allow it, else the server-rendered view.

State keys: ``render_mode``, ``browser_webgl`` (None until the page says), ``view_in_browser``,
``rt3d_meshes`` (mesh key -> typed arrays), ``rt3d_parts`` (the parts: mesh key, group,
colours, surface properties), ``rt3d_frame`` (index, matrices ``m``, ellipse points ``e``,
painted quads shown ``n``, ``run``: whether the tracks take their whole-run colours),
``rt3d_track_cells`` (the painted tracks' quads in painting order), ``rt3d_track_run`` and
``rt3d_tracks`` (the painted tracks' colours, colour-bar title, range and labels: over the whole
run, and up to frame ``stop``), ``rt3d_overlay`` (the 2-D overlay's labels, legend and colour
map), ``rt3d_visible`` (part name -> shown), ``rt3d_camera`` (a camera preset to apply:
vtk.js camera settings and a ``serial``) and ``rt3d_urgent`` (``app.front_keys.URGENT_KEY``:
a count of the frames to be drawn at once, not after the view's idle wait: a live control
change's first frame; a count, not a flag on the frame, so that it survives the front's merging of
state messages; a message that carries it goes past the front's window,
:mod:`app.serve.coalesce`).
"""

from __future__ import annotations

import hashlib
import time

from trame.widgets import client, html
from trame.widgets import vtk as vtk_widgets

from viz.browser_scene import BrowserScene, camera_state

from ..front_keys import URGENT_KEY
from .widgets import own_update

RENDER_MODES = ("browser", "server")
TRACK_REFRESH_S = 1.0  # a live session's painted tracks are re-sent at most this often
VIEW_REF = "rt3d_view"
IDENTITY = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]

# Run by the page: ``utils.rt3d.head`` for the view's bindings (the first values of a typed array,
# decoded once), ``utils.rt3d.drawOnAnimationFrame`` (the view's drawing) and
# ``utils.rt3d.plainTranslucency`` (its translucent parts blended in drawing order), then whether
# this browser can draw WebGL, told to the server once trame is up.
DETECT_WEBGL = """
(function racetraceWebgl(tries) {
  if (!(window.trame && window.trame.state)) {
    if (tries < 200) setTimeout(function () { racetraceWebgl(tries + 1); }, 50);
    return;
  }
  var kinds = { int32: Int32Array, uint8: Uint8Array, float32: Float32Array };
  var decoded = new WeakMap();
  window.trame.utils.rt3d = {
    head: function (array, count) {
      if (!array || !array.bvals) return null;
      var seen = decoded.get(array);
      if (!seen) {
        var text = atob(array.bvals);
        var bytes = new Uint8Array(text.length);
        for (var i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
        seen = { whole: new kinds[array.dtype](bytes.buffer), count: -1, head: null };
        decoded.set(array, seen);
      }
      var n = Math.max(0, Math.min(count | 0, seen.whole.length));
      if (n !== seen.count) {
        seen.count = n;
        seen.head = seen.whole.subarray(0, n);
      }
      return seen.head;
    },
    // the vtk.js view of the trame view component named viewRef (undefined until mounted)
    vtkView: function (viewRef) {
      var component = window.trame.refs[viewRef];
      return component && component.$ && component.$.provides && component.$.provides.view;
    },
    // trame-vtk's view draws on a 1 ms timer that every change restarts, so a page still taking
    // state messages keeps putting the drawing off (about one drawing a second while playing
    // in software WebGL); the view named viewRef draws at the second animation frame after a
    // change instead, at most once per frame: a played frame's changes reach vtk.js in the
    // task that applies it and in the frame after it (drawn at the first animation frame, a
    // frame was drawn twice, its second drawing asked for as the first ended: 1.6 drawings of
    // 250-400 ms per played frame in software WebGL, 1.0 at the second animation frame).
    // app.serve.coalesce.READ_SCRIPT counts a message as taken after that second animation
    // frame. A drawing holds the page until the frame is on screen (in software WebGL the page
    // then reads the picture back: a few tenths of a second on a loaded machine), so while live
    // (live_on) after one the view waits IDLE_SHARE times as long (at most MOST_IDLE_MS) before
    // it draws again: meanwhile the page takes its messages, and a frame that must be seen at
    // once (drawNow) is drawn at the next animation frame. After a live control moved on this
    // page (expectChange) the view begins no other drawing until the frame showing the change
    // comes (drawNow), for at most HOLD_FOR_CHANGE_MS: a drawing begun meanwhile holds the page
    // (0.1-0.2 s in software WebGL, measured), and the change's frame would wait for it. `shown`
    // says when the last drawing began and when it was on screen (performance.now() ms). Called
    // when the view is created (it may not be mounted yet: retried).
    drawOnAnimationFrame: function (viewRef, tries) {
      var view = window.trame.utils.rt3d.vtkView(viewRef);
      if (!(view && view.renderWindow && view.render)) {
        if ((tries | 0) < 100) {
          setTimeout(function () {
            window.trame.utils.rt3d.drawOnAnimationFrame(viewRef, (tries | 0) + 1);
          }, 100);
        }
        return;
      }
      if (view.render.onAnimationFrame) return;
      if (view.render.cancel) view.render.cancel();
      var rt3d = window.trame.utils.rt3d;
      var pending = 0, timer = 0, nextAt = 0;
      function draw() {
        pending = 0;
        if (!view.renderWindow) return;  // the view was removed
        var start = performance.now();
        if (start < rt3d.heldUntil && window.trame.state.get('live_on')) {
          // asked for before the control moved: drawn once the hold ends (or by drawNow)
          timer = setTimeout(atSecondFrame, rt3d.heldUntil - start);
          return;
        }
        view.renderer.resetCameraClippingRange();
        view.renderWindow.render();
        setTimeout(function () {  // a task after the frame: the picture is on screen
          var end = performance.now();
          nextAt = end + Math.min(rt3d.IDLE_SHARE * (end - start), rt3d.MOST_IDLE_MS);
          rt3d.shown = { start: start, end: end };
        }, 0);
      }
      function next() { pending = requestAnimationFrame(draw); }
      function atSecondFrame() {
        if (timer) clearTimeout(timer);
        timer = 0;
        if (!pending) pending = requestAnimationFrame(next);
      }
      var render = function () {
        if (pending || timer) return;
        var wait = window.trame.state.get('live_on') ? nextAt - performance.now() : 0;
        if (wait > 0) timer = setTimeout(atSecondFrame, wait);
        else atSecondFrame();
      };
      render.now = function () {  // at the next animation frame
        rt3d.heldUntil = 0;
        if (timer) clearTimeout(timer);
        if (pending) cancelAnimationFrame(pending);
        timer = 0;
        pending = requestAnimationFrame(draw);
      };
      render.cancel = function () {
        if (pending) cancelAnimationFrame(pending);
        if (timer) clearTimeout(timer);
        pending = timer = 0;
      };
      render.onAnimationFrame = true;
      view.render = render;
    },
    IDLE_SHARE: 1.0,
    HOLD_FOR_CHANGE_MS: 500,  // the target of a live change's latency (issue 24)
    heldUntil: 0,
    // a live control moved on this page: its frame is on its way (drawn by drawNow); until then
    // the view draws nothing else, at most HOLD_FOR_CHANGE_MS (see drawOnAnimationFrame)
    expectChange: function () {
      var rt3d = window.trame.utils.rt3d;
      if (window.trame.state.get('live_on')) {
        rt3d.heldUntil = performance.now() + rt3d.HOLD_FOR_CHANGE_MS;
      }
    },
    MOST_IDLE_MS: 500,  // the drawing's time counts the tasks queued before the page saw it end
    shown: null,
    // the view named viewRef draws at the next animation frame, not after its idle wait
    drawNow: function (viewRef) {
      var view = window.trame.utils.rt3d.vtkView(viewRef);
      if (view && view.render && view.render.now) view.render.now();
    },
    // The view named viewRef draws its translucent parts (the balls, the cage) blended over the
    // opaque ones in drawing order, as the server's VTK scene and the exports do, not with
    // vtk.js's order-independent translucency: that pass draws every opaque part a second time
    // (for depth) and the translucent ones into two half-float pictures which it then
    // composites, about half of a drawing in software WebGL (219 -> 117 ms of SwiftShader's CPU
    // at 1280 x 800, load 11). vtk.js takes that pass only where its WebGL 2 context has a
    // float colour buffer extension, so the view's own context (no other) says it has none.
    // Called when the view is created (it may not be mounted, nor its context made: retried).
    plainTranslucency: function (viewRef, tries) {
      var view = window.trame.utils.rt3d.vtkView(viewRef);
      var glWindow = view && view.renderWindow && view.renderWindow.getViews()[0];
      var gl = glWindow && glWindow.getContext && glWindow.getContext();
      if (!gl) {
        if ((tries | 0) < 100) {
          setTimeout(function () {
            window.trame.utils.rt3d.plainTranslucency(viewRef, (tries | 0) + 1);
          }, 100);
        }
        return;
      }
      if (gl.racetracePlainTranslucency) return;
      var getExtension = gl.getExtension.bind(gl);
      var hidden = window.trame.utils.rt3d.OIT_EXTENSIONS;
      gl.getExtension = function (name) {
        return hidden.indexOf(name) >= 0 ? null : getExtension(name);
      };
      gl.racetracePlainTranslucency = true;
    },
    OIT_EXTENSIONS: ['EXT_color_buffer_float', 'EXT_color_buffer_half_float'],
  };
  // In software WebGL (no GPU: SwiftShader) the view is drawn without multisampling, which
  // cut a drawing of the default scene from 0.37-0.46 s to 0.20-0.35 s at load 8 (one run);
  // a context whose caller asks for antialias keeps it.
  var software = false;
  var ok = false;
  try {
    var canvas = document.createElement('canvas');
    var gl = canvas.getContext('webgl2') || canvas.getContext('webgl');
    ok = !!gl;
    var info = gl && gl.getExtension('WEBGL_debug_renderer_info');
    software = !!info && /swiftshader/i.test(String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)));
  } catch (e) { ok = false; }
  if (software) {
    var getContext = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (kind, attributes) {
      if ((kind === 'webgl2' || kind === 'webgl') && !(attributes && 'antialias' in attributes)) {
        attributes = Object.assign({}, attributes, { antialias: false });
      }
      return getContext.call(this, kind, attributes);
    };
  }
  window.trame.utils.rt3d.software = software;
  window.trame.state.set('browser_webgl', ok);
})(0);
"""


def mesh_key(mesh: dict) -> str:
    """A key that names a mesh by its content (the balls share one sphere)."""
    digest = hashlib.blake2b(digest_size=8)
    for name in sorted(mesh):
        digest.update(name.encode())
        digest.update(mesh[name]["bvals"].encode())
    return digest.hexdigest()


class BrowserView:
    """The browser-drawn view of ``result`` (:class:`app.components.result_view.ResultView`)."""

    def __init__(self, result, render_mode: str = "browser"):
        if render_mode not in RENDER_MODES:
            raise ValueError(
                f"unknown render mode {render_mode!r}; use one of {', '.join(RENDER_MODES)}"
            )
        self.result = result
        self.render_mode = render_mode
        self.scene: BrowserScene | None = None
        self._actors = {}  # part name -> the server scene's actor (whose visibility it follows)
        self._tracks_sent = (-1, None, 0.0)  # (stop, quantity, monotonic time)
        self._cells_painter = None  # the painter whose quad order the page has
        self._run_sent = None  # (painter, quantity) of the whole-run colours on the page
        self.view = None

    @property
    def state(self):
        return self.result.state

    def init_state(self) -> None:
        s = self.state
        s.render_mode = self.render_mode
        s.browser_webgl = None
        s.view_in_browser = False
        s.rt3d_meshes = {}
        s.rt3d_parts = []
        s.rt3d_frame = {"index": 0, "n": [0, 0], "run": False, "m": {}, "e": [None, None]}
        s.rt3d_track_cells = {"polys": [None, None]}
        empty = {"stop": 0, "range": [0.0, 1.0], "title": "", "ticks": [], "c": [None, None]}
        s.rt3d_track_run = dict(empty)
        s.rt3d_tracks = dict(empty)
        s.rt3d_overlay = {"labels": [], "legend": [], "gradient": ""}
        s.rt3d_visible = {}
        s.rt3d_camera = {"serial": 0}
        s[URGENT_KEY] = 0

    @property
    def active(self) -> bool:
        """Whether the page shows the browser-drawn view."""
        return bool(self.state.view_in_browser)

    def choose(self, browser_webgl=None) -> bool:
        """Pick the view from ``render_mode`` and what the page said about WebGL; returns whether
        the browser view is on."""
        on = self.render_mode == "browser" and browser_webgl is True
        self.state.view_in_browser = on
        return on

    # ---- what is sent ---------------------------------------------------------------------------
    def show_scene(self, scene) -> None:
        """Send the meshes of ``scene`` (a :class:`viz.scene.BearingScene` with its source)."""
        self.scene = BrowserScene(scene)
        meshes, parts = {}, []
        actors = {}
        for part in self.scene.parts():
            key = mesh_key(part["mesh"])
            meshes.setdefault(key, part.pop("mesh"))
            part.pop("mesh", None)
            parts.append({**part, "mesh": key})
        layers = {name: list(scene.actors[name]) for name in scene.actors}
        for part in parts:
            name, layer = part["name"], part["layer"]
            if part["kind"] == "tracks":
                actors[name] = scene.tracks.actors[part["race"]]
            else:
                actors[name] = layers[layer][int(name.rsplit("_", 1)[1])]
        self._actors = actors
        self._tracks_sent = (-1, None, 0.0)
        self._cells_painter = self._run_sent = None
        s = self.state
        s.rt3d_meshes = meshes
        s.rt3d_parts = parts
        s.rt3d_overlay = self.scene.overlay_state()

    def refresh(self, index: int) -> None:
        """Everything but the meshes: visibility, frame ``index``, the painted tracks."""
        if self.scene is None:
            return
        self.state.rt3d_visible = {
            name: bool(actor.GetVisibility()) for name, actor in self._actors.items()
        }
        self.state.rt3d_overlay = self.scene.overlay_state()
        self.show_frame(index, tracks_now=True)

    def _send_track_cells(self, whole_run: bool) -> bool:
        """Send the painted tracks' quads when the painter changed (a new source or painting
        option) and, with ``whole_run``, their whole-run colours when the colouring changed;
        returns whether the painter can paint."""
        painter = self.scene.scene.tracks.painter
        if painter is None:
            return False
        if painter is not self._cells_painter:
            self.state.rt3d_track_cells = self.scene.track_cells()
            self._cells_painter, self._run_sent = painter, None
            self._tracks_sent = (-1, None, 0.0)
        quantity = self.scene.scene.options.track_quantity
        if whole_run and self._run_sent != (painter, quantity):
            n = self.scene.scene.source.n_frames
            self.state.rt3d_track_run = self.scene.track_state(n, quantity)
            self._run_sent = (painter, quantity)
        return True

    def show_frame(self, index: int, tracks_now: bool = False) -> None:
        """Send frame ``index``: the matrices, the ellipses and how many painted quads are shown.
        While playing the tracks take their whole-run colours (sent once); a frame chosen by hand
        (or ``tracks_now``) gets the colours painted up to it."""
        if self.scene is None:
            return
        options = self.scene.scene.options
        if not self._send_track_cells(whole_run=True):
            self.state.rt3d_frame = self.scene.frame_state(index, options.ellipse_scale, 0)
            return
        n = self.scene.scene.source.n_frames
        stop = n if options.track_whole_run else index + 1
        playing = bool(self.state.playing) and not tracks_now
        frame = self.scene.frame_state(index, options.ellipse_scale, stop)
        frame["run"] = playing
        if not playing:
            sent_stop, sent_quantity, _ = self._tracks_sent
            if (stop, options.track_quantity) != (sent_stop, sent_quantity) or tracks_now:
                self.state.rt3d_tracks = self.scene.track_state(stop, options.track_quantity)
                self._tracks_sent = (stop, options.track_quantity, time.monotonic())
        self.state.rt3d_frame = frame

    def show_live_frame(self, index: int, urgent: bool = False) -> None:
        """Send frame ``index`` of a live session's window: the matrices and ellipses, and the
        session's accumulated tracks (:class:`app.live_view.LiveTracks`, every quad shown) at
        most every :data:`TRACK_REFRESH_S` (the window slides, so frame numbers do not say what
        is new); ``urgent``: the page draws it at once (``rt3d_urgent``)."""
        if self.scene is None:
            return
        options = self.scene.scene.options
        self._send_track_cells(whole_run=False)
        frame = self.scene.frame_state(index, options.ellipse_scale)
        frame["run"] = False
        _, sent_quantity, sent_at = self._tracks_sent
        if sent_quantity != options.track_quantity or time.monotonic() - sent_at >= TRACK_REFRESH_S:
            self.state.rt3d_tracks = self.scene.track_state(0, options.track_quantity)
            self._tracks_sent = (-1, options.track_quantity, time.monotonic())
        self.state.rt3d_frame = frame
        if urgent:
            self.state[URGENT_KEY] = int(self.state[URGENT_KEY]) + 1

    def set_camera(self, plotter) -> None:
        """Send the server scene's camera (a preset just applied) to the browser, which applies
        it once (then the camera is the browser's own: orbiting costs the server nothing)."""
        camera = camera_state(plotter)
        camera["centerOfRotation"] = camera["focalPoint"]
        camera["serial"] = int(self.state.rt3d_camera.get("serial", 0)) + 1
        self.state.rt3d_camera = camera

    # ---- page -----------------------------------------------------------------------------------
    def build(self) -> None:
        """``#view-3d-browser``: the vtk.js view (one representation per part) and the 2-D
        overlay over it."""
        with html.Div(id="view-3d-browser", style="width: 100%; height: 100%; position: relative;"):
            with vtk_widgets.VtkView(ref=VIEW_REF, background=([1, 1, 1],)) as view:
                self.view = view
                with vtk_widgets.VtkGeometryRepresentation(
                    v_for="part in rt3d_parts",
                    key="part.name",
                    actor=(
                        "{ userMatrix: (part.group && rt3d_frame.m[part.group]) || "
                        f"{IDENTITY}, visibility: rt3d_visible[part.name] !== false }}",
                    ),
                    property=("part.property",),
                    # colorMode 2: the uint8 colours are drawn as they are (no colour map)
                    mapper=(
                        "{ scalarVisibility: !!part.colours || part.kind === 'tracks', "
                        "colorMode: 2 }",
                    ),
                ):
                    with vtk_widgets.VtkPolyData(
                        "rt3d_polydata",
                        connectivity="manual",
                        points=(
                            "part.kind === 'ellipses' && rt3d_frame.e[part.race] ? "
                            "rt3d_frame.e[part.race] : rt3d_meshes[part.mesh].points",
                        ),
                        # a painted track: the first n quads in painting order (n: the frame's)
                        polys=(
                            "part.kind === 'tracks' ? utils.rt3d.head("
                            "rt3d_track_cells.polys[part.race], 5 * rt3d_frame.n[part.race]) : "
                            "rt3d_meshes[part.mesh].polys",
                        ),
                        lines=("rt3d_meshes[part.mesh].lines",),
                    ):
                        with vtk_widgets.VtkCellData():
                            vtk_widgets.VtkDataArray(
                                v_if="part.kind === 'tracks' && "
                                "(rt3d_frame.run ? rt3d_track_run : rt3d_tracks).c[part.race]",
                                registration="setScalars",
                                name="rgba",
                                type="Uint8Array",
                                number_of_components=("4",),  # a number, not the text "4"
                                values=(
                                    "utils.rt3d.head((rt3d_frame.run ? rt3d_track_run : "
                                    "rt3d_tracks).c[part.race], 4 * rt3d_frame.n[part.race])",
                                ),
                            )
                            vtk_widgets.VtkDataArray(
                                v_if="part.colours && part.colours.location === 'cell'",
                                registration="setScalars",
                                name="rgba",
                                type="Uint8Array",
                                number_of_components=("part.colours.components",),
                                values=("part.colours.values",),
                            )
                        with vtk_widgets.VtkPointData():
                            vtk_widgets.VtkDataArray(
                                v_if="part.colours && part.colours.location === 'point'",
                                registration="setScalars",
                                name="rgba",
                                type="Uint8Array",
                                number_of_components=("part.colours.components",),
                                values=("part.colours.values",),
                            )
            with own_update():  # the colour bar follows rt3d_frame, which changes every frame
                _overlay()
            # the view draws at most once per animation frame (see DETECT_WEBGL)
            client.ClientStateChange(
                value="rt3d_parts",
                trigger_on_create=True,
                change=f"utils.rt3d.drawOnAnimationFrame('{VIEW_REF}')",
            )
            # translucent parts blended in drawing order, as on the server (DETECT_WEBGL)
            client.ClientStateChange(
                value="rt3d_parts",
                trigger_on_create=True,
                change=f"utils.rt3d.plainTranslucency('{VIEW_REF}')",
            )
            # a frame to be seen at once is drawn at the next animation frame (DETECT_WEBGL)
            client.ClientStateChange(value=URGENT_KEY, change=f"utils.rt3d.drawNow('{VIEW_REF}')")
            # a camera preset chosen on the server is applied once the view is there
            client.ClientStateChange(
                value="rt3d_camera",
                trigger_on_create=True,
                change=f"rt3d_camera.position && trame.refs.{VIEW_REF} && "
                f"trame.refs.{VIEW_REF}.setCamera(rt3d_camera)",
            )


OVERLAY_BOX = (
    "position: absolute; background: rgba(255, 255, 255, 0.8); color: #202020; "
    "border-radius: 4px; font-size: 12px; line-height: 16px; pointer-events: none; z-index: 2; "
)


def _overlay() -> None:
    """The server view's 2-D overlay as HTML over the canvas: ``#rt3d-labels`` (the teaching
    overlay's labels) over ``#rt3d-legend`` (its legend), lower left, and ``#rt3d-colour-bar`` (the
    painted tracks' colour bar in the strip right of the bearing, where the server view has it:
    title, colours, labels from top to bottom); the colour bar follows the colours drawn (whole
    run while playing, else up to the frame)."""
    with html.Div(
        v_show="show_labels && (rt3d_overlay.labels.length || rt3d_overlay.legend.length)",
        style=OVERLAY_BOX + "bottom: 4px; left: 4px; padding: 2px 6px;",
    ):
        with html.Div(id="rt3d-labels", classes="mb-1"):
            html.Div("{{ words }}", v_for="(words, k) in rt3d_overlay.labels", key="k")
        with html.Div(id="rt3d-legend"):
            with html.Div(v_for="(entry, k) in rt3d_overlay.legend", key="k", classes="rt3d-entry"):
                html.Span(
                    style=(
                        "{display: 'inline-block', width: '14px', height: '8px', "
                        "marginRight: '4px', verticalAlign: 'middle', background: entry[1]}",
                    ),
                )
                html.Span("{{ entry[0] }}")
    with html.Div(
        id="rt3d-colour-bar",
        v_show="show_tracks && (rt3d_frame.run ? rt3d_track_run : rt3d_tracks).ticks.length",
        style=OVERLAY_BOX + "top: 20%; height: 60%; right: 2%; min-width: 10%; padding: 2px 4px; "
        "display: flex; flex-direction: column;",
    ):
        html.Div(
            "{{ (rt3d_frame.run ? rt3d_track_run : rt3d_tracks).title }}",
            classes="rt3d-bar-title",
            style="font-size: 13px; margin-bottom: 4px;",
        )
        with html.Div(style="flex: 1; display: flex; gap: 4px; min-height: 0;"):
            html.Div(
                classes="rt3d-bar-colours",
                style=("{flex: '0 0 14px', background: rt3d_overlay.gradient}",),
            )
            with html.Div(
                style="display: flex; flex-direction: column; justify-content: space-between;"
            ):
                html.Span(
                    "{{ tick }}",
                    v_for="(tick, k) in (rt3d_frame.run ? rt3d_track_run : rt3d_tracks).ticks",
                    key="k",
                    classes="rt3d-bar-tick",
                )
