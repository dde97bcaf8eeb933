"""`racetrace serve` with several browsers, in headless Chromium: one session per browser, the
solver queue, refused origins and tokens, and a server stopped (killed) during a run.

Screenshots go to ``test-artifacts/browser/`` (gitignored).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS, FIRST_IMAGE
from tests.helpers.serve import descendants, free_port, stop_server

pytestmark = BROWSER_MARKS
START_S = 300  # a cold numba cache compiles the quasi-static kernels first; the machine is shared


def _start(tmp_path: Path, *options: str) -> dict:
    if not any(o.startswith("--render") for o in options):
        options = (*options, "--render", "server")  # these tests read the server's images
    runs = tmp_path / "runs"
    port = free_port()
    log = open(tmp_path / f"serve-{port}.log", "w+")  # noqa: SIM115 - closed in _stop
    proc = subprocess.Popen(
        [sys.executable, "-m", "racetrace", "serve", "--port", str(port), "--runs-dir", str(runs)]
        + list(options),
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    server = {"url": f"http://127.0.0.1:{port}/", "port": port, "runs": runs, "proc": proc}
    server["log"] = log
    deadline = time.monotonic() + START_S
    while True:
        log.seek(0)
        text = log.read()
        if "serving on" in text:
            break
        if proc.poll() is not None or time.monotonic() > deadline:
            proc.kill()
            pytest.fail(f"racetrace serve did not start:\n{text[-3000:]}")
        time.sleep(0.2)
    server["banner"] = text
    return server


def _stop(server: dict) -> None:
    stop_server(server, timeout_s=60)


def _alive(pids) -> set[int]:
    alive = set()
    for pid in pids:
        try:
            state = (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":
            alive.add(pid)
    return alive


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    s = _start(tmp_path_factory.mktemp("sessions"), "--max-runs", "1")
    yield s
    _stop(s)


def _open(browser, url: str, width: int, height: int):
    """A new browser (its own cookies: its own session) showing the app at this window size."""
    context = browser.new_context(viewport={"width": width, "height": height})
    page = context.new_page()
    page.goto(url, timeout=START_S * 1000)
    page.wait_for_selector(FIRST_IMAGE, timeout=START_S * 1000)
    page.wait_for_function(
        "document.querySelector('#status').innerText.trim().endsWith('done')", timeout=60_000
    )
    return page


def _image_size(page) -> list[int]:
    return page.evaluate(
        "() => { const i = document.querySelector('#view-3d img');"
        " return [i.naturalWidth, i.clientWidth]; }"
    )


def _wait_image_width(page, timeout_s=30.0) -> list[int]:
    """The image's natural and shown widths, once the server has drawn it at the shown size."""
    deadline = time.monotonic() + timeout_s
    while True:
        natural, shown = _image_size(page)
        if abs(natural - shown) <= 2 or time.monotonic() > deadline:
            return [natural, shown]
        time.sleep(0.5)


def _set_field(page, name: str, value: str) -> None:
    box = page.locator(f"#field-{name} input")
    box.fill(value)
    box.press("Tab")


