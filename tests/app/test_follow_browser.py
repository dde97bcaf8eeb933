"""Follow mode in headless Chromium: a follower opened from the presenter's join code
(``/?follow=CODE``, its own browser) shows the presenter's lesson page, frame and highlighted ball,
with the banner that says it follows; the presenter sees it counted; what the follower's page
changes does not reach the presenter. Screenshots go to ``test-artifacts/browser/follow/``."""

from __future__ import annotations

import time

import pytest

from app.lessons.format import load_lessons
from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS, FIRST_IMAGE

pytestmark = BROWSER_MARKS
SHOTS = ARTIFACTS / "follow"
LESSON = load_lessons().lessons[1]
TITLE_IS = "t => (document.querySelector('#lesson-title') || {}).innerText === t"


def _page(browser, url: str):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    page = context.new_page()
    page.goto(url)
    page.wait_for_selector(FIRST_IMAGE, timeout=180_000)
    return context, page


def _state(page, key: str):
    return page.evaluate(f"window.trame.state.get('{key}')")


def _hold_frame(page, frame: int) -> None:
    """Pause the page on ``frame``. Frames the server sent while it was still playing can reach
    the page after a frame set there (CI saw 47..51 overwrite 240): pause, wait until the frame
    stops moving, then set it, and check that it holds (three tries)."""
    for _ in range(3):
        page.evaluate("window.trame.state.set('playing', false)")
        before = None
        for _tick in range(40):  # at most 10 s for the frames in flight to arrive
            now = _state(page, "frame")
            if now == before:
                break
            before = now
            time.sleep(0.25)
        page.evaluate(f"window.trame.state.set('frame', {frame})")
        time.sleep(1)  # nothing on the server moves the frame on now: it is still the one set
        if _state(page, "frame") == frame and _state(page, "playing") is False:
            return
    raise AssertionError(f"the frame set ({frame}) did not hold: {_state(page, 'frame')}")


def test_a_follower_sees_the_presenters_lesson_and_frame(browser, server):
    SHOTS.mkdir(parents=True, exist_ok=True)
    presenter_context, presenter = _page(browser, server["url"])
    presenter.evaluate("window.trame.state.set('playing', false)")  # the shared machine is busy
    presenter.locator(f"#lesson-{LESSON.id}").click()
    presenter.wait_for_function(TITLE_IS, arg=LESSON.title, timeout=120_000)
    # the title is shown before the lesson's result (which resets the frame): wait for the result
    presenter.wait_for_function(
        "n => window.trame.state.get('lesson_result') === n",
        arg=LESSON.results[0].name,
        timeout=120_000,
    )
    frames = presenter.evaluate("window.trame.state.get('frame_max')")
    frame = max(1, int(frames) // 3)
    _hold_frame(presenter, frame)
    presenter.evaluate("window.trame.state.set('trace_ball', 2)")
    code = _state(presenter, "follow_code")
    assert len(code) == 6

    follower_context, follower = _page(browser, f"{server['url']}?follow={code}")
    try:
        assert f"/follow/{code}/" in follower.url
        follower.wait_for_function(TITLE_IS, arg=LESSON.title, timeout=60_000)
        follower.wait_for_function(f"window.trame.state.get('frame') === {frame}", timeout=60_000)
        assert _state(follower, "trace_ball") == 2
        assert "read-only" in follower.locator("#follow-banner").inner_text()
        presenter.wait_for_function(
            "(document.querySelector('#follow-button') || {}).textContent.includes('1 following')",
            timeout=60_000,
        )
        # the presenter moves on: the follower follows
        presenter.evaluate(f"window.trame.state.set('frame', {frame + 1})")
        follower.wait_for_function(
            f"window.trame.state.get('frame') === {frame + 1}", timeout=60_000
        )
        follower.screenshot(path=str(SHOTS / "follower.png"))
        presenter.locator("#follow-button").click()
        presenter.wait_for_selector("#follow-qr", timeout=30_000)
        presenter.screenshot(path=str(SHOTS / "presenter-follow-card.png"))
        # what the follower's page sets stays in that page: the presenter's state is unchanged
        follower.evaluate("window.trame.state.set('frame', 0)")
        follower.evaluate("window.trame.state.set('playing', true)")
        time.sleep(2)
        assert _state(presenter, "frame") == frame + 1
        assert _state(presenter, "playing") is False
    finally:
        follower_context.close()
    presenter.wait_for_function(
        "(document.querySelector('#follow-button') || {}).textContent.includes('0 following')",
        timeout=60_000,
    )
    presenter_context.close()


def test_a_wrong_join_code_gets_a_page_that_says_so(browser, server):
    context = browser.new_context()
    page = context.new_page()
    answer = page.goto(f"{server['url']}?follow=QQQQQQ")
    assert answer.status == 404
    assert "No class with join code QQQQQQ" in page.locator("#follow-refused").inner_text()
    context.close()


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from tests.helpers.serve import start_server, stop_server

    root = tmp_path_factory.mktemp("follow-browser")
    served = start_server(root / "runs", root / "serve.log")
    yield served
    stop_server(served, timeout_s=60)
