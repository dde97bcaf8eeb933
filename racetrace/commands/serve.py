"""``racetrace serve``: the browser app (3-D view, charts, background runs).

The app needs the ``app`` extra; without it the command says how to install it and exits 2.
"""

from __future__ import annotations

import sys

from ..extras import missing_modules

EXIT_NO_APP = 2
APP_EXTRA_MESSAGE = "the browser app needs the app extra: pip install 'racetrace[app]'"
# The top-level modules of the packages in the ``app`` extra of pyproject.toml.
APP_MODULES = (
    "trame",
    "trame_vuetify",
    "trame_pyvista",
    "trame_rca",
    "trame_vtk",
    "trame_plotly",
    "pyvista",
    "vtkmodules",
    "plotly",
    "imageio",
    "imageio_ffmpeg",
    "aiohttp",
    "msgpack",
    "segno",
    "wslink",
)


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "serve",
        help="open the browser app",
        description="Serve the racetrace browser app. It opens on the default case, already "
        "solved, so the page shows a moving bearing straight away. Each browser gets its own "
        "session (--shared: one for all). A --host other than a loopback address is reachable "
        "from the network: the server then prints its address with a random access token and "
        "refuses requests without it.",
    )
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1)")
    p.add_argument("--port", type=int, default=8080, help="port (default 8080)")
    p.add_argument("--open", action="store_true", help="open the page in the default browser")
    p.add_argument(
        "--runs-dir",
        default=None,
        help="folder for saved runs (default: $RACETRACE_RUNS_DIR or the user data dir)",
    )
    p.add_argument(
        "--case", default=None, help="shipped case to open (default spindle-combined-load)"
    )
    p.add_argument(
        "--shared",
        action="store_true",
        help="one session for every browser (a design review on a shared screen); by default "
        "each browser gets its own case, run, camera and view size",
    )
    p.add_argument(
        "--max-runs",
        type=int,
        default=None,
        help="solver processes at once, over all sessions (default: the number of cores); "
        "further runs wait in a queue",
    )
    p.add_argument(
        "--render",
        choices=("browser", "server"),
        default="browser",
        help="who draws the 3-D view: 'browser' (default: each browser draws it with WebGL, the "
        "server sends the moving parts' positions; a browser without WebGL gets server-rendered "
        "images) or 'server' (every frame rendered on the server)",
    )
    p.set_defaults(func=run)


def missing_app_modules() -> list[str]:
    """The modules of the ``app`` extra that cannot be found here (the extra is not installed)."""
    return missing_modules(APP_MODULES)


def app_extra_problem() -> str | None:
    """The message for a missing ``app`` extra, naming the missing modules; None if installed."""
    missing = missing_app_modules()
    if not missing:
        return None
    return f"racetrace serve: {APP_EXTRA_MESSAGE}\n(missing: {', '.join(missing)})"


def run(args) -> int:
    problem = app_extra_problem()
    if problem:
        print(problem, file=sys.stderr)
        return EXIT_NO_APP
    from app.main import serve

    return serve(
        host=args.host,
        port=args.port,
        open_browser=args.open,
        runs_dir=args.runs_dir,
        case_name=args.case,
        shared=args.shared,
        max_runs=args.max_runs,
        render=args.render,
    )
