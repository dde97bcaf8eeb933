"""The server log without the noise of browsers that leave: no traceback for a closed connection.

A browser that closes its tab, loses its network or is killed leaves frames queued for a socket
that is closing; sending them fails harmlessly, but asyncio, aiohttp and wslink would each log
the failure with a traceback. :func:`quiet_closed_connections` drops those records (in the front
and in every session process, which share the log) and keeps every other error as it was.
"""

from __future__ import annotations

import asyncio
import logging


def quiet_closed_connections(**_) -> None:
    """Drop the log records of sends to a closed connection in this process's running loop.

    Called from the loop (a trame ``on_server_ready`` callback, or the front's start-up).
    """
    loop = asyncio.get_event_loop()

    def handler(loop, context):
        if _is_closed_connection(context.get("exception")):
            return
        loop.default_exception_handler(context)

    loop.set_exception_handler(handler)
    # aiohttp logs the same failed sends itself, as "Error handling request" with a traceback
    logging.getLogger("aiohttp.server").addFilter(not_a_closed_connection)
    # and wslink logs a failed reply to a closed browser as three error lines without exc_info
    logging.getLogger("wslink.protocol").addFilter(not_a_closed_connection_text)


def _is_closed_connection(error: BaseException | None) -> bool:
    """Whether ``error``, or an error it was raised while handling, is a closed connection."""
    while error is not None:
        if isinstance(error, ConnectionResetError):
            return True
        error = error.__context__
    return False


def not_a_closed_connection(record: logging.LogRecord) -> bool:
    """Logging filter: False for records about a write to a connection that is already closing."""
    return not _is_closed_connection(record.exc_info[1] if record.exc_info else None)


def not_a_closed_connection_text(record: logging.LogRecord) -> bool:
    """Logging filter for wslink: False for its lines about a reply to a closed websocket.

    wslink writes "Exception raised", the exception's repr and the traceback as three records; the
    header alone says nothing, so it is dropped too (a real error still shows its repr and trace).
    """
    text = record.getMessage()
    return not ("closing transport" in text or text == "Exception raised")
