"""The Studies panel at state level: a small study builds up point by point, charts its metric,
opens a point's run in the result view, and Cancel keeps what is done."""

from __future__ import annotations

import time

import pytest

from app.components.studies import SLOT_WAIT_S
from app.state import DEFAULT_CASE, RacetraceApp
from solver.study import Study
from tests.helpers.app_session import trame_server
from tests.helpers.processes import wait_until

pytest.importorskip("distributed")

SMALL = """
title = "app study"
base = "spindle-axial-preload"
[vary]
"operating.radial_load_N" = [0.0, 400.0, 800.0]
"""


@pytest.fixture
def app(app):
    """The session of tests/app/conftest.py, its studies on one worker."""
    app.studies.workers = 1
    return app


def _wait(app, timeout_s=600):
    wait_until(
        app.studies.poll, timeout_s, 0.5, lambda: f"the study did not end: {app.state.study_status}"
    )


def test_shipped_studies_are_offered(app):
    assert {"seed-spindle", "218-radial-load"} <= set(app.state.study_names)
    assert app.state.study_name in app.state.study_names


def test_a_study_builds_up_charts_and_opens_a_point(app):
    app.studies.start(Study.from_text(SMALL), "small")
    assert app.state.study_running
    _wait(app)
    s = app.state
    assert s.study_status == "done" and not s.study_running
    assert [r["point"] for r in s.study_rows] == ["p0001", "p0002", "p0003"]
    assert all(r["status"] == "done" for r in s.study_rows)
    assert s.study_sweep == "sweep 1"
    traces = s.chart_study["data"]
    assert len(traces) == 2  # inner and outer, one model
    outer = next(t for t in traces if t["name"].startswith("outer"))
    assert list(outer["x"]) == [0.0, 400.0, 800.0]
    # each marker knows its run: a click on it opens that point
    assert outer["customdata"] == [[p, "quasistatic"] for p in ("p0001", "p0002", "p0003")]
    assert outer["y"][0] < outer["y"][1] < outer["y"][2]
    s.study_metric = "peak_pressure"
    s.flush()
    assert "peak pressure" in str(s.chart_study["layout"])
    serial = int(s.result_serial)
    app.studies.open_point("p0002", "quasistatic")
    assert int(s.result_serial) == serial + 1
    assert "p0002" in s.result_label
    assert app.result.dataset.coords["radial_load"] == pytest.approx(400.0)


def test_cancel_keeps_the_finished_runs(app):
    app.studies.start(Study.from_text(SMALL), "small")
    app.studies.cancel()
    _wait(app)
    assert app.state.study_status.startswith("cancelled")
    assert not app.state.study_running
    assert {r["status"] for r in app.state.study_rows} <= {"done", "pending"}


# ---- results of shipped studies and studies run before -------------------------------------------
def test_a_shipped_studys_results_open_without_running(app):
    s = app.state
    values = [i["value"] for i in s.study_results_items]
    assert "shipped:seed-spindle.study.nc" in values
    s.study_results = "shipped:seed-spindle.study.nc"
    s.flush()
    assert s.study_status.startswith("showing Seed study")
    assert len(s.study_rows) == 30  # 15 points, quasi-static and dynamic
    assert "radial load" in s.study_sweeps and s.study_sweep == "radial load"
    outer = next(t for t in s.chart_study["data"] if t["name"] == "outer, dynamic")
    assert list(outer["x"]) == [0.0, 300.0, 600.0, 1000.0, 1500.0]
    # its full runs are not shipped: opening a point says so, the result on show stays
    assert not any(r["openable"] for r in s.study_rows)
    serial = int(s.result_serial)
    app.studies.open_point("p0002", "dynamic")
    assert "not shipped" in s.study_status and int(s.result_serial) == serial
    s.study_results = "folder:../../etc"
    s.flush()
    assert s.study_status.startswith("error: no such study results")


