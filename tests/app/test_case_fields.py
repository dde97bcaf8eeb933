"""Case form: fields from the case schema, text parsing, messages routed to fields."""

from __future__ import annotations

import pytest

from app.case_fields import FormField, apply_form, form_fields, parse_value


def test_fields_follow_the_schema():
    from solver.case.schema import FIELDS

    fields = form_fields()
    assert [f.key for f in fields] == [s.key for s in FIELDS]
    names = [f.name for f in fields]
    assert len(set(names)) == len(names)  # element ids field-<name> are unique
    by_name = {f.name: f for f in fields}
    assert by_name["ball_count"].kind == "int"
    assert by_name["axial_load_N"].label.endswith("(N)")
    assert "silicon_nitride" in by_name["ball_material"].choices


def test_parse_value():
    f_int = FormField("bearing.ball_count", "ball_count", "int", "Number of balls", "", "")
    f_float = FormField(
        "operating.axial_load_N", "axial_load_N", "float", "Axial load (N)", "N", ""
    )
    f_bool = FormField("x.flag", "flag", "bool", "Flag", "", "")
    assert parse_value(f_int, " 12 ") == 12
    assert parse_value(f_float, "1e3") == 1000.0
    assert parse_value(f_float, "") is None
    assert parse_value(f_bool, "True") is True
    with pytest.raises(ValueError, match=r"bearing.ball_count = '12.5': must be a whole number"):
        parse_value(f_int, "12.5")
    with pytest.raises(ValueError, match=r"operating.axial_load_N = 'abc': must be a number"):
        parse_value(f_float, "abc")
    with pytest.raises(ValueError, match="true or false"):
        parse_value(f_bool, "maybe")


def test_apply_form_routes_problems_to_fields(fixture_model):
    from solver import parse_case

    case = parse_case(fixture_model.FIXTURE_CASE)
    fields = form_fields()
    ok = apply_form(case, fields, {"axial_load_N": "750"})
    assert ok.valid and ok.case.operating.axial_load_N == 750.0
    bad = apply_form(case, fields, {"inner_groove_radius_ratio": "0.49", "ball_count": "x"})
    assert not bad.valid
    assert "must be a number" in bad.errors["ball_count"]
    bad = apply_form(case, fields, {"inner_groove_radius_ratio": "0.49"})
    assert "0.49" in bad.errors["inner_groove_radius_ratio"]
    assert set(bad.errors) == {"inner_groove_radius_ratio"}
    unchanged = apply_form(case, fields, {})
    assert unchanged.case is case
    # a rule that names two keys: its message shows at the field it is filed under
    none = apply_form(case, fields, {"axial_load_N": "0", "radial_load_N": "0"})
    assert not none.valid
    assert any("nothing holds the balls" in m for m in [*none.errors.values(), *none.general])


def test_rule_between_two_keys_reaches_both_fields(fixture_model):
    """ball_diameter_mm = 60 on a 54 mm pitch circle: the message concerns both diameters."""
    from solver import parse_case

    case = parse_case(fixture_model.FIXTURE_CASE)
    fields = form_fields()
    bad = apply_form(case, fields, {"ball_diameter_mm": "60"})
    assert not bad.valid
    message = bad.errors["pitch_diameter_mm"]
    assert "must be larger than the ball diameter" in message
    assert bad.errors["ball_diameter_mm"] == message
    land = apply_form(case, fields, {"inner_shoulder_diameter_mm": "80"})
    assert "less than the pitch diameter 54 mm" in land.errors["inner_shoulder_diameter_mm"]
    assert land.errors["pitch_diameter_mm"] == land.errors["inner_shoulder_diameter_mm"]
    assert land.general == ()


def test_route_problems_does_not_repeat_a_message():
    from app.case_fields import route_problems
    from solver.errors import Problem

    fields = form_fields()
    a = Problem("bearing.ball_count", "too many", ("bearing.ball_diameter_mm",))
    b = Problem("bearing.ball_diameter_mm", "too big")
    errors, general = route_problems([a, b, Problem("nowhere.key", "lost")], fields)
    assert errors == {"ball_count": "too many", "ball_diameter_mm": "too many; too big"}
    assert general == ("lost",)


