"""What a played frame costs the page (headless Chromium, the browser-drawn view): the page's
components that do not show the frame are not re-rendered while a result plays, and the 3-D view
is drawn at most once per animation frame."""

from __future__ import annotations

import pytest

from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

CANVAS = "#view-3d-browser canvas"
PLAYED = 8  # frames the page must have taken while counting

# Hooks every Vue component instance of the page (walked from the app's root vnode) so that each
# re-render is counted under the element id the component was given (or its component name).
COUNT_UPDATES = """() => {
  const counts = {};
  window.racetraceUpdates = counts;
  const seen = new WeakSet();
  function hook(instance) {
    if (seen.has(instance)) return;
    seen.add(instance);
    const props = instance.vnode.props || {};
    const name = props.id || (props.class && String(props.class).includes('rt-view-col')
      ? 'rt-view-col' : instance.type.name || 'anonymous');
    (instance.u || (instance.u = [])).push(() => { counts[name] = (counts[name] || 0) + 1; });
  }
  function walk(vnode) {
    if (!vnode || typeof vnode !== 'object') return;
    if (vnode.component) { hook(vnode.component); walk(vnode.component.subTree); }
    if (vnode.suspense) walk(vnode.suspense.activeBranch);
    if (Array.isArray(vnode.children)) vnode.children.forEach(walk);
  }
  walk(document.querySelector('#app').__vue_app__._container._vnode);
}"""

# Counts, over ``seconds``, the frames the page took, its animation frames and the drawings of
# the 3-D view (its interactor's render events), and the most drawings between two animation frames.
COUNT_DRAWS = """(seconds) => new Promise((done) => {
  const view = window.trame.refs.rt3d_view.$.provides.view;
  let draws = 0, sinceFrame = 0, most = 0, ticks = 0;
  const counting = view.interactor.onRenderEvent(() => {
    draws += 1; sinceFrame += 1; most = Math.max(most, sinceFrame);
  });
  const frames = new Set();
  const t0 = performance.now();
  function tick() {
    ticks += 1; sinceFrame = 0;
    frames.add(window.trame.state.get('rt3d_frame').index);
    if (performance.now() - t0 < seconds * 1000) requestAnimationFrame(tick);
    else { counting.unsubscribe(); done({ draws, most, ticks, frames: frames.size }); }
  }
  requestAnimationFrame(tick);
})"""


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from tests.helpers.serve import serve_for_module

    yield from serve_for_module(tmp_path_factory, "--render", "browser")


@pytest.fixture
def page(browser, server):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    pg = context.new_page()
    pg.goto(server["url"])
    pg.wait_for_selector(CANVAS, timeout=120_000)
    pg.wait_for_function(
        "window.trame.state.get('rt3d_parts').length > 0 && window.trame.refs.rt3d_view",
        timeout=60_000,
        polling=200,
    )
    yield pg
    context.close()


def _play(page, frames: int) -> None:
    """Play until the page has taken ``frames`` state messages holding a frame index."""
    page.evaluate(
        """() => { window.racetraceFrames = 0;
             window.trame.state.addListener(({ type, keys }) => {
               if (type === 'dirty-state' && keys.includes('frame')) window.racetraceFrames += 1;
             }); }"""
    )
    page.evaluate("window.trame.state.set('playing', true)")
    page.wait_for_function(f"window.racetraceFrames >= {frames}", timeout=120_000, polling=100)


def test_a_played_frame_re_renders_only_what_shows_the_frame(page):
    page.evaluate(COUNT_UPDATES)
    _play(page, PLAYED)
    page.evaluate("window.trame.state.set('playing', false)")
    counts = page.evaluate("window.racetraceUpdates")
    # the frame's own bits are re-rendered (or the count would not see anything) ...
    assert counts.get("VSlider", 0) >= PLAYED // 2, counts
    # ... but not the column holding the view and its controls, nor the controls that do not
    # change with the frame (before: all of them, with every frame)
    unchanged = [
        name
        for name in counts
        if name == "rt-view-col" or name.startswith(("camera-", "export-", "track-quantity"))
    ]
    assert not unchanged, {name: counts[name] for name in unchanged}


def test_the_3d_view_is_drawn_at_most_once_per_animation_frame_while_playing(page):
    page.evaluate("window.trame.state.set('playing', true)")
    page.wait_for_timeout(1000)
    counted = page.evaluate(COUNT_DRAWS, 4)
    page.evaluate("window.trame.state.set('playing', false)")
    print("3-D view while playing", counted)
    assert counted["frames"] >= 2, counted  # frames arrived
    assert counted["draws"] >= 2, counted  # and were drawn
    assert counted["most"] <= 1, counted  # never twice between two animation frames


# A page busy with one message after another (5 ms of work each, as a state message costs), each
# asking the view to draw, as a changed property of the scene does, for ``seconds``: how many
# times the view was drawn meanwhile.
DRAWS_WHILE_BUSY = """(seconds) => new Promise((done) => {
  const view = window.trame.refs.rt3d_view.$.provides.view;
  let draws = 0;
  const counting = view.interactor.onRenderEvent(() => { draws += 1; });
  const channel = new MessageChannel();
  const t0 = performance.now();
  channel.port1.onmessage = () => {
    const t = performance.now();
    while (performance.now() - t < 5) { /* the message's work */ }
    view.render();
    if (performance.now() - t0 < seconds * 1000) channel.port2.postMessage(0);
    else { counting.unsubscribe(); done(draws); }
  };
  channel.port2.postMessage(0);
})"""


def test_a_page_busy_with_messages_still_draws_the_3d_view(page):
    # trame-vtk's own scheduling (a 1 ms timer restarted by every request) drew nothing here:
    # every message came before the timer and restarted it
    draws = page.evaluate(DRAWS_WHILE_BUSY, 2)
    assert draws >= 2, draws


