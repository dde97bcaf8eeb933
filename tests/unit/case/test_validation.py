"""Validation messages: one test per class of error, asserting the key and what the message says.

Every message must name its key and the offending value; these tests also check the substance
(what is allowed, and why) so that a vague message fails.
"""

from __future__ import annotations

import copy
import math

import pytest

from solver.case import Case, parse_case

DELETE = object()


def edit(data: dict, changes: dict) -> dict:
    """Apply {"section.key": value} to a nested dict (DELETE removes the key)."""
    for dotted, value in changes.items():
        parts = dotted.split(".")
        node = data
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        if value is DELETE:
            node.pop(parts[-1], None)
        else:
            node[parts[-1]] = value
    return data


# (changes, key of the expected problem, substrings that message must contain)
CASES = [
    (
        {"bearing.inner_groove_radius_ratio": 0.49},
        "bearing.inner_groove_radius_ratio",
        ["= 0.49", "at least 0.501", "cannot hold it"],
    ),
    (
        {"bearing.outer_groove_radius_ratio": 0.5},
        "bearing.outer_groove_radius_ratio",
        ["= 0.5:", "at least 0.501"],
    ),
    ({"bearing.ball_diameter_mm": DELETE}, "bearing.ball_diameter_mm", ["is missing", "mm"]),
    ({"operating.inner_ring_speed_rpm": DELETE}, "operating.inner_ring_speed_rpm", ["is missing"]),
    (
        {"bearing.ball_diameter_mm": "seven"},
        "bearing.ball_diameter_mm",
        ['"seven"', "must be a number", "text"],
    ),
    ({"bearing.ball_diameter_mm": float("nan")}, "bearing.ball_diameter_mm", ["nan", "finite"]),
    (
        {"operating.inner_ring_speed_rpm": float("inf")},
        "operating.inner_ring_speed_rpm",
        ["inf", "finite"],
    ),
    (
        {"operating.outer_ring_speed_rpm": -float("inf")},
        "operating.outer_ring_speed_rpm",
        ["-inf", "finite"],
    ),
    ({"operating.axial_load_N": True}, "operating.axial_load_N", ["true", "must be a number"]),
    (
        {"bearing.diametral_clearance_mm": 0.02},
        "bearing.free_contact_angle_deg",
        ["free_contact_angle_deg = 15", "diametral_clearance_mm = 0.02", "exactly one"],
    ),
    (
        {"bearing.free_contact_angle_deg": DELETE},
        "bearing.free_contact_angle_deg",
        ["diametral_clearance_mm", "exactly one"],
    ),
    (
        {"operating.misalignment_deg": 0.05, "operating.tilting_moment_Nm": 2.0},
        "operating.tilting_moment_Nm",
        ["misalignment_deg = 0.05", "tilting_moment_Nm = 2", "at most one"],
    ),
    (
        {"bearing.pitch_diameter_mm": 7.0},
        "bearing.pitch_diameter_mm",
        ["= 7:", "larger than the ball diameter", "7.144"],
    ),
    (
        {"bearing.free_contact_angle_deg": 60.0},
        "bearing.free_contact_angle_deg",
        ["= 60:", "less than 60"],
    ),
    (
        {"bearing.free_contact_angle_deg": -1.0},
        "bearing.free_contact_angle_deg",
        ["= -1:", "at least 0"],
    ),
    (
        {"bearing.free_contact_angle_deg": DELETE, "bearing.diametral_clearance_mm": -0.01},
        "bearing.diametral_clearance_mm",
        ["= -0.01", "at least 0", "preload"],
    ),
    (
        {"bearing.free_contact_angle_deg": DELETE, "bearing.diametral_clearance_mm": 0.6},
        "bearing.diametral_clearance_mm",
        ["= 0.6", "less than 0.5001 mm", "60 degrees"],
    ),
    (
        {"bearing.ball_material": "steel"},
        "bearing.ball_material",
        ['"steel"', "unknown material", "bearing_steel", "silicon_nitride", "[materials.NAME]"],
    ),
    (
        {
            "bearing.ring_material": {
                "youngs_modulus_GPa": 0.0,
                "poisson_ratio": 0.3,
                "density_kg_m3": 7800.0,
            }
        },
        "bearing.ring_material.youngs_modulus_GPa",
        ["= 0:", "greater than 0"],
    ),
    (
        {
            "bearing.ring_material": {
                "youngs_modulus_GPa": 200.0,
                "poisson_ratio": 0.5,
                "density_kg_m3": 7800.0,
            }
        },
        "bearing.ring_material.poisson_ratio",
        ["= 0.5:", "less than 0.5"],
    ),
    (
        {
            "bearing.ring_material": {
                "youngs_modulus_GPa": 200.0,
                "poisson_ratio": -0.1,
                "density_kg_m3": 7800.0,
            }
        },
        "bearing.ring_material.poisson_ratio",
        ["= -0.1", "at least 0"],
    ),
    (
        {
            "bearing.ring_material": {
                "youngs_modulus_GPa": 200.0,
                "poisson_ratio": 0.3,
                "density_kg_m3": -1.0,
            }
        },
        "bearing.ring_material.density_kg_m3",
        ["= -1", "greater than 0"],
    ),
    (
        {"bearing.ring_material": {"youngs_modulus_GPa": 200.0, "poisson_ratio": 0.3}},
        "bearing.ring_material.density_kg_m3",
        ["is missing"],
    ),
    (
        {
            "materials.m50": {
                "youngs_modulus_GPa": 200.0,
                "poisson_ratio": 0.3,
                "density_kg_m3": 0.0,
            },
            "bearing.ring_material": "m50",
        },
        "materials.m50.density_kg_m3",
        ["= 0:", "greater than 0"],
    ),
    (
        {"operating.axial_load_N": -100.0},
        "operating.axial_load_N",
        ["= -100", "at least 0", "only in +x"],
    ),
    (
        {"operating.radial_load_N": -1.0},
        "operating.radial_load_N",
        ["= -1", "at least 0", "radial_load_angle_deg"],
    ),
    (
        {"operating.axial_load_N": 0.0, "operating.radial_load_N": 0.0},
        "operating.axial_load_N",
        ["nothing holds the balls"],
    ),
    (
        {"operating.axial_load_N": DELETE, "operating.radial_load_N": DELETE},
        "operating.axial_load_N",
        ["nothing holds the balls"],
    ),
    ({"bearing.ball_count": 2}, "bearing.ball_count", ["= 2:", "at least 3"]),
    ({"bearing.ball_count": 18.5}, "bearing.ball_count", ["= 18.5", "whole number"]),
    ({"bearing.ball_count": "18"}, "bearing.ball_count", ['"18"', "without quotes"]),
    (
        {"simulation.samples_per_revolution": 2},
        "simulation.samples_per_revolution",
        ["= 2:", "at least 8"],
    ),
    (
        {"simulation.shaft_revolutions": 0.0},
        "simulation.shaft_revolutions",
        ["= 0:", "greater than 0"],
    ),
    (
        {"simulation.shaft_revolutions": 1e6},
        "simulation.shaft_revolutions",
        ["= 1000000", "at most 1000"],
    ),
    (
        {"operating.misalignment_frame": "wall"},
        "operating.misalignment_frame",
        ['"wall"', '"space"', '"ring"'],
    ),
    (
        {"cage.guidance": "outer"},
        "cage.guidance",
        ['"outer"', '"outer_ring"', '"inner_ring"', '"ball"', "did you mean"],
    ),
    (
        {"cage.pocket_diametral_clearance_mm": 0.0},
        "cage.pocket_diametral_clearance_mm",
        ["= 0:", "at least 0.001"],
    ),
    (
        {"cage.guide_diametral_clearance_mm": -0.1},
        "cage.guide_diametral_clearance_mm",
        ["= -0.1", "at least 0.001"],
    ),
    ({"cage.mass_g": 0.0}, "cage.mass_g", ["= 0:", "at least 1e-09"]),
    ({"lubricant.viscosity_Pas": 0.0}, "lubricant.viscosity_Pas", ["= 0:", "greater than 0"]),
    (
        {"lubricant.pressure_viscosity_per_GPa": -5.0},
        "lubricant.pressure_viscosity_per_GPa",
        ["= -5", "greater than 0"],
    ),
    (
        {"lubricant.traction": {"mu_zero": 0.06, "mu_max": 0.05}},
        "lubricant.traction.mu_zero",
        ["= 0.06", "at most mu_max = 0.05"],
    ),
    (
        {"lubricant.traction": {"mu_max": 0.05, "mu_infinity": 0.07}},
        "lubricant.traction.mu_infinity",
        ["= 0.07", "at most mu_max = 0.05"],
    ),
    (
        {"lubricant.traction": {"mu_infinity": 0.0}},
        "lubricant.traction.mu_infinity",
        ["= 0:", "greater than 0"],
    ),
    (
        {"lubricant.traction": {"slip_at_max_m_s": 0.0}},
        "lubricant.traction.slip_at_max_m_s",
        ["= 0:", "greater than 0"],
    ),
    ({"lubricant.traction": 0.05}, "lubricant.traction", ["= 0.05", "inline table", "mu_max"]),
]


