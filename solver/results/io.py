"""Save and load results Datasets as NetCDF (netCDF4 engine), atomically."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import xarray as xr

ENGINE = "netcdf4"


def save_dataset(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` to ``path`` atomically: a temporary file in the same directory, then os.replace.

    The temporary file is removed if writing fails; an existing file at ``path`` is left untouched
    then. String variables (e.g. ``race_control``) are stored as NetCDF variable-length strings.
    Returns the path written.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine=ENGINE)
        os.chmod(tmp, 0o666 & ~_current_umask())  # mkstemp made it private (0600)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def load_dataset(path) -> xr.Dataset:
    """Read a results Dataset fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        return ds.load()


def _current_umask() -> int:
    """The process umask (read by setting and restoring it)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
