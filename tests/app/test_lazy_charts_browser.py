"""In headless Chromium: once the chart bundle has run, each chart of the page first draws in a
task of its own, not in the bundle's task nor in another chart's (app/static/racetrace-charts.js):
a follower's page takes its frames between them."""

from __future__ import annotations

from pathlib import Path

import trame_client

from app.lazy_charts import STATIC_DIR
from tests.helpers.browser import BROWSER_MARKS

pytestmark = BROWSER_MARKS

ORIGIN = "http://charts.test"
VUE = Path(trame_client.__file__).parent / "module" / "vue3-www" / "vue.global.js"
CHARTS = 3
# Each mark notes the mark made before it in the same task (None: it is the first in its task):
# the task's mark is forgotten by a timer queued when it is made, which runs before any task
# queued after it.
MARKS = """
window.marks = [];
window.mark = function (what) {
  window.marks.push([what, window.taskMark]);
  window.taskMark = what;
  setTimeout(function () { if (window.taskMark === what) window.taskMark = null; }, 0);
};
window.taskMark = null;
"""
# the page: CHARTS charts of the stand-in component, then the bundle fetched
PAGE = f"""<html><head><title>charts</title>
<script>{MARKS}</script>
<script src="{ORIGIN}/vue.global.js"></script>
<script src="{ORIGIN}/racetrace-charts.js"></script>
</head><body><div id="app"></div>
<script>
const app = Vue.createApp({{
  render: () => Array.from({{ length: {CHARTS} }}, (_, k) =>
    Vue.h(Vue.resolveComponent('racetrace-chart'), {{ key: k, name: 'chart' + k, data: [],
                                                       layout: {{}} }})),
}});
app.use(window.racetrace_charts);
app.mount('#app');
window.racetrace_charts.load('{ORIGIN}/bundle.js');
</script></body></html>"""
# a stand-in for trame-plotly's bundle: notes its run, and each chart's mounting
BUNDLE = """
window.mark('bundle');
window.trame_plotly = {
  install(app) {
    app.component('TramePlotly', {
      props: ['name', 'data', 'layout'],
      mounted() { window.mark(this.name); },
      render() { return Vue.h('div', { class: 'drawn' }, this.name); },
    });
  },
};
"""


def test_each_chart_first_draws_in_a_task_of_its_own(browser):
    charts = (STATIC_DIR / "racetrace-charts.js").read_text()
    files = {
        "/": ("text/html", PAGE),
        "/vue.global.js": ("text/javascript", VUE.read_text()),
        "/racetrace-charts.js": ("text/javascript", charts),
        "/bundle.js": ("text/javascript", BUNDLE),
    }

    def serve(route):
        path = route.request.url.removeprefix(ORIGIN)
        kind, body = files[path]
        route.fulfill(status=200, content_type=kind, body=body)

    context = browser.new_context()
    try:
        page = context.new_page()
        errors = []
        page.on("pageerror", lambda error: errors.append(error))
        page.route(f"{ORIGIN}/**", serve)
        page.goto(ORIGIN + "/")
        page.wait_for_function(f"document.querySelectorAll('.drawn').length === {CHARTS}")
        marks = page.evaluate("window.marks")
        assert not errors
        # the bundle ran first, then every chart, each the first mark of its task
        assert [what for what, _ in marks] == ["bundle"] + [f"chart{k}" for k in range(CHARTS)]
        assert [before for _, before in marks] == [None] * (CHARTS + 1), marks
    finally:
        context.close()
