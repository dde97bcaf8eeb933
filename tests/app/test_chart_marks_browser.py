"""In headless Chromium with the real plotly bundle: a chart that follows the time moves its marks
(the overlay's shapes) without plotly's react() of the whole figure, at most once per animation
frame, and ends on the last overlay it was given (app/static/racetrace-charts.js)."""

from __future__ import annotations

from pathlib import Path

import trame_client
import trame_plotly

from app.lazy_charts import STATIC_DIR
from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

ORIGIN = "http://marks.test"
VUE = Path(trame_client.__file__).parent / "module" / "vue3-www" / "vue.global.js"
BUNDLE = Path(trame_plotly.__file__).parent / "module" / "serve" / "trame-plotly.umd.js"
CHARTS = STATIC_DIR / "racetrace-charts.js"
# the plot drawn (plotly has given its element the layout)
DRAWN = "(() => { const p = document.querySelector('.js-plotly-plot'); return p && p.layout })()"
# one chart against time: a trace of 2000 points and a shape of the figure's own; its overlay is a
# dotted time marker at x (a shape), set by window.setMarker(x) or a list of them in one task
PAGE = f"""<html><head><title>marks</title>
<script src="{ORIGIN}/vue.global.js"></script>
<script src="{ORIGIN}/racetrace-charts.js"></script>
</head><body><div id="app"></div>
<script>
const xs = Array.from({{ length: 2000 }}, (_, k) => k);
const figure = (scale) => ({{
  data: [{{ type: 'scatter', mode: 'lines', x: xs, y: xs.map((x) => scale * Math.sin(x / 50)) }}],
  layout: {{ shapes: [{{ type: 'line', x0: 0, x1: 2000, y0: 0, y1: 0, xref: 'x', yref: 'y' }}],
            margin: {{ l: 40, r: 10, t: 10, b: 30 }} }},
}});
const marker = (x) => ({{ data: [], shapes: [{{ type: 'line', x0: x, x1: x, xref: 'x',
  y0: 0, y1: 1, yref: 'y domain', line: {{ dash: 'dot' }} }}] }});
const state = Vue.shallowReactive({{ figure: figure(1), overlay: marker(0) }});
window.setMarker = (x) => {{ state.overlay = marker(x); }};
window.setMarkers = (xs) => xs.forEach(window.setMarker);
window.setFigure = (scale, x) => {{ state.figure = figure(scale); state.overlay = marker(x); }};
window.twoFrames = () => new Promise((done) =>
  requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(done, 0))));
const app = Vue.createApp({{
  render: () => Vue.h(Vue.resolveComponent('racetrace-chart'), {{
    data: state.figure.data, layout: state.figure.layout, overlay: state.overlay,
    style: 'width: 600px; height: 300px' }}),
}});
app.use(window.racetrace_charts);
app.mount('#app');
window.racetrace_charts.load('{ORIGIN}/bundle.js');
</script></body></html>"""
# counts plotly's react() and relayout() calls from now on
COUNT_CALLS = """() => {
  window.calls = { react: 0, relayout: 0 };
  for (const name of Object.keys(window.calls)) {
    const call = window.Plotly[name];
    window.Plotly[name] = function (...args) {
      window.calls[name] += 1;
      return call.apply(this, args);
    };
  }
}"""
# the x of each shape the plot shows (its layout after plotly's updates), and its traces' y scale
SHOWN = """() => {
  const plot = document.querySelector('.js-plotly-plot');
  return { shapes: plot._fullLayout.shapes.map((s) => s.x0),
           scale: Math.max(...plot._fullData[0].y) };
}"""


def _page(browser):
    files = {
        "/": ("text/html", PAGE),
        "/vue.global.js": ("text/javascript", VUE.read_text()),
        "/racetrace-charts.js": ("text/javascript", CHARTS.read_text()),
        "/bundle.js": ("text/javascript", BUNDLE.read_text()),
    }

    def serve(route):
        kind, body = files[route.request.url.removeprefix(ORIGIN)]
        route.fulfill(status=200, content_type=kind, body=body)

    context = browser.new_context()
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda error: errors.append(error))
    page.route(f"{ORIGIN}/**", serve)
    page.goto(ORIGIN + "/")
    page.wait_for_function(DRAWN, timeout=60_000)
    page.evaluate("window.twoFrames()")
    page.evaluate(COUNT_CALLS)
    return context, page, errors


def test_moving_the_marks_does_not_react_the_whole_figure(browser):
    context, page, errors = _page(browser)
    try:
        for x in range(100, 1100, 100):  # a frame at a time, each given time to show
            page.evaluate(f"window.setMarker({x})")
            page.evaluate("window.twoFrames()")
            assert page.evaluate(SHOWN)["shapes"] == [0, x]
        calls = page.evaluate("window.calls")
        assert calls == {"react": 0, "relayout": 10}, calls
        assert not errors
    finally:
        context.close()


def test_marks_given_faster_than_frames_move_once_and_end_on_the_last(browser):
    context, page, errors = _page(browser)
    try:
        page.evaluate("window.setMarkers([300, 400, 500, 600, 1234])")  # one task: one frame
        page.evaluate("window.twoFrames()")
        calls = page.evaluate("window.calls")
        assert calls == {"react": 0, "relayout": 1}, calls
        assert page.evaluate(SHOWN)["shapes"] == [0, 1234]
        assert not errors
    finally:
        context.close()


def test_a_new_figure_is_drawn_whole_with_the_marks_of_now(browser):
    context, page, errors = _page(browser)
    try:
        page.evaluate("window.setMarker(700)")
        page.evaluate("window.twoFrames()")
        page.evaluate("window.setFigure(3, 900)")  # a new figure and its marks in one task
        page.evaluate("window.twoFrames()")
        shown = page.evaluate(SHOWN)
        assert shown["shapes"] == [0, 900]
        assert abs(shown["scale"] - 3) < 0.01  # the new figure's traces
        calls = page.evaluate("window.calls")
        assert calls == {"react": 1, "relayout": 1}, calls  # the marker, then the new figure
        assert not errors
    finally:
        context.close()
