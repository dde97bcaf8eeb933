"""`racetrace cache` and `racetrace cache clean [--all]`: what is listed, what is removed, what is
kept. Each run has its own user cache and temp folders."""

from __future__ import annotations

import errno
import os
import subprocess
import sys
from pathlib import Path

import pytest

import solver
from racetrace import cli
from racetrace.commands.cache import format_size
from solver import _numba_cache
from solver._numba_cache import CacheFolder, remove_folders, version_folder_name

CURRENT = version_folder_name(Path(solver.__file__).parent)
OTHER = "racetrace-numba-0123456789abcdef"
LEGACY = "numba-fedcba9876543210"  # the name in racetrace's own cache folder in older installs


def env_for(tmp_path: Path, numba_cache_dir: Path | None = None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    (tmp_path / "tmp").mkdir(exist_ok=True)
    env.update(XDG_CACHE_HOME=str(tmp_path / "xdg"), TMPDIR=str(tmp_path / "tmp"))
    if numba_cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(numba_cache_dir)
    return env


def racetrace(env, *args):
    return subprocess.run(
        [sys.executable, "-m", "racetrace", "cache", *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )


def fill(folder: Path, size: int) -> Path:
    (folder / "sub").mkdir(parents=True)
    (folder / "sub" / "kernel.nbc").write_bytes(b"\0" * size)
    return folder


@pytest.fixture
def user_cache(tmp_path):
    """racetrace's user cache folder with two old versions, an unrelated folder and a symlink."""
    root = tmp_path / "xdg" / "racetrace"
    fill(root / OTHER, 2500)
    fill(root / LEGACY, 1500)
    fill(root / "notes", 10)
    target = fill(tmp_path / "elsewhere", 10)
    (root / "racetrace-numba-aaaaaaaaaaaaaaaa").symlink_to(target, target_is_directory=True)
    return root


def test_cache_shows_this_versions_folder_and_the_others_with_sizes(tmp_path, user_cache):
    result = racetrace(env_for(tmp_path))
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert f"compiled kernels of this version: {user_cache / CURRENT} (0 B)" in out
    assert f"{user_cache / OTHER}  2.5 kB" in out
    assert f"{user_cache / LEGACY}  1.5 kB" in out
    assert "other versions (2, 4.0 kB;" in out
    assert "notes" not in out and "aaaaaaaa" not in out


def test_clean_removes_other_versions_only(tmp_path, user_cache):
    env = env_for(tmp_path)
    result = racetrace(env, "clean")
    assert result.returncode == 0, result.stderr
    assert "removed 2 folder(s), 4.0 kB" in result.stdout
    assert sorted(p.name for p in user_cache.iterdir()) == sorted(
        [CURRENT, "notes", "racetrace-numba-aaaaaaaaaaaaaaaa"]
    )
    assert (tmp_path / "elsewhere" / "sub" / "kernel.nbc").is_file()  # symlink not followed
    again = racetrace(env, "clean")
    assert again.returncode == 0 and "nothing to remove" in again.stdout
    assert "other versions: none" in racetrace(env).stdout


def test_clean_all_removes_this_versions_folder_too(tmp_path, user_cache):
    result = racetrace(env_for(tmp_path), "clean", "--all")
    assert result.returncode == 0, result.stderr
    assert "removed 3 folder(s)" in result.stdout
    assert not (user_cache / CURRENT).exists() and not (user_cache / OTHER).exists()
    assert (user_cache / "notes").is_dir()


def test_a_users_numba_cache_dir_is_looked_at_and_only_racetraces_folders_go(tmp_path):
    mine = tmp_path / "mine"
    fill(mine / OTHER, 100)
    fill(mine / "numba-fedcba9876543210", 100)  # not racetrace's name in a folder of the user's
    fill(mine / "their_project_abc", 100)
    env = env_for(tmp_path, numba_cache_dir=mine)
    shown = racetrace(env)
    assert f"compiled kernels of this version: {mine / CURRENT}" in shown.stdout
    assert str(mine / OTHER) in shown.stdout
    assert racetrace(env, "clean").returncode == 0
    assert sorted(p.name for p in mine.iterdir()) == sorted(
        [CURRENT, "numba-fedcba9876543210", "their_project_abc"]
    )


def test_a_folder_that_cannot_be_removed_is_named_and_exits_1(
    monkeypatch, tmp_path, user_cache, capsys
):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.setenv("TMPDIR", str(tmp_path / "tmp"))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(user_cache / CURRENT))
    (tmp_path / "tmp").mkdir()
    real_rmtree = _numba_cache.shutil.rmtree

    def rmtree(path, *args, **kwargs):
        if Path(path).name == LEGACY:
            raise PermissionError(errno.EACCES, "Permission denied", str(path))
        real_rmtree(path, *args, **kwargs)

    monkeypatch.setattr(_numba_cache.shutil, "rmtree", rmtree)
    assert cli.main(["cache", "clean"]) == 1
    captured = capsys.readouterr()
    assert f"cannot remove {user_cache / LEGACY}: Permission denied" in captured.err
    assert "removed 1 folder(s), 2.5 kB" in captured.out
    assert (user_cache / LEGACY).is_dir() and not (user_cache / OTHER).exists()


def test_remove_folders_reports_what_it_could_not_remove(tmp_path):
    not_a_folder = tmp_path / "racetrace-numba-0000000000000000"
    not_a_folder.write_text("")
    gone = tmp_path / "racetrace-numba-1111111111111111"
    failed = remove_folders([CacheFolder(not_a_folder, 0, False), CacheFolder(gone, 0, False)])
    assert [path for path, _ in failed] == [not_a_folder, gone]
    assert all(reason for _, reason in failed)


@pytest.mark.parametrize(
    ("size", "text"),
    [(0, "0 B"), (999, "999 B"), (1500, "1.5 kB"), (2_500_000, "2.5 MB"), (3.2e9, "3.2 GB")],
)
def test_format_size(size, text):
    assert format_size(size) == text
