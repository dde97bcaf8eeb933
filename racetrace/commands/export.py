"""``racetrace export RESULT.nc --csv OUT.csv``: export a saved result through the ``ds.racetrace``
accessor.

``--csv`` writes the per-contact table (one row per time, ball and race; columns named
``<variable> [<units>]``, solver.results.io.contact_table), atomically. Images and animations of
the 3-D view need the app's renderer: export them from the app. Exit codes: 0 written, 2 invalid
input (a missing or unreadable result, a file that is not a racetrace result, named with what it
lacks, no export named, an output that cannot be written).
"""

from __future__ import annotations

import sys
from pathlib import Path

from solver import clean_message

from ._output import output_problem

EXIT_INVALID_INPUT = 2


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "export",
        help="export a saved result (NetCDF) as a CSV table",
        description="Export a results NetCDF file (from racetrace simulate or quasistatic "
        "--output, or the app's runs folder). --csv writes the per-contact table: one row per "
        "time, ball and race. PNG and MP4 of the 3-D view are exported from the app.",
    )
    parser.add_argument("result", metavar="RESULT.nc", help="results file (NetCDF)")
    parser.add_argument("--csv", metavar="OUT.csv", help="write the per-contact table as CSV")
    parser.set_defaults(func=run)


def _fail(message: str) -> int:
    print(f"racetrace: invalid input:\n{message}", file=sys.stderr)
    return EXIT_INVALID_INPUT


def run(args) -> int:
    from solver import CaseError, load_result

    if not args.csv:
        return _fail("name what to export: --csv OUT.csv (images and animations: use the app)")
    source = Path(args.result)
    if not source.is_file():
        return _fail(f"{args.result}: no such results file")
    target = Path(args.csv)
    problem = output_problem(target, "--csv", "table.csv")
    if problem:
        return _fail(problem)
    try:
        ds = load_result(source, args.result)
    except CaseError as error:
        return _fail(clean_message(error))
    try:
        ds.racetrace.to_csv(target)
    except ValueError as error:
        return _fail(f"{args.result}: {error}")
    except OSError as error:
        return _fail(f"--csv {args.csv}: {clean_message(error)}")
    print(f"racetrace: wrote {target}", file=sys.stderr)
    return 0
