"""The study warm-up compiles the kernels the study's own runs use: one case per model and
lubricant traction path (the rheology path too), before the points start."""

from __future__ import annotations

import pytest

pytest.importorskip("distributed")


def test_warm_up_cases_cover_each_model_and_traction_path():
    from solver.study import Study
    from solver.study.worker import warm_up_cases

    study = Study.from_text(
        'title = "paths"\nbase = "spindle-combined-load"\nmodel = "both"\n'
        '[vary]\n"lubricant.traction_model" = ["slip_curve", "rheology", "rheology"]\n'
    )
    cases = warm_up_cases(study.points())
    paths = [(model, case.lubricant.traction_model) for model, case in cases]
    assert sorted(paths) == [
        ("dynamic", "rheology"),
        ("dynamic", "slip_curve"),
        ("quasistatic", "rheology"),
        ("quasistatic", "slip_curve"),
    ]


def test_the_warm_up_note_says_compiling_on_a_cold_cache(monkeypatch):
    import solver.compiled
    from solver.study.runner import _warm_up_note

    monkeypatch.setattr(solver.compiled, "dynamic_model_compiled", lambda: False)
    assert "compiling the solver kernels the study uses (first run only)" in _warm_up_note(True)
    assert "not counted in the ETA" in _warm_up_note(True)
    monkeypatch.setattr(solver.compiled, "dynamic_model_compiled", lambda: True)
    assert _warm_up_note(True).startswith("loading the compiled solver kernels")
