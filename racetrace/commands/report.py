"""``racetrace report RUN_OR_STUDY --output review.html``: the standalone review report.

RUN_OR_STUDY is a result NetCDF file (racetrace simulate / quasistatic --output, the app's runs
folder) or a study folder (racetrace study --output). The page is one HTML file with everything
embedded: it opens from disk with no server and no network, and prints to PDF from the browser.
With ``--points`` a study's report also writes the run report of each finished point beside it
(``OUTPUT_STEM.points/``) and links each point of its table to it.
Needs the ``report`` extra; without it the command says how to install it (exit 2). The output
path is checked before the page is built, and the source is checked to be a racetrace result
(:func:`solver.results.validate.check_result`): either problem is an invalid input (exit 2) naming
what is wrong.
"""

from __future__ import annotations

import sys
from pathlib import Path

from ._output import output_problem


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "report",
        help="write a standalone HTML review report of a result or a study",
        description=(
            "Write a self-contained HTML review report (Panel) of RUN_OR_STUDY: a results NetCDF "
            "file or a study folder. Exit codes: 0 written, 2 invalid input or the report extra "
            "missing."
        ),
    )
    parser.add_argument("source", metavar="RUN_OR_STUDY", help="result .nc file or study folder")
    parser.add_argument("--output", "-o", default="review.html", help="HTML file to write")
    parser.add_argument(
        "--points",
        action="store_true",
        help=(
            "with a study folder: also write each finished point's run report beside the page "
            "(OUTPUT_STEM.points/POINT.MODEL.html), linked from the points table"
        ),
    )
    parser.set_defaults(func=run)


def run(args) -> int:
    from racetrace.cli import EXIT_INVALID_INPUT
    from report.build import missing_report_modules
    from solver import CaseError, Problem

    # the page takes a minute to build: check where it goes first
    problem = output_problem(Path(args.output), "--output", "review.html")
    if problem:
        raise CaseError(Problem("output", problem))
    missing = missing_report_modules()
    if missing:
        print(
            "racetrace: the report needs the 'report' extra (missing: "
            f'{", ".join(missing)}). Install it with: pip install -e ".[report]"',
            file=sys.stderr,
        )
        return EXIT_INVALID_INPUT
    from report import build_report

    info = build_report(
        args.source,
        args.output,
        point_reports=args.points,
        log=lambda line: print(f"racetrace: writing {line}", file=sys.stderr),
    )
    size = info["bytes"] / 1e6
    print(
        f"racetrace: wrote {info['path']} ({size:.1f} MB, {info['kind']} report)", file=sys.stderr
    )
    for note in info["notes"]:
        print(f"racetrace: decimated: {note}", file=sys.stderr)
    if info["unresolved"]:
        print(
            "warning: the page still refers to: " + ", ".join(info["unresolved"][:5]),
            file=sys.stderr,
        )
    return 0
