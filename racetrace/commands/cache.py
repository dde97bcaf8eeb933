"""``racetrace cache``: where numba's compiled kernels are kept, their size, and the folders of
other versions; ``racetrace cache clean [--all]`` removes those folders (exit 1 if one cannot be).

Run it with the same ``NUMBA_CACHE_DIR`` as the solver runs, so that it looks in the same place.
"""

from __future__ import annotations

import sys

EXIT_NOT_REMOVED = 1


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "cache",
        help="show the compiled-kernel cache, or remove old versions (cache clean)",
        description="Show where numba's compiled kernels are kept (one folder per version of the "
        "solver sources), their size and the folders of other versions. "
        "`racetrace cache clean` removes the folders of other versions.",
    )
    actions = parser.add_subparsers(dest="cache_action", metavar="ACTION")
    actions.add_parser("show", help="show the cache folders (the default)")
    clean = actions.add_parser("clean", help="remove the cache folders of other versions")
    clean.add_argument(
        "--all",
        action="store_true",
        help="remove this version's folder too (its kernels are compiled again on the next run)",
    )
    parser.set_defaults(func=run)


def format_size(size_bytes: int) -> str:
    """Size in B, kB, MB or GB (powers of 1000)."""
    if size_bytes < 1000:
        return f"{size_bytes} B"
    size = size_bytes / 1000
    for unit in ("kB", "MB"):
        if size < 1000:
            return f"{size:.1f} {unit}"
        size /= 1000
    return f"{size:.1f} GB"


def describe(folders, active) -> str:
    """The text of ``racetrace cache``: this version's folder, then the others."""
    current = [f for f in folders if f.current]
    others = [f for f in folders if not f.current]
    if active is None:
        lines = ["compiled kernels: no cache folder is in use (see the warning above)"]
    else:
        size = format_size(current[0].size_bytes) if current else "empty"
        lines = [f"compiled kernels of this version: {active} ({size})"]
    if others:
        total = format_size(sum(f.size_bytes for f in others))
        lines.append(
            f"other versions ({len(others)}, {total}; `racetrace cache clean` removes them):"
        )
        lines += [f"  {f.path}  {format_size(f.size_bytes)}" for f in others]
    else:
        lines.append("other versions: none")
    return "\n".join(lines)


def run(args) -> int:
    from solver import active_folder, cache_folders, remove_folders

    folders = cache_folders()
    active = active_folder()
    if getattr(args, "cache_action", None) != "clean":
        print(describe(folders, active))
        return 0
    doomed = [f for f in folders if args.all or not f.current]
    failed = remove_folders(doomed)
    failed_paths = {path for path, _ in failed}
    removed = [f for f in doomed if f.path not in failed_paths]
    for folder in removed:
        print(f"removed {folder.path} ({format_size(folder.size_bytes)})")
    freed = format_size(sum(f.size_bytes for f in removed))
    print(f"removed {len(removed)} folder(s), {freed}" if removed else "nothing to remove")
    for path, reason in failed:
        print(f"racetrace cache: cannot remove {path}: {reason}", file=sys.stderr)
    return EXIT_NOT_REMOVED if failed else 0