# After a drawing the view waits (utils.rt3d.IDLE_SHARE times as long as the drawing held the
# page, at most utils.rt3d.MOST_IDLE_MS; set here to a wait of seconds) before it draws again;
# asked to draw meanwhile, it counts the drawings over ``seconds``, then a frame to be seen at
# once (``rt3d_urgent`` counted up, as the server does for a live control change's first frame)
# and counts again.
DRAWS_AFTER_A_DRAWING = """(seconds) => new Promise((done) => {
  const view = window.trame.refs.rt3d_view.$.provides.view;
  const rt3d = window.trame.utils.rt3d;
  const draws = [];
  const counting = view.interactor.onRenderEvent(() => draws.push(performance.now()));
  window.trame.state.set('live_on', true);  // the view waits while live
  rt3d.IDLE_SHARE = 1000;
  rt3d.MOST_IDLE_MS = 1e6;
  view.render.now();  // a drawing, after which the view waits
  const first = () => new Promise((ok) => {
    const look = () => (rt3d.shown && draws.length && rt3d.shown.end > draws[0]) ? ok()
      : setTimeout(look, 10);
    look();
  });
  first().then(() => {
    const asked = performance.now();
    const ask = setInterval(() => view.render(), 20);
    setTimeout(() => {
      clearInterval(ask);
      const waiting = draws.filter((t) => t > asked).length;
      const urgentAt = performance.now();
      window.trame.state.set('rt3d_urgent', (window.trame.state.get('rt3d_urgent') || 0) + 1);
      setTimeout(() => {
        counting.unsubscribe();
        rt3d.IDLE_SHARE = 1.0;
        rt3d.MOST_IDLE_MS = 500;
        window.trame.state.set('live_on', false);
        const urgent = draws.filter((t) => t > urgentAt);
        done({ waiting, urgent: urgent.length, after: urgent.length ? urgent[0] - urgentAt : null,
               software: rt3d.software,
               antialias: view.openglRenderWindow.getContext().getContextAttributes().antialias });
      }, seconds * 1000);
    }, seconds * 1000);
  });
})"""


def test_after_a_drawing_the_view_waits_but_draws_a_frame_to_be_seen_at_once(page):
    """A drawing in software WebGL holds the page for a few tenths of a second on a loaded
    machine; the view then leaves the page idle for a while (to take its messages) before it
    draws again, except for a frame that must be seen at once. In software WebGL the view is
    drawn without multisampling."""
    page.evaluate("window.trame.state.set('playing', false)")
    page.wait_for_timeout(500)
    counted = page.evaluate(DRAWS_AFTER_A_DRAWING, 1.5)
    print("drawings after a drawing", counted)
    assert counted["waiting"] == 0, counted  # asked every 20 ms for 1.5 s: it waited
    assert counted["urgent"] >= 1, counted  # the frame to be seen at once was drawn
    assert counted["software"] is True, counted  # headless Chromium draws WebGL in SwiftShader
    assert counted["antialias"] is False, counted


# While live, after a live control moved on the page (utils.rt3d.expectChange, which the live
# controls call; HOLD_FOR_CHANGE_MS set here to 800 ms) the view is asked to draw every 20 ms:
# the drawings over 500 ms (one was asked for just before it moved: it waits too), the delay of the
# drawing of the change's frame (rt3d_urgent counted up, as the server does), and, with no such
# frame coming, the delay of the first drawing after it moved.
DRAWS_WHILE_A_CHANGE_IS_EXPECTED = """() => new Promise((done) => {
  const view = window.trame.refs.rt3d_view.$.provides.view;
  const rt3d = window.trame.utils.rt3d;
  const draws = [];
  const counting = view.interactor.onRenderEvent(() => draws.push(performance.now()));
  window.trame.state.set('live_on', true);
  rt3d.IDLE_SHARE = 0;
  rt3d.HOLD_FOR_CHANGE_MS = 800;
  view.render();  // a drawing asked for just before the control moved
  const ask = setInterval(() => view.render(), 20);
  const moved = performance.now();
  rt3d.expectChange();
  setTimeout(() => {
    const held = draws.filter((t) => t > moved + 20).length;
    const urgentAt = performance.now();
    window.trame.state.set('rt3d_urgent', (window.trame.state.get('rt3d_urgent') || 0) + 1);
    setTimeout(() => {
      const urgent = draws.filter((t) => t > urgentAt);
      const again = performance.now();
      rt3d.expectChange();
      setTimeout(() => {
        clearInterval(ask);
        counting.unsubscribe();
        rt3d.IDLE_SHARE = 1.0;
        rt3d.HOLD_FOR_CHANGE_MS = 500;
        window.trame.state.set('live_on', false);
        const after = draws.filter((t) => t > again + 20);
        done({ held, urgent: urgent.length ? urgent[0] - urgentAt : null,
               expired: after.length ? after[0] - again : null });
      }, 1500);
    }, 300);
  }, 500);
})"""


def test_after_a_live_control_moves_the_view_draws_nothing_until_the_change_comes(page):
    """A drawing holds the page for 0.1-0.2 s in software WebGL: begun while a live change's
    frame is on its way, it would delay that frame's drawing. After a live control moves the
    view waits for the change's frame, a bounded time."""
    page.evaluate("window.trame.state.set('playing', false)")
    page.wait_for_timeout(500)
    counted = page.evaluate(DRAWS_WHILE_A_CHANGE_IS_EXPECTED)
    print("drawings while a change is expected", counted)
    assert counted["held"] == 0, counted  # asked every 20 ms
    assert counted["urgent"] is not None and counted["urgent"] < 250, counted
    assert counted["expired"] is not None and counted["expired"] >= 750, counted
