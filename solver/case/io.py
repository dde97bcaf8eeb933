"""Reading cases: :func:`load_case` reads a case file, :func:`parse_case` reads TOML text.

Nothing here guesses whether a string is a path or TOML: a path goes to :func:`load_case`, text to
:func:`parse_case`. Errors are :class:`solver.errors.CaseError` messages that name the file (or the
source of the text) and say what to do, never tracebacks.
"""

from __future__ import annotations

import os
import re
import stat
import tomllib
from pathlib import Path

from solver.errors import CaseError, Problem

from .model import Case

#: Largest case file or text accepted, in bytes. A case file is a few kB; the limit keeps a wrong
#: file (a log, a data file, /proc or /dev entries) from filling the memory.
MAX_CASE_BYTES = 1_000_000

_LOCATION = re.compile(r"\(at line (\d+), column (\d+)\)")
_SHOWN_LINE = 80  # longest line quoted in a message


def _file_problem(message: str) -> CaseError:
    return CaseError(Problem("file", message))


def _kind(mode: int) -> str:
    """What a non-regular file is, in words."""
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _too_large(source: str) -> CaseError:
    return _file_problem(
        f"{source} is larger than {MAX_CASE_BYTES // 1_000_000} MB: a case file holds a few kB of "
        "TOML; check that this is the case file you meant"
    )


def read_case_bytes(path: Path) -> bytes:
    """Bytes of the case file ``path``, at most :data:`MAX_CASE_BYTES`; CaseError otherwise.

    Only a regular file is opened: its type is checked before opening (opening a FIFO would wait
    for a writer) and again on the open file. At most ``MAX_CASE_BYTES + 1`` bytes are read, so a
    file that reports a wrong size (such as those under /proc) cannot exhaust the memory.
    """
    # a path with a line break is almost surely case text given in the place of a path
    hint = " (load_case reads a file; parse_case reads TOML text)" if "\n" in str(path) else ""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise _file_problem(f"case file not found: {path}{hint}") from None
    except OSError as error:
        raise _file_problem(f"cannot read {path}: {error.strerror}{hint}") from None
    if stat.S_ISDIR(info.st_mode):
        raise _file_problem(f"{path} is a folder, not a case file: give a .toml file")
    if not stat.S_ISREG(info.st_mode):
        raise _file_problem(
            f"{path} is {_kind(info.st_mode)}, not a case file: give a .toml file saved on disk"
        )
    if info.st_size > MAX_CASE_BYTES:
        raise _too_large(str(path))
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(path, flags)
    except OSError as error:
        raise _file_problem(f"cannot read {path}: {error.strerror}") from None
    with os.fdopen(fd, "rb") as handle:
        mode = os.fstat(handle.fileno()).st_mode
        if not stat.S_ISREG(mode):  # replaced between the check and the opening
            raise _file_problem(
                f"{path} is {_kind(mode)}, not a case file: give a .toml file saved on disk"
            )
        try:
            data = handle.read(MAX_CASE_BYTES + 1)
        except OSError as error:
            raise _file_problem(f"cannot read {path}: {error.strerror}") from None
    if len(data) > MAX_CASE_BYTES:
        raise _too_large(str(path))
    return data


def decode_case_bytes(data: bytes, source: str = "case text") -> str:
    """Text of a case file's bytes: UTF-8, with or without a byte-order mark; CaseError if the
    bytes are not UTF-8 text or exceed :data:`MAX_CASE_BYTES`."""
    if len(data) > MAX_CASE_BYTES:
        raise _too_large(source)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise _file_problem(
            f"{source} is not a text file (not UTF-8: {error.reason} at byte {error.start}); "
            "save the case as UTF-8 text"
        ) from None


def parse_toml(text: str, source: str = "case text") -> dict:
    """Nested dict from TOML text; CaseError naming the line (and showing it) if it is not TOML."""
    if len(text) > MAX_CASE_BYTES or len(text.encode("utf-8", "surrogatepass")) > MAX_CASE_BYTES:
        raise _too_large(source)
    if not text.strip() or all(
        not line.strip() or line.lstrip().startswith("#") for line in text.splitlines()
    ):
        raise _file_problem(
            f"{source} is empty: a case needs at least a [bearing] and "
            "an [operating] section (see `racetrace cases show NAME`)"
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
            shown = lines[line_no - 1].strip() if 0 < line_no <= len(lines) else ""
            if len(shown) > _SHOWN_LINE:
                shown = shown[: _SHOWN_LINE - 4] + " ..."
            message = _LOCATION.sub("", message).strip()
            where = f" at line {line_no}, column {match.group(2)}" + (
                f": {shown!r}" if shown else ""
            )
        raise _file_problem(
            f"{source} is not valid TOML{where} ({message}); "
            "write key = value lines under [section] headers, text in double quotes"
        ) from None
    except RecursionError:
        raise _file_problem(
            f"{source} nests arrays or tables hundreds of levels deep; a case file has sections "
            "of key = value lines (at most one inline table deep)"
        ) from None
    except (ValueError, OverflowError) as error:  # e.g. an integer with thousands of digits
        raise _file_problem(
            f"{source} holds a value that cannot be read ({error}); "
            "write numbers as decimals such as 500.0 or 1.5e3"
        ) from None


def parse_case(text: str, source: str = "case text", base_dir=None) -> Case:
    """Validated case from TOML ``text`` (never read as a path). ``source`` names the text in
    messages (e.g. an uploaded file's name); ``base_dir`` is the folder a history file
    (``{ file = ... }``) is read from (None: the text has no folder, and a history file is an
    error). Raises :class:`CaseError` listing every problem."""
    if not isinstance(text, str):
        raise TypeError(f"parse_case needs TOML text (str), not {type(text).__name__}")
    data = parse_toml(text, source)
    try:
        return Case.from_dict(data, base_dir)
    except RecursionError:
        raise _file_problem(
            f"{source} nests values too deeply to be a case: a case file has sections of "
            "key = value lines"
        ) from None


def load_case(path: str | os.PathLike) -> Case:
    """Validated case from the case file at ``path`` (a ``pathlib.Path`` or a str path; a str is
    always a path, never TOML text: use :func:`parse_case` for text).

    Refuses anything but a regular file of at most 1 MB of UTF-8 text (a byte-order mark is
    accepted). Raises :class:`CaseError` listing every problem found.
    """
    if not isinstance(path, str | os.PathLike):
        raise TypeError(f"load_case needs a path (str or pathlib.Path), not {type(path).__name__}")
    path = Path(path)
    text = decode_case_bytes(read_case_bytes(path), str(path))
    return parse_case(text, str(path), path.resolve().parent)
