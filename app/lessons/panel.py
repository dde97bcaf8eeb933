"""The Lessons panel's state and handlers, and presenter mode: a component of the session.

:class:`LessonController` reaches the other components through the controller: the case form's
(``take_case``, ``drop_pending_preview``: the lesson's case goes in the form, no preview is
solved) and the result view's (``show_unsaved``, ``set_camera``, ``step``, ``update_charts``).
One click on a lesson (``open_lesson``) shows its first result, places the camera, opens and
highlights its chart and fills its text from the results; its other results are one click away
(``show_lesson_result``).
Presenter mode (``presenter``) is a state flag the page styles (app/lessons/widgets.py); its keys
come here as ``lesson_key``.

State (all plain JSON): ``lessons`` (id, title, summary per lesson), ``lesson_problems`` (broken
lesson files, in words), ``lesson_id``, ``lesson_title``, ``lesson_explain``, ``lesson_try``,
``lesson_result`` (name of the result on show), ``lesson_results`` (name and label per result),
``lesson_warnings`` (the warnings of the result on show), ``lesson_unsupported`` (the claims of
the lesson its results do not bear out, in words: app/lessons/claims.py), ``lesson_chart`` (the
chart highlighted), ``lesson_message`` (why a lesson could not open), ``lesson_stale`` (true once
another result is on show than the lesson's: its text then no longer describes the view),
``presenter``.
"""

from __future__ import annotations

import logging

from ..components.base import Component
from . import widgets
from .claims import ClaimError, check_claims
from .format import LessonSet, load_lessons
from .results import lesson_result
from .text import lesson_text
from .values import lesson_values

log = logging.getLogger(__name__)

#: Charts always on the page (not in a collapsible panel).
ALWAYS_SHOWN = ("contact_angle", "raceway_map")


