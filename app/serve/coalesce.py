"""A browser that is behind its session gets only the newest state, not every stale one.

The front holds what a session has sent a browser that the browser has not taken yet
(:func:`app.serve.front._pump_to_browser`): a page whose main thread is busy (drawing the 3-D view
in software WebGL takes a third of a second) stops reading its websocket, and the messages wait
here (:class:`Backlog`). While they wait, a run of consecutive trame state publishes is merged
into one message: the later value of a key wins, every key is kept. The page then jumps to the
newest frame instead of playing every stale one, and what waits shrinks to one frame's state.

For the messages to wait here, where they can merge, rather than in the buffers on the way (a
browser's socket held 3.5 MB, seconds of frames, once it had read a 4 MB state quickly on
joining), every page the front serves says how many messages it has taken (:data:`READ_SCRIPT`,
:class:`PageReads`), and the front has at most :data:`READ_WINDOW` of them on their way to it;
the socket's send buffer is kept small as well (:func:`hold_at_front`). A client that does not
say (a script, the benchmarks' websocket clients) is sent everything at once.

A message is taken once the page has applied it **and drawn it**: counted at the first task
after the second animation frame after it (the 3-D view draws its changes in that frame's
callback, :mod:`app.components.browser_view`, and in software WebGL the browser's paint then
waits for the drawing). Why: measured in a headless Chromium follower of a playing presenter
(software WebGL, a loaded 2-core machine; ``performance.now()`` around the page's applying, its
animation frame callbacks and the first task after them), a played frame costs the page an apply
of about 100 ms (trame, Vue, vtk.js) and a drawing of 250-400 ms (SwiftShader; the main thread
waits for it in the paint). Counted when applied, the next messages were sent while the page
still drew the last one and waited behind that drawing: they were a drawing old when applied.
Counted once drawn, the message the front sends carries the session's state of the moment the
page finished a drawing (in the probe, 0 frames behind the presenter's session when applied,
median, against 11-18 frames before). A window of one message for a page whose drawing is slow
was tried as well and not kept: with the round trip to the front and back added to every drawing,
the Chromium follower of ``benchmarks/follow.py`` stalled in three runs of three (5-12 frames
shown in 30 s, against 56 without it).

What is merged: a whole wslink message in one chunk (header: id, offset 0, size), whose msgpack
body is ``{"wslink": ..., "id": "publish:trame.state.topic:N", "result": {key: value, ...}}`` —
what trame publishes for a state change (``trame_server.protocol.push_state_change``, sent by
:mod:`app.fan_out`). Merging is right because a state message carries whole values: trame itself
sends a key only when its value differs from the last one sent, so a page that applies only the
last of several values of a key shows what it would show after applying all of them. Every key
the app publishes is a whole value (a played frame's matrices, ellipses and painted-quad counts;
the charts' figures; the live tracks sent whole), none a delta to add to the previous one.

A picture of the server-rendered view (trame-rca's ``publish:trame.rca.topic.stream:N``, whose
body's ``result`` is ``{"name": view, "meta": {"type": "image/...", ...}, "content": bytes}``)
is a whole picture: a later picture of the same view replaces a waiting one, which is dropped.
Without that, a page slower than the session's pictures (about 20 a second while playing) fell
behind for good: a picture between each two frames' states kept them from merging, and what
waited grew by a megabyte a second (measured: a Chromium page at a CPU throttling of 8 had 3 659
messages, 70 MB, waiting after a minute of play). State publishes that a dropped picture kept
apart then merge. A video stream's packets (type ``application/octet-stream``) build on each other
and are barriers.

Everything else is a barrier, kept whole and in order: RPC replies and errors, other topics
(trame's actions), a message in several chunks, text, and anything that does not decode as
above. A state publish is never merged across a barrier.

A frame that must be seen at once (a live control change's first frame) is a state publish
that carries :data:`app.front_keys.URGENT_KEY`: it does not wait for the page to take what is on
its way. Measured in live mode (``benchmarks/live_app.py``, a quiet machine): with the window
full, such a frame waited at the front 0-170 ms (median 65 ms) for the page to finish drawing
the frames before it, which it would then have drawn first. It goes at once, past the window
(what waits before it goes with it, merged where it can be), and the page draws it at its next
animation frame.

Only what waits is merged: a message is merged into the one before it only while that one waits
behind a message on its way (the writer is sending, or waits for the page to take what it was
sent); messages that came at once while nothing was on its way are merged only once the page is
behind (it had to be waited for). A browser that keeps up gets the session's bytes unchanged and
costs no decoding.
"""

