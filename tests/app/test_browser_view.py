"""The 3-D view drawn by the browser (``racetrace serve --render browser``, the default) in headless
Chromium with software WebGL: the scene is a canvas, not server images, and both painted tracks
are drawn. Screenshots go to ``test-artifacts/browser/``."""

from __future__ import annotations

import pytest

from tests.app.test_browser import _set_state, _view_pixels
from tests.helpers.browser import ARTIFACTS, BROWSER_MARKS

pytestmark = BROWSER_MARKS

CANVAS = "#view-3d-browser canvas"


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from tests.helpers.serve import serve_for_module

    yield from serve_for_module(tmp_path_factory, "--render", "browser")


@pytest.fixture
def page(browser, server):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    pg = context.new_page()
    pg.goto(server["url"])
    pg.wait_for_selector(CANVAS, timeout=120_000)
    pg.wait_for_function(
        "window.trame.state.get('rt3d_parts').length > 0", timeout=60_000, polling=200
    )
    yield pg
    context.close()


def _painted_pixels(pixels):
    """Pixels in the painted tracks' colours (yellow to dark red: red well above blue)."""
    return pixels[..., 0] - pixels[..., 2] > 80


def test_the_browser_draws_the_view_and_both_painted_tracks(page):
    import numpy as np

    assert page.evaluate("window.trame.state.get('view_in_browser')") is True
    assert page.locator("#view-3d img").count() == 0  # no server images
    _set_state(page, playing=False, track_whole_run=True)
    others = ("balls", "cage", "labels", "traces", "ellipses", "edges")
    _set_state(page, **{f"show_{n}": False for n in others})
    shown = _view_pixels(page, "browser-tracks")
    bar, view = (page.locator(k).bounding_box() for k in ("#rt3d-colour-bar", "#view-3d"))
    _set_state(page, show_tracks=False)
    hidden = _view_pixels(page, "browser-no-tracks", differs_from=shown)
    _set_state(page, show_tracks=True)
    painted = _painted_pixels(shown) & ~_painted_pixels(hidden)
    # the colour bar (HTML over the canvas, shown with the tracks) is not the painted tracks
    painted[:, max(int(bar["x"] - view["x"]) - 2, 0) :] = False
    rows = np.flatnonzero(painted.any(axis=1))
    assert rows.size, "no painted track in the browser-drawn view"
    gaps = np.diff(rows)
    assert gaps.size and gaps.max() > 5, f"one painted band only, rows {rows.min()}-{rows.max()}"
    cut = rows[int(np.argmax(gaps))] + 1  # the outer ring is drawn above the inner one
    outer, inner = int(painted[:cut].sum()), int(painted[cut:].sum())
    print("browser view painted pixels (outer, inner)", outer, inner)
    assert outer > 100 and inner > 100, (outer, inner)


def test_a_page_without_webgl_gets_the_server_images(browser, server):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    # this page's canvases cannot give a WebGL context
    context.add_init_script(
        """const getContext = HTMLCanvasElement.prototype.getContext;
           HTMLCanvasElement.prototype.getContext = function (kind, ...rest) {
             return String(kind).startsWith('webgl') ? null : getContext.call(this, kind, ...rest);
           };"""
    )
    pg = context.new_page()
    try:
        pg.goto(server["url"])
        pg.wait_for_selector("#view-3d img[src]:not([src=''])", timeout=120_000)
        assert pg.evaluate("window.trame.state.get('browser_webgl')") is False
        assert pg.evaluate("window.trame.state.get('view_in_browser')") is False
        assert pg.locator(CANVAS).count() == 0
    finally:
        context.close()


def test_the_browser_view_shows_the_server_views_labels_legend_and_colour_bar(page):
    _set_state(page, playing=False, show_labels=True, show_tracks=True, frame=30)
    page.wait_for_function(
        "window.trame.state.get('rt3d_tracks').stop === 31", timeout=60_000, polling=200
    )
    overlay = page.evaluate("window.trame.state.get('rt3d_overlay')")
    tracks = page.evaluate("window.trame.state.get('rt3d_tracks')")
    labels = page.locator("#rt3d-labels")
    legend = page.locator("#rt3d-legend .rt3d-entry")
    bar = page.locator("#rt3d-colour-bar")
    assert labels.is_visible() and legend.first.is_visible() and bar.is_visible()
    colours = page.locator("#rt3d-colour-bar .rt3d-bar-colours").bounding_box()
    assert colours["width"] >= 10 and colours["height"] > 100, colours
    assert any(w.startswith("inner raceway") for w in overlay["labels"]), overlay["labels"]
    assert labels.inner_text().split("\n") == overlay["labels"]
    assert legend.all_inner_texts() == [words for words, _ in overlay["legend"]]
    assert "contact ellipses now" in legend.first.inner_text()
    assert page.locator("#rt3d-colour-bar .rt3d-bar-title").inner_text() == tracks["title"]
    ticks = page.locator("#rt3d-colour-bar .rt3d-bar-tick").all_inner_texts()
    assert ticks == tracks["ticks"] and len(ticks) == 5 and ticks[0] != ticks[-1]
    page.screenshot(path=str(ARTIFACTS / "browser-overlay.png"))
    _set_state(page, show_labels=False)
    page.wait_for_function("!document.querySelector('#rt3d-legend').checkVisibility()")


# one drawing of the view, counting the WebGL calls that only vtk.js's order-independent
# translucency makes (it draws into an off-screen framebuffer of two half-float pictures)
DRAW_COUNTING_OIT_CALLS = """() => {
  const view = window.trame.utils.rt3d.vtkView('rt3d_view');
  const gl = view.renderWindow.getViews()[0].getContext();
  const translucent = view.renderer.getActors().filter(
    (a) => a.getVisibility() && a.getMapper() && !a.getIsOpaque()).length;
  const calls = { drawBuffers: 0, clearBufferfv: 0 };
  for (const name of Object.keys(calls)) {
    const own = gl[name];
    gl[name] = function (...args) { calls[name] += 1; return own(...args); };
  }
  try { view.renderWindow.render(); }
  finally { for (const name of Object.keys(calls)) delete gl[name]; }
  return { translucent, ...calls };
}"""


def test_the_view_blends_its_translucent_parts_without_an_off_screen_pass(page):
    """The balls and the cage stay translucent, drawn blended in drawing order as on the server,
    not through vtk.js's order-independent translucency (an off-screen pass that drew every part
    twice: half of a drawing's cost in software WebGL)."""
    _set_state(page, playing=False, show_balls=True, show_cage=True)
    page.wait_for_function(
        "window.trame.utils.rt3d.vtkView('rt3d_view').renderWindow.getViews()[0].getContext()",
        timeout=60_000,
        polling=200,
    )
    page.wait_for_timeout(1000)  # the view's context is set up within 0.1 s of its creation
    drawn = page.evaluate(DRAW_COUNTING_OIT_CALLS)
    assert drawn["translucent"] >= 19, drawn  # the 18 balls and the cage
    assert drawn["drawBuffers"] == 0 and drawn["clearBufferfv"] == 0, drawn