def _set_revolutions(page, revolutions: int, timeout_s: float = 120.0) -> None:
    """Type ``revolutions`` into the form and wait until the server has validated it (its run
    size names them): a Run pressed before then would run the case the server still holds. The
    field is typed again if the server's first filling of the form overwrote it."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    wanted = f"{revolutions} shaft revolutions"
    deadline = time.monotonic() + timeout_s
    while True:
        _set_field(page, "shaft_revolutions", str(revolutions))
        try:
            page.wait_for_function(
                "w => (document.querySelector('#run-size') || {}).innerText?.includes(w)",
                arg=wanted,
                timeout=15_000,
            )
            return
        except PlaywrightTimeout:
            assert time.monotonic() < deadline, f"the server never took {wanted}: {_status(page)}"


def _status(page) -> str:
    return page.locator("#status").inner_text().strip()


def _wait_status(page, predicate, timeout_s: float) -> str:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        text = _status(page)
        if predicate(text):
            return text
        time.sleep(0.25)
    raise AssertionError(f"status still {_status(page)!r} after {timeout_s} s")


def test_two_browsers_keep_their_own_render_sizes(browser, server):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    big = _open(browser, server["url"], 1500, 1000)
    small = _open(browser, server["url"], 900, 700)
    try:
        big_natural, big_shown = _wait_image_width(big)
        small_natural, small_shown = _wait_image_width(small)
        big.screenshot(path=str(ARTIFACTS / "sessions-big.png"))
        small.screenshot(path=str(ARTIFACTS / "sessions-small.png"))
        assert abs(big_natural - big_shown) <= 2, (big_natural, big_shown)
        assert abs(small_natural - small_shown) <= 2, (small_natural, small_shown)
        assert big_natural > small_natural + 50
        # an edit in one browser stays there
        _set_field(small, "axial_load_N", "777")
        time.sleep(2)
        assert big.locator("#field-axial_load_N input").input_value() != "777"
    finally:
        small.context.close()
    time.sleep(2)  # the small browser has gone: the big one keeps its size
    assert abs(_image_size(big)[0] - big_shown) <= 2
    big.context.close()


def test_a_second_run_waits_in_the_queue(browser, server):
    first = _open(browser, server["url"], 1200, 900)
    second = _open(browser, server["url"], 1200, 900)
    try:
        for page in (first, second):
            _set_revolutions(page, 200)
            page.wait_for_function(
                "!document.querySelector('#run-button').disabled", timeout=120_000
            )
        first.locator("#run-button").click()
        _wait_status(first, lambda s: s.startswith("running"), 180)
        second.locator("#run-button").click()
        text = _wait_status(second, lambda s: s.startswith("queued"), 120)
        second.screenshot(path=str(ARTIFACTS / "sessions-queued.png"))
        assert "place 1 in the queue" in text and "at most 1 run at once" in text
        second.locator("#cancel-button").click()
        assert _wait_status(second, lambda s: s.startswith("cancelled"), 120) == "cancelled"
        first.locator("#cancel-button").click()
        _wait_status(first, lambda s: s.endswith(("cancelled", "done")), 120)
    finally:
        first.context.close()
        second.context.close()


def test_foreign_origin_is_refused(server):
    import aiohttp

    async def handshake(origin: str) -> int:
        jar = aiohttp.CookieJar(unsafe=True)  # keeps cookies of 127.0.0.1
        async with aiohttp.ClientSession(cookie_jar=jar) as session:
            # open the page first, as a browser does: the session cookie
            async with session.get(server["url"], headers={"Accept": "text/html"}) as page:
                assert page.status == 200
            try:
                async with session.ws_connect(f"ws://127.0.0.1:{server['port']}/ws", origin=origin):
                    return 101
            except aiohttp.WSServerHandshakeError as error:
                return error.status

    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    def status(origin: str) -> int:  # Playwright's loop runs in this thread: use another
        with ThreadPoolExecutor(1) as pool:
            return pool.submit(asyncio.run, handshake(origin)).result(timeout=START_S)

    assert status("http://evil.example") == 403
    assert status(f"http://127.0.0.1:{server['port']}") == 101
    request = urllib.request.Request(server["url"], headers={"Host": "rebind.example"})
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=10)
    assert refused.value.code == 403


def test_a_network_address_needs_the_printed_token(tmp_path):
    s = _start(tmp_path, "--host", "0.0.0.0")
    try:
        banner = s["banner"]
        assert "reachable from the network" in banner
        token = banner.split("?token=", 1)[1].split()[0]
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(s["url"], timeout=10)
        assert refused.value.code == 403
        assert b"access token required" in refused.value.read()
        with pytest.raises(urllib.error.HTTPError):
            urllib.request.urlopen(s["url"] + "?token=wrong", timeout=10)
        ok = urllib.request.urlopen(s["url"] + f"?token={token}", timeout=START_S)
        assert ok.status == 200
    finally:
        _stop(s)


def test_killed_server_saves_the_run_and_leaves_no_solver(browser, tmp_path):
    s = _start(tmp_path)
    try:
        page = _open(browser, s["url"], 1200, 900)
        _set_revolutions(page, 200)
        page.wait_for_function("!document.querySelector('#run-button').disabled", timeout=30_000)
        page.locator("#run-button").click()
        deadline = time.monotonic() + START_S
        while float(page.evaluate("window.trame.state.get('progress')") or 0) <= 0:
            assert time.monotonic() < deadline, _status(page)
            time.sleep(0.5)
        page.screenshot(path=str(ARTIFACTS / "sessions-before-kill.png"))
        below = descendants(s["proc"].pid)
        assert len(below) >= 3  # the spare session, this browser's session, its solver
        os.kill(s["proc"].pid, signal.SIGKILL)  # no chance to clean up: the children must
        s["proc"].wait()
        deadline = time.monotonic() + 60
        while _alive(below):
            assert time.monotonic() < deadline, f"still running: {_alive(below)}"
            time.sleep(0.5)
        page.context.close()
        metas = [json.loads(p.read_text()) for p in Path(s["runs"]).glob("*/run.json")]
        assert [m["status"] for m in metas] == ["cancelled"], metas
        assert " of 200 rev" in metas[0]["title"] and "server stopped" in metas[0]["title"]
    finally:
        _stop(s)


def test_shared_mode_gives_every_browser_the_same_session(tmp_path):
    s = _start(tmp_path, "--shared")
    try:
        assert "one session for every browser" in s["banner"]

        def session_cookie() -> str:  # a new browser each time: no cookies sent
            request = urllib.request.Request(s["url"], headers={"Accept": "text/html"})
            with urllib.request.urlopen(request, timeout=START_S) as response:
                cookie = response.headers.get("Set-Cookie", "")
            assert cookie.startswith("racetrace_session="), cookie
            return cookie.split(";")[0]

        assert session_cookie() == session_cookie()
    finally:
        _stop(s)