class LessonController(Component):
    """Lessons and presenter mode for one session (see the module docstring). ``lessons``: the
    lessons to offer (default: the shipped ones); ``cache_dir``: where results solved on first use
    are kept (default: :func:`app.lessons.results.lesson_cache_dir`)."""

    def __init__(self, session, lessons: LessonSet | None = None, cache_dir=None):
        super().__init__(session)
        self.set = load_lessons() if lessons is None else lessons
        self.cache_dir = cache_dir
        self._results: dict[tuple[str, str], object] = {}  # (lesson, result) -> Dataset
        self._values: dict[tuple[str, str], dict] = {}
        self._shown_serial = None  # result_serial of the lesson's result on show

    def init_state(self) -> None:
        s = self.state
        s.lessons = [
            {"id": lesson.id, "title": lesson.title, "summary": lesson.summary}
            for lesson in self.set.lessons
        ]
        s.lesson_problems = list(self.set.problems)
        s.lesson_id = None
        s.lesson_title = ""
        s.lesson_explain = ""
        s.lesson_try = ""
        s.lesson_result = None
        s.lesson_results = []
        s.lesson_warnings = []
        s.lesson_unsupported = []
        s.lesson_chart = None
        s.lesson_message = ""
        s.lesson_stale = False
        s.presenter = False

    def bind(self) -> None:
        s, ctrl = self.state, self.ctrl
        ctrl.open_lesson = self.open_lesson
        ctrl.show_lesson_result = self.show_result
        ctrl.next_lesson = self.next_lesson
        ctrl.previous_lesson = self.previous_lesson
        ctrl.lesson_key = self.key
        self.session.server.trigger("lesson_key")(self.key)  # called by the page's key handler
        s.change("presenter")(self._on_presenter)
        s.change("result_serial")(self._on_result_serial)

    def _on_result_serial(self, result_serial=0, **_):
        """Another result than the lesson's is on show (a preview after an edit, a run): the
        lesson's text no longer describes the view, and the page says so."""
        if self.state.lesson_id and result_serial != self._shown_serial:
            self.state.lesson_stale = True

    def _on_presenter(self, presenter=False, **_):
        """Presenter mode hides the form (the drawer); the charts are redrawn at their new size."""
        self.state.main_drawer = not presenter
        self.ctrl.update_charts()

    # ---- results ---------------------------------------------------------------------------------
    def _dataset(self, lesson, spec):
        key = (lesson.id, spec.name)
        if key not in self._results:
            ds, where = lesson_result(lesson, spec, cache_dir=self.cache_dir)
            log.info("lesson %s, result %s: %s", lesson.id, spec.name, where)
            self._results[key] = ds
            self._values[key] = lesson_values(ds)
        return self._results[key]

    # ---- handlers --------------------------------------------------------------------------------
    def open_lesson(self, lesson_id: str, result_name: str | None = None) -> None:
        """Open lesson ``lesson_id`` on its first result (or ``result_name``)."""
        try:
            lesson = self.set.get(lesson_id)
            for spec in lesson.results:
                self._dataset(lesson, spec)
        except Exception as error:  # the page says why, in words; the previous lesson stays
            log.warning("lesson %s did not open: %s", lesson_id, error)
            self.state.lesson_message = f"lesson {lesson_id} could not be opened: {error}"
            return
        values = {spec.name: self._values[(lesson.id, spec.name)] for spec in lesson.results}
        explain, try_this = lesson_text(lesson, values)
        try:
            unsupported = [
                f"The results do not bear out {o.claim.says!r} ({o.claim.holds.text})."
                for o in check_claims(lesson, values)
                if not o.holds
            ]
        except ClaimError as error:
            unsupported = [str(error)]
        with self.state:
            s = self.state
            s.lesson_message = ""
            s.lesson_id = lesson.id
            s.lesson_title = lesson.title
            s.lesson_explain = explain
            s.lesson_try = try_this
            s.lesson_unsupported = unsupported
            s.lesson_results = [{"name": r.name, "label": r.label} for r in lesson.results]
            s.lesson_chart = lesson.chart
            if lesson.chart not in ALWAYS_SHOWN:
                s.open_panels = sorted(set(s.open_panels or ()) | {lesson.chart})
        self.show_result(result_name or lesson.results[0].name)
        self.ctrl.set_camera(lesson.camera)

    def show_result(self, name: str) -> None:
        """Show result ``name`` of the open lesson: its case in the form, the result in the view."""
        if not self.state.lesson_id:
            return
        lesson = self.set.get(self.state.lesson_id)
        spec = lesson.result(name)
        ds = self._dataset(lesson, spec)
        self.ctrl.drop_pending_preview()  # a preview on its way must not replace this result
        self.state.case_name = None  # picking a shipped case afterwards (even the same) reloads it
        # the form holds the case the result on show was solved from (spec.case(): the lesson's
        # case under a title naming what the lesson changed), so nothing is out of date until an
        # edit; a result without a readable case of its own gets the spec's
        self.ctrl.take_case(ds.racetrace.case() or spec.case())
        self.ctrl.show_unsaved(ds, f"lesson: {spec.label}")  # the runs list names no run
        self._shown_serial = self.state.result_serial
        with self.state:
            self.state.lesson_stale = False
            self.state.lesson_result = spec.name
            self.state.lesson_warnings = ds.racetrace.warnings()

    def _move(self, delta: int) -> None:
        ids = [lesson.id for lesson in self.set.lessons]
        if not ids:
            return
        current = self.state.lesson_id
        index = ids.index(current) + delta if current in ids else (0 if delta > 0 else -1)
        self.open_lesson(ids[index % len(ids)])

    def next_lesson(self) -> None:
        self._move(1)

    def previous_lesson(self) -> None:
        self._move(-1)

    def key(self, key: str) -> None:
        """A key pressed on the page outside a text field: space plays or pauses, the left and
        right arrows step one frame, N and P open the next and previous lesson, Escape leaves
        presenter mode."""
        if key == " ":
            self.state.playing = not self.state.playing
        elif key == "ArrowRight":
            self.state.playing = False
            self.ctrl.step(1)
        elif key == "ArrowLeft":
            self.state.playing = False
            self.ctrl.step(-1)
        elif key in ("n", "N"):
            self.next_lesson()
        elif key in ("p", "P"):
            self.previous_lesson()
        elif key == "Escape":
            self.state.presenter = False

    # ---- page -----------------------------------------------------------------------------------
    def build_page_assets(self) -> None:
        """Presenter mode's style sheet and key handler (once per page)."""
        widgets.page_assets()

    def build_toolbar(self) -> None:
        """``#presenter-button`` in the toolbar."""
        widgets.presenter_button()

    def build_ui(self) -> None:
        """``#lessons-panel``: the lessons and the open lesson's text (app/lessons/widgets.py)."""
        widgets.lessons_panel(self.ctrl)


__all__ = ["ALWAYS_SHOWN", "LessonController"]