def test_default_text_shows_the_value_used_when_empty():
    by_name = {f.name: f for f in form_fields()}
    # plain schema defaults with their units (docs/case-format.md, "Every key")
    assert by_name["viscosity_Pas"].default_text == "0.01 Pa s"
    assert by_name["pressure_viscosity_per_GPa"].default_text == "20 1/GPa"
    assert by_name["mu_max"].default_text == "0.05"
    assert by_name["slip_at_max_m_s"].default_text == "1 m/s"
    assert by_name["axial_load_N"].default_text == "0 N"
    assert by_name["misalignment_axis_deg"].default_text == "90 deg"
    assert by_name["guidance"].default_text == "outer_ring"
    assert by_name["samples_per_revolution"].default_text == "180"
    # estimated from the bearing: the rule
    assert by_name["pocket_diametral_clearance_mm"].default_text == "estimated: 0.028 D"
    # no default: required keys and optional ones with nothing in their place
    for name in ("ball_count", "ball_diameter_mm", "inner_shoulder_diameter_mm", "title"):
        assert by_name[name].default_text == "", name


def test_default_text_of_dynamic_switches_is_what_a_run_uses():
    """The [simulation] switches left empty: the text agrees with the SI inputs the dynamic model
    reads for a case without them (solver.inputs.to_inputs)."""
    from solver.catalogue import resolve_case
    from solver.inputs import to_inputs

    case = resolve_case("218-heavy-combined")  # no dynamic-model switches in the file
    sim = to_inputs(case).simulation
    by_name = {f.name: f for f in form_fields()}
    used = {
        "ball_race_traction": sim.traction,
        "contact_damping_ratio": sim.damping_ratio,
        "gravity_m_s2": sim.gravity,
        "tolerance": sim.tolerance,
        "model_cage": sim.cage,
    }
    for name, value in used.items():
        text = by_name[name].default_text
        if isinstance(value, bool):
            assert text == ("true" if value else "false"), name
        else:
            assert float(text.split()[0]) == pytest.approx(value), name


def test_default_text_of_lubricant_is_the_oil_a_run_uses():
    """A case without [lubricant] (the catalogue's 218 bearing at its modest operating point)
    runs on the schema's default oil: the same values."""
    from solver.catalogue import resolve_case
    from solver.inputs import to_inputs

    oil = to_inputs(resolve_case("218-angular-contact")).lubricant
    assert oil.given is False
    by_name = {f.name: f for f in form_fields()}
    assert float(by_name["viscosity_Pas"].default_text.split()[0]) == oil.viscosity
    pv = float(by_name["pressure_viscosity_per_GPa"].default_text.split()[0]) * 1e-9
    assert pv == pytest.approx(oil.pressure_viscosity)
    names = ("mu_zero", "mu_max", "slip_at_max_m_s", "mu_infinity")
    texts = tuple(float(by_name[n].default_text.split()[0]) for n in names)
    assert texts == oil.traction.values()


def test_estimated_default_texts_give_the_value_for_the_case(fixture_model):
    from app.case_fields import estimated_default_texts
    from solver import parse_case

    case = parse_case(fixture_model.FIXTURE_CASE)
    texts = estimated_default_texts(case, form_fields())
    # 0.028 D with D = 7.144 mm: 0.2000 mm; 0.5 D = 3.572 mm
    assert texts["pocket_diametral_clearance_mm"] == "0.2 mm (estimated: 0.028 D)"
    assert texts["guide_land_width_mm"].startswith("3.57 mm")
    assert set(texts) == {
        "pocket_diametral_clearance_mm",
        "guide_diametral_clearance_mm",
        "mass_g",
        "guide_land_width_mm",
    }


def test_estimated_default_texts_of_a_history_case_give_its_sampling():
    from app.case_fields import estimated_default_texts
    from solver.catalogue import resolve_case

    case = resolve_case("spindle-radial-step").with_values({"simulation.samples_per_second": None})
    texts = estimated_default_texts(case, form_fields())
    # 180 samples per revolution at 20 000 rpm: 60 000 per second
    assert texts["samples_per_second"].startswith("6e+04 1/s (estimated: 180 samples per")


def test_a_history_key_shows_its_history_and_an_edit_of_another_key_keeps_it():
    from app.case_fields import apply_form, case_form_values
    from solver.catalogue import resolve_case

    case = resolve_case("spindle-start-up")
    fields = form_fields()
    values = case_form_values(case, fields)
    # the ramp in words, as `racetrace check` prints it, in the speed's place
    assert values["inner_ring_speed_rpm"] == "smooth ramp from 0 to 20000 rpm, 0 s to 0.3 s"
    edited = {f.name: values[f.name] for f in fields}
    edited["axial_load_N"] = "200"
    result = apply_form(case, fields, {k: v for k, v in edited.items() if v is not None})
    assert result.valid, (result.errors, result.general)
    assert result.case.operating.axial_load_N == 200.0
    ramp = case.histories["operating.inner_ring_speed_rpm"]
    assert result.case.histories["operating.inner_ring_speed_rpm"].spec == ramp.spec
    assert "ramp" in result.case.to_toml()
