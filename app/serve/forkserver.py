"""Session processes forked from one pre-imported process, so that they share its memory.

A session process (:mod:`app.serve.session_process`) imports VTK, pyvista, trame, plotly,
xarray, numba and the solver: about 300 MB of memory that is the same in every session. Started from
:mod:`multiprocessing`'s fork server, whose process has imported all that once
(:data:`PRELOAD`, :mod:`app.serve.preload`), every session is a fork of it and shares those
pages with it and with the other sessions (copy on write) instead of holding its own copy.

The fork server is a child of the front, started with the first session; it imports the modules
and loads the numba kernels a session uses first, and nothing more (no render window, no OpenGL
context, no thread): each session creates its own render window after the fork. When the front
ends, the fork server ends, and so do the sessions (they watch their parent,
:func:`app.process.die_with_parent`).

:class:`ForkedProcess` gives a forked session the interface of ``asyncio.subprocess.Process`` that
:class:`app.serve.front.Front` uses (``pid``, ``returncode``, ``send_signal``, ``kill``, ``wait``).
"""

from __future__ import annotations

import asyncio
import multiprocessing
import os
import signal
import sys

PRELOAD = ["app.serve.preload"]  # imported once by the fork server, before any fork


def available() -> bool:
    """Whether sessions can be forked here (Linux and macOS have the fork server)."""
    return sys.platform != "win32" and "forkserver" in multiprocessing.get_all_start_methods()


def _context():
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(PRELOAD)
    return context


def _run_session(argv: list[str], secret: str) -> None:
    """The forked process: run one session with ``argv`` (app.serve.session_process options) that
    answers requests carrying ``secret`` only."""
    _let_go_of_the_fork_server()
    from app.serve.session_process import main

    sys.exit(main(argv, secret=secret))


def _let_go_of_the_fork_server() -> None:
    """Close this process's copy of the pipe whose end tells the fork server that the front has
    gone. The fork server hands it to every process it forks; held by a session, the fork
    server would outlive a killed front, and so would the sessions (they end with their parent,
    the fork server)."""
    from multiprocessing import forkserver as mp_forkserver

    server = getattr(mp_forkserver, "_forkserver", None)
    fd = getattr(server, "_forkserver_alive_fd", None)
    if fd is not None:
        try:
            os.close(fd)
        except OSError:
            pass
        server._forkserver_alive_fd = None


class ForkedProcess:
    """A session process forked by the fork server, seen as an ``asyncio.subprocess.Process``."""

    def __init__(self, process: multiprocessing.Process):
        self._process = process
        self.pid = process.pid

    @property
    def returncode(self) -> int | None:
        """None while running; the exit code, or minus the signal that ended it."""
        return self._process.exitcode

    def send_signal(self, sig: int) -> None:
        if self.returncode is None:
            os.kill(self.pid, sig)

    def terminate(self) -> None:
        self.send_signal(signal.SIGTERM)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)

    async def wait(self) -> int:
        """Wait (without blocking the event loop) until the process has ended; its return code."""
        while self._process.exitcode is None:
            await asyncio.sleep(0.1)
        return self._process.exitcode


def start_session(argv: list[str], secret: str) -> ForkedProcess:
    """Fork a session process running ``app.serve.session_process`` with ``argv`` and ``secret``
    (sent to the fork server over its private socket, never on a command line).

    Blocks until the fork server has forked it (the first call waits for the fork server to
    import :data:`PRELOAD`, a few seconds): call it in a thread from an event loop.
    """
    # Ctrl-C in a terminal reaches the whole process group; the front stops its sessions itself.
    # The first call starts the fork server, a new interpreter that a SIGINT during its start-up
    # would kill with a traceback: it (and the sessions it forks) inherit this thread's blocked
    # SIGINT. Only the main thread handles Python's signals, so nothing else is held back.
    # (multiprocessing's resource tracker, started first, unblocks SIGINT in the calling thread
    # after starting itself with it blocked: start it before blocking.)
    if hasattr(signal, "pthread_sigmask"):
        from multiprocessing import resource_tracker

        resource_tracker.ensure_running()
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    process = _context().Process(
        target=_run_session, args=(list(argv), secret), name="racetrace-session"
    )
    process.start()
    return ForkedProcess(process)


__all__ = ["ForkedProcess", "PRELOAD", "available", "start_session"]
