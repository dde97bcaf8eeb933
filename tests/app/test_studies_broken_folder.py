"""The Studies panel on a study folder that is not one: the message, no exception."""

from __future__ import annotations

import pytest

from app.state import DEFAULT_CASE, RacetraceApp
from tests.app.test_state import _server

pytest.importorskip("distributed")


@pytest.mark.parametrize(
    "manifest",
    ["{not json", "[]", '{"title": "t", "base": "b", "varied_keys": [], "points": [[]]}'],
)
def test_a_broken_study_folder_is_named_not_a_study_folder(tmp_path, manifest):
    app = RacetraceApp(_server(), runs_dir=tmp_path / "runs", render=False)
    app.start(DEFAULT_CASE, play=False)
    try:
        folder = tmp_path / "runs" / ".studies" / "broken"
        folder.mkdir(parents=True)
        (folder / "study.json").write_text(manifest)
        app.studies.list_results()
        app.studies.open_results("folder:broken")
        assert "not a study folder" in app.state.study_status
        assert app.state.study_rows in (None, [])
    finally:
        app.shutdown()
