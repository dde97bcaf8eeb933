"""Process-wide services shared by every browser session: the runs folder and the solver pool.

One :class:`Services` object lives as long as the server; each session (:class:`app.state.
RacetraceApp`) holds a reference to it and keeps everything else (case, result, camera) to itself.
"""

from __future__ import annotations

from pathlib import Path

from ..run_store import RunStore, default_runs_dir
from .pool import SolverPool


class Services:
    """The run store on ``runs_dir`` (default :func:`app.run_store.default_runs_dir`) and the
    pool of solver processes (``slots_dir``, ``max_runs``: see :class:`SolverPool`)."""

    def __init__(
        self,
        runs_dir: str | Path | None = None,
        slots_dir: str | Path | None = None,
        max_runs: int | None = None,
    ):
        self.store = RunStore(runs_dir if runs_dir is not None else default_runs_dir())
        self.pool = SolverPool(slots_dir, max_runs)

    def shutdown(self) -> None:
        """Stop every solver process (the server is exiting)."""
        self.pool.shutdown()


__all__ = ["Services", "SolverPool"]
