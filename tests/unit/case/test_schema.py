"""FIELDS is the one schema table: check that the parser, the dataclasses, the writer and the docs
agree with it entry by entry."""

from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import tomli_w

from solver.case import FIELDS, MATERIAL_FIELDS, OPTIONAL, REQUIRED, Estimated, parse_case
from solver.case.schema import METHOD_NEEDS, Field
from solver.case.validate import _MISSING, check_value
from solver.case.writer import toml_value

FULL = {
    "cage": {
        "guidance": "ball",
        "pocket_diametral_clearance_mm": 0.2,
        "guide_diametral_clearance_mm": 0.3,
        "mass_g": 5.0,
        "pocket_friction": 0.1,
        "guide_land_width_mm": 3.0,
    },
    "lubricant": {
        "viscosity_Pas": 0.02,
        "pressure_viscosity_per_GPa": 18.0,
        "traction": {"mu_zero": 0.01, "mu_max": 0.06, "slip_at_max_m_s": 2.0, "mu_infinity": 0.04},
    },
    "simulation": {"shaft_revolutions": 3.0, "samples_per_revolution": 90},
}


def _get(obj, path):
    for part in path:
        obj = getattr(obj, part)
    return obj


def test_last_segments_are_unique():
    """The app uses field-<last segment> as element ids."""
    names = [f.name for f in FIELDS]
    assert len(names) == len(set(names))


def test_every_field_is_an_attribute_with_the_written_value(valid):
    data = copy.deepcopy(valid)
    data.update(copy.deepcopy(FULL))
    data["bearing"]["inner_shoulder_diameter_mm"] = 49.0
    data["operating"]["misalignment_deg"] = 0.01
    case = parse_case(tomli_w.dumps(data))
    for f in FIELDS:
        expected = data
        for part in f.path:
            expected = expected.get(part, _MISSING) if isinstance(expected, dict) else _MISSING
        value = _get(case, f.path)
        if expected is not _MISSING:
            assert value == expected, f.key
        elif f.default is OPTIONAL or f.applies == "history":  # a steady case
            assert value is None, f.key
        else:
            assert f.default is not REQUIRED
            assert value == f.default, f.key


@pytest.mark.parametrize("f", [f for f in FIELDS if f.required], ids=lambda f: f.key)
def test_each_required_key_is_required(valid, problems, f):
    data = copy.deepcopy(valid)
    node = data
    for part in f.path[:-1]:
        node = node[part]
    del node[f.name]
    found = problems(data)
    assert f.key in found and "is missing" in found[f.key][0]


@pytest.mark.parametrize(
    "f",
    [f for f in FIELDS + MATERIAL_FIELDS if f.minimum is not None or f.maximum is not None],
    ids=lambda f: f.key,
)
def test_bounds_follow_the_table(f):
    step = 1 if f.type == "int" else 1e-9 * max(1.0, abs(f.minimum or 0), abs(f.maximum or 0))
    for bound, inclusive, outside in (
        (f.minimum, f.minimum_inclusive, -step),
        (f.maximum, f.maximum_inclusive, step),
    ):
        if bound is None:
            continue
        bound = int(bound) if f.type == "int" else float(bound)
        problems = []
        assert check_value(f, f.key, bound + outside, problems) is _MISSING
        assert problems and problems[0].key == f.key
        problems = []
        on_bound = check_value(f, f.key, bound, problems)
        assert (on_bound is not _MISSING) == inclusive, f"{f.key} at {bound}"
        assert (problems == []) == inclusive


@pytest.mark.parametrize(
    "f", [f for f in FIELDS if f.type in ("float", "int")], ids=lambda f: f.key
)
def test_numbers_reject_text_and_non_finite(f):
    for bad in ("1.0", float("nan"), float("inf"), True, [1.0]):
        problems = []
        assert check_value(f, f.key, bad, problems) is _MISSING
        assert problems[0].key == f.key and f.key in problems[0].message


@pytest.mark.parametrize("f", [f for f in FIELDS if f.type == "choice"], ids=lambda f: f.key)
def test_every_choice_is_accepted_and_others_rejected(valid, f):
    case = parse_case(tomli_w.dumps(valid))
    for choice in f.choices:
        # a lubrication method comes with the supply key it needs (docs/lubrication.md)
        need = METHOD_NEEDS.get(choice) if f.key == "lubricant.method" else None
        supply = {f"lubricant.{need}": 1.0} if need else {}
        assert _get(case.with_values({f.key: choice} | supply), f.path) == choice
    problems = []
    assert check_value(f, f.key, "not-a-choice", problems) is _MISSING


def test_plain_defaults_satisfy_their_own_rules():
    for f in FIELDS:
        if f.default in (REQUIRED, OPTIONAL) or isinstance(f.default, Estimated):
            continue
        problems = []
        assert check_value(f, f.key, f.default, problems) == f.default, f.key


