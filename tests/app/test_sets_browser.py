"""A bearing set in the browser (`racetrace serve`, headless Chromium): the shipped DB pair picked,
solved by the quasi-static set model, its set panel drawn, and the painted tracks of both of its
bearings in the 3-D view. Screenshots are kept in ``test-artifacts/browser/`` (gitignored):
``set-page.png``, ``set-panel.png`` and, per bearing, ``set-bearing-<k>-tracks.png``.
"""

from __future__ import annotations

import time

import pytest

from tests.app.test_browser import _open_case, _set_state, _track_pixels
from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS, FIRST_IMAGE

pytestmark = BROWSER_MARKS

PAIR_TITLE = "DB pair, light preload"  # words of the shipped pair's title in the case picker
LAYERS_OFF = ("balls", "cage", "labels", "traces", "ellipses", "edges")  # only rings and tracks


@pytest.fixture
def page(browser, server):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    context = browser.new_context(viewport={"width": 1500, "height": 1000})
    pg = context.new_page()
    pg.goto(server["url"])
    pg.wait_for_selector(FIRST_IMAGE, timeout=60_000)
    pg.wait_for_selector("#chart-contact-angle .main-svg", timeout=60_000)
    yield pg
    context.close()


def _state(pg, key: str):
    return pg.evaluate(f"window.trame.state.get('{key}')")


def _wait_label(pg, words: str, timeout_s: float = 60.0) -> None:
    deadline = time.monotonic() + timeout_s
    while words not in pg.locator("#result-label").inner_text():
        assert time.monotonic() < deadline, pg.locator("#result-label").inner_text()
        time.sleep(0.25)


def test_a_db_pair_is_solved_and_both_bearings_tracks_are_painted(page):
    _set_state(page, playing=False)
    _open_case(page, PAIR_TITLE)
    assert page.locator("#status").inner_text().strip().endswith("preview done")
    panel = page.locator("#set-panel")
    panel.wait_for(state="visible", timeout=30_000)
    # the set along the shaft, the load sharing (a bar per bearing and load) and the balls of
    # both bearings are drawn; the stiffness table has a row per bearing and one for the set
    page.wait_for_selector("#chart-set-layout .main-svg", timeout=60_000)
    assert page.locator("#chart-set-sharing .bars .point").count() == 4
    assert page.locator("#chart-set-load .scatterlayer .trace").count() == 2
    rows = page.locator("#set-stiffness tbody tr")
    assert rows.count() == 3
    assert "set" in rows.nth(2).inner_text()
    # the set's fields are in the form, and Run runs the set's dynamic model
    assert page.locator("#field-set_arrangement").count() == 1
    assert page.locator("#field-preload_force_N input").input_value() == "100.0"
    assert not page.locator("#run-button").is_disabled()
    assert "dynamic run" in page.locator("#run-size").inner_text()
    page.screenshot(path=str(ARTIFACTS / "set-page.png"), full_page=True)
    panel.screenshot(path=str(ARTIFACTS / "set-panel.png"))

    shown = {f"show_{n}": _state(page, f"show_{n}") for n in LAYERS_OFF}
    _set_state(page, track_whole_run=True, **{key: False for key in shown})
    counts = {}
    try:
        for index, name in enumerate(("bearing 1", "bearing 2")):
            _set_state(page, set_bearing=index)
            _wait_label(page, f"{name} of the set")
            _set_state(page, frame=0)
            counts[name] = _track_pixels(page, f"set-bearing-{index + 1}")
    finally:
        _set_state(page, **shown)
    print("track pixels and thickness per bearing", counts)
    for name, races in counts.items():
        for count, _ in races:
            assert count > 200, (name, counts)  # both rings of both bearings painted
