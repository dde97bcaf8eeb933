"""Exceptions of the public solver API.

`CaseError` means the input is wrong (the CLI exits with code 2); `NoSolutionError` means the input is
valid but the model found no solution (exit code 3). Both carry messages written for the user: they name
what is wrong and what to try, so callers print them as they are, never with a traceback.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a case: the dotted key (e.g. ``bearing.ball_count``) and the message."""

    key: str
    message: str

    def __str__(self) -> str:
        return self.message


class CaseError(ValueError):
    """Invalid case input. ``problems`` lists every problem found, each naming its key."""

    def __init__(self, problems: list[Problem] | Problem | str):
        if isinstance(problems, str):
            problems = [Problem("", problems)]
        elif isinstance(problems, Problem):
            problems = [problems]
        self.problems: list[Problem] = list(problems)
        super().__init__("\n".join(p.message for p in self.problems))

    def for_key(self, key: str) -> list[str]:
        """Messages that concern ``key`` (a dotted case-file key)."""
        return [p.message for p in self.problems if p.key == key]


class NoSolutionError(RuntimeError):
    """The model could not find a solution for a valid case; the message says why and what to try."""


class SimulationDiverged(RuntimeError):
    """The dynamic integration diverged; the message names the likely cause."""
