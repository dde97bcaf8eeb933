"""Process lifetime: a child process that ends with its parent."""

from __future__ import annotations

import signal
import sys


def die_with_parent(sig: int = signal.SIGTERM) -> None:
    """Ask Linux to send ``sig`` to this process when its parent ends (no-op elsewhere).

    A session process (:mod:`app.serve.session_process`) asks for SIGTERM, so it saves its run
    before it goes; a solver process (:mod:`app.runner`) asks for SIGKILL: it never runs on its own.
    """
    if not sys.platform.startswith("linux"):
        return
    import ctypes

    try:
        libc = ctypes.CDLL("libc.so.6", use_errno=True)
        libc.prctl(1, int(sig))  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
