"""What the page gets while a result plays (app.components.result_view's play loop): each played
frame goes out in one state message that holds the frame index together with what the frame shows,
and nothing else changes with the frame (no browser here: the session's state pushes are
recorded)."""

from __future__ import annotations

import asyncio

from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server

# what a played frame may push with the browser-drawn view: the index, the time controls' words, the
# close-up's numbers and the frame's matrices and ellipses; the two charts that follow the time
# once a second (CHART_FOLLOW_S) may go with it
FRAME_KEYS = {"frame", "frame_time", "closeup_numbers", "rt3d_frame"}
CHART_KEYS = {"chart_contact_angle", "chart_raceway_map"}
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
