"""The Lessons panel and presenter mode in headless Chromium: every lesson opens from its button
with its chart highlighted; presenter mode at 1280x720 and 1920x1080 gives the 3-D view and one
chart the screen, in large type, and answers its keys. Screenshots are kept in
``test-artifacts/browser/lessons/``."""

from __future__ import annotations

import time

import pytest

from app.lessons.format import load_lessons
from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS

pytestmark = BROWSER_MARKS
import playwright.sync_api as playwright_api  # noqa: E402

LESSONS = load_lessons().lessons
SHOTS = ARTIFACTS / "lessons"
DRAWER_OPEN = (
    "document.querySelector('nav.v-navigation-drawer')"
    ".classList.contains('v-navigation-drawer--active')"
)


@pytest.fixture(scope="module")
def page(browser, server):
    """One page for the whole module (the served app is one session: each new page costs the
    busy server a first frame); the tests resize its viewport."""
    SHOTS.mkdir(parents=True, exist_ok=True)
    context = browser.new_context(viewport={"width": 1280, "height": 720})
    pg = context.new_page()
    pg.goto(server["url"])
    pg.wait_for_selector("#view-3d img", timeout=120_000)
    pg.wait_for_selector("#chart-contact-angle .main-svg", timeout=120_000)
    # paused: on this shared 2-core machine a playing view keeps the server rendering
    pg.evaluate("window.trame.state.set('playing', false)")
    yield pg
    context.close()


def _until(page, script: str, arg=None) -> None:
    """Wait until the JavaScript function ``script`` of ``arg`` is true in ``page`` (120 s at the
    most: a busy 2-core machine renders slowly)."""
    page.wait_for_function(script, arg=arg, timeout=120_000)


#: True when the lesson title shown is ``t``.
TITLE_IS = "t => (document.querySelector('#lesson-title') || {}).innerText === t"


def _open_lesson(page, lesson):
    page.locator(f"#lesson-{lesson.id}").click()
    try:
        _until(page, TITLE_IS, lesson.title)
    except playwright_api.TimeoutError:
        page.screenshot(path=str(SHOTS / f"failed-{lesson.id}.png"))
        raise


def _chart_id(chart):
    return "chart-" + chart.replace("_", "-")


def test_every_lesson_opens_from_its_button(page):
    page.set_viewport_size({"width": 1280, "height": 720})
    assert page.locator("#lessons-panel [id^=lesson-0]").count() == len(LESSONS)
    for lesson in LESSONS:
        _open_lesson(page, lesson)
        text = page.locator("#lesson-text").inner_text()
        assert len(text) > 200 and "{" not in text and "(no " not in text
        assert page.locator("#lesson-try").inner_text().strip()
        chart = page.locator(f"#{_chart_id(lesson.chart)}")
        chart.wait_for(state="visible", timeout=120_000)
        assert "rt-lesson-chart" in chart.get_attribute("class")
        assert page.locator(".rt-lesson-chart").count() == 1
        _until(
            page, "l => document.body.innerText.includes(l)", f"lesson: {lesson.results[0].label}"
        )
        page.screenshot(path=str(SHOTS / f"{lesson.id}-1280x720.png"))
    # a lesson's other result is one click away
    _open_lesson(page, next(ls for ls in LESSONS if ls.id == "04-misalignment"))
    page.locator("#lesson-result-ring").click()
    _until(
        page,
        "() => document.body.innerText.includes('turning with the inner ring (dynamic run)')"
        " && document.querySelector('#field-misalignment_frame').innerText.includes('ring')",
    )


#: True when the toolbar's "out of date: the form has changed" chip is shown.
STALE_SHOWN = (
    "() => { const c = document.querySelector('#result-stale');"
    " return !!c && c.offsetParent !== null && getComputedStyle(c).display !== 'none'; }"
)