def test_estimates_satisfy_their_own_rules(valid):
    case = parse_case(tomli_w.dumps(valid))
    for f in FIELDS:
        if isinstance(f.default, Estimated):
            value = _get(case, f.path)
            if f.default.reads == "history":  # estimated only for a case with a time history
                assert value is None, f.key
                continue
            assert math.isfinite(value) and check_value(f, f.key, value, []) == value, f.key


#: The geometry keys with a physical lower bound: a subnormal or tiny value is refused by the
#: validator, never passed on to the solvers (a 5e-324 mm ball divided by zero there).
GEOMETRY_MINIMA = (
    "bearing.ball_diameter_mm",
    "bearing.pitch_diameter_mm",
    "bearing.inner_groove_radius_ratio",
    "bearing.outer_groove_radius_ratio",
    "bearing.inner_shoulder_diameter_mm",
    "bearing.outer_shoulder_diameter_mm",
    "cage.pocket_diametral_clearance_mm",
    "cage.guide_diametral_clearance_mm",
    "cage.mass_g",
    "cage.guide_land_width_mm",
)


@pytest.mark.parametrize("key", GEOMETRY_MINIMA)
@pytest.mark.parametrize("below", ["subnormal", "tiny", "a thousandth of the minimum"])
def test_geometry_refuses_values_below_its_physical_minimum(valid, problems, key, below):
    from solver.case.schema import field

    minimum = field(key).minimum
    assert minimum is not None and minimum > 0 and field(key).minimum_inclusive, key
    value = {"subnormal": 5e-324, "tiny": 1e-300}.get(below, minimum * 1e-3)
    edited = copy.deepcopy(valid)
    *path, last = key.split(".")
    node = edited
    for part in path:
        node = node.setdefault(part, {})
    node[last] = 0.5 + value if "ratio" in key else value
    (message,) = problems(edited)[key]
    assert "must be at least" in message, message


def test_estimates_satisfy_their_rules_for_the_smallest_bearing_accepted(valid):
    """The estimated cage values stay within their bounds down to the geometry's minima."""
    from solver.case.schema import field

    smallest = copy.deepcopy(valid)
    smallest["bearing"].update(
        ball_count=3,
        ball_diameter_mm=field("bearing.ball_diameter_mm").minimum,
        pitch_diameter_mm=field("bearing.pitch_diameter_mm").minimum,
    )
    case = parse_case(tomli_w.dumps(smallest))
    checked = 0
    for f in FIELDS:
        if isinstance(f.default, Estimated) and f.default.reads == "bearing":
            value = _get(case, f.path)
            assert check_value(f, f.key, value, []) == value, (f.key, value)
            checked += 1
    assert checked >= 4


def test_field_metadata_is_complete():
    for f in FIELDS:
        assert f.type in ("float", "int", "str", "choice", "bool", "material"), f.key
        assert f.label and f.help.endswith("."), f.key
        assert (f.type == "choice") == bool(f.choices), f.key
        assert isinstance(f, Field)


def _default_cell(f) -> str:
    if f.default is REQUIRED:
        return "**required**"
    if f.default is OPTIONAL:
        return "absent"
    if isinstance(f.default, Estimated):
        return f"estimated: {f.default.description}"
    return f"`{toml_value(f.default)}`"


def test_every_key_is_documented_as_in_the_schema():
    """docs/case-format.md lists every key with the schema's unit, default, bounds and help."""
    doc = (Path(__file__).parents[3] / "docs" / "case-format.md").read_text()
    for f in FIELDS:
        unit = f.unit or "–"
        row = f"| `{f.key}` | {unit} | {_default_cell(f)} | {f.allowed_text()} | {f.help} |"
        assert row in doc.splitlines(), row
    for f in MATERIAL_FIELDS:
        row = f"| `{f.key}` | {f.unit or '–'} | {f.allowed_text()} | {f.help} |"
        assert row in doc.splitlines(), row


def test_every_number_has_bounds_with_reasons():
    """An upper bound on every number keeps values within what the solvers compute without
    overflow; each bound says why in its messages."""
    for f in FIELDS + MATERIAL_FIELDS:
        if f.type not in ("float", "int"):
            continue
        assert f.minimum is not None and f.maximum is not None, f.key
        assert f.reason and (f.reason_high or f.reason), f.key
        assert math.isfinite(f.minimum) and math.isfinite(f.maximum), f.key


def test_every_simulation_switch_has_its_default_in_the_schema(valid):
    """The [simulation] switches have plain defaults (the full model), read into every case."""
    case = parse_case(tomli_w.dumps(valid))
    expected = {
        "ball_race_traction": True,
        "contact_damping_ratio": 0.05,
        "gravity_m_s2": 9.81,
        "tolerance": 1e-4,
        "model_cage": True,
        "quasistatic_ball_speeds": "traction",
    }
    for name, value in expected.items():
        f = next(f for f in FIELDS if f.key == f"simulation.{name}")
        assert f.default == value and getattr(case.simulation, name) == value, name
    # every key a steady case reads has a default (a history case needs its duration)
    assert all(
        f.default is not OPTIONAL
        for f in FIELDS
        if f.section == "simulation" and f.applies != "history"
    )
