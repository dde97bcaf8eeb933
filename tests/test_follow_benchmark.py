"""benchmarks/follow.py's reading of a V8 CPU profile of the Chromium follower's page: each
sample counted by the script it was in, from the sampled frame out."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


@pytest.fixture(scope="module")
def follow():
    sys.path.insert(0, str(BENCHMARKS))  # follow.py imports its neighbour app_frames
    try:
        spec = importlib.util.spec_from_file_location("follow_benchmark", BENCHMARKS / "follow.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(BENCHMARKS))


def _frame(name: str, url: str = "") -> dict:
    return {"functionName": name, "url": url, "scriptId": "0", "lineNumber": 0, "columnNumber": 0}


PLOTLY = "http://127.0.0.1/__racetrace_charts_3/plotly/trame-plotly.umd.js"
CHARTS = "http://127.0.0.1/__racetrace_charts_3/app/racetrace-charts.js"
# (root) -> (program); (root) -> moveMarks (the stand-in) -> relayout (plotly) -> slice (V8's, no
# address); (root) -> render (vtk.js); (root) -> task (the page's inline script); (root) -> (idle)
PROFILE = {
    "nodes": [
        {"id": 1, "callFrame": _frame("(root)"), "children": [2, 3, 6, 7, 8]},
        {"id": 2, "callFrame": _frame("(program)")},
        {"id": 3, "callFrame": _frame("moveMarks", CHARTS), "children": [4]},
        {"id": 4, "callFrame": _frame("relayout", PLOTLY), "children": [5]},
        {"id": 5, "callFrame": _frame("slice")},
        {"id": 6, "callFrame": _frame("render", "http://127.0.0.1/__trame_vtk/trame-vtk.js")},
        {"id": 7, "callFrame": _frame("task", "http://127.0.0.1/")},
        {"id": 8, "callFrame": _frame("(idle)")},
    ],
    "samples": [2, 2, 2, 2, 5, 5, 4, 3, 6, 7],
    "timeDeltas": [1000] * 10,
}


def test_profile_shares_count_each_sample_by_the_innermost_script_it_was_in(follow):
    shares = follow.profile_shares(PROFILE)
    assert shares == pytest.approx(
        {
            "native, outside JavaScript": 0.4,
            "plotly (the charts)": 0.3,  # relayout and the V8 function it called
            "the charts' stand-in": 0.1,
            "vtk.js (the 3-D view)": 0.1,
            "other": 0.1,
        }
    )
    # largest first
    assert list(shares)[:2] == ["native, outside JavaScript", "plotly (the charts)"]


def test_profile_shares_of_a_profile_without_samples_is_empty(follow):
    assert follow.profile_shares({**PROFILE, "samples": []}) == {}
