"""The [set] table of a case (docs/case-format.md, "Bearing sets"): arrangements, positions,
preload, loads, and the errors that name what is wrong."""

from __future__ import annotations

import pytest

from solver import CaseError, dynamic_problems, parse_case
from solver.case.bearing_set import ARRANGEMENTS

HEAD = """title = "set"
[bearing]
ball_count = 18
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 15.0
ball_material = "bearing_steel"
ring_material = "bearing_steel"
[operating]
inner_ring_speed_rpm = 10000.0
"""


def case(set_text: str, head: str = HEAD):
    return parse_case(head + set_text)


def messages(set_text: str, head: str = HEAD) -> str:
    with pytest.raises(CaseError) as info:
        case(set_text, head)
    return str(info.value)


def test_a_single_bearing_case_has_no_set():
    single = parse_case(HEAD.replace("10000.0\n", "10000.0\naxial_load_N = 100.0\n"))
    assert single.bearing_set is None


@pytest.mark.parametrize("name", sorted(ARRANGEMENTS))
def test_arrangements_place_their_bearings_along_the_shaft(name):
    c = case(f'[set]\narrangement = "{name}"\nwidth_mm = 15.0\nspacing_mm = 20.0\n')
    s = c.bearing_set
    assert s.directions == ARRANGEMENTS[name]
    assert [b.position_mm for b in s.bearings] == [20.0 * i for i in range(len(s.bearings))]
    assert c.to_dict()["set"]["arrangement"] == name
    assert parse_case(c.to_toml()) == c


def test_back_to_back_and_face_to_face_are_mirror_images():
    assert ARRANGEMENTS["DB"] == ("+x", "-x") and ARRANGEMENTS["DF"] == ("-x", "+x")
    assert ARRANGEMENTS["QBC"] == ("+x", "+x", "-x", "-x")


def test_explicit_bearings_with_a_catalogue_and_an_inline_bearing():
    c = case(
        """[set]
width_mm = 15.0
[set.preload]
kind = "spring"
force_N = 120.0
spring_side = "-x"
[set.load]
position_mm = -50.0
force_N = [-100.0, 200.0, 0.0]
moment_Nm = [0.0, 3.0]
[[set.bearing]]
name = "front"
position_mm = 0.0
direction = "+x"
catalogue = "7008C-hybrid-spindle"
[[set.bearing]]
name = "rear"
position_mm = 120.0
direction = "-x"
[set.bearing.bearing]
ball_count = 16
ball_diameter_mm = 7.144
pitch_diameter_mm = 54.0
inner_groove_radius_ratio = 0.54
outer_groove_radius_ratio = 0.53
free_contact_angle_deg = 25.0
ball_material = "bearing_steel"
ring_material = "bearing_steel"
"""
    )
    s = c.bearing_set
    front, rear = s.bearings
    assert (front.name, front.source, front.case.bearing.ball_material) == (
        "front",
        "catalogue 7008C-hybrid-spindle",
        "silicon_nitride",
    )
    assert (rear.source, rear.case.bearing.ball_count) == ("inline", 16)
    assert s.load_force_N == (-100.0, 200.0, 0.0) and s.load_moment_Nm == (0.0, 3.0)
    assert (s.preload_kind, s.preload_force_N, s.spring_side) == ("spring", 120.0, "-x")
    assert parse_case(c.to_toml()) == c


