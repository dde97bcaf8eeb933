"""``racetrace export RESULT.nc --csv OUT.csv``: export a saved result through the ``ds.racetrace``
accessor; ``racetrace export SET.nc [SET2.nc ...] --ross DIR --nodes N1,N2``: the bearings of a
bearing-set result as ROSS bearing elements.

``--csv`` writes the per-contact table (one row per time, ball and race; columns named
``<variable> [<units>]``, solver.results.io.contact_table), atomically. ``--ross`` writes one
``ross.BearingElement`` TOML file per bearing of a set (racetrace.rotordynamics,
docs/rotordynamics.md) at the ROSS shaft nodes ``--nodes``: from several results of the set at
different speeds, coefficients over those speeds. Images and animations of the 3-D view need the
app's renderer: export them from the app. Exit codes: 0 written, 2 invalid input (a missing or
unreadable result, a file that is not a racetrace result, named with what it lacks, no export
named, an output that cannot be written).
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
    parser.add_argument(
        "result",
        metavar="RESULT.nc",
        nargs="+",
        help="results file (NetCDF); with --ross, one or more bearing-set results of one set at "
        "different speeds",
    )
    parser.add_argument("--csv", metavar="OUT.csv", help="write the per-contact table as CSV")
    parser.add_argument(
        "--ross",
        metavar="DIR",
        help="write each bearing of a bearing-set result as a ROSS BearingElement TOML file in "
        "DIR (ross.BearingElement.load reads it; docs/rotordynamics.md)",
    )
    parser.add_argument(
        "--nodes",
        metavar="N1,N2,...",
        help="with --ross: the ROSS shaft node of each bearing, in the set's order",
    )
    parser.set_defaults(func=run)


def _fail(message: str) -> int:
    print(f"racetrace: invalid input:\n{message}", file=sys.stderr)
    return EXIT_INVALID_INPUT


def _nodes(text: str | None) -> list[int] | str:
    """The node list of ``--nodes``, or the problem with it."""
    if not text:
        return (
            "--ross needs --nodes N1,N2,...: the ROSS shaft node of each bearing of the set, in "
            "its order (racetrace solve CASE lists the bearings and their positions)"
        )
    try:
        nodes = [int(item) for item in text.split(",")]
    except ValueError:
        return f"--nodes {text}: give integers separated by commas, e.g. --nodes 3,4"
    if min(nodes) < 0:
        return f"--nodes {text}: a node is an integer >= 0"
    return nodes


def _run_ross(args) -> int:
    from racetrace.rotordynamics import RossExportError, write_ross_elements
    from solver import ResultWriteError, load_dataset

    nodes = _nodes(args.nodes)
    if isinstance(nodes, str):
        return _fail(nodes)
    results = []
    for name in args.result:
        if not Path(name).is_file():
            return _fail(f"{name}: no such results file")
        try:
            results.append(load_dataset(Path(name)))
        except (OSError, ValueError, RuntimeError) as error:  # netCDF4 raises RuntimeError too
            return _fail(f"{name}: not readable as a NetCDF result ({clean_message(error)})")
    target = Path(args.ross)
    if target.exists() and not target.is_dir():
        return _fail(f"--ross {args.ross}: exists and is not a folder; give a folder name")
    source = args.result[0] if len(args.result) == 1 else "result"
    try:
        written = write_ross_elements(results, nodes, target, source=source)
    except RossExportError as error:
        return _fail(str(error))
    except (ResultWriteError, OSError) as error:
        return _fail(f"--ross {args.ross}: {clean_message(error)}")
    for path in written:
        print(f"racetrace: wrote {path}", file=sys.stderr)
    return 0


def run(args) -> int:
    from solver import CaseError, load_result

    if args.ross:
        if args.csv:
            return _fail("give --csv or --ross, one at a time")
        return _run_ross(args)
    if args.nodes:
        return _fail("--nodes is read with --ross only")
    if not args.csv:
        return _fail(
            "name what to export: --csv OUT.csv, or --ross DIR for a bearing set (images and "
            "animations: use the app)"
        )
    if len(args.result) != 1:
        return _fail("--csv exports one result: give one RESULT.nc")
    args.result = args.result[0]
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
