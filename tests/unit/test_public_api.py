"""The public solver API names resolve to what solver/__init__ promises."""

import importlib


def test_catalogue_stays_the_function_after_its_submodule_is_imported():
    importlib.import_module("solver.catalogue")
    import solver

    assert callable(solver.catalogue)
    assert "spindle-combined-load" in [entry.name for entry in solver.catalogue()]


def test_lazy_names_resolve():
    import solver

    for name in (
        "load_case",
        "Case",
        "solve_quasistatic",
        "simulate",
        "save_dataset",
        "load_dataset",
        "result_warnings",
    ):
        assert getattr(solver, name) is not None, name
    assert "result_warnings" in solver.__all__


def test_result_warnings_is_the_checks_function():
    import solver
    from solver.results.checks import result_warnings

    assert solver.result_warnings is result_warnings


def test_dir_lists_the_lazy_public_names():
    import solver

    listed = dir(solver)
    for name in ("load_case", "parse_case", "solve_quasistatic", "simulate", "SimulationOptions"):
        assert name in listed


def test_every_public_name_resolves():
    import solver

    for name in solver.__all__:
        assert getattr(solver, name) is not None, name


def test_layer_contracts_hold():
    """The layers written as import-linter contracts in pyproject.toml (solver never imports a view,
    physics never imports models, models never resolve catalogue names, views use only the public
    door, the report never imports the app, the app has no import cycle)."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    lint = Path(sys.executable).with_name("lint-imports")
    done = subprocess.run(
        [str(lint)],
        cwd=root,
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"},
        timeout=300,
    )
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
