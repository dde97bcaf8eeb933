"""Lesson files: a good file reads into a Lesson; every kind of mistake is named in words; a
broken file in a folder is reported and the others still load."""

from __future__ import annotations

import pytest

from app.lessons.format import (
    CAMERAS,
    CHARTS,
    LessonError,
    load_lessons,
    parse_lesson,
    placeholders,
)

GOOD = """
title = "Axial load"
summary = "one line"

[[results]]
name = "main"
label = "500 N"
case = "spindle-axial-preload"
model = "quasistatic"
overrides = { "operating.axial_load_N" = 300.0 }

[[results]]
name = "run"
case = "spindle-axial-preload"
model = "dynamic"
shaft_revolutions = 3
samples_per_revolution = 24

[view]
camera = "axial"
chart = "ellipse"

[text]
try_this = "Raise the load."

[[text.explain]]
say = "The inner ring carries {axial_load:.0f} N at {run.speed_rpm} rpm."
descriptive = true

[[text.explain]]
say = "The angle is {inner_contact_angle:.2f} deg, above the free angle."
claim."above the free angle" = "inner_contact_angle > free_contact_angle"
"""


def _problems(text: str) -> list[str]:
    with pytest.raises(LessonError) as info:
        parse_lesson(text, "broken")
    assert str(info.value).startswith("lesson broken.toml: ")
    return info.value.problems


def test_good_lesson_reads_completely():
    lesson = parse_lesson(GOOD, "07-mine")
    assert lesson.id == "07-mine" and lesson.title == "Axial load"
    assert [r.name for r in lesson.results] == ["main", "run"]
    main, run = lesson.results
    assert main.overrides == (("operating.axial_load_N", 300.0),)
    assert main.case().operating.axial_load_N == 300.0
    assert run.model == "dynamic" and run.shaft_revolutions == 3.0
    assert run.samples_per_revolution == 24
    assert (lesson.camera, lesson.chart) == ("axial", "ellipse")
    assert lesson.result("run") is run
    with pytest.raises(KeyError):
        lesson.result("nope")
    assert [bool(s.descriptive) for s in lesson.sentences] == [True, False]
    (claim,) = lesson.sentences[1].claims
    assert claim.says == "above the free angle"
    assert claim.holds.names == (("", "inner_contact_angle"), ("", "free_contact_angle"))
    assert lesson.explain.startswith("The inner ring carries {axial_load:.0f} N at")
    # the solved case carries a title naming the lesson and the result, not the catalogue's
    assert main.case().title == "Axial load: 500 N" and run.case().title == "Axial load: run"


def test_defaults_for_view_and_run_length():
    text = GOOD.replace('camera = "axial"\nchart = "ellipse"\n', "").replace(
        "shaft_revolutions = 3\nsamples_per_revolution = 24\n", ""
    )
    lesson = parse_lesson(text, "x")
    assert (lesson.camera, lesson.chart) == ("isometric", "contact_angle")
    assert lesson.results[1].shaft_revolutions == 4.0
    assert lesson.results[1].samples_per_revolution == 60


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (('title = "Axial load"', ""), "title is missing"),
        (('camera = "axial"', 'camera = "top"'), "camera must be one of isometric"),
        (('chart = "ellipse"', 'chart = "pie"'), "chart must be one of contact_angle"),
        (("{axial_load:.0f}", "{axial_lod:.0f}"), "unknown value 'axial_lod'"),
        (("{run.speed_rpm}", "{other.speed_rpm}"), "names the result 'other'"),
        (("{axial_load:.0f}", "{axial_load:.0q}"), "is not a number format"),
        (("{axial_load:.0f}", "{axial_load!r}"), "conversions"),
        (("{axial_load:.0f}", "{axial_load"), "write {{ and }} for literal braces"),
        (
            (
                'case = "spindle-axial-preload"\nmodel = "q',
                'case = "spindle-axial-prelod"\nmodel = "q',
            ),
            "did you mean spindle-axial-preload",
        ),
        (("= 300.0 }", "= -5.0 }"), "overrides: "),
        (('model = "dynamic"', 'model = "fast"'), "model must be one of quasistatic, dynamic"),
        (
            ("shaft_revolutions = 3", "shaft_revolutions = 500"),
            "shaft_revolutions = 500 is outside",
        ),
        (("samples_per_revolution = 24", "samples_per_revolution = 2.5"), "must be a whole number"),
        (('name = "run"', 'name = "Run!"'), "name must be a short lower-case word"),
        (('name = "run"', 'name = "main"'), "result names must differ"),
        (('summary = "one line"', 'sumary = "one line"'), "unknown key sumary"),
        (('try_this = "Raise the load."', ""), "try_this is missing"),
        (("above the free angle.", "below the free angle."), "quotes words the sentence does not"),
        (('free_contact_angle"', 'free_angle"'), "unknown value 'free_angle'"),
        (("> free_contact_angle", "> > free_contact_angle"), "not a condition"),
        (("> free_contact_angle", "> nope.free_contact_angle"), "names the result 'nope'"),
        (("inner_contact_angle > free_contact_angle", "2 > 1"), "names no value"),
        (("descriptive = true", "descriptive = 1"), "descriptive must be true or false"),
        (("descriptive = true\n", ""), "neither a claim nor descriptive = true"),
        (("{axial_load:.0f} N at", "{axial_load:.0f} N, more than"), "marked descriptive"),
        (
            ('[[text.explain]]\nsay = "The inner', '[[text.explain]]\nsai = "The inner'),
            "unknown key sai",
        ),
        (
            ('overrides = { "operating.axial_load_N" = 300.0 }', 'overrides = "more load"'),
            "overrides must be a table of dotted case keys",
        ),
        (("title", "title = ["), "not valid TOML"),
    ],
)
def test_mistakes_are_named(change, expected):
    old, new = change
    assert old in GOOD
    problems = _problems(GOOD.replace(old, new, 1))
    assert any(expected in p for p in problems), problems


