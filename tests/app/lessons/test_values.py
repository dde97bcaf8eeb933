"""The values a lesson quotes, against numbers computed here from the Dataset directly."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import solver  # noqa: F401
from app.lessons import results as lesson_results
from app.lessons.format import load_lessons
from app.lessons.values import VALUES, lesson_values
from solver import RPM

LESSONS = load_lessons()
DOCS = Path(__file__).resolve().parents[3] / "docs" / "lessons.md"


def _shipped(lesson_id: str, name: str):
    lesson = LESSONS.get(lesson_id)
    path = lesson_results.shipped_results_dir() / lesson_results.shipped_name(
        lesson, lesson.result(name)
    )
    return solver.load_dataset(path)


@pytest.fixture(scope="module")
def speed():
    return _shipped("02-speed", "speed")


@pytest.fixture(scope="module")
def run():
    return _shipped("03-radial-load", "radial")


def test_quasistatic_values(speed):
    v = lesson_values(speed)
    assert v["speed_rpm"] == pytest.approx(30000.0)
    assert v["axial_load"] == 500.0 and v["ball_count"] == 18
    for race in ("inner", "outer"):
        angles = speed["contact_angle"].sel(race=race).values
        assert v[f"{race}_contact_angle"] == pytest.approx(angles.mean())
        assert v[f"{race}_contact_angle_max"] == pytest.approx(angles.max())
        assert v[f"{race}_semi_major"] == pytest.approx(
            1e3 * speed["ellipse_semi_major"].sel(race=race).values.mean()
        )
        assert v[f"{race}_pressure"] == pytest.approx(
            1e-9 * speed["max_pressure"].sel(race=race).values.max()
        )
    assert v["gyroscopic_moment"] == pytest.approx(1e3 * speed["gyroscopic_moment"].values.mean())
    assert v["centrifugal_force"] == pytest.approx(speed["centrifugal_force"].values.mean())
    assert v["race_control"] == "outer"
    # steady running under a pure axial load: every ball alike, so the track is a line
    assert v["inner_band_thickness"] == pytest.approx(0.0, abs=1e-9)
    assert v["shaft_revolutions"] is None
    assert v["warning_count"] == 0 and v["loaded_balls"] == 18
    assert v["misalignment_frame"] == "fixed in space"


def test_epicyclic_cage_speed_by_hand(speed):
    # omega_c = omega_i (1 - D cos(alpha_0) / d_m) / 2 with the outer ring at rest
    omega_i = 30000.0 * 2 * math.pi / 60
    expected = omega_i * (1 - 7.144 * math.cos(math.radians(15.0)) / 54.0) / 2
    assert float(speed.racetrace.metric("epicyclic_cage_speed")) == pytest.approx(expected)
    v = lesson_values(speed)
    assert v["cage_slip"] == pytest.approx(100 * (1 - float(speed["cage_speed"]) / expected))


def test_dynamic_values_use_the_analysed_window(run):
    v = lesson_values(run)
    start = float(run.racetrace.summary()["analysis_start_time"])
    window = run.sel(time=run["time"] >= start)
    load = window["contact_load"].sel(race="outer").values
    angle = window["contact_angle"].sel(race="outer").values
    assert v["outer_contact_angle"] == pytest.approx(angle[load > 0].mean(), rel=1e-6)
    assert v["outer_load_min"] == pytest.approx(load.min())
    assert v["cage_speed_rpm"] == pytest.approx(
        window["cage_speed"].values.mean() * 60 / (2 * math.pi), rel=1e-6
    )
    assert v["inner_band_thickness"] == pytest.approx(
        float(
            run.racetrace.summary()["trajectory_band_thickness"].sel(
                race="inner", frame="inner_ring"
            )
        )
    )
    assert v["gyroscopic_moment"] is None and v["race_control"] is None
    assert v["shaft_revolutions"] == pytest.approx(12.0, rel=1e-3)
    # centrifugal force from the ball's mass and the mean orbital speed
    density = float(run.coords["density"].sel(body="ball"))
    mass = density * math.pi * 7.144e-3**3 / 6
    omega = window["orbital_speed"].values.mean()
    assert v["centrifugal_force"] == pytest.approx(mass * 0.027 * omega**2, rel=1e-5)
    loaded = (window["contact_load"].sel(race="inner") > 0).sum("ball").values
    assert v["loaded_balls"] == int(np.median(loaded))


def test_every_value_is_documented():
    with open(DOCS, encoding="utf-8") as handle:
        doc = handle.read()
    missing = [name for name in VALUES if f"`{name}`" not in doc]
    assert not missing, f"docs/lessons.md does not list: {missing}"


def test_docs_example_is_the_shipped_lesson_and_reads():
    from app.lessons.format import parse_lesson

    doc = DOCS.read_text(encoding="utf-8")
    example = doc.split("```toml\n", 1)[1].split("```", 1)[0]
    shipped = Path(__file__).resolve().parents[3] / "assets" / "lessons" / "02-speed.toml"
    assert example == shipped.read_text(encoding="utf-8")
    assert parse_lesson(example, "02-speed") == LESSONS.get("02-speed")


def test_no_controlling_race_when_ball_speeds_come_from_traction():
    overload = _shipped("06-overload", "overload")  # the default quasi-static ball speeds
    assert set(overload["race_control"].values) == {"traction"}
    assert lesson_values(overload)["race_control"] is None


def test_a_run_along_a_history_quotes_its_inputs_phases_and_skid():
    """Lesson 7's start-up: the speed varies (a data variable over time), quoted at the end of
    the run and at t = 0; the first phase is the ramp, the last the speed held after it."""
    run = _shipped("07-start-up-skid", "startup")
    assert "inner_ring_speed" not in run.coords and run["inner_ring_speed"].dims == ("time",)
    v = lesson_values(run)
    assert v["speed_rpm"] == pytest.approx(20000.0, rel=1e-6)
    assert v["start_speed_rpm"] == 0.0
    assert v["first_phase_end_time"] == pytest.approx(0.05) == v["last_phase_start_time"]
    by_phase = run.racetrace.phase_metrics()["mean_instantaneous_cage_slip"].values
    assert v["first_phase_cage_slip"] == pytest.approx(100.0 * by_phase[0], rel=1e-12)
    assert v["last_phase_cage_slip"] == pytest.approx(100.0 * by_phase[-1], rel=1e-12)
    ratio = run["skidding_ratio"].values
    fast = run["inner_ring_speed"].values >= 0.1 * 20000.0 * RPM  # the extent's samples
    assert v["min_skidding_ratio"] == pytest.approx(float(np.nanmin(ratio[fast])), rel=1e-6)
    assert v["skid_warnings"] == 1
    # a quasi-static result has neither phases nor a skid
    rest = _shipped("02-speed", "rest")
    assert lesson_values(rest)["first_phase_cage_slip"] is None
    assert lesson_values(rest)["min_skidding_ratio"] is None
