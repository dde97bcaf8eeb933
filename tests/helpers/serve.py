"""A ``racetrace serve`` subprocess for browser tests: started on a free loopback port with its own
runs folder, waited for until it answers HTTP, and stopped again."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

START_S = 300  # a cold numba cache compiles the quasi-static kernels first; the machine is shared


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server(runs: Path, log_path: Path, *options: str) -> dict:
    """Start ``racetrace serve`` on ``runs`` and return once its page answers: a dict with the
    ``url``, ``runs`` folder, ``proc`` and open ``log`` file (for :func:`stop_server`)."""
    port = free_port()
    log = open(log_path, "w+")  # noqa: SIM115 - closed in stop_server
    proc = subprocess.Popen(
        [sys.executable, "-m", "racetrace", "serve", "--port", str(port), "--runs-dir", str(runs)]
        + list(options),
        stdout=log,
        stderr=subprocess.STDOUT,
        env=dict(os.environ),
    )
    url = f"http://127.0.0.1:{port}/"
    deadline = time.monotonic() + START_S
    while True:
        try:
            urllib.request.urlopen(url, timeout=2)
            break
        except OSError:
            if proc.poll() is not None or time.monotonic() > deadline:
                log.seek(0)
                proc.kill()
                pytest.fail(f"racetrace serve did not start:\n{log.read()[-3000:]}")
            time.sleep(0.5)
    return {"url": url, "runs": runs, "proc": proc, "log": log}


def stop_server(server: dict) -> None:
    proc = server["proc"]
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
    server["log"].close()
