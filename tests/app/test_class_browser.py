"""The app in front of a class and on a laptop, in headless Chromium: at 1280x720 (and the other
common laptop and projector sizes) the time slider keeps a usable width and the camera buttons
stay on one line; the contact ellipses can be seen at the opening scale (pixels of their colour in
the 3-D view); presenter mode shows the whole lesson text without scrolling; N and P change the
lesson wherever the focus is. Screenshots at 1280x720 and 1920x1080 are kept in
``test-artifacts/browser/class/``."""

from __future__ import annotations

import io

import pytest

from app.lessons.format import load_lessons
from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS, FIRST_IMAGE
from viz.marks import ELLIPSE_COLOUR

pytestmark = BROWSER_MARKS

SHOTS = ARTIFACTS / "class"
LAPTOPS = ((1280, 720), (1280, 800), (1366, 768))
MIN_SLIDER_PX = 300  # a time slider narrower than this cannot be scrubbed frame by frame
MIN_ELLIPSE_PIXELS = 150  # pixels of the ellipse colour in the 3-D view at the opening scale
LESSONS = load_lessons().lessons
TITLE_IS = "t => (document.querySelector('#lesson-title') || {}).innerText === t"


@pytest.fixture(scope="module")
def page(browser, server):
    """One page at 1280x720 for the module (each new page costs the busy server a first frame)."""
    SHOTS.mkdir(parents=True, exist_ok=True)
    context = browser.new_context(viewport={"width": 1280, "height": 720})
    pg = context.new_page()
    pg.goto(server["url"], timeout=120_000)
    pg.wait_for_selector(FIRST_IMAGE, timeout=120_000)
    pg.wait_for_function(
        "window.trame && window.trame.state.get('result_serial') > 0", timeout=120_000
    )
    pg.evaluate("window.trame.state.set('playing', false)")
    yield pg
    context.close()


def _until(pg, script: str, arg=None, timeout_s: float = 120.0) -> None:
    pg.wait_for_function(script, arg=arg, timeout=timeout_s * 1000, polling=250)


def _settle(pg) -> None:
    """Wait for the page to lay out again and a frame of the view's new size to arrive."""
    pg.wait_for_timeout(1500)


def _colour_pixels(png: bytes, colour: str, tolerance: int = 40) -> int:
    """Pixels of ``png`` within ``tolerance`` (per channel) of ``colour`` ('#rrggbb')."""
    import numpy as np
    from PIL import Image

    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=int)
    target = np.array([int(colour[k : k + 2], 16) for k in (1, 3, 5)])
    return int(np.all(np.abs(rgb - target) <= tolerance, axis=-1).sum())


@pytest.mark.parametrize("size", LAPTOPS, ids=lambda s: f"{s[0]}x{s[1]}")
def test_time_slider_and_camera_buttons_keep_their_room_on_a_laptop(page, size):
    page.set_viewport_size({"width": size[0], "height": size[1]})
    _settle(page)
    slider = page.locator("#time-slider .v-slider").bounding_box()
    assert slider["width"] >= MIN_SLIDER_PX, f"time slider {slider['width']:.0f} px at {size}"
    tops = page.evaluate(
        "[...document.querySelectorAll('[id^=camera-]')].map(b => b.getBoundingClientRect().top)"
    )
    assert len(tops) == 6 and max(tops) - min(tops) < 2, f"camera buttons wrap at {size}: {tops}"


@pytest.mark.parametrize("size", LAPTOPS, ids=lambda s: f"{s[0]}x{s[1]}")
def test_every_lesson_button_shows_its_whole_title_on_a_laptop(page, size):
    page.set_viewport_size({"width": size[0], "height": size[1]})
    _settle(page)
    cut = page.evaluate(
        """() => {
          const panel = document.querySelector('#lessons-panel').getBoundingClientRect();
          return [...document.querySelectorAll('#lessons-panel [id^=lesson-]')]
            .filter(b => b.tagName === 'BUTTON')
            .map(b => {
              const box = b.getBoundingClientRect();
              const text = b.querySelector('.v-btn__content') || b;
              const inside = box.left >= panel.left - 1 && box.right <= panel.right + 1;
              const whole = text.scrollWidth <= text.clientWidth + 1
                && text.getBoundingClientRect().left >= box.left - 1
                && text.getBoundingClientRect().right <= box.right + 1;
              return inside && whole ? null : [b.id, Math.round(box.left), Math.round(box.right),
                Math.round(panel.left), Math.round(panel.right)];
            })
            .filter(x => x);
        }"""
    )
    count = page.locator("#lessons-panel button[id^=lesson-]").count()
    assert count == len(LESSONS), count
    assert not cut, f"lesson buttons cut at {size}: {cut}"


