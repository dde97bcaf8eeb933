"""Who draws the 3-D view (app.components.browser_view): the choice of view and what a played
frame sends to a browser that draws the scene itself (no browser here: the session's state pushes
are recorded)."""

from __future__ import annotations

import json

import pytest

from app.components.browser_view import BrowserView
from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server

# what a played frame may push with the browser-drawn view: the time controls' words and the
# frame's matrices and ellipses (the meshes, parts and painted tracks are not among them)
FRAME_KEYS = {"frame", "frame_time", "closeup_numbers", "rt3d_frame"}
MAX_FRAME_BYTES = 40_000  # 18 balls: 20 matrices and 2 x 18 ellipses of 25 points (float32)


def _set(app, **values):
    with app.state:
        for k, v in values.items():
            app.state[k] = v


def _session(tmp_path, render_mode: str) -> RacetraceApp:
    a = RacetraceApp(
        trame_server(),
        runs_dir=tmp_path,
        render=True,
        window_size=(200, 150),
        render_mode=render_mode,
    )
    a.start(DEFAULT_CASE, play=False)
    return a


@pytest.mark.parametrize(
    ("mode", "webgl", "in_browser"),
    [
        ("browser", True, True),
        ("browser", False, False),  # no WebGL in this browser: the server's images
        ("browser", None, False),  # the page has not said yet
        ("server", True, False),  # racetrace serve --render server
    ],
)
def test_the_view_is_drawn_by_the_browser_only_when_the_mode_and_webgl_allow(
    mode, webgl, in_browser
):
    class Result:  # what BrowserView reads of the result view
        state = trame_server().state

    view = BrowserView(Result(), mode)
    view.init_state()
    assert view.choose(webgl) is in_browser
    assert Result.state.view_in_browser is in_browser


def test_an_unknown_render_mode_is_refused_naming_the_choices():
    with pytest.raises(ValueError, match="browser, server"):
        BrowserView(object(), "gpu")


def test_a_played_frame_sends_only_the_moving_parts(tmp_path):
    a = _session(tmp_path, "browser")
    try:
        pushed = []
        a.state._push_state_fn = lambda update: pushed.append(dict(update))
        _set(a, browser_webgl=True)
        assert a.state.view_in_browser
        first = {k for update in pushed for k in update}
        assert {"rt3d_frame", "rt3d_tracks", "rt3d_visible"} <= first  # brought up to date
        assert a.state.rt3d_parts and a.state.rt3d_meshes  # sent with the result
        _set(a, playing=True)  # no event loop here: frames are set by hand, as the loop does
        for frame in (5, 6, 7):
            pushed.clear()
            _set(a, frame=frame)
            keys = {k for update in pushed for k in update}
            assert keys <= FRAME_KEYS | {"chart_contact_angle_now", "chart_raceway_map_now"}, keys
            assert "rt3d_frame" in keys
            sizes = {k: len(json.dumps(update[k])) for update in pushed for k in update}
            assert sizes["rt3d_frame"] < MAX_FRAME_BYTES, sizes
            assert a.state.rt3d_frame["index"] == frame
        # the server's own scene did not move: nothing was rendered on the server
        assert a.result.scene.frame_index != 7
        # the tracks follow by hand-chosen frames at once
        _set(a, playing=False)
        pushed.clear()
        _set(a, frame=40)
        assert a.state.rt3d_tracks["stop"] == 41
    finally:
        a.shutdown()


def test_the_server_scene_is_brought_to_the_frame_before_a_png_export(tmp_path):
    a = _session(tmp_path, "browser")
    try:
        _set(a, browser_webgl=True, frame=9)
        assert a.result.scene.frame_index != 9  # the browser draws: the server scene stays
        a.result.sync_scene()
        assert a.result.scene.frame_index == 9
    finally:
        a.shutdown()


def test_server_mode_renders_every_frame_on_the_server(tmp_path):
    a = _session(tmp_path, "server")
    try:
        _set(a, browser_webgl=True, frame=9)
        assert not a.state.view_in_browser
        assert a.result.scene.frame_index == 9
        assert a.state.rt3d_parts == []  # no meshes sent for a browser view never shown
    finally:
        a.shutdown()


def test_a_live_frame_drawn_by_the_browser_sends_the_window_frame_and_the_live_tracks(tmp_path):
    from app.live_view import LiveTracks, LiveWindow
    from solver import geometry_from_result
    from tests.app.conftest import make_dynamic_dataset
    from viz.frames import FrameSource

    a = _session(tmp_path, "browser")
    try:
        _set(a, browser_webgl=True)
        ds = make_dynamic_dataset(n_time=60)
        scene = a.result.live_scene(ds)
        assert geometry_from_result(ds) is not None and scene is not None
        layout = scene.layout
        whole = FrameSource.from_dynamic(ds)
        reference = [whole.reference_contact_angle(r) for r in (0, 1)]
        tracks = LiveTracks(layout.grooves, layout.grids, reference, 1.0)
        window = LiveWindow(revolutions=100.0)
        source = None
        for k in (0, 30):
            source = window.add(ds.isel(time=slice(k, k + 30)), {})
            tracks.add(source)
        pushed = []
        a.state._push_state_fn = lambda update: pushed.append(dict(update))
        with a.state:
            a.result.show_live_frame(window.source, 10, tracks, "t = live")
        keys = {k for update in pushed for k in update}
        assert "rt3d_frame" in keys and a.state.rt3d_frame["index"] == 10
        sent = a.state.rt3d_tracks
        assert sent["stop"] == tracks.stop == 59  # 60 samples: 59 sweeps from one to the next
        assert sent["range"][1] > sent["range"][0]
        # the server's scene did not render the frame (the browser draws)
        assert a.result.scene.frame_index != 10
    finally:
        a.shutdown()


