"""The numba cache folder follows every change of the solver sources (stale callers are never
loaded)."""

import os
import subprocess
import sys
from pathlib import Path

from solver._numba_cache import configure_numba_cache, source_fingerprint


def test_fingerprint_changes_with_any_source_file(tmp_path):
    (tmp_path / "physics").mkdir()
    (tmp_path / "kernels.py").write_text("def rhs(): return callee()\n")
    (tmp_path / "physics" / "callee.py").write_text("def callee(): return 1.0\n")
    before = source_fingerprint(tmp_path)
    assert source_fingerprint(tmp_path) == before
    (tmp_path / "physics" / "callee.py").write_text("def callee(): return 2.0\n")  # callee only
    assert source_fingerprint(tmp_path) != before


def test_solver_import_points_numba_at_a_folder_keyed_by_the_sources(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["XDG_CACHE_HOME"] = str(tmp_path)
    code = "import os, solver, numba; print(os.environ['NUMBA_CACHE_DIR'])"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    folder = Path(out.stdout.strip())
    solver_dir = Path(__file__).parents[2] / "solver"
    assert folder.name == f"numba-{source_fingerprint(solver_dir)}"
    assert folder.is_dir() and tmp_path in folder.parents


def test_a_users_numba_cache_dir_is_respected(monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "mine"))
    assert configure_numba_cache(tmp_path) is None
    assert os.environ["NUMBA_CACHE_DIR"] == str(tmp_path / "mine")
