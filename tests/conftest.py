"""Test-session set-up shared by every test.

With ``-n N`` (pytest-xdist, the README's test command), the controller loads or compiles the
solver's numba kernels once before the workers start (:func:`tests.helpers.warm.warm_kernels`):
otherwise each worker, and each ``racetrace`` process a test starts before the on-disk cache is
written, compiles the same kernels at the same time on a fresh clone. The summary at the end says
how long it took.
"""

from __future__ import annotations

import pytest

WARMED = pytest.StashKey[str]()


def pytest_configure(config) -> None:
    if hasattr(config, "workerinput"):  # an xdist worker: the controller has warmed the cache
        return
    workers = config.getoption("numprocesses", default=None)
    if not workers or config.getoption("collectonly"):
        return
    from tests.helpers.warm import warm_kernels

    config.stash[WARMED] = warm_kernels()


def pytest_terminal_summary(terminalreporter, config) -> None:
    if WARMED in config.stash:
        terminalreporter.write_line(config.stash[WARMED])