@pytest.mark.parametrize(
    ("changes", "key", "expected"), CASES, ids=[f"{c[1]}-{i}" for i, c in enumerate(CASES)]
)
def test_rejected_with_message(valid, problems, changes, key, expected):
    found = problems(edit(valid, changes))
    assert key in found, f"no problem for {key}; got {found}"
    message = " | ".join(found[key])
    assert key.split(".")[-1] in message  # the message names its key
    for text in expected:
        assert text in message, f"{text!r} not in {message!r}"


def test_example_message_from_the_contract(valid, problems):
    """The exact wording given in case-format.md."""
    found = problems(edit(valid, {"bearing.inner_groove_radius_ratio": 0.49}))
    assert found["bearing.inner_groove_radius_ratio"] == [
        "bearing.inner_groove_radius_ratio = 0.49: must be at least 0.501 (a groove tighter "
        "than the ball cannot hold it, and a closer fit than 0.501 is no longer a Hertz point "
        "contact; grooves are made from about 0.505)"
    ]


def test_all_problems_are_listed_at_once(valid, problems):
    found = problems(
        edit(
            valid,
            {
                "bearing.ball_count": 2,
                "bearing.ball_diamter_mm": 7.0,
                "operating.axial_load_N": -1.0,
                "cage.guidance": "none",
                "bearing.ring_material": "unobtainium",
            },
        )
    )
    assert {
        "bearing.ball_count",
        "bearing.ball_diamter_mm",
        "operating.axial_load_N",
        "cage.guidance",
        "bearing.ring_material",
    } <= set(found)


