"""The solver pool: background runners for the sessions, and the solver slots they share.

At most ``max_runs`` solver processes run at once (default: the number of processor cores),
across every session of the server, even sessions in other processes: a slot is an exclusive
lock (``fcntl.flock``) on one of ``max_runs`` files in the slots folder, released when the run
ends or its process dies. A run that finds no free slot waits in a queue (a ticket file per
waiting run, in order of arrival) and is told its place. A study started from the page takes
slots in the same queue, one per Dask worker it runs (app.components.studies), so runs and study
points together never exceed ``max_runs``.
"""

from __future__ import annotations

import os
import secrets
import tempfile
import time
from pathlib import Path

from ..runner import SolverRunner


def default_max_runs() -> int:
    """The default cap on solver processes: the number of processor cores."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


class Ticket:
    """A run's place in the queue for a solver slot; :meth:`SolverPool.try_acquire` turns it into
    a held slot (``slot`` is then set)."""

    def __init__(self, path: Path):
        self.path = path
        self.slot = None  # the open, locked slot file while held
        self.place = 0  # runs ahead in the queue (0: next)

    @property
    def held(self) -> bool:
        return self.slot is not None


class SolverPool:
    """Every :class:`SolverRunner` a session uses comes from here, and every run takes a slot.

    ``slots_dir``: the folder of slot locks and queue tickets shared by the server's processes
    (default: a new temporary folder, private to this pool); ``max_runs``: the cap (default
    :func:`default_max_runs`).
    """

    def __init__(self, slots_dir: str | Path | None = None, max_runs: int | None = None):
        self.max_runs = int(max_runs) if max_runs else default_max_runs()
        if self.max_runs < 1:
            raise ValueError(f"max_runs = {max_runs}: must be at least 1")
        if slots_dir is None:
            slots_dir = tempfile.mkdtemp(prefix="racetrace-slots-")
        self.dir = Path(slots_dir)
        (self.dir / "queue").mkdir(parents=True, exist_ok=True)
        self._runners: list[SolverRunner] = []

    # ---- runners --------------------------------------------------------------------------------
    def runner(self) -> SolverRunner:
        """A new runner for one session (at most one run at a time each)."""
        runner = SolverRunner()
        self._runners.append(runner)
        return runner

    def release(self, runner: SolverRunner) -> None:
        """Stop ``runner``'s process and forget it (its session has ended)."""
        runner.shutdown()
        if runner in self._runners:
            self._runners.remove(runner)

    def shutdown(self) -> None:
        """Stop every runner's process."""
        for runner in list(self._runners):
            self.release(runner)

    # ---- slots ----------------------------------------------------------------------------------
    def enqueue(self) -> Ticket:
        """A ticket at the end of the queue."""
        name = f"{time.time_ns():020d}-{os.getpid()}-{secrets.token_hex(4)}"
        path = self.dir / "queue" / name
        path.touch()
        return Ticket(path)

    def _waiting(self) -> list[Path]:
        """Tickets of live processes, oldest first (a dead process's tickets are removed)."""
        alive = []
        for path in sorted((self.dir / "queue").iterdir()):
            try:
                pid = int(path.name.split("-")[1])
            except (IndexError, ValueError):
                continue
            if _pid_alive(pid):
                alive.append(path)
            else:
                path.unlink(missing_ok=True)
        return alive

    def try_acquire(self, ticket: Ticket) -> bool:
        """Take a free slot for ``ticket`` if it is first in the queue; else update its place."""
        import fcntl

        if ticket.held:
            return True
        waiting = self._waiting()
        ticket.place = waiting.index(ticket.path) if ticket.path in waiting else 0
        if ticket.place > 0:
            return False
        for i in range(self.max_runs):
            handle = open(self.dir / f"slot-{i}.lock", "a+")  # noqa: SIM115 - held while running
            try:
                fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                handle.close()
                continue
            ticket.slot = handle
            ticket.path.unlink(missing_ok=True)
            return True
        return False

    def drop(self, ticket: Ticket | None) -> None:
        """Leave the queue, or free the slot held."""
        if ticket is None:
            return
        ticket.path.unlink(missing_ok=True)
        if ticket.slot is not None:
            ticket.slot.close()  # closing the file releases its lock
            ticket.slot = None


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
