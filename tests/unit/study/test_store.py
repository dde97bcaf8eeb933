"""The study folder: what is read is validated ("not a study folder"), a resume checks every input
that determines a point, temporary files of a killed run are removed, and the study Dataset keeps
no path of the machine that ran it. No Dask: the folders are written by hand."""

from __future__ import annotations

import json

import pytest

import solver
from solver.errors import CaseError
from solver.study import Study, StudyFolder, open_study, study_dataset

STUDY = 'title = "store"\nbase = "base.toml"\n[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n'
DONE = {
    "status": "done",
    "message": "",
    "metrics": {"excursion": {"inner": 1.0, "outer": 2.0}, "cage_slip": 0.01},
    "wall_time_s": 0.1,
}


def base_case_text(axial_load_N: float) -> str:
    import solver

    case = solver.catalogue().get("spindle-axial-preload").load()
    return case.with_values({"operating.axial_load_N": axial_load_N}).to_toml()


@pytest.fixture
def study_dir(tmp_path):
    """A study file with a base case file next to it (axial load 500 N)."""
    (tmp_path / "base.toml").write_text(base_case_text(500.0))
    (tmp_path / "study.toml").write_text(STUDY)
    return tmp_path


def finished_folder(study_dir, runs=("p0001",)):
    """The study run in ``study_dir/out`` with ``runs`` finished (records written by hand)."""
    study = Study.from_file(study_dir / "study.toml")
    folder = StudyFolder(study_dir / "out")
    from solver._numba_cache import SOLVER_DIR, source_fingerprint
    from solver.study.store import study_inputs

    inputs = study_inputs(study.spec, study.base, source_fingerprint(SOLVER_DIR))
    folder.start(study.spec, study.points(), "test", resume=False, inputs=inputs)
    for name in runs:
        folder.save_run(name, "quasistatic", DONE, None)
    return folder


def run_again(study_dir, **options):
    """Study.run on the folder with every run finished: only the checks run, no cluster."""
    study = Study.from_file(study_dir / "study.toml")
    return study.run(study_dir / "out", **options)


# ---- not a study folder ---------------------------------------------------------------------
@pytest.mark.parametrize(
    "content, why",
    [
        ("{not json", "not JSON"),
        ("[1, 2]", "holds list"),
        ('{"title": "t", "base": "b", "varied_keys": []}', "'points'"),
        ('{"title": "t", "base": "b", "varied_keys": [], "points": [[1]]}', "points[0] is list"),
        (
            '{"title": "t", "base": "b", "varied_keys": [], "points": [{"name": "../../etc", '
            '"sweep": "s", "models": ["dynamic"], "coordinates": {}}]}',
            "point name",
        ),
        ('{"title": 3, "base": "b"}', "'title'"),
        ("[" * 100_000 + "]" * 100_000, "deep"),
        (b"\xff\xfe{}", "not UTF-8"),
    ],
)
def test_a_broken_manifest_is_not_a_study_folder(tmp_path, content, why):
    data = content if isinstance(content, bytes) else content.encode()
    (tmp_path / "study.json").write_bytes(data)
    with pytest.raises(CaseError) as info:
        open_study(tmp_path)
    assert "not a study folder" in str(info.value) and why in str(info.value)


@pytest.mark.parametrize(
    "record, why",
    [
        ("[1]", "holds list"),
        ('{"status": "maybe"}', "'status'"),
        ('{"status": "done", "metrics": {"excursion": 3}}', "excursion"),
        ('{"status": "done", "metrics": [1]}', "'metrics'"),
        ("not json", "not JSON"),
    ],
)
def test_a_broken_run_record_is_named(study_dir, record, why):
    folder = finished_folder(study_dir, runs=())
    folder.record_path("p0002", "quasistatic").write_text(record)
    with pytest.raises(CaseError) as info:
        open_study(folder.path)
    message = str(info.value)
    assert "not a study folder" in message and why in message
    assert "p0002.quasistatic.json" in message and "delete it" in message


def test_a_point_name_cannot_reach_outside_the_folder(study_dir):
    folder = finished_folder(study_dir)
    with pytest.raises(CaseError):
        folder.load_point("../../base", "quasistatic")


# ---- resume checks the inputs -------------------------------------------------------------------
def test_resume_refuses_an_edited_base_case_file(study_dir):
    finished_folder(study_dir)
    (study_dir / "base.toml").write_text(base_case_text(1500.0))
    with pytest.raises(CaseError) as info:
        run_again(study_dir, resume=True)
    message = str(info.value)
    assert "base case" in message and "operating.axial_load_N 500.0 -> 1500.0" in message
    assert "--restart" in message