@pytest.mark.parametrize(
    ("changes", "key", "suggestion"),
    [
        ({"bearing.ball_diamter_mm": 7.0}, "bearing.ball_diamter_mm", "bearing.ball_diameter_mm"),
        ({"operating.axial_load": 7.0}, "operating.axial_load", "operating.axial_load_N"),
        (
            {"lubricant.traction": {"mu_maximum": 0.05}},
            "lubricant.traction.mu_maximum",
            "lubricant.traction.mu_max",
        ),
        (
            {
                "materials.x": {
                    "youngs_modulus": 200.0,
                    "poisson_ratio": 0.3,
                    "density_kg_m3": 7800.0,
                }
            },
            "materials.x.youngs_modulus",
            "materials.x.youngs_modulus_GPa",
        ),
        ({"titel": "x"}, "titel", "title"),
    ],
)
def test_unknown_key_suggests_nearest(valid, problems, changes, key, suggestion):
    found = problems(edit(valid, changes))
    assert key in found
    assert f"did you mean {suggestion}?" in found[key][0]


def test_unknown_section_suggests_nearest(valid, problems):
    valid["operatng"] = valid.pop("operating")
    found = problems(valid)
    assert "did you mean [operating]?" in found["operatng"][0]
    assert "[operating] section is missing" in found["operating"][0]


