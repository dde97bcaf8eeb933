"""Runs folder: save, list and reopen runs; location from argument, environment or user dir."""

from __future__ import annotations

import numpy as np
import pytest

from app.run_store import ENV_VAR, RunStore, default_runs_dir


def test_round_trip(tmp_path, qs_dataset, dynamic_dataset):
    store = RunStore(tmp_path / "runs")
    assert store.list() == []
    a = store.save(qs_dataset, qs_dataset.attrs["case"], "spindle, preview")
    partial = dynamic_dataset.assign_attrs(complete=0)
    b = store.save(partial, "title = 'x'\n", "run two")
    runs = store.list()
    assert {r.run_id for r in runs} == {a.run_id, b.run_id}
    assert {r.status for r in runs} == {"done", "cancelled"}
    assert b.status == "cancelled" and b.model == "dynamic"
    ds, case_text = store.load(a.run_id)
    np.testing.assert_allclose(ds["contact_angle"].values, qs_dataset["contact_angle"].values)
    assert case_text == qs_dataset.attrs["case"]
    ds_b, _ = store.load(b.run_id)
    np.testing.assert_allclose(ds_b["time"].values, dynamic_dataset["time"].values)
    # a fresh store on the same folder (a server restart / page reload) sees the same runs
    assert [r.run_id for r in RunStore(tmp_path / "runs").list()] == [r.run_id for r in runs]
    # no temporary folders left behind
    assert not [p for p in (tmp_path / "runs").iterdir() if p.name.startswith(".")]


def test_a_saved_result_without_its_coordinates_is_refused_by_name(tmp_path, qs_dataset):
    """A result of an older version (no operating-point and geometry coordinates) cannot feed the
    views: reopening it says which run and what is missing instead of failing in a view."""
    store = RunStore(tmp_path)
    old = store.save(qs_dataset.drop_vars(["inner_ring_speed", "outer_ring_speed"]), "", "old")
    with pytest.raises(ValueError, match=f"saved run {old.run_id}: .*inner_ring_speed"):
        store.load(old.run_id)


def test_failed_save_leaves_nothing(tmp_path, qs_dataset):
    store = RunStore(tmp_path)
    with pytest.raises((TypeError, ValueError, RuntimeError)):
        store.save(
            qs_dataset.assign(bad=(("ball",), [object()] * qs_dataset.sizes["ball"])), "", "x"
        )
    assert store.list() == []
    assert list(tmp_path.iterdir()) == []


def test_unknown_run_is_named(tmp_path):
    with pytest.raises(FileNotFoundError, match="no saved run 'nope'"):
        RunStore(tmp_path).load("nope")


def test_default_dir(tmp_path):
    assert default_runs_dir({ENV_VAR: str(tmp_path)}) == tmp_path
    d = default_runs_dir({})
    assert d.name == "runs" and "racetrace" in str(d)


def test_describe_case_names_the_values_run():
    from app.run_store import describe_case
    from solver.catalogue import catalogue

    case = catalogue().get("spindle-combined-load").load()
    text = describe_case(case)
    assert text.startswith(f"{case.bearing.designation}: ")
    op = case.operating
    assert f"{op.inner_ring_speed_rpm:g} rpm" in text
    assert f"Fa {op.axial_load_N:g} N" in text and f"Fr {op.radial_load_N:g} N" in text
    axial_only = describe_case(catalogue().get("spindle-axial-preload").load())
    assert "Fr" not in axial_only and "tilt" not in axial_only
    tilted = describe_case(catalogue().get("spindle-misalignment-ring").load())
    assert "tilt 0.05 deg (ring)" in tilted


def test_a_run_id_the_page_adds_to_its_list_is_not_a_listed_run(tmp_path, qs_dataset):
    """A client writing its own entry into ``runs`` does not make it a run to open or compare:
    the run store's listing decides."""
    from app.state import DEFAULT_CASE, RacetraceApp
    from tests.helpers.app_session import trame_server

    app = RacetraceApp(trame_server(), runs_dir=tmp_path / "runs", render=False)
    try:
        app.start(DEFAULT_CASE, play=False)
        saved = app.store.save(qs_dataset, qs_dataset.attrs["case"], "saved")
        s = app.state
        fake = "20260101-000000-not-a-run-abcd"
        s.runs = [*s.runs, {"title": "mine", "value": fake}]
        s.flush()
        assert not app.runs.is_listed(fake)
        assert app.runs.is_listed(saved.run_id)  # saved after the page's list was made
        s.run_id = fake
        s.flush()
        assert s.status == f"error: no run {fake!r} in the runs folder"
        s.compare_ids = [fake]
        s.flush()
        assert s.compare_message == f"cannot compare with {fake}: not a saved run"
    finally:
        app.shutdown()
