"""Follow mode at the front: a class watches a presenter's session, read-only unless handed over.

A follower opens ``/?follow=CODE`` (the presenter's join code, :mod:`app.components.follow`); the
front sends it to ``/follow/CODE/``, whose page, scripts and websocket it relays to the
presenter's own session process (:mod:`app.serve.front`): a follower is one more websocket client
of that session, not a session of its own (no process, no solver slot, and no render: the session
publishes each image once, to every client). The page's websocket URL follows the page's path
(``/follow/CODE/ws``), so the front tells a follower's connection from the presenter's by its
path, whatever cookies the browser holds.

Read-only is enforced here, on the server: every message a follower's page sends is a wslink RPC
(msgpack, in chunks, :func:`read_rpc`), and :meth:`FollowerGate.refusal` lets through only what
reads the session (its state, the hello, error reports, lifecycle notes). A state change, a
controller call or a mouse event on the 3-D view passes only while the presenter lets followers
drive (state ``follow_drive``, read from the session at that moment, :data:`STATUS_PATH`); a
follower never changes the ``follow_*`` keys (it cannot hand itself the controls), and never sizes
the render or pushes images. A refused call is answered with a wslink error naming why, so the
page's call ends instead of waiting.

What a follower's page is sent is what the presenter's session publishes, through the front's
per-browser backlog (:mod:`app.serve.coalesce`): a page that draws slowly is sent at most two
messages beyond what it has drawn, then the newest state, so it shows a frame the presenter's
session played about when the page was ready for one, not a queue of older frames. There is no
prediction: the page shows no frame before the presenter's session has played it.

A class ends with its presenter: the front stops a session whose presenter's page has been gone
for its idle time, whatever followers it has, and closes their websockets first with
:data:`PRESENTER_LEFT_CLOSE` (their page then says the presenter has left). Join codes cannot be
guessed by trying them: a client address that sent :data:`WRONG_CODES_PER_MINUTE` wrong codes in a
minute is refused every code until the minute has passed (:class:`WrongCodeLimit`).
"""

from __future__ import annotations

import re
import secrets
from collections import deque
from dataclasses import dataclass

import msgpack

from ..follow_names import JOINED

STATUS_PATH = "/__racetrace_follow/status"  # a session's join code and hand-over, as JSON
PREFIX = "/follow/"  # a follower's page and websocket: /follow/CODE/...
CODE_PATTERN = re.compile(r"[A-Z0-9]{4,12}")
MAX_MESSAGE_BYTES = 1 << 20  # a follower's message larger than this is refused unread
MAX_PENDING = 16  # unfinished (chunked) messages of one follower at once

# wslink's chunk header: message id, offset, total size (three little-endian uint32)
_HEADER = 12
# what any follower may call: reading the state, the hello, and notes that change nothing
ALWAYS = frozenset({"trame.state.get", "trame.error.client", "trame.rca.video.codecs"})
# the one controller call a follower's page makes: "I am here, send me the picture on show"
LIFECYCLE = frozenset({"client_connected", "client_exited", "client_unmounted"})
# what a follower may call while the presenter lets followers drive
WHEN_DRIVING = frozenset({"trame.state.update", "trame.trigger", "trame.rca.event"})
READ_ONLY_ERROR = -32001  # the wslink error code of a refused call (JSON-RPC's server range)
PRESENTER_LEFT_CLOSE = 4001  # a follower's websocket closed because its class ended
# wrong join codes a client address may send in WRONG_CODES_WINDOW_S before it is refused every
# code: a class behind one address (a school's network) mistypes a few; guessing one of 31**6
# codes at this rate takes decades
WRONG_CODES_PER_MINUTE = 20
WRONG_CODES_WINDOW_S = 60.0
MAX_ADDRESSES = 4096  # client addresses whose wrong codes are remembered at once


def normal_code(text: str) -> str:
    """A join code as typed (``abc-234`` -> ``ABC234``); "" if it cannot be one."""
    code = re.sub(r"[\s-]", "", str(text)).upper()
    return code if CODE_PATTERN.fullmatch(code) else ""


def follow_url(host_header: str, code: str, token: str = "") -> str:
    """The address a follower opens: this server as the presenter reached it, the join code, and
    the access token when the server has one (the token rules apply to followers too)."""
    query = f"follow={code}" + (f"&token={token}" if token else "")
    return f"http://{host_header}/?{query}"


def qr_svg(url: str) -> bytes:
    """``url`` as a QR code, an SVG image (black on white, with its quiet zone)."""
    import io

    import segno

    out = io.BytesIO()
    segno.make(url, error="m").save(out, kind="svg", scale=6, border=4, xmldecl=False)
    return out.getvalue()


