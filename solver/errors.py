"""Exceptions of the public solver API.

`CaseError` means the input is wrong (the CLI exits with code 2); `NoSolutionError` means the input
is valid but the model found no solution (exit code 3). Both carry messages written for the user:
they name what is wrong and what to try, so callers print them as they are, never with a traceback.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a case: the dotted key (e.g. ``bearing.ball_count``) and the message.

    ``related_keys`` names the other keys a rule between keys involves (e.g. the ball diameter for
    a pitch diameter that is too small): the message concerns each of them, so a form shows it at
    every field involved. ``key`` is the one the problem is filed under.
    """

    key: str
    message: str
    related_keys: tuple[str, ...] = ()

    @property
    def keys(self) -> tuple[str, ...]:
        """Every key the message concerns: ``key`` first, then the related keys (no repeats)."""
        return tuple(dict.fromkeys((self.key, *self.related_keys)))

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
        """Messages that concern ``key`` (a dotted case-file key), as main or related key."""
        return [p.message for p in self.problems if key in p.keys]


class NoSolutionError(RuntimeError):
    """The model found no solution for a valid case; the message says why and what to try."""


class SimulationDiverged(RuntimeError):
    """The dynamic integration diverged; the message names the likely cause."""
