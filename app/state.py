"""One session of the app: its trame state and the components that handle it (testable without a
browser).

:class:`RacetraceApp` composes the session's components (:mod:`app.components`): the case form
(``form``), the result on show with its scene, charts and time controls (``result``), the bearing
set on show (``set_panel``: the set along the shaft, its load sharing and stiffness), the saved
runs and the background run (``runs``), the comparison with a saved run (``compare``), the
exports (``exports``), the studies (``studies``), the Lessons panel with presenter mode
(``lessons``, :mod:`app.lessons.panel`) and follow mode (``follow``: join code, followers,
hand-over). Process-wide services (the run store and the solver
pool, :mod:`app.services`) are shared with the other sessions. Each component builds its own
section of the page, bound to its own state keys and controller actions, and :mod:`app.ui`
arranges the sections; each component's module lists its keys. The session itself keeps
``status`` (ends in ``done``, ``cancelled`` or ``error: ...``) and counts the connected browsers.
"""

from __future__ import annotations

from pathlib import Path

from .components import CaseForm, Compare, Export, Live, ResultView, Runs, SetPanel, Studies
from .components.export import EXPORT_URL
from .components.follow import Follow
from .fan_out import publish_once
from .lessons.panel import LessonController
from .services import Services

DEFAULT_CASE = "spindle-combined-load"


class RacetraceApp:
    """State and handlers of one racetrace page.

    ``server``: a trame server (``trame.app.get_server``); ``runs_dir``: runs folder (default
    :func:`app.run_store.default_runs_dir`), used when no ``services`` are given; ``render``: build
    the pyvista scene (False in pure state tests); ``window_size``: 3-D view size in pixels;
    ``render_mode``: who draws the 3-D view, ``"browser"`` (where the page has WebGL) or
    ``"server"`` (:mod:`app.components.browser_view`).
    """

    EXPORT_URL = EXPORT_URL

    def __init__(
        self,
        server,
        runs_dir: str | Path | None = None,
        render: bool = True,
        window_size=(650, 480),
        services: Services | None = None,
        render_mode: str = "browser",
    ):
        self.server = server
        self.state, self.ctrl = server.state, server.controller
        self.services = services if services is not None else Services(runs_dir)
        self.clients = 0  # connected browsers
        self._client_ids = set()
        self.form = CaseForm(self)
        self.result = ResultView(
            self, render=render, window_size=window_size, render_mode=render_mode
        )
        self.set_panel = SetPanel(self)
        self.runs = Runs(self)
        self.live = Live(self)
        self.compare = Compare(self)
        self.exports = Export(self)
        self.studies = Studies(self)
        self.lessons = LessonController(self)
        self.follow = Follow(self)
        self.components = (
            self.form,
            self.result,
            self.set_panel,
            self.runs,
            self.live,
            self.compare,
            self.exports,
            self.studies,
            self.lessons,
            self.follow,
        )
        self.state.status = "starting"
        for component in self.components:
            component.init_state()
        for component in self.components:
            component.provide()
            component.bind()
        # Count browser connections at the websocket level: the page's own "exited" signal is not
        # sent when a browser is killed, and a play loop without viewers floods the log.
        self.server.add_protocol_to_configure(self._configure_protocol)

    @property
    def store(self):
        """The runs folder (:class:`app.run_store.RunStore`), shared by every session."""
        return self.services.store

    @property
    def exports_dir(self) -> Path:
        return self.exports.exports_dir

    def start(self, case_name: str = DEFAULT_CASE, play: bool = True) -> None:
        """Open ``case_name`` solved (quasi-static) before the first page is served."""
        self.form.open_first(case_name)
        self.state.playing = play

    def _configure_protocol(self, protocol) -> None:
        connect, close = protocol.onConnect, protocol.onClose

        def on_connect(request, client_id):
            connect(request, client_id)
            publish_once(protocol)  # one packing per published message, whatever the pages
            self._client_ids.add(client_id)
            self.clients = len(self._client_ids)
            self.result._on_playing(self.state.playing)
            self.runs.watch()

        def on_close(client_id):
            close(client_id)
            self._client_ids.discard(client_id)
            self.clients = len(self._client_ids)
            with self.state:
                self.live.client_count(self.clients)  # a live session ends with its page

        protocol.onConnect, protocol.onClose = on_connect, on_close

    def shutdown(self) -> None:
        """Stop the background run and the animation."""
        for component in self.components:
            component.shutdown()
