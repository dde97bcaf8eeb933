"""Study files: validation messages name the study key, points expand grids and zips."""

from __future__ import annotations

import pytest

from solver.errors import CaseError
from solver.study import Study, parse_study, shipped_studies, study_points
from solver.study.spec import MAX_POINTS

BASE = 'title = "t"\nbase = "spindle-axial-preload"\n'


def problems(text: str) -> dict[str, str]:
    with pytest.raises(CaseError) as info:
        Study.from_text(text)
    return {p.key: p.message for p in info.value.problems}


def test_quoted_and_dotted_keys_mean_the_same():
    quoted = parse_study(BASE + '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n')
    dotted = parse_study(BASE + "vary.operating.radial_load_N = [0.0, 300.0]\n")
    assert (
        quoted.sweeps[0].vary == dotted.sweeps[0].vary == {"operating.radial_load_N": [0.0, 300.0]}
    )


def test_grid_has_every_combination_last_key_fastest():
    text = BASE + (
        "[vary]\n"
        '"operating.radial_load_N" = [0.0, 300.0]\n'
        '"operating.axial_load_N" = [400.0, 500.0, 600.0]\n'
    )
    points = Study.from_text(text).points()
    assert [p.name for p in points] == [f"p{i:04d}" for i in range(1, 7)]
    pairs = [
        (p.values["operating.radial_load_N"], p.values["operating.axial_load_N"]) for p in points
    ]
    assert pairs == [
        (0.0, 400.0), (0.0, 500.0), (0.0, 600.0), (300.0, 400.0), (300.0, 500.0), (300.0, 600.0)
    ]  # fmt: skip
    assert points[4].case.operating.axial_load_N == 500.0
    assert points[4].case.operating.radial_load_N == 300.0
    assert all(p.models == ("quasistatic",) for p in points)


def test_zip_takes_lists_together_and_set_and_run_apply():
    text = BASE + (
        'model = "both"\ncombine = "zip"\n[run]\nshaft_revolutions = 2.5\n'
        '[vary]\n"operating.radial_load_N" = [0.0, 300.0]\n'
        '"operating.misalignment_deg" = [0.05, 0.1]\n'
        '[set]\n"operating.misalignment_frame" = "ring"\n'
    )
    points = Study.from_text(text).points()
    assert len(points) == 2
    case = points[1].case
    assert (case.operating.radial_load_N, case.operating.misalignment_deg) == (300.0, 0.1)
    assert case.operating.misalignment_frame == "ring"
    assert case.simulation.shaft_revolutions == 2.5
    assert points[1].models == ("quasistatic", "dynamic")


def test_zip_of_unequal_lists_names_combine_and_lengths():
    found = problems(
        BASE + 'combine = "zip"\n[vary]\n"operating.radial_load_N" = [0.0, 1.0]\n'
        '"operating.axial_load_N" = [400.0]\n'
    )
    assert "combine" in found
    assert "operating.radial_load_N has 2" in found["combine"]
    assert "grid" in found["combine"]


def test_unknown_keys_are_named_with_a_suggestion():
    found = problems(BASE + 'modle = "dynamic"\n[vary]\n"operating.radial_load_N" = [1.0]\n')
    assert "modle" in found and "'model'" in found["modle"]
    found = problems(BASE + '[vary]\n"operating.radial_lod_N" = [1.0]\n')
    assert "vary.operating.radial_lod_N" in found
    assert "operating.radial_load_N" in found["vary.operating.radial_lod_N"]


def test_bad_choices_empty_lists_and_missing_base():
    found = problems('title = "t"\nmodel = "fast"\n[vary]\n"operating.radial_load_N" = []\n')
    assert set(found) >= {"base", "model", "vary.operating.radial_load_N"}
    assert "'quasistatic'" in found["model"]
    assert "non-empty list" in found["vary.operating.radial_load_N"]


def test_an_invalid_point_names_the_point_the_value_and_the_key():
    found = problems(BASE + '[vary]\n"operating.radial_load_N" = [0.0, -5.0]\n')
    assert list(found) == ["vary.operating.radial_load_N"]
    message = found["vary.operating.radial_load_N"]
    assert "point p0002" in message and "-5.0" in message


def test_sweeps_are_joined_and_numbered():
    text = BASE + (
        "[[sweep]]\nvary.operating.radial_load_N = [0.0, 300.0]\n"
        '[[sweep]]\nname = "tilt"\nmodel = "dynamic"\n'
        "vary.operating.misalignment_deg = [0.1]\n"
        'set.operating.misalignment_frame = "ring"\n'
    )
    study = Study.from_text(text)
    assert [(p.name, p.sweep) for p in study.points()] == [
        ("p0001", "sweep 1"),
        ("p0002", "sweep 1"),
        ("p0003", "tilt"),
    ]
    assert study.spec.varied_keys == (
        "operating.radial_load_N",
        "operating.misalignment_deg",
        "operating.misalignment_frame",
    )
    found = problems(BASE + '[[sweep]]\ncombine = "zip"\nvary.operating.radial_load_N = [1.0]\n'
                     '[[sweep]]\nmodel = "x"\nvary.operating.radial_load_N = [1.0]\n')  # fmt: skip
    assert "sweep[2].model" in found


def test_too_many_points_is_refused_before_any_case_is_built():
    n = int(MAX_POINTS**0.5) + 2
    values = ", ".join(f"{100.0 + i}" for i in range(n))
    found = problems(
        BASE + f'[vary]\n"operating.radial_load_N" = [{values}]\n'
        f'"operating.axial_load_N" = [{values}]\n'
    )
    assert "more than" in found["vary"]


def test_base_that_is_not_a_case_names_base(tmp_path):
    found = problems('base = "no-such-case"\n[vary]\n"operating.radial_load_N" = [1.0]\n')
    assert "base" in found and "no-such-case" in found["base"]


def test_base_file_is_relative_to_the_study_file(tmp_path):
    from solver.catalogue import catalogue

    (tmp_path / "cases").mkdir()
    (tmp_path / "cases" / "mine.toml").write_text(catalogue().get("spindle-axial-preload").text())
    study = tmp_path / "s.toml"
    study.write_text('base = "cases/mine.toml"\n[vary]\n"operating.radial_load_N" = [10.0]\n')
    points = Study.from_file(study).points()
    assert points[0].case.operating.radial_load_N == 10.0


def test_the_shipped_studies_are_valid():
    shipped = shipped_studies()
    assert {"seed-spindle", "218-radial-load"} <= set(shipped)
    for name in shipped:
        study = Study.from_file(name)
        assert study.points(), name
    seed = Study.from_file("seed-spindle")
    frames = {p.case.operating.misalignment_frame for p in seed.points()}
    assert frames == {"space", "ring"}
    speeds = {p.case.operating.inner_ring_speed_rpm for p in seed.points()}
    assert min(speeds) == 5000.0 and max(speeds) == 30000.0
    assert study_points(seed.spec)[-1].case.operating.radial_load_N == 300.0


def test_a_dynamic_study_of_a_bearing_set_is_refused_naming_the_point():
    text = (
        'title = "t"\nbase = "spindle-pair-db-light-preload"\nmodel = "dynamic"\n'
        '[vary]\n"set.preload.force_N" = [100.0, 200.0]\n'
    )
    with pytest.raises(CaseError) as info:
        Study.from_text(text).points()
    (first, second) = info.value.problems
    assert first.key == "model" and "point p0001" in first.message
    assert "runs the quasi-static model only" in first.message and "racetrace simulate" in (
        first.message
    )
