"""The run store never stops for what is in its folder and never loses a finished run: client-set
run ids name listed runs only, broken run folders are listed with their reason, leftovers of stopped
servers are tidied (job results recovered), and a read-only or full folder keeps runs in memory."""

from __future__ import annotations

import json
import os
import tempfile
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.run_store import (
    CASE_FILE,
    META_FILE,
    RESULT_FILE,
    RunNotSavedError,
    RunStore,
    UnknownRunError,
)
from tests.helpers.faults import read_only_folder, small_file_system


@pytest.fixture
def store(tmp_path, qs_dataset):
    store = RunStore(tmp_path / "runs")
    store.save(qs_dataset, qs_dataset.attrs["case"], "good run")
    return store


# ---- identifiers set by a client -----------------------------------------------------------------
@pytest.mark.parametrize(
    "run_id",
    ["../", "..", ".", "../runs", "../../etc/passwd", "/etc", "/", "a/b", "a\\b", "nope", "",
     ".tmp-x", ".exports", None, 12, ["x"], {"a": 1}, "x" * 10_000, "good\x00"],
)  # fmt: skip
def test_only_listed_run_ids_are_accepted(store, run_id):
    for call in (store.load, store.info, store.path):
        with pytest.raises(UnknownRunError) as caught:
            call(run_id)
        assert isinstance(caught.value, FileNotFoundError)  # what callers already catch
        assert len(str(caught.value)) < 400


def test_an_absolute_path_to_a_run_folder_is_not_an_id(store):
    (good,) = store.list()
    for run_id in (str(store.root / good.run_id), f"../runs/{good.run_id}", f"{good.run_id}/"):
        with pytest.raises(UnknownRunError):
            store.load(run_id)
    ds, _ = store.load(good.run_id)  # the listed id itself opens
    assert ds.sizes["ball"] > 0


def test_a_run_json_naming_another_id_does_not_redirect(store):
    (good,) = store.list()
    meta_path = store.root / good.run_id / META_FILE
    meta = json.loads(meta_path.read_text())
    meta["run_id"] = "../../elsewhere"
    meta_path.write_text(json.dumps(meta))
    assert [r.run_id for r in store.list()] == [good.run_id]


