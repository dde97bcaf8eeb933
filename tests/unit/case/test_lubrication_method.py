"""The case key lubricant.method and its supply keys: what each method gives the models (oil
fraction of the drag mixture, cage-land flooding, the supplied oil's viscosity), the warning
when no method is named, the overrides, and a clear error for every key in the wrong place."""

from __future__ import annotations

import pytest

import solver
from solver.case.schema import (
    ASSUMED_METHOD,
    ASSUMED_OIL_VOLUME_FRACTION,
    GREASE_OIL_VOLUME_FRACTION,
    STARVED_LAND_FLOODING,
)
from solver.errors import CaseError
from solver.inputs import to_inputs
from solver.models.dynamic import SimulationOptions
from solver.models.dynamic.params import build_params
from tests.helpers.cases import SPINDLE


def _case(lubricant_lines: str = "", cage_lines: str = ""):
    cage = f"\n[cage]\n{cage_lines}" if cage_lines else ""
    return solver.parse_case(SPINDLE + cage + "\n[lubricant]\n" + lubricant_lines)


def _params(inputs):
    """The dynamic model's parameters of ``inputs`` (mixture density and viscosity)."""
    return build_params(inputs, SimulationOptions())


def _problems(lubricant_lines: str) -> list:
    with pytest.raises(CaseError) as info:
        _case(lubricant_lines)
    return info.value.problems


def test_a_case_without_method_warns_which_method_is_assumed():
    case = _case()
    assert case.lubricant.method is None
    [warning] = [w for w in case.warnings() if w.key == "lubricant.method"]
    assert f'"{ASSUMED_METHOD}"' in warning.message
    assert f"{ASSUMED_OIL_VOLUME_FRACTION:g}" in warning.message
    oil = to_inputs(case).lubricant
    assert oil.method == ASSUMED_METHOD and oil.method_assumed
    assert oil.oil_volume_fraction == ASSUMED_OIL_VOLUME_FRACTION
    assert to_inputs(case).cage.land_flooding == 1.0
    assert "assumed" in oil.description
    # a case that names its method has no such warning
    named = _case('method = "grease"\n')
    assert not [w for w in named.warnings() if w.key == "lubricant.method"]


def test_oil_air_holds_its_flow_for_a_cage_revolution_and_starves_the_land():
    low = to_inputs(_case('method = "oil_air"\noil_flow_mm3_h = 30.0\n'))
    high = to_inputs(_case('method = "oil_air"\noil_flow_mm3_h = 60.0\n'))
    assert 0.0 < low.lubricant.oil_volume_fraction < 1e-6
    assert high.lubricant.oil_volume_fraction == pytest.approx(
        2.0 * low.lubricant.oil_volume_fraction
    )
    assert low.cage.land_flooding == STARVED_LAND_FLOODING
    dry = to_inputs(_case('method = "oil_air"\noil_flow_mm3_h = 0.0\n'))
    assert dry.lubricant.oil_volume_fraction == 0.0
    mist = to_inputs(_case('method = "oil_mist"\noil_flow_mm3_h = 30.0\n'))
    assert mist.lubricant.oil_volume_fraction == low.lubricant.oil_volume_fraction
    assert "oil_mist" in mist.lubricant.description


def test_oil_jet_floods_and_its_temperature_sets_the_supplied_oil_viscosity():
    warm = to_inputs(_case('method = "oil_jet"\njet_flow_l_min = 1.0\n'))
    cold = to_inputs(_case('method = "oil_jet"\njet_flow_l_min = 1.0\njet_temperature_C = 20.0\n'))
    assert warm.cage.land_flooding == 1.0
    air = to_inputs(_case('method = "oil_air"\noil_flow_mm3_h = 60.0\n'))
    assert warm.lubricant.oil_volume_fraction > 1e4 * air.lubricant.oil_volume_fraction
    assert warm.lubricant.mixture_viscosity_of_oil == warm.lubricant.viscosity
    assert cold.lubricant.mixture_viscosity_of_oil > warm.lubricant.viscosity
    assert _params(cold).mixture_viscosity > _params(warm).mixture_viscosity


def test_oil_bath_below_the_balls_gives_no_oil_and_deeper_gives_more():
    dry = to_inputs(_case('method = "oil_bath"\noil_level_mm = 0.0\n'))
    half = to_inputs(_case('method = "oil_bath"\noil_level_mm = 3.572\n'))
    deep = to_inputs(_case('method = "oil_bath"\noil_level_mm = 20.0\n'))
    assert dry.lubricant.oil_volume_fraction == 0.0
    assert 0.0 < half.lubricant.oil_volume_fraction < deep.lubricant.oil_volume_fraction
    assert _params(dry).mixture_density < _params(deep).mixture_density


def test_grease_is_a_low_fixed_fraction_with_a_starved_land():
    inputs = to_inputs(_case('method = "grease"\n'))
    assert inputs.lubricant.oil_volume_fraction == GREASE_OIL_VOLUME_FRACTION
    assert inputs.cage.land_flooding == STARVED_LAND_FLOODING


def test_explicit_fraction_and_flooding_override_the_method():
    inputs = to_inputs(
        _case('method = "oil_air"\noil_volume_fraction = 0.02\n', "land_flooding = 0.8\n")
    )
    assert inputs.lubricant.oil_volume_fraction == 0.02
    assert inputs.cage.land_flooding == 0.8
    assert "given" in inputs.lubricant.mixture_basis


def test_a_method_without_its_supply_names_the_missing_key():
    for method, key in (
        ("oil_air", "oil_flow_mm3_h"),
        ("oil_mist", "oil_flow_mm3_h"),
        ("oil_jet", "jet_flow_l_min"),
        ("oil_bath", "oil_level_mm"),
    ):
        [problem] = _problems(f'method = "{method}"\n')
        assert problem.key == f"lubricant.{key}"
        assert "is missing" in problem.message and method in problem.message
        assert "oil_volume_fraction" in problem.message  # the other way to fix it


def test_a_key_of_another_method_is_an_error_naming_the_method_that_reads_it():
    [problem] = _problems('method = "oil_air"\noil_flow_mm3_h = 30.0\noil_level_mm = 5.0\n')
    assert problem.key == "lubricant.oil_level_mm"
    assert '"oil_bath"' in problem.message and '"oil_air"' in problem.message
    [problem] = _problems("jet_flow_l_min = 1.0\n")
    assert problem.key == "lubricant.jet_flow_l_min"
    assert "names no lubricant.method" in problem.message


def test_an_unknown_method_and_a_negative_flow_are_refused():
    [problem] = _problems('method = "splash"\n')
    assert problem.key == "lubricant.method" and '"oil_air"' in problem.message
    [problem] = _problems('method = "oil_air"\noil_flow_mm3_h = -1.0\n')
    assert problem.key == "lubricant.oil_flow_mm3_h"


def test_method_keys_round_trip_through_the_case_text():
    case = _case('method = "oil_jet"\njet_flow_l_min = 1.5\njet_temperature_C = 35.0\n')
    again = solver.parse_case(case.to_toml())
    assert again == case
    assert again.lubricant.method == "oil_jet" and again.lubricant.jet_flow_l_min == 1.5
