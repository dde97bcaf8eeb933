"""Entry point of the browser app: check the address and off-screen rendering, then run the front
server (one session process per browser, :mod:`app.serve.front`)."""

from __future__ import annotations

import os
import shutil
import sys

from viz.offscreen import check_offscreen_rendering, configure_environment

EXIT_NO_RENDERING = 2  # also used for an unusable --host/--port (invalid input)


def serve(
    host: str = "127.0.0.1",
    port: int = 8080,
    open_browser: bool = False,
    runs_dir: str | None = None,
    case_name: str | None = None,
    shared: bool = False,
    max_runs: int | None = None,
    render: str = "browser",
) -> int:
    """Serve the app until interrupted. Returns 2 if off-screen rendering does not work here.

    Each browser gets its own session process (:mod:`app.serve.front`); ``shared``: one session for
    every browser. ``max_runs``: solver processes at once (default: the number of cores).
    ``render``: who draws the 3-D view, ``"browser"`` (where the browser has WebGL) or
    ``"server"``.
    """
    problem = _port_problem(host, port)
    if problem:
        print(f"racetrace serve: {problem}", file=sys.stderr)
        return EXIT_NO_RENDERING
    if render not in ("browser", "server"):
        print(f"racetrace serve: --render {render}: use browser or server", file=sys.stderr)
        return EXIT_NO_RENDERING
    if max_runs is not None and max_runs < 1:
        print(f"racetrace serve: --max-runs {max_runs}: must be at least 1", file=sys.stderr)
        return EXIT_NO_RENDERING
    configure_environment()
    check = check_offscreen_rendering()
    if not check.ok:
        print(f"racetrace serve: {check.message}", file=sys.stderr)
        return EXIT_NO_RENDERING
    from .access import Access, is_loopback, new_token
    from .run_store import RunStore, default_runs_dir
    from .serve import preparing
    from .serve.front import Front, pool_dir, run_front
    from .services.pool import default_max_runs

    runs = str(runs_dir if runs_dir is not None else default_runs_dir())
    for line in RunStore(runs).recover().messages():  # what a stopped server left behind
        print(f"racetrace: {line}", flush=True)
    max_runs = max_runs or default_max_runs()
    token = "" if is_loopback(host) else new_token()
    slots = pool_dir()
    # the fork server (started with the first session) says there what it is preparing
    os.environ[preparing.ENV] = str(slots / "preparing.txt")
    session_args = ["--runs-dir", runs, "--slots-dir", str(slots), "--max-runs", str(max_runs)]
    session_args += ["--render", render]
    if case_name:
        session_args += ["--case", case_name]
    front = Front(Access(host, token), session_args, shared=shared)
    shown_host = f"[{host}]" if ":" in host else host
    url = f"http://{shown_host}:{port}/" + (f"?token={token}" if token else "")
    mode = "one session for every browser" if shared else "one session per browser"
    banner = (
        f"racetrace: serving on {url}  (runs folder: {runs}; {mode}; "
        f"at most {max_runs} solver run{'s' * (max_runs != 1)} at once)"
    )
    if token:
        banner += (
            f"\nracetrace: WARNING: --host {host} is reachable from the network; only browsers "
            "given the address above (with its access token) can use the app"
        )

    def listening() -> None:
        print(banner, flush=True)
        if open_browser:
            import webbrowser

            webbrowser.open(url)

    try:
        run_front(front, host, port, listening)
    except OSError as error:  # e.g. the port was taken while we started
        print(
            f"racetrace serve: cannot serve on {host}:{port}: {error.strerror or error}",
            file=sys.stderr,
        )
        return EXIT_NO_RENDERING
    finally:
        shutil.rmtree(slots, ignore_errors=True)
    return 0


def _port_problem(host: str, port: int) -> str:
    """A message when ``host:port`` cannot be bound (in use, bad address), else ""."""
    import socket

    if not 0 < port < 65536:
        return f"--port {port}: must be between 1 and 65535"
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except socket.gaierror as error:
        return f"--host {host!r}: unknown address ({error.strerror})"
    family, _, _, _, address = infos[0]
    with socket.socket(family, socket.SOCK_STREAM) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind(address)
        except OSError as error:
            return (
                f"cannot listen on {host}:{port} ({error.strerror}); "
                "choose another port with --port"
            )
    return ""
