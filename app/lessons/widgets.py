"""The Lessons panel and presenter mode on the page (trame + Vuetify 3), bound to the state of
:class:`app.lessons.panel.LessonController`.

Stable element ids used by tests: lessons-panel, lesson-<id> (one button per lesson),
lesson-title, lesson-text, lesson-stale, lesson-try, lesson-result-<name> (one button per result
of the open lesson), lesson-warnings, lesson-problems, lesson-message, lesson-previous,
lesson-next, presenter-button.

Presenter mode adds the class ``rt-presenter`` around the page content (:data:`PRESENTER_CSS`):
the form drawer, the scene and export controls, the runs card and every chart but the lesson's
(or the contact-angle chart) and the note under the view (the lesson says what is seen) are
hidden; the 3-D view with its time controls and the side column share the screen in
large, high-contrast type: the lesson on top, whole, and its chart below in the height left
(:data:`PANEL_HEIGHT_SCRIPT`). :data:`KEYS_SCRIPT` sends space, the arrows, N, P and Escape to the
server (``lesson_key``) wherever the focus is, unless on a text field; Escape leaves presenter
mode in the page itself. The drawer (``main_drawer``) is closed and opened by the page as
presenter mode is switched, and by the server when it switches it.
"""

from __future__ import annotations

from trame.widgets import client, html
from trame.widgets import vuetify3 as v3

from ..components.widgets import HIDE, alert, alert_list, button_list, icon_button

PRESENTER_CSS = """
#lessons-panel .v-btn__content { white-space: normal; }
.rt-lesson-chart { outline: 3px solid #ffb300; outline-offset: 2px; border-radius: 4px; }
.rt-presenter { background: #000; color: #fff; min-height: calc(100vh - 64px); }
.rt-presenter .rt-hide-in-presenter,
.rt-presenter .rt-chart:not(.rt-lesson-chart),
.rt-presenter .rt-chart .text-caption,
.rt-presenter .v-expansion-panel-title { display: none !important; }
.rt-presenter .v-expansion-panel,
.rt-presenter .v-expansion-panel-text__wrapper { background: transparent; padding: 0; }
.rt-presenter .v-expansion-panel::after { border: none; }
.rt-presenter #view-3d { height: calc(100vh - 175px) !important; }
.rt-presenter #scene-note { display: none; }
@media (min-width: 960px) {
  .rt-presenter .rt-view-col { flex: 0 0 55%; max-width: 55%; }
  .rt-presenter .rt-side { flex: 0 0 45%; max-width: 45%; }
}
.rt-presenter .rt-side { display: flex; flex-direction: column; }
.rt-presenter .rt-side > * { order: 2; }
.rt-presenter .rt-side > #lessons-panel { order: 1; }
.rt-presenter .rt-lesson-chart > div:first-child {
  height: max(140px, calc(100vh - 100px - var(--rt-lesson-panel-height, 45vh))) !important; }
.rt-presenter #lessons-panel { background: #111; color: #fff; border-color: #fff; }
.rt-presenter #lesson-title { font-size: 1.6rem !important; line-height: 1.3 !important; }
.rt-presenter #lesson-text { font-size: 1.1rem !important; line-height: 1.4 !important; }
.rt-presenter .rt-frame-time { font-size: 1.1rem !important; color: #fff; }
"""

# Presenter mode: the lesson panel on top of the side column, whole; the lesson's chart below it
# takes the height left (``--rt-lesson-panel-height``, kept up to date here).
PANEL_HEIGHT_SCRIPT = """
(function () {
  if (window.racetraceLessonPanelHeight) return;
  window.racetraceLessonPanelHeight = true;
  const observer = new ResizeObserver(function (entries) {
    const height = entries[0].target.getBoundingClientRect().height;
    document.documentElement.style.setProperty('--rt-lesson-panel-height', height + 'px');
  });
  (function watch() {
    const panel = document.querySelector('#lessons-panel');
    if (panel) observer.observe(panel); else setTimeout(watch, 200);
  })();
})();
"""

KEYS_SCRIPT = """
(function () {
  if (window.racetraceLessonKeys) return;
  window.racetraceLessonKeys = true;
  const KEYS = [' ', 'ArrowLeft', 'ArrowRight', 'n', 'N', 'p', 'P', 'Escape'];
  // on the window, before any element sees the key (capture): the 3-D view and other widgets
  // that take keys for themselves do not keep them from the lessons, wherever the focus is
  window.addEventListener('keydown', function (event) {
    const target = event.target;
    const tag = target && target.tagName;
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    if (target && (target.isContentEditable || tag === 'INPUT' || tag === 'TEXTAREA' ||
        tag === 'SELECT')) return;
    if (KEYS.indexOf(event.key) < 0 || !window.trame) return;
    event.preventDefault();
    event.stopPropagation();
    if (event.key === 'Escape') {  // leave presenter mode here: the drawer comes back at once
      window.trame.state.update({ presenter: false, main_drawer: true });
      return;
    }
    window.trame.trigger('lesson_key', [event.key]);
  }, true);
})();
"""