# ---- a study built from the case in the form -----------------------------------------------------
def test_a_shipped_set_studys_results_chart_the_set_and_each_bearing(app):
    """Opening the bearing-set study's results offers the set's metrics (the per-race ones are
    not its) and charts the set's axial stiffness with a line per bearing, in N/µm; the
    per-race metric chosen before falls back to the first of the set's."""
    s = app.state
    s.study_metric = "band_width"
    s.study_results = "shipped:spindle-pair-db-speed.study.nc"
    s.flush()
    assert s.study_status.startswith("showing 7008C-class DB pair")
    assert [i["value"] for i in s.study_metric_items][:3] == [
        "axial_stiffness",
        "radial_stiffness",
        "tilt_stiffness",
    ]
    assert s.study_metric == "axial_stiffness"
    traces = s.chart_study["data"]
    assert [t["name"] for t in traces] == ["set", "bearing 1", "bearing 2"]
    assert all(len(t["y"]) == 6 for t in traces)
    assert "N/µm" in str(s.chart_study["layout"])
    s.study_metric = "bearing_tilt_stiffness"
    s.flush()
    assert [t["name"] for t in s.chart_study["data"]] == ["bearing 1", "bearing 2"]
    # the table's figures are the set's stiffness (a set study has no per-race figures)
    assert s.study_table_heads == ["axial N/µm", "radial N/µm"]
    first = s.study_rows[0]
    i = list(app.studies.dataset()["point"].values).index(first["point"])
    axial = float(app.studies.dataset()["axial_stiffness"].values[i, 0]) * 1e-6
    assert first["figures"][0] == f"{axial:.4g}" and axial > 1.0
    assert all("-" not in r["figures"] for r in s.study_rows)
    s.study_results = "shipped:seed-spindle.study.nc"  # one bearing's study: its own metrics
    s.flush()
    assert s.study_metric == "excursion"
    assert "band_width" in [i["value"] for i in s.study_metric_items]
    assert s.study_table_heads == ["exc i/o deg", "band i/o deg"]
    assert all(len(r["figures"][0].split(" / ")) == 2 for r in s.study_rows)


def test_values_are_a_list_or_start_stop_count():
    from app.study_building import StudyInputError, parse_values

    assert parse_values("0, 300, 600", "v") == [0.0, 300.0, 600.0]
    assert parse_values("0:1500:4", "v") == [0.0, 500.0, 1000.0, 1500.0]
    for text, words in (
        ("", "give values"),
        ("0, lots", "not a list of numbers"),
        ("0:10:2.5", "whole number"),
        ("0:10", "not a list of numbers"),
        ("nan", "finite"),
    ):
        with pytest.raises(StudyInputError, match=words):
            parse_values(text, "values of operating.radial_load_N")


def test_a_built_study_file_is_valid_and_says_what_is_wrong(tmp_path):
    from app.study_building import StudyInputError, build_study_text
    from solver.catalogue import catalogue

    (tmp_path / "base.toml").write_text(catalogue().get(DEFAULT_CASE).load().to_toml())
    varied = [("operating.radial_load_N", [0.0, 500.0]), ("operating.axial_load_N", [300.0, 600.0])]
    text = build_study_text("t", varied, "zip", "both", "1.5")
    study = Study.from_text(text, folder=tmp_path)
    assert len(study.points()) == 2
    assert "shaft_revolutions = 1.5" in text and 'combine = "zip"' in text
    assert (
        len(
            Study.from_text(
                build_study_text("t", varied, "grid", "quasistatic", ""), folder=tmp_path
            ).points()
        )
        == 4
    )
    with pytest.raises(StudyInputError, match="as many values"):
        build_study_text("t", [varied[0], ("operating.axial_load_N", [1.0])], "zip", "both", 1)
    with pytest.raises(StudyInputError, match="run length"):
        build_study_text("t", varied, "grid", "dynamic", "long")
    with pytest.raises(StudyInputError, match="the same"):
        build_study_text("t", [varied[0], varied[0]], "grid", "quasistatic", 1)


def test_a_study_built_from_a_history_case_runs_for_the_case_duration(tmp_path):
    """A case with a time history runs for simulation.duration_s, not for shaft revolutions: the
    built study sets the case's duration on every point and its dynamic points are valid cases."""
    from app.study_building import build_study_text
    from solver.catalogue import catalogue

    case = catalogue().get("spindle-start-up").load()
    (tmp_path / "base.toml").write_text(case.to_toml())
    varied = [("operating.axial_load_N", [100.0, 200.0])]
    text = build_study_text(
        "t", varied, "grid", "dynamic", "2", duration_s=case.simulation.duration_s
    )
    assert "shaft_revolutions" not in text
    assert '"simulation.duration_s" = 0.4' in text
    study = Study.from_text(text, folder=tmp_path)
    points = study.points()
    assert len(points) == 2
    assert all(p.case.simulation.duration_s == 0.4 for p in points)


