"""What the page gets while a result plays (app.components.result_view's play loop): each played
frame goes out in one state message that holds the frame index together with what the frame shows,
and nothing else changes with the frame (no browser here: the session's state pushes are
recorded)."""

from __future__ import annotations

import asyncio

import numpy as np

from app import charts
from app.components.base import fig_json
from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server

# what a played frame may push with the browser-drawn view: the index, the time controls' words, the
# close-up's numbers and the frame's matrices and ellipses, and the marks of the frame on the two
# charts that follow the time (their overlays; not their figures)
FRAME_KEYS = {"frame", "frame_time", "closeup_numbers", "rt3d_frame"}
CHART_KEYS = {"chart_contact_angle_now", "chart_raceway_map_now"}
FIGURE_KEYS = {"chart_contact_angle", "chart_raceway_map"}  # sent with a result or an option
PLAYED = 6  # frames played by the test


def _play(app: RacetraceApp, frames: int) -> list[dict]:
    """Run the session's play loop until it has pushed ``frames`` frame indices; the pushes."""
    with app.state:
        app.state.playing = True  # outside an event loop: the loop is started by hand below
    app.clients = 1  # the loop plays while a browser is connected
    pushed = []
    app.state._push_state_fn = lambda update: pushed.append(dict(update))

    async def play():
        task = asyncio.get_running_loop().create_task(app.result._play_loop())
        while sum("frame" in update for update in pushed) < frames and not task.done():
            await asyncio.sleep(0.01)
        app.state.playing = False  # the loop ends at its next tick
        await asyncio.wait_for(task, 10)

    asyncio.run(play())
    return pushed


def test_a_played_frame_is_one_message_with_the_index_and_what_the_frame_shows(tmp_path):
    app = RacetraceApp(
        trame_server(), runs_dir=tmp_path, render=True, window_size=(200, 150)
    )  # the browser-drawn view, the app's default
    app.start(DEFAULT_CASE, play=False)
    try:
        with app.state:
            app.state.browser_webgl = True
        assert app.state.view_in_browser
        pushed = _play(app, PLAYED)
        frames = [update for update in pushed if "frame" in update]
        assert len(frames) >= PLAYED, pushed
        for update in pushed:
            keys = set(update)
            # never the index alone and the frame's content in a second message (two Vue updates
            # and two drawings per frame), never the content without its index
            assert {"frame", "frame_time", "rt3d_frame"} <= keys, keys
            assert keys <= FRAME_KEYS | CHART_KEYS, keys
            assert update["rt3d_frame"]["index"] == update["frame"]
    finally:
        app.shutdown()


def test_while_playing_the_charts_get_the_marks_of_each_frame_not_their_figures(tmp_path):
    app = RacetraceApp(trame_server(), runs_dir=tmp_path, render=False)
    app.start(DEFAULT_CASE, play=False)
    try:
        figures = {key: app.state[key] for key in FIGURE_KEYS}
        pushed = _play(app, PLAYED)
        frames = [update for update in pushed if "frame" in update]
        assert len(frames) >= PLAYED, pushed
        for update in pushed:
            assert not set(update) & FIGURE_KEYS, set(update)  # the figures are not sent again
        for update in frames:  # the marks go with every frame
            assert CHART_KEYS <= set(update), set(update)
        for key, figure in figures.items():
            assert app.state[key] is figure
        # the figure and the marks show what the whole figure of the frame showed
        s, source, frame = app.state, app.result.source, frames[-1]["frame"]
        shown = charts.merge_overlay(s.chart_contact_angle, s.chart_contact_angle_now)
        assert shown == fig_json(charts.contact_angle_figure(source, None, current=frame))
        map_shown = charts.merge_overlay(s.chart_raceway_map, s.chart_raceway_map_now)
        now = charts.current_contact_traces(source, frame, None)
        points = sorted((x, y) for t in now for x, y in zip(t.x, t.y, strict=True))
        circles = [
            c
            for c in map_shown["layout"]["shapes"]
            if c.get("templateitemname") == charts.NOW_SHAPE
        ]
        anchors = sorted((c["xanchor"], c["yanchor"]) for c in circles)
        np.testing.assert_allclose(anchors, points)
        # an option changes the figure: sent again, once
        pushed.clear()
        with app.state:
            app.state.map_colour = "ball"
        sent = [update for update in pushed if "chart_raceway_map" in update]
        assert len(sent) == 1 and app.state.chart_raceway_map is not figures["chart_raceway_map"]
    finally:
        app.shutdown()
