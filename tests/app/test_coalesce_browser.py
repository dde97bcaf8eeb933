"""In headless Chromium: a page the front serves says how many websocket messages it has
applied (app.serve.coalesce.READ_SCRIPT), counted once reads like trame's own (the message as a
Blob, its header then its body) are done, with trame's handler set after the socket is made; and
it gets the session's last state."""

from __future__ import annotations

import threading

import pytest
from aiohttp import web

from app.serve import coalesce
from tests.app.test_coalesce import _state
from tests.app.test_follow_front import _stand_in_session, front_in_thread
from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

MESSAGES = 40
# as trame's client: the socket made, then its handlers set; each message read as a Blob, in two
# reads, before it is applied
PAGE = """<html><head><title>stand-in</title></head><body><div id="app">app</div>
<script>
window.applied = 0;
window.addEventListener('load', () => {
  const socket = new WebSocket(window.location.href.replace(/^http/, 'ws').split('?')[0] + 'ws');
  socket.binaryType = 'blob';
  socket.onmessage = async (e) => {
    await e.data.slice(0, 12).arrayBuffer();
    const body = new Uint8Array(await e.data.slice(12).arrayBuffer());
    window.applied += 1;
    window.frame = body[body.length - 1];  // {..., "result": {"frame": i}}: i, a fixint
  };
  window.socket = socket;
});
</script></body></html>"""


@pytest.fixture
def counting_front(monkeypatch):
    """A front on a loopback port, in a thread of its own, whose stand-in session sends each
    page MESSAGES state messages; its base URL and the page's counts the front noted."""
    noted: list[str] = []
    note = coalesce.PageReads.note

    def noting(self, text):
        noted.append(text)
        return note(self, text)

    monkeypatch.setattr(coalesce.PageReads, "note", noting)

    async def streaming(request):
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        for i in range(MESSAGES):
            await ws.send_bytes(_state({"frame": i}))
        async for _ in ws:
            pass
        return ws

    with front_in_thread(monkeypatch, _stand_in_session(PAGE, websocket=streaming)) as served:
        yield served[0], noted


def test_a_page_says_how_many_messages_it_has_applied(browser, counting_front):
    base, noted = counting_front
    context = browser.new_context()
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda error: errors.append(error))
    try:
        page.goto(base + "/")
        page.wait_for_function(f"window.frame === {MESSAGES - 1}", timeout=30_000, polling=100)
        applied = page.evaluate("window.applied")
        expected = f"{coalesce.READ_PREFIX}{applied}"
        for _ in range(100):
            if expected in noted:
                break
            threading.Event().wait(0.05)
        counts = [int(text[len(coalesce.READ_PREFIX) :]) for text in noted]
        # from the socket's opening on, every message applied is counted, in order; the page
        # got the last frame, in as many messages as were sent (merged when it was behind)
        assert counts == list(range(applied + 1)), counts
        assert 1 <= applied <= MESSAGES
        assert not errors
    finally:
        context.close()
