"""The Lessons panel and presenter mode at state level (no browser): one click sets the case,
result, camera and chart and fills the text; keys; broken lessons reported."""

from __future__ import annotations

import shutil

import pytest

from app.lessons.format import load_lessons, shipped_lessons_dir
from app.lessons.panel import LessonController
from app.state import DEFAULT_CASE, RacetraceApp
from tests.helpers.app_session import trame_server

IDS = [lesson.id for lesson in load_lessons().lessons]


@pytest.fixture(scope="module")
def app(tmp_path_factory):
    root = tmp_path_factory.mktemp("lessons-app")
    a = RacetraceApp(trame_server(), runs_dir=root / "runs", render=False)
    a.lessons.cache_dir = root / "cache"
    a.start(DEFAULT_CASE, play=False)
    yield a
    a.shutdown()


def test_lessons_are_listed(app):
    assert [item["id"] for item in app.state.lessons] == IDS
    assert all(item["title"] and item["summary"] for item in app.state.lessons)
    assert app.state.lesson_problems == []


@pytest.mark.parametrize("lesson_id", IDS)
def test_one_click_opens_a_lesson(app, lesson_id):
    lesson = app.lessons.set.get(lesson_id)
    app.lessons.open_lesson(lesson_id)
    s = app.state
    spec = lesson.results[0]
    assert s.lesson_id == lesson_id and s.lesson_title == lesson.title
    assert s.lesson_result == spec.name
    assert s.camera == lesson.camera and s.lesson_chart == lesson.chart
    if lesson.chart not in ("contact_angle", "raceway_map"):
        assert lesson.chart in s.open_panels
    # the result on show is the lesson's, and the form holds its case
    case = spec.case()
    assert s.result_label == f"lesson: {spec.label}"
    assert app.result.dataset.attrs["model"] == spec.model
    assert float(app.result.dataset.coords["axial_load"]) == case.operating.axial_load_N
    assert float(s.fv_axial_load_N) == case.operating.axial_load_N
    assert s.fv_title == f"{lesson.title}: {spec.label}"  # not the base case's title
    assert s.case_valid and s.case_name is None
    # numbers in the text come from that result
    assert s.lesson_explain and "{" not in s.lesson_explain and "(no " not in s.lesson_explain
    assert s.lesson_try
    assert [r["name"] for r in s.lesson_results] == [r.name for r in lesson.results]
    assert s.lesson_warnings == app.result.dataset.racetrace.warnings()
    s.flush()  # no preview replaces the lesson's result
    assert s.result_label == f"lesson: {spec.label}"
    # the form holds the very case the result on show was solved from: nothing is out of date
    assert app.result.dataset.racetrace.case().title == s.fv_title
    assert s.result_stale is False
    assert s.lesson_unsupported == []  # every claim of the text holds in the result on show
    for other in lesson.results[1:]:
        app.lessons.show_result(other.name)
        s.flush()
        assert s.result_stale is False and s.fv_title == f"{lesson.title}: {other.label}"


def test_other_result_of_a_lesson(app):
    app.lessons.open_lesson("04-misalignment")
    assert str(app.result.dataset.coords["misalignment_frame"].values) == "space"
    app.lessons.show_result("ring")
    assert app.state.lesson_result == "ring"
    assert str(app.result.dataset.coords["misalignment_frame"].values) == "ring"
    assert app.state.fv_misalignment_frame == "ring"


def test_overload_lesson_lists_its_warnings(app):
    app.lessons.open_lesson("06-overload")
    assert len(app.state.lesson_warnings) == 3
    assert any("over the shoulder" in w for w in app.state.lesson_warnings)


def test_keys_play_step_and_move_between_lessons(app):
    app.lessons.open_lesson(IDS[0])
    s = app.state
    s.playing = False
    app.lessons.key(" ")
    assert s.playing is True
    app.lessons.key(" ")
    assert s.playing is False
    s.frame = 3
    app.lessons.key("ArrowRight")
    assert s.frame == 4
    app.lessons.key("ArrowLeft")
    app.lessons.key("ArrowLeft")
    assert s.frame == 2
    app.lessons.key("n")
    assert s.lesson_id == IDS[1]
    app.lessons.key("P")
    app.lessons.key("p")
    assert s.lesson_id == IDS[-1]  # wraps round
    app.lessons.key("N")
    assert s.lesson_id == IDS[0]
    app.lessons.key("x")  # other keys do nothing
    assert s.lesson_id == IDS[0]


def test_presenter_mode_hides_the_form(app):
    s = app.state
    with s:
        s.presenter = True
    assert s.main_drawer is False
    app.lessons.key("Escape")
    s.flush()
    assert s.presenter is False and s.main_drawer is True


def test_broken_lesson_is_reported_others_still_open(tmp_path, app):
    folder = tmp_path / "lessons"
    shutil.copytree(str(shipped_lessons_dir()), folder, ignore=shutil.ignore_patterns("*.nc"))
    (folder / "00-broken.toml").write_text('title = "x"\n[view]\ncamera = "top"\n', "utf-8")
    controller = LessonController(app, lessons=load_lessons(folder))
    controller.init_state()
    try:
        assert len(app.state.lesson_problems) == 1 == len(controller.set.problems)
        assert app.state.lesson_problems[0].startswith("lesson 00-broken.toml:")
        assert "camera must be one of" in app.state.lesson_problems[0]
        assert [item["id"] for item in app.state.lessons] == IDS
    finally:
        app.lessons.init_state()  # the session's own lessons again


def test_a_lesson_that_cannot_open_says_why(app, monkeypatch):
    from app.lessons import panel

    def fail(*_args, **_kwargs):
        raise OSError("disk on fire")

    app.lessons.open_lesson(IDS[0])
    monkeypatch.setattr(panel, "lesson_result", fail)
    app.lessons._results.clear()
    app.lessons.open_lesson(IDS[1])
    assert "could not be opened: disk on fire" in app.state.lesson_message
    assert app.state.lesson_id == IDS[0]  # the open lesson stays


def test_text_is_marked_once_another_result_is_on_show(app):
    app.lessons.open_lesson("02-speed")
    s = app.state
    s.flush()
    assert s.lesson_stale is False
    with s:
        s.fv_axial_load_N = "700"  # an edit: the preview replaces the lesson's result
    app.form.preview_now()
    s.flush()
    assert s.result_label == "quasi-static preview"
    assert s.lesson_stale is True and s.lesson_id == "02-speed"
    app.lessons.show_result("rest")  # back to a result of the lesson
    s.flush()
    assert s.lesson_stale is False


def test_a_claim_the_results_do_not_bear_out_is_shown(tmp_path, app):
    folder = tmp_path / "lessons"
    folder.mkdir()
    text = (shipped_lessons_dir() / "02-speed.toml").read_text("utf-8")
    wrong = text.replace("outer_contact_angle < free_contact_angle", "outer_contact_angle > 20")
    assert wrong != text
    (folder / "02-speed.toml").write_text(wrong, "utf-8")
    controller = LessonController(app, lessons=load_lessons(folder), cache_dir=tmp_path / "c")
    try:
        controller.open_lesson("02-speed")
        (message,) = app.state.lesson_unsupported
        assert "'below the free contact angle' (outer_contact_angle > 20)" in message
    finally:
        app.lessons.init_state()
