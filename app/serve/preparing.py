"""What ``racetrace serve`` is preparing before its first session answers, said in the terminal
and on the page.

The fork server (:mod:`app.serve.preload`) imports the libraries and loads or compiles the
kernels a session uses first: on an empty numba cache that takes minutes. It says what it is
doing with :func:`say`: a line in the terminal (at each new step, and every
:data:`TERMINAL_EVERY_S` while a step goes on) and the same words in the file named by
``$RACETRACE_PREPARING_FILE``, which the front reads (:func:`read`) to show them on the page it
serves meanwhile. Light on purpose: imported before anything heavy.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ENV = "RACETRACE_PREPARING_FILE"
TERMINAL_EVERY_S = 15.0  # a step that goes on is said again in the terminal this often
_last = {"step": None, "at": -float("inf")}  # what the terminal was told last (this process)


def say(text: str) -> None:
    """Tell the terminal and the front's page that the server is now doing ``text`` (its step is
    the part before a colon: 'compiling ...: 12 so far' repeats the step 'compiling ...')."""
    step = text.split(":", 1)[0]
    now = time.monotonic()
    if step != _last["step"] or now - _last["at"] >= TERMINAL_EVERY_S:
        _last["step"], _last["at"] = step, now
        print(f"racetrace: preparing: {text}", file=sys.stderr, flush=True)
    path = os.environ.get(ENV)
    if path:
        try:  # written whole (replaced), so the front never reads half a line
            partial = Path(f"{path}.{os.getpid()}.tmp")
            partial.write_text(text, encoding="utf-8")
            os.replace(partial, path)
        except OSError:  # the page then says less; the terminal has it
            pass


def read(path: str | os.PathLike | None) -> str:
    """The last words :func:`say` wrote to ``path`` ('' when there are none)."""
    if not path:
        return ""
    try:
        return Path(path).read_text(encoding="utf-8").strip()
    except OSError:
        return ""
