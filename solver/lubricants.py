"""Named oils: ``[lubricant]`` key values of three common bearing oils, each value with its source.

Copy an oil's keys into a case's ``[lubricant]`` section (:func:`lubricant_table` gives them as a
TOML-ready dict; docs/case-format.md lists them). Values are typical data of the oil class, not of
one product. :data:`KEY_SOURCES` gives, for every key of every oil, the document the value comes
from, or, starting with ``ESTIMATE``, why it is an estimate (a class value no document found
through the project's tools states). Documents:

- [ISO3448] ISO 3448:1992, Industrial liquid lubricants - ISO viscosity classification (also
  published as ES ISO 3448:2005): grade VG n spans n +/- 10 % mm^2/s at 40 degC (VG 22:
  19.8-24.2, VG 32: 28.8-35.2).
- [SB-T2.3] Stachowiak & Batchelor, Engineering Tribology, Table 2.3 "Dynamic viscosity and
  pressure-viscosity coefficients of some commonly used lubricants": two spindle oils with
  alpha = 20 and 25.7 /GPa at 30 degC, 16 and 20.3 /GPa at 60 degC.
- [MIL23699] MIL-PRF-23699F (1997), Lubricating oil, aircraft turbine engine, synthetic base,
  section 1.1: nominal viscosity 5 mm^2/s at 100 degC, neopentyl polyol ester base stocks.
- [JT1977] Johnson & Tevaarwerk, Shear behaviour of elastohydrodynamic oil films, Proc. R. Soc.
  Lond. A 356 (1977) 215-236, and [BW1979] Bair & Winer, Shear strength measurements of
  lubricants at high pressure, J. Lubr. Technol. 101 (1979) 251-257: the form of the rheological
  law (Eyring stress, film shear modulus, limiting shear stress growing with pressure); the
  numbers given to each oil are estimates of the class, not values read from these papers.
- [VEO] "Observations of viscoelastic behaviour of an elastohydrodynamic lubricant film", abstract
  (scilit record c72484bb7d8f02b302ce42281110aa4a): a high-viscosity mineral oil at 23 degC has an
  effective elastic shear modulus of 0.1 to 1.0 GPa over 1.0 to 2.0 GPa contact pressure.

No published traction curve with numbers was found to fit these parameters to (the search record
is in docs/case-format.md, "Validation against a published traction curve").
"""

from __future__ import annotations

import math


def _beta(nu_40: float, nu_100: float) -> float:
    """Temperature-viscosity coefficient [1/K] through two kinematic viscosities 60 K apart."""
    return math.log(nu_40 / nu_100) / 60.0


_RHEOLOGY_ESTIMATE = (
    "ESTIMATE: class value for the law of [JT1977]/[BW1979], not measured for this oil"
)

#: name -> (``[lubricant]`` keys, one-line description)
OILS: dict[str, tuple[dict, str]] = {
    "spindle-mineral-vg32": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 32.0e-6 * 870.0,  # 32 mm^2/s at 40 degC, 870 kg/m^3
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(32.0, 5.4), 4),
            "pressure_viscosity_per_GPa": 22.0,
            "eyring_stress_MPa": 5.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.07,
            "film_shear_modulus_GPa": 0.5,
            "thermal_conductivity_W_mK": 0.13,
            "density_kg_m3": 870.0,
        },
        "paraffinic mineral spindle oil ISO VG 32",
    ),
    "ester-vg22": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 22.0e-6 * 920.0,
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(22.0, 4.6), 4),
            "pressure_viscosity_per_GPa": 13.0,
            "eyring_stress_MPa": 3.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.06,
            "film_shear_modulus_GPa": 0.4,
            "thermal_conductivity_W_mK": 0.15,
            "density_kg_m3": 920.0,
        },
        "synthetic (polyol) ester spindle oil ISO VG 22",
    ),
    "jet-oil-mil-prf-23699": (
        {
            "traction_model": "rheology",
            "viscosity_Pas": 25.0e-6 * 1000.0,
            "reference_temperature_C": 40.0,
            "temperature_viscosity_per_K": round(_beta(25.0, 5.0), 4),
            "pressure_viscosity_per_GPa": 13.7,
            "eyring_stress_MPa": 3.0,
            "limiting_shear_stress_MPa": 2.0,
            "limiting_shear_coefficient": 0.06,
            "film_shear_modulus_GPa": 0.4,
            "thermal_conductivity_W_mK": 0.15,
            "density_kg_m3": 1000.0,
        },
        "gas-turbine jet oil to MIL-PRF-23699 (5 mm^2/s polyol ester); the ADORE example traction "
        "curve of physics.md is for this oil class",
    ),
}