def test_key_in_wrong_section_names_its_home(valid, problems):
    found = problems(edit(valid, {"bearing.radial_load_N": 10.0}))
    assert "belongs in [operating]" in found["bearing.radial_load_N"][0]


def test_section_given_as_value(valid, problems):
    valid["cage"] = 3
    assert "must be a section" in problems(valid)["cage"][0]


def test_too_many_balls_names_how_many_fit(valid, problems):
    """Z balls fit when d_m sin(pi/Z) > D: the largest Z is the largest integer < pi/asin(D/d_m)."""
    D, dm = 7.144, 54.0
    bound = math.pi / math.asin(D / dm)
    z_max = math.ceil(bound) - 1
    found = problems(edit(valid, {"bearing.ball_count": z_max + 1}))
    message = found["bearing.ball_count"][0]
    assert f"{z_max + 1} balls of diameter 7.144 mm do not fit" in message
    assert f"at most {z_max} fit" in message
    ok = edit(valid, {"bearing.ball_count": z_max})
    assert Case.from_dict(ok).bearing.ball_count == z_max


def test_clearance_just_below_sixty_degrees_is_accepted(valid):
    """alpha_0 = 60 deg at P_d = A_0 = (f_i + f_o - 1) D; just below it the case is valid."""
    a0 = (0.54 + 0.53 - 1.0) * 7.144
    case = Case.from_dict(
        edit(
            valid,
            {
                "bearing.free_contact_angle_deg": DELETE,
                "bearing.diametral_clearance_mm": 0.999 * a0,
            },
        )
    )
    alpha = math.degrees(case.geometry().free_contact_angle)
    assert 59.0 < alpha < 60.0


def test_user_material_cannot_shadow_builtin(valid, problems):
    found = problems(
        edit(
            valid,
            {
                "materials.bearing_steel": {
                    "youngs_modulus_GPa": 1.0,
                    "poisson_ratio": 0.3,
                    "density_kg_m3": 1.0,
                }
            },
        )
    )
    assert "built-in" in found["materials.bearing_steel"][0]


def test_misalignment_or_moment_alone_holds_the_balls(valid):
    base = edit(valid, {"operating.axial_load_N": 0.0, "operating.radial_load_N": 0.0})
    assert Case.from_dict(edit(copy.deepcopy(base), {"operating.misalignment_deg": 0.05}))
    assert Case.from_dict(edit(copy.deepcopy(base), {"operating.tilting_moment_Nm": 1.0}))


def test_integral_float_ball_count_is_accepted_as_int(valid):
    case = Case.from_dict(edit(valid, {"bearing.ball_count": 18.0}))
    assert case.bearing.ball_count == 18 and isinstance(case.bearing.ball_count, int)


def test_not_a_table(problems):
    assert "" in problems([1, 2])