def test_build_a_study_from_the_current_case_runs_it_and_lists_it(app):
    s = app.state
    assert "operating.radial_load_N" in {i["value"] for i in s.study_key_items}
    s.fv_axial_load_N = "700"  # an edit in the form: the study's base is the edited case
    s.flush()
    s.study_key1, s.study_values1 = "operating.radial_load_N", "0:800:3"
    s.study_key2, s.study_values2 = "operating.inner_ring_speed_rpm", "10000, 20000"
    s.study_combine, s.study_model = "grid", "quasistatic"
    s.flush()
    app.studies.build()
    assert s.study_running, s.study_status
    _wait(app)
    assert s.study_status == "done" and s.study_progress == 100
    assert len(s.study_rows) == 6 and all(r["status"] == "done" for r in s.study_rows)
    assert all(r["openable"] for r in s.study_rows)
    folder = app.studies.folder.path
    base = (folder.parent / f"{folder.name}.base.toml").read_text()
    assert "../" + folder.name + ".base.toml" in (folder / "study.toml").read_text()
    assert "700" in base
    app.studies.open_point("p0006", "quasistatic")
    assert "p0006 (radial_load_N = 800, inner_ring_speed_rpm = 20000)" in s.result_label
    ds = app.result.dataset
    assert ds.coords["radial_load"] == pytest.approx(800.0)
    assert ds.coords["axial_load"] == pytest.approx(700.0)
    # the study is listed among the results to open again
    name = app.studies.folder.path.name
    assert f"folder:{name}" in [i["value"] for i in s.study_results_items]


def test_a_study_that_cannot_be_built_is_said_in_words(app):
    s = app.state
    s.study_key1, s.study_values1 = "operating.radial_load_N", "0, -500"
    s.flush()
    app.studies.build()
    assert not s.study_running
    assert s.study_status.startswith("error:") and "radial_load_N" in s.study_status
    assert not list((app.store.root / ".studies").iterdir())  # nothing left behind
    s.study_values1 = "lots"
    s.flush()
    app.studies.build()
    assert "not a list of numbers" in s.study_status
    s.study_key1 = "bearing.nothing"
    s.flush()
    app.studies.build()
    assert "not a numeric key" in s.study_status
    s.fv_ball_count = "0"
    s.study_key1 = "operating.radial_load_N"
    s.flush()
    app.studies.build()
    assert "not valid" in s.study_status


# ---- hostile state: a client's values never name a server file ----------------------------------
def test_study_results_only_open_what_the_server_lists(app, tmp_path, monkeypatch):
    """A client rewrites ``study_results_items`` to offer itself an absolute file and a folder
    out of ``.studies``, then picks them: nothing outside the two roots is opened."""
    import shutil

    import xarray as xr

    import solver.study
    from app.components.studies import SHIPPED_RESULTS

    secret = tmp_path / "outside.study.nc"  # a readable study Dataset outside the shipped root
    shutil.copy(SHIPPED_RESULTS / "seed-spindle.study.nc", secret)
    opened = []
    real_open_dataset, real_open_study = xr.open_dataset, solver.study.open_study
    monkeypatch.setattr(
        xr, "open_dataset", lambda p, *a, **k: opened.append(p) or real_open_dataset(p, *a, **k)
    )
    monkeypatch.setattr(
        solver.study, "open_study", lambda p: opened.append(p) or real_open_study(p)
    )
    s = app.state
    for value in (
        f"shipped:{secret}",
        "shipped:../../../" + secret.name,
        "folder:../..",
        "folder:../../" + tmp_path.name,
        "folder:/",
        "folder:\x00",
    ):
        s.study_results_items = [*s.study_results_items, {"title": "mine", "value": value}]
        s.study_results = value
        s.flush()
        assert s.study_status.startswith("error: no such study results"), (value, s.study_status)
        assert s.study_rows == [] and app.studies.dataset() is None
    assert opened == []


def test_study_name_is_a_shipped_study_only(app, tmp_path, monkeypatch):
    """``study_name`` naming a study file on the server (any path) runs nothing."""
    study_file = tmp_path / "mine.toml"
    study_file.write_text(SMALL)
    started = []
    monkeypatch.setattr(app.studies, "start", lambda *a, **k: started.append(a))
    s = app.state
    for name in (str(study_file), "../" * 8 + str(study_file), "/etc/passwd", ["seed-spindle"]):
        s.study_name = name
        s.flush()
        app.studies.run()
        assert s.study_status.startswith("error: no shipped study"), (name, s.study_status)
    assert started == []
    s.study_name = "seed-spindle"  # a shipped study still starts
    s.flush()
    app.studies.run()
    assert len(started) == 1 and started[0][1] == "seed-spindle"