from __future__ import annotations

import asyncio
import contextlib
import secrets
import socket
from collections import deque
from dataclasses import dataclass

import msgpack
from aiohttp import WSMsgType
from wslink.protocol import MAX_MSG_SIZE

from ..front_keys import URGENT_KEY

#: the id of a trame state publish starts with this (then wslink's publish count)
STATE_ID_PREFIX = "publish:trame.state.topic:"
_STATE_ID = STATE_ID_PREFIX.encode()
#: the id of a picture of a server-rendered view (trame-rca's stream topic) starts with this
PICTURE_ID_PREFIX = "publish:trame.rca.topic.stream:"
_PICTURE_ID = PICTURE_ID_PREFIX.encode()
_HEADER = 12  # wslink's chunk header: message id, offset, total size (little-endian uint32 each)
_ID_WITHIN = 64  # the id is among a body's first bytes: {"wslink": "1.0", "id": ...}
#: What the front hands the operating system for one browser before it waits (bytes): the socket's
#: send buffer and the transport's buffer above it. Messages beyond it wait in :class:`Backlog`,
#: where they merge; on its own, the kernel grows a loopback socket's send buffer to megabytes,
#: seconds of frames that a slow page would still play one by one.
SEND_BUFFER_BYTES = 64 * 1024
#: A page served by the front says how many websocket messages it has taken, as a text message
#: ``racetrace-read:N`` (:data:`READ_SCRIPT`); the front then has at most :data:`READ_WINDOW`
#: messages on their way to it (in the kernel's buffers, the browser's, the page's task queue):
#: a page in software WebGL on a loaded machine takes about one message a second, so every
#: message more on its way is a second more behind.
READ_PREFIX = "racetrace-read:"
READ_WINDOW = 2
_URGENT = URGENT_KEY.encode()  # an urgent state publish (app.front_keys): sent past the window
#: A page that gets no animation frame (a hidden tab) counts what it applied after this (ms).
DRAWN_FALLBACK_MS = 1000


@dataclass
class _Waiting:
    """A message waiting for the browser: its websocket type and bytes (None while a merge is
    not packed yet); ``size``: its bytes, or at most that many while not packed; for a state
    publish, its id and state (decoded when a message comes after it; ``state`` None: a
    barrier), and its size when last packed."""

    type: WSMsgType
    data: bytes | str | None
    size: int
    decoded: bool = False
    rpc_id: str = ""
    state: dict | None = None
    packed_size: int = 0
    picture_of: str | None = None  # the view it is a whole picture of (decoded)
    urgent: bool = False  # a state publish carrying URGENT_KEY, or merged with one

    def decode(self) -> None:
        """Find out, once, whether this is a state publish or a whole picture of a view."""
        if self.decoded:
            return
        self.decoded = True
        found = state_publish(self.type, self.data)
        if found is not None:
            self.rpc_id, self.state = found
            self.packed_size = self.size
        else:
            self.picture_of = picture_view(self.type, self.data)

    def find_urgent(self) -> None:
        """Whether this is an urgent state publish (:data:`URGENT_KEY`): decoded only when its
        bytes hold the key's name."""
        if isinstance(self.data, bytes) and _URGENT in self.data:
            self.decode()
            self.urgent = self.state is not None and URGENT_KEY in self.state

    def pack(self) -> None:
        """Pack the merged state into :attr:`data`; :attr:`size` is then exact."""
        self.data = state_message(self.rpc_id, self.state)
        self.size = self.packed_size = len(self.data)


