"""The numba cache folder follows every change of the solver sources, wherever it is (stale callers
are never loaded), falls back to the temp dir when nothing else can be written, and importing the
solver deletes nothing.

Most tests run a small package in a subprocess: ``x.caller`` calls ``y.callee``, both
``@njit(cache=True)``, and the package configures its cache with a copy of solver/_numba_cache.py,
as the solver does.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

import solver
from solver import _numba_cache
from solver._numba_cache import configure_numba_cache, source_fingerprint, version_folder_name

SOLVER_DIR = Path(solver.__file__).parent

INIT = """from pathlib import Path
from ._numba_cache import configure_numba_cache
configure_numba_cache(Path(__file__).parent)
"""
CALLER = """from numba import njit
from .y import callee

@njit(cache=True)
def caller(x):
    return 10.0 * callee(x)
"""
CALLEE = """from numba import njit

@njit(cache=True)
def callee(x):
    return x + {value}
"""
RUN = """import os, sys
if {numba_first}:
    import numba
import kernelpkg.x
print(kernelpkg.x.caller(1.0))
print(os.environ.get("NUMBA_CACHE_DIR", ""))
"""


def make_package(root: Path, value: float, configured: bool = True) -> Path:
    """``root/kernelpkg`` with the callee returning ``x + value``; returns the package folder."""
    package = root / "kernelpkg"
    package.mkdir(parents=True, exist_ok=True)
    if configured:
        shutil.copy(Path(_numba_cache.__file__), package / "_numba_cache.py")
        (package / "__init__.py").write_text(INIT)
    else:
        (package / "__init__.py").write_text("")
    (package / "x.py").write_text(CALLER)
    set_callee(package, value)
    return package


def set_callee(package: Path, value: float) -> None:
    (package / "y.py").write_text(CALLEE.format(value=value))


def clean_env(tmp_path: Path, **overrides: str) -> dict[str, str]:
    """The test process's environment with its own cache, temp and bytecode settings."""
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    (tmp_path / "tmp").mkdir(exist_ok=True)
    env.update(
        XDG_CACHE_HOME=str(tmp_path / "xdg"),
        TMPDIR=str(tmp_path / "tmp"),
        PYTHONDONTWRITEBYTECODE="1",
    )
    env.update(overrides)
    return env


def run_package(root: Path, env: dict[str, str], numba_first: bool = False) -> tuple[float, str]:
    """Call ``kernelpkg.x.caller(1.0)`` in a fresh interpreter; return it and NUMBA_CACHE_DIR."""
    env = {**env, "PYTHONPATH": str(root)}
    code = RUN.format(numba_first=numba_first)
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr
    value, folder = out.stdout.split("\n")[:2]
    return float(value), folder


def unwritable(tmp_path: Path) -> Path:
    """A path that nobody, root included, can create: it lies under a regular file."""
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    return blocker / "cache"


