"""Reading case files: path or TOML text → validated :class:`Case`; errors are
messages, never tracebacks."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from solver.errors import CaseError, Problem

from .model import Case
from .validate import validate

_LOCATION = re.compile(r"\(at line (\d+), column (\d+)\)")


def _looks_like_path(text: str) -> bool:
    """A one-line string without '=' that names a file rather than holding TOML."""
    stripped = text.strip()
    return bool(stripped) and "\n" not in stripped and "=" not in stripped and "[" not in stripped


def read_case_text(path: Path) -> str:
    """Text of a case file; CaseError if it cannot be read."""
    if not path.exists():
        raise CaseError(Problem("file", f"case file not found: {path}"))
    if path.is_dir():
        raise CaseError(Problem("file", f"{path} is a folder, not a case file"))
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as error:
        raise CaseError(
            Problem(
                "file",
                f"{path} is not a text file (not UTF-8: {error.reason} at byte {error.start})",
            )
        ) from None
    except OSError as error:
        raise CaseError(Problem("file", f"cannot read {path}: {error.strerror}")) from None


def parse_toml(text: str, source: str = "case text") -> dict:
    """Nested dict from TOML text; CaseError naming the line (and showing it) if it is not TOML."""
    if not text.strip() or all(
        not line.strip() or line.lstrip().startswith("#") for line in text.splitlines()
    ):
        raise CaseError(
            Problem(
                "file",
                f"{source} is empty: a case needs at least a [bearing] and "
                "an [operating] section (see `racetrace cases show NAME`)",
            )
        )
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        message = str(error)
        match = _LOCATION.search(message)
        where = ""
        if match:
            line_no = int(match.group(1))
            lines = text.splitlines()
            shown = lines[line_no - 1] if 0 < line_no <= len(lines) else ""
            message = _LOCATION.sub("", message).strip()
            where = f" at line {line_no}, column {match.group(2)}" + (
                f": {shown.strip()!r}" if shown.strip() else ""
            )
        raise CaseError(
            Problem(
                "file",
                f"{source} is not valid TOML{where} ({message}); "
                "write key = value lines under [section] headers, text in "
                "double quotes",
            )
        ) from None


def load_case(path_or_text: str | Path) -> Case:
    """Validated case from a file (``pathlib.Path`` or str path) or from TOML text.

    A str is read as a path when it names an existing file, or when it is a single line without
    ``=`` (then a missing file is reported as such); otherwise it is TOML text. Raises
    :class:`solver.errors.CaseError` listing every problem found.
    """
    if isinstance(path_or_text, Path):
        path = path_or_text
        text, source = read_case_text(path), str(path)
    elif isinstance(path_or_text, str):
        candidate = Path(path_or_text.strip()) if _looks_like_path(path_or_text) else None
        if candidate is not None:
            text, source = read_case_text(candidate), str(candidate)
        else:
            text, source = path_or_text, "case text"
    else:
        raise CaseError(
            Problem(
                "file", f"load_case needs a path or TOML text, not {type(path_or_text).__name__}"
            )
        )
    return validate(parse_toml(text, source))
