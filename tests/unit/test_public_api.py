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
