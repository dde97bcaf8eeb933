"""Follow mode, the presenter's side: the join code, the followers counted, hand-over.

A class follows this session from ``/?follow=CODE`` (:mod:`app.serve.follow`): each follower is
one more websocket client of this session process, so it sees what the presenter sees (the case,
the result, the frame, the lesson page, the ball followed) from the state this session publishes
to every client, and the images the view pushes once to all. The front keeps followers read-only
unless the presenter hands over.

State keys:
- ``follow_code``: the join code, made once per session (:func:`new_join_code`); it ends with the
  session.
- ``follow_count``: followers connected now (the front marks their websockets,
  :data:`app.follow_names.FOLLOWER_HEADER`).
- ``follow_presenter``: whether a presenter's page (a websocket the front did not mark as a
  follower's) is connected now. Followers' pages say when the presenter has left: the front ends a
  session whose presenter has been gone for :data:`app.serve.front.IDLE_S`, followers or not.
- ``follow_drive``: whether followers may drive (change the state, press buttons, turn the view);
  the presenter's switch ``#follow-drive``. Followers never change a ``follow_*`` key.

Page: ``#follow-button`` in the toolbar ("class CODE · N following") opens ``#follow-card`` with
the QR code of the follow address (``#follow-qr``, served by the front), the code
(``#follow-code``), the count (``#follow-count``) and the hand-over switch.
"""

from __future__ import annotations

import secrets
import time

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from ..follow_names import FOLLOWER_HEADER, JOINED, QR_NAME
from .base import Component

# no 0/O, 1/I/L: read aloud or copied from a projector without mistakes
CODE_ALPHABET = "ABCDEFGHJKMNPQRSTUVWXYZ23456789"
CODE_LENGTH = 6  # 31**6: about 9e8 codes
JOIN_PUSH_S = 0.5  # a follower joining re-sends the picture on show at most this often


def new_join_code() -> str:
    """A random join code of :data:`CODE_LENGTH` characters of :data:`CODE_ALPHABET`."""
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))


class Follow(Component):
    """Follow mode for one session (see the module docstring)."""

    def __init__(self, session):
        super().__init__(session)
        self._followers: set[str] = set()
        self._presenters: set[str] = set()
        self._last_join_push = -JOIN_PUSH_S
        self.code = new_join_code()

    def init_state(self) -> None:
        s = self.state
        s.follow_code = self.code
        s.follow_count = 0
        s.follow_presenter = False
        s.follow_drive = False

    def bind(self) -> None:
        self.session.server.add_protocol_to_configure(self._configure_protocol)
        self.ctrl.trigger(JOINED)(self.guarded(self._on_joined))

    def _on_joined(self) -> None:
        """A follower's page is connected: push the picture on show (a follower does not size
        the render, which is what pushes a first image to a new page), at most every
        :data:`JOIN_PUSH_S` seconds whatever followers send."""
        now = time.monotonic()
        if now - self._last_join_push >= JOIN_PUSH_S:
            self._last_join_push = now
            self.ctrl.push_view()

    def status(self) -> dict:
        """What the front asks before it lets a follower's change through: the join code and
        whether followers may drive now."""
        return {"code": self.code, "drive": self.state.follow_drive is True}

    def _configure_protocol(self, protocol) -> None:
        connect, close = protocol.onConnect, protocol.onClose

        def on_connect(request, client_id):
            connect(request, client_id)
            if request.headers.get(FOLLOWER_HEADER) == "1":
                self._followers.add(client_id)
            else:
                self._presenters.add(client_id)
            self._count()

        def on_close(client_id):
            close(client_id)
            self._followers.discard(client_id)
            self._presenters.discard(client_id)
            self._count()

        protocol.onConnect, protocol.onClose = on_connect, on_close

    def _count(self) -> None:
        with self.state:
            self.state.follow_count = len(self._followers)
            self.state.follow_presenter = bool(self._presenters)

    def build_toolbar(self) -> None:
        """``#follow-button`` and the card it opens."""
        with v3.VMenu(close_on_content_click=False, location="bottom end"):
            with v3.Template(v_slot_activator="{ props }"):
                v3.VBtn(
                    "class {{ follow_code }} · {{ follow_count }} following",
                    v_bind="props",
                    id="follow-button",
                    prepend_icon="mdi-account-group",
                    size="small",
                    variant="text",
                    classes="mr-2",
                    title="Let a class follow this page",
                )
            with v3.VCard(id="follow-card", width=300, classes="pa-3"):
                html.Div("Follow this page", classes="text-subtitle-1")
                html.Img(
                    src=QR_NAME,
                    id="follow-qr",
                    alt="QR code of the follow address",
                    style="width: 100%; image-rendering: pixelated;",
                )
                html.Div(
                    "join code {{ follow_code }}",
                    id="follow-code",
                    classes="text-h6 text-center",
                )
                html.Div(
                    "scan the code, or open this server's address with ?follow={{ follow_code }}",
                    classes="text-caption",
                )
                html.Div(
                    "{{ follow_count }} following", id="follow-count", classes="text-body-2 mt-1"
                )
                v3.VSwitch(
                    v_model=("follow_drive",),
                    label="followers may drive",
                    id="follow-drive",
                    density="compact",
                    hide_details=True,
                    color="primary",
                )
                html.Div(
                    "{{ follow_drive ? 'followers can change what is shown' "
                    ": 'followers watch, read-only' }}",
                    classes="text-caption",
                )