def test_quasistatic_result_rejects_run_length():
    text = GOOD.replace('model = "quasistatic"\n', 'model = "quasistatic"\nshaft_revolutions = 2\n')
    assert any("applies to a dynamic result only" in p for p in _problems(text))


def test_no_results():
    start = GOOD.index("[[results]]")
    end = GOOD.index("[view]")
    problems = _problems(GOOD[:start] + GOOD[end:])
    assert any("no [[results]]" in p for p in problems)


def test_every_problem_is_reported_at_once():
    text = GOOD.replace('camera = "axial"', 'camera = "top"').replace(
        'chart = "ellipse"', 'chart = "pie"'
    )
    assert len(_problems(text)) == 2


def test_placeholders_lists_fields():
    assert placeholders("a {x:.1f} b {r.y} {{c}}") == [("x", ".1f"), ("r.y", "")]


def test_broken_file_is_reported_and_the_others_load(tmp_path):
    (tmp_path / "01-good.toml").write_text(GOOD, encoding="utf-8")
    (tmp_path / "02-broken.toml").write_text(GOOD.replace("{axial_load", "{nope"), "utf-8")
    (tmp_path / "03-binary.toml").write_bytes(b"\xff\xfe title")
    (tmp_path / "notes.txt").write_text("not a lesson", encoding="utf-8")
    found = load_lessons(tmp_path)
    assert [lesson.id for lesson in found.lessons] == ["01-good"]
    assert len(found.problems) == 2
    assert found.problems[0].startswith("lesson 02-broken.toml: ")
    assert "unknown value 'nope'" in found.problems[0]
    assert "not UTF-8" in found.problems[1]
    assert found.get("01-good").title == "Axial load"
    with pytest.raises(KeyError, match="lessons: 01-good"):
        found.get("02-broken")


def test_missing_folder_is_reported(tmp_path):
    found = load_lessons(tmp_path / "none")
    assert found.lessons == () and "does not exist" in found.problems[0]


def test_shipped_lessons_all_load():
    found = load_lessons()
    assert found.problems == ()
    assert [lesson.id for lesson in found.lessons] == [
        "01-axial-load",
        "02-speed",
        "03-radial-load",
        "04-misalignment",
        "05-cage",
        "06-overload",
        "07-start-up-skid",
        "08-live-radial-load",
    ]
    for lesson in found.lessons:
        assert lesson.camera in CAMERAS and lesson.chart in CHARTS


def test_lesson_cameras_and_charts_are_the_apps():
    from app.charts import HELP
    from viz.camera import CAMERA_PRESETS

    assert set(CAMERAS) <= set(CAMERA_PRESETS)  # every camera a lesson may name is a preset
    assert set(CHARTS) <= set(HELP)  # and every chart one of the page's chart panels


def test_a_run_along_a_history_lasts_its_case_duration_and_stays_small():
    """A case with a time history runs for its simulation.duration_s: the lesson's run-length keys
    are refused for it, and its samples (duration x samples_per_second) must stay shippable."""
    history = GOOD.replace(
        'case = "spindle-axial-preload"\nmodel = "dynamic"',
        (
            'case = "spindle-start-up-skid"\nmodel = "dynamic"\n'
            'overrides = { "simulation.samples_per_second" = 4000.0 }'
        ),
    )
    problems = _problems(history)
    assert len(problems) == 2, problems
    assert all("applies to a steady case" in p and "simulation.duration_s" in p for p in problems)
    assert {p.split(":")[1].strip().split()[0] for p in problems} == {
        "shaft_revolutions",
        "samples_per_revolution",
    }
    fine = history.replace("shaft_revolutions = 3\nsamples_per_revolution = 24\n", "")
    lesson = parse_lesson(fine, "history")
    assert lesson.result("run").case().simulation.duration_s == 0.1
    too_long = fine.replace("4000.0", "20000.0")
    (problem,) = _problems(too_long)
    assert "2000 samples" in problem and "at most 1000" in problem