# ---- shoulder (land) diameters -----------------------------------------------------------------
# For the fixture bearing (D = 7.144 mm, d_m = 54 mm, f_i = 0.54, f_o = 0.53, alpha0 = 15 deg), by
# hand: d_i = 54 + 2 (0.04) 7.144 cos 15 - 2 (0.54) 7.144 = 46.84 mm and
# d_o = 54 - 2 (0.03) 7.144 cos 15 + 2 (0.53) 7.144 = 61.16 mm.
@pytest.mark.parametrize(
    ("key", "value", "words"),
    [
        (
            "bearing.inner_shoulder_diameter_mm",
            80.0,
            ["= 80:", "less than the pitch diameter 54 mm", "46.84 mm and 54 mm"],
        ),
        (
            "bearing.inner_shoulder_diameter_mm",
            54.0,
            ["= 54:", "less than the pitch diameter 54 mm"],
        ),
        (
            "bearing.outer_shoulder_diameter_mm",
            54.0,
            ["= 54:", "greater than the pitch diameter 54 mm", "54 mm and the outer", "61.16 mm"],
        ),
        (
            "bearing.outer_shoulder_diameter_mm",
            40.0,
            ["= 40:", "greater than the pitch diameter 54 mm"],
        ),
    ],
)
def test_land_beyond_the_pitch_circle_is_an_error(valid, problems, key, value, words):
    found = problems(edit(valid, {key: value}))
    (message,) = found[key]
    for word in words:
        assert word in message, message


def test_lands_just_inside_the_pitch_circle_are_accepted(valid):
    case = Case.from_dict(
        edit(
            valid,
            {
                "bearing.inner_shoulder_diameter_mm": 53.99,
                "bearing.outer_shoulder_diameter_mm": 54.01,
            },
        )
    )
    assert case.bearing.inner_shoulder_diameter_mm == 53.99


def test_swapped_lands_are_rejected_both(valid, problems):
    """inner land < d_m < outer land, so swapped lands break both bounds."""
    found = problems(
        edit(
            valid,
            {
                "bearing.inner_shoulder_diameter_mm": 58.9,
                "bearing.outer_shoulder_diameter_mm": 49.1,
            },
        )
    )
    assert {"bearing.inner_shoulder_diameter_mm", "bearing.outer_shoulder_diameter_mm"} <= set(
        found
    )


def test_lands_off_their_groove_still_load(valid):
    """The contract example's lands (below / beyond the groove bottoms) load with a warning."""
    case = Case.from_dict(
        edit(
            valid,
            {
                "bearing.inner_shoulder_diameter_mm": 45.9,
                "bearing.outer_shoulder_diameter_mm": 62.2,
                "lubricant.method": "grease",  # named: no warning of an assumed method
            },
        )
    )
    assert {w.key for w in case.warnings()} == {
        "bearing.inner_shoulder_diameter_mm",
        "bearing.outer_shoulder_diameter_mm",
    }


@pytest.mark.parametrize(
    ("lubricant", "warned"),
    [
        ({"traction": {"mu_max": 0.06}}, True),  # rheology by default: the table is not read
        ({"traction_model": "rheology", "traction": {"mu_max": 0.06}}, True),
        ({"traction_model": "slip_curve", "traction": {"mu_max": 0.06}}, False),
        ({"viscosity_Pas": 0.02}, False),  # no table
        (None, False),  # no [lubricant]
    ],
)
def test_traction_table_ignored_by_the_rheology_is_a_warning(valid, lubricant, warned):
    """A traction table the rheology does not read loads, with a warning naming the table and the
    fix; the warning survives saving and loading, and a case without a table never gains one."""
    if lubricant is not None:
        valid["lubricant"] = lubricant
    case = Case.from_dict(valid)
    found = [w for w in case.warnings() if w.key == "lubricant.traction"]
    assert len(found) == int(warned)
    if warned:
        assert 'traction_model = "slip_curve"' in found[0].message
        assert "lubricant.traction_model" in found[0].keys
    for again in (Case.from_dict(case.to_dict()), parse_case(case.to_toml())):
        assert again == case
        assert [w.key for w in again.warnings()].count("lubricant.traction") == int(warned)
    edited = case.with_values({"operating.axial_load_N": 600.0})
    assert [w.key for w in edited.warnings()].count("lubricant.traction") == int(warned)
    assert edited.lubricant.traction == case.lubricant.traction


