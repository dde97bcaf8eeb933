"""Plotly charts whose 4.6 MB JavaScript bundle is loaded after the first 3-D frame.

``trame.widgets.plotly.Figure`` puts the trame-plotly bundle (plotly.js inside) among the scripts
the page runs before it mounts: parsing it kept the first 3-D frame waiting ~2.5 s on this 2-core
machine. Here the page gets a small stand-in component instead (``static/racetrace-charts.js``,
element ``<racetrace-chart>``); the bundle is only served, and the page script
:data:`LOAD_AFTER_FIRST_FRAME` fetches it once ``#view-3d`` shows a drawn image (not the empty
``<img src="">`` it holds before the first frame; or after 10 s). The
stand-in then renders trame-plotly's chart with the same attributes, each chart's first drawing in
a task of its own after the bundle's: in one task, the bundle's run and every chart's first drawing
held a joining follower's page 4-10 s on a loaded machine (headless Chromium), with no frame taken.
"""

from __future__ import annotations

from pathlib import Path

import trame_plotly
from trame_client.widgets.core import AbstractElement

SERVE_PREFIX = f"__racetrace_charts_{trame_plotly.__version__}"
BUNDLE_URL = f"{SERVE_PREFIX}/plotly/trame-plotly.umd.js"
STAND_IN_URL = f"{SERVE_PREFIX}/app/racetrace-charts.js"
STATIC_DIR = Path(__file__).with_name("static")


def enable(server) -> None:
    """Serve the stand-in component (run at start-up) and the plotly bundle (fetched later)."""
    from trame_plotly import module as plotly_module

    server.enable_module(
        {
            "serve": {
                f"{SERVE_PREFIX}/plotly": str(Path(plotly_module.__file__).with_name("serve")),
                f"{SERVE_PREFIX}/app": str(STATIC_DIR),
            },
            "scripts": [STAND_IN_URL],
            "vue_use": ["racetrace_charts"],
        }
    )


# Waits for the first drawn image in #view-3d (an <img src=""> is there before the first frame;
# at most 10 s), then fetches the chart library.
LOAD_AFTER_FIRST_FRAME = """
(function racetraceLoadCharts(tries) {
  var img = document.querySelector('#view-3d img[src]');
  var canvas = document.querySelector('#view-3d canvas');
  if (window.racetrace_charts && ((img && img.getAttribute('src')) || canvas || tries > 100)) {
    window.racetrace_charts.load('__BUNDLE_URL__');
  } else {
    setTimeout(function () { racetraceLoadCharts(tries + 1); }, 100);
  }
})(0);
""".replace("__BUNDLE_URL__", BUNDLE_URL)


class ChartFigure(AbstractElement):
    """A plotly figure bound to the state key ``state_key`` (plotly JSON with data and layout);
    ``overlay_key``: the state key of what marks the current frame on it (a chart that follows
    the time: ``{"data": [traces], "shapes": [shapes]}``, :func:`app.charts.merge_overlay`),
    merged with the figure by the page (``static/racetrace-charts.js``)."""

    def __init__(self, state_key: str, overlay_key: str | None = None, **kwargs):
        if overlay_key is not None:
            kwargs["overlay"] = (overlay_key,)
        super().__init__(
            "racetrace-chart",
            data=(f"{state_key}.data",),
            layout=(f"{state_key}.layout",),
            **kwargs,
        )
        self._attr_names += ["data", "layout", "overlay", ("display_mode_bar", "displayModeBar")]
        self._event_names += ["click"]  # plotly's click on a point: $event.points[0] ...
