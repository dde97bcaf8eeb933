"""File names that come from a page: a bare name under a folder the server chose, never a path.

Every state key or controller argument of the app that ends in a file or folder name goes
through :func:`child_path` after the value was found among the names the server lists itself
(never among names the client sent back).
"""

from __future__ import annotations

from pathlib import Path

#: Longest name accepted (the usual file-system limit on one path component).
MAX_NAME_CHARS = 255


class UnsafeNameError(ValueError):
    """A name from a page that is not a bare file name under its folder; the message says why."""


def name_problem(name) -> str:
    """Why ``name`` (as a client sent it) is not a bare file name ("" when it is)."""
    if not isinstance(name, str):
        return f"a name must be text, not {type(name).__name__}"
    if not name:
        return "the name is empty"
    if len(name) > MAX_NAME_CHARS:
        return f"the name is longer than {MAX_NAME_CHARS} characters"
    if "\x00" in name:
        return "the name holds a NUL character"
    if "/" in name or "\\" in name:
        return "the name holds a path separator"
    if name in (".", ".."):
        return "the name is a reference to a folder"
    return ""


def child_path(root: str | Path, name, what: str = "file") -> Path:
    """``root / name`` for a bare file name ``name`` whose resolved path stays under the
    resolved ``root`` (symbolic links followed); :class:`UnsafeNameError` naming ``what`` and the
    reason otherwise (an absolute name, ``..``, a separator, NUL, a link leading out)."""
    shown = repr(name)[:80]
    problem = name_problem(name)
    if problem:
        raise UnsafeNameError(f"{what} {shown} refused: {problem}")
    root = Path(root)
    base = root.resolve()
    target = (base / name).resolve()
    if target == base or not target.is_relative_to(base):
        raise UnsafeNameError(f"{what} {shown} refused: it leads out of its folder")
    return root / name