_COMMON = {
    "traction_model": "the rheological traction law of solver.physics.rheology",
    "reference_temperature_C": "the temperature of the viscosity grade [ISO3448]",
    "eyring_stress_MPa": _RHEOLOGY_ESTIMATE,
    "limiting_shear_stress_MPa": _RHEOLOGY_ESTIMATE,
    "limiting_shear_coefficient": _RHEOLOGY_ESTIMATE,
    "film_shear_modulus_GPa": _RHEOLOGY_ESTIMATE
    + "; inside the 0.1-1.0 GPa measured for a mineral oil at 23 degC and 1-2 GPa [VEO]",
    "thermal_conductivity_W_mK": "ESTIMATE: typical of lubricating oils (0.12-0.16 W/(m K))",
}

#: name -> {key: source}; a source starting with "ESTIMATE" marks a value no document found
#: through the project's tools states (module docstring).
KEY_SOURCES: dict[str, dict[str, str]] = {
    "spindle-mineral-vg32": {
        **_COMMON,
        "viscosity_Pas": "32 mm^2/s, the middle of grade VG 32 [ISO3448], times the density",
        "temperature_viscosity_per_K": "ESTIMATE: through 5.4 mm^2/s at 100 degC, typical of a "
        "viscosity index ~100 (ISO 3448 fixes only the 40 degC value)",
        "pressure_viscosity_per_GPa": "[SB-T2.3] spindle oils, interpolated to 40 degC: 18.7 and "
        "23.9 /GPa; 22 /GPa taken",
        "density_kg_m3": "ESTIMATE: typical of paraffinic mineral oils",
    },
    "ester-vg22": {
        **_COMMON,
        "viscosity_Pas": "22 mm^2/s, the middle of grade VG 22 [ISO3448], times the density",
        "temperature_viscosity_per_K": "ESTIMATE: through 4.6 mm^2/s at 100 degC, typical of a "
        "viscosity index ~140",
        "pressure_viscosity_per_GPa": "ESTIMATE: 13 /GPa, the order of the values tabulated for "
        "synthetic esters (attributed to Hamrock, NASA RP-1255, whose table could not be read "
        "through the project's tools)",
        "density_kg_m3": "ESTIMATE: typical of polyol esters",
    },
    "jet-oil-mil-prf-23699": {
        **_COMMON,
        "viscosity_Pas": "ESTIMATE: 25 mm^2/s at 40 degC, typical of 5 mm^2/s [MIL23699] oils "
        "(the specification's 40 degC limit was not found through the project's tools)",
        "temperature_viscosity_per_K": "through the nominal 5 mm^2/s at 100 degC [MIL23699] and "
        "the estimated 25 mm^2/s at 40 degC",
        "pressure_viscosity_per_GPa": "ESTIMATE: 13.7 /GPa for a formulated polyol ester "
        "(attributed to Hamrock, NASA RP-1255, whose table could not be read through the "
        "project's tools)",
        "density_kg_m3": "ESTIMATE: typical of polyol ester jet oils",
    },
}


def lubricant_table(name: str) -> dict:
    """The ``[lubricant]`` keys of oil ``name``; ValueError naming the known oils otherwise."""
    try:
        keys, _ = OILS[name]
    except KeyError:
        raise ValueError(f"unknown oil {name!r}; known oils: {', '.join(OILS)}") from None
    return dict(keys)


def estimated_keys(name: str) -> list[str]:
    """The keys of oil ``name`` whose values are estimates (no document states them)."""
    lubricant_table(name)  # the same error for an unknown oil
    return [k for k, source in KEY_SOURCES[name].items() if source.startswith("ESTIMATE")]
