"""What numba is doing while a process prepares the solver: compiling kernels (an empty cache: the
first run after installing or changing the solver) or loading them compiled from its cache.

numba announces a ``"numba:compile"`` event only when it compiles a kernel, never when it loads one
from the cache, so a listener tells the two apart exactly (a file check cannot: a cached kernel
may still be compiled again for other argument types).
"""

from __future__ import annotations

import time
from contextlib import contextmanager

COMPILING = "compiling the solver's kernels (first run only)"
LOADING = "loading the compiled kernels"


@contextmanager
def watching_compiles(on_compile, every_s: float = 1.0):
    """Within the block, call ``on_compile(count)`` when numba starts compiling its first kernel
    and then at most every ``every_s`` seconds while it compiles more (``count``: kernels whose
    compilation has started so far, the one under way included)."""
    from numba.core import event

    class Listener(event.Listener):
        def __init__(self):
            self.count = 0
            self.said = -float("inf")

        def on_start(self, _event):
            self.count += 1
            now = time.monotonic()
            if self.count == 1 or now - self.said >= every_s:
                self.said = now
                on_compile(self.count)

        def on_end(self, _event):
            pass

    listener = Listener()
    event.register("numba:compile", listener)
    try:
        yield listener
    finally:
        event.unregister("numba:compile", listener)


def compiling_words(count: int) -> str:
    """'compiling the solver's kernels (first run only): 12 so far'."""
    return f"{COMPILING}: {count} so far"