@pytest.fixture
def own_environment(monkeypatch, tmp_path):
    """In-process tests: the environment and numba's setting are restored afterwards."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    config = sys.modules.get("numba.core.config")
    if config is not None:
        monkeypatch.setattr(config, "CACHE_DIR", config.CACHE_DIR)
    return monkeypatch


def test_fingerprint_changes_with_any_source_file(tmp_path):
    (tmp_path / "physics").mkdir()
    (tmp_path / "kernels.py").write_text("def rhs(): return callee()\n")
    (tmp_path / "physics" / "callee.py").write_text("def callee(): return 1.0\n")
    before = source_fingerprint(tmp_path)
    assert source_fingerprint(tmp_path) == before
    (tmp_path / "physics" / "callee.py").write_text("def callee(): return 2.0\n")  # callee only
    assert source_fingerprint(tmp_path) != before


def test_solver_import_points_numba_at_a_folder_keyed_by_the_sources(tmp_path):
    code = "import os, solver, numba; print(os.environ['NUMBA_CACHE_DIR'])"
    out = subprocess.run(
        [sys.executable, "-c", code], env=clean_env(tmp_path), capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    folder = Path(out.stdout.strip())
    assert folder.name == f"racetrace-numba-{source_fingerprint(SOLVER_DIR)}"
    assert folder.is_dir() and folder.parent == tmp_path / "xdg" / "racetrace"
    assert out.stderr == ""


def test_a_users_numba_cache_dir_gets_a_keyed_subfolder_also_when_numba_came_first(tmp_path):
    mine = tmp_path / "mine"
    code = (
        "import os, numba, solver\n"
        "print(os.environ['NUMBA_CACHE_DIR'])\n"
        "print(numba.config.CACHE_DIR)\n"
    )
    env = clean_env(tmp_path, NUMBA_CACHE_DIR=str(mine))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    expected = str(mine / version_folder_name(SOLVER_DIR))
    assert out.stdout.split() == [expected, expected]


def test_a_process_started_by_racetrace_keeps_its_folder(own_environment, tmp_path):
    package = make_package(tmp_path / "src", 1.0)
    first = configure_numba_cache(package)
    assert first == tmp_path / "xdg" / "racetrace" / version_folder_name(package)
    assert configure_numba_cache(package) == first  # the variable it set is taken as is
    set_callee(package, 2.0)  # a newer version started with the older one's variable
    assert configure_numba_cache(package) == first.parent / version_folder_name(package) != first


@pytest.mark.parametrize(
    "where",
    ["users NUMBA_CACHE_DIR", "users NUMBA_CACHE_DIR, numba imported first", "install folder"],
)
def test_changing_only_a_callee_computes_the_new_value(tmp_path, where):
    root = tmp_path / "src"
    package = make_package(root, 1.0)
    if where == "install folder":  # the user cache folder cannot be written
        env = clean_env(tmp_path, XDG_CACHE_HOME=str(unwritable(tmp_path)))
        expected_root = package / "__pycache__"
    else:
        env = clean_env(tmp_path, NUMBA_CACHE_DIR=str(tmp_path / "mine"))
        expected_root = tmp_path / "mine"
    numba_first = "numba imported first" in where

    value, folder = run_package(root, env, numba_first)
    assert value == 20.0
    assert Path(folder) == expected_root / version_folder_name(package)
    assert list(Path(folder).rglob("*.nbi")), "the first run must have filled the cache"
    assert run_package(root, env, numba_first)[0] == 20.0  # served from the cache

    set_callee(package, 2.0)  # x.py, the caller's file, is untouched
    value, new_folder = run_package(root, env, numba_first)
    assert value == 30.0
    assert new_folder != folder


def test_numba_alone_loads_a_stale_caller_after_a_callee_changes(tmp_path):
    """Why the cache folder is keyed: without it, a plain NUMBA_CACHE_DIR gives the old value."""
    root = tmp_path / "src"
    package = make_package(root, 1.0, configured=False)
    env = clean_env(tmp_path, NUMBA_CACHE_DIR=str(tmp_path / "plain"))
    assert run_package(root, env)[0] == 20.0
    set_callee(package, 2.0)
    assert run_package(root, env)[0] == 20.0  # stale: 30.0 is right


def test_nothing_writable_falls_back_to_the_temp_dir_with_one_warning(tmp_path):
    """Real solver sources whose install folder, like the user cache folder, cannot be written."""
    copy = tmp_path / "src"
    shutil.copytree(SOLVER_DIR, copy / "solver", ignore=shutil.ignore_patterns("__pycache__"))
    for folder in [copy / "solver", *(p for p in (copy / "solver").rglob("*") if p.is_dir())]:
        (folder / "__pycache__").write_text("")  # a file where numba's in-tree cache would go
    blocked = unwritable(tmp_path)
    env = clean_env(
        tmp_path,
        HOME=str(blocked),
        XDG_CACHE_HOME=str(blocked),
        PYTHONPATH=str(copy),
    )
    code = (
        "import os, solver\n"
        "assert solver.__file__.startswith(os.environ['PYTHONPATH']), solver.__file__\n"
        "import solver.models.dynamic, solver.models.quasistatic, solver.physics.traction\n"
        "print(os.environ['NUMBA_CACHE_DIR'])\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        cwd=tmp_path,  # not the project folder, which "-c" would put first on sys.path
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert "Traceback" not in out.stderr
    warnings = [line for line in out.stderr.splitlines() if line.startswith("racetrace: warning:")]
    assert len(warnings) == 1, out.stderr
    assert "NUMBA_CACHE_DIR" in warnings[0] and str(blocked) in warnings[0]
    folder = Path(out.stdout.strip())
    assert folder.name == version_folder_name(copy / "solver")
    assert (tmp_path / "tmp") in folder.parents
    assert folder.is_dir() and not folder.parent.stat().st_mode & 0o077  # private to this user


def test_an_unwritable_numba_cache_dir_is_named_in_a_warning(own_environment, tmp_path, capsys):
    blocked = unwritable(tmp_path)
    own_environment.setenv("NUMBA_CACHE_DIR", str(blocked))
    package = make_package(tmp_path / "src", 1.0)
    folder = configure_numba_cache(package)
    assert folder == tmp_path / "xdg" / "racetrace" / version_folder_name(package)
    assert os.environ["NUMBA_CACHE_DIR"] == str(folder)
    err = capsys.readouterr().err
    assert err.count("racetrace: warning:") == 1 and f"NUMBA_CACHE_DIR={blocked}" in err


def test_importing_the_solver_deletes_nothing(tmp_path):
    root = tmp_path / "xdg" / "racetrace"
    old = [root / "racetrace-numba-0123456789abcdef", root / "numba-fedcba9876543210"]
    month_ago = time.time() - 30 * 24 * 3600
    for folder in old:
        folder.mkdir(parents=True)
        (folder / "kernel.nbi").write_bytes(b"x")
        os.utime(folder, (month_ago, month_ago))
    out = subprocess.run(
        [sys.executable, "-c", "import solver"], env=clean_env(tmp_path), capture_output=True
    )
    assert out.returncode == 0, out.stderr
    assert all((folder / "kernel.nbi").is_file() for folder in old)
    assert sorted(p.name for p in root.iterdir()) == sorted(
        [*(f.name for f in old), version_folder_name(SOLVER_DIR)]
    )