def test_open_point_opens_only_a_point_of_the_study_on_show(app, tmp_path, qs_dataset):
    """``study_open(point, model)`` with a point that climbs out of the study folder: the file
    it names is not read and the result on show stays."""
    import solver
    from solver.study import StudyFolder

    folder = tmp_path / "runs" / ".studies" / "s-1"
    folder.mkdir(parents=True)
    solver.save_dataset(qs_dataset, tmp_path / "secret.quasistatic.nc")
    app.studies.folder = StudyFolder(folder)
    s = app.state
    serial = int(s.result_serial)
    for point, model in (
        ("../../../../secret", "quasistatic"),
        (str(tmp_path / "secret"), "quasistatic"),
        ("p0001", "../../../../../secret.quasistatic"),
        (["p0001"], "quasistatic"),
    ):
        app.studies.open_point(point, model)
        assert s.study_status.startswith("error: no point"), (point, s.study_status)
    # the client's own table naming such a point changes nothing
    s.study_rows = [{"point": "../../../../secret", "model": "quasistatic", "openable": True}]
    s.flush()
    app.studies.open_point("../../../../secret", "quasistatic")
    assert s.study_status.startswith("error: no point")
    assert int(s.result_serial) == serial


def test_built_study_varies_only_the_forms_numeric_keys(app):
    """A client adding a key to ``study_key_items`` does not make it a key to vary."""
    s = app.state
    s.study_key_items = [*s.study_key_items, {"title": "x", "value": "simulation.nothing"}]
    s.study_key1, s.study_values1 = "simulation.nothing", "1, 2"
    s.flush()
    app.studies.build()
    assert not s.study_running
    assert "is not a numeric key of the case" in s.study_status


# ---- a study from the page takes solver slots, as runs do ---------------------------------------
@pytest.fixture
def capped(tmp_path):
    """A session whose server runs at most one solver at once (``--max-runs 1``)."""
    from app.services import Services

    services = Services(tmp_path / "runs", tmp_path / "slots", max_runs=1)
    a = RacetraceApp(trame_server(), services=services, render=False)
    a.start(DEFAULT_CASE, play=False)
    yield a
    a.shutdown()


def _slot_free(pool) -> bool:
    """Whether a run could take a solver slot now."""
    probe = pool.enqueue()
    try:
        return pool.try_acquire(probe)
    finally:
        pool.drop(probe)


def _watched(study, pool, seen, real=True):
    """``study`` whose run records (workers, a slot free for a run) when its points start."""
    run = study.run

    def watched_run(output, **options):
        seen.append((options.get("workers"), _slot_free(pool)))
        return run(output, **options) if real else None

    study.run = watched_run
    return study


def test_a_page_study_and_a_run_never_compute_at_once(capped):
    """With ``--max-runs 1`` a study from the page waits while a run computes, and no run can
    start while its points compute (the study's Dask cluster is covered by the tests above)."""
    pool = capped.services.pool
    run_slot = pool.enqueue()  # a run of another session is computing: it holds the one slot
    assert pool.try_acquire(run_slot)
    seen = []
    capped.studies.start(_watched(Study.from_text(SMALL), pool, seen, real=False), "small")
    time.sleep(2 * SLOT_WAIT_S + 0.5)
    assert not capped.studies.poll()
    assert seen == []  # no Dask cluster, no point computed while the run holds the slot
    assert capped.state.study_status.startswith("queued: place 1 in the queue for a solver")
    pool.drop(run_slot)  # the run ends
    _wait(capped, 60)
    assert capped.state.study_status == "done"
    assert seen == [(1, False)]  # one worker, and no slot left for a run while it computed
    assert _slot_free(pool)  # given back at the end


def test_a_page_study_takes_the_free_slots_up_to_the_cap(tmp_path):
    from app.services import Services

    services = Services(tmp_path / "runs", tmp_path / "slots", max_runs=2)
    a = RacetraceApp(trame_server(), services=services, render=False)
    try:
        pool = services.pool
        seen = []
        a.studies.start(_watched(Study.from_text(SMALL), pool, seen, real=False), "small")
        _wait(a, 60)
        held = pool.enqueue()  # a run takes one of the two slots
        assert pool.try_acquire(held)
        a.studies.start(_watched(Study.from_text(SMALL), pool, seen, real=False), "small")
        _wait(a, 60)
        pool.drop(held)
        a.studies.workers = 5  # more workers asked for than the cap: the cap wins
        a.studies.start(_watched(Study.from_text(SMALL), pool, seen, real=False), "small")
        _wait(a, 60)
        assert seen == [(2, False), (1, False), (2, False)]
    finally:
        a.shutdown()


def test_a_page_study_cancelled_in_the_queue_computes_nothing(capped):
    pool = capped.services.pool
    run_slot = pool.enqueue()
    assert pool.try_acquire(run_slot)
    seen = []
    capped.studies.start(_watched(Study.from_text(SMALL), pool, seen, real=False), "small")
    capped.studies.cancel()
    _wait(capped, 60)
    assert capped.state.study_status.startswith("cancelled") and seen == []
    assert list((pool.dir / "queue").iterdir()) == []  # its ticket left the queue
    pool.drop(run_slot)
