"""Comparison of the result on show (A) with a saved run (B).

State keys: ``compare_id`` (the run chosen as B), ``compare_label``, ``compare_summary`` (rows of
:func:`app.charts.summary_rows`), ``compare_message`` (why the chosen run cannot be compared, ""
when fine); the charts ``chart_compare_runs``, ``chart_compare_angle``, ``chart_compare_load``
are set here too (declared by :mod:`app.components.result_view`).
"""

from __future__ import annotations

from .. import charts
from ..frames import frame_source
from .base import Component, fig_json


class Compare(Component):
    def __init__(self, session):
        super().__init__(session)
        self._compare_key = None  # (result_serial, compare_id) of the comparison shown
        self._compare_run = None  # (run_id, Dataset, FrameSource) of the last run compared with

    def init_state(self) -> None:
        s = self.state
        s.compare_id = None
        s.compare_label = ""
        s.compare_summary = []
        s.compare_message = ""

    def bind(self) -> None:
        self.on_change("compare_id")(self._on_compare_id)

    def is_current(self) -> bool:
        """Whether the comparison shown is of the result on show and the chosen run."""
        return self._compare_key == (int(self.state.result_serial), self.state.compare_id)

    def _on_compare_id(self, compare_id=None, **_):
        self.update_comparison()

    def update_comparison(self) -> None:
        """Compare the result on show (A) with the saved run chosen in ``compare_id`` (B).

        Sets ``chart_compare_runs`` (side-by-side raceway maps), ``chart_compare_angle`` and
        ``chart_compare_load`` (overlays versus ball azimuth), ``compare_summary`` (table rows of
        :func:`app.charts.run_summary`) and ``compare_label``; all are emptied when nothing is
        chosen or the run cannot be loaded, and ``compare_message`` then says why in words.
        """
        result = self.session.result
        run_id = self.state.compare_id
        if not run_id or result.source is None:
            self._clear_comparison("")
            return
        if not self.session.runs.is_listed(run_id):
            self._clear_comparison(f"cannot compare with {str(run_id)[:80]}: not a saved run")
            return
        try:
            ds, other = self._load_compare_run(run_id)
        except (OSError, ValueError) as error:
            self._clear_comparison(f"cannot compare with {run_id}: {error}")
            return
        self._compare_key = (int(self.state.result_serial), run_id)
        label = next((r["title"] for r in self.state.runs if r["value"] == run_id), run_id)
        summaries = {
            "A": charts.run_summary(result.source, result.dataset),
            "B": charts.run_summary(other, ds),
        }
        with self.state:
            s = self.state
            s.chart_compare_runs = fig_json(charts.side_by_side_raceway_maps(result.source, other))
            s.chart_compare_angle = fig_json(charts.compare_angle_figure(result.source, other))
            s.chart_compare_load = fig_json(charts.compare_load_figure(result.source, other))
            s.compare_summary = charts.summary_rows(summaries)
            s.compare_label = label
            s.compare_message = ""

    def _load_compare_run(self, run_id: str):
        """(Dataset, FrameSource) of saved run ``run_id``; the last one is kept for reuse."""
        if self._compare_run is None or self._compare_run[0] != run_id:
            ds, _ = self.session.store.load(run_id)
            self._compare_run = (run_id, ds, frame_source(ds))
        return self._compare_run[1], self._compare_run[2]

    def _clear_comparison(self, message: str) -> None:
        """Empty the comparison charts and table; ``message`` says why ("" when not asked for)."""
        with self.state:
            s = self.state
            for name in ("compare_runs", "compare_angle", "compare_load"):
                s[f"chart_{name}"] = {"data": [], "layout": {}}
            s.compare_summary = []
            s.compare_label = ""
            s.compare_message = message
        self._compare_key = None
