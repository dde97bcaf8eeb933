"""One session of ``racetrace serve`` in its own process: a trame server on a loopback port.

Started by the front server (:mod:`app.serve.front`), which relays one browser (or, with
``--shared``, every browser) to it: forked from the front's pre-imported fork server
(:mod:`app.serve.forkserver`), or as a new Python process with the command below. The process
ends with its parent: when the front ends, even killed, the session saves a run in progress
(marked incomplete) and stops its solver process.

A session listens on 127.0.0.1 only, and answers only requests that carry the secret the front
gave it (:mod:`app.serve.session_guard`): the front is its only client.

``RACETRACE_SESSION_SECRET=... python -m app.serve.session_process --port P [--runs-dir D]
[--case NAME] [--slots-dir S] [--max-runs N] [--render browser|server]``
"""

from __future__ import annotations

import argparse
import os
import sys

HOST = "127.0.0.1"  # whatever address the front serves on


def main(argv=None, secret: str | None = None) -> int:
    """Run one session until SIGTERM. ``argv``: the options above; ``secret``: the front's
    secret for this session (default: taken out of the environment variable
    :data:`app.serve.session_guard.SECRET_ENV`)."""
    from .session_guard import SECRET_ENV

    secret = secret or os.environ.pop(SECRET_ENV, "")  # the solver processes do not need it
    p = argparse.ArgumentParser(prog="python -m app.serve.session_process")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--runs-dir", default=None)
    p.add_argument("--case", default=None)
    p.add_argument("--slots-dir", default=None)
    p.add_argument("--max-runs", type=int, default=None)
    p.add_argument("--render", choices=("browser", "server"), default="browser")
    args = p.parse_args(argv)
    if not secret:
        p.error(f"no session secret in ${SECRET_ENV}: sessions are started by racetrace serve")
    _trame_options_only(trame_options(args.port))
    from ..process import die_with_parent

    die_with_parent()
    from viz.offscreen import configure_environment

    configure_environment()
    import pyvista as pv
    from trame.app import get_server

    from ..access import Access
    from ..services import Services
    from ..state import DEFAULT_CASE, RacetraceApp
    from ..ui import build_ui
    from .follow import STATUS_PATH
    from .quiet_log import quiet_closed_connections
    from .session_guard import front_only

    pv.global_theme.multi_samples = 0
    server = get_server("racetrace", client_type="vue3")
    services = Services(args.runs_dir, slots_dir=args.slots_dir, max_runs=args.max_runs)
    app = RacetraceApp(server, services=services, render_mode=args.render)
    app.start(args.case or DEFAULT_CASE)
    app.exports_dir.mkdir(parents=True, exist_ok=True)
    server.enable_module({"serve": {app.EXPORT_URL: str(app.exports_dir)}})
    build_ui(app)

    def guard(ws_server, **_):
        if ws_server.host != HOST:  # a trame option read from elsewhere would be a hole
            raise RuntimeError(f"the session would listen on {ws_server.host}, not {HOST}")
        # only the front's relay (which checked the browser) may use this session
        ws_server.app.middlewares.append(front_only(secret, Access(HOST)))
        # the front reads the join code and the hand-over here (app.serve.follow)
        ws_server.app.router.add_get(STATUS_PATH, follow_status)

    async def follow_status(_request):
        from aiohttp import web

        return web.json_response(app.follow.status(), headers={"Cache-Control": "no-store"})

    server.controller.on_server_bind.add(guard)
    server.controller.on_server_ready.add(quiet_closed_connections)
    try:
        server.start(
            host=HOST,
            port=args.port,
            open_browser=False,
            show_connection_info=False,
            disable_logging=True,
        )
    finally:
        app.shutdown()
    return 0


def trame_options(port: int) -> list[str]:
    """The session's trame server options: listen on 127.0.0.1:``port``, and never stop on its
    own (wslink stops a server after 300 s without a websocket by default; the front decides
    when a session ends, :data:`app.serve.front.IDLE_S`)."""
    return ["--host", HOST, "--port", str(port), "--timeout", "0"]


def _trame_options_only(options: list[str]) -> None:
    """Make trame's server read ``options``, and only them, as its command line.

    trame parses ``sys.argv`` (or ``--trame-args``, or ``$TRAME_ARGS``) when it starts, and an
    option found there wins over the arguments of ``server.start``. A forked session still holds
    the front's ``sys.argv`` (``racetrace serve --host 0.0.0.0 ...``), so trame would listen on
    the front's address; a new process holds this module's own options. Both are this process's
    to replace: its options are parsed already.
    """
    del sys.argv[1:]
    os.environ["TRAME_ARGS"] = " ".join(options)


if __name__ == "__main__":
    sys.exit(main())