@pytest.mark.parametrize("presenter", [False, True], ids=["normal", "presenter"])
def test_no_lesson_opens_out_of_date(page, presenter):
    """Opening a lesson puts its result on show and its case in the form: the two agree, so the
    "out of date" chip stays hidden, for every result of every lesson; in presenter mode too, in
    front of a class, where the lecturer moves on with the N key."""
    page.set_viewport_size({"width": 1280, "height": 720})
    _open_lesson(page, LESSONS[0])
    if presenter:
        page.locator("#presenter-button").click()
        page.wait_for_selector("#content.rt-presenter", timeout=120_000)
    try:
        for index, lesson in enumerate(LESSONS):
            if index and presenter:
                page.evaluate("document.activeElement && document.activeElement.blur()")
                page.keyboard.press("n")
                _until(page, TITLE_IS, lesson.title)
            elif index:
                _open_lesson(page, lesson)
            for spec in lesson.results:
                if len(lesson.results) > 1:
                    page.locator(f"#lesson-result-{spec.name}").click()
                _until(page, "l => document.body.innerText.includes(l)", f"lesson: {spec.label}")
                time.sleep(0.5)  # a staleness the server would compute has reached the page
                assert page.locator("#result-stale").count() == 1  # the chip is on the page ...
                assert not page.evaluate(STALE_SHOWN), (lesson.id, spec.name)  # ... and hidden
                assert "out of date" not in page.locator("body").inner_text()
            if presenter:
                page.screenshot(path=str(SHOTS / f"presenter-{lesson.id}-1280x720.png"))
    finally:
        if page.evaluate("window.trame.state.get('presenter')"):
            page.locator("#presenter-button").click()


@pytest.mark.parametrize(("width", "height"), [(1280, 720), (1920, 1080)])
def test_presenter_mode(page, width, height):
    page.set_viewport_size({"width": width, "height": height})
    try:
        lesson = LESSONS[2]
        _open_lesson(page, lesson)
        assert page.locator("#field-axial_load_N").is_visible()
        page.locator("#presenter-button").click()
        page.wait_for_selector("#content.rt-presenter", timeout=120_000)
        _until(page, f"() => !{DRAWER_OPEN}")
        for hidden in ("#run-button", "#export", "#camera-axial"):
            assert not page.locator(hidden).is_visible(), hidden
        time.sleep(1.5)  # the drawer slides away, the chart redraws at its new size
        view = page.locator("#view-3d").bounding_box()
        chart = page.locator(f"#{_chart_id(lesson.chart)}").bounding_box()
        assert view["height"] > 0.75 * height
        assert view["width"] > 0.5 * width
        # the chart beside the view; on a 720-px projector it yields to the whole lesson text
        # (tests/app/test_class_browser.py), down to its smallest height
        assert chart["height"] >= (140 if height <= 720 else 0.3 * height)
        assert chart["x"] >= view["x"] + view["width"] - 1
        assert view["width"] + chart["width"] > 0.9 * width
        # the only chart on screen is the lesson's
        visible = [c for c in page.locator(".rt-chart").all() if c.is_visible()]
        assert len(visible) == 1
        # large, high-contrast type
        size = page.evaluate(
            "parseFloat(getComputedStyle(document.querySelector('#lesson-title')).fontSize)"
        )
        assert size >= 24
        colours = page.evaluate(
            "[getComputedStyle(document.querySelector('#content')).backgroundColor,"
            " getComputedStyle(document.querySelector('#content')).color]"
        )
        assert colours == ["rgb(0, 0, 0)", "rgb(255, 255, 255)"]
        # the rendered 3-D image follows the larger view
        _until(page, "h => document.querySelector('#view-3d img').naturalHeight > 0.6 * h", height)
        page.screenshot(path=str(SHOTS / f"presenter-{width}x{height}.png"))
        # keys: N and P move between lessons, space plays and pauses, arrows step
        page.keyboard.press("n")
        _until(page, TITLE_IS, LESSONS[3].title)
        page.keyboard.press("p")
        _until(page, TITLE_IS, lesson.title)
        icon = page.locator("#play-button i")
        playing = "mdi-pause" in icon.get_attribute("class")
        page.keyboard.press(" ")
        expected = "mdi-play" if playing else "mdi-pause"
        _until(
            page, "c => document.querySelector('#play-button i').className.includes(c)", expected
        )
        if expected == "mdi-pause":
            page.keyboard.press(" ")
            _until(
                page,
                "() => document.querySelector('#play-button i').className.includes('mdi-play')",
            )
        time.sleep(0.5)
        before = page.locator(".rt-frame-time").inner_text()
        page.keyboard.press("ArrowRight")
        _until(page, "b => document.querySelector('.rt-frame-time').innerText !== b", before)
        page.screenshot(path=str(SHOTS / f"presenter-{width}x{height}-stepped.png"))
        page.keyboard.press("Escape")
        page.wait_for_selector("#content:not(.rt-presenter)", timeout=120_000)
        _until(page, f"() => {DRAWER_OPEN}")
    finally:
        if page.evaluate("window.trame.state.get('presenter')"):
            page.locator("#presenter-button").click()
