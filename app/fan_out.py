"""What a session publishes to its pages is serialised once, whatever the number of pages.

trame publishes a state change (a played frame: ``frame``, ``rt3d_frame``, the time words) or an
image of the server-rendered view through wslink, whose handler packs the message (msgpack) and
schedules its sending once per connected page: with a presenter and 30 followers, 31 packings and
31 tasks for the same bytes. A change a page made is echoed to the other pages; there each of
wslink's N per-page tasks sends to every page but the one that made it, so each other page
receives it N times.

:func:`publish_once` gives a session's protocols a publish that packs a message once and writes
the same chunks to each page's websocket in one task (wslink's framing: ``publish:TOPIC:0``
ids, chunks of at most wslink's message size, one message's chunks at a time under the
handler's lock); a page whose websocket fails while the message is on its way does not stop the
others from getting it. It is installed when the first page connects (wslink's handler, whose
publish the protocols hold, exists from then on).
"""

from __future__ import annotations

import logging

import msgpack
from wslink.chunking import generate_chunks
from wslink.core import schedule_coroutine
from wslink.protocol import MAX_MSG_SIZE

log = logging.getLogger("racetrace.fan_out")


def publish_once(protocol) -> bool:
    """Replace the wslink handler's publish held by ``protocol`` (trame's root protocol) and its
    link protocols by :class:`FanOut`'s; returns whether it did now (False when it was done
    already, or when no handler is there yet)."""
    handler = getattr(getattr(protocol, "publish", None), "__self__", None)
    if isinstance(handler, FanOut):
        return False
    needed = ("getAuthenticatedWebsockets", "network_monitor", "attachment_atomic")
    if handler is None or not all(hasattr(handler, name) for name in needed):
        return False  # another wslink than the one this was written for: its own publish stays
    fan_out = FanOut(handler)
    for link in {id(p): p for p in [protocol, *protocol.getLinkProtocols()]}.values():
        if getattr(link.publish, "__self__", None) is handler:
            link.publish = fan_out.publish
    return True


class FanOut:
    """Publishing for one wslink handler (:class:`wslink.protocol.WslinkHandler`)."""

    def __init__(self, handler):
        self.handler = handler
        self.packed = 0  # messages packed (one per publish)

    def publish(self, topic, data, client_id=None, skip_last_active_client=False) -> None:
        """wslink's ``publish``: to ``client_id`` only, or to every page (but the one whose
        call is being answered, with ``skip_last_active_client``)."""
        monitor = self.handler.network_monitor
        monitor.on_enter()
        schedule_coroutine(
            0,
            self._send,
            f"publish:{topic}:0",
            data,
            client_id,
            skip_last_active_client,
            done_callback=monitor.on_exit,
        )

    async def _send(self, rpcid: str, data, client_id, skip_last_active_client) -> None:
        handler = self.handler
        try:
            packed = msgpack.packb({"wslink": "1.0", "id": rpcid, "result": data})
        except Exception:  # a task's exception would go unseen: logged with what it was
            log.exception("a published message could not be packed (%s)", rpcid)
            return
        self.packed += 1
        sockets = [
            ws
            for ws in handler.getAuthenticatedWebsockets(client_id, skip_last_active_client)
            if ws is not None
        ]
        if not sockets:
            return
        failed = set()  # pages whose websocket failed: they get no more chunks of it
        with handler.network_monitor:
            async with handler.attachment_atomic:
                for chunk in generate_chunks(packed, MAX_MSG_SIZE):
                    for ws in sockets:
                        if ws.closed or id(ws) in failed:
                            continue
                        try:
                            await ws.send_bytes(chunk)
                        except (ConnectionError, RuntimeError) as error:
                            failed.add(id(ws))
                            log.debug("a page left while a message was on its way: %s", error)
        handler.network_monitor.network_call_completed()