def state_publish(message_type: WSMsgType, data: bytes | str) -> tuple[str, dict] | None:
    """``(id, state)`` of a wslink message that is a whole trame state publish in one chunk;
    None for anything else (a barrier)."""
    body = _one_chunk_body(message_type, data, _STATE_ID)
    if body is None:
        return None
    rpc_id, state = body["id"], body["result"]
    if not isinstance(state, dict) or not all(isinstance(k, str) for k in state):
        return None
    return rpc_id, state


def _one_chunk_body(message_type: WSMsgType, data: bytes | str, id_prefix: bytes) -> dict | None:
    """The msgpack body of a wslink message in one chunk whose id starts with ``id_prefix``
    (``{"wslink", "id", "result"}``); None for anything else."""
    if message_type != WSMsgType.BINARY or len(data) <= _HEADER:
        return None
    offset = int.from_bytes(data[4:8], "little")
    size = int.from_bytes(data[8:12], "little")
    if offset != 0 or size != len(data) - _HEADER:
        return None  # one chunk of a message in several: kept whole
    if id_prefix not in data[_HEADER : _HEADER + _ID_WITHIN]:
        return None  # not of this kind: not decoded
    try:
        body = msgpack.unpackb(data[_HEADER:], raw=False, strict_map_key=False)
    except Exception:  # msgpack raises several types for what is not msgpack
        return None
    if not isinstance(body, dict) or set(body) != {"wslink", "id", "result"}:
        return None
    if not isinstance(body["id"], str) or not body["id"].startswith(id_prefix.decode()):
        return None
    return body


def picture_view(message_type: WSMsgType, data: bytes | str) -> str | None:
    """The name of the view that a wslink message is one whole picture of (a trame-rca stream
    publish of an image, in one chunk); None for anything else (a video packet, a barrier)."""
    body = _one_chunk_body(message_type, data, _PICTURE_ID)
    if body is None:
        return None
    result = body["result"]
    if not isinstance(result, dict):
        return None
    name, meta = result.get("name"), result.get("meta")
    if not isinstance(name, str) or not isinstance(meta, dict):
        return None
    kind = meta.get("type")
    return name if isinstance(kind, str) and kind.startswith("image/") else None


def state_message(rpc_id: str, state: dict) -> bytes:
    """A trame state publish of ``state`` with id ``rpc_id``, as one wslink chunk."""
    body = msgpack.packb({"wslink": "1.0", "id": rpc_id, "result": state})
    header = secrets.randbits(32).to_bytes(4, "little") + (0).to_bytes(4, "little")
    return header + len(body).to_bytes(4, "little") + body


