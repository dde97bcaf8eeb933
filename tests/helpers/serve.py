"""A ``racetrace serve`` subprocess for browser tests: started on a free loopback port with its own
runs folder, waited for until it answers HTTP, and stopped again."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from app.serve.front import PREPARING_PATH

START_S = 300  # a cold numba cache compiles the quasi-static kernels first; the machine is shared


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(runs: Path, log_path: Path, *options: str, new_group: bool = False) -> dict:
    """Start ``racetrace serve`` on ``runs`` and return once its page answers: a dict with the
    ``url`` (with the access token the server printed, if any), ``port``, ``runs`` folder,
    ``proc`` and open ``log`` file (for :func:`stop_server`). ``new_group``: the server leads its
    own process group (so a test can signal the group, as Ctrl-C in a terminal does)."""
    port = free_port()
    if not any(o.startswith("--render") for o in options):
        # the tests written for the server-rendered view (its images) ask for it; the browser-drawn
        # view has its own tests (tests/app/test_browser_view.py)
        options = (*options, "--render", "server")
    log = open(log_path, "w+")  # noqa: SIM115 - closed in stop_server
    proc = subprocess.Popen(
        [sys.executable, "-m", "racetrace", "serve", "--port", str(port), "--runs-dir", str(runs)]
        + list(options),
        stdout=log,
        stderr=subprocess.STDOUT,
        env=dict(os.environ),
        process_group=0 if new_group else None,
    )
    deadline = time.monotonic() + START_S

    def failed() -> None:
        log.seek(0)
        proc.kill()
        pytest.fail(f"racetrace serve did not start:\n{log.read()[-3000:]}")

    while True:  # the banner says the front listens and names its token
        log.seek(0)
        text = log.read()
        if "serving on" in text:
            break
        if proc.poll() is not None or time.monotonic() > deadline:
            failed()
        time.sleep(0.2)
    token = text.split("?token=", 1)[1].split()[0] if "?token=" in text else ""
    url = f"http://127.0.0.1:{port}/" + (f"?token={token}" if token else "")
    status = f"http://127.0.0.1:{port}{PREPARING_PATH}" + (f"?token={token}" if token else "")
    while True:  # and the first session answers through it (the front says when it is ready)
        try:
            with urllib.request.urlopen(status, timeout=2) as answer:
                if json.loads(answer.read())["ready"]:
                    break
            time.sleep(0.5)
        except OSError:
            if proc.poll() is not None or time.monotonic() > deadline:
                failed()
            time.sleep(0.5)
    return {"url": url, "port": port, "token": token, "runs": runs, "proc": proc, "log": log}


def stop_server(server: dict, timeout_s: float = 10.0) -> None:
    """Stop a served app (SIGTERM; killed after ``timeout_s``) and close its log."""
    proc = server["proc"]
    proc.terminate()  # nothing when it has ended
    try:
        proc.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        proc.kill()
    server["log"].close()


def serve_for_module(tmp_path_factory, *options: str):
    """A module-scoped server fixture's body: starts ``racetrace serve`` with ``options`` on a
    runs folder and log of its own, yields what :func:`start_server` returns, stops it."""
    runs = tmp_path_factory.mktemp("runs")
    log = tmp_path_factory.mktemp("log") / "serve.log"
    served = start_server(runs, log, *options)
    yield served
    stop_server(served)


def descendants(pid: int) -> set[int]:
    """Processes below ``pid`` (from /proc)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(entry.name))
    found, todo = set(), [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.add(child)
            todo.append(child)
    return found