def test_the_first_live_frame_of_a_change_is_marked_to_be_drawn_at_once(tmp_path):
    """A live frame sent as urgent (the first to carry a control change) counts up
    ``rt3d_urgent``, which the page watches to draw at once; other frames leave it alone."""
    from app.live_view import LiveTracks, LiveWindow
    from tests.app.conftest import make_dynamic_dataset
    from viz.frames import FrameSource

    a = _session(tmp_path, "browser")
    try:
        _set(a, browser_webgl=True)
        ds = make_dynamic_dataset(n_time=40)
        layout = a.result.live_scene(ds).layout
        whole = FrameSource.from_dynamic(ds)
        reference = [whole.reference_contact_angle(r) for r in (0, 1)]
        tracks = LiveTracks(layout.grooves, layout.grids, reference, 1.0)
        window = LiveWindow(revolutions=100.0)
        tracks.add(window.add(ds, {}))
        pushed = []
        a.state._push_state_fn = lambda update: pushed.append(dict(update))

        def draw(index, urgent):
            pushed.clear()
            with a.state:
                a.result.show_live_frame(window.source, index, tracks, "t", urgent=urgent)
            return [u["rt3d_urgent"] for u in pushed if "rt3d_urgent" in u]

        before = int(a.state.rt3d_urgent)
        assert draw(5, urgent=False) == []
        assert draw(6, urgent=True) == [before + 1]
        assert draw(7, urgent=False) == []
        assert draw(8, urgent=True) == [before + 2]
    finally:
        a.shutdown()


def _decoded(typed: dict):
    import base64

    import numpy as np

    return np.frombuffer(base64.b64decode(typed["bvals"]), dtype=typed["dtype"])


def test_played_frames_carry_no_track_arrays_only_how_many_painted_quads_are_shown(tmp_path):
    import time

    import numpy as np

    a = _session(tmp_path, "browser")
    try:
        _set(a, browser_webgl=True)
        pushed = []
        a.state._push_state_fn = lambda update: pushed.append(dict(update))
        _set(a, playing=True)
        shown = []
        for frame in range(5, 35):  # 1.5 s of play: longer than any refresh period
            _set(a, frame=frame)
            shown.append(a.state.rt3d_frame.get("n"))
            time.sleep(0.05)
        keys = {k for update in pushed for k in update}
        assert not keys & {"rt3d_tracks", "rt3d_track_run", "rt3d_track_cells"}, keys
        assert a.state.rt3d_frame["run"] is True  # the whole-run colours, sent with the result
        assert all(c is not None for c in a.state.rt3d_track_run["c"])
        assert all(_decoded(p).size for p in a.state.rt3d_track_cells["polys"])
        shown = np.array(shown)
        assert (np.diff(shown, axis=0) >= 0).all() and (shown[-1] > shown[0]).any(), shown
        # the quads shown are exactly the cells the server's painter has painted by then
        painter = a.result.scene.tracks.painter
        bscene = a.result.browser.scene
        painter.accumulate(35)
        for race in (0, 1):
            texel = bscene._track_cells[race][2]
            assert shown[-1][race] == int(painter.painted(race).T.ravel()[texel].sum())
    finally:
        a.shutdown()


def test_a_paused_frame_gets_the_server_views_track_colours_and_its_2d_overlay(tmp_path):
    import numpy as np

    a = _session(tmp_path, "browser")
    try:
        _set(a, browser_webgl=True, playing=False, frame=60)
        a.result.sync_scene()  # the server's own scene at the frame, as an export draws it
        scene, bscene = a.result.scene, a.result.browser.scene
        sent, n = a.state.rt3d_tracks, a.state.rt3d_frame["n"]
        assert sent["stop"] == 61
        for race in (0, 1):
            server = np.asarray(scene.tracks._texels[race].point_data["rgba"])
            order = bscene._track_cells[race][2][bscene._track_order[race]]
            browser = _decoded(sent["c"][race]).reshape(-1, 4)
            assert n[race] > 0
            assert np.array_equal(browser[: n[race]], server[order[: n[race]]])
            ring = np.asarray(scene.tracks.actors[0].mapper.lookup_table.nan_color.int_rgba)
            assert (server[order[n[race] :]] == ring).all()  # the rest unpainted there too
        # the overlay: the same words and numbers as the server view's 2-D actors
        overlay = a.state.rt3d_overlay
        assert overlay["labels"] == scene.overlay.label_words and overlay["labels"]
        assert [w for w, _ in overlay["legend"]] == scene.overlay.legend_words()
        lo, hi = scene.track_range
        assert sent["ticks"] == [f"{v:.3g}" for v in np.linspace(hi, lo, 5)]
        assert sent["title"] == scene.plotter.scalar_bar.GetTitle().replace("\n", " ")
    finally:
        a.shutdown()
