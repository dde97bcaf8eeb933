"""racetrace study: invalid input is named (exit 2) before any cluster starts; study show."""

from __future__ import annotations

import json

from racetrace import cli


def test_invalid_study_names_the_key_and_exits_2(tmp_path, capsys):
    study = tmp_path / "bad.toml"
    study.write_text(
        'base = "spindle-axial-preload"\ncombine = "zip"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n"operating.axial_lod_N" = [1.0]\n'
    )
    assert cli.main(["study", str(study), "--output", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "vary.operating.axial_lod_N" in err and "operating.axial_load_N" in err
    assert not (tmp_path / "out").exists()


def test_output_is_required_and_workers_positive(tmp_path, capsys):
    assert cli.main(["study", "seed-spindle"]) == 2
    assert "--output DIR is required" in capsys.readouterr().err
    assert cli.main(["study", "seed-spindle", "-o", str(tmp_path / "o"), "--workers", "0"]) == 2
    assert "--workers 0" in capsys.readouterr().err


def test_show_needs_a_study_folder(tmp_path, capsys):
    assert cli.main(["study", "show"]) == 2
    assert cli.main(["study", "show", str(tmp_path)]) == 2
    assert "not a study folder" in capsys.readouterr().err


def test_show_prints_the_points_of_a_folder(tmp_path, capsys):
    from solver.study import Study, StudyFolder

    study = Study.from_text(
        'title = "shown"\nbase = "spindle-axial-preload"\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n'
    )
    folder = StudyFolder(tmp_path / "s")
    folder.start(study.spec, study.points(), "test", resume=False)
    record = {
        "status": "done",
        "message": "",
        "metrics": {"excursion": {"inner": 1.25, "outer": 2.5}, "cage_slip": 0.01},
        "wall_time_s": 0.1,
    }
    folder.save_run("p0001", "quasistatic", record, None)
    folder.save_run("p0002", "quasistatic", {"status": "failed", "message": "no solution"}, None)
    assert cli.main(["study", "show", str(tmp_path / "s")]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    p1 = next(line for line in lines if line.startswith("p0001"))
    assert "done" in p1 and "1.2500" in p1 and "2.5000" in p1
    assert "p0002 quasistatic: no solution" in out
    manifest = json.loads((tmp_path / "s" / "study.json").read_text())
    assert [p["name"] for p in manifest["points"]] == ["p0001", "p0002"]
