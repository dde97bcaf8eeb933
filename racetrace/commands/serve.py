"""``racetrace serve``: the browser app (3-D view, charts, background runs)."""

from __future__ import annotations


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "serve",
        help="open the browser app",
        description="Serve the racetrace browser app. It opens on the default case, already "
        "solved, so the page shows a moving bearing straight away.",
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
    p.set_defaults(func=run)


def run(args) -> int:
    from app.main import serve

    return serve(
        host=args.host,
        port=args.port,
        open_browser=args.open,
        runs_dir=args.runs_dir,
        case_name=args.case,
    )
