"""Finding a lesson's results: the shipped file when current, else the cache, else one solve that
is then cached."""

from __future__ import annotations

import pytest

import solver
from app.lessons import results as lesson_results
from app.lessons.format import load_lessons, parse_lesson

LESSONS = load_lessons()

NEW = """
title = "new"
[[results]]
name = "main"
case = "spindle-axial-preload"
overrides = { "operating.axial_load_N" = 321.0 }
[text]
try_this = "more"
[[text.explain]]
say = "{axial_load:.0f} N"
descriptive = true
"""


def test_shipped_result_is_used(tmp_path, monkeypatch):
    monkeypatch.setattr(lesson_results, "compute", lambda spec: pytest.fail("solved"))
    lesson = LESSONS.get("02-speed")
    ds, where = lesson_results.lesson_result(lesson, lesson.results[0], cache_dir=tmp_path)
    assert where == "shipped" and float(ds.coords["inner_ring_speed"]) > 3000.0
    assert list(tmp_path.iterdir()) == []


def test_new_lesson_is_solved_once_then_cached(tmp_path, monkeypatch):
    lesson = parse_lesson(NEW, "07-new")
    spec = lesson.results[0]
    ds, where = lesson_results.lesson_result(lesson, spec, cache_dir=tmp_path)
    assert where == "computed" and float(ds.coords["axial_load"]) == 321.0
    assert [p.name for p in tmp_path.iterdir()] == [f"{lesson_results.fingerprint(spec)}.nc"]
    monkeypatch.setattr(lesson_results, "compute", lambda spec: pytest.fail("solved again"))
    again, where = lesson_results.lesson_result(lesson, spec, cache_dir=tmp_path)
    assert where == "cache"
    assert float(again["contact_angle"].max()) == pytest.approx(float(ds["contact_angle"].max()))


def test_changed_case_does_not_reuse_a_shipped_file(tmp_path, monkeypatch):
    # the shipped 02-speed--speed.nc belongs to 30 000 rpm; at 25 000 rpm it must be solved anew
    text = (lesson_results.shipped_results_dir().parent / "02-speed.toml").read_text("utf-8")
    lesson = parse_lesson(text.replace("= 30000.0", "= 25000.0"), "02-speed")
    calls = []
    real = lesson_results.compute
    monkeypatch.setattr(lesson_results, "compute", lambda spec: calls.append(spec) or real(spec))
    ds, where = lesson_results.lesson_result(lesson, lesson.results[0], cache_dir=tmp_path)
    assert where == "computed" and len(calls) == 1
    assert float(ds.coords["inner_ring_speed"]) == pytest.approx(25000.0 * 3.141592653589793 / 30)


def test_unreadable_cache_file_is_solved_again(tmp_path):
    lesson = parse_lesson(NEW, "07-new")
    spec = lesson.results[0]
    (tmp_path / f"{lesson_results.fingerprint(spec)}.nc").write_text("garbage")
    _, where = lesson_results.lesson_result(lesson, spec, cache_dir=tmp_path)
    assert where == "computed"


def test_fingerprint_follows_case_model_and_length():
    base = parse_lesson(NEW, "a").results[0]
    other_load = parse_lesson(NEW.replace("321.0", "322.0"), "a").results[0]
    dynamic = parse_lesson(NEW.replace('name = "main"', 'name = "main"\nmodel = "dynamic"'), "a")
    longer = parse_lesson(
        NEW.replace('name = "main"', 'name = "main"\nmodel = "dynamic"\nshaft_revolutions = 5'),
        "a",
    )
    prints = {
        lesson_results.fingerprint(s)
        for s in (base, other_load, dynamic.results[0], longer.results[0])
    }
    assert len(prints) == 4
    assert lesson_results.fingerprint(base) == lesson_results.fingerprint(
        parse_lesson(NEW.replace('title = "new"', 'title = "renamed"'), "b").results[0]
    )


def test_cache_dir_from_environment(tmp_path):
    assert lesson_results.lesson_cache_dir({"RACETRACE_LESSON_CACHE": str(tmp_path)}) == tmp_path
    assert lesson_results.lesson_cache_dir({}).name == "lessons"


def test_fingerprint_follows_the_results_version_not_the_case_text(monkeypatch):
    """A comment or help-text change leaves the fingerprint alone; a results-version bump (a
    physics change that moves results) changes it, so shipped and cached results are redone."""
    from solver.results import provenance

    spec = parse_lesson(NEW, "a").results[0]
    case = spec.case()
    commented = solver.parse_case("# a comment\n" + case.to_toml().replace("\n", "  # note\n", 3))
    assert solver.result_fingerprint(commented, "quasistatic") == solver.result_fingerprint(
        case, "quasistatic"
    )
    before = lesson_results.fingerprint(spec)
    monkeypatch.setattr(provenance, "RESULTS_VERSION", provenance.RESULTS_VERSION + 1)
    assert lesson_results.fingerprint(spec) != before


def test_fingerprint_covers_values_from_the_bearing_and_the_named_oil():
    """Values the case does not write (estimated from the bearing, or from a named oil) still
    determine the result and so the fingerprint."""
    spec = parse_lesson(NEW, "a").results[0]
    case = spec.case()
    oiled = case.with_values({"lubricant.oil": "ester-vg22"})
    other_oil = case.with_values({"lubricant.oil": "spindle-mineral-vg32"})
    prints = {solver.result_fingerprint(c, "quasistatic") for c in (case, oiled, other_oil)}
    assert len(prints) == 3
