"""Follow mode's ending in headless Chromium: a follower's page (the front's banner on a stand-in
session's page, tests/app/test_follow_front.py) says that the presenter has left while the
session says so, and is replaced by "the class has ended" when the front ends the class at the
idle stop (it closes the follower's websocket with app.serve.follow.PRESENTER_LEFT_CLOSE)."""

from __future__ import annotations

import pytest

from app.serve import front as front_module
from tests.app.test_follow_front import CODE, _stand_in_session, front_in_thread
from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

# the stand-in session's page: a websocket to the session (as trame's page opens once loaded),
# and a trame state that says the presenter has left
PAGE = """<html><body><div id="app">app</div>
<script>
window.trame = { state: { get: (key) => ({ follow_presenter: false })[key] } };
window.addEventListener('load', () => {
  window.socket = new WebSocket(window.location.href.replace(/^http/, 'ws').split('?')[0] + 'ws');
});
</script></body></html>"""


@pytest.fixture
def stand_in_front(monkeypatch):
    """A front on a loopback port, in a thread of its own, with an idle stop of 1 s; its base
    URL."""
    monkeypatch.setattr(front_module, "IDLE_S", 1.0)
    monkeypatch.setattr(front_module, "REAP_EVERY_S", 0.1)
    with front_in_thread(monkeypatch, _stand_in_session(PAGE)) as served:
        yield served


def test_a_followers_page_says_the_presenter_left_then_that_the_class_ended(
    browser, stand_in_front
):
    base, processes = stand_in_front
    presenter_context = browser.new_context()
    presenter = presenter_context.new_page()
    presenter.goto(base + "/")
    presenter.wait_for_function("window.socket && window.socket.readyState === 1")
    follower_context = browser.new_context()
    follower = follower_context.new_page()
    errors = []  # the banner's script must run (a syntax error would leave the page inert)
    follower.on("pageerror", lambda error: errors.append(error))
    try:
        follower.goto(f"{base}/?follow={CODE}")
        follower.wait_for_function("window.socket && window.socket.readyState === 1")
        follower.wait_for_function(
            "document.getElementById('follow-banner').textContent"
            ".includes('the presenter has left')"
        )
        assert "2 minutes" not in follower.locator("#follow-banner").inner_text()  # 1 s here
        assert not processes[0].signals
        presenter_context.close()  # the presenter leaves; the class ends 1 s later
        follower.wait_for_selector("#follow-ended", timeout=30_000)
        assert f"class {CODE} has ended" in follower.locator("#follow-ended").inner_text()
        assert processes[0].signals
        assert not errors
    finally:
        follower_context.close()