# ---- rules between keys name every key involved ------------------------------------------------
@pytest.mark.parametrize(
    ("changes", "key", "related"),
    [
        (
            {"bearing.ball_diameter_mm": 60.0},
            "bearing.pitch_diameter_mm",
            {"bearing.ball_diameter_mm"},
        ),
        (
            {"bearing.ball_count": 40},
            "bearing.ball_count",
            {"bearing.ball_diameter_mm", "bearing.pitch_diameter_mm"},
        ),
        (
            {"bearing.diametral_clearance_mm": 0.02},
            "bearing.free_contact_angle_deg",
            {"bearing.diametral_clearance_mm"},
        ),
        (
            {"bearing.free_contact_angle_deg": DELETE, "bearing.diametral_clearance_mm": 0.6},
            "bearing.diametral_clearance_mm",
            {"bearing.inner_groove_radius_ratio", "bearing.outer_groove_radius_ratio"},
        ),
        (
            {"bearing.inner_shoulder_diameter_mm": 80.0},
            "bearing.inner_shoulder_diameter_mm",
            {"bearing.pitch_diameter_mm"},
        ),
        (
            {"operating.misalignment_deg": 0.05, "operating.tilting_moment_Nm": 2.0},
            "operating.tilting_moment_Nm",
            {"operating.misalignment_deg"},
        ),
        (
            {"operating.axial_load_N": 0.0, "operating.radial_load_N": 0.0},
            "operating.axial_load_N",
            {"operating.radial_load_N"},
        ),
        (
            {"lubricant.traction": {"mu_zero": 0.06, "mu_max": 0.05}},
            "lubricant.traction.mu_zero",
            {"lubricant.traction.mu_max"},
        ),
    ],
)
def test_rule_between_keys_names_the_related_keys(valid, changes, key, related):
    from solver.errors import CaseError

    with pytest.raises(CaseError) as info:
        Case.from_dict(edit(valid, changes))
    (problem,) = [p for p in info.value.problems if p.key == key]
    assert related <= set(problem.related_keys)
    for other in related:
        assert problem.message in info.value.for_key(other)


# ---- wording: every limit with its unit, no brackets inside brackets ---------------------------
def _bracket_depth(text: str) -> int:
    """Deepest nesting of (), [] and {} in ``text``."""
    depth = deepest = 0
    for char in text:
        if char in "([{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in ")]}":
            depth -= 1
    return deepest


def _all_messages(valid) -> list[str]:
    """Messages for every bound of every key and for each rule between keys."""
    from solver.case.schema import FIELDS

    from .conftest import problems_of

    edits = []
    for f in FIELDS:
        if f.minimum is not None:
            edits.append({f.key: f.minimum - 1.0})
        if f.maximum is not None:
            edits.append({f.key: f.maximum + 1.0})
        if f.required and f.section in ("bearing", "operating"):
            edits.append({f.key: DELETE})
    edits += [c[0] for c in CASES]
    edits += [
        {"bearing.inner_shoulder_diameter_mm": 80.0, "bearing.outer_shoulder_diameter_mm": 50.0},
        {"bearing.ball_count": 40},
        {"materials": {"x": 3}, "bearing.ball_material": "stel", "cage": 3},
        {"bearing.ball_material": {"youngs_modulus_GPa": 200.0}},
    ]
    messages = []
    for changes in edits:
        for found in problems_of(edit(copy.deepcopy(valid), changes)).values():
            messages += found
    return messages


def test_every_message_has_no_nested_brackets(valid):
    messages = _all_messages(valid)
    assert len(messages) > 60
    nested = [m for m in messages if _bracket_depth(m.replace("{ ", "").replace(" }", "")) > 1]
    assert nested == []