def page_assets() -> None:
    """The presenter-mode style sheet and the key handler (once per page)."""
    client.Style(PRESENTER_CSS)
    client.Script(PANEL_HEIGHT_SCRIPT)
    client.Script(KEYS_SCRIPT)


def presenter_button() -> None:
    """Toolbar button: presenter mode on and off."""
    v3.VBtn(
        text=("presenter ? 'leave presenter mode' : 'presenter mode'",),
        id="presenter-button",
        click="presenter = !presenter; main_drawer = !presenter",
        prepend_icon="mdi-projector-screen",
        variant="tonal",
        size="small",
        classes="mr-2",
        title="Projector view: 3-D view and one chart, large type. Keys: space play/pause, "
        "arrows step, N/P next/previous lesson, Esc leaves.",
    )


def lessons_panel(ctrl) -> None:
    """The Lessons card: one button per lesson; the open lesson's text, results and warnings."""
    with v3.VCard(variant="outlined", classes="mb-2 pa-2", id="lessons-panel"):
        with v3.VRow(dense=True, align="center", classes=HIDE):
            with v3.VCol(cols="auto"):
                html.Span("Lessons", classes="text-subtitle-1")
            with v3.VCol():
                button_list(
                    "lessons",
                    "lesson",
                    "lesson-",
                    (ctrl.open_lesson, "[lesson.id]"),
                    "lesson_id === lesson.id",
                    label="{{ lesson.title }}",
                    key="lesson.id",
                    idle="tonal",
                    title=("lesson.summary",),
                    # a title longer than the panel is wide wraps inside its button (with the
                    # .v-btn__content rule in PRESENTER_CSS); one line cut it on a 1280-px laptop
                    style="max-width: 100%; height: auto; min-height: 20px; padding: 2px 8px;"
                    " white-space: normal; text-align: left;",
                )
        html.Div(
            "{{ lesson_message }}",
            v_if="lesson_message",
            id="lesson-message",
            classes="text-error text-caption",
        )
        alert_list("lesson_problems", "error", "lesson-problems", classes=HIDE)
        with html.Div(v_if="lesson_id"):
            _open_lesson(ctrl)


def _open_lesson(ctrl) -> None:
    """The open lesson: its title between previous/next, its results, text and warnings."""
    with v3.VRow(dense=True, align="center", classes="mt-1"):
        with v3.VCol(cols="auto"):
            _lesson_step(ctrl, forward=False)
        with v3.VCol():
            html.Div("{{ lesson_title }}", id="lesson-title", classes="text-subtitle-1")
        with v3.VCol(cols="auto"):
            _lesson_step(ctrl, forward=True)
    with html.Div(v_if="lesson_results.length > 1", classes="my-1"):
        button_list(
            "lesson_results",
            "result",
            "lesson-result-",
            (ctrl.show_lesson_result, "[result.name]"),
            "lesson_result === result.name",
        )
    html.Div(
        "The result on show is no longer this lesson's, so the numbers below describe "
        "the lesson's result ({{ lesson_results.find(r => r.name === lesson_result)"
        "?.label }}). Open the lesson again to return to it.",
        v_if="lesson_stale",
        id="lesson-stale",
        classes="text-caption text-warning my-1",
    )
    html.Div(
        "{{ lesson_explain }}",
        id="lesson-text",
        classes="text-body-2 my-1",
        style="white-space: pre-line;",
    )
    alert_list("lesson_unsupported", "error", "lesson-unsupported")
    alert(
        "info",
        "{{ lesson_try }}",
        id="lesson-try",
        title="Try this",
        classes=f"my-1 text-body-2 {HIDE}",
    )
    alert_list("lesson_warnings", "warning", "lesson-warnings")


def _lesson_step(ctrl, forward: bool) -> None:
    """``#lesson-next`` (N) or ``#lesson-previous`` (P)."""
    icon_button(
        "mdi-chevron-right" if forward else "mdi-chevron-left",
        ctrl.next_lesson if forward else ctrl.previous_lesson,
        "lesson-next" if forward else "lesson-previous",
        size="x-small",
        title="next lesson (N)" if forward else "previous lesson (P)",
    )


__all__ = [
    "KEYS_SCRIPT",
    "PRESENTER_CSS",
    "lessons_panel",
    "page_assets",
    "presenter_button",
]