def test_resume_refuses_another_solver_unless_accepted_and_then_records_it(study_dir):
    folder = finished_folder(study_dir, runs=("p0001", "p0002"))
    manifest = json.loads((folder.path / "study.json").read_text())
    manifest["inputs"]["solver_sources"] = "0123456789abcdef"
    (folder.path / "study.json").write_text(json.dumps(manifest))
    with pytest.raises(CaseError) as info:
        run_again(study_dir, resume=True)
    assert "solver changed" in str(info.value) and "--accept-solver-change" in str(info.value)
    ds = run_again(study_dir, resume=True, accept_solver_change=True)
    changes = json.loads(ds.attrs["solver_changes"])
    assert changes[0]["from"] == "0123456789abcdef" and changes[0]["finished_runs"] == 2
    kept = json.loads((folder.path / "study.json").read_text())
    assert kept["solver_changes"] == changes
    assert list(ds["status"].values[:, 0]) == ["done", "done"]


def test_resume_of_a_folder_without_recorded_inputs_is_refused(study_dir):
    folder = finished_folder(study_dir)
    manifest = json.loads((folder.path / "study.json").read_text())
    del manifest["inputs"]
    (folder.path / "study.json").write_text(json.dumps(manifest))
    with pytest.raises(CaseError, match="does not record the inputs"):
        run_again(study_dir, resume=True)


def test_restart_deletes_the_previous_runs_only(study_dir):
    folder = finished_folder(study_dir, runs=("p0001", "p0002"))
    (study_dir / "base.toml").write_text(base_case_text(1500.0))
    mine = folder.path / "notes.txt"
    mine.write_text("kept")
    folder.start(
        Study.from_file(study_dir / "study.toml").spec, [], "test", resume=False, restart=True
    )
    assert folder.record("p0001", "quasistatic") is None
    assert mine.read_text() == "kept"


def test_resume_removes_the_half_written_files_of_a_killed_run(study_dir):
    folder = finished_folder(study_dir, runs=("p0001", "p0002"))
    left = [
        folder.points_dir / ".p0002.quasistatic.nc.k3j_x9ab.tmp",
        folder.points_dir / ".p0001.dynamic.json.abcd1234.tmp",
        folder.path / ".study.nc.zz99yy88.tmp",
    ]
    other = folder.points_dir / ".notes.tmp"
    for path in [*left, other]:
        path.write_text("half")
    lines = []
    run_again(study_dir, resume=True, log=lines.append)
    assert not any(path.exists() for path in left) and other.exists()
    assert any("removed 3 half-written file(s)" in line for line in lines)


def test_the_study_dataset_names_its_folder_without_the_path(study_dir):
    folder = finished_folder(study_dir)
    assert study_dataset(folder).attrs["study_folder"] == "out"


def test_the_study_dataset_carries_the_fingerprint_of_what_its_points_depend_on(
    study_dir, monkeypatch
):
    ds = study_dataset(finished_folder(study_dir))
    study = Study.from_file(study_dir / "study.toml")
    before = study.fingerprint()
    assert ds.attrs["results_fingerprint"] == before
    assert ds.attrs["results_version"] == solver.RESULTS_VERSION
    # a title or a comment leaves it; a value, another model or another results version moves it
    (study_dir / "study.toml").write_text("# note\n" + STUDY.replace('"store"', '"other"'))
    assert Study.from_file(study_dir / "study.toml").fingerprint() == study.fingerprint()
    (study_dir / "study.toml").write_text(STUDY.replace("300.0", "301.0"))
    assert Study.from_file(study_dir / "study.toml").fingerprint() != study.fingerprint()
    (study_dir / "study.toml").write_text('model = "both"\n' + STUDY)
    assert Study.from_file(study_dir / "study.toml").fingerprint() != study.fingerprint()
    (study_dir / "study.toml").write_text(STUDY)
    from solver.results import provenance

    monkeypatch.setattr(provenance, "RESULTS_VERSION", solver.RESULTS_VERSION + 1)
    assert Study.from_file(study_dir / "study.toml").fingerprint() != before


def test_restart_does_not_write_into_a_folder_that_is_not_a_study_folder(study_dir):
    other = study_dir / "other"
    other.mkdir()
    (other / "thesis.tex").write_text("mine")
    study = Study.from_file(study_dir / "study.toml")
    with pytest.raises(CaseError, match="not empty"):
        StudyFolder(other).start(study.spec, study.points(), "test", resume=False, restart=True)
    assert sorted(p.name for p in other.iterdir()) == ["thesis.tex"]


def test_study_runs_lists_the_runs_a_point_makes_in_table_order():
    import xarray as xr

    from solver.study import study_runs

    status = [["done", "not run"], ["failed", "pending"]]
    ds = xr.Dataset({"status": (("point", "model"), status)})
    assert list(study_runs(ds)) == [(0, 0, "done"), (1, 0, "failed"), (1, 1, "pending")]
