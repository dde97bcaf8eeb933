"""The ``racetrace`` command line: one sub-command per module in ``racetrace.commands``.

Exit codes: 0 success, 2 invalid input (the validation message, no traceback), 3 the solver found no
solution (the message says why and what to try), 130 interrupted. Messages have their control
characters escaped and their length capped (:func:`solver.errors.clean_message`). With ``--json``,
a failure also prints ``{"error": {...}}`` on stdout, so stdout is always JSON.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys

from solver import CaseError, NoSolutionError, __version__, clean_message

# Sub-command modules, in the order they are listed by --help. Each defines
# ``register(subparsers)``, which adds its parser and sets ``func`` to a callable(args) -> int.
COMMAND_MODULES = (
    "cases",
    "check",
    "quasistatic",
    "simulate",
    "study",
    "report",
    "export",
    "serve",
    "cache",
)

EXIT_OK = 0
EXIT_INVALID_INPUT = 2
EXIT_NO_SOLUTION = 3
EXIT_INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="racetrace",
        description="Simulate angular contact ball bearings and their contact trajectories.",
    )
    parser.add_argument("--version", action="version", version=f"racetrace {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        importlib.import_module(f"racetrace.commands.{name}").register(subparsers)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return EXIT_INVALID_INPUT
    try:
        return int(args.func(args) or 0)
    except CaseError as error:
        print(f"racetrace: invalid input:\n{clean_message(error)}", file=sys.stderr)
        _json_error(args, "invalid input", EXIT_INVALID_INPUT, error)
        return EXIT_INVALID_INPUT
    except NoSolutionError as error:
        print(f"racetrace: no solution: {clean_message(error)}", file=sys.stderr)
        _json_error(args, "no solution", EXIT_NO_SOLUTION, error)
        return EXIT_NO_SOLUTION
    except KeyboardInterrupt:
        print("racetrace: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED


def _json_error(args, kind: str, code: int, error: Exception) -> None:
    """With ``--json``, stdout holds JSON also when the command fails: ``{"error": {"kind",
    "exit_code", "message", "problems": [{"key", "message"}]}}`` (problems of invalid input)."""
    if not getattr(args, "json", False):
        return
    problems = [{"key": p.key, "message": p.message} for p in getattr(error, "problems", [])]
    body = {"kind": kind, "exit_code": code, "message": clean_message(error)}
    if problems:
        body["problems"] = problems
    try:
        print(json.dumps({"error": body}, indent=2))
    except (OSError, ValueError):  # stdout closed: stderr already has the message
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
