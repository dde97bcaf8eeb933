"""The report installs and runs with the ``report`` extra alone: it never imports the app or the
command line, and builds a page when trame, the app and the CLI cannot be imported."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("panel")
pytest.importorskip("pyvista")

ROOT = Path(__file__).parents[2]

# Solves the default case quasi-statically and builds its report in a clean interpreter in which
# trame (any ``trame*`` module), ``app`` and ``racetrace`` are not installed; prints what the
# report returned and every import of a blocked module that was tried (also those caught).
BLOCKED_BUILD = """import json
import sys


class NotInstalled:
    tried = []

    def find_spec(self, name, path=None, target=None):
        top = name.split(".")[0]
        if top.startswith("trame") or top in ("app", "racetrace"):
            self.tried.append(name)
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


sys.meta_path.insert(0, NotInstalled())
import solver
import report

result = sys.argv[1] + "/qs.nc"
solver.save_dataset(
    solver.solve_quasistatic(solver.catalogue().get("spindle-combined-load").load()), result
)
info = report.build_report(result, sys.argv[1] + "/review.html")
print(json.dumps({"kind": info["kind"], "unresolved": info["unresolved"],
                  "tried": NotInstalled.tried}))
"""


def imported_packages(package: str) -> dict[str, set[str]]:
    """Top-level packages each module of ``package`` (a folder at the repository root) imports,
    relative imports resolved."""
    found = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        names = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom):
                names.add(package if node.level else (node.module or "").split(".")[0])
        found[str(path.relative_to(ROOT))] = names
    return found


@pytest.mark.parametrize(
    "package, forbidden",
    [("report", {"app", "racetrace"}), ("viz", {"app", "racetrace", "report"})],
)
def test_report_and_drawing_package_never_import_the_app_or_the_cli(package, forbidden):
    modules = imported_packages(package)
    assert modules, f"no modules found under {package}/"
    wrong = {module: sorted(names & forbidden) for module, names in modules.items()}
    assert not any(wrong.values()), {m: n for m, n in wrong.items() if n}


def test_report_builds_without_trame_the_app_or_the_cli(tmp_path):
    result = subprocess.run(
        [sys.executable, "-c", BLOCKED_BUILD, str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=900,
        cwd=ROOT,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    info = json.loads(result.stdout.splitlines()[-1])
    assert info == {"kind": "run", "unresolved": [], "tried": []}
    assert (tmp_path / "review.html").stat().st_size > 100_000