def test_contact_ellipses_are_visible_at_the_opening_scale(page):
    page.set_viewport_size({"width": 1280, "height": 720})
    _settle(page)
    scale = page.evaluate("window.trame.state.get('ellipse_scale')")
    assert scale > 1
    assert page.locator("#ellipse-scale-label").inner_text().strip() == f"ellipses × {scale:g}"
    shot = page.locator("#view-3d").screenshot(path=str(SHOTS / "view-1280x720.png"))
    pixels = _colour_pixels(shot, ELLIPSE_COLOUR)
    assert pixels >= MIN_ELLIPSE_PIXELS, f"{pixels} pixels of the ellipse colour"


def test_presenter_mode_shows_the_whole_lesson_text_and_keys_work_from_anywhere(page):
    page.set_viewport_size({"width": 1280, "height": 720})
    first = LESSONS[0]
    page.locator(f"#lesson-{first.id}").click()
    _until(page, TITLE_IS, first.title)
    page.locator("#presenter-button").click()
    _until(page, "() => document.querySelector('.rt-presenter') !== null")
    _settle(page)
    for lesson in LESSONS[:3]:
        _until(page, TITLE_IS, lesson.title)
        _settle(page)
        text = page.locator("#lesson-text")
        box = text.bounding_box()
        fits = page.evaluate("e => e.scrollHeight <= e.clientHeight + 1", text.element_handle())
        assert fits, f"lesson {lesson.id}: its text scrolls in presenter mode"
        assert box["y"] >= 0 and box["y"] + box["height"] <= 720, (lesson.id, box)
        assert page.evaluate("document.scrollingElement.scrollTop") == 0
        # and the time slider under the view, in the window too
        slider = page.locator("#time-slider .v-slider").bounding_box()
        assert slider["y"] + slider["height"] <= 720 and slider["width"] >= MIN_SLIDER_PX
        page.screenshot(path=str(SHOTS / f"presenter-{lesson.id}-1280x720.png"))
        # the focus on the 3-D view (it takes keys for its own camera) or on a plain block
        target = "#view-3d [tabindex]" if lesson is LESSONS[0] else "#lesson-text"
        page.evaluate(
            "s => { const e = document.querySelector(s); e.setAttribute('tabindex', "
            "e.getAttribute('tabindex') || '-1'); e.focus(); }",
            target,
        )
        page.keyboard.press("n")
    _until(page, TITLE_IS, LESSONS[3].title)
    page.keyboard.press("p")
    _until(page, TITLE_IS, LESSONS[2].title)
    page.keyboard.press("Escape")
    _until(page, "() => document.querySelector('.rt-presenter') === null")


def test_screenshots_at_projector_and_full_hd_sizes(page):
    for width, height in ((1280, 720), (1920, 1080)):
        page.set_viewport_size({"width": width, "height": height})
        _settle(page)
        slider = page.locator("#time-slider .v-slider").bounding_box()
        assert slider["width"] >= MIN_SLIDER_PX
        page.screenshot(path=str(SHOTS / f"page-{width}x{height}.png"))


def test_studies_table_keeps_to_the_side_column_at_1600_px(page):
    page.set_viewport_size({"width": 1600, "height": 900})
    page.evaluate("window.trame.state.set('presenter', false)")
    page.evaluate("window.trame.state.set('open_panels', ['studies'])")
    page.wait_for_selector("#study-build-run", timeout=30_000)
    page.evaluate("window.trame.state.set('study_results', 'shipped:seed-spindle.study.nc')")
    _until(page, "() => document.querySelectorAll('#study-table tbody tr').length === 30")
    _settle(page)
    overflow = page.evaluate(
        "() => { const w = document.querySelector('#study-table .v-table__wrapper'); "
        "return w.scrollWidth - w.clientWidth; }"
    )
    assert overflow <= 1, f"the study table is {overflow} px wider than its column"
    table = page.locator("#study-table").bounding_box()
    side = page.locator(".rt-side").bounding_box()
    assert table["x"] + table["width"] <= side["x"] + side["width"] + 1
    page.locator("#studies").scroll_into_view_if_needed()
    page.screenshot(path=str(SHOTS / "studies-1600x900.png"))
