"""Save and load results Datasets as NetCDF (netCDF4 engine), and export the per-contact table as
CSV; every file is written atomically."""

from __future__ import annotations

import errno
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

import xarray as xr

ENGINE = "netcdf4"
_PER_CONTACT_DIMS = {"ball", "race", "time", "ring_angle"}  # ring_angle: over one revolution
_COMPONENT_DIMS = {"axis", "tilt_axis", "quaternion", "frame", "body"}  # not one value per contact


def save_dataset(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` to ``path`` atomically: a temporary file in the same directory, then os.replace.

    The temporary file is removed if writing fails; an existing file at ``path`` is left untouched
    then, and :class:`solver.errors.ResultWriteError` names ``path`` and the reason (a missing or
    read-only folder, a full disk, a file-size limit). String variables (e.g. ``race_control``)
    are stored as NetCDF variable-length strings. Returns the path written.
    """
    return atomic_write(path, lambda tmp: ds.to_netcdf(tmp, engine=ENGINE))


def load_dataset(path) -> xr.Dataset:
    """Read a results Dataset fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        return ds.load()


#: Errors netCDF4 and xarray raise for a file that is not NetCDF, is cut short, or holds
#: attributes they cannot decode (a units or fill-value attribute of the wrong type, say).
_READ_ERRORS = (
    OSError,
    RuntimeError,
    ValueError,
    TypeError,
    KeyError,
    IndexError,
    AttributeError,
    OverflowError,
    RecursionError,
    MemoryError,
)


def load_result(path, source: str | None = None) -> xr.Dataset:
    """Read the racetrace result (or study Dataset) at ``path`` fully into memory, after checking
    that it is one (:func:`solver.results.validate.check_result`) and that it fits in the free
    memory; the values the views draw are checked too (finite positions). Anything else, a file
    that cannot be read included, is a :class:`solver.errors.CaseError` naming ``source``
    (default: the path) and what is wrong."""
    from solver.errors import CaseError, Problem, clean_message

    from .validate import check_result

    source = str(path) if source is None else source

    def unreadable(error: BaseException) -> CaseError:
        reason = clean_message(getattr(error, "strerror", None) or error or type(error).__name__)
        return CaseError(
            Problem("result", f"{source}: not a readable results NetCDF file ({reason[:300]})")
        )

    try:
        ds = xr.open_dataset(path, engine=ENGINE)
    except _READ_ERRORS as error:
        raise unreadable(error) from None
    with ds:
        check_result(ds, source)
        need = sum(int(v.nbytes) for v in ds.variables.values())
        free = available_memory_bytes()
        if free is not None and need > free:
            raise CaseError(
                Problem(
                    "result",
                    f"{source} needs about {need / 1e6:,.0f} MB of memory to read and "
                    f"{free / 1e6:,.0f} MB are free",
                )
            )
        try:
            loaded = ds.load()
        except _READ_ERRORS as error:
            raise unreadable(error) from None
    return check_result(loaded, source, values=True)


def available_memory_bytes() -> int | None:
    """Memory available to a new allocation (Linux MemAvailable: free memory and the caches the
    system can drop), None where unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def contact_table(ds: xr.Dataset):
    """The per-contact variables of a result as a flat table (pandas DataFrame).

    One row per (time or ring angle,) ball and race, with the index columns ``time`` (dynamic
    results) or ``ring_angle`` (a quasi-static solution over one revolution), ``ball`` and ``race``
    first; one column per numeric variable with dims (ball, race[, time]), named
    ``<variable> [<units>]``, in the Dataset's units (angles in degree). ValueError when the result
    has no per-contact variable (or holds several results: select one element first).
    """
    names = [
        n
        for n, v in ds.data_vars.items()
        if {"ball", "race"} <= set(v.dims)
        and not set(v.dims) & _COMPONENT_DIMS
        and v.dtype.kind in "fiu"
    ]
    if not names:
        raise ValueError("the result has no per-contact variables (ball, race) to export")
    extra = [d for d in ds[names].dims if d not in _PER_CONTACT_DIMS]
    if extra:
        raise ValueError(
            f"the result holds several results along {', '.join(extra)}: select one element "
            "first (e.g. ds.isel(" + extra[0] + "=0))"
        )
    sub = ds[names].reset_coords(drop=True)
    order = [d for d in ("time", "ring_angle", "ball", "race") if d in sub.dims]
    frame = sub.to_dataframe(dim_order=order).reset_index()
    return frame.rename(columns={n: f"{n} [{ds[n].attrs.get('units', '1')}]" for n in names})


def save_csv(ds: xr.Dataset, path) -> Path:
    """Write :func:`contact_table` of ``ds`` to ``path`` as CSV, atomically. Returns the path."""
    table = contact_table(ds)
    return atomic_write(path, lambda tmp: table.to_csv(tmp, index=False))


def probe_write(folder, prefix: str, suffix: str = "") -> None:
    """Write a small temporary file named ``<prefix>...<suffix>`` in ``folder`` and remove it:
    OSError when the folder cannot take a new file now (missing, not a folder, read-only, full)."""
    fd, probe = tempfile.mkstemp(prefix=prefix, suffix=suffix, dir=folder)
    try:
        os.write(fd, b"racetrace")
    finally:
        os.close(fd)
        os.remove(probe)


def atomic_write(path, write: Callable[[str], object]) -> Path:
    """Call ``write(temporary_path)`` for a temporary file next to ``path``, then move it onto
    ``path``. On any failure, an interruption (KeyboardInterrupt, SystemExit) included, the
    temporary file is removed and ``path`` is left as it was. The file gets the permissions the
    umask gives a new file. Returns ``Path(path)``.

    A failure to write (OSError, or the RuntimeError netCDF4 raises for a full disk) is raised as
    :class:`solver.errors.ResultWriteError` naming ``path``; an existing ``path`` that is not a
    regular file (a folder, a device such as /dev/null) is refused the same way, never replaced.
    """
    from solver.errors import ResultWriteError

    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise ResultWriteError(path, "it is a folder; give a file name")
    if path.exists() and not path.is_file():
        raise ResultWriteError(path, "it exists and is not a regular file")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    except OSError as error:
        raise ResultWriteError(path, _reason(error)) from error
    os.close(fd)
    try:
        write(tmp)
        os.chmod(tmp, 0o666 & ~_current_umask())  # mkstemp made it private (0600)
        os.replace(tmp, path)
    except BaseException as error:
        try:
            os.remove(tmp)
        except FileNotFoundError:
            pass
        if isinstance(error, OSError | RuntimeError) and not isinstance(error, ResultWriteError):
            raise ResultWriteError(path, _reason(error)) from error
        raise
    return path


def _reason(error: BaseException) -> str:
    """Why a write failed, in words: the OS's reason, or netCDF4's message with a hint."""
    if isinstance(error, OSError) and error.strerror:
        reason = error.strerror
        if error.errno == errno.EFBIG:
            reason += " (a file-size limit, e.g. ulimit -f)"
        return reason
    text = str(error) or type(error).__name__
    if isinstance(error, RuntimeError):  # netCDF4 gives no errno: "NetCDF: HDF error" and such
        text += " (is the disk full or the folder read-only?)"
    return text


def _current_umask() -> int:
    """The process umask (read by setting and restoring it)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
