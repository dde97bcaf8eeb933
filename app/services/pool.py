"""The solver pool: hands out background runners (:class:`app.runner.SolverRunner`) to sessions and
stops them all when the server exits."""

from __future__ import annotations

from ..runner import SolverRunner


class SolverPool:
    """Every :class:`SolverRunner` a session uses comes from here."""

    def __init__(self):
        self._runners: list[SolverRunner] = []

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