@pytest.mark.parametrize(
    ("set_text", "key_text"),
    [
        ('[set]\narrangement = "DX"\nwidth_mm = 15.0\n', "unknown arrangement"),
        ('[set]\narrangement = "DB"\nwidth_mm = 15.0\nspacing_mm = 10.0\n', "overlap"),
        (
            '[set]\narrangement = "DT"\nwidth_mm = 15.0\n[set.load]\nforce_N = [-50.0, 0, 0]\n',
            "no bearing of the set carries thrust towards -x",
        ),
        (
            '[set]\narrangement = "DT"\nwidth_mm = 15.0\n[set.preload]\nkind = "force"\n'
            "force_N = 100.0\n",
            "needs bearings facing both ways",
        ),
        ('[set]\narrangement = "DB"\n', "set.width_mm is missing"),
        (
            '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[set.preload]\nkind = "force"\n',
            "set.preload.force_N is missing",
        ),
        (
            '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[set.preload]\nkind = "offset"\n'
            "offset_um = 5.0\nforce_N = 3.0\n",
            "set.preload.force_N is not read",
        ),
        ('[set]\narrangement = "DB"\nwidth_mm = 15.0\nspeed = 3\n', "unknown key set.speed"),
        (
            '[set]\nwidth_mm = 15.0\n[[set.bearing]]\ndirection = "+x"\nposition_mm = 0.0\n'
            '[[set.bearing]]\ndirection = "up"\nposition_mm = 20.0\n',
            'set.bearing[2].direction = \'up\': give "+x" or "-x"',
        ),
        (
            '[set]\nwidth_mm = 15.0\n[[set.bearing]]\ndirection = "+x"\n'
            '[[set.bearing]]\ndirection = "-x"\n',
            "set.bearing[1].position_mm is missing",
        ),
        (
            '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[[set.bearing]]\n'
            'catalogue = "7008C-hybrid-spindel"\n[[set.bearing]]\n',
            "did you mean 7008C-hybrid-spindle",
        ),
        (
            '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[[set.bearing]]\n'
            "bearing = { ball_count = 2 }\n[[set.bearing]]\n",
            "set.bearing[1] (inline)",
        ),
        (
            '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[set.load]\nforce_N = [1.0, 2.0]\n',
            "set.load.force_N = [1.0, 2.0]: give 3 numbers",
        ),
    ],
)
def test_errors_name_what_is_wrong(set_text, key_text):
    assert key_text in messages(set_text)


def test_operating_loads_are_refused_in_a_set_case():
    head = HEAD.replace("10000.0\n", "10000.0\naxial_load_N = 100.0\n")
    text = messages('[set]\narrangement = "DB"\nwidth_mm = 15.0\n', head)
    assert "operating.axial_load_N is not read for a bearing set" in text


def test_a_set_without_external_load_is_valid_and_the_dynamic_model_runs_it():
    c = case(
        '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[set.preload]\nkind = "offset"\n'
        "offset_um = 10.0\n"
    )
    assert c.bearing_set.preload_offset_um == 10.0
    assert dynamic_problems(c) == []


def test_the_sets_dynamic_model_runs_a_spring_preload():
    c = case(
        '[set]\narrangement = "DB"\nwidth_mm = 15.0\n[set.preload]\nkind = "spring"\n'
        'force_N = 200.0\nspring_side = "-x"\n'
    )
    assert dynamic_problems(c) == []


def test_the_sets_dynamic_run_length_counts_the_balls_of_every_bearing():
    from solver import dynamic_ball_count
    from solver.case.validate import MAX_DYNAMIC_BALL_SAMPLES

    four = case('[set]\narrangement = "QBC"\nwidth_mm = 15.0\n')
    assert dynamic_ball_count(four) == 4 * 18
    # a run that one bearing's 18 balls could keep, but not the set's 72
    samples = MAX_DYNAMIC_BALL_SAMPLES // 36
    long = four.with_values(
        {"simulation.shaft_revolutions": samples / 100, "simulation.samples_per_revolution": 100}
    )
    (problem,) = dynamic_problems(long)
    assert problem.key == "simulation.shaft_revolutions" and "72 balls" in problem.message


def test_the_sets_dynamic_model_needs_the_rings_to_turn():
    still = case(
        '[set]\narrangement = "DB"\nwidth_mm = 15.0\n',
        HEAD.replace("10000.0\n", "0.0\n"),
    )
    (problem,) = dynamic_problems(still)
    assert problem.key == "operating.inner_ring_speed_rpm"
    assert "bearing set" in problem.message and "history" not in problem.message


def test_a_set_with_a_time_history_is_refused_with_the_key_named():
    head = HEAD.replace(
        "inner_ring_speed_rpm = 10000.0\n",
        "inner_ring_speed_rpm = { ramp = { from = 0, to = 10000, start_s = 0, duration_s = 0.1 } }"
        "\n[simulation]\nduration_s = 0.2\n",
    )
    text = messages('[set]\narrangement = "DB"\nwidth_mm = 15.0\n', head)
    assert "operating.inner_ring_speed_rpm" in text and "not modelled for sets" in text