def test_a_symbolic_link_in_the_folder_is_not_a_run(store, tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (store.root / "linked").symlink_to(outside)
    assert "linked" not in [r.run_id for r in store.list()]
    with pytest.raises(UnknownRunError):
        store.load("linked")


# ---- broken run folders --------------------------------------------------------------------------
def _break(store, run_id, how):
    folder = store.root / run_id
    meta = folder / META_FILE
    if how == "created null":
        data = json.loads(meta.read_text())
        data["created"] = None
        meta.write_text(json.dumps(data))
    elif how == "title a number":
        data = json.loads(meta.read_text())
        data["title"] = 5
        meta.write_text(json.dumps(data))
    elif how == "status unknown":
        data = json.loads(meta.read_text())
        data["status"] = "\x1b[2Jrunning"
        meta.write_text(json.dumps(data))
    elif how == "created not a time":
        data = json.loads(meta.read_text())
        data["created"] = "yesterday"
        meta.write_text(json.dumps(data))
    elif how == "run.json a list":
        meta.write_text("[1, 2]")
    elif how == "run.json not JSON":
        meta.write_text("{'title': ")
    elif how == "run.json deep":
        meta.write_text("[" * 100_000 + "]" * 100_000)
    elif how == "run.json binary":
        meta.write_bytes(b"\xff\xfe\x00")
    elif how == "no run.json":
        meta.unlink()
    elif how == "no result":
        (folder / RESULT_FILE).unlink()
    elif how == "no case":
        (folder / CASE_FILE).unlink()
    elif how == "result empty":
        (folder / RESULT_FILE).write_bytes(b"")
    elif how == "result not NetCDF":
        (folder / RESULT_FILE).write_text("this is not a result")
    elif how == "result a folder":
        (folder / RESULT_FILE).unlink()
        (folder / RESULT_FILE).mkdir()


BREAKS = {
    "created null": "created",
    "title a number": "title",
    "status unknown": "status",
    "created not a time": "ISO 8601",
    "run.json a list": "list",
    "run.json not JSON": "cannot be read",
    "run.json deep": "cannot be read",
    "run.json binary": "cannot be read",
    "no run.json": "no run.json",
    "no result": "no result.nc",
    "no case": "no case.toml",
    "result empty": "result.nc is empty",
    "result not NetCDF": "not a NetCDF file",
    "result a folder": "no result.nc",
}


@pytest.mark.parametrize("how", list(BREAKS))
def test_broken_run_is_listed_with_its_reason(store, qs_dataset, how):
    broken = store.save(qs_dataset, qs_dataset.attrs["case"], "to be broken")
    _break(store, broken.run_id, how)
    runs = {r.run_id: r for r in store.list()}
    assert len(runs) == 2  # the good run stays listed
    info = runs[broken.run_id]
    assert info.status == "broken" and info.broken
    assert BREAKS[how] in info.problem, info.problem
    assert "\x1b" not in info.label and "broken: " in info.label
    with pytest.raises(ValueError, match=f"saved run {broken.run_id} is broken"):
        store.load(broken.run_id)
    assert [r.status for r in store.list(include_broken=False)] == ["done"]


def test_a_truncated_result_is_a_clean_error_on_loading(store, qs_dataset):
    run = store.save(qs_dataset, qs_dataset.attrs["case"], "truncated")
    result = store.root / run.run_id / RESULT_FILE
    result.write_bytes(result.read_bytes()[:600])
    with pytest.raises(ValueError, match=f"saved run {run.run_id} cannot be read"):
        store.load(run.run_id)


def test_stray_files_in_the_folder_are_ignored(store):
    (store.root / "notes.txt").write_text("mine")
    (store.root / "weird name").mkdir()
    runs = store.list()
    assert [r.status for r in runs if r.run_id == "weird name"] == ["broken"]
    assert "notes.txt" not in [r.run_id for r in runs]


def test_a_missing_or_unreadable_root_lists_nothing(tmp_path):
    assert RunStore(tmp_path / "nowhere").list() == []
    (tmp_path / "file").write_text("x")
    assert RunStore(tmp_path / "file").list() == []


# ---- start-up: leftovers of stopped servers ------------------------------------------------------
def _age(path, seconds=3600):
    old = time.time() - seconds
    os.utime(path, (old, old), follow_symlinks=False)


def test_recover_saves_job_results_and_removes_leftovers(store, dynamic_dataset, qs_dataset):
    from solver.results.io import save_dataset

    root = store.root
    partial = dynamic_dataset.assign_attrs(complete=0, case=qs_dataset.attrs["case"])
    save_dataset(partial, root / ".job-0a1b2c3d.nc")
    (root / ".job-deadbeef.nc").write_bytes(b"\x89HDF\r\n\x1a\n" + b"\0" * 100)  # half written
    (root / ".tmp-20260101-000000-run-abcd").mkdir()
    (root / ".tmp-20260101-000000-run-abcd" / RESULT_FILE).write_text("x")
    (root / "..job-0a1b2c3d.nc.x1y2.tmp").write_text("x")
    fresh = root / ".job-fresh.nc"  # another server may be writing this one
    fresh.write_text("x")
    for path in root.iterdir():
        if path != fresh:
            _age(path)
    report = store.recover(min_age_s=60)
    assert sorted(report.removed) == sorted(
        [".job-0a1b2c3d.nc", ".job-deadbeef.nc", ".tmp-20260101-000000-run-abcd",
         "..job-0a1b2c3d.nc.x1y2.tmp"]
    )  # fmt: skip
    assert fresh.exists()
    (recovered,) = report.recovered
    assert recovered.status == "cancelled" and recovered.title.startswith("recovered: ")
    assert [r.run_id for r in report.incomplete] == [recovered.run_id]
    ds, case_text = store.load(recovered.run_id)
    assert ds.sizes["time"] == dynamic_dataset.sizes["time"] and case_text
    assert report.folder_problem == "" and not report.broken
    lines = report.messages()
    assert any("recovered" in line for line in lines) and any(
        "stopped early" in line for line in lines
    )


def test_recover_reports_broken_runs_and_never_raises(store, qs_dataset):
    run = store.save(qs_dataset, qs_dataset.attrs["case"], "b")
    _break(store, run.run_id, "created null")
    report = store.recover()
    assert [r.run_id for r in report.broken] == [run.run_id]
    assert any(run.run_id in line and "created" in line for line in report.messages())


# ---- read-only and full folders ------------------------------------------------------------------
def test_read_only_folder_keeps_finished_runs_in_memory(tmp_path, qs_dataset):
    with read_only_folder(tmp_path / "ro") as root:
        store = RunStore(root)
        problem = store.folder_problem()
        assert str(root) in problem and "kept in memory" in problem
        report = store.recover()
        assert report.folder_problem == problem
        info = store.save(qs_dataset, "title = 'x'\n", "unsaved run")
        assert not info.saved and str(root) in info.problem
        assert [r.run_id for r in store.list()] == [info.run_id]
        assert "not saved" in store.list()[0].label
        ds, case_text = store.load(info.run_id)
        assert ds is qs_dataset and case_text == "title = 'x'\n"
        with pytest.raises(UnknownRunError, match="kept in memory only"):
            store.path(info.run_id)
        with pytest.raises(RunNotSavedError, match=str(root)):
            store.save(qs_dataset, "", "strict", keep_in_memory=False)
        assert list(root.iterdir()) == []


def test_job_path_is_in_the_runs_folder_or_else_in_the_temp_folder(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    writable = RunStore(tmp_path / "runs").job_path()
    assert writable.parent == tmp_path / "runs" and writable.name.startswith(".job-")
    with read_only_folder(tmp_path / "ro") as root:
        elsewhere = RunStore(root).job_path()
    assert elsewhere.parent == tmp_path / "tmp" and elsewhere.suffix == ".nc"


def test_netcdf_runtime_error_keeps_the_run_and_leaves_no_files(tmp_path, qs_dataset, monkeypatch):
    import app.run_store

    def disk_full(ds, path):
        path.write_bytes(b"\x89HDF\r\n\x1a\n")
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(app.run_store, "save_netcdf", disk_full)
    store = RunStore(tmp_path)
    info = store.save(qs_dataset, "", "full disk")
    assert not info.saved and "NetCDF: HDF error" in info.problem and str(tmp_path) in info.problem
    assert list(tmp_path.iterdir()) == []
    assert store.load(info.run_id)[0] is qs_dataset


def test_full_file_system_keeps_the_run_in_memory(tmp_path, dynamic_dataset):
    with small_file_system(tmp_path / "full", size="64k") as root:
        store = RunStore(root)
        noise = np.random.default_rng(0).random(100_000)  # 800 kB that does not compress
        big = dynamic_dataset.assign(noise=(("n",), noise))
        info = store.save(big, "", "too big")
        assert not info.saved and str(root) in info.problem
        assert [p.name for p in root.iterdir()] == []
        assert store.load(info.run_id)[0] is big


# ---- any run.json ----------------------------------------------------------------------------
_JSON = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20),
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4)
    ),
    max_leaves=12,
)
_FIELDS = st.fixed_dictionaries(
    {},
    optional={k: _JSON | st.text(max_size=30) for k in ("title", "model", "status", "created")},
)


@settings(max_examples=60, deadline=None, database=None, derandomize=True)
@given(meta=_FIELDS | _JSON)
def test_any_run_json_is_listed_never_raises(tmp_path_factory, meta):
    root = tmp_path_factory.mktemp("runs")
    folder = root / "20260101-000000-run-abcd"
    folder.mkdir()
    (folder / META_FILE).write_text(json.dumps(meta), encoding="utf-8")
    (folder / RESULT_FILE).write_bytes(b"CDF\x01" + b"\0" * 20)
    (folder / CASE_FILE).write_text("")
    (info,) = RunStore(root).list()
    assert info.status in ("done", "cancelled", "broken")
    assert info.broken == bool(info.problem)
    assert not _has_control(info.label)
    if info.broken:
        with pytest.raises(ValueError, match="is broken"):
            RunStore(root).load(info.run_id)


def _has_control(text: str) -> bool:
    return any(ord(c) < 32 or 0x7F <= ord(c) < 0xA0 for c in text)
