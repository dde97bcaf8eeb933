"""Faults for the reliability tests: a read-only folder, a small (full) file system and a NetCDF
write that fails half-way.

Both work for any user: an ordinary user gets a folder without write permission; root, whom
permissions do not stop, gets a read-only or a tiny tmpfs mounted on the folder (skipped where
mounting is not allowed). Mounts are always undone.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
from pathlib import Path

import pytest


def _mount(args: list[str]) -> bool:
    try:
        done = subprocess.run(["mount", *args], capture_output=True, timeout=20)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


def _umount(path: Path) -> None:
    subprocess.run(["umount", "-l", str(path)], capture_output=True, timeout=20)


@contextlib.contextmanager
def read_only_folder(path: Path):
    """``path`` (created, empty) as a folder nobody can write in, for the ``with`` block."""
    path.mkdir(parents=True, exist_ok=True)
    if os.geteuid() != 0:
        path.chmod(0o555)
        try:
            yield path
        finally:
            path.chmod(0o755)
        return
    if not _mount(["-t", "tmpfs", "-o", "ro,size=64k", "tmpfs", str(path)]):
        pytest.skip("running as root and cannot mount a read-only tmpfs")
    try:
        yield path
    finally:
        _umount(path)


@contextlib.contextmanager
def small_file_system(path: Path, size: str = "64k"):
    """``path`` as a tmpfs of ``size`` bytes (full after a few writes), for the ``with`` block."""
    path.mkdir(parents=True, exist_ok=True)
    if not _mount(["-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)]):
        pytest.skip("cannot mount a small tmpfs here")
    try:
        yield path
    finally:
        _umount(path)


def check_failed_write_keeps_the_old_file(target: Path, write, monkeypatch) -> None:
    """``write()`` saves over the existing NetCDF file ``target``; let xarray's writer leave a
    partial file and fail as a full disk does: ``write`` raises that OSError, ``target`` keeps its
    old bytes and no temporary file is left beside it."""
    import xarray as xr

    before = target.read_bytes()

    def broken(self, *args, **kwargs):
        Path(args[0]).write_bytes(b"partial")
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", broken)
    with pytest.raises(OSError, match="disk full"):
        write()
    assert target.read_bytes() == before
    assert sorted(p.name for p in target.parent.iterdir()) == [target.name]
