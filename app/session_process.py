"""One session of ``racetrace serve`` in its own process: a trame server on a loopback port.

Started by the front server (:mod:`app.front`), which relays one browser (or, with ``--shared``,
every browser) to it: forked from the front's pre-imported fork server
(:mod:`app.services.forkserver`), or as a new Python process with the command below. The process
ends with its parent: when the front ends, even killed, the session saves a run in progress
(marked incomplete) and stops its solver process.

``python -m app.session_process --port P [--runs-dir D] [--case NAME] [--slots-dir S]
[--max-runs N]``
"""

from __future__ import annotations

import argparse
import sys


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m app.session_process")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--runs-dir", default=None)
    p.add_argument("--case", default=None)
    p.add_argument("--slots-dir", default=None)
    p.add_argument("--max-runs", type=int, default=None)
    args = p.parse_args(argv)
    from .services.process import die_with_parent

    die_with_parent()
    from .offscreen import configure_environment

    configure_environment()
    import pyvista as pv
    from trame.app import get_server

    from .access import Access, middleware
    from .services import Services
    from .state import DEFAULT_CASE, RacetraceApp
    from .ui import build_ui

    pv.global_theme.multi_samples = 0
    server = get_server("racetrace", client_type="vue3")
    services = Services(args.runs_dir, slots_dir=args.slots_dir, max_runs=args.max_runs)
    app = RacetraceApp(server, services=services)
    app.start(args.case or DEFAULT_CASE)
    app.exports_dir.mkdir(parents=True, exist_ok=True)
    server.enable_module({"serve": {app.EXPORT_URL: str(app.exports_dir)}})
    build_ui(app)
    access = Access("127.0.0.1")

    def guard(ws_server, **_):
        # only the front's relay (which checked the browser) may use this session
        ws_server.app.middlewares.append(middleware(access))

    server.controller.on_server_bind.add(guard)
    from .main import quiet_closed_connections

    server.controller.on_server_ready.add(quiet_closed_connections)
    try:
        server.start(
            host="127.0.0.1",
            port=args.port,
            open_browser=False,
            show_connection_info=False,
            disable_logging=True,
        )
    finally:
        app.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
