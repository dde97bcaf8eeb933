"""A websocket client that speaks to a trame page's session as the page does (wslink: msgpack
messages in chunks): the hello, the state read at start, state changes, and the state the session
publishes. Used by the follow-mode tests and benchmarks/follow.py."""

from __future__ import annotations

import asyncio
import itertools
import secrets
import time

import aiohttp
import msgpack


def chunk(message: dict) -> bytes:
    """``message`` as one wslink chunk (header: id, offset 0, size)."""
    body = msgpack.packb(message)
    ident = secrets.randbits(32).to_bytes(4, "little")
    return ident + (0).to_bytes(4, "little") + len(body).to_bytes(4, "little") + body


class WslinkClient:
    """One page's websocket: :meth:`connect`, then :meth:`call`; ``state`` follows what the session
    publishes, and ``frames`` records ``(time.monotonic(), frame)`` as each frame index arrives.
    ``received`` counts the bytes of the websocket messages read (as sent: compressed when asked
    for); with ``count_keys``, ``key_bytes`` the bytes of each published state key's value
    (msgpack, uncompressed)."""

    def __init__(self, count_keys: bool = False):
        self.ws: aiohttp.ClientWebSocketResponse | None = None
        self.state: dict = {}
        self.frames: list[tuple[float, int]] = []
        self.images = 0  # images the 3-D view received
        self.received = 0
        self.count_keys = count_keys
        self.key_bytes: dict[str, int] = {}
        self._ids = itertools.count(1)
        self._replies: dict[str, asyncio.Future] = {}
        self._pending: dict[int, bytearray] = {}
        self._reader: asyncio.Task | None = None

    async def connect(
        self,
        http: aiohttp.ClientSession,
        url: str,
        origin: str,
        timeout: float = 30.0,
        deflate: bool = False,
    ) -> None:
        """Open the websocket at ``url`` (``ws://.../ws``), say hello and read the whole state
        (each answer within ``timeout`` seconds). ``deflate``: ask for compressed messages
        (permessage-deflate), as browsers do."""
        self.ws = await http.ws_connect(
            url, origin=origin, max_msg_size=0, compress=15 if deflate else 0
        )
        self._reader = asyncio.get_running_loop().create_task(self._read())
        await self.call("wslink.hello", [{"secret": "wslink-secret"}], system=True, timeout=timeout)
        initial = await self.call("trame.state.get", [], timeout=timeout)
        self.state.update(initial["state"])

    async def call(self, method: str, args: list, system: bool = False, timeout: float = 30.0):
        """Call ``method``; its result, or raise RuntimeError with the error the session sent."""
        n = next(self._ids)
        rpcid = f"system:c0:{n}" if system else f"rpc:c0:{n}"
        reply = asyncio.get_running_loop().create_future()
        self._replies[rpcid] = reply
        await self.ws.send_bytes(
            chunk({"wslink": "1.0", "id": rpcid, "method": method, "args": args})
        )
        message = await asyncio.wait_for(reply, timeout)
        if "error" in message:
            raise RuntimeError(message["error"].get("message", "error"))
        return message.get("result")

    async def update(self, **changes) -> None:
        """Change state keys as the page does when a control changes."""
        await self.call(
            "trame.state.update", [[{"key": k, "value": v} for k, v in changes.items()]]
        )

    async def wait_for(self, key: str, predicate, timeout: float = 30.0):
        """Wait until the published ``state[key]`` satisfies ``predicate``; its value."""
        deadline = time.monotonic() + timeout
        while not (key in self.state and predicate(self.state[key])):
            if time.monotonic() > deadline:
                raise TimeoutError(f"{key} is {self.state.get(key)!r} after {timeout} s")
            await asyncio.sleep(0.05)
        return self.state[key]

    async def close(self) -> None:
        if self._reader is not None:
            self._reader.cancel()
        if self.ws is not None:
            await self.ws.close()

    async def _read(self) -> None:
        async for raw in self.ws:
            if raw.type != aiohttp.WSMsgType.BINARY:
                break
            data = raw.data
            self.received += len(data)
            ident = int.from_bytes(data[0:4], "little")
            offset = int.from_bytes(data[4:8], "little")
            size = int.from_bytes(data[8:12], "little")
            body = self._pending.setdefault(ident, bytearray(size))
            body[offset : offset + len(data) - 12] = data[12:]
            if offset + len(data) - 12 < size:
                continue  # chunks of a message arrive in order
            del self._pending[ident]
            self._receive(msgpack.unpackb(bytes(body), raw=False, strict_map_key=False))

    def _receive(self, message: dict) -> None:
        rpcid = str(message.get("id", ""))
        if rpcid.startswith("publish:trame.state.topic:"):
            changes = message.get("result") or {}
            self.state.update(changes)
            if self.count_keys:
                for key, value in changes.items():
                    size = len(msgpack.packb(value, default=str))
                    self.key_bytes[key] = self.key_bytes.get(key, 0) + size
            if "frame" in changes:
                self.frames.append((time.monotonic(), changes["frame"]))
        elif rpcid.startswith("publish:trame.rca.topic.stream:"):
            self.images += 1
        elif rpcid in self._replies:
            reply = self._replies.pop(rpcid)
            if not reply.done():
                reply.set_result(message)
