"""``racetrace cases``: list the shipped bearings and cases; ``racetrace cases show NAME``
prints one
as a case file to start from (exit 2 with suggestions for an unknown name)."""

from __future__ import annotations

import sys


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "cases",
        help="list shipped bearings and example cases, or print one (cases show NAME)",
        description="List the shipped catalogue, or print an entry as a case file to start from.",
    )
    actions = parser.add_subparsers(dest="cases_action", metavar="ACTION")
    show = actions.add_parser("show", help="print a catalogue entry as a complete case file")
    show.add_argument("name", help="catalogue name (see `racetrace cases`)")
    actions.add_parser("list", help="list the catalogue (the default)")
    parser.set_defaults(func=run)


def format_table(entries) -> str:
    """Plain-text table: name, kind, provenance, title."""
    rows = [("NAME", "KIND", "PROVENANCE", "TITLE")]
    rows += [(e.name, e.kind, e.provenance, e.title) for e in entries]
    widths = [max(len(r[i]) for r in rows) for i in range(3)]
    return "\n".join(
        f"{r[0]:<{widths[0]}}  {r[1]:<{widths[1]}}  {r[2]:<{widths[2]}}  {r[3]}".rstrip()
        for r in rows
    )


def run(args) -> int:
    import solver

    cat = solver.catalogue()
    if getattr(args, "cases_action", None) == "show":
        sys.stdout.write(cat.get(args.name).case_text())  # unknown name: CaseError -> exit 2
        return 0
    print(format_table(cat.entries))
    print("\nPrint one as a case file: racetrace cases show NAME > my-case.toml")
    return 0
