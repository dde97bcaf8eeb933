"""Where a command writes its result: checked before a run, with a fallback when writing fails.

A run can take hours: its output path is checked before it starts (:func:`output_problem`), its
size is compared with the free memory and disk (:func:`size_problems`), and a result that cannot be
written where asked is saved in the temporary folder instead (:func:`save_result`), never lost.
"""

from __future__ import annotations

import os
import resource
import secrets
import shutil
import stat
import sys
import tempfile
from datetime import UTC, datetime
from pathlib import Path

#: A run whose estimate exceeds this fraction of the free memory or disk gets a warning.
WARN_FRACTION = 0.5


def output_problem(path: Path, option: str = "--output", example: str = "run.nc") -> str:
    """Why a result cannot be written to ``path`` ("" when it can): the folder is missing, not a
    folder or not writable, or ``path`` is a folder or a special file (the message then suggests
    the file name ``example`` in it). The check writes and removes a small temporary file in the
    folder."""
    folder = path.parent if str(path.parent) else Path(".")
    try:
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except OSError as error:
        return f"{option} {path}: cannot be used ({error.strerror})"
    if info is not None and stat.S_ISDIR(info.st_mode):
        return f"{option} {path} is a folder: give a file name, such as {path / example}"
    if info is not None and not stat.S_ISREG(info.st_mode):
        return f"{option} {path} exists and is not a regular file: give a file name to write"
    if not folder.exists():
        return f"{option} {path}: folder '{folder}' does not exist; create it or choose another"
    if not folder.is_dir():
        return f"{option} {path}: '{folder}' is not a folder"
    try:
        from solver import probe_write

        probe_write(folder, f".{path.name}.", ".tmp")
    except OSError as error:
        return f"{option} {path}: cannot write in folder '{folder}' ({error.strerror})"
    return ""


def free_memory_bytes() -> int | None:
    """Memory available to a new allocation (Linux MemAvailable), None where unknown."""
    from solver import available_memory_bytes

    return available_memory_bytes()


def _mb(n: float) -> str:
    return f"{n / 1e6:,.0f} MB" if n >= 1e6 else f"{n / 1e3:,.0f} kB"


def _room(
    need: int,
    available: int | None,
    over: str,
    most: str,
    errors: list[str],
    warnings: list[str],
    **words,
) -> None:
    """Append ``over`` to ``errors`` when ``need`` bytes exceed ``available``, or ``most`` to
    ``warnings`` when they take more than :data:`WARN_FRACTION` of it (nothing when ``available``
    is None: unknown). In the messages ``{need}`` and ``{available}`` become sizes in words, and
    the other fields the ``words`` of those names."""
    if available is None:
        return
    fields = {"need": _mb(need), "available": _mb(available), **words}
    if need > available:
        errors.append(over.format(**fields))
    elif need > WARN_FRACTION * available:
        warnings.append(most.format(**fields))


def size_problems(
    memory_bytes: int,
    file_bytes: int,
    folder: Path,
    free_memory: int | None = None,
    free_disk: int | None = None,
    file_limit: int | None = None,
) -> tuple[list[str], list[str]]:
    """(errors, warnings) for a run needing ``memory_bytes`` and a file of ``file_bytes`` in
    ``folder``: an error when the memory, the free disk or the file-size limit (ulimit -f) is
    smaller, a warning when the estimate takes more than half of the memory or disk. The free
    amounts are measured when not given."""
    if free_memory is None:
        free_memory = free_memory_bytes()
    if free_disk is None:
        try:
            free_disk = shutil.disk_usage(folder).free
        except OSError:
            free_disk = None
    if file_limit is None:
        soft, _ = resource.getrlimit(resource.RLIMIT_FSIZE)
        file_limit = None if soft == resource.RLIM_INFINITY else soft
    errors, warnings = [], []
    fix = "give fewer revolutions or samples per revolution, or split the run"
    _room(
        memory_bytes,
        free_memory,
        "the run needs about {need} of memory and {available} are available: {fix}",
        "the run needs about {need} of memory, more than half of the {available} available",
        errors,
        warnings,
        fix=fix,
    )
    _room(
        file_bytes,
        free_disk,
        "the result file will take about {need} and '{folder}' has {available} free: free some "
        "space, choose another --output, or {fix}",
        "the result file will take about {need}, more than half of the {available} free in "
        "'{folder}'",
        errors,
        warnings,
        fix=fix,
        folder=folder,
    )
    if file_limit is not None and file_bytes > file_limit:
        errors.append(
            f"the result file will take about {_mb(file_bytes)}, more than this shell's file-size "
            f"limit of {_mb(file_limit)} (ulimit -f): raise the limit or {fix}"
        )
    return errors, warnings


def fallback_path(path: Path) -> Path:
    """A new file name in the temporary folder for a result that was to go to ``path``."""
    stamp = datetime.now(UTC).strftime("%Y%m%d-%H%M%S")
    name = f"racetrace-{path.stem or 'result'}-{stamp}-{secrets.token_hex(2)}{path.suffix or '.nc'}"
    return Path(tempfile.gettempdir()) / name


def save_result(ds, path: Path, report=None) -> Path | None:
    """Write ``ds`` to ``path``; when that fails, to :func:`fallback_path` instead, saying where
    (``report(message)``, stderr by default). Returns the path written, None when neither could be
    written (both reasons said)."""
    from solver import ResultWriteError, clean_message, save_dataset

    report = report or say
    try:
        return save_dataset(ds, path)
    except ResultWriteError as error:
        first = clean_message(error)
    fallback = fallback_path(path)
    try:
        save_dataset(ds, fallback)
    except ResultWriteError as error:
        report(f"racetrace: {first}; {clean_message(error)}: the result could not be saved")
        return None
    report(f"racetrace: {first}; the result was saved to {fallback} instead")
    return fallback


def say(message: str) -> None:
    """Print on stderr; a closed terminal (after a hang-up) must not stop the command."""
    try:
        print(message, file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass
