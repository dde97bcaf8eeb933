"""Exceptions of the public solver API.

`CaseError` means the input is wrong (the CLI exits with code 2); `NoSolutionError` means the input
is valid but the model found no solution (exit code 3). Both carry messages written for the user:
they name what is wrong and what to try, so callers print them as they are, never with a traceback.
"""

from __future__ import annotations

import unicodedata
from dataclasses import dataclass

#: Longest message of one problem, in characters (a longer one is cut, saying so).
MAX_PROBLEM_CHARS = 1_000
#: Longest text of a whole error (all its problems), in characters: a case with thousands of
#: problems gives the first ones and the count of the others, never a message of megabytes.
MAX_MESSAGE_CHARS = 8_000

# Characters that change what a terminal or a page shows rather than being shown: C0/C1 controls
# (escape sequences, bell, carriage return ...), line and paragraph separators, the bidirectional
# overrides and isolates (they reorder the text around them) and lone surrogates (not printable).
_HIDDEN_CATEGORIES = {"Cc", "Cs", "Zl", "Zp"}
_BIDI_CONTROLS = set("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\u200e\u200f")


def _escape_char(ch: str) -> str:
    code = ord(ch)
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}"


def printable(text: str, keep_newlines: bool = False) -> str:
    """``text`` with every control character written as a visible escape (``\\x1b``, ``\\u202e``).

    Escape sequences, carriage returns, bells and bidirectional overrides from a case file would
    otherwise act on the terminal or the page showing the message (clear the screen, set the window
    title, reorder the text). ``keep_newlines`` leaves line feeds between lines of a message.
    """
    if not isinstance(text, str):
        text = str(text)
    out = []
    for ch in text:
        if ch == "\n" and keep_newlines:
            out.append(ch)
        elif ch in _BIDI_CONTROLS or unicodedata.category(ch) in _HIDDEN_CATEGORIES:
            out.append(_escape_char(ch))
        else:
            out.append(ch)
    return "".join(out)


def clip(text: str, limit: int) -> str:
    """``text`` cut to at most about ``limit`` characters, saying how much was left out."""
    if len(text) <= limit:
        return text
    return text[:limit] + f" ... ({len(text) - limit} more characters)"


def clean_message(text, limit: int = MAX_MESSAGE_CHARS) -> str:
    """A message safe to print: control characters escaped (line feeds kept), length capped."""
    return clip(printable(str(text), keep_newlines=True), limit)


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

    def __post_init__(self):
        # every message is shown to a user: escape control characters, cap its length
        object.__setattr__(self, "message", clip(printable(self.message), MAX_PROBLEM_CHARS))
        object.__setattr__(self, "key", clip(printable(self.key), MAX_PROBLEM_CHARS))

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
        super().__init__(_joined(self.problems))

    def for_key(self, key: str) -> list[str]:
        """Messages that concern ``key`` (a dotted case-file key), as main or related key."""
        return [p.message for p in self.problems if key in p.keys]


def _joined(problems: list[Problem]) -> str:
    """One line per problem, at most :data:`MAX_MESSAGE_CHARS` in all (then a count of the rest)."""
    lines: list[str] = []
    size = 0
    for index, problem in enumerate(problems):
        if lines and size + len(problem.message) > MAX_MESSAGE_CHARS:
            rest = len(problems) - index
            lines.append(
                f"... and {rest} more problem{'s' if rest > 1 else ''} "
                "(fix the ones above and check again)"
            )
            break
        lines.append(problem.message)
        size += len(problem.message) + 1
    return "\n".join(lines)


class NoSolutionError(RuntimeError):
    """The model found no solution for a valid case; the message says why and what to try."""


class SimulationDiverged(RuntimeError):
    """The dynamic integration diverged; the message names the likely cause."""


class ResultWriteError(OSError):
    """A result file could not be written (folder missing or read-only, disk full, a file-size
    limit; netCDF4 reports some of these as RuntimeError). ``path`` is the file that was to be
    written; the message names it and the reason. Nothing is left at ``path`` or beside it."""

    def __init__(self, path, reason: str):
        self.path = path
        self.reason = reason
        super().__init__(f"could not write {path}: {reason}")

    def __str__(self) -> str:
        return f"could not write {self.path}: {self.reason}"