class WrongCodeLimit:
    """The wrong join codes each client address sent in the last :data:`WRONG_CODES_WINDOW_S`
    seconds; an address that sent :data:`WRONG_CODES_PER_MINUTE` is refused until the oldest of
    them is that old. At most :data:`MAX_ADDRESSES` addresses are remembered (the longest quiet
    ones are forgotten first). Times: monotonic seconds."""

    def __init__(
        self,
        limit: int = WRONG_CODES_PER_MINUTE,
        window_s: float = WRONG_CODES_WINDOW_S,
        max_addresses: int = MAX_ADDRESSES,
    ):
        self.limit, self.window_s, self.max_addresses = limit, window_s, max_addresses
        self._wrong: dict[str, deque[float]] = {}

    def retry_after(self, address: str, now: float) -> float:
        """Seconds before ``address`` may try a join code again (0 when it may now)."""
        times = self._recent(address, now)
        if len(times) < self.limit:
            return 0.0
        return max(times[-self.limit] + self.window_s - now, 0.0)

    def note_wrong(self, address: str, now: float) -> None:
        """``address`` sent a join code that no class has."""
        times = self._recent(address, now)
        self._wrong.pop(address, None)  # to the end: the most recently active
        times.append(now)
        while len(times) > self.limit:
            times.popleft()
        self._wrong[address] = times
        while len(self._wrong) > self.max_addresses:
            del self._wrong[next(iter(self._wrong))]

    def _recent(self, address: str, now: float) -> deque[float]:
        times = self._wrong.get(address, deque())
        while times and times[0] <= now - self.window_s:
            times.popleft()
        if not times:
            self._wrong.pop(address, None)
        return times


@dataclass
class Message:
    """A follower's whole wslink message: its chunks as received and the decoded RPC (None when
    it could not be decoded)."""

    chunks: list[bytes]
    rpc: dict | None


class FollowerGate:
    """The read-only gate of one follower's websocket (see the module docstring)."""

    def __init__(self):
        self._pending: dict[int, tuple[list[bytes], bytearray, int]] = {}

    def add_chunk(self, data: bytes) -> Message | None:
        """Take one binary websocket message; return the message it completes (None until then).

        Raises ValueError for what no wslink client sends (a short chunk, a message over
        :data:`MAX_MESSAGE_BYTES`, chunks that do not fit)."""
        if len(data) < _HEADER:
            raise ValueError("not a wslink chunk (shorter than its header)")
        ident = int.from_bytes(data[0:4], "little")
        offset = int.from_bytes(data[4:8], "little")
        size = int.from_bytes(data[8:12], "little")
        if size > MAX_MESSAGE_BYTES:
            raise ValueError(f"a follower's message of {size} bytes (at most {MAX_MESSAGE_BYTES})")
        chunks, body, received = self._pending.get(ident) or ([], bytearray(size), 0)
        content = data[_HEADER:]
        if len(body) != size or offset + len(content) > size:
            raise ValueError("a wslink chunk that does not fit its message")
        body[offset : offset + len(content)] = content
        chunks.append(bytes(data))
        received += len(content)
        if received < size:
            if ident not in self._pending and len(self._pending) >= MAX_PENDING:
                raise ValueError(f"more than {MAX_PENDING} unfinished messages from a follower")
            self._pending[ident] = (chunks, body, received)
            return None
        self._pending.pop(ident, None)
        return Message(chunks, read_rpc(bytes(body)))

    @staticmethod
    def refusal(rpc: dict | None, driving: bool) -> str:
        """Why a follower may not send ``rpc`` now ("" if it may); ``driving``: whether the
        presenter lets followers drive."""
        if not isinstance(rpc, dict) or not isinstance(rpc.get("method"), str):
            return "not a wslink call"
        method, args = rpc["method"], rpc.get("args")
        if str(rpc.get("id", "")).startswith("system:") and method == "wslink.hello":
            return ""
        if method in ALWAYS:
            return ""
        if method == "trame.lifecycle.update":
            name = args[0] if isinstance(args, list) and args else None
            return "" if name in LIFECYCLE else f"lifecycle {name!r} is not a follower's"
        if method == "trame.trigger" and isinstance(args, list) and args and args[0] == JOINED:
            return ""
        if method not in WHEN_DRIVING:
            return f"{method} is not a follower's to call"
        if method == "trame.state.update":
            keys = _changed_keys(args)
            if keys is None:
                return "a state change that is not a list of keys and values"
            own = sorted(k for k in keys if k.startswith("follow_"))
            if own:
                return f"only the presenter changes {', '.join(own)}"
        if not driving:
            return "read-only: the presenter has not handed over"
        return ""


def _changed_keys(args) -> list[str] | None:
    """The state keys a ``trame.state.update`` call's ``args`` change (None if malformed)."""
    if not isinstance(args, list) or len(args) != 1 or not isinstance(args[0], list):
        return None
    keys = []
    for change in args[0]:
        if not isinstance(change, dict) or not isinstance(change.get("key"), str):
            return None
        keys.append(change["key"])
    return keys


def read_rpc(body: bytes) -> dict | None:
    """A wslink message body (msgpack) as a dict, or None if it is not one."""
    try:
        rpc = msgpack.unpackb(body, raw=False, strict_map_key=False)
    except (ValueError, msgpack.ExtraData, msgpack.FormatError, msgpack.StackError):
        return None
    except Exception:  # msgpack raises its own types for truncated or odd input
        return None
    return rpc if isinstance(rpc, dict) else None


def refusal_reply(rpc: dict | None, reason: str) -> bytes | None:
    """The wslink error a refused call ``rpc`` gets (one chunk), or None when it has no id to
    answer."""
    if not isinstance(rpc, dict) or "id" not in rpc:
        return None
    body = msgpack.packb(
        {
            "wslink": "1.0",
            "id": rpc["id"],
            "error": {"code": READ_ONLY_ERROR, "message": f"racetrace follower: {reason}"},
        }
    )
    ident = secrets.randbits(32).to_bytes(4, "little")
    return ident + (0).to_bytes(4, "little") + len(body).to_bytes(4, "little") + body
