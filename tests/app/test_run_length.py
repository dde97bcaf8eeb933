"""The run length of a case in words and the size of its run: revolutions for a steady case,
seconds for a case with a time history."""

from __future__ import annotations

import numpy as np
import xarray as xr

from app.components.runs import _title
from app.run_length import run_length_words, run_size_text
from app.run_store import describe_case
from solver.catalogue import resolve_case


def test_a_history_case_runs_for_its_duration():
    case = resolve_case("spindle-start-up")  # 0.4 s at 20 000 samples per second
    assert run_length_words(case) == "0.4 s"
    text = run_size_text(case)
    assert text.startswith("dynamic run: 0.4 s at 20 000 samples per second: 8 000 samples")
    assert "MB" in text and "None" not in text and "revolution" not in text
    title = describe_case(case)
    assert title.endswith(", 0.4 s")
    assert "smooth ramp from 0 to 20000 rpm" in title and "None" not in title


def test_a_steady_case_runs_for_its_revolutions():
    case = resolve_case("spindle-combined-load")
    assert run_length_words(case) == "10 rev"
    assert run_size_text(case).startswith(
        "dynamic run: 10 shaft revolutions at 180 samples per revolution: 1 800 samples"
    )


def test_a_cancelled_history_run_says_how_far_it_went():
    case = resolve_case("spindle-radial-step")  # 0.1 s
    title = describe_case(case)
    ds = xr.Dataset(coords={"time": np.linspace(0.0, 0.03, 4)})
    info = {"title": title, "duration_s": 0.1, "revolutions": None}
    assert _title(ds, info).endswith("0.03 of 0.1 s")
    done = xr.Dataset(coords={"time": np.linspace(0.0, 0.1, 4)})
    assert _title(done, info) == title
