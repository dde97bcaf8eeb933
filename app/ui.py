"""Page layout (trame + Vuetify 3): where each component's UI section goes.

Every component of the session (:mod:`app.components`, :mod:`app.lessons.panel`) builds its own
section, bound to its own state keys and controller actions; this module only arranges them: the
toolbar, the drawer (the case form) and the content (the 3-D view with its controls beside the
lessons, the run card and the charts). The stable element ids are listed in app/README.md.
"""

from __future__ import annotations

from trame.ui.vuetify3 import SinglePageWithDrawerLayout
from trame.widgets import client, html
from trame.widgets import vuetify3 as v3

from . import lazy_charts
from .components.widgets import HIDE


def build_ui(app) -> SinglePageWithDrawerLayout:
    """Build the page for ``app`` (a :class:`RacetraceApp` whose scene already exists)."""
    server = app.server
    # The chart library is loaded once the first 3-D frame is on screen (see app.lazy_charts).
    lazy_charts.enable(server)
    with SinglePageWithDrawerLayout(server, full_height=True) as layout:
        client.Script(lazy_charts.LOAD_AFTER_FIRST_FRAME)
        app.lessons.build_page_assets()
        layout.title.set_text("racetrace")
        layout.footer.hide()  # trame's footer covered the chart captions
        with layout.toolbar:
            v3.VSpacer()
            app.form.build_toolbar()
            app.result.build_toolbar()
            app.lessons.build_toolbar()
            app.follow.build_toolbar()
        with layout.drawer as drawer:
            drawer.width = 380
            app.form.build_ui()
        with layout.content:
            _content(app)
    return layout


def _content(app) -> None:
    """The 3-D view column (kept in sight while the other column scrolls) and the side column."""
    with v3.VContainer(
        fluid=True, classes=("presenter ? 'pa-2 rt-presenter' : 'pa-2'",), id="content"
    ):
        with v3.VRow(dense=True):
            with v3.VCol(
                cols=12,
                md=7,
                classes="rt-view-col",
                style="position: sticky; top: 64px; align-self: flex-start;",
            ):
                app.result.build_view()
                with html.Div(classes=HIDE):
                    app.result.build_scene_controls()
                    app.exports.build_ui()
            with v3.VCol(cols=12, md=5, classes="rt-side"):
                app.lessons.build_ui()
                with html.Div(classes=HIDE):
                    app.runs.build_ui()
                    app.live.build_ui()
                app.set_panel.build_ui()
                app.result.build_charts()
                with v3.VExpansionPanels(
                    v_model=("open_panels",), multiple=True, variant="accordion"
                ):
                    app.result.build_chart_panels()
                    app.compare.build_ui()
                    app.studies.build_ui()
