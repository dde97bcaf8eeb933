"""The bearing set on show: the set along the shaft, the bearing the 3-D view and the charts show,
the load sharing, every bearing's balls and the stiffness table (:mod:`app.set_charts`; a
dynamic run of a set: at its last stored sample, without the stiffness table).

State keys: ``set_shown`` (the result on show is a bearing set), ``set_bearing`` (the index of
the bearing shown in the 3-D view and the single-bearing charts), ``set_bearing_items`` (the
selector's choices), ``set_lines`` (the set in words), ``set_stiffness`` (rows of the stiffness
table: name, axial, radial, tilt) and the figures ``chart_set_layout``, ``chart_set_sharing``,
``chart_set_load`` and ``chart_set_angle`` (plotly JSON).

The result view tells this panel of every result it shows (``show_set``: the set's Dataset, or
None for a single bearing) and shows the bearing chosen here (``show_set_bearing``).
"""

from __future__ import annotations

from trame.widgets import html
from trame.widgets import vuetify3 as v3

from .. import set_charts
from .base import Component, as_int, fig_json
from .widgets import chart, select

SET_CHARTS = ("set_layout", "set_sharing", "set_load", "set_angle", "set_spring")


class SetPanel(Component):
    """The set panel of the result on show (empty and hidden for a single bearing)."""

    PROVIDES = ("show_set", "set_bearing_index")

    def __init__(self, session):
        super().__init__(session)
        self.dataset = None  # the set's Dataset on show (None: a single bearing)

    def init_state(self) -> None:
        s = self.state
        s.set_shown = False
        s.set_bearing = 0
        s.set_bearing_items = []
        s.set_lines = []
        s.set_stiffness = []
        s.set_spring_shown = False
        for name in SET_CHARTS:
            s[f"chart_{name}"] = {"data": [], "layout": {}}

    def bind(self) -> None:
        self.on_change("set_bearing")(self._on_set_bearing)

    def set_bearing_index(self, count: int) -> int:
        """The bearing chosen (an index below ``count``; the first when out of range)."""
        return as_int(self.state.set_bearing, 0, 0, max(count - 1, 0))

    def show_set(self, ds, index: int = 0) -> None:
        """Show the set ``ds`` (None: the result on show is a single bearing) with bearing
        ``index`` chosen."""
        s = self.state
        self.dataset = ds
        if ds is None:
            s.set_shown = False
            s.set_bearing_items, s.set_lines, s.set_stiffness = [], [], []
            s.set_spring_shown = False
            return
        names = set_charts.bearing_names(ds)
        s.set_shown = True
        s.set_bearing_items = [
            {"title": f"{name} ({ds['bearing_direction'].values[k]})", "value": k}
            for k, name in enumerate(names)
        ]
        if as_int(s.set_bearing, -1) != index:
            s.set_bearing = index
        s.set_lines = set_charts.describe_set(ds)
        s.set_stiffness = set_charts.stiffness_rows(ds)
        s.chart_set_layout = fig_json(set_charts.layout_figure(ds, index))
        s.chart_set_sharing = fig_json(set_charts.sharing_figure(ds))
        s.chart_set_load = fig_json(set_charts.ball_figure(ds, "contact_load"))
        s.chart_set_angle = fig_json(set_charts.ball_figure(ds, "contact_angle"))
        spring = set_charts.spring_figure(ds)
        s.set_spring_shown = spring is not None
        s.chart_set_spring = fig_json(spring) if spring is not None else {"data": [], "layout": {}}

    def _on_set_bearing(self, set_bearing=0, **_):
        if self.dataset is None:
            return
        index = self.set_bearing_index(self.dataset.sizes["bearing"])
        self.ctrl.show_set_bearing(index)

    # ---- page -----------------------------------------------------------------------------------
    def build_ui(self) -> None:
        """``#set-panel`` (a set only): ``#set-bearing`` (the bearing shown), the set in words
        (``#set-lines``), the set along the shaft, the load sharing, the balls of every bearing,
        the stiffness table (``#set-stiffness``) and, for a dynamic run with a spring preload,
        the floating outer rings' shift over time (``#chart-set-spring``)."""
        with html.Div(id="set-panel", v_if="set_shown", classes="mb-2"):
            html.Div("Bearing set", classes="text-subtitle-1")
            select(
                "bearing shown in the 3-D view and the charts",
                "set_bearing",
                "set_bearing_items",
                id="set-bearing",
            )
            with html.Div(id="set-lines", classes="text-caption px-1"):
                html.Div("{{ line }}", v_for="(line, i) in set_lines", key="i")
            chart("chart-set-layout", "chart_set_layout", set_charts.HELP["set_layout"])
            chart("chart-set-sharing", "chart_set_sharing", set_charts.HELP["set_sharing"])
            chart("chart-set-load", "chart_set_load", set_charts.HELP["set_balls"])
            chart("chart-set-angle", "chart_set_angle", set_charts.HELP["set_balls"])
            with html.Div(v_if="set_spring_shown"):
                chart("chart-set-spring", "chart_set_spring", set_charts.HELP["set_spring"])
            _stiffness_table()


def _stiffness_table() -> None:
    """``#set-stiffness``: axial, radial and tilting stiffness of every bearing and of the set."""
    t_unit = set_charts.TRANSLATION_UNIT[0]
    r_unit = set_charts.TILT_UNIT[0]
    with v3.VTable(
        density="compact", id="set-stiffness", classes="text-caption", v_if="set_stiffness.length"
    ):
        with html.Thead(), html.Tr():
            html.Th("stiffness")
            html.Th(f"axial, {t_unit}")
            html.Th(f"radial, {t_unit}")
            html.Th(f"tilting, {r_unit}")
        with html.Tbody():
            with html.Tr(v_for="row in set_stiffness", key="row.name"):
                html.Td("{{ row.name }}")
                html.Td("{{ row.axial }}")
                html.Td("{{ row.radial }}")
                html.Td("{{ row.tilt }}")
    html.Div(
        "Each bearing's stiffness about its ball-centre plane, the set's at the external load's "
        "point on the shaft (results: bearing_stiffness, set_stiffness, 5 x 5 each); ball speeds "
        "held at their solved values.",
        v_if="set_stiffness.length",
        classes="text-caption text-medium-emphasis px-1",
    )
