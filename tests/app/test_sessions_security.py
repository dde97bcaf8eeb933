"""`racetrace serve --host 0.0.0.0`: the front is reachable from the network, its sessions are not,
and a session answers the front only (its secret), whatever Host or Origin a client writes.

Traffic goes to loopback addresses only: 127.0.0.2 stands for "another address of this machine"
(a socket bound to 0.0.0.0 answers there, one bound to 127.0.0.1 does not).
"""

from __future__ import annotations

import asyncio
import socket
import sys
import urllib.error
import urllib.request
from pathlib import Path

import aiohttp
import pytest

from app.serve.session_guard import SECRET_HEADER
from tests.helpers.serve import START_S, descendants, start_server, stop_server

pytestmark = pytest.mark.skipif(
    not sys.platform.startswith("linux"), reason="finds the session ports in /proc (Linux)"
)
OTHER_ADDRESS = "127.0.0.2"


def _listening_ports(pids: set[int]) -> set[int]:
    """The TCP ports on which the processes ``pids`` listen (from /proc)."""
    inodes = set()
    for pid in pids:
        try:
            links = [p.readlink() for p in (Path("/proc") / str(pid) / "fd").iterdir()]
        except OSError:
            continue
        inodes |= {str(link)[8:-1] for link in links if str(link).startswith("socket:[")}
    ports = set()
    for table in ("tcp", "tcp6"):
        for line in (Path("/proc/net") / table).read_text().splitlines()[1:]:
            fields = line.split()
            if fields[3] == "0A" and fields[9] in inodes:  # 0A: LISTEN
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports


def _answers(address: str, port: int) -> bool:
    """Whether a TCP connection to ``address:port`` is accepted."""
    with socket.socket() as client:
        client.settimeout(5)
        try:
            client.connect((address, port))
        except OSError:
            return False
        return True


def _listener(address: str) -> socket.socket:
    sock = socket.socket()
    sock.bind((address, 0))
    sock.listen()
    return sock


def test_the_connect_check_tells_the_two_bindings_apart():
    """The control for the test below: this machine routes 127.0.0.2 to a socket bound to
    0.0.0.0 but not to one bound to 127.0.0.1, so "no answer on 127.0.0.2" means the latter."""
    with _listener("0.0.0.0") as everywhere, _listener("127.0.0.1") as loopback:
        assert _answers(OTHER_ADDRESS, everywhere.getsockname()[1])
        assert _answers("127.0.0.1", loopback.getsockname()[1])
        assert not _answers(OTHER_ADDRESS, loopback.getsockname()[1])


def _direct_websocket(port: int, headers: dict) -> int:
    """The handshake status of a websocket opened straight to a session port."""

    async def handshake() -> int:
        async with aiohttp.ClientSession() as client:
            try:
                async with client.ws_connect(f"ws://127.0.0.1:{port}/ws", headers=headers):
                    return 101
            except aiohttp.WSServerHandshakeError as error:
                return error.status

    return asyncio.run(handshake())


def _front_websocket(server: dict) -> int:
    """The handshake status of the page's websocket through the front, as a browser opens it."""

    async def handshake() -> int:
        jar = aiohttp.CookieJar(unsafe=True)  # keeps the cookies of 127.0.0.1
        async with aiohttp.ClientSession(cookie_jar=jar) as client:
            async with client.get(server["url"], headers={"Accept": "text/html"}) as page:
                assert page.status == 200
                assert "<html" in (await page.text()).lower()
            front = f"127.0.0.1:{server['port']}"
            try:
                async with client.ws_connect(f"ws://{front}/ws", origin=f"http://{front}"):
                    return 101
            except aiohttp.WSServerHandshakeError as error:
                return error.status

    return asyncio.run(handshake())


def _direct_get(port: int, headers: dict) -> int:
    request = urllib.request.Request(f"http://127.0.0.1:{port}/", headers=headers)
    try:
        with urllib.request.urlopen(request, timeout=30) as response:
            return response.status
    except urllib.error.HTTPError as error:
        return error.code


def test_sessions_listen_on_loopback_and_answer_the_front_only(tmp_path):
    server = start_server(tmp_path / "runs", tmp_path / "serve.log", "--host", "0.0.0.0")
    try:
        assert server["token"], "a network address must print an access token"
        # a browser through the front: its page and its websocket (a session is given to it)
        assert _front_websocket(server) == 101
        front_port = server["port"]
        assert _answers(OTHER_ADDRESS, front_port)  # the front is on every address, as asked
        session_ports = _listening_ports(descendants(server["proc"].pid)) - {front_port}
        assert session_ports, "no session process listens"
        for port in session_ports:
            assert not _answers(OTHER_ADDRESS, port), f"a session answers on {OTHER_ADDRESS}"
            forged = {"Host": f"127.0.0.1:{port}", "Origin": f"http://127.0.0.1:{port}"}
            assert _direct_get(port, forged) == 403
            assert _direct_get(port, {**forged, SECRET_HEADER: "guessed"}) == 403
            assert _direct_websocket(port, forged) == 403
            assert _direct_websocket(port, {**forged, SECRET_HEADER: "guessed"}) == 403
        # the front still serves the browser after all that
        with urllib.request.urlopen(server["url"], timeout=START_S) as page:
            assert page.status == 200
    finally:
        stop_server(server)
