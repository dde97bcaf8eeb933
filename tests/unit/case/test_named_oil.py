"""The case key lubricant.oil: a named oil's values fill the [lubricant] keys not given."""

import pytest

import solver
from solver.lubricants import lubricant_table, oil_names
from tests.helpers.cases import SPINDLE


def _case(lubricant_lines: str):
    return solver.parse_case(SPINDLE + "\n[lubricant]\n" + lubricant_lines)


@pytest.mark.parametrize("name", oil_names())
def test_named_oil_fills_every_key_the_case_does_not_give(name):
    case = _case(f'oil = "{name}"\n')
    for key, value in lubricant_table(name).items():
        assert getattr(case.lubricant, key) == value, key
    assert case.from_oil == {f"lubricant.{key}" for key in lubricant_table(name)}


def test_keys_the_case_gives_override_the_oil():
    case = _case('oil = "ester-vg22"\npressure_viscosity_per_GPa = 15.0\n')
    assert case.lubricant.pressure_viscosity_per_GPa == 15.0
    assert case.lubricant.viscosity_Pas == lubricant_table("ester-vg22")["viscosity_Pas"]
    assert "lubricant.pressure_viscosity_per_GPa" not in case.from_oil


def test_keys_no_oil_gives_keep_the_schema_default():
    default = solver.parse_case(SPINDLE + "\n[lubricant]\n")
    case = _case('oil = "spindle-mineral-vg32"\n')
    assert "oil_volume_fraction" not in lubricant_table("spindle-mineral-vg32")
    assert case.lubricant.oil_volume_fraction == default.lubricant.oil_volume_fraction


def test_case_text_names_the_oil_and_writes_its_values_as_comments():
    """A changed oil must not leave the old oil's values behind as given keys."""
    case = _case('oil = "ester-vg22"\n')
    text = case.to_toml()
    assert 'oil = "ester-vg22"' in text
    assert "# viscosity_Pas = " in text and "from the named oil ester-vg22" in text
    assert solver.parse_case(text) == case
    other = case.with_values({"lubricant.oil": "spindle-mineral-vg32"})
    assert other.lubricant.viscosity_Pas == lubricant_table("spindle-mineral-vg32")["viscosity_Pas"]


def test_unknown_oil_is_an_error_naming_the_known_oils():
    with pytest.raises(solver.CaseError) as error:
        _case('oil = "castor"\n')
    message = str(error.value)
    assert "lubricant.oil" in message and "castor" in message
    for name in oil_names():
        assert name in message


def test_result_attribute_names_the_oil_and_the_default_oil_text_has_its_numbers():
    """The ``lubricant`` attribute of a result says where the oil came from, with numbers (no
    unformatted template text)."""
    named = solver.to_inputs(_case('oil = "ester-vg22"\n')).lubricant.description
    assert "ester-vg22" in named
    default = solver.to_inputs(solver.parse_case(SPINDLE)).lubricant.description
    assert "{" not in default and "pressure-viscosity 20 /GPa" in default