def test_every_bound_states_its_unit(valid, problems):
    from solver.case.schema import FIELDS, format_number

    checked = 0
    for f in FIELDS:
        if not f.unit or f.type not in ("float", "int"):
            continue
        for bound, step in ((f.minimum, -1.0), (f.maximum, 1.0)):
            if bound is None:
                continue
            (message,) = problems(edit(copy.deepcopy(valid), {f.key: bound + step}))[f.key]
            assert f"{format_number(bound)} {f.unit}" in message, message
            checked += 1
    assert checked >= 15


def test_traction_rule_holds_for_the_defaults_of_keys_not_given(valid, problems):
    """mu_max = 0.03 alone: the default mu_infinity (0.036) would exceed the peak."""
    found = problems(edit(copy.deepcopy(valid), {"lubricant.traction": {"mu_max": 0.03}}))
    (message,) = found["lubricant.traction.mu_infinity"]
    assert "mu_infinity = 0.036 (the default)" in message and "mu_max = 0.03" in message
    ok = edit(valid, {"lubricant.traction": {"mu_max": 0.03, "mu_infinity": 0.02}})
    assert Case.from_dict(ok).lubricant.traction.mu_infinity == 0.02


def test_equal_ring_speeds_are_valid_but_not_for_the_dynamic_model(valid):
    from solver.case import dynamic_problems

    case = Case.from_dict(edit(copy.deepcopy(valid), {"operating.outer_ring_speed_rpm": 20000.0}))
    (problem,) = dynamic_problems(case)
    assert problem.key == "operating.inner_ring_speed_rpm"
    assert "operating.outer_ring_speed_rpm" in problem.keys
    assert "turn relative to each other" in problem.message and "20000" in problem.message
    # a bearing at rest or starting from rest runs along a history for a duration
    assert "history" in problem.message and "simulation.duration_s" in problem.message
    assert "simulation.duration_s" in problem.keys
    assert dynamic_problems(Case.from_dict(valid)) == []
    at_rest = Case.from_dict(edit(copy.deepcopy(valid), {"operating.inner_ring_speed_rpm": 0.0}))
    assert dynamic_problems(at_rest)


def test_a_dynamic_run_too_large_for_memory_is_refused_with_the_numbers(valid):
    from solver.case import dynamic_problems
    from solver.case.validate import MAX_DYNAMIC_BALL_SAMPLES

    # 18 balls: 1000 revolutions at 180 samples is 3.24 million ball-samples
    big = edit(copy.deepcopy(valid), {"simulation": {"shaft_revolutions": 1000.0}})
    (problem,) = dynamic_problems(Case.from_dict(big))
    assert problem.key == "simulation.shaft_revolutions"
    assert "180000 samples of 18 balls" in problem.message
    assert "bearing.ball_count" in problem.keys
    limit = MAX_DYNAMIC_BALL_SAMPLES // (18 * 180) * 1.0  # revolutions at the limit
    ok = edit(copy.deepcopy(valid), {"simulation": {"shaft_revolutions": limit}})
    assert dynamic_problems(Case.from_dict(ok)) == []


def test_a_dynamic_run_shorter_than_one_sample_is_refused(valid):
    from solver.case import dynamic_problems
    from solver.case.validate import dynamic_run_size, run_length_problems

    short = edit(copy.deepcopy(valid), {"simulation": {"shaft_revolutions": 1e-9}})
    (problem,) = dynamic_problems(Case.from_dict(short))
    assert problem.key == "simulation.shaft_revolutions"
    assert "before its first output sample" in problem.message and "0.00556" in problem.message
    one = edit(copy.deepcopy(valid), {"simulation": {"shaft_revolutions": 1 / 180}})
    assert dynamic_problems(Case.from_dict(one)) == []
    (named,) = run_length_problems(1e-9, 8, 18, ("--revolutions", "--samples-per-revolution"))
    assert named.message.startswith("--revolutions = 1e-09 at --samples-per-revolution = 8")
    size = dynamic_run_size(1.0, 180, 18)
    assert size.samples == 180 and size.memory_bytes == 181 * 18 * 1_500
