"""Each component builds its own section of the page (app/ui.py only arranges the sections), and
the components reach each other through the controller, not through the session."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.helpers.app_session import trame_server

APP = Path(__file__).resolve().parents[2] / "app"

# (component attribute of the session, section builder, element ids the section holds)
SECTIONS = (
    (
        "form",
        "build_ui",
        ("case-select", "case-reset", "case-upload", "case-download", "field-axial_load_N"),
    ),
    ("form", "build_toolbar", ("result-stale",)),
    ("result", "build_toolbar", ("result-label",)),
    (
        "follow",
        "build_toolbar",
        (
            "follow-button",
            "follow-card",
            "follow-qr",
            "follow-code",
            "follow-count",
            "follow-drive",
        ),
    ),
    (
        "result",
        "build_view",
        ("view-3d", "ball-legend", "closeup-numbers", "scene-note", "play-button", "step-back"),
    ),
    (
        "result",
        "build_scene_controls",
        ("camera-isometric", "camera-close-up", "exaggeration", "ellipse-scale", "track-quantity"),
    ),
    (
        "result",
        "build_charts",
        ("chart-contact-angle", "map-colour", "map-skip-startup", "chart-raceway-map"),
    ),
    ("result", "build_chart_panels", ("chart-load-azimuth", "chart-ellipse", "chart-comparison")),
    (
        "set_panel",
        "build_ui",
        (
            "set-panel",
            "set-bearing",
            "set-lines",
            "chart-set-layout",
            "chart-set-sharing",
            "chart-set-load",
            "chart-set-angle",
            "set-stiffness",
        ),
    ),
    (
        "runs",
        "build_ui",
        ("run-button", "cancel-button", "status", "run-confirm", "result-warnings", "progress"),
    ),
    (
        "live",
        "build_ui",
        ("live-button", "live-stop", "live-pause", "live-record", "live-data", "live-radial-load"),
    ),
    ("compare", "build_ui", ("compare-select", "compare-legend", "compare-summary")),
    ("exports", "build_ui", ("export-netcdf", "export-mp4", "export-link")),
    ("studies", "build_ui", ("studies", "study-results", "study-build-run", "study-table")),
    ("lessons", "build_ui", ("lessons-panel", "lesson-title", "lesson-try", "lesson-next")),
    ("lessons", "build_toolbar", ("presenter-button",)),
)


@pytest.fixture(scope="module")
def rendering_app(tmp_path_factory):
    """A session that renders (its 3-D view is part of a section), on the default case."""
    from app.state import DEFAULT_CASE, RacetraceApp

    session = RacetraceApp(trame_server(), runs_dir=tmp_path_factory.mktemp("runs"))
    session.start(DEFAULT_CASE, play=False)
    yield session
    session.shutdown()


def _ids(html: str) -> set[str]:
    return set(re.findall(r'\bid="([^"]+)"', html))


def _section_html(session, component: str, builder: str) -> str:
    from trame.ui.html import DivLayout

    with DivLayout(session.server, template_name=f"{component}-{builder}") as layout:
        getattr(getattr(session, component), builder)()
    return layout.html


def test_each_component_builds_its_own_section(rendering_app):
    shown = set()
    for component, builder, expected in SECTIONS:
        ids = _ids(_section_html(rendering_app, component, builder))
        assert set(expected) <= ids, f"{component}.{builder}: missing {set(expected) - ids}"
        shown |= ids
    # every stable element id of app/README.md with a fixed name is in one of the sections
    readme = (APP / "README.md").read_text("utf-8")
    listed = readme.split("## Stable element ids", 1)[1].split("The trame state", 1)[0]
    stable = set()
    for name in re.findall(r"`([a-z0-9-]+(?:-<[a-z|-]+>)?)`", listed):
        head, _, choices = name.partition("-<")
        if not choices:
            stable.add(name)
        elif "|" in choices:  # e.g. export-<netcdf|csv|png|gif|mp4>
            stable |= {f"{head}-{c}" for c in choices.rstrip(">").split("|")}
    # the page's own container (app/ui.py), its presenter class and the words `status` ends in
    stable -= {"content", "rt-presenter", "done", "cancelled"}
    # what the front adds to a follower's page, and its pages for a wrong join code, an ended
    # class and too many wrong codes (app.serve.front)
    stable -= {"follow-banner", "follow-refused", "follow-ended", "follow-too-many"}
    assert stable <= shown, f"stable ids in no section: {sorted(stable - shown)}"


# The result view's quasi-static lines (reading the form's case for the run's provenance) and the
# export (drawing with the result view's renderer) are the places that still read another
# component; every other reaches the others through the controller (Component.provide).
ALLOWED_SESSION_READS = {"result_view.py", "export.py"}


def test_components_reach_each_other_through_the_controller(app):
    pattern = re.compile(r"self\.session\.(form|result|runs|compare|exports|studies|lessons)\b")
    found = {
        path.name: len(pattern.findall(path.read_text("utf-8")))
        for path in [*APP.glob("components/*.py"), *APP.glob("lessons/*.py")]
    }
    assert {name for name, count in found.items() if count} <= ALLOWED_SESSION_READS, found
    # what a component offers is a controller function that calls it
    for component in app.components:
        for name in component.PROVIDES:
            assert getattr(app.ctrl, name).func == getattr(component, name), name
    assert app.ctrl.edited_case() is app.form.case is not None
    assert app.ctrl.shown_result().case_text == app.result.shown_case_text
