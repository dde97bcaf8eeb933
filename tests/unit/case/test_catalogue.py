"""The shipped catalogue: every entry loads, the literature bearings carry their published
numbers."""

from __future__ import annotations

import math

import pytest

from solver.case import FIELDS, CaseError, parse_case
from solver.case.schema import OPTIONAL
from solver.catalogue import catalogue, modest_operating_point, resolve_case

EXPECTED = {
    "bearings": {
        "218-angular-contact",
        "209-deep-groove",
        "7008C-hybrid-spindle",
        "7210B-angular-contact",
        "turbopump-hybrid",
    },
    "cases": {
        "spindle-axial-preload",
        "spindle-combined-load",
        "spindle-misalignment-space",
        "spindle-misalignment-ring",
        "218-heavy-combined",
        "209-radial",
        # time histories (issue 24)
        "spindle-start-up",
        "spindle-start-up-skid",
        "spindle-live-radial-push",
        "spindle-radial-step",
        "spindle-unbalance",
        "spindle-load-spectrum",
        # bearing sets (issue 25)
        "spindle-pair-db-light-preload",
        "spindle-pair-db-medium-preload",
        "spindle-pair-db-heavy-preload",
        "spindle-pair-df-misalignment",
        "spindle-front-tbt-medium-preload",
    },
}


def test_catalogue_lists_the_required_entries():
    cat = catalogue()
    assert {e.name for e in cat.bearings} == EXPECTED["bearings"]
    assert {e.name for e in cat.cases} == EXPECTED["cases"]
    assert list(cat) == list(cat.entries) and len(cat) == 22
    for entry in cat.entries:
        assert entry.title and entry.provenance in (
            "estimated",
            "manufacturer",
            "literature",
            "measured",
        )


@pytest.mark.parametrize("name", sorted(EXPECTED["bearings"] | EXPECTED["cases"]))
def test_every_entry_loads_and_round_trips(name):
    entry = catalogue().get(name)
    case = entry.load()
    assert parse_case(case.to_toml(), "text", case.source_dir or None) == case
    assert case.bearing.provenance == entry.provenance
    if entry.kind == "bearing":  # the starting case keeps the shipped bearing
        assert case.title == entry.title


def test_218_numbers_as_published():
    case = catalogue().get("218-angular-contact").load()
    b = case.bearing
    assert (b.ball_diameter_mm, b.pitch_diameter_mm, b.ball_count) == (22.225, 125.26, 16)
    assert b.inner_groove_radius_ratio == b.outer_groove_radius_ratio == 0.5232
    assert b.free_contact_angle_deg == 40.0 and b.provenance == "literature"
    assert case.ball_material.youngs_modulus == case.ring_material.youngs_modulus == 208e9


def test_209_clearance_gives_the_closed_form_contact_angle():
    """alpha_0 = arccos(1 - P_d / (2 (f_i + f_o - 1) D)) = arccos(1 - 0.015 / 1.016)."""
    case = catalogue().get("209-deep-groove").load()
    assert case.bearing.diametral_clearance_mm == 0.015 and case.bearing.ball_count == 9
    assert math.isclose(
        case.geometry().free_contact_angle, math.acos(1.0 - 0.015 / 1.016), rel_tol=1e-12
    )


def test_seed_study_cases():
    cat = catalogue()
    combined = cat.get("spindle-combined-load").load()
    assert combined.operating.inner_ring_speed_rpm == 20000.0
    assert (combined.operating.axial_load_N, combined.operating.radial_load_N) == (500.0, 300.0)
    assert combined.ball_material.name == "silicon_nitride"
    traction = combined.lubricant.traction
    assert (traction.mu_zero, traction.mu_max, traction.slip_at_max_m_s, traction.mu_infinity) == (
        0.0,
        0.05,
        1.0,
        0.036,
    )
    space = cat.get("spindle-misalignment-space").load().operating
    ring = cat.get("spindle-misalignment-ring").load().operating
    assert space.misalignment_deg == ring.misalignment_deg == 0.05
    assert (space.misalignment_frame, ring.misalignment_frame) == ("space", "ring")
    assert cat.get("spindle-axial-preload").load().operating.radial_load_N == 0.0


def test_7008C_shoulders_lie_on_the_grooves():
    g = catalogue().get("7008C-hybrid-spindle").load().geometry()
    assert g.inner_groove_bottom_diameter < g.inner_shoulder_diameter < g.pitch_diameter
    assert g.pitch_diameter < g.outer_shoulder_diameter < g.outer_groove_bottom_diameter


def test_bearing_case_text_has_a_modest_operating_point():
    entry = catalogue().get("7008C-hybrid-spindle")
    text = entry.case_text()
    case = parse_case(text)
    assert case == entry.load()
    # written by the case writer: estimates and the absent [lubricant] as comments
    assert text.endswith(case.to_toml())
    assert "# pocket_diametral_clearance_mm = " in text and "# [lubricant] not given" in text
    # every value but the bearing and the operating point is the schema's default or estimate
    assert not case.lubricant_given
    # a steady case: every estimate from the bearing, none from a history
    assert case.estimated == {f.key for f in FIELDS if f.estimated and f.default.reads == "bearing"}
    for f in FIELDS:
        if f.section in ("cage", "lubricant", "simulation") and not f.estimated:
            value = case
            for part in f.path:
                value = getattr(value, part)
            assert value == (None if f.default is OPTIONAL else f.default), f.key
    speed, load = modest_operating_point(18, 7.144, 54.0)
    assert case.operating.inner_ring_speed_rpm == speed
    assert abs(speed * 54.0 - 5e5) / 5e5 < 0.05  # d_m n close to 500 000 mm rpm
    assert case.operating.axial_load_N == load == pytest.approx(0.5 * 18 * 7.144**2, rel=0.05)


def test_unknown_name_suggests():
    with pytest.raises(CaseError) as info:
        catalogue().get("spindle-combined")
    problem = info.value.problems[0]
    assert problem.key == "catalogue" and "spindle-combined-load" in problem.message


def test_resolve_case_accepts_names_paths_and_cases(tmp_path):
    case = resolve_case("209-radial")
    assert case.operating.radial_load_N == 4450.0
    file = tmp_path / "c.toml"
    file.write_text(case.to_toml())
    assert resolve_case(str(file)) == case == resolve_case(file) == resolve_case(case)
    with pytest.raises(CaseError, match="not found"):
        resolve_case(str(tmp_path / "missing.toml"))
    with pytest.raises(CaseError, match="neither a case file nor a catalogue name"):
        resolve_case("209-radail")


def test_resolve_case_names_a_folder_as_such(tmp_path):
    with pytest.raises(CaseError) as info:
        resolve_case(str(tmp_path))
    assert "is a folder, not a case file" in str(info.value)