# Added to every page the front serves, before the page's own scripts.
#
# The page's websocket receives binary messages as ArrayBuffers, not Blobs. trame's client asks
# for Blobs and reads each message in two asynchronous Blob reads (its header, then its body)
# before it applies it; in Chromium a Blob read goes through the browser process, and a live
# change's frame was applied 40-120 ms after it came (measured, benchmarks/live_app.py, a quiet
# machine), most of it in those reads. Here a page that asks for Blobs gets, in their place,
# views of the received ArrayBuffer that answer trame's reads (``slice``, ``size``,
# ``arrayBuffer``) at once, so a message is applied in the task that receives it. A page that
# asks for ArrayBuffers gets them as they come.
#
# The page counts the websocket messages it has taken and says so every READ_WINDOW / 2 of them.
# A message is taken once the page has applied it (by the task after the one that received it)
# and drawn it: the 3-D view draws at the second animation frame after a change
# (app.components.browser_view) and the browser then paints (in software WebGL the paint waits
# for the drawing), so the count goes at the first task after the second animation frame after
# it, or after DRAWN_FALLBACK_MS for a page that gets no animation frame (a hidden tab).
def _script(text: str) -> str:
    """``text`` with the page's constants filled in."""
    for name, value in (
        ("__EVERY__", max(1, READ_WINDOW // 2)),
        ("__FALLBACK__", DRAWN_FALLBACK_MS),
        ("__PREFIX__", READ_PREFIX),
    ):
        text = text.replace(name, str(value))
    return text


READ_SCRIPT = _script("""<script>
(function () {
  var Native = window.WebSocket, every = __EVERY__, fallback = __FALLBACK__;
  // bytes start to end of a received ArrayBuffer, read as trame reads a Blob
  function Received(buffer, start, end) {
    this.buffer = buffer; this.start = start; this.size = end - start;
  }
  Received.prototype.slice = function (from, to) {
    var size = this.size;
    function at(k, otherwise) {
      if (k === undefined) return otherwise;
      return k < 0 ? Math.max(size + k, 0) : Math.min(k, size);
    }
    var a = at(from, 0), b = Math.max(a, at(to, size));
    return new Received(this.buffer, this.start + a, this.start + b);
  };
  Received.prototype.arrayBuffer = function () {
    return Promise.resolve(this.buffer.slice(this.start, this.start + this.size));
  };
  window.WebSocket = class extends Native {
    constructor(url, protocols) {
      super(url, protocols);
      var socket = this, asksBlobs = true, onmessage = null, wrapped = new Map();
      var taken = 0, told = 0, applied = 0, timer = 0, frame = 0;
      Object.getOwnPropertyDescriptor(Native.prototype, 'binaryType').set.call(this, 'arraybuffer');
      Object.defineProperty(this, 'binaryType', {
        get: function () { return asksBlobs ? 'blob' : 'arraybuffer'; },
        set: function (kind) { asksBlobs = kind === 'blob'; },
      });
      function forPage(event) {  // what the page's code is given for a received message
        var data = event.data;
        if (!(asksBlobs && data instanceof ArrayBuffer)) return event;
        return { type: 'message', data: new Received(data, 0, data.byteLength), target: socket,
                 currentTarget: socket, origin: event.origin, lastEventId: event.lastEventId,
                 timeStamp: event.timeStamp, ports: [] };
      }
      Object.defineProperty(this, 'onmessage', {
        get: function () { return onmessage; },
        set: function (handler) { onmessage = typeof handler === 'function' ? handler : null; },
      });
      this.addEventListener = function (type, listener, options) {
        if (type !== 'message' || typeof listener !== 'function') {
          return Native.prototype.addEventListener.call(this, type, listener, options);
        }
        if (!wrapped.has(listener)) {
          wrapped.set(listener, function (event) { return listener.call(socket, forPage(event)); });
        }
        return Native.prototype.addEventListener.call(this, type, wrapped.get(listener), options);
      };
      this.removeEventListener = function (type, listener, options) {
        var inner = type === 'message' && wrapped.get(listener);
        return Native.prototype.removeEventListener.call(this, type, inner || listener, options);
      };
      function tell() { told = taken; socket.send('__PREFIX__' + taken); }
      function drawn(upto) {
        clearTimeout(timer);
        cancelAnimationFrame(frame);
        timer = frame = 0;
        taken = Math.max(taken, upto);
        if (taken - told >= every && socket.readyState === 1) tell();
        if (applied > taken) watch();
      }
      function watch() {  // what was applied before the next animation frame, once drawn
        timer = setTimeout(function () { drawn(applied); }, fallback);
        frame = requestAnimationFrame(function () {
          var upto = applied;
          frame = requestAnimationFrame(function () {
            frame = 0;
            setTimeout(function () { drawn(upto); }, 0);
          });
        });
      }
      function took() {
        applied += 1;
        if (!timer) watch();
      }
      Native.prototype.addEventListener.call(this, 'message', function (event) {
        if (onmessage) onmessage.call(socket, forPage(event));
        setTimeout(took, 0);  // trame applies it in this task's microtasks
      });
      Native.prototype.addEventListener.call(this, 'open', tell);
    }
  };
})();
</script>""")


def with_read_script(page: str) -> str:
    """``page`` (HTML) with :data:`READ_SCRIPT` first in its head."""
    head = page.find("<head>")
    if head < 0:
        return READ_SCRIPT + page
    return page[: head + 6] + READ_SCRIPT + page[head + 6 :]


class PageReads:
    """What the front has sent one page and what the page says it has taken
    (:data:`READ_PREFIX`). A page that never says (a client without :data:`READ_SCRIPT`) is
    sent everything at once, as before; one that does has at most ``window`` messages on their
    way, the rest wait in its :class:`Backlog`, where they merge."""

    def __init__(self, window: int = READ_WINDOW):
        self.window = window
        self.sent = 0  # messages sent to the page
        self.taken = 0  # messages the page says it has taken
        self.counting = False  # the page says what it has taken
        self._changed = asyncio.Event()

    def note(self, text: str) -> bool:
        """Take a text message from the page: whether it was the page's count (then it is the
        front's, not the session's)."""
        if not text.startswith(READ_PREFIX):
            return False
        try:
            taken = int(text[len(READ_PREFIX) :])
        except ValueError:
            return True
        self.counting = True
        self.taken = max(self.taken, min(taken, self.sent))
        self._changed.set()
        return True

    async def room(self, urgent=lambda: False) -> bool:
        """Wait until another message may go to the page, or ``urgent()`` says that one must go
        now (:meth:`urge` wakes the wait to ask); whether it had to wait."""
        waited = False
        while self.counting and self.sent - self.taken >= self.window and not urgent():
            waited = True
            self._changed.clear()
            await self._changed.wait()
        return waited

    def urge(self) -> None:
        """Something urgent waits: :meth:`room` asks its ``urgent`` again."""
        self._changed.set()

    def stop(self) -> None:
        """No more waiting for the page (its socket closes): :meth:`room` returns at once."""
        self.counting = False
        self._changed.set()


def hold_at_front(transport) -> None:
    """Keep what waits for the browser on ``transport`` (an asyncio transport) at the front: at
    most :data:`SEND_BUFFER_BYTES` in the socket's send buffer (Linux doubles what is asked) and
    in the transport's buffer; nothing is done for a transport without a socket."""
    if transport is None:
        return
    sock = transport.get_extra_info("socket")
    if sock is not None:
        with contextlib.suppress(OSError):
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SEND_BUFFER_BYTES)
    with contextlib.suppress(AttributeError, NotImplementedError, ValueError):
        transport.set_write_buffer_limits(high=SEND_BUFFER_BYTES // 4)


class Backlog:
    """The messages a session sent one browser that the browser has not taken yet, in order
    (see the module docstring). The reader of the session's websocket calls :meth:`put`; the
    browser's writer calls :meth:`get` for the next message to send, and comes back for another
    once it is sent."""

    def __init__(self):
        self._waiting: deque[_Waiting] = deque()
        self._wake = asyncio.Event()
        self._writer_waits = True  # the writer waits in get(): nothing is on its way
        self._closed = False
        self.bytes = 0  # the waiting messages' bytes (at most: merges are packed when sent)
        self.merged = 0  # messages merged into a later one (never sent as they came)
        self.replaced = 0  # pictures dropped for a later one of the same view
        self.urgent = 0  # urgent messages waiting (URGENT_KEY), merged ones counted once each

    def __len__(self) -> int:
        return len(self._waiting)

    def put(self, message_type: WSMsgType, data: bytes | str) -> bool:
        """Add a message the session sent; merged into the last waiting one when both are state
        publishes and that one waits behind a message on its way; a picture that comes so drops
        the waiting pictures of its view (:meth:`_drop_replaced_pictures`). Whether it is
        urgent (:data:`URGENT_KEY`)."""
        item = _Waiting(message_type, data, len(data))
        item.find_urgent()
        self.urgent += item.urgent
        waits = bool(self._waiting) and not self._writer_waits
        if waits and self._merge(self._waiting[-1], item):
            return item.urgent
        self._waiting.append(item)
        self.bytes += item.size
        if waits:
            item.decode()  # once: the merge tried above may have decoded it
            if item.picture_of is not None:
                self._drop_replaced_pictures()
        self._wake.set()
        return item.urgent

    def _drop_replaced_pictures(self) -> None:
        """Drop every waiting picture that a later waiting picture of the same view replaces;
        the state publishes on either side of a dropped picture merge."""
        newest: set[str] = set()
        k = len(self._waiting) - 1
        while k >= 0:
            waiting = self._waiting[k]
            waiting.decode()
            view = waiting.picture_of
            if view is not None and view in newest:
                del self._waiting[k]
                self.bytes -= waiting.size
                self.replaced += 1
                if 0 < k < len(self._waiting) and self._merge(
                    self._waiting[k - 1], self._waiting[k]
                ):
                    self.bytes -= self._waiting[k].size
                    del self._waiting[k]
            elif view is not None:
                newest.add(view)
            k -= 1

    def _merge(self, into: _Waiting, item: _Waiting) -> bool:
        """Merge ``item`` into ``into`` (the message before it) when both are state publishes
        (``self.bytes`` counts ``into`` as merged, and no longer ``item``)."""
        if into.size + item.size > MAX_MSG_SIZE:
            return False  # the two together could be more than one wslink chunk
        for waiting in (into, item):
            waiting.decode()
            if waiting.state is None:
                return False  # a barrier or a picture
        into.state.update(item.state)  # the later value of a key wins; every key is kept
        into.rpc_id = item.rpc_id
        self.urgent -= into.urgent and item.urgent  # the two are one urgent message now
        into.urgent = into.urgent or item.urgent
        self.merged += 1
        # packed when sent; before that only when its bound doubled since it was last packed
        # (the merged state is at most the sum of the two): packing costs at most twice what
        # arrives, not a whole chart figure per merged frame
        before = into.size
        into.data, into.size = None, into.size + item.size
        if into.size > 2 * into.packed_size:
            into.pack()
        self.bytes += into.size - before
        return True

    async def get(self, behind: bool = False) -> tuple[WSMsgType, bytes | str] | None:
        """The next message to send (type, data), oldest first; None once :meth:`close` was
        called and nothing waits. ``behind``: the browser is behind (it has not said that it
        took what is on its way): the waiting pictures a later one replaces are dropped and the
        state publishes that wait at the head are merged first, those that came at once while
        nothing was on its way too."""
        self._writer_waits = True
        while not self._waiting:
            if self._closed:
                return None
            self._wake.clear()
            await self._wake.wait()
        self._writer_waits = False
        if behind:
            self._drop_replaced_pictures()
        head = self._waiting[0]
        while behind and len(self._waiting) > 1 and self._merge(head, self._waiting[1]):
            self.bytes -= self._waiting[1].size
            del self._waiting[1]
        self._waiting.popleft()
        self.bytes -= head.size
        self.urgent -= head.urgent
        if head.data is None:
            head.pack()
        return head.type, head.data

    def drop(self) -> None:
        """Forget every waiting message (the browser is closed as too slow)."""
        self._waiting.clear()
        self.bytes = self.urgent = 0

    def close(self) -> None:
        """No more messages: :meth:`get` returns None once the waiting ones are taken."""
        self._closed = True
        self._wake.set()
