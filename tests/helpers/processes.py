"""Waiting on what a test started: a condition polled until it holds, and a command started as a
real subprocess signalled once it is ready."""

from __future__ import annotations

import subprocess
import time
from collections.abc import Callable


def wait_until(
    done: Callable[[], bool], timeout_s: float, poll_s: float, failure: Callable[[], str]
) -> None:
    """Call ``done()`` every ``poll_s`` seconds until it is true; after ``timeout_s`` seconds the
    test fails with the message ``failure()`` returns then."""
    end = time.monotonic() + timeout_s
    while not done():
        assert time.monotonic() < end, failure()
        time.sleep(poll_s)


def signal_when(
    process: subprocess.Popen,
    ready: Callable[[], bool],
    signum: int,
    timeout_s: float,
    message: str,
    poll_s: float,
):
    """Send ``signum`` to ``process`` once ``ready()`` is true or the process has ended, polling
    every ``poll_s`` seconds (the test fails with ``message`` after ``timeout_s``), and return what
    ``communicate`` returns (stdout, stderr). The process is killed if it is still running after."""
    try:
        wait_until(
            lambda: process.poll() is not None or ready(), timeout_s, poll_s, lambda: message
        )
        process.send_signal(signum)
        return process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
