"""The packaging contract: the core (no extra) runs the solver and every command but `serve`
without a GUI module, and `serve` checks for exactly the modules of the `app` extra."""

from __future__ import annotations

import importlib.metadata
import re
import subprocess
import sys
import tomllib
from pathlib import Path

from racetrace.commands.serve import APP_MODULES

PYPROJECT = Path(__file__).parents[1] / "pyproject.toml"
GUI_MODULES = ("vtk", "vtkmodules", "pyvista", "trame", "plotly", "imageio", "playwright")

# A clean interpreter imports the solver's public surface and every command module, and runs the
# commands that need no GUI; then it lists the GUI modules that got imported.
CORE_RUN = """import sys
from pathlib import Path

import solver
from racetrace import cli

out = Path(sys.argv[1])
for name in solver.__all__:
    getattr(solver, name)
import solver.models.dynamic, solver.models.quasistatic, solver.results.io  # noqa: E401
parser = cli.build_parser()  # imports every command module
runs = [
    ["cases"],
    ["check", "spindle-combined-load"],
    ["quasistatic", "spindle-combined-load", "--json"],
    ["quasistatic", "spindle-combined-load", "--output", str(out / "qs.nc")],
    ["simulate", "spindle-combined-load", "--revolutions", "0.05", "--quiet",
     "--output", str(out / "run.nc")],
    ["cache"],
]
for argv in runs:
    assert cli.main(argv) == 0, argv
gui = sorted({m.split(".")[0] for m in sys.modules} & set(sys.argv[2].split(",")))
print("GUI:" + ",".join(gui))
"""


def requirement_name(requirement: str) -> str:
    name = re.match(r"[A-Za-z0-9._-]+", requirement).group(0)
    return re.sub(r"[-_.]+", "-", name).lower()


def project():
    return tomllib.loads(PYPROJECT.read_text())["project"]


def test_the_core_imports_no_gui_module(tmp_path):
    result = subprocess.run(
        [sys.executable, "-c", CORE_RUN, str(tmp_path), ",".join(GUI_MODULES)],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert result.stdout.splitlines()[-1] == "GUI:", result.stdout.splitlines()[-1]
    assert (tmp_path / "qs.nc").is_file() and (tmp_path / "run.nc").is_file()


def test_core_dependencies_hold_no_gui_or_test_package():
    core = {requirement_name(r) for r in project()["dependencies"]}
    extras = project()["optional-dependencies"]
    app = {requirement_name(r) for r in extras["app"]}
    test = {requirement_name(r) for r in extras["test"]}
    assert core.isdisjoint(app | test)
    assert "playwright" in test and "playwright" not in app
    assert {"pytest", "hypothesis"} <= test
    assert "ruff" in {requirement_name(r) for r in extras["dev"]}
    assert all(re.search(r">=\s*\d", r) for r in project()["dependencies"] + extras["app"])


def test_serve_checks_exactly_the_modules_of_the_app_extra():
    app = {requirement_name(r) for r in project()["optional-dependencies"]["app"]}
    provided_by = {
        module: {requirement_name(d) for d in dists}
        for module, dists in importlib.metadata.packages_distributions().items()
    }
    for module in APP_MODULES:
        assert provided_by.get(module, set()) & app, f"{module} is not from the app extra"
    for dist in app:
        assert any(dist in provided_by.get(m, set()) for m in APP_MODULES), (
            f"serve does not check for {dist}: add its top-level module to APP_MODULES"
        )
