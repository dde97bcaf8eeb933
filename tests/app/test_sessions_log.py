"""`racetrace serve`'s log stays readable: clients that vanish (a browser killed mid-animation, a
request reset before its answer or in the middle of its body) and a server stopped with SIGTERM
or Ctrl-C (SIGINT to the whole process group) leave no traceback, from the front nor from its
sessions (they write to the same log)."""

from __future__ import annotations

import os
import signal
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.helpers.serve import START_S, descendants, free_port, start_server

CHROMIUM = "/usr/bin/chromium"
needs_chromium = pytest.mark.skipif(
    not Path(CHROMIUM).exists(),
    reason=f"{CHROMIUM} is missing (apt-get install --no-install-recommends chromium)",
)

LAUNCH_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run"]
FIRST_IMAGE = "#view-3d img[src]:not([src=''])"


def _chromium_pids() -> set[int]:
    """The Chromium processes this test started (below this process)."""
    found = set()
    for pid in descendants(os.getpid()):
        try:
            name = (Path("/proc") / str(pid) / "comm").read_text().strip()
        except OSError:
            continue
        if "chrom" in name:
            found.add(pid)
    return found


def _open_and_kill_a_browser(url: str) -> None:
    """Open the app in Chromium, let it play, then kill Chromium (its sockets just drop)."""
    import playwright.sync_api as playwright_api

    with playwright_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS)
        page = browser.new_page(viewport={"width": 1000, "height": 760})
        page.goto(url, timeout=START_S * 1000)
        page.wait_for_selector(FIRST_IMAGE, timeout=START_S * 1000)
        page.evaluate("window.trame.state.set('playing', true)")
        time.sleep(3)  # frames are streaming to the page
        pids = _chromium_pids()
        assert pids, "no Chromium process found below the test"
        for pid in pids:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        try:
            browser.close()
        except playwright_api.Error:
            pass  # its process is gone


def _send_and_reset(port: int, request: bytes, wait_s: float) -> None:
    """Send ``request`` to the front, then drop the connection with a reset (no FIN)."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as client:
        client.sendall(request)
        time.sleep(wait_s)
        client.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))


def _requests_that_leave(port: int) -> None:
    host = f"Host: 127.0.0.1:{port}\r\n".encode()
    page = b"GET / HTTP/1.1\r\n" + host + b"Accept: text/html\r\n\r\n"
    _send_and_reset(port, page, 0.0)  # gone before its answer
    cut = b"POST / HTTP/1.1\r\n" + host + b"Content-Length: 100000\r\n\r\nthe first bytes"
    _send_and_reset(port, cut, 0.5)  # gone in the middle of its body


@pytest.mark.browser
@needs_chromium
@pytest.mark.parametrize("stop", ["SIGTERM", "SIGINT to the group"])
def test_a_vanished_browser_and_a_stop_leave_no_traceback(tmp_path, stop):
    server = start_server(tmp_path / "runs", tmp_path / "serve.log", new_group=True)
    proc, log = server["proc"], server["log"]
    try:
        _requests_that_leave(server["port"])
        _open_and_kill_a_browser(server["url"])
        time.sleep(5)  # the front and the session notice the dropped connection
        if stop == "SIGTERM":
            proc.send_signal(signal.SIGTERM)
        else:  # Ctrl-C in a terminal signals every process of the foreground group
            os.killpg(proc.pid, signal.SIGINT)
        assert proc.wait(timeout=120) == 0
        _assert_all_gone(proc.pid)  # the session processes have written their last lines
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    log.seek(0)
    text = log.read()
    log.close()
    assert "serving on" in text
    _assert_quiet(text)
    _assert_all_gone(proc.pid)


def _assert_quiet(log: str) -> None:
    assert "Traceback" not in log, log[-6000:]
    for noise in ("Error", "Exception", "Unclosed", "never retrieved", "destroyed"):
        assert noise not in log, log[-6000:]


def _assert_all_gone(group: int) -> None:
    """Nothing of the server (process group ``group``) is left running."""
    deadline = time.monotonic() + 60
    while subprocess.run(["pgrep", "-g", str(group)], capture_output=True).stdout:
        assert time.monotonic() < deadline, "processes of the server are still running"
        time.sleep(0.5)


@pytest.mark.parametrize(
    "moment", ["SIGTERM while the fork server imports", "Ctrl-C while the first session starts"]
)
def test_a_stop_during_start_up_is_quiet(tmp_path, moment):
    """Stopped before the server is ready: while its fork server still imports what the sessions
    use (before the banner), or while the first session process starts (after it)."""
    log_path = tmp_path / "serve.log"
    with open(log_path, "w+") as log:
        proc = subprocess.Popen(
            [sys.executable, "-m", "racetrace", "serve", "--port", str(free_port())]
            + ["--runs-dir", str(tmp_path / "runs")],
            stdout=log,
            stderr=subprocess.STDOUT,
            process_group=0,
        )
        try:
            deadline = time.monotonic() + START_S
            while not _reached(moment, proc.pid, log_path):
                assert proc.poll() is None and time.monotonic() < deadline, log_path.read_text()
                time.sleep(0.1)
            if moment.startswith("SIGTERM"):
                proc.send_signal(signal.SIGTERM)
            else:
                os.killpg(proc.pid, signal.SIGINT)
            assert proc.wait(timeout=START_S) == 0
        finally:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
    text = log_path.read_text()
    _assert_quiet(text)
    _assert_all_gone(proc.pid)


def _reached(moment: str, pid: int, log_path: Path) -> bool:
    if moment.startswith("SIGTERM"):  # the fork server runs, the banner is not out yet
        return any("forkserver" in _command_line(child) for child in descendants(pid))
    return "serving on" in log_path.read_text()  # the first session is forked and starts


def _command_line(pid: int) -> str:
    try:
        return (Path("/proc") / str(pid) / "cmdline").read_bytes().decode(errors="replace")
    except OSError:
        return ""
