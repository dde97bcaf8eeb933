"""The 3-D view drawn by the browser (vtk.js through trame-vtk's declarative components).

The server keeps its pyvista scene (:class:`viz.scene.BearingScene`: the exports render it off
screen, and it holds the layers, the camera presets and the painted-track fields); the browser
gets the scene's meshes once per result (:class:`viz.browser_scene.BrowserScene`) and, for a
played frame, only the moving parts' matrices and the contact ellipses of the frame. The painted
tracks' cell colours are sent when they have grown: at most every :data:`TRACK_REFRESH_S` while
playing, at once when a frame is chosen by hand. The camera lives in the browser (a preset is sent
once when chosen).

Which view a page shows: ``render_mode`` (``racetrace serve --render browser|server``) and
``browser_webgl`` (set by the page itself: whether the browser can draw WebGL); the browser view
when both allow it, else the server-rendered view.

State keys: ``render_mode``, ``browser_webgl`` (None until the page says), ``view_in_browser``,
``rt3d_meshes`` (mesh key -> typed arrays), ``rt3d_parts`` (the parts: mesh key, group,
colours, surface properties), ``rt3d_frame`` (index, matrices ``m``, ellipse points ``e``),
``rt3d_tracks`` (the painted tracks' colours ``c`` up to frame ``stop``), ``rt3d_visible`` (part
name -> shown) and ``rt3d_camera`` (a camera preset to apply: vtk.js camera settings and a
``serial``).
"""

from __future__ import annotations

import hashlib
import time

from trame.widgets import client, html
from trame.widgets import vtk as vtk_widgets

from viz.browser_scene import BrowserScene, camera_state

RENDER_MODES = ("browser", "server")
TRACK_REFRESH_S = 1.0  # while playing, the painted tracks are re-sent at most this often
VIEW_REF = "rt3d_view"
IDENTITY = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]

# Run by the page: whether this browser can draw WebGL, told to the server once trame is up.
DETECT_WEBGL = """
(function racetraceWebgl(tries) {
  if (!(window.trame && window.trame.state)) {
    if (tries < 200) setTimeout(function () { racetraceWebgl(tries + 1); }, 50);
    return;
  }
  var ok = false;
  try {
    var canvas = document.createElement('canvas');
    ok = !!(canvas.getContext('webgl2') || canvas.getContext('webgl'));
  } catch (e) { ok = false; }
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
        s.rt3d_frame = {"index": 0, "m": {}, "e": [None, None]}
        s.rt3d_tracks = {"stop": 0, "range": [0.0, 1.0], "c": [None, None]}
        s.rt3d_visible = {}
        s.rt3d_camera = {"serial": 0}

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
        s = self.state
        s.rt3d_meshes = meshes
        s.rt3d_parts = parts

    def refresh(self, index: int) -> None:
        """Everything but the meshes: visibility, frame ``index``, the painted tracks."""
        if self.scene is None:
            return
        self.state.rt3d_visible = {
            name: bool(actor.GetVisibility()) for name, actor in self._actors.items()
        }
        self.show_frame(index, tracks_now=True)

    def show_frame(self, index: int, tracks_now: bool = False) -> None:
        """Send frame ``index``: the matrices and ellipses; the painted tracks when they are due
        (``tracks_now``, or :data:`TRACK_REFRESH_S` after the last time, or going back)."""
        if self.scene is None:
            return
        options = self.scene.scene.options
        self.state.rt3d_frame = self.scene.frame_state(index, options.ellipse_scale)
        n = self.scene.scene.source.n_frames
        stop = n if options.track_whole_run else index + 1
        sent_stop, sent_quantity, sent_at = self._tracks_sent
        due = (
            tracks_now
            or not self.state.playing  # a frame chosen by hand
            or sent_quantity != options.track_quantity
            or stop < sent_stop
            or (stop != sent_stop and time.monotonic() - sent_at >= TRACK_REFRESH_S)
        )
        if due:
            self.state.rt3d_tracks = self.scene.track_state(stop, options.track_quantity)
            self._tracks_sent = (stop, options.track_quantity, time.monotonic())

    def show_live_frame(self, index: int) -> None:
        """Send frame ``index`` of a live session's window: the matrices and ellipses, and the
        session's accumulated tracks (:class:`app.live_view.LiveTracks`) at most every
        :data:`TRACK_REFRESH_S` (the window slides, so frame numbers do not say what is new)."""
        if self.scene is None:
            return
        options = self.scene.scene.options
        self.state.rt3d_frame = self.scene.frame_state(index, options.ellipse_scale)
        _, sent_quantity, sent_at = self._tracks_sent
        if sent_quantity != options.track_quantity or time.monotonic() - sent_at >= TRACK_REFRESH_S:
            self.state.rt3d_tracks = self.scene.track_state(0, options.track_quantity)
            self._tracks_sent = (-1, options.track_quantity, time.monotonic())

    def set_camera(self, plotter) -> None:
        """Send the server scene's camera (a preset just applied) to the browser, which applies
        it once (then the camera is the browser's own: orbiting costs the server nothing)."""
        camera = camera_state(plotter)
        camera["centerOfRotation"] = camera["focalPoint"]
        camera["serial"] = int(self.state.rt3d_camera.get("serial", 0)) + 1
        self.state.rt3d_camera = camera

    # ---- page -----------------------------------------------------------------------------------
    def build(self) -> None:
        """``#view-3d-browser``: the vtk.js view (one representation per part)."""
        with html.Div(id="view-3d-browser", style="width: 100%; height: 100%;"):
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
                        polys=("rt3d_meshes[part.mesh].polys",),
                        lines=("rt3d_meshes[part.mesh].lines",),
                    ):
                        with vtk_widgets.VtkCellData():
                            vtk_widgets.VtkDataArray(
                                v_if="part.kind === 'tracks' && rt3d_tracks.c[part.race]",
                                registration="setScalars",
                                name="rgba",
                                type="Uint8Array",
                                number_of_components=("4",),  # a number, not the text "4"
                                values=("rt3d_tracks.c[part.race]",),
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
            # a camera preset chosen on the server is applied once the view is there
            client.ClientStateChange(
                value="rt3d_camera",
                trigger_on_create=True,
                change=f"rt3d_camera.position && trame.refs.{VIEW_REF} && "
                f"trame.refs.{VIEW_REF}.setCamera(rt3d_camera)",
            )
