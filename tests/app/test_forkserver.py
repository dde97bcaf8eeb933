"""Session processes forked from the pre-imported fork server (app.serve.forkserver)."""

from __future__ import annotations

import asyncio
import multiprocessing
import signal
import subprocess
import sys
import time

import pytest

from app.serve import forkserver


def _sleep() -> None:
    time.sleep(60)


def test_forked_process_behaves_like_an_asyncio_subprocess():
    process = multiprocessing.get_context("fork").Process(target=_sleep)
    process.start()
    forked = forkserver.ForkedProcess(process)
    try:
        assert forked.pid == process.pid
        assert forked.returncode is None
        forked.send_signal(signal.SIGTERM)
        assert asyncio.run(asyncio.wait_for(forked.wait(), 30)) == -signal.SIGTERM
        assert forked.returncode == -signal.SIGTERM
        forked.kill()  # an ended process: nothing to signal, no error
    finally:
        process.kill()
        process.join()


def _fresh_python(code: str) -> subprocess.CompletedProcess:
    """Run ``code`` in a new Python interpreter (it must succeed); its output as text."""
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )


def test_preload_imports_without_threads_or_render_window():
    """The fork server imports PRELOAD before forking: it must not start Python threads or make
    a VTK render window (each session makes its own after the fork)."""
    code = (
        "import threading, sys\n"
        "import app.serve.preload\n"
        "import vtkmodules.vtkRenderingCore as rc\n"
        "print(threading.active_count(), 'pyvista' in sys.modules, 'app.state' in sys.modules)\n"
    )
    out = _fresh_python(code)
    assert out.stdout.split() == ["1", "True", "True"], out.stderr[-2000:]


def test_the_session_lets_go_of_the_fork_servers_alive_pipe(monkeypatch):
    import os
    from multiprocessing import forkserver as mp_forkserver

    read, write = os.pipe()
    os.set_blocking(read, False)  # reading with the write end still open raises, never hangs
    server = mp_forkserver.ForkServer()
    server._forkserver_alive_fd = write
    monkeypatch.setattr(mp_forkserver, "_forkserver", server)
    forkserver._let_go_of_the_fork_server()
    assert server._forkserver_alive_fd is None
    assert os.read(read, 1) == b""  # the only write end is closed: the reader sees the end
    os.close(read)


@pytest.mark.skipif(not forkserver.available(), reason="no fork server on this platform")
def test_front_forks_sessions_where_it_can():
    from app.access import Access
    from app.serve.front import Front

    assert Front(Access("127.0.0.1"), []).fork
    assert not Front(Access("127.0.0.1"), [], fork=False).fork


def test_a_forked_session_gives_trame_its_own_options_not_the_fronts():
    """A forked session holds the front's sys.argv; trame must read the session's options only
    (on 127.0.0.1, its port, no idle stop), whatever that command line or $TRAME_ARGS say."""
    code = (
        "import os, sys\n"
        "sys.argv = ['racetrace', 'serve', '--host', '0.0.0.0', '--port', '80', '--timeout', '9']\n"
        "os.environ['TRAME_ARGS'] = '--host 0.0.0.0'\n"
        "from app.serve.session_process import _trame_options_only, trame_options\n"
        "_trame_options_only(trame_options(4321))\n"
        "from trame.app import get_server\n"
        "options = get_server('session').cli.parse_known_args()[0]\n"
        "print(options.host, options.port, options.timeout)\n"
    )
    out = _fresh_python(code)
    assert out.stdout.split() == ["127.0.0.1", "4321", "0"], out.stderr[-2000:]
