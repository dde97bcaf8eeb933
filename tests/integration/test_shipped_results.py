"""Shipped lesson results against a fresh solve: a change that moves a result must bump
``solver.RESULTS_VERSION`` (and regenerate the shipped files with tools/make_lesson_results.py).

Each shipped result is solved again from its lesson's case; the figures a lesson reads are compared
with the shipped file: every quasi-static contact load and angle, and for a dynamic run the means
over its analysed window of the contact loads and angles of each race, the cage speed and the
friction torque. A shipped file whose results version is the current one must agree within the
tolerances below; one of an older version fails the fast test of its fingerprint instead.
"""

from __future__ import annotations

import numpy as np
import pytest

import solver
from app.lessons import results as lesson_results
from app.lessons.format import load_lessons

LESSONS = load_lessons()
SPECS = [(lesson, spec) for lesson in LESSONS.lessons for spec in lesson.results]

#: Relative agreement of a quasi-static result (a deterministic Newton solve, stored in double).
QUASISTATIC_RTOL = 1e-6
#: Relative agreement of a dynamic run's window means (stored in single precision; a change at the
#: rounding level moves an explicit run of several revolutions by a few tenths of a percent).
DYNAMIC_RTOL = 1e-2


def _window_means(ds) -> dict[str, np.ndarray]:
    """Means over the analysed window of what a dynamic lesson reads."""
    window = ds.sel(time=slice(float(ds["analysis_start_time"]), None))
    return {
        "contact_load": window["contact_load"].mean(("time", "ball")).values,
        "contact_angle": window["contact_angle"].mean(("time", "ball")).values,
        "cage_speed": window["cage_speed"].mean("time").values,
        "friction_torque": window["friction_torque"].mean("time").values,
    }


def _figures(ds) -> dict[str, np.ndarray]:
    if ds.attrs.get("model") == "dynamic":
        return _window_means(ds)
    return {name: ds[name].values for name in ("contact_load", "contact_angle")}


@pytest.mark.slow
@pytest.mark.parametrize(
    ("lesson", "spec"), SPECS, ids=[f"{lesson.id}--{spec.name}" for lesson, spec in SPECS]
)
def test_shipped_result_matches_a_fresh_solve(lesson, spec):
    path = lesson_results.shipped_results_dir() / lesson_results.shipped_name(lesson, spec)
    shipped = solver.load_dataset(path)
    assert shipped.attrs.get(lesson_results.FINGERPRINT_ATTR) == lesson_results.fingerprint(spec), (
        f"{path.name} is out of date: run python tools/make_lesson_results.py"
    )
    assert int(shipped.attrs[lesson_results.RESULTS_VERSION_ATTR]) == solver.RESULTS_VERSION
    fresh = lesson_results.compute(spec)
    rtol = DYNAMIC_RTOL if spec.model == "dynamic" else QUASISTATIC_RTOL
    for name, expected in _figures(shipped).items():
        got = _figures(fresh)[name]
        scale = np.max(np.abs(expected))
        worst = float(np.max(np.abs(got - expected)) / scale)
        assert worst <= rtol, (
            f"{path.name}: {name} moved by {worst:.2e} of its largest value (allowed {rtol:g}) "
            f"while solver.RESULTS_VERSION is still {solver.RESULTS_VERSION}: if the change is "
            "meant, bump RESULTS_VERSION in solver/results/provenance.py and run "
            "python tools/make_lesson_results.py"
        )
