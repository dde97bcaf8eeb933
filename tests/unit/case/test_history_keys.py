"""Operating keys given as time histories (docs/case-format.md, "Time histories"): each form gives
the knots, sine and rate of its closed form, the record the models read holds them in SI units, and
every mistake gets a message naming the key and the fix."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from solver.case import Case, parse_case
from solver.case.validate import validate
from solver.history import (
    CH_AXIAL_LOAD,
    CH_INNER_SPEED,
    CH_RADIAL_LOAD,
    CH_RADIAL_LOAD_ANGLE,
    FRAME_INNER_RING,
    FRAME_SPACE,
    channel_value,
)
from solver.history.integral import channel_integral
from solver.inputs import operating_at, to_inputs
from solver.results.provenance import case_values, result_fingerprint
from solver.units import RPM

from .conftest import problems_of

RAMP = {"ramp": {"from": 0.0, "to": 20000.0, "start_s": 0.1, "duration_s": 0.4}}


def history_case(valid, run=None, **operating):
    """The valid case with ``operating`` keys replaced and a [simulation] of ``run``."""
    data = copy.deepcopy(valid)
    data["operating"].update(operating)
    data["simulation"] = {"duration_s": 1.0} if run is None else run
    return data


def case_of(data, base_dir=None) -> Case:
    return Case.from_dict(data, base_dir)


def value(case, channel, t):
    return float(channel_value(to_inputs(case).history, channel, t))


# ---- each form against its closed form ----------------------------------------------------
def test_linear_ramp_in_rpm_becomes_rad_s_knots(valid):
    case = case_of(history_case(valid, inner_ring_speed_rpm=RAMP))
    assert case.operating.inner_ring_speed_rpm == 0.0  # the value at t = 0
    for t, rpm in ((0.0, 0.0), (0.1, 0.0), (0.2, 5000.0), (0.3, 10000.0), (0.5, 20000.0)):
        assert value(case, CH_INNER_SPEED, t) == pytest.approx(rpm * RPM, abs=1e-9), t
    assert value(case, CH_INNER_SPEED, 0.9) == pytest.approx(20000.0 * RPM)  # holds after
    assert to_inputs(case).operating.inner_ring_speed == 0.0


def test_smooth_ramp_is_the_c1_smoothstep(valid):
    ramp = dict(RAMP, interpolation="smooth")
    case = case_of(history_case(valid, inner_ring_speed_rpm=ramp))
    s = 0.25  # a quarter of the ramp: 3 s^2 - 2 s^3 = 0.15625
    expected = 20000.0 * (3 * s**2 - 2 * s**3)
    assert value(case, CH_INNER_SPEED, 0.2) == pytest.approx(expected * RPM)
    assert value(case, CH_INNER_SPEED, 0.3) == pytest.approx(10000.0 * RPM)


def test_step_jumps_at_its_time(valid):
    step = {"step": {"from": 100.0, "to": 800.0, "at_s": 0.05}}
    case = case_of(history_case(valid, radial_load_N=step))
    assert case.operating.radial_load_N == 100.0
    assert value(case, CH_RADIAL_LOAD, 0.0499999) == 100.0
    assert value(case, CH_RADIAL_LOAD, 0.05) == 800.0  # right-continuous
    assert case.histories["operating.radial_load_N"].times == (0.05, 0.05)


def test_sine_in_the_keys_unit(valid):
    sine = {"sine": {"mean": 300.0, "amplitude": 100.0, "frequency_Hz": 50.0, "phase_deg": 30.0}}
    case = case_of(history_case(valid, radial_load_N=sine))
    for t in (0.0, 0.003, 0.0117):
        expected = 300.0 + 100.0 * math.sin(2 * math.pi * 50.0 * t + math.radians(30.0))
        assert value(case, CH_RADIAL_LOAD, t) == pytest.approx(expected, rel=1e-12)
    assert case.operating.radial_load_N == pytest.approx(350.0)  # 300 + 100 sin 30 deg


def test_table_interpolates_linearly_and_holds_its_ends(valid):
    table = {"table": [[0.1, 100.0], [0.2, 300.0], [0.2, 500.0], [0.4, 100.0]]}
    case = case_of(history_case(valid, axial_load_N=table))
    expected = {0.0: 100.0, 0.15: 200.0, 0.1999: 299.8, 0.2: 500.0, 0.3: 300.0, 0.6: 100.0}
    for t, v in expected.items():
        assert value(case, CH_AXIAL_LOAD, t) == pytest.approx(v), t


def test_history_file_is_read_beside_the_case(valid, tmp_path):
    (tmp_path / "spectrum.csv").write_text(
        "time_s,radial_load_N,other\n0,0,1\n0.1,200,1\n0.2,200,1\n", encoding="utf-8"
    )
    data = history_case(valid, radial_load_N={"file": "spectrum.csv"})
    case = case_of(data, tmp_path)
    history = case.histories["operating.radial_load_N"]
    assert history.times == (0.0, 0.1, 0.2) and history.values == (0.0, 200.0, 200.0)
    assert value(case, CH_RADIAL_LOAD, 0.05) == pytest.approx(100.0)
    # another column by name
    (tmp_path / "two.csv").write_text("load,time_s\n50,0\n70,1\n", encoding="utf-8")
    data = history_case(valid, axial_load_N={"file": "two.csv", "column": "load"})
    assert value(case_of(data, tmp_path), CH_AXIAL_LOAD, 0.5) == pytest.approx(60.0)


def test_load_turning_with_the_shaft(valid):
    angle = {"rotating": "with_shaft", "start_deg": 30.0}
    case = case_of(history_case(valid, radial_load_angle_deg=angle))
    inputs = to_inputs(case)
    assert inputs.history.radial_load_frame == FRAME_INNER_RING
    assert value(case, CH_RADIAL_LOAD_ANGLE, 0.3) == pytest.approx(math.radians(30.0))
    # the load's azimuth in space: the start plus the shaft's angle (20 000 rpm for 1.01 ms)
    t = 1.01e-3
    turned = math.radians(30.0) + 20000.0 * RPM * t
    assert operating_at(inputs, t).radial_load_angle == pytest.approx(turned % (2 * math.pi))


def test_load_turning_in_space_at_its_own_speed(valid):
    angle = {"rotating_rpm": 600.0, "start_deg": -90.0}
    case = case_of(history_case(valid, radial_load_angle_deg=angle))
    inputs = to_inputs(case)
    assert inputs.history.radial_load_frame == FRAME_SPACE
    assert inputs.history.rate[CH_RADIAL_LOAD_ANGLE] == pytest.approx(600.0 * RPM)
    # 0.0125 s at 10 rev/s: an eighth of a turn past -90 deg
    assert math.degrees(operating_at(inputs, 0.0125).radial_load_angle) == pytest.approx(315.0)


def test_operating_at_a_time_takes_every_channel(valid):
    step = {"step": {"from": 100.0, "to": 800.0, "at_s": 0.05}}
    inputs = to_inputs(case_of(history_case(valid, inner_ring_speed_rpm=RAMP, radial_load_N=step)))
    op = operating_at(inputs, 0.3)
    assert op.inner_ring_speed == pytest.approx(10000.0 * RPM)
    assert op.radial_load == 800.0 and op.axial_load == 500.0
    with pytest.raises(ValueError, match=">= 0"):
        operating_at(inputs, -1.0)


def test_steady_case_has_no_history_and_runs_in_revolutions(valid):
    inputs = to_inputs(case_of(valid))
    assert inputs.history is None
    assert inputs.simulation.duration is None and inputs.simulation.samples_per_second is None
    assert inputs.simulation.shaft_revolutions == 10.0
    assert operating_at(inputs, 5.0) is inputs.operating


def test_history_case_runs_for_its_duration(valid):
    case = case_of(history_case(valid, {"duration_s": 0.6}, inner_ring_speed_rpm=RAMP))
    sim = to_inputs(case).simulation
    assert sim.duration == 0.6 and sim.shaft_revolutions is None
    # estimated: 180 samples per revolution at the top speed, 20 000 rpm
    assert sim.samples_per_second == 180 * 20000.0 / 60.0
    assert "simulation.samples_per_second" in case.estimated
    slow = case_of(history_case(valid, radial_load_N={"step": {"from": 0, "to": 1, "at_s": 0}}))
    assert slow.simulation.samples_per_second == 180 * 20000.0 / 60.0
    rest = {"ramp": {"from": 0.0, "to": 100.0, "duration_s": 1.0}}
    assert case_of(
        history_case(valid, inner_ring_speed_rpm=rest)
    ).simulation.samples_per_second == (
        1000.0  # the floor of the estimate
    )


def test_channel_integral_matches_quadrature(valid):
    sine = {"sine": {"mean": 1000.0, "amplitude": 300.0, "frequency_Hz": 7.0, "phase_deg": 40.0}}
    for form in (RAMP, dict(RAMP, interpolation="smooth"), sine):
        record = to_inputs(case_of(history_case(valid, inner_ring_speed_rpm=form))).history
        for t in (0.05, 0.27, 0.5, 0.8):
            grid = np.linspace(0.0, t, 20001)
            samples = [channel_value(record, CH_INNER_SPEED, x) for x in grid]
            quad = np.trapezoid(samples, grid)
            assert channel_integral(record, CH_INNER_SPEED, t) == pytest.approx(quad, rel=1e-6)


# ---- written back, and in the fingerprint -------------------------------------------------
def test_history_case_round_trips(valid, tmp_path):
    (tmp_path / "s.csv").write_text("time_s,radial_load_N\n0,0\n0.5,300\n", encoding="utf-8")
    data = history_case(
        valid,
        inner_ring_speed_rpm=dict(RAMP, interpolation="smooth"),
        radial_load_N={"file": "s.csv"},
        radial_load_angle_deg={"rotating": "with_shaft"},
        axial_load_N={"sine": {"mean": 500.0, "amplitude": 50.0, "frequency_Hz": 10.0}},
    )
    case = case_of(data, tmp_path)
    assert parse_case(case.to_toml(), "text", tmp_path) == case
    assert Case.from_dict(case.to_dict(), tmp_path) == case
    assert "shaft_revolutions" not in case.to_dict().get("simulation", {})
    # a result's text needs no other file: the file's points written inline, solving the same
    inline = parse_case(case.to_toml(inline_files=True))
    assert inline.histories["operating.radial_load_N"].form == "table"
    assert result_fingerprint(inline, "dynamic") == result_fingerprint(case, "dynamic")


def test_fingerprint_follows_the_history(valid, tmp_path):
    base = case_of(history_case(valid, inner_ring_speed_rpm=RAMP))
    longer = copy.deepcopy(RAMP)
    longer["ramp"]["duration_s"] = 0.5
    changed = case_of(history_case(valid, inner_ring_speed_rpm=longer))
    assert result_fingerprint(base, "dynamic") != result_fingerprint(changed, "dynamic")
    csv = tmp_path / "s.csv"
    csv.write_text("time_s,radial_load_N\n0,0\n0.5,300\n", encoding="utf-8")
    data = history_case(valid, radial_load_N={"file": "s.csv"})
    before = result_fingerprint(case_of(data, tmp_path), "dynamic")
    csv.write_text("time_s,radial_load_N\n0,0\n0.5,350\n", encoding="utf-8")
    assert result_fingerprint(case_of(data, tmp_path), "dynamic") != before
    # a steady case's values hold no key of a history case
    assert not {"simulation.duration_s", "histories"} & set(case_values(case_of(valid)))


# ---- every mistake named ------------------------------------------------------------------
def _only(problems, key):
    assert key in problems, problems
    (message,) = problems[key]
    return message


def test_non_monotonic_table(valid):
    table = {"table": [[0, 100], [0.2, 300], [0.1, 200]]}
    message = _only(
        problems_of(history_case(valid, radial_load_N=table)), "operating.radial_load_N"
    )
    assert "must not decrease" in message and "point 3" in message and "sort" in message


def test_unknown_form_key_suggests_the_right_one(valid):
    ramp = {"ramp": {"from": 0, "to": 1, "duration_s": 1}, "interpolaton": "smooth"}
    problems = problems_of(history_case(valid, radial_load_N=ramp))
    message = _only(problems, "operating.radial_load_N.interpolaton")
    assert "did you mean operating.radial_load_N.interpolation" in message
    bad = {"ramp": {"from": 0, "to": 1, "duration": 1}}
    problems = problems_of(history_case(valid, radial_load_N=bad))
    assert "operating.radial_load_N.ramp.duration" in problems


def test_no_form_or_two_forms(valid):
    both = {"step": {"from": 0, "to": 1, "at_s": 0.1}, "sine": {}}
    message = _only(problems_of(history_case(valid, radial_load_N=both)), "operating.radial_load_N")
    assert "exactly one of" in message and "step and sine" in message
    message = _only(
        problems_of(history_case(valid, radial_load_N={"rotating": "with_shaft"})),
        "operating.radial_load_N",
    )
    assert "radial_load_angle_deg only" in message


def test_negative_duration_and_times(valid):
    ramp = {"ramp": {"from": 0, "to": 1, "duration_s": -0.5}}
    problems = problems_of(history_case(valid, radial_load_N=ramp))
    assert "must be greater than 0" in _only(problems, "operating.radial_load_N.ramp.duration_s")
    step = {"step": {"from": 0, "to": 1, "at_s": -1}}
    problems = problems_of(history_case(valid, radial_load_N=step))
    assert "times start at 0" in _only(problems, "operating.radial_load_N.step.at_s")


def test_values_outside_the_keys_bounds_anywhere(valid):
    table = {"table": [[0, 100], [0.2, -50]]}
    message = _only(
        problems_of(history_case(valid, radial_load_N=table)), "operating.radial_load_N"
    )
    assert "at t = 0.2 s is -50 N" in message and "at least 0 N at every time" in message
    sine = {"sine": {"mean": 100.0, "amplitude": 150.0, "frequency_Hz": 5.0}}
    message = _only(problems_of(history_case(valid, axial_load_N=sine)), "operating.axial_load_N")
    assert "the sine reaches -50 N (mean - amplitude)" in message
    fast = {"ramp": {"from": 0, "to": 600000, "duration_s": 1}}
    message = _only(
        problems_of(history_case(valid, inner_ring_speed_rpm=fast)),
        "operating.inner_ring_speed_rpm",
    )
    assert "at most 500000 rpm" in message


def test_loads_both_zero_at_a_knot(valid):
    data = history_case(
        valid,
        axial_load_N={"table": [[0, 500], [0.1, 0]]},
        radial_load_N={"step": {"from": 300, "to": 0, "at_s": 0.1}},
    )
    message = _only(problems_of(data), "operating.axial_load_N")
    assert "at t = 0.1 s the axial and the radial load are both 0" in message


def test_history_file_problems(valid, tmp_path):
    data = history_case(valid, radial_load_N={"file": "missing.csv"})
    with pytest.raises(Exception) as info:
        validate(data, tmp_path)
    assert "file not found" in str(info.value) and "operating.radial_load_N.file" in str(info.value)
    (tmp_path / "a.csv").write_text("time_s,load\n0,1\n", encoding="utf-8")
    data = history_case(valid, radial_load_N={"file": "a.csv"})
    with pytest.raises(Exception, match="no column 'radial_load_N' in the header row"):
        validate(data, tmp_path)
    (tmp_path / "b.csv").write_text("time_s,radial_load_N\n0,1\n0.1,x\n", encoding="utf-8")
    data = history_case(valid, radial_load_N={"file": "b.csv"})
    with pytest.raises(Exception, match="row 3, column radial_load_N: 'x' is not a finite number"):
        validate(data, tmp_path)
    # text without a folder cannot name a file
    data = history_case(valid, radial_load_N={"file": "a.csv"})
    problems = problems_of(data)
    message = _only(problems, "operating.radial_load_N.file")
    assert "not read from a file" in message and "table = " in message
    assert set(problems) == {"operating.radial_load_N.file"}  # one mistake, one message


def test_run_length_keys_of_each_kind_of_case(valid):
    data = history_case(valid, {}, radial_load_N={"step": {"from": 0, "to": 1, "at_s": 0.1}})
    assert "simulation.duration_s is missing" in _only(problems_of(data), "simulation.duration_s")
    data["simulation"] = {"duration_s": 0.2, "shaft_revolutions": 5.0}
    message = _only(problems_of(data), "simulation.shaft_revolutions")
    assert "read only by a steady case" in message and "give simulation.duration_s" in message
    steady = copy.deepcopy(valid)
    steady["simulation"] = {"duration_s": 0.2}
    message = _only(problems_of(steady), "simulation.duration_s")
    assert "read only by a case with a time history" in message
    assert "give simulation.shaft_revolutions" in message


def test_rotating_load_speed_within_the_ring_speed_bounds(valid):
    angle = {"rotating_rpm": 600001.0}
    problems = problems_of(history_case(valid, radial_load_angle_deg=angle))
    assert "within ±500000 rpm" in _only(problems, "operating.radial_load_angle_deg.rotating_rpm")
    bad = {"rotating": "with_case"}
    problems = problems_of(history_case(valid, radial_load_angle_deg=bad))
    assert 'must be "with_shaft"' in _only(problems, "operating.radial_load_angle_deg.rotating")


def test_dynamic_problems_of_a_history_case(valid):
    from solver.case import dynamic_problems

    # a start from rest is a run: no rule on equal speeds at t = 0
    case = case_of(history_case(valid, inner_ring_speed_rpm=RAMP))
    assert dynamic_problems(case) == []
    still = {"table": [[0, 0], [1, 0]]}
    (problem,) = dynamic_problems(case_of(history_case(valid, inner_ring_speed_rpm=still)))
    assert "equal at every point of their histories" in problem.message
    # the run length: duration x samples per second x balls within the memory limit
    long = case_of(
        history_case(
            valid, {"duration_s": 100.0, "samples_per_second": 1e6}, inner_ring_speed_rpm=RAMP
        )
    )
    (problem,) = dynamic_problems(long)
    assert problem.key == "simulation.duration_s" and "ball-samples" in problem.message


# ---- the examples of docs/case-format.md ----------------------------------------------------
DOC = __import__("pathlib").Path(__file__).resolve().parents[3] / "docs" / "case-format.md"
#: The history forms docs/case-format.md must show with an example, and how to tell one.
FORMS = {
    "ramp": "ramp",
    "step": "step",
    "sine": "sine",
    "rotating with the shaft": "rotating =",
    "rotating at a speed": "rotating_rpm",
    "table inline": "table =",
    "table from a CSV file": "file =",
}


def _history_examples() -> list[str]:
    """The ```toml blocks of the doc's "Time histories" section."""
    import re

    doc = DOC.read_text(encoding="utf-8")
    section = doc.split("## Time histories", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```toml\n(.*?)```", section, flags=re.S)


def test_the_doc_shows_each_history_form_with_an_example():
    examples = _history_examples()
    missing = [form for form, mark in FORMS.items() if not any(mark in e for e in examples)]
    assert not missing, f"docs/case-format.md has no example of: {missing}"
    assert "```text\ntime_s," in DOC.read_text(encoding="utf-8")  # the CSV file itself


@pytest.mark.parametrize("index", range(len(FORMS)))
def test_every_history_example_of_the_doc_parses(valid, tmp_path, index):
    """Each example, put into the [operating] table of a valid case (the CSV example beside it,
    as the doc shows it), reads into a history case."""
    import re
    import tomllib

    examples = _history_examples()
    assert len(examples) == len(FORMS)
    keys = tomllib.loads(examples[index])
    doc = DOC.read_text(encoding="utf-8")
    (csv,) = re.findall(r"```text\n(time_s,.*?)```", doc, flags=re.S)
    (tmp_path / "spectrum.csv").write_text(csv, encoding="utf-8")
    data = history_case(valid, **keys)
    data["operating"].setdefault("axial_load_N", 300.0)
    case = Case.from_dict(data, tmp_path)
    assert set(case.histories) & {f"operating.{k}" for k in keys}, examples[index]
