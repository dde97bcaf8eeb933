"""Case form: fields from the case schema, text parsing, messages routed to fields."""

from __future__ import annotations

import pytest

from app.caseform import FormField, apply_form, form_fields, parse_value


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
    from solver import load_case

    case = load_case(fixture_model.FIXTURE_CASE)
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
