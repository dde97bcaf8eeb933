"""Quasi-static solutions over one revolution: a misalignment turning with the inner ring draws a
line on the inner raceway (in the inner ring's frame) and a band on the outer one; fixed in space,
the roles swap (the quasi-static answer of a fixed tilt: one solution in steady running)."""

from __future__ import annotations

import numpy as np
import pytest

import solver

ANGLES = 8


def _spread(ds, race: str) -> float:
    """Largest difference (degree) between the contact-angle curves of the ring angles, each as a
    periodic function of the azimuth in the race's own ring frame: 0 for a line."""
    grid = np.linspace(0.0, 360.0, 73)
    curves = []
    for k in range(ds.sizes["ring_angle"]):
        e = ds.isel(ring_angle=k).sel(race=race)
        az, alpha = e["raceway_azimuth"].values, e["contact_angle"].values
        curves.append(np.interp(grid, az, alpha, period=360.0))
    curves = np.array(curves)
    return float(np.max(curves.max(axis=0) - curves.min(axis=0)))


@pytest.fixture(scope="module")
def turning():
    return solver.solve_over_revolution("spindle-misalignment-ring", angles=ANGLES)


@pytest.fixture(scope="module")
def fixed():
    return solver.solve_over_revolution("spindle-misalignment-space", angles=ANGLES)


def test_angles_and_turning_axis(turning):
    np.testing.assert_allclose(turning["ring_angle"].values, np.arange(ANGLES) * 360.0 / ANGLES)
    assert turning["ring_angle"].attrs["units"] == "degree"
    axis = turning["misalignment_axis"].values
    np.testing.assert_allclose(np.diff(axis), 360.0 / ANGLES)
    assert turning["raceway_azimuth"].dims == ("ring_angle", "ball", "race")


def test_turning_misalignment_is_a_line_inside_and_a_band_outside(turning):
    inner, outer = _spread(turning, "inner"), _spread(turning, "outer")
    assert inner < 0.1 * outer, (inner, outer)


def test_fixed_misalignment_is_a_line_outside_and_a_band_inside(fixed):
    inner, outer = _spread(fixed, "inner"), _spread(fixed, "outer")
    assert outer < 0.1 * inner, (inner, outer)


def test_too_few_angles_is_named():
    with pytest.raises(ValueError, match="at least 2"):
        solver.solve_over_revolution("spindle-misalignment-ring", angles=1)


# ---- the quasi-static answer of a tilt turning with the ring -------------------------------------
RING, SPACE = "spindle-misalignment-ring", "spindle-misalignment-space"


@pytest.fixture(scope="module")
def study_points():
    """The quasi-static records of a study's runs of the turning and the fixed tilt."""
    from solver.study.worker import run_one

    records = {}
    for name in (RING, SPACE):
        record, ds = run_one(solver.resolve_case(name), "quasistatic")
        assert record["status"] == "done", record["message"]
        records[name] = (record["metrics"], ds)
    return records


def test_the_answer_of_a_turning_tilt_spans_one_revolution(study_points):
    from solver.models.quasistatic import REVOLUTION_RING_ANGLES

    _, ring = study_points[RING]
    _, space = study_points[SPACE]
    assert ring.sizes["ring_angle"] == REVOLUTION_RING_ANGLES
    assert "ring_angle" not in space.dims  # what is fixed in space is the same at every angle


def test_study_point_of_a_turning_tilt_differs_from_the_fixed_one(study_points):
    """Turning with the inner ring, the tilt draws a line on the inner raceway (in the inner
    ring's frame: excursion about the band width, thickness near 0) and a band on the outer one
    (thickness about the band width, small excursion); fixed in space, the roles swap: the inner
    ring turns through the tilt, so its track is the band and the outer track the line."""
    ring, _ = study_points[RING]
    space, _ = study_points[SPACE]
    width = ring["band_width"]
    assert ring["excursion"]["inner"] == pytest.approx(width["inner"], rel=0.02)
    assert ring["band_thickness"]["inner"] < 0.02 * width["inner"]
    assert ring["band_thickness"]["outer"] == pytest.approx(width["outer"], rel=0.05)
    # the dynamic model draws the same outer band: excursion about 1.1-1.2 deg of 5.2 deg
    assert ring["excursion"]["outer"] < 0.25 * width["outer"]
    assert ring["excursion"]["outer"] < 0.25 * space["excursion"]["outer"]
    # fixed in space (dynamic, lesson 4: inner excursion 1.15 deg, the scatter of its bin medians
    # over 3 shaft revolutions, thickness 6.0 deg of 5.9; outer excursion 5.21, thickness 0.02)
    width = space["band_width"]
    assert space["excursion"]["inner"] < 0.05 * width["inner"]
    assert space["band_thickness"]["inner"] == pytest.approx(width["inner"], rel=0.03)
    assert space["excursion"]["outer"] == pytest.approx(width["outer"], rel=0.02)
    assert space["band_thickness"]["outer"] < 0.02 * width["outer"]


def test_study_show_tells_the_fixed_tilt_from_the_turning_one(study_points, tmp_path, capsys):
    """``racetrace study show`` of the seed study's two tilts (fixed in space, turning with the
    ring): different quasi-static rows, each naming its model."""
    from racetrace import cli
    from solver.study import Study, StudyFolder

    study = Study.from_text(
        'title = "tilts"\nbase = "spindle-axial-preload"\nmodel = "quasistatic"\n'
        '[[sweep]]\nname = "fixed"\nvary."operating.misalignment_deg" = [0.05]\n'
        'set."operating.misalignment_frame" = "space"\n'
        '[[sweep]]\nname = "turning"\nvary."operating.misalignment_deg" = [0.05]\n'
        'set."operating.misalignment_frame" = "ring"\n'
    )
    folder = StudyFolder(tmp_path / "s")
    folder.start(study.spec, study.points(), "test", resume=False)
    for point, name in (("p0001", SPACE), ("p0002", RING)):
        metrics, _ = study_points[name]
        folder.save_run(point, "quasistatic", {"status": "done", "metrics": metrics}, None)
    assert cli.main(["study", "show", str(tmp_path / "s"), "--wide"]) == 0  # every column
    out = capsys.readouterr().out
    lines = out.splitlines()
    units = ("deg", "GPa", "N", "ms")  # a column's name is its first word: "exc_i deg"
    header = next(line.split() for line in lines if line.lstrip().startswith("point"))
    header = [word for word in header if word not in units]
    rows = {
        line.split()[0]: dict(zip(header, line.split(), strict=False))
        for line in lines
        if line.startswith("p000")
    }
    fixed, turning = rows["p0001"], rows["p0002"]
    assert fixed["model"] == turning["model"] == "quasistatic"
    columns = [c for c in header if c.startswith(("exc_", "band_"))]
    assert [fixed[c] for c in columns] != [turning[c] for c in columns]
    # fixed: the inner band (no excursion), the outer line; turning: the inner line
    assert float(fixed["exc_i"]) < 0.3 < float(turning["exc_i"])
    assert float(fixed["band_i"]) > 5.0 > float(turning["band_i"])
    assert float(fixed["exc_o"]) > 5.0 > float(turning["exc_o"])


def test_study_point_agrees_with_solve_over_revolution(study_points):
    ring, _ = study_points[RING]
    direct = solver.solve_over_revolution(RING)
    for name, value in ring.items():
        expected = direct.racetrace.metric(name)
        if isinstance(value, dict):
            for race, v in value.items():
                np.testing.assert_allclose(v, float(expected.sel(race=race)), rtol=1e-9)
        else:
            np.testing.assert_allclose(value, float(expected), rtol=1e-9)


def test_contact_metrics_span_every_ring_angle(study_points):
    """Largest load and peak pressure: the largest at any ring angle; mean contact angle: over
    every ring angle and ball."""
    _, ds = study_points[RING]
    for name in ("largest_load", "peak_pressure"):
        value = ds.racetrace.metric(name)
        assert value.dims == ("race",)
        per_angle = [
            ds.isel(ring_angle=k).racetrace.metric(name) for k in range(ds.sizes["ring_angle"])
        ]
        np.testing.assert_allclose(value.values, np.max(per_angle, axis=0))
    mean = ds.racetrace.metric("mean_contact_angle")
    np.testing.assert_allclose(
        mean.values, ds["contact_angle"].mean(("ring_angle", "ball")).values, rtol=1e-12
    )


def test_cli_gives_the_study_answer(study_points, capsys):
    """``racetrace quasistatic`` quotes the same answer (metrics over the revolution) as a study."""
    import json

    from racetrace.cli import main

    assert main(["quasistatic", RING, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ring, _ = study_points[RING]
    assert out["ring_angles"] == study_points[RING][1].sizes["ring_angle"]
    for race in ("inner", "outer"):
        trajectory = out["trajectory"][race]
        assert trajectory["excursion_deg"] == pytest.approx(ring["excursion"][race], rel=1e-12)
        assert trajectory["band_thickness_deg"] == pytest.approx(
            ring["band_thickness"][race], rel=1e-12
        )
        assert out["max_contact_load_N"][race] == pytest.approx(
            ring["largest_load"][race], rel=1e-12
        )


def test_a_saved_revolution_is_a_valid_result(study_points, tmp_path):
    _, ds = study_points[RING]
    path = solver.save_dataset(ds, tmp_path / "ring.nc")
    back = solver.load_result(path, "ring.nc")
    assert back.sizes["ring_angle"] == ds.sizes["ring_angle"]
    np.testing.assert_allclose(
        back.racetrace.metric("excursion").values, ds.racetrace.metric("excursion").values
    )
    assert "over one revolution" in back.attrs["misalignment_note"]


def test_a_revolution_with_bad_ring_angles_is_refused(study_points):
    from solver.results.validate import result_problems

    _, ds = study_points[RING]
    assert result_problems(ds, True) == []
    reversed_angles = ds.assign_coords(ring_angle=ds["ring_angle"].values[::-1])
    assert any("ring_angle" in p for p in result_problems(reversed_angles, True))
    dynamic = ds.assign_attrs(model="dynamic")
    assert any("ring_angle" in p for p in result_problems(dynamic, False))


def test_the_contact_table_of_a_revolution_has_a_row_per_ring_angle(study_points):
    _, ds = study_points[RING]
    table = solver.contact_table(ds)
    assert list(table.columns[:3]) == ["ring_angle", "ball", "race"]
    assert len(table) == ds.sizes["ring_angle"] * ds.sizes["ball"] * 2
